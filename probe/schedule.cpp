#include "probe/schedule.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <vector>

namespace aniso::probe {
namespace {

// Every field as a double: the integers are counts far below 2^53, so the round trip is exact.
constexpr std::size_t n_scalars = 12;

std::vector<double> fields_of(const ForkResult& f) {
  std::vector<double> v{static_cast<double>(f.index),
                        f.strain_rate,
                        f.time_step,
                        static_cast<double>(f.half_steps),
                        static_cast<double>(f.hold_steps),
                        static_cast<double>(f.contacts_start),
                        static_cast<double>(f.sliding_start),
                        static_cast<double>(f.contacts_final),
                        static_cast<double>(f.sliding_final),
                        static_cast<double>(f.samples_half.size()),
                        static_cast<double>(f.samples_final.size()),
                        0.0};
  v.insert(v.end(), f.stress_start.data(), f.stress_start.data() + 9);
  for (const Vec3* e : {&f.strain_half, &f.strain_final})
    v.insert(v.end(), e->data(), e->data() + 3);
  for (const auto* samples : {&f.samples_half, &f.samples_final})
    for (const Mat3& m : *samples)
      v.insert(v.end(), m.data(), m.data() + 9);
  return v;
}

} // namespace

int fork_group_count(int n_ranks, int n_to_run) {
  return std::max(1, std::min(n_ranks, n_to_run));
}

int fork_group_of_rank(int rank, int n_ranks, int n_to_run) {
  return static_cast<int>(static_cast<std::int64_t>(rank) * fork_group_count(n_ranks, n_to_run) / n_ranks);
}

std::vector<char> pack_fork(const ForkResult& fork) {
  const std::vector<double> fields = fields_of(fork);
  std::vector<char> bytes(fields.size() * sizeof(double));
  std::memcpy(bytes.data(), fields.data(), bytes.size());
  return bytes;
}

ForkResult unpack_fork(const std::vector<char>& bytes) {
  check_invariant(bytes.size() % sizeof(double) == 0 && bytes.size() >= n_scalars * sizeof(double),
                  "packed fork result has whole fields");
  std::vector<double> v(bytes.size() / sizeof(double));
  std::memcpy(v.data(), bytes.data(), bytes.size());
  ForkResult f;
  const auto count = [&](std::size_t k) { return static_cast<std::int64_t>(v[k]); };
  f.index = static_cast<int>(v[0]);
  f.strain_rate = v[1];
  f.time_step = v[2];
  f.half_steps = count(3);
  f.hold_steps = count(4);
  f.contacts_start = count(5);
  f.sliding_start = count(6);
  f.contacts_final = count(7);
  f.sliding_final = count(8);
  f.samples_half.resize(static_cast<std::size_t>(count(9)));
  f.samples_final.resize(static_cast<std::size_t>(count(10)));
  check_invariant(v.size() == n_scalars + 15 + 9 * (f.samples_half.size() + f.samples_final.size()),
                  "packed fork result has the size its counts say");
  auto next = v.begin() + static_cast<std::ptrdiff_t>(n_scalars);
  const auto take = [&](double* out, std::ptrdiff_t n) {
    std::copy(next, next + n, out);
    next += n;
  };
  take(f.stress_start.data(), 9);
  take(f.strain_half.data(), 3);
  take(f.strain_final.data(), 3);
  for (auto* samples : {&f.samples_half, &f.samples_final})
    for (Mat3& m : *samples)
      take(m.data(), 9);
  return f;
}

ForkResults run_forks(const h5::Checkpoint& checkpoint, const std::string& path, const ProbeConfig& config,
                      const mpi::Comm& comm, const Logger& logger, ForkTimes* times,
                      const ForkResults& finished) {
  std::vector<int> pending;
  for (int index = 0; index < n_fork_files; ++index)
    if (!finished[static_cast<std::size_t>(index)]) pending.push_back(index);
  ForkResults results = finished;
  if (pending.empty()) return results;
  const int n_ranks = comm.size();
  const auto n_pending = static_cast<int>(pending.size());
  const int groups = fork_group_count(n_ranks, n_pending);
  const int group = fork_group_of_rank(comm.rank(), n_ranks, n_pending);
  mpi::Comm group_comm = comm.split(group, comm.rank());
  try {
    for (int k = group; k < n_pending; k += groups) {
      const int index = pending[static_cast<std::size_t>(k)];
      results[static_cast<std::size_t>(index)] =
          run_fork(checkpoint, path, index, config, group_comm, logger, times);
    }
  } catch (const Interrupted& stop) {
    logger->debug("{}", stop.what()); // the group's ranks agree; its later forks stay empty
  }
  group_comm.free();
  // The lowest world rank of each group holds its results; it broadcasts them to everyone (no
  // bytes: the fork was not done).
  for (int k = 0; k < n_pending; ++k) {
    const int index = pending[static_cast<std::size_t>(k)];
    const int owner_group = k % groups;
    int owner = 0;
    while (fork_group_of_rank(owner, n_ranks, n_pending) != owner_group)
      ++owner;
    auto& slot = results[static_cast<std::size_t>(index)];
    std::vector<char> bytes;
    if (comm.rank() == owner && slot) bytes = pack_fork(*slot);
    comm.broadcast(bytes, owner);
    slot.reset();
    if (!bytes.empty()) slot = unpack_fork(bytes);
  }
  return results;
}

std::array<ForkResult, n_fork_files> run_all_forks(const h5::Checkpoint& checkpoint, const std::string& path,
                                                   const ProbeConfig& config, const mpi::Comm& comm,
                                                   const Logger& logger, ForkTimes* times) {
  const ForkResults results = run_forks(checkpoint, path, config, comm, logger, times, {});
  std::array<ForkResult, n_fork_files> all;
  for (int index = 0; index < n_fork_files; ++index) {
    const auto& slot = results[static_cast<std::size_t>(index)];
    if (!slot) throw Interrupted(fmt::format("fork {} stopped on SIGTERM", index));
    all[static_cast<std::size_t>(index)] = *slot;
  }
  return all;
}

} // namespace aniso::probe
