#include "dem/io/prepare_pieces.hpp"

#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/content_hash.hpp"
#include "common/h5/file.hpp"
#include "common/root_only.hpp"
#include "common/units.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/relaxation_state.hpp"
#include "dem/io/run_folder.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <regex>

namespace aniso::dem::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* prepare_group = "prepare";
constexpr const char* prepare_command = "prepare";

const char* kind_name(PieceKind kind) {
  return kind == PieceKind::seized ? "seized" : "consolidated";
}

// The rng_state of a piece: the four streams of the protocol (sizes, placement, agitation,
// refinement), which a resumed prepare continues from.
std::vector<std::array<std::uint64_t, 4>> piece_streams(const h5::Checkpoint& checkpoint,
                                                        const std::string& path) {
  require_file(checkpoint.rng_state.size() == 4,
               fmt::format("{}: /rng_state: {} streams, expected the 4 of a prepare", path,
                           checkpoint.rng_state.size()));
  return checkpoint.rng_state;
}

} // namespace

std::vector<std::string> prepare_piece_files(const std::string& folder) {
  static const std::regex pattern(R"(prepare_(seized|consolidated)_\d+_\d+(_interrupted)?\.h5)");
  return files_matching(folder, pattern);
}

std::size_t check_prepare_folder(const std::string& folder, bool resume, const mpi::Comm& comm) {
  std::size_t count = 0;
  run_on_root(comm, [&] {
    const std::vector<std::string> names = prepare_piece_files(folder);
    count = names.size();
    require_input(resume || names.empty(),
                  fmt::format("prepare: '{}' holds the pieces of a prepare stopped on SIGTERM ({}): continue "
                              "it with --resume, or delete them to prepare anew",
                              folder, fmt::join(names, ", ")));
  });
  return static_cast<std::size_t>(comm.max(static_cast<std::int64_t>(count))); // rank 0's, on every rank
}

PreparePieces::PreparePieces(std::string folder, h5::Provenance provenance, const mpi::Comm& comm,
                             double keep_interval_seconds)
    : folder_(std::move(folder)), provenance_(std::move(provenance)),
      config_hash_(h5::content_hash_of_bytes(provenance_.config)), comm_(comm),
      keep_interval_seconds_(keep_interval_seconds) {}

std::string PreparePieces::path(const PieceName& piece) const {
  return fmt::format("{}/prepare_{}_{}_{}.h5", folder_, kind_name(piece.kind), piece.cycle, piece.refinement);
}

bool PreparePieces::exists(const std::string& path) const {
  if (folder_.empty()) return false;
  return comm_.any(comm_.is_root() && fs::exists(path)); // rank 0's view, on every rank
}

void PreparePieces::write(const std::string& file_path, const PieceName& piece, const Simulation& simulation,
                          const std::vector<std::array<std::uint64_t, 4>>& rng_state,
                          const std::function<void(h5::Group&)>& fill) const {
  if (folder_.empty()) return;
  // The checkpoint and its /prepare group appear together or not at all.
  write_checkpoint(file_path, simulation, {rng_state, {}}, provenance_, [&](h5::File& file) {
    h5::Group group = file.create_group(prepare_group);
    group.write_attribute("piece", kind_name(piece.kind));
    group.write_attribute<std::int32_t>("cycle", piece.cycle);
    group.write_attribute<std::int32_t>("refinement", piece.refinement);
    group.write_attribute("config_hash", config_hash_);
    fill(group);
  });
}

Simulation PreparePieces::read(const std::string& file_path, const PieceName& piece,
                               const std::function<void(const h5::Group&)>& take,
                               std::vector<std::array<std::uint64_t, 4>>& rng_state) const {
  const h5::Checkpoint checkpoint = h5::read_checkpoint(file_path, comm_);
  rng_state = piece_streams(checkpoint, file_path);
  const h5::File file = h5::File::open(file_path);
  require_file(file.has_child(prepare_group),
               fmt::format("{}: no /{} group: not a piece of aniso-dem prepare", file_path, prepare_group));
  const h5::Group group = file.open_group(prepare_group);
  if (group.read_string_attribute("piece") != kind_name(piece.kind) ||
      group.read_attribute<std::int32_t>("cycle") != piece.cycle ||
      group.read_attribute<std::int32_t>("refinement") != piece.refinement)
    group.fail("names another piece than its file name");
  require_input(group.read_string_attribute("config_hash") == config_hash_,
                fmt::format("prepare --resume: '{}' was made with another configuration (its "
                            "/provenance holds it): resume with that configuration, or delete the "
                            "prepare_*.h5 files of '{}' to prepare anew",
                            file_path, folder_));
  take(group);
  return from_checkpoint(checkpoint, file_path, comm_);
}

