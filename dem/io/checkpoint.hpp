#pragma once
// Simulation <-> checkpoint. The checkpoint carries every setting a run needs to continue bit
// for bit (the parameter table, parameters.hpp, says which), so a restart does not depend on
// the config. This folder and common/h5/ are the only places that know the file's layout.

#include "common/h5/checkpoint.hpp"
#include "dem/simulation.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace aniso::dem::io {

/// Root attribute of a checkpoint written by `aniso-dem replicate`: the file it tiled (with
/// replicated_from_hash and replicate_copies; dem/interop/replicate.hpp). Such a file is no state
/// a loading passed through, so `load --resume` refuses it.
inline constexpr const char* replicated_from_attribute = "replicated_from";

/// What a checkpoint records beside the simulation's own state.
struct CheckpointLabels {
  std::vector<std::array<std::uint64_t, 4>> rng_state; ///< every random stream's state (prepare)
  std::string run_id;                                  ///< the loading run that wrote it (load)
};

/// The rows this rank owns of the run's full state (pass to h5::write_checkpoint with the
/// simulation's comm); the equilibrium ratios are measured fresh (collective).
h5::Checkpoint to_checkpoint(const Simulation& simulation, const CheckpointLabels& labels = {});

/// Writes the simulation's state to `path` atomically (collective) and returns what was written.
h5::Checkpoint write_checkpoint(const std::string& path, const Simulation& simulation,
                                const CheckpointLabels& labels, const h5::Provenance& provenance,
                                const std::function<void(h5::File&)>& add = {});

/// Rebuilds a simulation that continues exactly where the checkpoint was written, decomposed
/// over `comm` (collective; every rank passes the whole checkpoint). FileError naming `path`
/// for a file the simulation cannot start from.
Simulation from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path, const mpi::Comm& comm);

/// The cell and its controller as a checkpoint stores them, and back.
h5::CellState cell_state(const PeriodicCell& cell, const model::CellControl& control);
std::pair<PeriodicCell, model::CellControl> cell_and_control(const h5::CellState& state);

} // namespace aniso::dem::io
