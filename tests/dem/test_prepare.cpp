// The preparation protocol's cycle selection (dem/prepare.cpp, paper section 2):
// the cycles stop at the first one that seizes at or below the target void ratio,
// and the kept cycle is the one nearest the target; stopping early changes nothing
// in the cycles that did run.
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace aniso;
using namespace aniso::dem;

DemConfig fast_config(int cycles, double target) {
  DemConfig config = test::small_config(150, 3);
  config.prepare.inertial_number = 0.05;
  config.prepare.consolidation_tolerance = 0.02;
  config.prepare.cycles = cycles;
  config.prepare.target_void_ratio = target;
  return config;
}

PreparedAssembly prepare(const DemConfig& config) {
  return prepare_assembly(config, make_silent_logger(), mpi::Comm(MPI_COMM_SELF));
}

TEST(Prepare, CyclesStopAtTheTargetAndKeepTheNearest) {
  // An unreachable target: every cycle runs, each denser than the one before.
  const PreparedAssembly all = prepare(fast_config(4, 0.0));
  ASSERT_EQ(all.cycle_void_ratios.size(), 4u);
  EXPECT_EQ(all.chosen_cycle, 4);
  for (std::size_t k = 1; k < 4; ++k)
    EXPECT_LT(all.cycle_void_ratios[k], all.cycle_void_ratios[k - 1]);

  // A target just above cycle 3's void ratio, nearer cycle 3 than cycle 2: three cycles run.
  const double e2 = all.cycle_void_ratios[1], e3 = all.cycle_void_ratios[2];
  const double target = e3 + 0.25 * (e2 - e3);
  const PreparedAssembly stopped = prepare(fast_config(10, target));
  ASSERT_EQ(stopped.cycle_void_ratios.size(), 3u);
  EXPECT_EQ(stopped.chosen_cycle, 3);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_EQ(stopped.cycle_void_ratios[k], all.cycle_void_ratios[k]);
  EXPECT_LT(std::abs(stopped.consolidated.mean_stress - 100e3), 0.02 * 100e3);
}

} // namespace
