#include "voxel/void_analysis.hpp"

#include "voxel/euler.hpp"
#include "voxel/openings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aniso::voxel {

std::uint32_t squared_radius(double rho) {
  return static_cast<std::uint32_t>(std::floor(rho * rho + 1e-9));
}

namespace {

// True if r2 = a^2 + b^2 (+ c^2 when three squares are allowed): the squared radii at which the
// digital disk (two) or ball (three) gains voxels. Three squares: all but 4^a (8b + 7) (Legendre).
bool sum_of_squares(std::uint32_t r2, int squares) {
  if (squares == 3) {
    while (r2 != 0 && r2 % 4 == 0)
      r2 /= 4;
    return r2 % 8 != 7;
  }
  for (std::uint32_t a = 0; a * a <= r2; ++a) {
    const std::uint32_t rest = r2 - a * a;
    const auto b = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(rest)));
    for (std::uint32_t c = b > 0 ? b - 1 : 0; c <= b + 1; ++c)
      if (c * c == rest) return true;
  }
  return false;
}

} // namespace

std::vector<double> opening_radii(double step, std::uint32_t max_d2, int squares) {
  std::vector<double> sizes{0.0};
  if (step == 0) {
    for (std::uint32_t r2 = 1;; ++r2) {
      if (!sum_of_squares(r2, squares)) continue;
      sizes.push_back(std::sqrt(static_cast<double>(r2)));
      if (r2 >= max_d2) break;
    }
    return sizes;
  }
  for (std::size_t k = 1;; ++k) {
    const double rho = static_cast<double>(k) * step;
    sizes.push_back(rho);
    if (squared_radius(rho) >= max_d2) break;
  }
  return sizes;
}

namespace {

std::uint32_t max_void_distance(std::span<const std::uint32_t> distance) {
  std::uint32_t largest = 0;
  for (const std::uint32_t d2 : distance)
    if (d2 != infinite_distance) largest = std::max(largest, d2);
  return largest;
}

// One opening to compute: a size of the ball (axis -1) or of the disk with axis `axis`.
struct Job {
  int axis;
  std::size_t size_index;
};

Curve spar_curve(const Grid& grid, std::span<const std::uint8_t> phase, int axis, std::uint64_t void_voxels) {
  const RunLengths runs = void_run_lengths(grid, phase, axis);
  Curve curve;
  const std::size_t n = grid.n[static_cast<std::size_t>(axis)];
  for (std::size_t length = 0; length <= n; ++length) {
    curve.size.push_back(static_cast<double>(length));
    curve.kept.push_back(length == 0 ? void_voxels : runs.opening_volume(length));
  }
  curve.infinite = runs.infinite_volume;
  curve.median = median_size(curve, void_voxels);
  return curve;
}

} // namespace

double median_size(const Curve& curve, std::uint64_t void_voxels) {
  if (void_voxels == 0) return std::numeric_limits<double>::quiet_NaN();
  const double total = static_cast<double>(void_voxels);
  for (std::size_t k = 1; k < curve.size.size(); ++k) {
    const double f0 = static_cast<double>(curve.kept[k - 1]) / total;
    const double f1 = static_cast<double>(curve.kept[k]) / total;
    if (f0 >= 0.5 && f1 < 0.5)
      return curve.size[k - 1] + (f0 - 0.5) / (f0 - f1) * (curve.size[k] - curve.size[k - 1]);
  }
  return std::numeric_limits<double>::infinity();
}

std::array<double, 3> normalized_medians(const std::array<double, 3>& medians) {
  const double trace = medians[0] + medians[1] + medians[2];
  std::array<double, 3> normalized{};
  for (std::size_t a = 0; a < 3; ++a)
    normalized[a] =
        std::isfinite(trace) && trace > 0 ? 3 * medians[a] / trace : std::numeric_limits<double>::quiet_NaN();
  return normalized;
}

VoidAnalysis analyze_voids(const Grid& grid, std::span<const std::uint8_t> phase,
                           const VoidAnalysisOptions& options, const mpi::Comm& comm) {
  VoidAnalysis result;
  result.voxels = grid.size();
  result.void_voxels = static_cast<std::uint64_t>(std::count(phase.begin(), phase.end(), std::uint8_t{0}));
  result.euler = void_euler_characteristic(grid, phase);
  if (options.spars)
    for (int axis = 0; axis < 3; ++axis)
      result.spar[static_cast<std::size_t>(axis)] = spar_curve(grid, phase, axis, result.void_voxels);

  // Distance maps to the solid: [0] 3D for the ball, [1 + a] in the plane normal to x_a for disks.
  std::array<std::vector<std::uint32_t>, 4> solid_distance;
  std::array<Axes, 4> axes{Axes::all(), Axes::plane(0), Axes::plane(1), Axes::plane(2)};
  std::array<Curve*, 4> curves{&result.ball, &result.disk[0], &result.disk[1], &result.disk[2]};
  std::vector<Job> jobs;
  for (int family = 0; family < 4; ++family) {
    if ((family == 0 && !options.balls) || (family > 0 && !options.disks)) continue;
    const auto f = static_cast<std::size_t>(family);
    solid_distance[f] = distance_to_solid(grid, phase, axes[f]);
    curves[f]->size =
        opening_radii(options.radius_step, max_void_distance(solid_distance[f]), family == 0 ? 3 : 2);
    curves[f]->kept.assign(curves[f]->size.size(), 0);
    curves[f]->kept[0] = result.void_voxels;
    for (std::size_t k = 1; k < curves[f]->size.size(); ++k)
      jobs.push_back({family, k});
  }
  // Each rank takes every size-th job; exact integer sums put the curves together.
  std::vector<std::int64_t> counts(jobs.size(), 0);
  std::vector<std::uint32_t> work;
  for (std::size_t j = static_cast<std::size_t>(comm.rank()); j < jobs.size();
       j += static_cast<std::size_t>(comm.size())) {
    const auto f = static_cast<std::size_t>(jobs[j].axis);
    const std::uint32_t r2 = squared_radius(curves[f]->size[jobs[j].size_index]);
    counts[j] = static_cast<std::int64_t>(round_opening_volume(grid, solid_distance[f], axes[f], r2, work));
  }
  counts = comm.sum(std::span<const std::int64_t>(counts));
  for (std::size_t j = 0; j < jobs.size(); ++j)
    curves[static_cast<std::size_t>(jobs[j].axis)]->kept[jobs[j].size_index] =
        static_cast<std::uint64_t>(counts[j]);
  for (Curve* curve : curves)
    if (!curve->size.empty()) curve->median = median_size(*curve, result.void_voxels);
  return result;
}

} // namespace aniso::voxel
