#pragma once
// Index arithmetic of a periodic voxel grid, x1 fastest (the layout of h5::VoxelImage::phase).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace aniso::voxel {

struct Grid {
  std::array<std::size_t, 3> n{}; ///< voxels along x1, x2, x3

  [[nodiscard]] std::size_t size() const { return n[0] * n[1] * n[2]; }
  /// Memory distance between neighbours along `axis` (0, 1, 2).
  [[nodiscard]] std::size_t stride(int axis) const {
    return axis == 0 ? 1 : (axis == 1 ? n[0] : n[0] * n[1]);
  }
  [[nodiscard]] std::size_t index(std::size_t i, std::size_t j, std::size_t k) const {
    return i + n[0] * (j + n[1] * k);
  }
};

/// One byte per voxel, 1 = in the set.
using Mask = std::vector<std::uint8_t>;

} // namespace aniso::voxel
