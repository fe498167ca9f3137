// The FIRE minimiser (dem/protocol/fire.hpp) through the relaxation it drives
// (dem/protocol/relax.hpp), on hand-made assemblies whose static state is known: a
// frictionless compressed lattice of spheres, and of ovoids with parallel axes, displaced and
// set moving at random must come back to the lattice (the one state where every force balances);
// a chain of spheres, where each sphere touches two, and a stack of ovoids pressed cap to cap;
// and a frictional lattice, which must end
// balanced and stay so. A relaxation that cannot converge within its budget stops with
// ConvergenceError naming the ratio it reached.
#include "common/error.hpp"
#include "common/rng.hpp"
#include "dem/io/parameters.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/model/rotation.hpp"
#include "dem/protocol/relax.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using aniso::Vec3;
using namespace aniso;
using namespace aniso::dem;

constexpr double radius = 0.1e-3;
constexpr int cells =
    3; // face-centred cubic cells per axis: the cell spans more than twice the interaction range

struct Lattice {
  Simulation simulation;
  std::vector<Vec3> sites; ///< every particle's site, by id
};

/// A face-centred cubic lattice (12 contacts a particle: rigid under central forces alone) of
/// particles of half-width `radius` and aspect ratio `aspect`, axes along x3, its x3 scaled by
/// `aspect`, in a cell that compresses the nearest neighbours' centre distance to 2 radius -
/// `overlap`. Friction `friction`, no damping but the minimiser's.
Lattice lattice(double aspect, double overlap, double friction) {
  DemConfig config = test::small_config(4 * cells * cells * cells);
  config.particles.aspect_ratio = aspect;
  config.material.friction = friction;
  const double side = std::sqrt(2.0) * (2 * radius - overlap); // of a cubic cell of four sites
  const Vec3 scale(side, side, aspect * side);
  const std::vector<Vec3> basis{Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 0, 0.5), Vec3(0, 0.5, 0.5)};
  data::Particles particles;
  std::vector<Vec3> sites;
  std::uint64_t id = 0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      for (int k = 0; k < cells; ++k)
        for (const Vec3& b : basis) {
          sites.push_back((Vec3(i, j, k) + b + Vec3::Constant(0.25)).cwiseProduct(scale));
          particles.add(id++, radius, aspect, config.particles.splice_angle, config.particles.density,
                        sites.back());
        }
  SimulationSettings settings = io::settings_from_config(config, 2 * radius);
  settings.material.damping_ratio = 0.0;
  return {Simulation(std::move(particles), PeriodicCell(scale * cells), model::CellControl{}, settings,
                     mpi::Comm(MPI_COMM_SELF)),
          sites};
}

/// Moves every particle by up to `shift` along each axis, turns ovoids by up to `turn` radians
/// and sets them moving at up to `speed`, from one seeded stream.
void disturb(Simulation& simulation, double shift, double turn, double speed) {
  RandomStream stream(11, 0);
  data::Particles& particles = simulation.particles();
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    particles.position[k] +=
        Vec3(stream.uniform(-shift, shift), stream.uniform(-shift, shift), stream.uniform(-shift, shift));
    particles.velocity[k] =
        Vec3(stream.uniform(-speed, speed), stream.uniform(-speed, speed), stream.uniform(-speed, speed));
    if (particles.aspect_ratio[k] != 1.0) {
      const Vec3 axis(stream.uniform(-1, 1), stream.uniform(-1, 1), 0.0);
      particles.orientation[k] = Quat(Eigen::AngleAxisd(turn, axis.normalized())) * particles.orientation[k];
    }
  }
}

EquilibriumConfig fire_tolerances(double tolerance) {
  EquilibriumConfig config;
  config.method = Relaxer::fire;
  config.tolerance = tolerance;
  config.verify_steps = 0;
  return config;
}

/// The largest distance of a particle from its site, the lattice's drift as a whole removed.
double largest_offset(const Lattice& lattice) {
  const data::Particles& particles = lattice.simulation.particles();
  const Vec3 lengths = lattice.simulation.cell().lengths();
  Vec3 mean = Vec3::Zero();
  std::vector<Vec3> offsets(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    offsets[k] = PeriodicCell::minimum_image_of_wrapped(
        particles.position[k] - lattice.sites[particles.id[k]], lengths);
    mean += offsets[k];
  }
  mean /= static_cast<double>(particles.size());
  double largest = 0;
  for (const Vec3& offset : offsets)
    largest = std::max(largest, (offset - mean).norm());
  return largest;
}

