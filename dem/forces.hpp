#pragma once
// The force pass: every candidate pair through the narrow phase (the sphere fast path, or the
// ovoid contact of dem/ovoid_contact.hpp when either particle is an ovoid) and the contact
// law, forces and torques summed on both particles in pair order (partner id ascending),
// per-pair results kept for stress and output.

#include "common/cell.hpp"
#include "dem/config.hpp"
#include "dem/contact_law.hpp"
#include "dem/contact_sums.hpp"
#include "dem/neighbors.hpp"
#include "dem/particle_shape.hpp"
#include "dem/particles.hpp"

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
  const ShapeTable* shapes = nullptr;
  HertzRadius hertz_radius = HertzRadius::halfwidth;
};

/// Zeroes forces and torques, then adds every contact's. `strain_rate` is the
/// cell's diagonal rate, which adds the affine part to relative velocities. `bodies` is the
/// caller's scratch for the particles' world-frame bodies, refilled here (kept between passes
/// so that a step allocates nothing). With `sums`, every touching contact this rank counts (its
/// lower-id particle owned here) is added to them as its record is written.
ForcePass compute_contact_forces(Particles& particles, const PeriodicCell& cell, const Vec3& strain_rate,
                                 const ContactMaterial& material, double time_step, const ContactInput& input,
                                 NeighborList& neighbors, std::vector<ConvexBody>& bodies,
                                 ContactSums* sums = nullptr);

/// Geometry of the pair of world-frame bodies a and b with centre separation d (minimum image,
/// from a to b), for an ovoid on either side; `guess` is the normal to start from. The Hertz radius follows
/// `input.hertz_radius`. With `separating` (the pair's cached separating direction, zero for none), a pair
/// that this direction still proves apart is answered at once; the cache is then updated: the new separating
/// direction if the pair is apart, zero if it touches.
struct OvoidPairGeometry {
  ContactGeometry contact;
  double hertz_radius = 0;
};
OvoidPairGeometry ovoid_pair_geometry(const ConvexBody& a, const ConvexBody& b, const Vec3& d,
                                      const Vec3& guess, const PairProperties& properties,
                                      const ContactInput& input, bool stop_if_separated,
                                      Vec3* separating = nullptr);

} // namespace aniso::dem