void PreparePieces::keep(const PieceName& piece, const Simulation& simulation,
                         const PieceRecord& record) const {
  write(path(piece), piece, simulation, record.rng_state,
        [&](h5::Group& group) { group.write_attribute("compaction_strain", record.compaction_strain); });
  if (folder_.empty()) return;
  // The piece supersedes its state in progress (kept on SIGTERM or by the keep clock).
  run_on_root(comm_, [&] {
    const std::string in_progress = interrupted_path(path(piece));
    std::error_code error;
    fs::remove(in_progress, error);
    require_file(!error, fmt::format("prepare: cannot remove '{}': {}", in_progress, error.message()));
  });
}

std::optional<KeptPiece> PreparePieces::find(const PieceName& piece) const {
  const std::string file_path = path(piece);
  if (!exists(file_path)) return std::nullopt;
  PieceRecord record;
  Simulation simulation = read(
      file_path, piece,
      [&](const h5::Group& group) {
        record.compaction_strain = group.read_attribute<double>("compaction_strain");
      },
      record.rng_state);
  return KeptPiece{std::move(simulation), record, file_path};
}

std::string PreparePieces::keep_stopped_compaction(const PieceName& seized, const Simulation& simulation,
                                                   const std::vector<std::array<std::uint64_t, 4>>& rng_state,
                                                   const CompactionState& state) const {
  if (folder_.empty()) return {};
  const std::string file_path = interrupted_path(path(seized));
  write(file_path, seized, simulation, rng_state, [&](h5::Group& group) {
    group.write_attribute<std::int64_t>("steps", state.steps);
    group.write_attribute<std::uint8_t>("holding", state.holding ? 1 : 0);
    group.write_attribute<std::int64_t>("held_since", state.held_since);
    group.write_attribute_with_units("start_volume", state.start_volume, units::cubic_metre);
    group.write_attribute_with_units("start_length", state.start_length, units::metre);
  });
  return file_path;
}

std::optional<KeptCompaction> PreparePieces::find_stopped_compaction(const PieceName& seized) const {
  const std::string file_path = interrupted_path(path(seized));
  if (!exists(file_path)) return std::nullopt;
  CompactionState state;
  std::vector<std::array<std::uint64_t, 4>> rng_state; // those of the seized piece before it, agitated
  Simulation simulation = read(
      file_path, seized,
      [&](const h5::Group& group) {
        state.steps = group.read_attribute<std::int64_t>("steps");
        state.holding = group.read_attribute<std::uint8_t>("holding") != 0;
        state.held_since = group.read_attribute<std::int64_t>("held_since");
        state.start_volume = group.read_attribute<double>("start_volume");
        state.start_length = group.read_attribute<double>("start_length");
      },
      rng_state);
  return KeptCompaction{std::move(simulation), state, file_path};
}

std::string
PreparePieces::keep_stopped_consolidation(const PieceName& consolidated, const Simulation& simulation,
                                          const std::vector<std::array<std::uint64_t, 4>>& rng_state,
                                          const protocol::RelaxationState& state) const {
  if (folder_.empty()) return {};
  InterruptedRelaxation relaxation;
  relaxation.command = prepare_command;
  relaxation.purpose = "consolidation";
  relaxation.state = state;
  const std::string file_path = interrupted_path(path(consolidated));
  write_interrupted_checkpoint(file_path, simulation, {rng_state, {}}, provenance_, &relaxation);
  return file_path;
}

std::optional<KeptRelaxation> PreparePieces::find_stopped_consolidation(const PieceName& consolidated) const {
  const std::string file_path = interrupted_path(path(consolidated));
  if (!exists(file_path)) return std::nullopt;
  const h5::Checkpoint checkpoint = h5::read_checkpoint(file_path, comm_);
  const std::optional<InterruptedRelaxation> relaxation = read_interrupted_relaxation(file_path);
  require_file(relaxation.has_value() && relaxation->command == prepare_command,
               fmt::format("{}: holds no consolidation of aniso-dem prepare stopped on SIGTERM", file_path));
  return KeptRelaxation{from_checkpoint(checkpoint, file_path, comm_), relaxation->state, file_path};
}

void PreparePieces::remove_all() const {
  if (folder_.empty()) return;
  run_on_root(comm_, [&] {
    for (const std::string& name : prepare_piece_files(folder_)) {
      std::error_code error;
      fs::remove(fs::path(folder_) / name, error);
      require_file(!error, fmt::format("prepare: cannot remove '{}/{}': {}", folder_, name, error.message()));
    }
  });
}

} // namespace aniso::dem::io