TEST(Minimiser, FrictionlessSphereLatticeReturnsToItsSites) {
  const double overlap = 1e-3 * radius;
  Lattice l = lattice(1.0, overlap, 0.0);
  ASSERT_EQ(l.simulation.equilibrium().n_contacts, 6 * 4 * cells * cells * cells);
  const Mat3 stress = l.simulation.stress();
  disturb(l.simulation, 0.2 * overlap, 0.0, 1e-3);
  ASSERT_GT(largest_offset(l), 0.05 * overlap);
  const protocol::Relaxation relaxed = protocol::relax_to_equilibrium(l.simulation, fire_tolerances(1e-9),
                                                                      200000, make_silent_logger(), "test");
  // Force ratio 1e-9 leaves offsets of about 1e-9 of the contact's compression.
  EXPECT_LT(largest_offset(l), 1e-6 * overlap) << relaxed.steps << " steps";
  EXPECT_NEAR(l.simulation.stress()(0, 0), stress(0, 0), 1e-8 * std::abs(stress(0, 0)));
  EXPECT_NEAR(l.simulation.stress()(2, 2), stress(2, 2), 1e-8 * std::abs(stress(2, 2)));
  std::printf("sphere lattice: static again in %lld steps\n", static_cast<long long>(relaxed.steps));
}

// Ovoids of aspect ratio 0.9 in the face-centred lattice with x3 scaled by 0.9 touch all twelve
// neighbours at an overlap of 1% of their half-width (flatter ones, or less compressed, touch
// only the four in their layer, and a layer alone is not rigid). Their aligned state balances
// by symmetry but is not stable: disturbed, the ovoids turn (by about 0.19 rad) into a state
// of lower energy. Whatever that state, it must be static: balanced in force and torque, and
// kept through an undamped window with every particle where the minimiser left it (to 1e-4 of
// the overlap: the residual force of 1e-8 moves them by picometres).
TEST(Minimiser, FrictionlessOvoidLatticeFindsAStaticState) {
  const double overlap = 1e-2 * radius;
  Lattice l = lattice(0.9, overlap, 0.0);
  ASSERT_EQ(l.simulation.equilibrium().n_contacts, 6 * 4 * cells * cells * cells);
  disturb(l.simulation, 0.05 * overlap, 1e-3, 1e-3);
  EquilibriumConfig config = fire_tolerances(1e-8);
  config.verify_steps = 4000;
  const protocol::Relaxation relaxed =
      protocol::relax_to_equilibrium(l.simulation, config, 400000, make_silent_logger(), "test");
  EXPECT_LT(relaxed.equilibrium.unbalanced_force_ratio, 1e-8);
  EXPECT_LT(relaxed.equilibrium.unbalanced_torque_ratio, 1e-8);
  EXPECT_GE(relaxed.verifying_steps, config.verify_steps);
  const std::vector<Vec3> before = l.simulation.particles().position;
  for (int k = 0; k < 4000; ++k)
    l.simulation.step();
  double moved = 0;
  for (std::size_t k = 0; k < before.size(); ++k)
    moved =
        std::max(moved, PeriodicCell::minimum_image_of_wrapped(
                            l.simulation.particles().position[k] - before[k], l.simulation.cell().lengths())
                            .norm());
  EXPECT_LT(moved, 1e-4 * overlap); // a state that gave way would move by the overlap or more
  std::printf("ovoid lattice: static in %lld steps\n", static_cast<long long>(relaxed.steps));
}

// With friction the ovoids' static state is not unique either; it must be balanced and verified.
TEST(Minimiser, FrictionalOvoidLatticeEndsBalancedAndVerified) {
  const double overlap = 1e-2 * radius;
  Lattice l = lattice(0.9, overlap, 0.5);
  disturb(l.simulation, 0.05 * overlap, 1e-3, 1e-3);
  EquilibriumConfig config = fire_tolerances(1e-6);
  config.verify_steps = 4000;
  const protocol::Relaxation relaxed =
      protocol::relax_to_equilibrium(l.simulation, config, 200000, make_silent_logger(), "test");
  EXPECT_LT(relaxed.equilibrium.unbalanced_force_ratio, 1e-6);
  EXPECT_LT(relaxed.equilibrium.unbalanced_torque_ratio, 1e-6);
  EXPECT_GE(relaxed.verifying_steps, config.verify_steps);
}

