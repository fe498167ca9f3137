#pragma once
// Test helpers for the voxel stage: random periodic images and brute-force references (the
// definitions, evaluated literally: erosion then dilation with the structuring element, periodic
// wrap; distance as a minimum over all voxels and images).
#include "common/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

namespace aniso::test {

using voxel::Grid;
using voxel::Mask;

/// Offset of a structuring element, voxels.
struct Offset {
  int x, y, z;
};

/// Voxels solid with probability solid_fraction, independently (phase 1 = solid).
inline Mask random_phase(const Grid& grid, double solid_fraction, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::bernoulli_distribution solid(solid_fraction);
  Mask phase(grid.size());
  for (auto& v : phase)
    v = solid(engine) ? 1 : 0;
  return phase;
}

/// Random overlapping solid balls (a Boolean model): pores of many sizes, like a packing.
inline Mask blob_phase(const Grid& grid, int balls, double radius, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  Mask phase(grid.size(), 0);
  for (int b = 0; b < balls; ++b) {
    const double cx = unit(engine) * static_cast<double>(grid.n[0]);
    const double cy = unit(engine) * static_cast<double>(grid.n[1]);
    const double cz = unit(engine) * static_cast<double>(grid.n[2]);
    const double r = radius * (0.6 + 0.8 * unit(engine));
    for (std::size_t k = 0; k < grid.n[2]; ++k)
      for (std::size_t j = 0; j < grid.n[1]; ++j)
        for (std::size_t i = 0; i < grid.n[0]; ++i) {
          auto wrapped = [](double d, std::size_t n) {
            const double L = static_cast<double>(n);
            while (d > L / 2)
              d -= L;
            while (d < -L / 2)
              d += L;
            return d;
          };
          const double dx = wrapped(static_cast<double>(i) + 0.5 - cx, grid.n[0]);
          const double dy = wrapped(static_cast<double>(j) + 0.5 - cy, grid.n[1]);
          const double dz = wrapped(static_cast<double>(k) + 0.5 - cz, grid.n[2]);
          if (dx * dx + dy * dy + dz * dz <= r * r) phase[grid.index(i, j, k)] = 1;
        }
  }
  return phase;
}

inline std::size_t shifted(const Grid& grid, std::size_t index, const Offset& o, int sign) {
  const std::size_t i = index % grid.n[0];
  const std::size_t j = (index / grid.n[0]) % grid.n[1];
  const std::size_t k = index / (grid.n[0] * grid.n[1]);
  auto wrap = [](std::int64_t v, std::size_t n) {
    const auto m = static_cast<std::int64_t>(n);
    return static_cast<std::size_t>(((v % m) + m) % m);
  };
  return grid.index(wrap(static_cast<std::int64_t>(i) + sign * o.x, grid.n[0]),
                    wrap(static_cast<std::int64_t>(j) + sign * o.y, grid.n[1]),
                    wrap(static_cast<std::int64_t>(k) + sign * o.z, grid.n[2]));
}

/// Opening of the void (phase 0) by the element: erosion {x : x + b void for all b}, then
/// dilation {p : p - b in the erosion for some b}.
inline Mask brute_force_opening(const Grid& grid, const Mask& phase, const std::vector<Offset>& element) {
  Mask eroded(grid.size(), 0);
  for (std::size_t x = 0; x < grid.size(); ++x) {
    bool fits = true;
    for (const Offset& b : element)
      if (phase[shifted(grid, x, b, +1)] != 0) {
        fits = false;
        break;
      }
    eroded[x] = fits ? 1 : 0;
  }
  Mask opened(grid.size(), 0);
  for (std::size_t p = 0; p < grid.size(); ++p)
    for (const Offset& b : element)
      if (eroded[shifted(grid, p, b, -1)] != 0) {
        opened[p] = 1;
        break;
      }
  return opened;
}

/// Digital ball (normal = -1) or disk with axis `normal` of squared radius r2.
inline std::vector<Offset> round_element(int r2, int normal) {
  std::vector<Offset> element;
  const int r = static_cast<int>(std::sqrt(static_cast<double>(r2))) + 1;
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        const int along[3] = {x, y, z};
        if (normal >= 0 && along[normal] != 0) continue;
        if (x * x + y * y + z * z <= r2) element.push_back({x, y, z});
      }
  return element;
}

/// Spar: `length` voxels starting at the origin along `axis`.
inline std::vector<Offset> spar_element(int length, int axis) {
  std::vector<Offset> element;
  for (int t = 0; t < length; ++t)
    element.push_back({axis == 0 ? t : 0, axis == 1 ? t : 0, axis == 2 ? t : 0});
  return element;
}

/// Squared periodic distance from every voxel to the nearest mask voxel over the axes with use[a].
inline std::vector<std::uint32_t> brute_force_distance(const Grid& grid, const Mask& mask,
                                                       const bool use[3]) {
  std::vector<std::uint32_t> out(grid.size(), 0xFFFFFFFFU);
  auto coord = [&](std::size_t index, int a) {
    return a == 0 ? index % grid.n[0]
                  : (a == 1 ? (index / grid.n[0]) % grid.n[1] : index / (grid.n[0] * grid.n[1]));
  };
  for (std::size_t p = 0; p < grid.size(); ++p)
    for (std::size_t q = 0; q < grid.size(); ++q) {
      if (mask[q] == 0) continue;
      std::uint32_t d2 = 0;
      bool same_plane = true;
      for (int a = 0; a < 3; ++a) {
        const auto n = static_cast<std::int64_t>(grid.n[static_cast<std::size_t>(a)]);
        std::int64_t d =
            std::abs(static_cast<std::int64_t>(coord(p, a)) - static_cast<std::int64_t>(coord(q, a)));
        d = std::min(d, n - d);
        if (use[a]) {
          d2 += static_cast<std::uint32_t>(d * d);
        } else if (d != 0) {
          same_plane = false;
        }
      }
      if (same_plane) out[p] = std::min(out[p], d2);
    }
  return out;
}

} // namespace aniso::test
