// The cell servo during biaxial plane-strain loading at constant mean stress
// (dem/protocol/load.hpp, dem/model/cell_control.hpp): after the start-up transient the mean
// stress stays near its target, axis 2 does not move at all and axis 1
// follows the prescribed rate exactly.
//
// Measured on 150 particles (seed 11), |p - p0|/p0 after 0.1 % strain, over
// 0.1-0.5 % strain, incremental Mindlin law, servo capped at 20 times the loading rate:
//   contact damping 0.3 during loading: median 2.8e-4, 95th percentile 8.3e-4, max 1.3e-3;
//   damping 0.05 (the default dem.integration.damping): median 2.7e-3, 95th
//   percentile 1.3e-2, max 3.2e-2. A 150-particle assembly suffers small
//   collapses that take p away for a moment; the 0.5 % goal holds for the
//   median, not for the maximum, at this size.
#include "dem/io/parameters.hpp"
#include "dem/protocol/load.hpp"
#include "dem/protocol/rates.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using aniso::Vec3;
using namespace aniso;
using namespace aniso::dem;
using namespace aniso::dem::io;
using namespace aniso::dem::protocol;

struct LoadingResult {
  double median = 0, p95 = 0, worst = 0, worst_transient = 0;
  std::size_t updates = 0;
};

/// The assembly prepared once for all tests: the library's preparation protocol
/// with one compaction cycle, consolidated by the stress servo on all three
/// axes to 100 kPa until p is within 1 % and the assembly is at rest.
const Simulation& consolidated_assembly(const DemConfig& config) {
  static const Simulation simulation = [&] {
    DemConfig prepare = config;
    prepare.prepare.consolidation_tolerance = 0.01;
    Simulation prepared = test::prepared_assembly(prepare);
    const StateMeasures m = prepared.measure();
    std::printf(
        "[ measured ] consolidated in %lld steps: p = %.5g Pa, e = %.4f, Z = %.3f, Z without rattlers %.3f\n",
        static_cast<long long>(prepared.step_count()), m.mean_stress, m.void_ratio, m.coordination,
        m.coordination_no_rattlers);
    return prepared;
  }();
  return simulation;
}

/// Biaxial loading by dem::start_loading to 0.5 % strain; checks the kinematics
/// at every step and returns the servo error statistics after 0.1 % strain.
LoadingResult load_biaxially(Simulation simulation, const DemConfig& config) {
  const double p0 = config.load.mean_stress;
  EXPECT_LT(std::abs(mean_stress_compression_positive(simulation.stress()) - p0), 0.01 * p0);
  start_loading(simulation, config);
  const double rate = strain_rate_for_inertial_number(config.load.inertial_number, config.particles.d50,
                                                      config.particles.density, p0);
  const double dt = simulation.settings().time_step;
  const std::int64_t interval = simulation.settings().control_interval;
  const double transient = 0.001, final_strain = 0.005;
  std::vector<double> errors;
  double expected_length = simulation.cell().lengths()[0];
  const double length_2 = simulation.cell().lengths()[1];
  LoadingResult result;
  while (-simulation.cell().engineering_strain()[0] < final_strain) {
    simulation.step();
    expected_length *= 1.0 - dt * rate;
    // Plane strain: axis 2 never moves; axis 1 runs at exactly the prescribed rate.
    EXPECT_EQ(simulation.cell().lengths()[1], length_2);
    EXPECT_EQ(simulation.control().strain_rate[0], -rate);
    EXPECT_EQ(simulation.control().strain_rate[1], 0.0);
    if (::testing::Test::HasFailure()) return result;
    if (simulation.step_count() % interval != 0) continue;
    const double error = std::abs(simulation.servo_error());
    if (-simulation.cell().engineering_strain()[0] < transient) {
      result.worst_transient = std::max(result.worst_transient, error);
    } else {
      errors.push_back(error);
    }
  }
  EXPECT_EQ(simulation.cell().engineering_strain()[1], 0.0);
  EXPECT_NEAR(simulation.cell().lengths()[0] / expected_length, 1.0, 1e-12);
  EXPECT_EQ(simulation.control().mode[2], model::AxisMode::stress);
  EXPECT_TRUE(simulation.control().hold_mean_stress);

  std::sort(errors.begin(), errors.end());
  result.updates = errors.size();
  if (errors.empty()) return result;
  result.median = errors[errors.size() / 2];
  result.p95 = errors[errors.size() * 95 / 100];
  result.worst = errors.back();
  const StateMeasures end = simulation.measure();
  std::printf(
      "[ measured ] damping %.2f, rate %.4g /s to strain %.4f: |p - p0|/p0 after strain %.3f: median %.3g, "
      "95th percentile %.3g, max %.3g (%zu updates); max in the transient %.3g; q/p at the end %.3f\n",
      config.integration.damping, rate, -simulation.cell().engineering_strain()[0], transient, result.median,
      result.p95, result.worst, result.updates, result.worst_transient,
      end.deviatoric_stress / end.mean_stress);
  return result;
}

DemConfig servo_config() {
  DemConfig config = test::small_config(150, 11);
  EXPECT_EQ(config.load.mean_stress, config.prepare.confining_pressure);
  return config;
}

// With contact damping 0.3 during loading (the preparation's ratio) the servo
// holds p within 0.5 % once past the start-up transient, but for brief
// collapses: from the assembly consolidated in static equilibrium (since
// 2026-12-02) the median is 0.066 %, the 95th percentile 0.27 % and the
// maximum 0.65 % (before, from a state not at rest: 0.028 %, -, 0.13 %).
TEST(Servo, HoldsMeanStressDuringDampedBiaxialLoading) {
  DemConfig config = servo_config();
  const Simulation& consolidated = consolidated_assembly(config);
  config.integration.damping = 0.3;
  const LoadingResult result = load_biaxially(consolidated, config);
  ASSERT_GT(result.updates, 1000u);
  EXPECT_LT(result.median, 0.002);
  EXPECT_LT(result.p95, 0.005);
  EXPECT_LT(result.worst, 0.01);
}

// Every loading default (contact damping 0.05): the median error is within the
// 0.5 % goal; the maximum on 150 particles is about 3 % (see the top).
TEST(Servo, HoldsMeanStressDuringDefaultLoading) {
  const DemConfig config = servo_config();
  const LoadingResult result = load_biaxially(consolidated_assembly(config), config);
  ASSERT_GT(result.updates, 1000u);
  EXPECT_LT(result.median, 0.005);
  EXPECT_LT(result.p95, 0.02);
  EXPECT_LT(result.worst, 0.05);
}

} // namespace
