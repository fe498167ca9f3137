#pragma once
// The timing table a DEM run ends with (common/timer.hpp): the engine's sections of the time
// steps, the protocol's own work outside them (checkpoint and history output), and the rest.

#include "common/log.hpp"
#include "common/mpi.hpp"
#include "common/timer.hpp"
#include "dem/simulation.hpp"

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

/// The halo volume of the decomposition the run ended with, one line for the timing table's
/// phases (collective; none on one rank): ghosts per rank, their share of the owned particles, and
/// what a per-step refresh sends. It is what a run on many ranks pays in MPI at every step.
std::vector<std::string> halo_lines(const Simulation& simulation);

} // namespace aniso::dem::protocol
