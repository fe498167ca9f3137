// The void analysis on 1 or 2 MPI ranks (sizes dealt out to ranks, counts summed) gives the same
// bits as one process alone.
#include "common/mpi.hpp"
#include "tests/voxel/reference.hpp"
#include "voxel/void_analysis.hpp"

#include <gtest/gtest.h>

#include <bit>

namespace {

TEST(MpiVoxel, RanksGiveTheSameBitsAsOneProcess) {
  const aniso::voxel::Grid grid{{36, 30, 26}};
  const aniso::voxel::Mask phase = aniso::test::blob_phase(grid, 45, 4.0, 21);
  aniso::voxel::VoidAnalysisOptions options;
  options.radius_step = 0.5;
  const auto alone = aniso::voxel::analyze_voids(grid, phase, options, aniso::mpi::Comm(MPI_COMM_SELF));
  const auto together = aniso::voxel::analyze_voids(grid, phase, options, aniso::mpi::Comm::world());
  EXPECT_EQ(together.ball.kept, alone.ball.kept);
  EXPECT_GT(alone.ball.kept.size(), 8U);
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_EQ(together.disk[a].kept, alone.disk[a].kept);
    EXPECT_EQ(together.spar[a].kept, alone.spar[a].kept);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(together.disk[a].median),
              std::bit_cast<std::uint64_t>(alone.disk[a].median));
  }
  EXPECT_EQ(std::bit_cast<std::uint64_t>(together.ball.median),
            std::bit_cast<std::uint64_t>(alone.ball.median));
  EXPECT_EQ(together.euler, alone.euler);
}

} // namespace
