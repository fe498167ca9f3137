#pragma once
// Hand-built checkpoints for the fabric tests: sphere lattices (simple cubic, FCC) in a periodic
// cell, optionally jittered and affinely stretched, with every contact found by brute force and
// given a Hertz-like normal force plus a small tangential force, and single placed particles.

#include "common/h5/checkpoint.hpp"
#include "common/h5/provenance.hpp"
#include "common/rng.hpp"
#include "common/tensor.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "../common/checkpoint_sample.hpp"

namespace aniso::fabric::test {

enum class Lattice { simple_cubic, fcc };

struct LatticeSpec {
  Lattice kind = Lattice::simple_cubic;
  int cells = 4;               ///< cubic unit cells per axis
  double diameter = 1e-3;      ///< [m]
  double spacing = 0.98e-3;    ///< nearest-neighbour distance before stretching [m]
  Vec3 stretch = Vec3::Ones(); ///< affine stretch of the cell per axis (strain + 1)
  double jitter = 0;           ///< random displacement amplitude, in units of the diameter
  std::uint64_t seed = 1;
  double tangential_ratio = 0.1; ///< tangential force / normal force
  bool random_orientations = false;
};

inline Quat random_orientation(RandomStream& random) {
  Quat q(random.normal(), random.normal(), random.normal(), random.normal());
  return q.normalized();
}

/// Adds every touching pair (minimum image) as a contact of `c`, with forces.
inline void add_contacts(h5::Checkpoint& c, double tangential_ratio) {
  const std::size_t n = c.particles.size();
  const Vec3 L = c.cell.lengths;
  for (std::uint64_t i = 0; i < n; ++i) {
    for (std::uint64_t j = i + 1; j < n; ++j) {
      Vec3 d = c.particles.position[j] - c.particles.position[i];
      Vec3i shift = Vec3i::Zero();
      for (int a = 0; a < 3; ++a) {
        shift[a] = static_cast<int>(-std::nearbyint(d[a] / L[a]));
        d[a] += shift[a] * L[a];
      }
      const double distance = d.norm();
      const double reach = 0.5 * (c.particles.diameter[i] + c.particles.diameter[j]);
      if (distance >= reach) continue;
      const Vec3 normal = d / distance;
      const double overlap = reach - distance;
      const double fn = 1e9 * std::pow(overlap, 1.5) * std::sqrt(0.25 * c.particles.diameter[i]);
      const Vec3 tangent = normal.unitOrthogonal();
      c.contacts.particles.push_back({i, j});
      c.contacts.image_shift.push_back(shift);
      c.contacts.normal.push_back(normal);
      Vec3 point = c.particles.position[i] + (0.5 * c.particles.diameter[i] - 0.5 * overlap) * normal;
      for (int a = 0; a < 3; ++a)
        point[a] -= std::floor(point[a] / L[a]) * L[a];
      c.contacts.point.push_back(point);
      c.contacts.overlap.push_back(overlap);
      c.contacts.force.push_back(-fn * normal + tangential_ratio * fn * tangent);
      c.contacts.tangential_force.push_back(tangential_ratio * fn * tangent);
      c.contacts.sliding.push_back(0);
    }
  }
}

/// An empty checkpoint with a cell of the given lengths and the parameters fabric reads.
inline h5::Checkpoint empty_checkpoint(const Vec3& lengths, const Vec3& reference_lengths, double d50) {
  h5::Checkpoint c;
  c.time = 1e-3;
  c.step = 1000;
  c.time_step = 1e-8;
  c.cell.lengths = lengths;
  c.cell.reference_lengths = reference_lengths;
  c.parameters = {{"d50", d50, "m"}, {"density", 2650.0, "kg/m^3"}};
  c.rng_state = {{1, 2, 3, 4}};
  return c;
}

/// Appends one particle (id = its row).
inline void add_particle(h5::Checkpoint& c, double diameter, double aspect_ratio, const Vec3& position,
                         const Quat& orientation, const Vec3& velocity = Vec3::Zero()) {
  const std::size_t k = c.particles.size();
  c.particles.resize(k + 1);
  const double mass = 2650.0 * std::numbers::pi * diameter * diameter * diameter * aspect_ratio / 6.0;
  c.particles.id[k] = k;
  c.particles.diameter[k] = diameter;
  c.particles.aspect_ratio[k] = aspect_ratio;
  c.particles.mass[k] = mass;
  c.particles.inertia[k] = Vec3::Constant(0.1 * mass * diameter * diameter);
  c.particles.position[k] = position;
  c.particles.orientation[k] = orientation;
  c.particles.velocity[k] = velocity;
  c.particles.angular_velocity[k] = Vec3::Zero();
  c.particles.force[k] = Vec3::Zero();
  c.particles.torque[k] = Vec3::Zero();
}

inline h5::Checkpoint lattice_checkpoint(const LatticeSpec& spec) {
  const bool fcc = spec.kind == Lattice::fcc;
  const double a = fcc ? spec.spacing * std::sqrt(2.0) : spec.spacing; // cubic lattice constant
  const Vec3 reference = Vec3::Constant(a * spec.cells);
  h5::Checkpoint c = empty_checkpoint(reference.cwiseProduct(spec.stretch), reference, spec.diameter);
  std::vector<Vec3> basis{Vec3::Zero()};
  if (fcc) basis = {Vec3(0, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 0, 0.5), Vec3(0, 0.5, 0.5)};
  RandomStream random(spec.seed, 0);
  for (int x = 0; x < spec.cells; ++x)
    for (int y = 0; y < spec.cells; ++y)
      for (int z = 0; z < spec.cells; ++z)
        for (const Vec3& b : basis) {
          Vec3 p = (Vec3(x, y, z) + b + Vec3::Constant(0.25)) * a;
          p += spec.jitter * spec.diameter *
               Vec3(random.uniform01() - 0.5, random.uniform01() - 0.5, random.uniform01() - 0.5);
          p = p.cwiseProduct(spec.stretch);
          const Quat q = spec.random_orientations ? random_orientation(random) : Quat::Identity();
          const Vec3 v =
              1e-3 * Vec3(random.uniform01() - 0.5, random.uniform01() - 0.5, random.uniform01() - 0.5);
          add_particle(c, spec.diameter, 1.0, p, q, v);
        }
  add_contacts(c, spec.tangential_ratio);
  return c;
}

/// The fixed provenance of the checkpoint tests (tests/common/checkpoint_sample.hpp).
inline h5::Provenance test_provenance() {
  return aniso::test::sample_provenance(1);
}

} // namespace aniso::fabric::test
