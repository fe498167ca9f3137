#pragma once
// Candidate pairs from bins that follow the deforming periodic cell, kept as a
// Verlet list with a skin. Pairs are sorted by (id_i, id_j) with id_i < id_j,
// which fixes the order in which forces are summed on every particle
// (partner id ascending): the root of bit-identical results.

#include "common/cell.hpp"
#include "dem/contact_law.hpp"
#include "dem/particles.hpp"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace aniso::dem {

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
  ContactHistory history;
};

/// How far the pairs of a list may have moved since it was built, from each particle's shift
/// (beyond the cell's affine strain) and, for ovoids, the turn of its axis.
struct ListMotion {
  /// Bound on the change of any pair's centre separation [m]: the rebuild test.
  double separation = 0;
  /// Bound on the change of any pair's gap along a fixed direction (the separation plus each
  /// ovoid's support change, radius times the chord of its axis turn) [m]: what a proof that
  /// a pair is apart must exceed to stay valid.
  double gap = 0;
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
  /// How far this rank's owned particles have moved since the build. With several ranks the
  /// bounds of all ranks combine by their maximum (ghosts are other ranks' owned particles).
  [[nodiscard]] ListMotion motion_since_build(const Particles& particles, const PeriodicCell& cell) const;
  /// True when the particles may have moved far enough to miss a pair (motion of all ranks).
  [[nodiscard]] bool needs_rebuild(const ListMotion& motion) const { return motion.separation > skin_; }
  /// True when owned particles may have moved far enough (fluctuation plus cell strain) to miss a pair.
  [[nodiscard]] bool needs_rebuild(const Particles& particles, const PeriodicCell& cell) const {
    return needs_rebuild(motion_since_build(particles, cell));
  }
  /// Declares the motion of all ranks since the build for the next force pass, which may then
  /// skip the pairs proven apart since (see clearances()). Without it the pass skips none.
  void set_motion(const ListMotion& motion) { gap_motion_ = motion.gap; }
  /// The gap motion declared for this force pass and forgets it (negative: none declared).
  double take_gap_motion() { return std::exchange(gap_motion_, -1.0); }
  /// The largest radius of all particles on all ranks, so that every rank takes the same decisions.
  void set_max_radius(double radius) { global_max_radius_ = radius; }

  [[nodiscard]] const std::vector<Pair>& pairs() const { return pairs_; }
  [[nodiscard]] std::vector<ContactHistory>& history() { return history_; }
  [[nodiscard]] const std::vector<ContactHistory>& history() const { return history_; }
  /// R* and m* of each pair, fixed while the pair exists.
  [[nodiscard]] const std::vector<PairProperties>& properties() const { return properties_; }
  [[nodiscard]] std::vector<ContactRecord>& records() { return records_; }
  [[nodiscard]] const std::vector<ContactRecord>& records() const { return records_; }
  /// Per pair, the last direction that proved an ovoid pair apart (zero: none). A cache for the
  /// narrow phase's early exit only: no result depends on it, so it is not part of the state that
  /// checkpoints and migrating particles carry.
  [[nodiscard]] std::vector<Vec3>& separating_normals() { return separating_normals_; }
  /// Per pair, a proof that it is apart: the gap it had, less the gap motion at that time
  /// and a round-off margin [m]. While it exceeds the gap motion declared since, the pair is
  /// still apart and its narrow phase can be skipped: a pure saving, the forces do not change.
  /// -infinity: no proof. Like separating_normals(), a cache that no result depends on.
  [[nodiscard]] std::vector<double>& clearances() { return clearances_; }
  [[nodiscard]] double skin() const { return skin_; }
  [[nodiscard]] std::int64_t n_builds() const { return n_builds_; }

  /// Index of the pair (i, j) in pairs(), or -1 if absent (binary search by ids).
  [[nodiscard]] std::int64_t find(const Particles& particles, std::uint32_t i, std::uint32_t j) const;

private:
  double skin_;
  std::vector<Pair> pairs_;
  std::vector<ContactHistory> history_;
  std::vector<ContactRecord> records_;
  std::vector<PairProperties> properties_;
  std::vector<Vec3> separating_normals_;
  std::vector<double> clearances_;
  std::vector<std::array<std::uint64_t, 2>>
      pair_ids_; ///< ids of pairs_, for carrying history across migration
  double global_max_radius_ = 0;
  std::vector<Vec3> position_at_build_;
  std::vector<Vec3> axis_at_build_; ///< owned ovoids' axes (zero for spheres, whose turn is irrelevant)
  double gap_motion_ = -1;          ///< declared for the next force pass; negative: none
  Vec3 lengths_at_build_ = Vec3::Ones();
  double max_radius_ = 0;
  std::int64_t n_builds_ = 0;
};

/// Every pair closer than `range` beyond touching, by brute force over all pairs (tests only).
std::vector<Pair> brute_force_pairs(const Particles& particles, const PeriodicCell& cell, double range);

} // namespace aniso::dem
