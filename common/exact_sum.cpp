#include "common/exact_sum.hpp"

#include <cmath>
#include <cstring>

namespace aniso {
namespace {

__extension__ using uint128 = unsigned __int128; // GCC/Clang extension, exact 128-bit products
__extension__ using int128 = __int128;
// The fast lane's window (see exact_sum.hpp): terms up to 2^30 times smaller than the first one's
// last bit and 2^12 times larger go there.
constexpr int lane_below = 30;

// Bit position of limb 0's least significant bit is 2^-offset. The smallest
// mantissa bit of any double is 2^-1074, so 1152 keeps every position
// non-negative; 72 limbs of 32 bits reach 2^1152, above DBL_MAX.
constexpr int offset = 1152;
constexpr std::int64_t normalize_every = std::int64_t{1} << 30;
constexpr std::uint64_t digit_mask = 0xffffffffULL;

} // namespace

void ExactSum::add_outside_lane(double term) {
  // Read sign, exponent and mantissa straight from the IEEE-754 bits: much
  // cheaper than frexp/ldexp, and exact for normals and subnormals alike.
  std::uint64_t bits = 0;
  std::memcpy(&bits, &term, sizeof bits);
  const auto biased_exponent = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased_exponent == 0x7ff) {
    nonfinite_ = true;
    return;
  }
  std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased_exponent != 0) mantissa |= std::uint64_t{1} << 52; // implicit leading bit of normals
  if (mantissa == 0) return;
  // value = mantissa * 2^(e - 1075) for normals, mantissa * 2^-1074 for subnormals.
  const int lsb_exponent = (biased_exponent == 0 ? 1 : biased_exponent) - 1075;
  if (!lane_set_) {
    lane_lsb_ = lsb_exponent - lane_below;
    lane_set_ = true;
  }
  const int lane_shift = lsb_exponent - lane_lsb_;
  if (lane_shift >= 0 && lane_shift <= lane_span) {
    // At most 53 + 42 = 95 bits a term, 2^31 terms: below 2^126.
    const auto shifted_term = static_cast<int128>(static_cast<uint128>(mantissa) << lane_shift);
    lane_ += (bits >> 63) != 0 ? -shifted_term : shifted_term;
    if (++lane_count_ >= lane_capacity) flush_lane();
    return;
  }
  const int position = lsb_exponent + offset;
  const int limb = position / digit_bits;
  const int shift = position % digit_bits;
  const uint128 shifted = static_cast<uint128>(mantissa) << shift;
  const std::int64_t sign = (bits >> 63) != 0 ? -1 : 1;
  limbs_[limb] += sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted) & digit_mask);
  limbs_[limb + 1] +=
      sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted >> 32) & digit_mask);
  limbs_[limb + 2] +=
      sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted >> 64) & digit_mask);
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

void ExactSum::flush_lane() {
  if (lane_ != 0) {
    // |lane| < 2^127, placed at bit lane_lsb_ + offset: five 32-bit digits from limb `limb` on.
    const std::int64_t sign = lane_ < 0 ? -1 : 1;
    const uint128 magnitude = lane_ < 0 ? -static_cast<uint128>(lane_) : static_cast<uint128>(lane_);
    const int position = lane_lsb_ + offset;
    const int limb = position / digit_bits;
    const int shift = position % digit_bits;
    const uint128 low = magnitude << shift;
    const std::uint64_t high = shift == 0 ? 0 : static_cast<std::uint64_t>(magnitude >> (128 - shift));
    for (int k = 0; k < 4; ++k)
      limbs_[limb + k] +=
          sign * static_cast<std::int64_t>(static_cast<std::uint64_t>(low >> (32 * k)) & digit_mask);
    limbs_[limb + 4] += sign * static_cast<std::int64_t>(high & digit_mask);
    ++pending_;
  }
  lane_ = 0;
  lane_count_ = 0;
}

void ExactSum::normalize() {
  flush_lane();
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
