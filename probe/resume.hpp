#pragma once
// A `run` stopped by SIGTERM keeps the forks it finished as fork files (probe_<stem>_fork<N>.h5, the
// files `fork` writes) and the same command then runs only the others. Once the result is written
// the fork files it used are removed: their forks are in the result's /forks, and a later run
// (another build, perhaps) starts afresh.

#include "common/h5/provenance.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "probe/files.hpp"
#include "probe/schedule.hpp"

#include <string>

namespace aniso::probe {

/// The forks whose fork files in `folder` come from this checkpoint (content hash) and `settings`.
/// A fork file of other settings or another checkpoint is run anew and replaced; an unreadable one
/// is named in a warning and run anew. Collective: rank 0 reads, every rank receives.
ForkResults finished_forks(const std::string& folder, const std::string& input, const ProbeSource& source,
                           const ForkSettings& settings, const mpi::Comm& comm, const Logger& logger);

/// Writes, on rank 0, a fork file for each fork done in `results` and not in `finished`.
void keep_forks(const std::string& folder, const std::string& input, const ProbeSource& source,
                const ForkSettings& settings, const ForkResults& results, const ForkResults& finished,
                const h5::Provenance& provenance, const mpi::Comm& comm);

/// Rank 0: removes the fork files of the forks in `finished` (the result now holds them).
void remove_finished(const std::string& folder, const std::string& input, const ForkResults& finished,
                     const mpi::Comm& comm);

/// What a stopped run did and left: "stopped on SIGTERM: forks 0, 1 done (kept in ...); forks 2, ...
/// left; continue with the same command: <command>".
std::string stop_message(const std::string& folder, const std::string& input, const ForkResults& results,
                         const std::string& command);

} // namespace aniso::probe
