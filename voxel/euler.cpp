#include "voxel/euler.hpp"

#include <array>

namespace aniso::voxel {
namespace {

// Bit b = a + 2 b' + 4 c of a vertex configuration is the voxel at offset (-a, -b', -c) from the
// vertex (a, b', c in {0, 1}); the bit is set when that voxel is void. The vertex owns the cells
// of the complex that start at it in the + directions: itself, the edges to +x1, +x2, +x3, the
// faces spanned by two of them, and the cube (the voxel at offset 0).
constexpr std::array<int, 256> vertex_contributions() {
  std::array<int, 256> table{};
  for (int config = 0; config < 256; ++config) {
    const auto any = [config](int required_zero_bits) {
      // Some voxel whose offset is 0 along every axis in required_zero_bits is void.
      for (int bit = 0; bit < 8; ++bit)
        if ((bit & required_zero_bits) == 0 && ((config >> bit) & 1) != 0) return 1;
      return 0;
    };
    const int vertex = any(0);
    const int edges = any(1) + any(2) + any(4);
    const int faces = any(1 | 2) + any(2 | 4) + any(1 | 4);
    const int cube = any(1 | 2 | 4);
    table[static_cast<std::size_t>(config)] = vertex - edges + faces - cube;
  }
  return table;
}

constexpr std::array<int, 256> contribution = vertex_contributions();

} // namespace

std::int64_t void_euler_characteristic(const Grid& grid, std::span<const std::uint8_t> phase) {
  const auto [n0, n1, n2] = grid.n;
  std::int64_t chi = 0;
  const auto planes = static_cast<std::int64_t>(n2);
#pragma omp parallel for schedule(static) reduction(+ : chi)
  for (std::int64_t kk = 0; kk < planes; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    const std::size_t km = (k + n2 - 1) % n2;
    for (std::size_t j = 0; j < n1; ++j) {
      const std::size_t jm = (j + n1 - 1) % n1;
      for (std::size_t i = 0; i < n0; ++i) {
        const std::size_t im = (i + n0 - 1) % n0;
        unsigned config = 0;
        const std::array<std::size_t, 2> is{i, im};
        const std::array<std::size_t, 2> js{j, jm};
        const std::array<std::size_t, 2> ks{k, km};
        for (unsigned bit = 0; bit < 8; ++bit)
          if (phase[grid.index(is[bit & 1U], js[(bit >> 1U) & 1U], ks[(bit >> 2U) & 1U])] == 0)
            config |= 1U << bit;
        chi += contribution[config];
      }
    }
  }
  return chi;
}

} // namespace aniso::voxel
