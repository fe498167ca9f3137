#pragma once
// The finished pieces of `aniso-dem prepare`, kept in its output folder so that a prepare stopped
// on SIGTERM continues with --resume to the bits of an uninterrupted one
// (docs/formats/checkpoint.md, "Kept pieces of a prepare"):
//   prepare_seized_<cycle>_<refinement>.h5        a compaction cycle's (or refinement's) seized state
//   prepare_consolidated_<cycle>_<refinement>.h5  that state consolidated to p0
//   prepare_seized_<c>_<r>_interrupted.h5         a compaction stopped on SIGTERM
//   prepare_consolidated_<c>_<r>_interrupted.h5   a consolidation stopped on SIGTERM (/relaxation)
// Each is a checkpoint with the protocol's random streams then; all but the last have a /prepare
// group naming the piece, the configuration it was made with and the protocol's state.

#include "common/h5/file.hpp"
#include "common/h5/provenance.hpp"
#include "common/mpi.hpp"
#include "dem/protocol/relax.hpp"
#include "dem/simulation.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace aniso::dem::io {

enum class PieceKind : std::uint8_t { seized, consolidated };

/// Which piece: a compaction cycle (refinement 0) or a refinement of it, seized or consolidated.
struct PieceName {
  PieceKind kind = PieceKind::seized;
  int cycle = 1;
  int refinement = 0;
};

/// What a piece records beside the simulation's state.
struct PieceRecord {
  std::vector<std::array<std::uint64_t, 4>> rng_state; ///< the protocol's streams after the piece
  double compaction_strain = 0; ///< volumetric strain of the last cycle's compaction then
};

/// Where a compaction stands at a control update: with the simulation's state there, all it
/// needs to continue to the bits of an uninterrupted one.
struct CompactionState {
  std::int64_t steps = 0;      ///< taken so far
  bool holding = false;        ///< the cell held still, waiting for the forces to balance
  std::int64_t held_since = 0; ///< the step at which the cell was last held or released
  double start_volume = 0;     ///< cell volume when the compaction began [m^3]
  double start_length = 0;     ///< and its length along x [m]
};

struct KeptCompaction {
  Simulation simulation; ///< mid-compaction
  CompactionState state;
  std::string path;
};

struct KeptPiece {
  Simulation simulation;
  PieceRecord record;
  std::string path;
};

struct KeptRelaxation {
  Simulation simulation; ///< mid-relaxation
  protocol::RelaxationState state;
  std::string path;
};

/// The piece files of a prepare in `folder`, by name (sorted).
std::vector<std::string> prepare_piece_files(const std::string& folder);

/// Before a prepare into `folder` (collective): a fresh one refuses (InputError) a folder that
/// holds pieces, which only --resume continues; returns how many pieces there are.
std::size_t check_prepare_folder(const std::string& folder, bool resume, const mpi::Comm& comm);

/// A prepare's pieces in its output folder. Every call is collective.
class PreparePieces {
public:
  /// `provenance` is written on every piece; its effective configuration is the one a kept
  /// piece must have been made with. The compaction or consolidation in progress is kept, as a
  /// SIGTERM stop keeps it, every `keep_interval_seconds` of wall time (common/keep_clock.hpp).
  PreparePieces(std::string folder, h5::Provenance provenance, const mpi::Comm& comm,
                double keep_interval_seconds);
  /// Keeps nothing and holds nothing: a prepare in memory alone (the tests').
  explicit PreparePieces(const mpi::Comm& comm) : comm_(comm) {}

  /// How often the piece in progress is kept (infinity: never).
  [[nodiscard]] double keep_interval_seconds() const { return keep_interval_seconds_; }

  [[nodiscard]] std::string path(const PieceName& piece) const;
  /// Writes the piece atomically, and removes what was kept of it in progress.
  void keep(const PieceName& piece, const Simulation& simulation, const PieceRecord& record) const;
  /// The piece if the folder holds it; InputError when it was made with another configuration.
  [[nodiscard]] std::optional<KeptPiece> find(const PieceName& piece) const;

  /// Writes the compaction towards `seized` stopped with `state`, atomically; returns the path.
  std::string keep_stopped_compaction(const PieceName& seized, const Simulation& simulation,
                                      const std::vector<std::array<std::uint64_t, 4>>& rng_state,
                                      const CompactionState& state) const;
  /// The compaction towards `seized` stopped on SIGTERM, if the folder holds it.
  [[nodiscard]] std::optional<KeptCompaction> find_stopped_compaction(const PieceName& seized) const;

  /// Writes the consolidation `consolidated` stopped with `state`, atomically; returns the path.
  std::string keep_stopped_consolidation(const PieceName& consolidated, const Simulation& simulation,
                                         const std::vector<std::array<std::uint64_t, 4>>& rng_state,
                                         const protocol::RelaxationState& state) const;
  /// The consolidation `consolidated` stopped on SIGTERM, if the folder holds it.
  [[nodiscard]] std::optional<KeptRelaxation> find_stopped_consolidation(const PieceName& consolidated) const;

  /// Removes every piece file (after prepared.h5 is written).
  void remove_all() const;

private:
  std::string folder_; ///< "": keeps nothing
  h5::Provenance provenance_;
  std::string config_hash_; ///< of provenance_.config
  mpi::Comm comm_;
  double keep_interval_seconds_ = INFINITY;

  [[nodiscard]] bool exists(const std::string& path) const;
  // A checkpoint of `simulation` at `path` with a /prepare group that `fill` completes, atomically.
  void write(const std::string& path, const PieceName& piece, const Simulation& simulation,
             const std::vector<std::array<std::uint64_t, 4>>& rng_state,
             const std::function<void(h5::Group&)>& fill) const;
  // The checkpoint at `path` (its streams in rng_state) and its /prepare group, checked to be
  // `piece` of this configuration; `take` reads the rest of the group.
  [[nodiscard]] Simulation read(const std::string& path, const PieceName& piece,
                                const std::function<void(const h5::Group&)>& take,
                                std::vector<std::array<std::uint64_t, 4>>& rng_state) const;
};

} // namespace aniso::dem::io
