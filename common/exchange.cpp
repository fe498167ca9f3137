#include "common/exchange.hpp"

#include "common/error.hpp"

#include <numeric>

namespace aniso {

std::vector<std::vector<char>> exchange_bytes(const mpi::Comm& comm,
                                              const std::vector<std::vector<char>>& outgoing) {
  const auto n_ranks = static_cast<std::size_t>(comm.size());
  check_invariant(outgoing.size() == n_ranks, "one outgoing buffer per rank");
  std::vector<int> send_counts(n_ranks), receive_counts(n_ranks);
  for (std::size_t r = 0; r < n_ranks; ++r)
    send_counts[r] = static_cast<int>(outgoing[r].size());
  if (MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm.raw()) !=
      MPI_SUCCESS) {
    throw Error(ExitCode::internal_error, "MPI_Alltoall (exchange counts) failed");
  }
  std::vector<int> send_offsets(n_ranks, 0), receive_offsets(n_ranks, 0);
  std::exclusive_scan(send_counts.begin(), send_counts.end(), send_offsets.begin(), 0);
  std::exclusive_scan(receive_counts.begin(), receive_counts.end(), receive_offsets.begin(), 0);
  std::vector<char> send(static_cast<std::size_t>(send_offsets.back() + send_counts.back()));
  for (std::size_t r = 0; r < n_ranks; ++r) {
    std::copy(outgoing[r].begin(), outgoing[r].end(), send.begin() + send_offsets[r]);
  }
  std::vector<char> receive(static_cast<std::size_t>(receive_offsets.back() + receive_counts.back()));
  if (MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPI_CHAR, receive.data(),
                    receive_counts.data(), receive_offsets.data(), MPI_CHAR, comm.raw()) != MPI_SUCCESS) {
    throw Error(ExitCode::internal_error, "MPI_Alltoallv (exchange) failed");
  }
  std::vector<std::vector<char>> incoming(n_ranks);
  for (std::size_t r = 0; r < n_ranks; ++r) {
    incoming[r].assign(receive.begin() + receive_offsets[r],
                       receive.begin() + receive_offsets[r] + receive_counts[r]);
  }
  return incoming;
}

void FixedExchange::resize(const mpi::Comm& comm, const std::vector<std::size_t>& send_counts,
                           const std::vector<std::size_t>& receive_counts) {
  const auto n_ranks = static_cast<std::size_t>(comm.size());
  check_invariant(send_counts.size() == n_ranks && receive_counts.size() == n_ranks, "one count per rank");
  const auto me = static_cast<std::size_t>(comm.rank());
  check_invariant(send_counts[me] == 0 && receive_counts[me] == 0, "nothing is exchanged with oneself");
  send_offsets_.assign(n_ranks + 1, 0);
  receive_offsets_.assign(n_ranks + 1, 0);
  std::inclusive_scan(send_counts.begin(), send_counts.end(), send_offsets_.begin() + 1);
  std::inclusive_scan(receive_counts.begin(), receive_counts.end(), receive_offsets_.begin() + 1);
  send_.resize(send_offsets_.back());
  receive_.resize(receive_offsets_.back());
}

std::span<double> FixedExchange::outgoing(int rank) {
  const auto r = static_cast<std::size_t>(rank);
  return {send_.data() + send_offsets_[r], send_offsets_[r + 1] - send_offsets_[r]};
}

std::span<const double> FixedExchange::incoming(int rank) const {
  const auto r = static_cast<std::size_t>(rank);
  return {receive_.data() + receive_offsets_[r], receive_offsets_[r + 1] - receive_offsets_[r]};
}

void FixedExchange::exchange(const mpi::Comm& comm) {
  constexpr int tag = 7101; // a tag of its own: a message of another exchange can never match
  requests_.clear();
  const int n_ranks = comm.size();
  for (int r = 0; r < n_ranks; ++r) {
    const auto at = receive_offsets_[static_cast<std::size_t>(r)];
    const auto count = receive_offsets_[static_cast<std::size_t>(r) + 1] - at;
    if (count == 0) continue;
    requests_.emplace_back();
    if (MPI_Irecv(receive_.data() + at, static_cast<int>(count), MPI_DOUBLE, r, tag, comm.raw(),
                  &requests_.back()) != MPI_SUCCESS)
      throw Error(ExitCode::internal_error, "MPI_Irecv (fixed exchange) failed");
  }
  for (int r = 0; r < n_ranks; ++r) {
    const std::span<double> out = outgoing(r);
    if (out.empty()) continue;
    requests_.emplace_back();
    if (MPI_Isend(out.data(), static_cast<int>(out.size()), MPI_DOUBLE, r, tag, comm.raw(),
                  &requests_.back()) != MPI_SUCCESS)
      throw Error(ExitCode::internal_error, "MPI_Isend (fixed exchange) failed");
  }
  if (MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE) != MPI_SUCCESS)
    throw Error(ExitCode::internal_error, "MPI_Waitall (fixed exchange) failed");
}

std::vector<std::vector<char>> all_gather_bytes(const mpi::Comm& comm, const std::vector<char>& mine) {
  return exchange_bytes(comm, std::vector<std::vector<char>>(static_cast<std::size_t>(comm.size()), mine));
}

} // namespace aniso
