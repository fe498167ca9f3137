#pragma once
// A relaxation stopped on SIGTERM, in the checkpoint written where it stopped: the optional
// /relaxation group (docs/formats/checkpoint.md) holds what the relaxation needs beyond the
// simulation's state to continue to the bits of an uninterrupted run, and what the command was
// doing around it.

#include "common/h5/provenance.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/protocol/relax.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace aniso::dem::io {

struct InterruptedRelaxation {
  std::string command;              ///< the aniso-dem subcommand that ran it: load, relax, consolidate
  std::string purpose;              ///< load: "increment" or "checkpoint"; else the command
  double strain = 0;                ///< load: the loading strain it relaxes at
  double next_history = 0;          ///< load: the strain of the next history row then
  std::int64_t next_checkpoint = 0; ///< load: the index of the next checkpoint then
  protocol::RelaxationState state;
};

/// Writes the simulation's state to `path` as write_checkpoint does, with `relaxation` (if any) in
/// its /relaxation group, atomically (collective).
void write_interrupted_checkpoint(const std::string& path, const Simulation& simulation,
                                  const CheckpointLabels& labels, const h5::Provenance& provenance,
                                  const InterruptedRelaxation* relaxation);

/// The /relaxation group of the checkpoint at `path`, if it has one (every rank reads it).
std::optional<InterruptedRelaxation> read_interrupted_relaxation(const std::string& path);

/// What a checkpoint written after a relaxation records of it: root attributes
/// `static_held_steps` (the steps the state stayed static at the fixed cell) and `static_verified`
/// (1 when that was the whole verification window, 0 when it ended on max_windows).
std::function<void(h5::File&)> relaxation_record(const protocol::Relaxation& relaxed);

/// Where a command writing `output` leaves its interrupted state: `output` with "_interrupted"
/// before its extension (relaxed.h5 -> relaxed_interrupted.h5).
std::string interrupted_path(const std::string& output);

} // namespace aniso::dem::io
