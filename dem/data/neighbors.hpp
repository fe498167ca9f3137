#pragma once
// Candidate pairs from bins that follow the deforming periodic cell, kept as a
// Verlet list with a skin. Pairs are sorted by (id_i, id_j) with id_i < id_j,
// which fixes the order in which forces are summed on every particle
// (partner id ascending): the root of bit-identical results.

#include "common/cell.hpp"
#include "dem/data/particles.hpp"
#include "dem/model/contact_law.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace aniso::dem::data {

struct Pair {
  std::uint32_t i; ///< local index of the particle with the lower id
  std::uint32_t j; ///< local index of the particle with the higher id
};

/// What the last force evaluation found for one pair (overlap <= 0: not touching).
struct ContactRecord {
  Vec3 normal = Vec3::Zero();      ///< unit, from i to j
  Vec3 branch = Vec3::Zero();      ///< centre of j minus centre of i (minimum image) [m]
  Vec3 point = Vec3::Zero();       ///< contact point relative to the centre of i [m]
  double overlap = 0;              ///< [m]
  Vec3 force_on_i = Vec3::Zero();  ///< [N]
  double normal_force = 0;         ///< elastic normal force [N]
  double tangential_stiffness = 0; ///< [N/m], for the elastic energy
};

/// The history of a contact, keyed by particle ids: what travels with a migrating particle.
struct HistoryRecord {
  std::uint64_t id_i = 0; ///< lower id
  std::uint64_t id_j = 0;
  model::ContactHistory history;
};

/// How far the pairs of a list may have moved, from each particle's shift (beyond the cell's
/// affine strain) and, for ovoids, the turn of its axis. With several ranks the bounds of all
/// ranks combine by their maximum (ghosts are other ranks' owned particles).
struct ListMotion {
  /// Since the build: bound on the change of any pair's centre separation [m], the rebuild test.
  double separation = 0;
  /// Since the build: bound on the change of any pair's gap along a fixed direction (the
  /// separation plus each ovoid's support change, radius times the chord of its axis turn) [m].
  double gap = 0;
  /// The same gap bound over the last step alone (since the previous measure_motion) [m].
  double step_gap = 0;
};

/// A proof that a pair is apart: the gap it had (a lower bound of its surfaces' distance) less
/// the motion bounds at that time and a round-off margin [m]. Between instants t1 < t2 a gap
/// falls by at most B(t1) + B(t2), B the bound since the build, and by at most T(t2) - T(t1), T
/// the sum of the step bounds; the proof holds while either is short of the gap.
struct ApartProof {
  double after_build = -std::numeric_limits<double>::infinity();  ///< gap - B(t1): holds while > B(t)
  double after_travel = -std::numeric_limits<double>::infinity(); ///< gap + T(t1): holds while > T(t)
  [[nodiscard]] bool exists() const { return after_build != -std::numeric_limits<double>::infinity(); }
};

/// The motion bounds of one force pass, B and T above (negative: none declared, no proof holds).
struct GapBounds {
  double from_build = -1;
  double travelled = -1;
  [[nodiscard]] bool known() const { return from_build >= 0; }
  [[nodiscard]] bool hold(const ApartProof& proof) const {
    return proof.after_build > from_build || proof.after_travel > travelled;
  }
  [[nodiscard]] ApartProof prove(double gap, double margin) const {
    return {gap - from_build - margin, gap + travelled - margin};
  }
};

class NeighborList {
public:
  /// `skin` is the extra distance beyond touching that a pair may close before the next rebuild [m].
  explicit NeighborList(double skin) : skin_(skin) {}