// Four spheres on a line along x1 in a cell four compressed diameters long: each touches two.
TEST(Minimiser, ChainOfTouchingSpheresComesToEqualSpacing) {
  DemConfig config = test::small_config(4);
  config.material.friction = 0.0;
  const double overlap = 2e-3 * radius, spacing = 2 * radius - overlap;
  data::Particles particles;
  for (int k = 0; k < 4; ++k)
    particles.add(static_cast<std::uint64_t>(k), radius, 1.0, config.particles.splice_angle,
                  config.particles.density,
                  Vec3((k + 0.5) * spacing + (k == 1 ? 0.3 * overlap : 0.0), 0.5e-3, 0.5e-3));
  SimulationSettings settings = io::settings_from_config(config, 2 * radius);
  settings.material.damping_ratio = 0.0;
  Simulation simulation(std::move(particles), PeriodicCell(Vec3(4 * spacing, 1e-3, 1e-3)),
                        model::CellControl{}, settings, mpi::Comm(MPI_COMM_SELF));
  ASSERT_EQ(simulation.equilibrium().n_contacts, 4);
  (void)protocol::relax_to_equilibrium(simulation, fire_tolerances(1e-10), 100000, make_silent_logger(),
                                       "test");
  const auto& x = simulation.particles().position;
  for (int k = 0; k < 4; ++k) {
    const double gap =
        PeriodicCell::minimum_image_of_wrapped(x[(k + 1) % 4] - x[k], simulation.cell().lengths())[0];
    EXPECT_NEAR(gap, spacing, 1e-8 * overlap) << "pair " << k;
  }
}

// Eight alpha = 0.5 ovoids stacked along x1 on their axes, each pressing its two neighbours cap
// to cap. One pushed along the stack must come back to equal spacing, every axis still along x1.
// (A turned one is no test: the compressed column buckles sideways, as a chain of spheres
// would, and falls apart.)
TEST(Minimiser, StackOfOvoidsComesBackToItsAlignedEqualSpacing) {
  constexpr int n = 8;
  constexpr double aspect = 0.5;
  DemConfig config = test::small_config(n);
  config.particles.aspect_ratio = aspect;
  config.material.friction = 0.0;
  const double overlap = 2e-3 * radius, spacing = 2 * aspect * radius - overlap;
  const Quat axis_along_x1(Eigen::AngleAxisd(std::acos(-1.0) / 2, Vec3::UnitY()));
  data::Particles particles;
  for (int k = 0; k < n; ++k) {
    particles.add(static_cast<std::uint64_t>(k), radius, aspect, config.particles.splice_angle,
                  config.particles.density,
                  Vec3((k + 0.5) * spacing + (k == 2 ? 0.3 * overlap : 0.0), 0.5e-3, 0.5e-3), axis_along_x1);
  }
  SimulationSettings settings = io::settings_from_config(config, 2 * radius);
  settings.material.damping_ratio = 0.0;
  Simulation simulation(std::move(particles), PeriodicCell(Vec3(n * spacing, 1e-3, 1e-3)),
                        model::CellControl{}, settings, mpi::Comm(MPI_COMM_SELF));
  ASSERT_EQ(simulation.equilibrium().n_contacts, n);
  const protocol::Relaxation relaxed = protocol::relax_to_equilibrium(simulation, fire_tolerances(1e-10),
                                                                      200000, make_silent_logger(), "test");
  const data::Particles& p = simulation.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::size_t next = (k + 1) % p.size();
    const double gap = PeriodicCell::minimum_image_of_wrapped(p.position[next] - p.position[k],
                                                              simulation.cell().lengths())[0];
    EXPECT_NEAR(gap, spacing, 1e-6 * overlap) << "pair " << k;
    const Vec3 axis = p.orientation[k] * Vec3::UnitZ();
    EXPECT_GT(std::abs(axis[0]), 1.0 - 1e-10) << "ovoid " << p.id[k] << " axis " << axis.transpose();
  }
  std::printf("ovoid stack: static again in %lld steps\n", static_cast<long long>(relaxed.steps));
}

// With friction the static state is not unique, but it must be balanced and stay balanced and
// keep p through a window of the run's own dynamics.
TEST(Minimiser, FrictionalLatticeEndsBalancedAndVerified) {
  const double overlap = 1e-3 * radius;
  Lattice l = lattice(1.0, overlap, 0.5);
  disturb(l.simulation, 0.2 * overlap, 0.0, 1e-3);
  EquilibriumConfig config = fire_tolerances(1e-6);
  config.verify_steps = 4000;
  const protocol::Relaxation relaxed =
      protocol::relax_to_equilibrium(l.simulation, config, 200000, make_silent_logger(), "test");
  EXPECT_LT(relaxed.equilibrium.unbalanced_force_ratio, 1e-6);
  EXPECT_GE(relaxed.verifying_steps, config.verify_steps);
}

TEST(Minimiser, ARelaxationBeyondItsBudgetNamesTheRatioReached) {
  Lattice l = lattice(1.0, 1e-3 * radius, 0.5);
  disturb(l.simulation, 2e-4 * radius, 0.0, 1e-3);
  try {
    (void)protocol::relax_to_equilibrium(l.simulation, fire_tolerances(1e-12), 200, make_silent_logger(),
                                         "budget");
    FAIL() << "no ConvergenceError";
  } catch (const ConvergenceError& error) {
    EXPECT_NE(std::string(error.what()).find("budget: not in equilibrium after 200 steps"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("unbalanced-force ratio"), std::string::npos) << error.what();
  }
}

} // namespace
