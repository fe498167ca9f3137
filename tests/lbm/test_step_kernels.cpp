// The step at every x86-64 level this binary carries and this CPU runs (lbm/step_kernels.hpp):
// the same bits as the baseline in every velocity component, in both precisions, and a level
// that cannot run is refused by name.
#include "common/error.hpp"
#include "common/log.hpp"
#include "lbm/flow.hpp"
#include "lbm/geometry.hpp"
#include "lbm/topology.hpp"
#include "tests/lbm/fixed_flow.hpp"
#include "tests/lbm/petsc_environment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

namespace aniso::lbm {
namespace {

const mpi::Comm self(MPI_COMM_SELF);

FlowResult run(const Topology& topology, Precision precision, InstructionSet level) {
  FlowSettings settings = fixed_flow_settings(precision);
  settings.instruction_set = level;
  return run_flow(topology, settings, self, make_silent_logger());
}

TEST(StepKernels, EveryLevelGivesTheBaselinesBits) {
  // Random spheres on an odd box: a fluid count that is no multiple of the 8-node blocks, so the
  // one-node remainder runs too, and gathers that jump where the pore space does.
  const Index3 shape{21, 19, 23};
  const h5::VoxelImage image = random_spheres(shape, 3.5, 0.5, 7);
  const Topology topology =
      build_topology(image.phase, make_partition(shape, Index3{1, 1, 1}, 0), all_periodic, self);
  ASSERT_NE(topology.n_fluid % 8, 0);
  const std::vector<InstructionSet> levels = runnable_instruction_sets();
  ASSERT_EQ(levels.back(), InstructionSet::baseline);
  for (Precision precision : {Precision::float64, Precision::float32}) {
    const FlowResult baseline = run(topology, precision, InstructionSet::baseline);
    for (InstructionSet level : levels) {
      std::cout << "level " << instruction_set_name(level) << "\n";
      const FlowResult result = run(topology, precision, level);
      ASSERT_EQ(result.velocity.size(), baseline.velocity.size());
      EXPECT_EQ(std::memcmp(result.velocity.data(), baseline.velocity.data(),
                            result.velocity.size() * sizeof(double)),
                0)
          << instruction_set_name(level);
      for (Eigen::Index a = 0; a < 3; ++a)
        EXPECT_EQ(result.mean_momentum[a], baseline.mean_momentum[a]) << instruction_set_name(level);
    }
  }
}

TEST(StepKernels, AutomaticPicksTheBestLevelAndALevelThatCannotRunIsRefused) {
  const std::vector<InstructionSet> levels = runnable_instruction_sets();
  // Under an emulated CPU (tests/lbm/CMakeLists.txt) the levels it must find.
  if (const char* expected = std::getenv("LBM_EXPECTED_LEVELS")) {
    std::string found;
    for (InstructionSet level : levels)
      found += (found.empty() ? "" : ",") + std::string(instruction_set_name(level));
    EXPECT_EQ(found, expected);
  }
  EXPECT_EQ(resolve_instruction_set(InstructionSet::automatic), levels.front());
  for (InstructionSet level : {InstructionSet::x86_64_v3, InstructionSet::x86_64_v4}) {
    if (std::find(levels.begin(), levels.end(), level) != levels.end()) continue;
    try {
      static_cast<void>(resolve_instruction_set(level));
      FAIL() << instruction_set_name(level) << " is not runnable here but was accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(instruction_set_name(level)), std::string::npos);
    }
  }
}

} // namespace
} // namespace aniso::lbm
