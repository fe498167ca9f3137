// Rigid-body dynamics of ovoids: torque-free rotation (dem/model/rotation.hpp) conserves energy and
// angular momentum, and oblique collisions of two ovoids through the whole time step conserve
// linear and angular momentum (with friction) and energy (without friction and damping).
#include "common/rng.hpp"
#include "dem/config.hpp"
#include "dem/io/parameters.hpp"
#include "dem/measures.hpp"
#include "dem/model/rotation.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace {

using aniso::Quat;
using aniso::Vec3;
using namespace aniso::dem;
using namespace aniso::dem::data;
using namespace aniso::dem::io;
using namespace aniso::dem::model;

TEST(OvoidRotation, TorqueFreeMotionConservesEnergyAndAngularMomentum) {
  const Vec3 inertia = particle_inertia(1.0, 0.5, std::numbers::pi / 4, 1.0);
  ASSERT_GT(inertia.z(), inertia.x()); // oblate: the axis is the axis of largest inertia
  Quat q(Eigen::AngleAxisd(0.4, Vec3(1, 2, -1).normalized()));
  Vec3 omega(3.0, -1.0, 2.0);
  const Vec3 momentum = inertia_times(inertia, q * Vec3::UnitZ(), omega);
  const double energy = rotational_energy(inertia, q, omega);
  for (int step = 0; step < 100000; ++step)
    free_rotation(q, omega, inertia, 1e-3);
  EXPECT_NEAR(rotational_energy(inertia, q, omega) / energy, 1.0, 1e-10); // round-off over 1e5 steps
  EXPECT_LT((inertia_times(inertia, q * Vec3::UnitZ(), omega) - momentum).norm() / momentum.norm(), 1e-10);
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
}

// The axis of a free axisymmetric body precesses about L at |L| / I1: its distance after 1.7 s,
// taken in `n_steps` equal steps, from the analytic axis.
double precession_error(int n_steps) {
  const Vec3 inertia(2.0, 2.0, 3.0);
  Quat q = Quat::Identity();
  Vec3 omega(0.5, 0.0, 1.0);
  const Vec3 momentum = inertia_times(inertia, Vec3::UnitZ(), omega);
  const double rate = momentum.norm() / inertia.x();
  for (int step = 0; step < n_steps; ++step)
    free_rotation(q, omega, inertia, 1.7 / n_steps);
  EXPECT_LT((particle_axis(q) - q * Vec3::UnitZ()).norm(), 1e-15);
  const Vec3 expected = Eigen::AngleAxisd(rate * 1.7, momentum.normalized()) * Vec3::UnitZ();
  return (q * Vec3::UnitZ() - expected).norm();
}

TEST(OvoidRotation, MatchesTheAnalyticPrecession) {
  EXPECT_LT(precession_error(1), 1e-14); // one step of 1.7 s: the library's sin and cos
}

// 17,000 steps of 1e-4 s: half angles below 1e-4 rad take the series for sine and cosine in
// free_rotation, which must be exact to round-off (a wrong x^3 term puts the axis 1e-8 off).
TEST(OvoidRotation, SmallStepsMatchTheAnalyticPrecession) {
  EXPECT_LT(precession_error(17000), 1e-11);
}

struct CollisionTotals {
  Vec3 momentum = Vec3::Zero();
  Vec3 angular_momentum = Vec3::Zero(); // about the cell origin, orbital plus spin
  double energy = 0;
  int contact_steps = 0;
};

CollisionTotals totals(const Simulation& simulation) {
  const Particles& p = simulation.particles();
  CollisionTotals t;
  for (std::size_t k = 0; k < p.n_owned; ++k) {
    t.momentum += p.mass[k] * p.velocity[k];
    t.angular_momentum +=
        p.position[k].cross(p.mass[k] * p.velocity[k]) +
        inertia_times(p.inertia[k], p.orientation[k] * Vec3::UnitZ(), p.angular_velocity[k]);
  }
  const StateMeasures m = simulation.measure();
  t.energy = m.kinetic_energy + m.elastic_energy;
  return t;
}

