#pragma once
// The force pass: every candidate pair through the narrow phase (the sphere fast path, or the
// ovoid contact of dem/model/ovoid_contact.hpp when either particle is an ovoid) and the contact
// law, forces and torques summed on both particles in pair order (partner id ascending),
// per-pair results kept for stress and output. A restart rebuilds those per-pair results here
// too, with the same arithmetic, so that a change to the contact geometry or law reaches both.

#include "common/cell.hpp"
#include "dem/data/contact_sums.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/model/contact_law.hpp"
#include "dem/model/ovoid_contact.hpp"
#include "dem/model/particle_shape.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

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
/// lower-id particle owned here) is added to them as its record is written, and to their
/// balance part, when they have one, as measure_equilibrium would add it.
ForcePass compute_contact_forces(data::Particles& particles, const PeriodicCell& cell,
                                 const Vec3& strain_rate, const model::ContactMaterial& material,
                                 double time_step, const ContactInput& input, data::NeighborList& neighbors,
                                 std::vector<model::ConvexBody>& bodies, data::ContactSums* sums = nullptr);

/// A contact as a stored state holds it: what a restart needs to rebuild its record and history.
struct StoredContact {
  std::array<std::uint64_t, 2> ids{};   ///< (id_i, id_j), id_i < id_j
  Vec3 normal = Vec3::Zero();           ///< unit, from i to j
  Vec3 point = Vec3::Zero();            ///< contact point [m], wrapped into the cell
  double overlap = 0;                   ///< [m], > 0
  Vec3 force = Vec3::Zero();            ///< force on i [N]
  Vec3 tangential_force = Vec3::Zero(); ///< elastic tangential force on i (Mindlin history) [N]
  bool sliding = false;
};

/// Overlap of particles i and j (local indices) at their present positions by the force pass's
/// narrow phase (< 0: apart); `guess` (zero: none) is the normal an ovoid pair's iteration starts from.
double pair_overlap(const data::Particles& particles, const PeriodicCell& cell, const ContactInput& input,
                    std::uint32_t i, std::uint32_t j, const Vec3& guess);

/// After a restart: the record and history of every stored contact whose pair this rank holds,
/// as the force pass left them at the stored step (the force on i as stored, the springs and the
/// sphere geometry by the force pass's own arithmetic). Each stored contact must be the one the
/// positions give, and every overlapping pair must have its row: FileError naming `source`
/// otherwise (an edited or damaged file would restart with forces the geometry does not have).
void restore_contact_records(std::span<const StoredContact> contacts, const data::Particles& particles,
                             const PeriodicCell& cell, const model::ContactMaterial& material,
                             const ContactInput& input, data::NeighborList& neighbors,
                             const std::string& source);

} // namespace aniso::dem
