#pragma once
// Running the seven forks (reference and six increments) on the ranks there are: the
// communicator is split into min(ranks, forks to run) groups, group g runs the forks g, g+groups, ...
// of those to run in turn, each
// fork decomposed over its group's ranks; then every fork's result is broadcast
// from its group so that all ranks hold all six. The DEM gives the same bits on
// any number of ranks, so the results do not depend on the split.

#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "probe/config.hpp"
#include "probe/fork.hpp"

#include <array>
#include <optional>
#include <string>

namespace aniso::probe {

/// Number of fork groups for `n_ranks` ranks and `n_to_run` forks to run, and the group of a rank
/// (ranks in contiguous blocks).
int fork_group_count(int n_ranks, int n_to_run = n_fork_files);
int fork_group_of_rank(int rank, int n_ranks, int n_to_run = n_fork_files);

/// One slot per fork, empty where the fork is not (yet) done.
using ForkResults = std::array<std::optional<ForkResult>, n_fork_files>;

/// The forks of `checkpoint` that `finished` lacks, over `comm` (collective); every rank receives
/// every result, `finished` ones included. On SIGTERM (stop_requested) each group drops the fork
/// it is running and starts no other: the forks not done stay empty. With `times`, adds the wall
/// time of this rank's forks to it.
ForkResults run_forks(const h5::Checkpoint& checkpoint, const std::string& path, const ProbeConfig& config,
                      const mpi::Comm& comm, const Logger& logger, ForkTimes* times,
                      const ForkResults& finished);

/// All seven forks (run_forks with none finished); Interrupted if SIGTERM stopped any.
std::array<ForkResult, n_fork_files> run_all_forks(const h5::Checkpoint& checkpoint, const std::string& path,
                                                   const ProbeConfig& config, const mpi::Comm& comm,
                                                   const Logger& logger, ForkTimes* times = nullptr);

/// Packs a fork result into bytes and back (for the broadcast); exact.
std::vector<char> pack_fork(const ForkResult& fork);
ForkResult unpack_fork(const std::vector<char>& bytes);

} // namespace aniso::probe
