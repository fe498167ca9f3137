// Tests of the force pass's proofs that a pair is apart (NeighborList::proofs): the list's
// two gap-motion bounds cover every change of a pair's support gap along a fixed direction under
// random translation, rotation of ovoids and cell strain; skipping the pairs so proven changes no
// force, torque, history or record bit; and in an assembly mixing spheres and two ovoid shapes,
// every touching pair (sphere-ovoid ones included) has the overlap of the narrow phase alone.
#include "common/cell.hpp"
#include "common/rng.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/force_pass.hpp"
#include "dem/model/integrator.hpp"
#include "dem/model/particle_shape.hpp"
#include "tests/dem/paper_sizes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

namespace {

using aniso::PeriodicCell;
using aniso::Quat;
using aniso::RandomStream;
using aniso::Vec3;
using namespace aniso::dem;
using namespace aniso::dem::data;
using namespace aniso::dem::model;

using namespace aniso::dem::test;
constexpr double kSplice = std::numbers::pi / 4;
constexpr double kAspectRatios[] = {0.5, 0.8, 1.0, 0.5}; // dealt in turn: half alpha = 0.5

Quat random_orientation(RandomStream& stream) {
  const Vec3 axis = Vec3(stream.normal(), stream.normal(), stream.normal()).normalized();
  return Quat(Eigen::AngleAxisd(stream.uniform(0, std::numbers::pi), axis));
}

/// `count` particles of mixed shapes at random positions and orientations (overlaps allowed).
Particles mixed_particles(const PeriodicCell& cell, std::size_t count, std::uint64_t seed) {
  RandomStream stream(seed, 0);
  Particles particles;
  const Vec3& lengths = cell.lengths();
  for (std::size_t k = 0; k < count; ++k) {
    const double radius = k == 0 ? kRadiusMax : stream.uniform(kRadiusMin, kRadiusMax);
    const Vec3 x(stream.uniform(0, lengths[0]), stream.uniform(0, lengths[1]), stream.uniform(0, lengths[2]));
    particles.add(k, radius, kAspectRatios[k % 4], kSplice, kDensity, x, random_orientation(stream));
  }
  return particles;
}

ShapeTable shapes_of(const Particles& particles) {
  ShapeTable shapes(kSplice);
  for (double alpha : particles.aspect_ratio)
    shapes.add(alpha);
  return shapes;
}

/// Support gap of pair k along the fixed unit direction n: a lower bound of the distance
/// between the two bodies when positive.
double support_gap(const Particles& particles, const ShapeTable& shapes, const PeriodicCell& cell,
                   const Pair& pair, const Vec3& n) {
  const Vec3 d = PeriodicCell::minimum_image_of_wrapped(
      particles.position[pair.j] - particles.position[pair.i], cell.lengths());
  const ConvexBody a =
      shapes.body(particles.radius[pair.i], particles.aspect_ratio[pair.i], particles.orientation[pair.i]);
  const ConvexBody b =
      shapes.body(particles.radius[pair.j], particles.aspect_ratio[pair.j], particles.orientation[pair.j]);
  return d.dot(n) - support_value(a, n) - support_value(b, -n);
}

/// Random fluctuating velocities that move a particle by about `shift` per step and spins that
/// turn the largest particle's rim by about `turn`.
void stir(Particles& particles, RandomStream& stream, double dt, double shift, double turn) {
  const double speed = shift / dt;
  const double spin = turn / dt / kRadiusMax;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    particles.velocity[k] = speed * Vec3(stream.normal(), stream.normal(), stream.normal());
    particles.angular_velocity[k] = spin * Vec3(stream.normal(), stream.normal(), stream.normal());
  }
}

// Between any two instants t1 < t2 of one list's life the support gap of a pair along a fixed
// direction falls by at most B(t1) + B(t2) and by at most T(t2) - T(t1) (ApartProof). Returns
// the largest fall as a fraction of each bound.
struct BoundUse {
  double from_build = 0;
  double travelled = 0;
  int rebuilds = 0;
};

