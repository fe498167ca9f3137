#pragma once
// The timing table a DEM run ends with (common/timer.hpp): the engine's sections of the time
// steps, the protocol's own work outside them (checkpoint and history output), and the rest.

#include "common/log.hpp"
#include "common/mpi.hpp"
#include "common/timer.hpp"

#include <string>
#include <vector>

namespace aniso::dem::protocol {

/// The rows of the engine's sections, then the protocol's, then "other" (collective).
std::vector<TimingRow> run_timing(const SectionTimes& engine, const SectionTimes& protocol,
                                  double wall_seconds, const mpi::Comm& comm);

/// Logs the table (info, rank 0), and after it each `phases` line: how much of the stepping a
/// protocol phase took ("relaxation: 28,269 of 56,560 steps, 4.1 s").
void log_timing(const Logger& logger, const std::vector<TimingRow>& rows, double wall_seconds, int n_ranks,
                const std::vector<std::string>& phases = {});

} // namespace aniso::dem::protocol
