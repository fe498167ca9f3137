#pragma once
// Exact squared Euclidean distance transform on the periodic grid, over all three axes (3D) or
// over the two axes of a plane (2D, every plane normal to the third axis separately). The distance
// from voxel p to a set T is min over t in T and over periodic images of |p - t|^2, in voxel
// units, computed by separable passes (Meijster, Roerdink & Hesselink 2000): one run-length pass
// along the first axis, then lower envelopes of parabolas along the others. The periodic wrap is
// exact: each parabola pass works on the line extended by half a period on both sides, which
// holds the nearest image of every voxel. Lines are independent, so OpenMP threads give the same
// bits as one thread.

#include "common/voxel_grid.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aniso::voxel {

/// Squared distance for "no target voxel reachable" (empty target set, or beyond a cap).
inline constexpr std::uint32_t infinite_distance = 0xFFFFFFFFU;

/// Which axes the transform spans: all three, or the plane normal to one axis.
struct Axes {
  std::array<int, 3> order{0, 1, 2}; ///< axes in pass order; the first gets the run-length pass
  int count = 3;                     ///< 3, or 2 for an in-plane transform

  static Axes all() { return {}; }
  /// The plane normal to `normal` (0, 1 or 2), in-plane axes in increasing order.
  static Axes plane(int normal);
};

/// The target set: voxels where mask != 0, or (mask empty) where values > threshold, the
/// erosion of a set by a ball or disk given its distance map.
struct Target {
  std::span<const std::uint8_t> mask;
  std::span<const std::uint32_t> values;
  std::uint32_t threshold = 0;

  static Target of_mask(std::span<const std::uint8_t> mask) { return {mask, {}, 0}; }
  static Target above(std::span<const std::uint32_t> values, std::uint32_t threshold) {
    return {{}, values, threshold};
  }
  [[nodiscard]] bool operator()(std::size_t index) const {
    return mask.empty() ? values[index] > threshold : mask[index] != 0;
  }
};

/// Squared distance from every voxel to the nearest voxel where target(index) holds, over `axes`.
/// Values above `cap` become infinite_distance (use cap to skip work when only d <= cap matters;
/// values <= cap are exact). `out` is resized to grid.size().
void squared_distance(const Grid& grid, const Target& target, Axes axes, std::uint32_t cap,
                      std::vector<std::uint32_t>& out);

/// The same with target = mask[index] != 0 and no cap.
std::vector<std::uint32_t> squared_distance(const Grid& grid, std::span<const std::uint8_t> mask, Axes axes);

} // namespace aniso::voxel
