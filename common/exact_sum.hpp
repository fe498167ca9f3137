#pragma once
// Exact summation of doubles in a fixed-point superaccumulator wide enough for
// every finite double. The exact sum does not depend on the order of the
// terms, so rounding it once gives a result that is bit-identical for any
// order and any partition over ranks. Used by Comm::sum_exact.

#include <array>
#include <cstdint>

namespace aniso {

class ExactSum {
public:
  /// 32-bit digits held in int64 limbs: 2^31 additions fit before a carry pass is needed.
  static constexpr int digit_bits = 32;
  static constexpr int n_limbs = 72; ///< covers every finite double (2^-1074 .. 2^1024) plus carry headroom
  using Limbs = std::array<std::int64_t, n_limbs>;

  ExactSum() { limbs_.fill(0); }

  /// Adds one finite term; non-finite terms set a flag that makes value() return NaN.
  void add(double term);
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
  void normalize();
  Limbs limbs_;
  std::int64_t pending_ = 0; ///< additions since the last carry pass
  bool nonfinite_ = false;
};

} // namespace aniso
