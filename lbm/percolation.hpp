#pragma once
// Whether the pore space of a voxel image connects across the cell along an axis. A flow along
// an axis with no such path has no steady flux: the LBM run only decays to round-off and gave a
// permeability of either sign (K11 = -1.8e-13 m^2 for a walled image, exit 0).

#include "common/h5/image.hpp"
#include "lbm/boundary.hpp"

namespace aniso::lbm {

/// True if void voxels (phase 0) joined by the D3Q19 links (the 6 face and 12 edge neighbours,
/// the links along which LBM populations stream) form a path that wraps around the periodic
/// cell along `axis`. Links cross the cell's faces only where `faces` is periodic. Breadth-first
/// search over the void voxels with their unwrapped period offsets, stopping at the first wrap.
[[nodiscard]] bool percolates(const h5::VoxelImage& image, int axis, const Faces& faces);

} // namespace aniso::lbm
