#pragma once
// The narrowest throat the pore space must pass to cross the periodic cell along each axis: where
// the bounce-back staircase makes the LBM wrong (a throat a few voxels wide carries a flow that
// two or three lattice nodes cannot resolve; docs/methods/lbm.md, "Where the method fails").

#include "common/h5/image.hpp"

#include <array>
#include <limits>

namespace aniso::lbm {

/// Per axis: the largest r such that the void voxels whose centres lie at least r (Euclidean, in
/// voxels) from the nearest solid voxel centre connect around the periodic cell along that axis
/// by D3Q19 links, given as the throat width 2 r - 1 voxels (the void voxels across a slit of odd
/// width; one less for an even one). 0: no path of void voxels crosses the cell along the axis;
/// infinity: an image without solid. Union-find over the void voxels in decreasing distance, with
/// the period offsets of each path, stopping when all three axes are crossed.
std::array<double, 3> throat_widths(const h5::VoxelImage& image);

inline constexpr double no_throat = std::numeric_limits<double>::infinity();

} // namespace aniso::lbm
