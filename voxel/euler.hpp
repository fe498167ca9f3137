#pragma once
// Euler-Poincare characteristic of the void phase of a periodic image (paper eq. (chiv1)), with
// 26-connected void and 6-connected solid: the void is the union of closed unit cubes, one per void
// voxel, on the 3-torus, and chi = V - E + F - C counts the vertices, edges, faces and cubes of
// that cubical complex. Each lattice vertex contributes what the 2x2x2 voxels around it decide
// (a 256-entry table), so chi is one pass over the image.

#include "common/voxel_grid.hpp"

#include <cstdint>
#include <span>

namespace aniso::voxel {

/// chi of the void (phase 0) on the periodic image.
std::int64_t void_euler_characteristic(const Grid& grid, std::span<const std::uint8_t> phase);

} // namespace aniso::voxel