BoundUse largest_use_of_the_gap_bounds(double shift, double turn, const Vec3& strain) {
  const PeriodicCell start_cell(Vec3(1.4e-3, 1.4e-3, 1.6e-3));
  Particles particles = mixed_particles(start_cell, 300, 7);
  const ShapeTable shapes = shapes_of(particles);
  RandomStream stream(7, 1);
  const double dt = 1e-8;
  const Vec3 strain_rate = strain / dt;
  PeriodicCell cell = start_cell;
  NeighborList list(kSkin);
  list.build(particles, cell);
  struct Reference {
    std::vector<Vec3> direction; // the centre line when recorded
    std::vector<double> gap;
    double from_build = 0; // B and T when recorded
    double travelled = 0;
  };
  const auto record = [&](double from_build, double travelled) {
    Reference r;
    r.from_build = from_build;
    r.travelled = travelled;
    for (const Pair& pair : list.pairs()) {
      const Vec3 d = PeriodicCell::minimum_image_of_wrapped(
          particles.position[pair.j] - particles.position[pair.i], cell.lengths());
      r.direction.push_back(d.normalized());
      r.gap.push_back(support_gap(particles, shapes, cell, pair, r.direction.back()));
    }
    return r;
  };
  Reference at_build = record(0, 0), recent = at_build;
  std::size_t checks = 0;
  BoundUse use;
  double travelled = 0;
  for (int step = 0; step < 300; ++step) {
    stir(particles, stream, dt, shift, turn);
    drift(particles, cell, strain_rate, dt);
    const ListMotion motion = list.measure_motion(particles, cell);
    EXPECT_GE(motion.gap, motion.separation);
    if (list.needs_rebuild(motion)) {
      list.build(particles, cell);
      ++use.rebuilds;
      travelled = 0;
      at_build = recent = record(0, 0);
      continue;
    }
    travelled += motion.step_gap;
    for (const Reference* reference : {&at_build, &recent}) {
      const double bound_build = reference->from_build + motion.gap;
      const double bound_travel = travelled - reference->travelled;
      for (std::size_t k = 0; k < list.pairs().size(); ++k) {
        const double fall = reference->gap[k] -
                            support_gap(particles, shapes, cell, list.pairs()[k], reference->direction[k]);
        EXPECT_LE(fall, bound_build) << "step " << step << ", pair " << k;
        EXPECT_LE(fall, bound_travel) << "step " << step << ", pair " << k;
        if (fall > bound_build || fall > bound_travel) return use;
        use.from_build = std::max(use.from_build, fall / bound_build);
        use.travelled = std::max(use.travelled, fall / bound_travel);
        ++checks;
      }
    }
    if (step % 7 == 0) recent = record(motion.gap, travelled);
  }
  std::printf("[ measured ] %zu gap checks, %d rebuilds, largest fall %.3f of B(t1) + B(t2), %.3f of T(t2) - "
              "T(t1)\n",
              checks, use.rebuilds, use.from_build, use.travelled);
  EXPECT_GT(checks, 100000u);
  return use;
}

TEST(ApartProofs, GapMotionBoundsEveryPairsGapChange) {
  const BoundUse use = largest_use_of_the_gap_bounds(kSkin / 25, kSkin / 25, Vec3(-1e-3, 0.3e-3, 0.6e-3));
  EXPECT_GT(use.rebuilds, 2);
  // The bounds are maxima over all particles: the worst pair uses a good part of each.
  EXPECT_GT(use.from_build, 0.2);
  EXPECT_GT(use.travelled, 0.2);
}

// Turns alone: the centres stand still, so only the ovoids' axis terms of the bounds can cover it.
TEST(ApartProofs, GapMotionBoundsTheTurnOfOvoidsAlone) {
  const BoundUse use = largest_use_of_the_gap_bounds(0.0, kSkin / 25, Vec3::Zero());
  EXPECT_EQ(use.rebuilds, 0);
  EXPECT_GT(use.from_build, 0.2);
  EXPECT_GT(use.travelled, 0.2);
}

void expect_same_bits(const Vec3& a, const Vec3& b, const char* what, std::size_t k) {
  for (int c = 0; c < 3; ++c)
    ASSERT_EQ(a[c], b[c]) << what << " of entry " << k;
}

