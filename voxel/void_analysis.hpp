#pragma once
// The paper's void-space distributions (section 3): f_rho (ball, eq. (fr)), f_l_i (spar along x_i,
// eq. (fli)) and f_r_i (disk with axis x_i, eq. (fri)) at every size, their medians, the matrices
// L^v (eq. (Lambdaii)) and R^v (eq. (Rii)), and the image Euler characteristic of the void.
//
// Work split: the ball and disk sizes are independent openings; with several MPI ranks each rank
// computes every size whose job number is congruent to its rank and the integer voxel counts are
// summed, so results do not depend on the rank count (nor on the OpenMP thread count: each opening
// is an exact integer count).

#include "common/mpi.hpp"
#include "common/voxel_grid.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace aniso::voxel {

/// One cumulative distribution: f(size[k]) = kept[k] / void_voxels, size[0] = 0 with f = 1.
struct Curve {
  std::vector<double> size;        ///< radius (ball, disk) or length (spar) [voxels]
  std::vector<std::uint64_t> kept; ///< void voxels kept by the opening of that size
  /// Spar only: void voxels on all-void lines (an opening of any length keeps them).
  std::uint64_t infinite = 0;
  /// Size where f crosses 0.5, linearly interpolated between the two bracketing sizes;
  /// +infinity if f never falls below 0.5 (a spar on mostly all-void lines). NaN if no void.
  double median = 0;
};

struct VoidAnalysisOptions {
  /// Ball and disk radii: 0 = every distinct digital element (rho = sqrt(r2) for every r2 that is a
  /// sum of three (ball) or two (disk) squares); > 0 = k * radius_step voxels, k = 0, 1, ...
  double radius_step = 0;
  bool balls = true;
  bool disks = true;
  bool spars = true;
};

struct VoidAnalysis {
  std::uint64_t voxels = 0;
  std::uint64_t void_voxels = 0;
  Curve ball;                ///< eq. (fr)
  std::array<Curve, 3> spar; ///< eq. (fli), along x1, x2, x3
  std::array<Curve, 3> disk; ///< eq. (fri), axis x1, x2, x3
  std::int64_t euler = 0;    ///< chi of the void, 26-connected void / 6-connected solid, periodic
};

/// Squared radius of the digital ball or disk of radius rho: the largest integer r2 <= rho^2.
std::uint32_t squared_radius(double rho);

/// Radii of the ball (squares = 3) or disk (squares = 2) openings, from 0 up to the first whose
/// erosion is empty (squared_radius >= max_d2, the largest squared distance to the solid): that
/// size and every larger one keep nothing. step > 0: k * step; step == 0: every distinct digital
/// element, rho = sqrt(r2) for every r2 that is a sum of `squares` squares.
std::vector<double> opening_radii(double step, std::uint32_t max_d2, int squares);

/// Linear interpolation of the size where kept/void crosses 0.5 (see Curve::median).
double median_size(const Curve& curve, std::uint64_t void_voxels);

/// L^v_ii = 3 m_i / (m_1 + m_2 + m_3) for medians m (eqs. (Lambdaii), (Rii)); NaN where undefined.
std::array<double, 3> normalized_medians(const std::array<double, 3>& medians);

/// The whole analysis of a periodic phase image (1 solid, 0 void). Collective on comm; every rank
/// passes the same image and receives the same result.
VoidAnalysis analyze_voids(const Grid& grid, std::span<const std::uint8_t> phase,
                           const VoidAnalysisOptions& options, const mpi::Comm& comm);

} // namespace aniso::voxel
