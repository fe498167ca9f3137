#pragma once
// Sparse exchange of byte buffers between ranks: the one place in aniso that
// moves point-to-point data. Stages pack what to send (ByteWriter), exchange,
// and unpack what arrived (ByteReader); how to send is decided here.

#include "common/mpi.hpp"

#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace aniso {

/// Sends outgoing[r] to rank r and returns incoming[r] from rank r (collective on comm).
/// Empty buffers cost no data; the counts travel in one all-to-all.
std::vector<std::vector<char>> exchange_bytes(const mpi::Comm& comm,
                                              const std::vector<std::vector<char>>& outgoing);

/// Every rank's buffer, in rank order, on every rank (collective).
std::vector<std::vector<char>> all_gather_bytes(const mpi::Comm& comm, const std::vector<char>& mine);

/// A repeated exchange of doubles whose sizes stay fixed between set-ups: the per-step refresh
/// of ghost particles. exchange_bytes costs an all-to-all of the counts (a synchronisation of
/// every rank), a fresh zero-filled receive buffer and three copies per call; here the counts
/// are given once, the buffers persist, callers write and read them in place, and only the
/// ranks that share data talk (point to point).
class FixedExchange {
public:
  /// The number of doubles this rank sends to and receives from each rank; they must mirror the
  /// partners' (the caller learnt them in an exchange_bytes set-up). Nothing goes to this rank.
  void resize(const mpi::Comm& comm, const std::vector<std::size_t>& send_counts,
              const std::vector<std::size_t>& receive_counts);
  /// Where to write what goes to `rank` before exchange().
  [[nodiscard]] std::span<double> outgoing(int rank);
  /// Sends every outgoing buffer and receives every incoming one (collective among partners).
  void exchange(const mpi::Comm& comm);
  /// What `rank` sent, after exchange().
  [[nodiscard]] std::span<const double> incoming(int rank) const;

private:
  std::vector<std::size_t> send_offsets_, receive_offsets_; ///< n_ranks + 1 each
  std::vector<double> send_, receive_;
  std::vector<MPI_Request> requests_;
};

/// Appends trivially copyable values to a byte buffer.
class ByteWriter {
public:
  explicit ByteWriter(std::vector<char>& buffer) : buffer_(buffer) {}
  template <class T> void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto at = buffer_.size();
    buffer_.resize(at + sizeof(T));
    std::memcpy(buffer_.data() + at, &value, sizeof(T));
  }

private:
  std::vector<char>& buffer_;
};

/// Reads values back in the order they were written.
class ByteReader {
public:
  explicit ByteReader(const std::vector<char>& buffer) : buffer_(buffer) {}
  template <class T> T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, buffer_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    return value;
  }
  [[nodiscard]] bool done() const { return offset_ >= buffer_.size(); }

private:
  const std::vector<char>& buffer_;
  std::size_t offset_ = 0;
};

} // namespace aniso
