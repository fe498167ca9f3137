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

std::vector<std::vector<char>> all_gather_bytes(const mpi::Comm& comm, const std::vector<char>& mine) {
  return exchange_bytes(comm, std::vector<std::vector<char>>(static_cast<std::size_t>(comm.size()), mine));
}

} // namespace aniso
