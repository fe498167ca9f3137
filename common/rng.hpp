#pragma once
// Seeded, splittable random streams with portable distributions.
// The standard library's distributions differ between implementations, so the
// few we need are written here: the same seed gives the same numbers with any
// compiler. Generator: xoshiro256** (Blackman & Vigna 2018), seeded through
// SplitMix64; independent streams come from (seed, stream id) pairs.

#include <array>
#include <cstdint>

namespace aniso {

class RandomStream {
public:
  using State = std::array<std::uint64_t, 4>;

  /// Stream number `stream_id` of the family seeded by `seed`. Different ids give independent streams.
  RandomStream(std::uint64_t seed, std::uint64_t stream_id);
  /// Restores a stream from a saved state (checkpoints store it).
  static RandomStream from_state(const State& state);

  /// Next raw 64-bit output.
  std::uint64_t next();
  /// Uniform on [0, 1) with 53 random bits.
  double uniform01();
  /// Uniform on [low, high).
  double uniform(double low, double high);
  /// Uniform integer on [0, n) without modulo bias (Lemire 2019). n > 0.
  std::uint64_t below(std::uint64_t n);
  /// Standard normal by the Marsaglia polar method (needs only log and sqrt).
  double normal();
  /// Normal with the given mean and standard deviation.
  double normal(double mean, double deviation) { return mean + deviation * normal(); }

  [[nodiscard]] const State& state() const { return state_; }

private:
  RandomStream() = default;
  State state_{};
};

/// SplitMix64 step: a good 64-bit mixer, used for seeding and hashing stream ids.
std::uint64_t splitmix64(std::uint64_t& state);

} // namespace aniso
