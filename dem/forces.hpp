#pragma once
// The force pass: every candidate pair through the narrow phase (spheres) and
// the contact law, forces and torques summed on both particles in pair order
// (partner id ascending), per-pair results kept for stress and output.

#include "common/cell.hpp"
#include "dem/contact_law.hpp"
#include "dem/neighbors.hpp"
#include "dem/particles.hpp"

namespace aniso::dem {

struct ForcePass {
  std::int64_t n_touching = 0;
  double worst_overlap = 0;     ///< largest overlap / smaller radius (NaN if an overlap was NaN)
  std::int64_t worst_pair = -1; ///< index into NeighborList::pairs() of that pair
};

/// Zeroes forces and torques, then adds every contact's. `strain_rate` is the
/// cell's diagonal rate, which adds the affine part to relative velocities.
ForcePass compute_contact_forces(Particles& particles, const PeriodicCell& cell, const Vec3& strain_rate,
                                 const ContactMaterial& material, double time_step, NeighborList& neighbors);

} // namespace aniso::dem
