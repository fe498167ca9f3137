#pragma once
// Exact morphological openings of the periodic void image by the paper's three structuring
// elements (Kuhn, Sun & Wang 2015, section 3, Fig. "templates"), one opening per size:
//  - ball of radius rho: the digital ball {z in Z^3 : |z|^2 <= rho^2}, eq. (fr);
//  - spar of length l along x_i: a row of l voxels, eq. (fli);
//  - disk of radius r with axis x_i: {z : z_i = 0, |z|^2 <= r^2}, eq. (fri).
// Ball and disk: the erosion of the void set V by B is {x : d_S(x)^2 > rho^2}, d_S the distance to
// the solid, and the dilation of that erosion E by B is {p : d_E(p)^2 <= rho^2}; both are exact
// squared distance transforms (3D for the ball, in-plane for the disk). Spar: a void run of length
// m >= l along x_i is covered by translates of the spar, a shorter one is not, so the opening keeps
// exactly the runs of length >= l (periodic wrap; an all-void line is a run of infinite length).

#include "common/distance_transform.hpp"
#include "common/voxel_grid.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aniso::voxel {

/// The structuring element families; disk and spar carry an axis.
enum class Template : std::uint8_t { ball = 0, disk = 1, spar = 2 };

/// Squared distance from every voxel to the solid (phase 1), over the ball's or a disk's axes.
/// This is the map from which every size's erosion is read.
std::vector<std::uint32_t> distance_to_solid(const Grid& grid, std::span<const std::uint8_t> phase,
                                             Axes axes);

/// Opening of the void by the ball (axes = all) or disk (axes = plane) of squared radius r2,
/// given distance_to_solid over the same axes. Returns the opening as a mask (1 = kept void voxel).
/// `work` is scratch of grid.size() values, reused between calls.
Mask round_opening(const Grid& grid, std::span<const std::uint32_t> solid_distance, Axes axes,
                   std::uint32_t r2, std::vector<std::uint32_t>& work);
/// Number of voxels in that opening, without building the mask.
std::uint64_t round_opening_volume(const Grid& grid, std::span<const std::uint32_t> solid_distance, Axes axes,
                                   std::uint32_t r2, std::vector<std::uint32_t>& work);

/// Opening of the void by the spar of `length` voxels along `axis`, as a mask.
Mask spar_opening(const Grid& grid, std::span<const std::uint8_t> phase, int axis, std::size_t length);

/// Void runs along `axis`: volume_by_length[m] = number of void voxels in runs of exactly m voxels
/// (m = 1 .. n_axis), infinite_volume = voxels on all-void lines. The spar opening of length l then
/// holds infinite_volume + sum over m >= l of volume_by_length[m] voxels.
struct RunLengths {
  std::vector<std::uint64_t> volume_by_length;
  std::uint64_t infinite_volume = 0;
  /// Voxels kept by the spar opening of length l >= 1.
  [[nodiscard]] std::uint64_t opening_volume(std::size_t length) const;
};
RunLengths void_run_lengths(const Grid& grid, std::span<const std::uint8_t> phase, int axis);

} // namespace aniso::voxel
