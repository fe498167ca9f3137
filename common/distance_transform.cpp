#include "common/distance_transform.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace aniso::voxel {
namespace {

using Value = std::uint32_t;
// Lines along x2 and x3 are gathered 16 at a time: 16 neighbours along x1 fill one 64-byte cache
// line of 4-byte distances, so the strided passes read whole cache lines.
constexpr std::size_t batch = 16;

std::int64_t floor_div(std::int64_t a, std::int64_t b) { // b > 0
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

Value capped(std::int64_t d2, Value cap) {
  return d2 > static_cast<std::int64_t>(cap) ? infinite_distance : static_cast<Value>(d2);
}

// Working memory of one thread: the lower envelope of one extended line.
struct Envelope {
  std::vector<std::int64_t> site;  // extended position of the parabola's apex
  std::vector<std::int64_t> value; // its height f
  std::vector<std::int64_t> start; // first extended position where it is the minimum
  void reserve(std::size_t length) {
    site.resize(length);
    value.resize(length);
    start.resize(length);
  }
};

// Run-length pass on one periodic line: out[p] = (distance along the line to the nearest target)^2.
void run_length_line(const std::uint8_t* target, std::size_t n, Value cap, Value* out) {
  const auto size = static_cast<std::int64_t>(n);
  std::int64_t last = -1;
  for (std::int64_t p = size - 1; p >= 0 && last < 0; --p)
    if (target[p] != 0) last = p;
  if (last < 0) {
    std::fill_n(out, n, infinite_distance);
    return;
  }
  std::int64_t first = 0;
  while (target[first] == 0)
    ++first;
  std::int64_t previous = last - size; // image of the last target before the line start
  for (std::int64_t p = 0; p < size; ++p) {
    if (target[p] != 0) previous = p;
    const std::int64_t d = p - previous;
    out[p] = capped(d * d, cap);
  }
  std::int64_t next = first + size; // image of the first target after the line end
  for (std::int64_t p = size - 1; p >= 0; --p) {
    if (target[p] != 0) next = p;
    const std::int64_t d = next - p;
    out[p] = std::min(out[p], capped(d * d, cap));
  }
}

// Parabola pass on one periodic line, in place: f[p] <- min over q and images of f[q] + (p - q)^2.
// Only apexes within `reach` of p can win (see parabola_reach), so the line is extended by
// h = min(n/2, reach) on each side: the nearest image of any useful q lies in [p - h, p + h].
void parabola_line(Value* f, std::size_t n, Value cap, std::int64_t reach, Envelope& envelope) {
  const auto size = static_cast<std::int64_t>(n);
  const std::int64_t h = std::min(size / 2, reach);
  const std::int64_t length = size + 2 * h;
  auto height = [&](std::int64_t x, std::int64_t k) {
    const std::int64_t d = x - envelope.site[k];
    return d * d + envelope.value[k];
  };
  std::int64_t k = -1;
  std::int64_t q = size - h; // position on the line of extended position u, kept without a modulo
  for (std::int64_t u = 0; u < length; ++u, ++q) {
    if (q == size) q = 0;
    const Value fu = f[q];
    if (fu == infinite_distance) continue;
    const auto value_u = static_cast<std::int64_t>(fu);
    while (k >= 0) {
      const std::int64_t d = envelope.start[k] - u;
      if (height(envelope.start[k], k) <= d * d + value_u) break;
      --k;
    }
    if (k < 0) {
      k = 0;
      envelope.site[0] = u;
      envelope.value[0] = value_u;
      envelope.start[0] = 0;
      continue;
    }
    const std::int64_t s = envelope.site[k];
    const std::int64_t w = 1 + floor_div(u * u - s * s + value_u - envelope.value[k], 2 * (u - s));
    if (w < length) {
      ++k;
      envelope.site[k] = u;
      envelope.value[k] = value_u;
      envelope.start[k] = w;
    }
  }
  if (k < 0) {
    std::fill_n(f, n, infinite_distance);
    return;
  }
  for (std::int64_t x = h + size - 1; x >= h; --x) {
    while (envelope.start[k] > x)
      --k;
    f[x - h] = capped(height(x, k), cap);
  }
}

// How far an apex q can be from a point p whose output it sets: output(p) <= f(p) (q = p is a
// candidate) and output(p) <= cap matters only, so (p - q)^2 <= min(f(p), cap). A line whose
// points are all finite needs sqrt(max f); one with an infinite point needs sqrt(cap) (or n/2).
// Returns -1 for a line with no finite value (nothing to do: it stays infinite).
std::int64_t parabola_reach(const Value* f, std::size_t n, Value cap) {
  Value largest = 0;
  bool any_finite = false;
  for (std::size_t t = 0; t < n; ++t) {
    if (f[t] == infinite_distance) {
      largest = std::max(largest, cap);
    } else {
      any_finite = true;
      largest = std::max(largest, std::min(f[t], cap));
    }
  }
  if (!any_finite) return -1;
  return static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(largest)))) + 1;
}

