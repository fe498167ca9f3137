// The preparation protocol's cycle selection (dem/prepare.cpp, paper section 2):
// the cycles stop at the first one that seizes at or below the target void ratio,
// and the kept cycle is the one nearest the target; stopping early changes nothing
// in the cycles that did run.
#include "common/error.hpp"
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
  config.prepare.void_ratio_tolerance = 1.0; // these tests are about the cycles, not the target
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

TEST(Prepare, AnUnreachableTargetFailsNamingTheVoidRatioReached) {
  DemConfig config = fast_config(2, 0.3); // far below what two cycles of 150 spheres reach
  config.prepare.void_ratio_tolerance = 0.003;
  try {
    (void)prepare(config);
    FAIL() << "expected a ConvergenceError";
  } catch (const ConvergenceError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("above the target dem.prepare.target_void_ratio = 0.3000"), std::string::npos)
        << message;
    EXPECT_NE(message.find("after 2 of at most 2 cycles"), std::string::npos) << message;
    EXPECT_EQ(error.code(), ExitCode::convergence_failure);
  }
}

TEST(Prepare, ACycleThatConsolidationCompactsPastTheToleranceIsNamed) {
  // The target is cycle 1's seized e, so the cycles stop there; consolidation to p0 then
  // compacts it by more than a tolerance of a third of that compaction. The message must
  // blame the consolidation, not a first cycle that packs too densely.
  const PreparedAssembly first = prepare(fast_config(1, 0.0));
  const double seized = first.cycle_void_ratios[0];
  const double compaction = seized - first.consolidated.void_ratio;
  ASSERT_GT(compaction, 0.0);
  DemConfig config = fast_config(3, seized);
  config.prepare.void_ratio_tolerance = compaction / 3;
  try {
    (void)prepare(config);
    FAIL() << "expected a ConvergenceError";
  } catch (const ConvergenceError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("consolidation to p0 compacted the kept cycle 1"), std::string::npos) << message;
    EXPECT_EQ(message.find("the first cycle already packs denser"), std::string::npos) << message;
  }
}

TEST(Prepare, ReachesTheTargetWithinItsTolerance) {
  // The paper's protocol reaches a target: the prepared e lies within the tolerance of it and
  // the assembly is consolidated to p0 in static equilibrium.
  const PreparedAssembly first = prepare(fast_config(1, 0.0));
  const double target = first.cycle_void_ratios[0] - 0.01;
  DemConfig config = fast_config(30, target);
  config.prepare.void_ratio_tolerance = 0.003;
  const PreparedAssembly prepared = prepare(config);
  EXPECT_LT(std::abs(prepared.consolidated.void_ratio - target), 0.003);
  EXPECT_LT(prepared.consolidated.unbalanced_force_ratio, config.equilibrium.tolerance);
  EXPECT_GT(prepared.cycle_void_ratios.size(), 1u);
}

} // namespace
