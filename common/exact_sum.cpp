#include "common/exact_sum.hpp"

#include <cmath>

namespace aniso {
namespace {

__extension__ using uint128 = unsigned __int128; // GCC/Clang extension, exact 128-bit products

// Bit position of limb 0's least significant bit is 2^-offset. frexp of the
// smallest subnormal gives an LSB exponent of -1126, so 1152 keeps every
// position non-negative; 72 limbs of 32 bits reach 2^1152, above DBL_MAX.
constexpr int offset = 1152;
constexpr std::int64_t normalize_every = std::int64_t{1} << 30;
constexpr std::uint64_t digit_mask = 0xffffffffULL;

} // namespace

void ExactSum::add(double term) {
  if (!std::isfinite(term)) {
    nonfinite_ = true;
    return;
  }
  if (term == 0.0) return;
  int exponent = 0;
  const double fraction = std::frexp(std::fabs(term), &exponent);             // term = fraction * 2^exponent
  const auto mantissa = static_cast<std::uint64_t>(std::ldexp(fraction, 53)); // exact: 53 bits
  const int position = exponent - 53 + offset;
  const int limb = position / digit_bits;
  const int shift = position % digit_bits;
  const uint128 shifted = static_cast<uint128>(mantissa) << shift;
  const std::int64_t sign = term < 0 ? -1 : 1;
  for (int d = 0; d < 3; ++d) {
    const auto digit =
        static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted >> (32 * d)) & digit_mask);
    limbs_[limb + d] += sign * digit;
  }
  if (++pending_ >= normalize_every) normalize();
}

void ExactSum::add(const ExactSum& other) {
  const Limbs theirs = other.normalized_limbs();
  normalize();
  for (int k = 0; k < n_limbs; ++k)
    limbs_[k] += theirs[k];
  nonfinite_ = nonfinite_ || other.nonfinite_;
  normalize();
}

void ExactSum::normalize() {
  // Canonical form: limbs 0..n-2 in [0, 2^32), the top limb carries the sign.
  for (int k = 0; k < n_limbs - 1; ++k) {
    const std::int64_t carry = limbs_[k] >> digit_bits; // arithmetic shift = floor division (C++20)
    limbs_[k] -= carry * (std::int64_t{1} << digit_bits);
    limbs_[k + 1] += carry;
  }
  pending_ = 0;
}

ExactSum::Limbs ExactSum::normalized_limbs() const {
  ExactSum copy = *this;
  copy.normalize();
  return copy.limbs_;
}

ExactSum ExactSum::from_limbs(const Limbs& limbs, bool nonfinite) {
  ExactSum sum;
  sum.limbs_ = limbs;
  sum.nonfinite_ = nonfinite;
  sum.normalize();
  return sum;
}

double ExactSum::value() const {
  if (nonfinite_) return std::nan("");
  ExactSum magnitude = *this;
  magnitude.normalize();
  const bool negative = magnitude.limbs_[n_limbs - 1] < 0;
  if (negative) {
    for (auto& limb : magnitude.limbs_)
      limb = -limb;
    magnitude.normalize();
  }
  int top = n_limbs - 1;
  while (top >= 0 && magnitude.limbs_[top] == 0)
    --top;
  if (top < 0) return 0.0;
  // Take 96 bits below and including the top digit; fold the rest into a sticky
  // bit so the conversion rounds to nearest as if it had seen every bit.
  uint128 head = 0;
  for (int k = top; k > top - 3; --k) {
    head <<= digit_bits;
    if (k >= 0) head |= static_cast<std::uint64_t>(magnitude.limbs_[k]);
  }
  bool sticky = false;
  for (int k = top - 3; k >= 0; --k)
    sticky = sticky || magnitude.limbs_[k] != 0;
  if (sticky) head |= 1;
  const double result = std::ldexp(static_cast<double>(head), digit_bits * (top - 2) - offset);
  return negative ? -result : result;
}

} // namespace aniso