  /// Rebuilds the pairs whose surfaces are closer than the skin and of which at least one
  /// particle is owned, and carries the contact history of pairs that survive over from the
  /// previous list (matched by ids) or from `carried` (histories that came with migrating particles).
  void build(const Particles& particles, const PeriodicCell& cell,
             const std::vector<HistoryRecord>& carried = {});
  /// How far this rank's owned particles have moved since the build and since the previous
  /// call (which it advances to now): call it once per step.
  [[nodiscard]] ListMotion measure_motion(const Particles& particles, const PeriodicCell& cell);
  /// True when the particles may have moved far enough to miss a pair (motion of all ranks).
  [[nodiscard]] bool needs_rebuild(const ListMotion& motion) const { return motion.separation > skin_; }
  /// True when owned particles may have moved far enough (fluctuation plus cell strain) to miss a pair.
  [[nodiscard]] bool needs_rebuild(const Particles& particles, const PeriodicCell& cell) const {
    return needs_rebuild(motion(particles, cell));
  }
  /// Declares the motion of all ranks for the next force pass, which may then skip the pairs
  /// proven apart (see proofs()). Without it the pass skips none.
  void set_motion(const ListMotion& motion) {
    travelled_ += motion.step_gap;
    bounds_ = {motion.gap, travelled_};
  }
  /// The bounds declared for this force pass, and forgets them.
  GapBounds take_gap_bounds() { return std::exchange(bounds_, GapBounds{}); }
  /// The largest radius of all particles on all ranks, so that every rank takes the same decisions.
  void set_max_radius(double radius) { global_max_radius_ = radius; }

  [[nodiscard]] const std::vector<Pair>& pairs() const { return pairs_; }
  [[nodiscard]] std::vector<model::ContactHistory>& history() { return history_; }
  [[nodiscard]] const std::vector<model::ContactHistory>& history() const { return history_; }
  /// R* and m* of each pair, fixed while the pair exists.
  [[nodiscard]] const std::vector<model::PairProperties>& properties() const { return properties_; }
  [[nodiscard]] std::vector<ContactRecord>& records() { return records_; }
  [[nodiscard]] const std::vector<ContactRecord>& records() const { return records_; }
  /// Per pair, the last direction that proved an ovoid pair apart (zero: none). A cache for the
  /// narrow phase's early exit only: no result depends on it, so it is not part of the state that
  /// checkpoints and migrating particles carry.
  [[nodiscard]] std::vector<Vec3>& separating_normals() { return separating_normals_; }
  /// Per pair, a proof that it is apart (none: ApartProof{}). While it holds the pair's narrow
  /// phase can be skipped: a pure saving, the forces do not change. Like separating_normals(),
  /// a cache that no result depends on.
  [[nodiscard]] std::vector<ApartProof>& proofs() { return proofs_; }
  [[nodiscard]] double skin() const { return skin_; }
  [[nodiscard]] std::int64_t n_builds() const { return n_builds_; }

  /// Index of the pair (i, j) in pairs(), or -1 if absent (binary search by ids).
  [[nodiscard]] std::int64_t find(const Particles& particles, std::uint32_t i, std::uint32_t j) const;

private:
  double skin_;
  std::vector<Pair> pairs_;
  std::vector<model::ContactHistory> history_;
  std::vector<ContactRecord> records_;
  std::vector<model::PairProperties> properties_;
  std::vector<Vec3> separating_normals_;
  std::vector<ApartProof> proofs_;
  std::vector<std::array<std::uint64_t, 2>>
      pair_ids_; ///< ids of pairs_, for carrying history across migration
  double global_max_radius_ = 0;
  [[nodiscard]] ListMotion motion(const Particles& particles, const PeriodicCell& cell) const;
  std::vector<Vec3> position_at_build_;
  std::vector<Vec3> axis_at_build_;   ///< owned ovoids' axes (zero for spheres, whose turn is irrelevant)
  std::vector<Vec3> position_before_; ///< at the previous measure_motion, and the axes and lengths
  std::vector<Vec3> axis_before_;
  Vec3 lengths_before_ = Vec3::Ones();
  double travelled_ = 0; ///< T: the step bounds summed since the build
  GapBounds bounds_;     ///< declared for the next force pass
  Vec3 lengths_at_build_ = Vec3::Ones();
  double max_radius_ = 0;
  std::int64_t n_builds_ = 0;
};

/// Every pair closer than `range` beyond touching, by brute force over all pairs (tests only).
std::vector<Pair> brute_force_pairs(const Particles& particles, const PeriodicCell& cell, double range);

} // namespace aniso::dem::data