void transform_line(Value* f, std::size_t n, Value cap, Envelope& envelope) {
  const std::int64_t reach = parabola_reach(f, n, cap);
  if (reach >= 0) parabola_line(f, n, cap, reach, envelope);
}

// Calls line(first_index, stride, length, lanes) for every group of up to `batch` lines along
// `axis` that are neighbours along x1 (one line at a time along x1 itself), in parallel.
template <class LineGroup> void for_each_line_group(const Grid& grid, int axis, const LineGroup& line) {
  const std::size_t n0 = grid.n[0];
  if (axis == 0) {
    const auto rows = static_cast<std::int64_t>(grid.n[1] * grid.n[2]);
#pragma omp parallel for schedule(static)
    for (std::int64_t row = 0; row < rows; ++row)
      line(static_cast<std::size_t>(row) * n0, 1, 1);
    return;
  }
  // Lines along x2: one group per (x1 block, k); along x3: one per (x1 block, j).
  const std::size_t blocks = (n0 + batch - 1) / batch;
  const std::size_t others = axis == 1 ? grid.n[2] : grid.n[1];
  const std::size_t other_stride = axis == 1 ? n0 * grid.n[1] : n0;
  const auto groups = static_cast<std::int64_t>(blocks * others);
#pragma omp parallel for schedule(static)
  for (std::int64_t group = 0; group < groups; ++group) {
    const std::size_t block = static_cast<std::size_t>(group) % blocks;
    const std::size_t other = static_cast<std::size_t>(group) / blocks;
    const std::size_t i0 = block * batch;
    line(i0 + other * other_stride, grid.stride(axis), std::min(batch, n0 - i0));
  }
}

void run_length_pass(const Grid& grid, const Target& target, int axis, Value cap, Value* out) {
  const std::size_t n = grid.n[static_cast<std::size_t>(axis)];
  for_each_line_group(grid, axis, [&](std::size_t first, std::size_t stride, std::size_t lanes) {
    thread_local std::vector<std::uint8_t> in;
    thread_local std::vector<Value> result;
    in.resize(n);
    result.resize(n);
    for (std::size_t lane = 0; lane < lanes; ++lane) {
      for (std::size_t t = 0; t < n; ++t)
        in[t] = target(first + lane + t * stride) ? 1 : 0;
      run_length_line(in.data(), n, cap, result.data());
      for (std::size_t t = 0; t < n; ++t)
        out[first + lane + t * stride] = result[t];
    }
  });
}

void parabola_pass(const Grid& grid, int axis, Value cap, Value* data) {
  const std::size_t n = grid.n[static_cast<std::size_t>(axis)];
  for_each_line_group(grid, axis, [&](std::size_t first, std::size_t stride, std::size_t lanes) {
    thread_local std::vector<Value> lines;
    thread_local Envelope envelope;
    lines.resize(batch * n);
    envelope.reserve(2 * n + 1);
    if (stride == 1) {
      transform_line(data + first, n, cap, envelope);
      return;
    }
    // Gather the group lane-major so that each line is contiguous, transform, scatter back.
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t lane = 0; lane < lanes; ++lane)
        lines[lane * n + t] = data[first + lane + t * stride];
    for (std::size_t lane = 0; lane < lanes; ++lane)
      transform_line(lines.data() + lane * n, n, cap, envelope);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t lane = 0; lane < lanes; ++lane)
        data[first + lane + t * stride] = lines[lane * n + t];
  });
}

} // namespace

Axes Axes::plane(int normal) {
  Axes axes;
  axes.count = 2;
  int slot = 0;
  for (int axis = 0; axis < 3; ++axis)
    if (axis != normal) axes.order[static_cast<std::size_t>(slot++)] = axis;
  axes.order[2] = normal;
  return axes;
}

void squared_distance(const Grid& grid, const Target& target, Axes axes, std::uint32_t cap,
                      std::vector<std::uint32_t>& out) {
  out.resize(grid.size());
  run_length_pass(grid, target, axes.order[0], cap, out.data());
  for (int pass = 1; pass < axes.count; ++pass)
    parabola_pass(grid, axes.order[static_cast<std::size_t>(pass)], cap, out.data());
}

std::vector<std::uint32_t> squared_distance(const Grid& grid, std::span<const std::uint8_t> mask, Axes axes) {
  std::vector<std::uint32_t> out;
  squared_distance(grid, Target::of_mask(mask), axes, infinite_distance - 1, out);
  return out;
}

} // namespace aniso::voxel
