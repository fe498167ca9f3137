#pragma once
// Simulation <-> checkpoint. The checkpoint carries every setting a run needs
// to continue bit for bit, so a restart does not depend on the config.

#include "common/h5/checkpoint.hpp"
#include "dem/simulation.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace aniso::dem::io {

/// The rows this rank owns of the run's full state (pass to h5::write_checkpoint with the
/// simulation's comm). `d50` is stored for the inertial number of later stages.
h5::Checkpoint to_checkpoint(const Simulation& simulation, double d50,
                             const std::vector<std::array<std::uint64_t, 4>>& rng_state);

/// Settings stored in a checkpoint's parameters (material, step, skin, servo).
SimulationSettings settings_from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path);

/// Rebuilds a simulation that continues exactly where the checkpoint was written, decomposed
/// over `comm` (collective; every rank passes the whole checkpoint).
Simulation from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path, const mpi::Comm& comm);

} // namespace aniso::dem::io
