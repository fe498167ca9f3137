#include "lbm/throats.hpp"

#include "common/distance_transform.hpp"
#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace aniso::lbm {
namespace {

using Offset = std::array<std::int16_t, 3>; // a voxel's position relative to its root, in periods

// Union-find over voxels with the period offset of each voxel relative to its parent: two voxels
// of one set reached along paths whose offsets differ lie on a loop that winds around the cell.
class PeriodicUnionFind {
public:
  explicit PeriodicUnionFind(std::size_t size) : parent_(size, unset), offset_(size, Offset{0, 0, 0}) {}

  [[nodiscard]] bool added(std::size_t v) const { return parent_[v] != unset; }
  void add(std::size_t v) { parent_[v] = static_cast<std::uint32_t>(v); }

  // The root of v and v's offset from it (path halving keeps offsets consistent).
  std::uint32_t find(std::size_t v, Offset& offset) {
    offset = {0, 0, 0};
    auto x = static_cast<std::uint32_t>(v);
    while (parent_[x] != x) {
      const std::uint32_t p = parent_[x];
      if (parent_[p] != p) { // halve: x skips p, its offset absorbs p's
        for (std::size_t a = 0; a < 3; ++a)
          offset_[x][a] = static_cast<std::int16_t>(offset_[x][a] + offset_[p][a]);
        parent_[x] = parent_[p];
      }
      for (std::size_t a = 0; a < 3; ++a)
        offset[a] = static_cast<std::int16_t>(offset[a] + offset_[x][a]);
      x = parent_[x];
    }
    return x;
  }

  // Joins u and its neighbour v, reached from u with the period shift `shift`. Returns the
  // winding of the loop this link closes (zero if it closes none).
  Offset join(std::size_t u, std::size_t v, const Offset& shift) {
    Offset ou, ov;
    const std::uint32_t ru = find(u, ou), rv = find(v, ov);
    Offset difference; // position of v through u minus its position through its own root
    for (std::size_t a = 0; a < 3; ++a)
      difference[a] = static_cast<std::int16_t>(ou[a] + shift[a] - ov[a]);
    if (ru == rv) return difference;
    parent_[rv] = ru; // rv's position relative to ru makes v's two positions agree
    offset_[rv] = difference;
    return {0, 0, 0};
  }

private:
  static constexpr std::uint32_t unset = 0xFFFFFFFFU;
  std::vector<std::uint32_t> parent_;
  std::vector<Offset> offset_;
};

} // namespace

std::array<double, 3> throat_widths(const h5::VoxelImage& image) {
  const std::size_t size = image.size();
  require_input(size < 0xFFFFFFFFU, "throat widths: images of 2^32 voxels or more are not supported");
  const std::array<std::int64_t, 3> n{static_cast<std::int64_t>(image.shape[0]),
                                      static_cast<std::int64_t>(image.shape[1]),
                                      static_cast<std::int64_t>(image.shape[2])};
  const voxel::Grid grid{image.shape};
  const std::vector<std::uint32_t> distance = voxel::squared_distance(grid, image.phase, voxel::Axes::all());
  // Void voxels from the farthest from the solid to the nearest (solid ones have distance 0).
  std::vector<std::uint32_t> order;
  order.reserve(size);
  for (std::size_t v = 0; v < size; ++v)
    if (image.phase[v] == 0) order.push_back(static_cast<std::uint32_t>(v));
  if (!order.empty() && distance[order.front()] == voxel::infinite_distance)
    return {no_throat, no_throat, no_throat};
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return distance[a] > distance[b]; });

  std::array<double, 3> width{0, 0, 0};
  std::array<bool, 3> crossed{false, false, false};
  PeriodicUnionFind sets(size);
  for (const std::uint32_t v : order) {
    sets.add(v);
    const std::array<std::int64_t, 3> at{v % n[0], (v / n[0]) % n[1], v / (n[0] * n[1])};
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const int moved = (dx != 0) + (dy != 0) + (dz != 0);
          if (moved == 0 || moved == 3) continue; // the 18 D3Q19 links
          const std::array<int, 3> link{dx, dy, dz};
          std::array<std::int64_t, 3> to{};
          Offset shift{0, 0, 0};
          for (std::size_t a = 0; a < 3; ++a) {
            to[a] = at[a] + link[a];
            if (to[a] < 0 || to[a] >= n[a]) {
              shift[a] = static_cast<std::int16_t>(to[a] < 0 ? -1 : 1);
              to[a] -= shift[a] * n[a];
            }
          }
          const auto next = static_cast<std::size_t>(to[0] + n[0] * (to[1] + n[1] * to[2]));
          if (!sets.added(next)) continue;
          const Offset winding = sets.join(v, next, shift);
          for (std::size_t a = 0; a < 3; ++a)
            if (winding[a] != 0 && !crossed[a]) {
              crossed[a] = true;
              width[a] = 2.0 * std::sqrt(static_cast<double>(distance[v])) - 1.0;
            }
        }
    if (crossed[0] && crossed[1] && crossed[2]) break;
  }
  return width;
}

} // namespace aniso::lbm
