// The equilibrium measures (dem/equilibrium.hpp) on hand-made contacts with
// known net forces, the global damping of the fluctuating motion, the
// relaxation to equilibrium (dem/protocol/relax.hpp) and the fixed-cell hold
// (dem/protocol/hold.hpp) of a small dense assembly.
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/history.hpp"
#include "dem/io/parameters.hpp"
#include "dem/model/integrator.hpp"
#include "dem/protocol/hold.hpp"
#include "dem/protocol/load.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/protocol/relax.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using aniso::Vec3;
using namespace aniso;
using namespace aniso::dem;
using namespace aniso::dem::data;
using namespace aniso::dem::io;
using namespace aniso::dem::protocol;

constexpr double radius = 0.1e-3;

/// Spheres of one radius at the given x on the line y = z = L/2 of a 1 mm cubic cell, at rest.
Simulation spheres_on_a_line(const std::vector<double>& x, double global_damping = 0.0) {
  DemConfig config = test::small_config(static_cast<std::int64_t>(x.size()));
  config.integration.global_damping = global_damping;
  Particles particles;
  const double length = 1e-3;
  for (std::size_t k = 0; k < x.size(); ++k) {
    particles.add(k, radius, 1.0, config.particles.splice_angle, config.particles.density,
                  Vec3(x[k], 0.5 * length, 0.5 * length));
  }
  const PeriodicCell cell(Vec3::Constant(length));
  SimulationSettings settings = settings_from_config(config, 2 * radius);
  settings.material.damping_ratio = 0.0;
  return Simulation(std::move(particles), cell, model::CellControl{}, settings, mpi::Comm(MPI_COMM_SELF));
}

TEST(Equilibrium, TwoTouchingSpheresAreWhollyUnbalanced) {
  // Each sphere feels the one contact force f and nothing else: mean |net| = f = mean |f_c|.
  const double overlap = 1e-6;
  const Simulation simulation = spheres_on_a_line({0.4e-3, 0.4e-3 + 2 * radius - overlap});
  const Equilibrium e = simulation.equilibrium();
  ASSERT_EQ(e.n_contacts, 1);
  EXPECT_NEAR(e.unbalanced_force_ratio, 1.0, 1e-12);
  // Hertz: k_n = 3 F / (2 delta) and the stored energy (2/5) F delta.
  const ContactRecord& record = simulation.neighbors().records()[0];
  EXPECT_NEAR(e.mean_normal_stiffness, 1.5 * record.normal_force / overlap, 1e-9 * e.mean_normal_stiffness);
  EXPECT_NEAR(e.elastic_energy, 0.4 * record.normal_force * overlap, 1e-12 * e.elastic_energy);
  EXPECT_EQ(e.kinetic_energy, 0.0);
}

TEST(Equilibrium, ASymmetricChainBalancesItsMiddleSphere) {
  // Three spheres, two equal contacts: the middle one is balanced, each end one feels f.
  // Mean |net| over the three loaded spheres is 2f/3, the mean contact force f.
  const double overlap = 1e-6, step = 2 * radius - overlap;
  const Simulation simulation = spheres_on_a_line({0.3e-3, 0.3e-3 + step, 0.3e-3 + 2 * step});
  const Equilibrium e = simulation.equilibrium();
  ASSERT_EQ(e.n_contacts, 2);
  EXPECT_NEAR(simulation.particles().force[1].norm(), 0.0, 1e-12 * simulation.particles().force[0].norm());
  EXPECT_NEAR(e.unbalanced_force_ratio, 2.0 / 3.0, 1e-9);
}

TEST(Equilibrium, SpheresWithoutContactsHaveNoRatio) {
  // A loose sphere counts for neither mean: with no contact at all the ratio is undefined.
  const Simulation apart = spheres_on_a_line({0.2e-3, 0.7e-3});
  EXPECT_EQ(apart.equilibrium().n_contacts, 0);
  EXPECT_TRUE(std::isnan(apart.equilibrium().unbalanced_force_ratio));
  // A third sphere far from a touching pair changes nothing.
  const double overlap = 1e-6;
  const Simulation pair_and_one = spheres_on_a_line({0.2e-3, 0.2e-3 + 2 * radius - overlap, 0.75e-3});
  EXPECT_NEAR(pair_and_one.equilibrium().unbalanced_force_ratio, 1.0, 1e-12);
}

