#include "common/rng.hpp"

#include <cmath>

namespace aniso {
namespace {

__extension__ using uint128 = unsigned __int128; // GCC/Clang extension, exact 128-bit products

constexpr std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

} // namespace

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

RandomStream::RandomStream(std::uint64_t seed, std::uint64_t stream_id) {
  std::uint64_t mixer = seed;
  std::uint64_t id_mixer = stream_id ^ 0x5851f42d4c957f2dULL;
  mixer ^= splitmix64(id_mixer);
  for (auto& word : state_)
    word = splitmix64(mixer);
  if ((state_[0] | state_[1] | state_[2] | state_[3]) == 0) state_[0] = 1; // all-zero state is a fixed point
}

RandomStream RandomStream::from_state(const State& state) {
  RandomStream stream;
  stream.state_ = state;
  return stream;
}

std::uint64_t RandomStream::next() {
  const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
  const std::uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double RandomStream::uniform01() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

double RandomStream::uniform(double low, double high) {
  return low + (high - low) * uniform01();
}

std::uint64_t RandomStream::below(std::uint64_t n) {
  uint128 product = static_cast<uint128>(next()) * n;
  auto low = static_cast<std::uint64_t>(product);
  if (low < n) {
    const std::uint64_t threshold = (0 - n) % n;
    while (low < threshold) {
      product = static_cast<uint128>(next()) * n;
      low = static_cast<std::uint64_t>(product);
    }
  }
  return static_cast<std::uint64_t>(product >> 64);
}

double RandomStream::normal() {
  // The second value of the pair is dropped on purpose: keeping it would be
  // hidden state outside state(), and a restored stream would then diverge.
  double u = 0, v = 0, s = 0;
  do {
    u = 2.0 * uniform01() - 1.0;
    v = 2.0 * uniform01() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  return u * factor;
}

} // namespace aniso
