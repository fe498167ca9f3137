#pragma once
// The force pass: every candidate pair through the narrow phase (the sphere fast path, or the
// ovoid contact of dem/model/ovoid_contact.hpp when either particle is an ovoid) and the contact
// law, forces and torques summed on both particles in pair order (partner id ascending),
// per-pair results kept for stress and output.

#include "common/cell.hpp"
#include "dem/config.hpp"
#include "dem/data/contact_sums.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/model/contact_law.hpp"
#include "dem/model/particle_shape.hpp"

namespace aniso::dem {

struct ForcePass {
  std::int64_t n_touching = 0;
  double worst_overlap = 0;           ///< largest overlap / smaller half-height (NaN if an overlap was NaN)
  std::int64_t worst_pair = -1;       ///< index into NeighborList::pairs() of that pair
  std::int64_t newton_iterations = 0; ///< ovoid narrow phase, summed over pairs
  std::int64_t n_unconverged = 0;     ///< ovoid pairs whose Newton iteration hit its limit
  std::int64_t n_skipped = 0;         ///< pairs skipped as proven apart (NeighborList::proofs)
};

/// What the force law needs from the geometry of one shape pair.
struct ContactInput {
  const model::ShapeTable* shapes = nullptr;
  model::HertzRadius hertz_radius = model::HertzRadius::halfwidth;
};

/// Zeroes forces and torques, then adds every contact's. `strain_rate` is the
/// cell's diagonal rate, which adds the affine part to relative velocities. `bodies` is the
/// caller's scratch for the particles' world-frame bodies, refilled here (kept between passes
/// so that a step allocates nothing). With `sums`, every touching contact this rank counts (its
/// lower-id particle owned here) is added to them as its record is written.
ForcePass compute_contact_forces(data::Particles& particles, const PeriodicCell& cell,
                                 const Vec3& strain_rate, const model::ContactMaterial& material,
                                 double time_step, const ContactInput& input, data::NeighborList& neighbors,
                                 std::vector<model::ConvexBody>& bodies, data::ContactSums* sums = nullptr);

} // namespace aniso::dem