TEST(Equilibrium, KineticEnergyOfKnownVelocities) {
  const double overlap = 1e-6;
  Simulation simulation = spheres_on_a_line({0.3e-3, 0.3e-3 + 2 * radius - overlap, 0.8e-3});
  Particles& particles = simulation.particles();
  particles.velocity[2] = Vec3(0.0, 0.3, 0.4); // |v| = 0.5 m/s, far from the others
  particles.angular_velocity[2] = Vec3(0.0, 0.0, 100.0);
  simulation.measure_stress_now(); // measures again
  const double mass = particles.mass[2], inertia = particles.inertia[2][2];
  const double expected = 0.5 * mass * 0.25 + 0.5 * inertia * 1e4;
  EXPECT_NEAR(simulation.equilibrium().kinetic_energy, expected, 1e-12 * expected);
  EXPECT_NEAR(simulation.equilibrium().kinetic_elastic_ratio(),
              expected / simulation.equilibrium().elastic_energy, 1e-12 * expected);
}

TEST(Equilibrium, GlobalDampingDecaysTheFluctuatingMotionAtItsRate) {
  // Two touching spheres and a free one: the free sphere's speed decays as exp(-gamma t),
  // gamma = 2 zeta sqrt(k_n / m_mean), and it keeps its direction.
  const double overlap = 1e-6, zeta = 0.5;
  Simulation simulation = spheres_on_a_line({0.3e-3, 0.3e-3 + 2 * radius - overlap, 0.8e-3}, zeta);
  const double k = simulation.equilibrium().mean_normal_stiffness;
  const double gamma = 2 * zeta * std::sqrt(k / simulation.particles().mass[0]);
  EXPECT_NEAR(simulation.global_damping_rate(), gamma, 1e-12 * gamma);
  simulation.particles().velocity[2] = Vec3(0.0, 1e-3, 0.0);
  // Fewer steps than a control interval: the rate stays as it is.
  const auto steps = static_cast<int>(simulation.settings().control_interval) - 1;
  for (int n = 0; n < steps; ++n)
    simulation.step();
  const double expected = 1e-3 * std::exp(-gamma * steps * simulation.settings().time_step);
  EXPECT_NEAR(simulation.particles().velocity[2].y(), expected, 1e-12);
  EXPECT_EQ(simulation.particles().velocity[2].x(), 0.0);
}

TEST(Equilibrium, SpinDampsAtItsOwnMultipleOfTheGlobalRate) {
  // dem.integration.global_damping_spin_factor f: a free sphere's spin decays as exp(-f gamma t)
  // while its speed decays as exp(-gamma t); f = 1 damps both alike (the former behaviour).
  const double overlap = 1e-6, zeta = 0.05, spin_factor = 6.0;
  Simulation simulation = spheres_on_a_line({0.3e-3, 0.3e-3 + 2 * radius - overlap, 0.8e-3}, zeta);
  SimulationSettings settings = simulation.settings();
  settings.global_damping_spin_factor = spin_factor;
  simulation.reconfigure(settings);
  const double gamma = simulation.global_damping_rate();
  ASSERT_GT(gamma, 0.0);
  simulation.particles().velocity[2] = Vec3(0.0, 1e-3, 0.0);
  simulation.particles().angular_velocity[2] = Vec3(0.0, 0.0, 10.0);
  const auto steps = static_cast<int>(simulation.settings().control_interval) - 1;
  for (int n = 0; n < steps; ++n)
    simulation.step();
  const double t = steps * simulation.settings().time_step;
  EXPECT_NEAR(simulation.particles().velocity[2].y(), 1e-3 * std::exp(-gamma * t), 1e-15);
  EXPECT_NEAR(simulation.particles().angular_velocity[2].z(), 10.0 * std::exp(-spin_factor * gamma * t),
              1e-12);
  EXPECT_LT(simulation.particles().angular_velocity[2].z(), 10.0 * std::exp(-5.0 * gamma * t));
}

/// The prepared 150-sphere assembly of the tests, consolidated in equilibrium.
const Simulation& prepared() {
  static const Simulation simulation = test::prepared_assembly(test::small_config(150, 5));
  return simulation;
}