// Forces with the proofs against the same passes without them, over a run whose list is
// rebuilt several times: every bit equal, and most pair evaluations skipped.
TEST(ApartProofs, SkippingProvenPairsChangesNoForce) {
  PeriodicCell cell(Vec3(1.6e-3, 1.6e-3, 1.8e-3)); // loose: pairs touch and part
  Particles particles = mixed_particles(cell, 300, 11);
  const ShapeTable shapes = shapes_of(particles);
  const ContactInput input{&shapes, HertzRadius::curvature};
  const ContactMaterial material;
  RandomStream stream(11, 1);
  const double dt = 1e-8;
  const Vec3 strain_rate(-1e-4 / dt, 0.5e-4 / dt, 0.5e-4 / dt);
  NeighborList list(kSkin);
  list.build(particles, cell);
  std::vector<ConvexBody> bodies, reference_bodies;
  std::int64_t skipped = 0, evaluated = 0, touching = 0;
  int rebuilds = 0;
  for (int step = 0; step < 300; ++step) {
    // The particles go for 10 steps and come back for 6, in turns: the motion bound rises and
    // falls, so that pairs touch on the way out and part on the way back while a proof they had
    // before touching would hold again; and the list still needs rebuilds now and then.
    if (step % 16 == 0) stir(particles, stream, dt, kSkin / 40, kSkin / 40);
    if (step % 16 == 10) {
      for (std::size_t k = 0; k < particles.size(); ++k) {
        particles.velocity[k] = -particles.velocity[k];
        particles.angular_velocity[k] = -particles.angular_velocity[k];
      }
    }
    drift(particles, cell, (step % 16 < 10 ? 1.0 : -1.0) * strain_rate, dt);
    const ListMotion motion = list.measure_motion(particles, cell);
    if (list.needs_rebuild(motion)) {
      list.build(particles, cell);
      ++rebuilds;
    } else {
      list.set_motion(motion);
    }
    NeighborList reference = list;
    reference.proofs().assign(reference.proofs().size(), ApartProof{});
    Particles reference_particles = particles;
    const ForcePass pass =
        compute_contact_forces(particles, cell, strain_rate, material, dt, input, list, bodies);
    const ForcePass full = compute_contact_forces(reference_particles, cell, strain_rate, material, dt, input,
                                                  reference, reference_bodies);
    ASSERT_EQ(full.n_skipped, 0);
    ASSERT_EQ(pass.n_touching, full.n_touching) << "step " << step;
    for (std::size_t k = 0; k < particles.size(); ++k) {
      expect_same_bits(particles.force[k], reference_particles.force[k], "force", k);
      expect_same_bits(particles.torque[k], reference_particles.torque[k], "torque", k);
    }
    for (std::size_t k = 0; k < list.pairs().size(); ++k) {
      expect_same_bits(list.history()[k].tangential_force, reference.history()[k].tangential_force,
                       "tangential force", k);
      expect_same_bits(list.history()[k].normal, reference.history()[k].normal, "history normal", k);
      ASSERT_EQ(list.history()[k].sliding, reference.history()[k].sliding);
      ASSERT_EQ(list.records()[k].overlap, reference.records()[k].overlap);
      expect_same_bits(list.records()[k].force_on_i, reference.records()[k].force_on_i, "record force", k);
    }
    skipped += pass.n_skipped;
    evaluated += static_cast<std::int64_t>(list.pairs().size());
    touching += pass.n_touching;
  }
  std::printf(
      "[ measured ] %lld pair evaluations, %lld skipped as proven apart, %lld touching, %d rebuilds\n",
      static_cast<long long>(evaluated), static_cast<long long>(skipped), static_cast<long long>(touching),
      rebuilds);
  EXPECT_GT(touching, 1000);
  EXPECT_GT(rebuilds, 1);
  EXPECT_GT(skipped, (evaluated - touching) / 5); // of the pairs apart
}

// A sphere meeting an ovoid in a mixed assembly takes the convex narrow phase with the sphere's
// own body: its overlap is that of convex_contact on the two bodies, and a sphere pair's is the
// radius sum less the distance.
TEST(MixedAssembly, EveryTouchingPairHasItsNarrowPhaseOverlap) {
  const PeriodicCell cell(Vec3(1.3e-3, 1.3e-3, 1.5e-3));
  Particles particles = mixed_particles(cell, 300, 13);
  const ShapeTable shapes = shapes_of(particles);
  NeighborList list(kSkin);
  list.build(particles, cell);
  std::vector<ConvexBody> bodies;
  const ForcePass pass = compute_contact_forces(particles, cell, Vec3::Zero(), ContactMaterial{}, 1e-8,
                                                {&shapes, HertzRadius::curvature}, list, bodies);
  int sphere_ovoid = 0, sphere_sphere = 0, ovoid_ovoid = 0;
  for (std::size_t k = 0; k < list.pairs().size(); ++k) {
    const Pair& pair = list.pairs()[k];
    const Vec3 d = PeriodicCell::minimum_image_of_wrapped(
        particles.position[pair.j] - particles.position[pair.i], cell.lengths());
    const bool sphere_i = particles.aspect_ratio[pair.i] == 1.0,
               sphere_j = particles.aspect_ratio[pair.j] == 1.0;
    const ConvexBody a =
        shapes.body(particles.radius[pair.i], particles.aspect_ratio[pair.i], particles.orientation[pair.i]);
    const ConvexBody b =
        shapes.body(particles.radius[pair.j], particles.aspect_ratio[pair.j], particles.orientation[pair.j]);
    const double expected = sphere_i && sphere_j
                                ? particles.radius[pair.i] + particles.radius[pair.j] - d.norm()
                                : convex_contact(a, b, d, d, false).overlap;
    const double recorded = list.records()[k].overlap;
    if (!(expected > 0)) {
      EXPECT_EQ(recorded, 0.0) << "pair " << k << " is apart";
      continue;
    }
    const double size = 2 * std::min(particles.radius[pair.i], particles.radius[pair.j]);
    EXPECT_NEAR(recorded, expected, 1e-9 * size) << "pair " << k;
    (sphere_i && sphere_j ? sphere_sphere : sphere_i || sphere_j ? sphere_ovoid : ovoid_ovoid) += 1;
  }
  std::printf("[ measured ] touching pairs: %d sphere-ovoid, %d sphere-sphere, %d ovoid-ovoid\n",
              sphere_ovoid, sphere_sphere, ovoid_ovoid);
  EXPECT_EQ(pass.n_touching, sphere_ovoid + sphere_sphere + ovoid_ovoid);
  EXPECT_GT(sphere_ovoid, 20);
  EXPECT_GT(sphere_sphere, 3);
}

} // namespace