// Two ovoids of aspect ratio 0.5 in random orientations, thrown at each other off-centre.
CollisionTotals collide(double friction, int seed, CollisionTotals& start) {
  DemConfig config;
  config.particles.aspect_ratio = 0.5;
  // An impact at 2 m/s resolved by about 30 steps (0.13 of the Rayleigh step of the volume-
  // equivalent sphere, 0.2 of that of the half-height used until 2026-12-02): at the loading
  // default of 0.5 it gets fewer than the 10 this test asks for (docs/methods/dem.md, "Time
  // step").
  config.integration.time_step_fraction = 0.13;
  const double radius = 0.1e-3;
  aniso::RandomStream stream(static_cast<std::uint64_t>(seed), 0);
  const auto random_quat = [&] {
    const double w = stream.normal(), x = stream.normal(), y = stream.normal(), z = stream.normal();
    return Quat(w, x, y, z).normalized();
  };
  Particles particles;
  const Vec3 centre = Vec3::Constant(0.5e-3);
  const double beta = config.particles.splice_angle;
  particles.add(0, radius, 0.5, beta, 2650, centre - Vec3(1.05 * radius, 0.2 * radius, 0), random_quat());
  particles.add(1, radius, 0.5, beta, 2650, centre + Vec3(1.05 * radius, 0.2 * radius, 0.1 * radius),
                random_quat());
  particles.velocity[0] = Vec3(1.0, 0.1, 0.0);
  particles.velocity[1] = Vec3(-1.0, 0.0, 0.05);
  particles.angular_velocity[0] = Vec3(0, 0, 2e3);
  const aniso::PeriodicCell state(Vec3::Constant(1e-3));
  SimulationSettings settings = settings_from_config(config, 2 * radius);
  settings.material.friction = friction;
  settings.material.damping_ratio = 0;
  Simulation simulation(std::move(particles), state, model::CellControl{}, settings,
                        aniso::mpi::Comm(MPI_COMM_SELF));
  start = totals(simulation);
  CollisionTotals end;
  bool touched = false;
  for (int step = 0; step < 20000; ++step) {
    simulation.step();
    const bool touching = simulation.measure().n_contacts > 0;
    if (touching) ++end.contact_steps;
    touched = touched || touching;
    if (touched && !touching) break;
  }
  const int steps = end.contact_steps;
  end = totals(simulation);
  end.contact_steps = steps;
  return end;
}

TEST(OvoidCollision, ConservesMomentumWithFrictionAndEnergyWithout) {
  for (int seed = 1; seed <= 5; ++seed) {
    CollisionTotals start;
    const CollisionTotals rough = collide(0.5, seed, start);
    ASSERT_GT(rough.contact_steps, 10) << "seed " << seed;
    const double p_scale = start.momentum.norm() + 1e-6 * 1e-3 * 1e-3; // momentum of the pair is nearly 0
    EXPECT_LT((rough.momentum - start.momentum).norm() / p_scale, 1e-10) << "seed " << seed;
    EXPECT_LT((rough.angular_momentum - start.angular_momentum).norm() / start.angular_momentum.norm(), 1e-10)
        << "seed " << seed;
    EXPECT_LT(rough.energy, start.energy * (1 + 1e-6)); // friction only dissipates
    const CollisionTotals smooth = collide(0.0, seed, start);
    std::printf("[ measured ] seed %d: %d steps in contact; frictionless energy error %.3g, with friction "
                "%.3g of the energy dissipated\n",
                seed, smooth.contact_steps, smooth.energy / start.energy - 1,
                1 - rough.energy / start.energy);
    EXPECT_NEAR(smooth.energy / start.energy, 1.0, 2e-4) << "seed " << seed;
  }
}

} // namespace