TEST(Equilibrium, PreparedAssemblyIsStaticAndHoldsItsStress) {
  const Simulation& start = prepared();
  const EquilibriumConfig tolerances;
  EXPECT_LT(start.equilibrium().unbalanced_force_ratio, tolerances.tolerance);
  // A static state keeps p at a fixed cell: 20,000 steps change it by less than 0.5 %.
  std::printf("[ measured ] prepared: force ratio %.3g torque ratio %.3g kinetic/elastic %.3g\n",
              start.equilibrium().unbalanced_force_ratio, start.equilibrium().unbalanced_torque_ratio,
              start.equilibrium().kinetic_elastic_ratio());
  Simulation held = start;
  const HoldReport report = hold_fixed_cell(held, 20000, make_silent_logger());
  RecordProperty("largest_drift", std::to_string(report.largest_drift));
  EXPECT_LT(report.largest_drift, 5e-3);
  EXPECT_EQ(report.samples.size(), static_cast<std::size_t>(20000 / held.settings().control_interval + 1));
  // The cell did not move.
  EXPECT_EQ(held.cell().lengths(), start.cell().lengths());
}

/// The prepared assembly after 3000 steps of biaxial loading: moving, out of balance.
Simulation loaded_for_3000_steps(const DemConfig& config) {
  Simulation simulation = prepared();
  start_loading(simulation, config);
  for (int n = 0; n < 3000; ++n)
    simulation.step();
  return simulation;
}

TEST(Equilibrium, ForcePassSumsGiveTheTraversalsBits) {
  // A control update that measures the equilibrium takes its contact part from the force pass
  // (ContactSums::balance); measure_equilibrium's own traversal of the records must agree to the
  // bit, on a moving, loaded assembly with the global damping on.
  DemConfig config = test::small_config(150, 5);
  config.integration.global_damping = 0.2;
  Simulation simulation = loaded_for_3000_steps(config);
  ASSERT_GT(simulation.settings().global_damping, 0.0);
  for (int n = 0; n < 3 * simulation.settings().control_interval; ++n) {
    simulation.step();
    if (!simulation.at_control_update()) continue;
    const Equilibrium fused = simulation.equilibrium();
    const Equilibrium traversed =
        measure_equilibrium(simulation.particles(), simulation.neighbors(), simulation.comm());
    ASSERT_GT(fused.n_contacts, 0);
    EXPECT_EQ(fused.n_contacts, traversed.n_contacts);
    EXPECT_EQ(fused.unbalanced_force_ratio, traversed.unbalanced_force_ratio);
    EXPECT_EQ(fused.unbalanced_torque_ratio, traversed.unbalanced_torque_ratio);
    EXPECT_EQ(fused.kinetic_energy, traversed.kinetic_energy);
    EXPECT_EQ(fused.elastic_energy, traversed.elastic_energy);
    EXPECT_EQ(fused.mean_normal_stiffness, traversed.mean_normal_stiffness);
  }
}

TEST(Equilibrium, RelaxationAfterLoadingMeetsTheTolerancesAndGivesTheControlBack) {
  const DemConfig config = test::small_config(150, 5);
  Simulation simulation = loaded_for_3000_steps(config);
  const model::CellControl loading = simulation.control();
  const double length_1 = simulation.cell().lengths()[0];
  const Relaxation relaxed =
      relax_to_equilibrium(simulation, config.equilibrium, 500000, make_silent_logger(), "test");
  EXPECT_LT(relaxed.equilibrium.unbalanced_force_ratio, config.equilibrium.tolerance);
  EXPECT_LT(relaxed.stress_error, config.equilibrium.stress_tolerance);
  EXPECT_EQ(simulation.cell().lengths()[0], length_1); // axis 1 held while relaxing
  EXPECT_EQ(simulation.control().target, loading.target);
  EXPECT_EQ(simulation.control().strain_rate[0], loading.strain_rate[0]);
  EXPECT_EQ(simulation.settings().global_damping, config.integration.global_damping);
}

TEST(Equilibrium, RelaxationThatRunsOutOfStepsNamesTheRatioReached) {
  const DemConfig config = test::small_config(150, 5);
  Simulation simulation = loaded_for_3000_steps(config);
  try {
    (void)relax_to_equilibrium(simulation, config.equilibrium, 20, make_silent_logger(), "test relaxation");
    FAIL() << "expected a ConvergenceError";
  } catch (const ConvergenceError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("test relaxation: not in equilibrium after 20 steps"), std::string::npos)
        << message;
    EXPECT_NE(message.find("unbalanced-force ratio"), std::string::npos) << message;
    EXPECT_EQ(error.code(), ExitCode::convergence_failure);
  }
}

