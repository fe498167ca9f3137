#pragma once
// Running the seven forks (reference and six increments) on the ranks there are: the
// communicator is split into min(ranks, 7) groups, group g runs forks g, g+groups, ... in turn, each
// fork decomposed over its group's ranks; then every fork's result is broadcast
// from its group so that all ranks hold all six. The DEM gives the same bits on
// any number of ranks, so the results do not depend on the split.

#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "probe/config.hpp"
#include "probe/fork.hpp"

#include <array>
#include <string>

namespace aniso::probe {

/// Number of fork groups for `n_ranks` ranks, and the group of a rank (ranks in contiguous blocks).
int fork_group_count(int n_ranks);
int fork_group_of_rank(int rank, int n_ranks);

/// All seven forks of `checkpoint` over `comm` (collective); every rank receives every result.
/// With `times`, adds the wall time of this rank's forks to it.
std::array<ForkResult, n_fork_files> run_all_forks(const h5::Checkpoint& checkpoint, const std::string& path,
                                                   const ProbeConfig& config, const mpi::Comm& comm,
                                                   const Logger& logger, ForkTimes* times = nullptr);

/// Packs a fork result into bytes and back (for the broadcast); exact.
std::vector<char> pack_fork(const ForkResult& fork);
ForkResult unpack_fork(const std::vector<char>& bytes);

} // namespace aniso::probe
