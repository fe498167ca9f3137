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
