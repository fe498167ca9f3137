#pragma once
// Exact summation of doubles in a fixed-point superaccumulator wide enough for
// every finite double. The exact sum does not depend on the order of the
// terms, so rounding it once gives a result that is bit-identical for any
// order and any partition over ranks. Used by Comm::sum_exact.

#include <array>
#include <cstdint>
#include <cstring>

namespace aniso {

class ExactSum {
public:
  /// 32-bit digits held in int64 limbs: 2^31 additions fit before a carry pass is needed.
  static constexpr int digit_bits = 32;
  static constexpr int n_limbs = 72; ///< covers every finite double (2^-1074 .. 2^1024) plus carry headroom
  using Limbs = std::array<std::int64_t, n_limbs>;

  ExactSum() { limbs_.fill(0); }

  /// Adds one finite term; non-finite terms set a flag that makes value() return NaN. Inline: the
  /// control update calls it twelve times a contact (dem/data/contact_sums.hpp).
  void add(double term) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &term, sizeof bits);
    const auto biased_exponent = static_cast<int>((bits >> 52) & 0x7ff);
    // The fast lane (normal terms inside its window); everything else takes add_outside_lane.
    const int lane_shift = biased_exponent - 1075 - lane_lsb_;
    if (lane_set_ && biased_exponent != 0 && biased_exponent != 0x7ff && lane_shift >= 0 &&
        lane_shift <= lane_span) {
      const std::uint64_t mantissa = (bits & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
      __extension__ const auto shifted =
          static_cast<__int128>(static_cast<unsigned __int128>(mantissa) << lane_shift);
      // Branch-free sign: the signs of stress terms are random, a branch on them mispredicts half the time.
      __extension__ const auto negative = -static_cast<__int128>(bits >> 63); // 0 or all ones
      lane_ += (shifted ^ negative) - negative;
      if (++lane_count_ >= lane_capacity) flush_lane();
      return;
    }
    add_outside_lane(term);
  }
  /// Adds another accumulator (exact).
  void add(const ExactSum& other);
  /// The exact sum rounded to double (deterministic function of the exact value).
  [[nodiscard]] double value() const;

  /// Carry-propagated limbs, suitable for an integer MPI_SUM across ranks
  /// (each limb then holds < 2^32 * n_ranks, far from overflow).
  [[nodiscard]] Limbs normalized_limbs() const;
  /// Rebuilds from limbs summed across ranks; nonfinite flags are OR-ed by the caller.
  static ExactSum from_limbs(const Limbs& limbs, bool nonfinite);
  [[nodiscard]] bool nonfinite() const { return nonfinite_; }

private:
  static constexpr int lane_span = 42; ///< exponents the lane holds above lane_lsb_
  static constexpr std::int64_t lane_capacity = std::int64_t{1} << 30; ///< terms before a flush
  void add_outside_lane(double term);
  void normalize();
  void flush_lane();
  Limbs limbs_;
  std::int64_t pending_ = 0; ///< additions since the last carry pass
  bool nonfinite_ = false;
  // The fast lane: a 128-bit integer holding, exactly, the terms whose bits lie in a window of
  // lane_span exponents above lane_lsb_ (chosen at the first term, 30 binary orders below it). Most
  // terms of a stress sum fall there and cost one shift and one 128-bit add instead of three limb
  // updates; the others take the limbs. The sum stays exact, so the result has the same bits.
  __extension__ __int128 lane_ = 0;
  int lane_lsb_ = 0;
  bool lane_set_ = false;
  std::int64_t lane_count_ = 0; ///< terms in the lane since its last flush (below 2^31: no overflow)
};

} // namespace aniso
