#include "common/h5/content_hash.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

namespace aniso::h5 {
namespace {

// FNV-1a, 64-bit variant (Fowler, Noll, Vo): offset basis and prime from its specification.
constexpr std::uint64_t fnv_offset_basis = 0xcbf29ce484222325ULL;
constexpr std::uint64_t fnv_prime = 0x100000001b3ULL;

std::uint64_t fnv1a(std::uint64_t hash, const char* data, std::size_t size) {
  for (std::size_t k = 0; k < size; ++k) {
    hash ^= static_cast<std::uint8_t>(data[k]);
    hash *= fnv_prime;
  }
  return hash;
}

std::string hex(std::uint64_t hash) {
  return fmt::format("{:016x}", hash);
}

} // namespace

std::string content_hash_of_bytes(std::string_view bytes) {
  return hex(fnv1a(fnv_offset_basis, bytes.data(), bytes.size()));
}

std::string content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(fmt::format("{}: cannot open to hash it: {}", path, std::strerror(errno)));
  std::uint64_t hash = fnv_offset_basis;
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    hash = fnv1a(hash, buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw FileError(fmt::format("{}: read error while hashing", path));
  return hex(hash);
}

std::string content_hash(const std::string& path, const mpi::Comm& comm) {
  std::vector<char> bytes;
  if (comm.is_root()) {
    const std::string hash = content_hash(path);
    bytes.assign(hash.begin(), hash.end());
  }
  comm.broadcast(bytes, 0);
  return {bytes.begin(), bytes.end()};
}

} // namespace aniso::h5
