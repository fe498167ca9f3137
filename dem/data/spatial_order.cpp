#include "dem/data/spatial_order.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace aniso::dem::data {
namespace {

// Spreads the low 21 bits of v so that two zero bits follow each.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

} // namespace

std::vector<std::size_t> spatial_order(const std::vector<Vec3>& positions, const Vec3& lengths,
                                       double bin_width) {
  std::array<std::uint64_t, 3> bins{};
  for (int a = 0; a < 3; ++a)
    bins[static_cast<std::size_t>(a)] =
        std::clamp<std::uint64_t>(static_cast<std::uint64_t>(lengths[a] / bin_width), 1, 1u << 21);
  std::vector<std::uint64_t> keys(positions.size());
  for (std::size_t k = 0; k < positions.size(); ++k) {
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      const auto n = bins[static_cast<std::size_t>(a)];
      const double scaled = std::floor(positions[k][a] / lengths[a] * static_cast<double>(n));
      const auto bin = static_cast<std::uint64_t>(std::clamp(scaled, 0.0, static_cast<double>(n - 1)));
      key |= spread_bits(bin) << a;
    }
    keys[k] = key;
  }
  std::vector<std::size_t> order(positions.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return keys[i] < keys[j]; });
  return order;
}

} // namespace aniso::dem::data