TEST(Equilibrium, LoadCheckpointsAreWrittenStaticAndStayStatic) {
  // A loading run with one checkpoint: the checkpoint records its equilibrium measures, meets
  // the tolerance, and held at a fixed cell keeps p within 0.5 % over 20,000 steps.
  DemConfig config = test::small_config(150, 5);
  config.load.final_strain = 0.004;
  config.load.checkpoint_strains = {0.003};
  const test::TemporaryFolder folder("equilibrium_load");
  Simulation simulation = prepared();
  start_loading(simulation, config);
  const std::string output = folder.file("");
  const LoadSummary summary = run_loading(simulation, config, output, test::test_provenance(),
                                          make_silent_logger(), false, "increments");
  ASSERT_EQ(summary.checkpoints.size(), 1u);
  EXPECT_GT(summary.relaxation_steps, 0);
  const h5::Checkpoint checkpoint = h5::read_checkpoint(summary.checkpoints[0], mpi::Comm(MPI_COMM_SELF));
  EXPECT_LT(checkpoint.unbalanced_force_ratio, config.equilibrium.tolerance);
  EXPECT_TRUE(std::isfinite(checkpoint.kinetic_elastic_ratio));
  Simulation held = from_checkpoint(checkpoint, summary.checkpoints[0], mpi::Comm(MPI_COMM_SELF));
  EXPECT_EQ(held.equilibrium().unbalanced_force_ratio, checkpoint.unbalanced_force_ratio);
  const HoldReport report = hold_fixed_cell(held, 20000, make_silent_logger());
  std::printf("[ measured ] checkpoint at 0.3%%: force ratio %.3g, relaxed in %lld steps, hold drift %.3g\n",
              checkpoint.unbalanced_force_ratio, static_cast<long long>(summary.relaxation_steps),
              report.largest_drift);
  EXPECT_LT(report.largest_drift, 5e-3);
}

TEST(Equilibrium, IncrementalLoadingRelaxesEveryIncrementAndResumesBitForBit) {
  // OVAL's loading: increments of 5e-4, each relaxed to a force ratio of 1e-2, and one more
  // ending at the checkpoint strain 0.07 %, between two multiples; a run resumed from that
  // checkpoint ends in the same bits as the uninterrupted one.
  DemConfig config = test::small_config(150, 5);
  config.load.final_strain = 0.002;
  config.load.increment = 5e-4;
  config.load.checkpoint_strains = {0.0007, 0.001};
  config.equilibrium.at_checkpoints = false; // the increment's own relaxation is what is tested
  config.load.history_interval = 2.5e-4;
  const test::TemporaryFolder folder("equilibrium_increments");
  const std::string output = folder.file("");
  const mpi::Comm self(MPI_COMM_SELF);
  Simulation straight = prepared();
  start_loading(straight, config);
  const LoadSummary first = run_loading(straight, config, output, test::test_provenance(),
                                        make_silent_logger(), false, "increments");
  EXPECT_GT(first.relaxation_steps, 0);
  const std::vector<double> ratios = History::read(output).column("unbalanced_force_ratio");
  const std::vector<double> strains = History::read(output).column("strain_11");
  // Every row after an increment's relaxation (strain a multiple of 5e-4) is near balance.
  for (std::size_t r = 1; r < ratios.size(); ++r) {
    const double increments = -strains[r] / config.load.increment;
    if (std::abs(increments - std::round(increments)) < 1e-3 && -strains[r] > 0) {
      EXPECT_LT(ratios[r], config.load.increment_tolerance) << "row " << r;
    }
  }
  const std::vector<double> p_straight = History::read(output).column("p");
  const h5::Checkpoint checkpoint = h5::read_checkpoint(first.checkpoints[0], self);
  EXPECT_NEAR(-checkpoint.cell.lengths[0] / checkpoint.cell.reference_lengths[0] + 1.0, 0.0007, 1e-6);
  EXPECT_LT(checkpoint.unbalanced_force_ratio, config.load.increment_tolerance); // an increment ended there
  Simulation resumed = from_checkpoint(checkpoint, first.checkpoints[0], self);
  (void)run_loading(resumed, config, output, test::test_provenance(), make_silent_logger(), true,
                    "increments");
  EXPECT_EQ(resumed.step_count(), straight.step_count());
  ASSERT_EQ(resumed.particles().size(), straight.particles().size());
  for (std::size_t k = 0; k < straight.particles().size(); ++k)
    ASSERT_EQ(resumed.particles().position[k], straight.particles().position[k]) << "particle " << k;
  EXPECT_EQ(History::read(output).column("p"), p_straight); // the resumed run rewrote the history
}

} // namespace
