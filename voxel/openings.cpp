#include "voxel/openings.hpp"

#include <algorithm>

namespace aniso::voxel {
namespace {

// Calls visit(first, stride, length) for every line along axis (sequentially, in index order of
// the other two coordinates).
template <class Visit> void for_each_line(const Grid& grid, int axis, const Visit& visit) {
  const std::size_t n0 = grid.n[0];
  const std::size_t n = grid.n[static_cast<std::size_t>(axis)];
  const std::size_t stride = grid.stride(axis);
  if (axis == 0) {
    for (std::size_t row = 0; row < grid.n[1] * grid.n[2]; ++row)
      visit(row * n0, stride, n);
    return;
  }
  const std::size_t others = axis == 1 ? grid.n[2] : grid.n[1];
  const std::size_t other_stride = axis == 1 ? n0 * grid.n[1] : n0;
  for (std::size_t other = 0; other < others; ++other)
    for (std::size_t i = 0; i < n0; ++i)
      visit(i + other * other_stride, stride, n);
}

// Runs of void voxels on one periodic line: calls run(start, length) with positions taken mod n;
// returns false (and calls nothing) if the whole line is void.
template <class Run>
bool for_each_void_run(std::span<const std::uint8_t> phase, std::size_t first, std::size_t stride,
                       std::size_t n, const Run& run) {
  std::size_t solid = n;
  for (std::size_t t = 0; t < n; ++t)
    if (phase[first + t * stride] != 0) {
      solid = t;
      break;
    }
  if (solid == n) return false;
  // Walk once around the line starting just after a solid voxel, so that no run is cut by the wrap.
  std::size_t length = 0;
  for (std::size_t step = 1; step <= n; ++step) {
    const std::size_t t = (solid + step) % n;
    if (phase[first + t * stride] == 0) {
      ++length;
    } else if (length > 0) {
      run((t + n - length) % n, length);
      length = 0;
    }
  }
  return true;
}

} // namespace

std::vector<std::uint32_t> distance_to_solid(const Grid& grid, std::span<const std::uint8_t> phase,
                                             Axes axes) {
  return squared_distance(grid, phase, axes);
}

std::uint64_t round_opening_volume(const Grid& grid, std::span<const std::uint32_t> solid_distance, Axes axes,
                                   std::uint32_t r2, std::vector<std::uint32_t>& work) {
  // Dilation of the erosion: only distances <= r2 matter, so the transform is capped at r2.
  squared_distance(grid, Target::above(solid_distance, r2), axes, r2, work);
  const auto size = static_cast<std::int64_t>(work.size());
  std::uint64_t kept = 0;
#pragma omp parallel for schedule(static) reduction(+ : kept)
  for (std::int64_t index = 0; index < size; ++index)
    kept += work[static_cast<std::size_t>(index)] <= r2 ? 1U : 0U;
  return kept;
}

Mask round_opening(const Grid& grid, std::span<const std::uint32_t> solid_distance, Axes axes,
                   std::uint32_t r2, std::vector<std::uint32_t>& work) {
  squared_distance(grid, Target::above(solid_distance, r2), axes, r2, work);
  Mask kept(grid.size());
  std::transform(work.begin(), work.end(), kept.begin(), [r2](std::uint32_t d2) { return d2 <= r2 ? 1 : 0; });
  return kept;
}

Mask spar_opening(const Grid& grid, std::span<const std::uint8_t> phase, int axis, std::size_t length) {
  Mask kept(grid.size(), 0);
  for_each_line(grid, axis, [&](std::size_t first, std::size_t stride, std::size_t n) {
    const bool has_solid =
        for_each_void_run(phase, first, stride, n, [&](std::size_t start, std::size_t run) {
          if (run < length) return;
          for (std::size_t t = 0; t < run; ++t)
            kept[first + ((start + t) % n) * stride] = 1;
        });
    if (!has_solid)
      for (std::size_t t = 0; t < n; ++t)
        kept[first + t * stride] = 1;
  });
  return kept;
}

RunLengths void_run_lengths(const Grid& grid, std::span<const std::uint8_t> phase, int axis) {
  const std::size_t n = grid.n[static_cast<std::size_t>(axis)];
  RunLengths runs;
  runs.volume_by_length.assign(n + 1, 0);
  for_each_line(grid, axis, [&](std::size_t first, std::size_t stride, std::size_t length) {
    const bool has_solid = for_each_void_run(phase, first, stride, length, [&](std::size_t, std::size_t run) {
      runs.volume_by_length[run] += run;
    });
    if (!has_solid) runs.infinite_volume += length;
  });
  return runs;
}

std::uint64_t RunLengths::opening_volume(std::size_t length) const {
  std::uint64_t kept = infinite_volume;
  for (std::size_t m = std::max<std::size_t>(length, 1); m < volume_by_length.size(); ++m)
    kept += volume_by_length[m];
  return kept;
}

} // namespace aniso::voxel
