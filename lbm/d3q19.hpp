#pragma once
// The D3Q19 velocity set: 19 discrete velocities (rest, 6 axis, 12 face
// diagonals) with weights 1/3, 1/18, 1/36 and sound speed c_s^2 = 1/3.
// Opposite velocities are adjacent (i odd, i + 1), so the TRT collision can
// walk the nine pairs directly.

#include <array>
#include <cstddef>

namespace aniso::lbm::d3q19 {

inline constexpr int q = 19;
inline constexpr double cs2 = 1.0 / 3.0;

inline constexpr std::array<std::array<int, 3>, q> c{{{0, 0, 0},
                                                      {1, 0, 0},
                                                      {-1, 0, 0},
                                                      {0, 1, 0},
                                                      {0, -1, 0},
                                                      {0, 0, 1},
                                                      {0, 0, -1},
                                                      {1, 1, 0},
                                                      {-1, -1, 0},
                                                      {1, -1, 0},
                                                      {-1, 1, 0},
                                                      {1, 0, 1},
                                                      {-1, 0, -1},
                                                      {1, 0, -1},
                                                      {-1, 0, 1},
                                                      {0, 1, 1},
                                                      {0, -1, -1},
                                                      {0, 1, -1},
                                                      {0, -1, 1}}};

inline constexpr std::array<double, q> w{1.0 / 3.0,  1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0,
                                         1.0 / 18.0, 1.0 / 18.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0,
                                         1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0,
                                         1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0};

// Internal linkage, as the kernels that call them (lbm/stream_collide.hpp).
namespace {

/// Index of the velocity -c[i].
constexpr int opposite(int i) {
  return i == 0 ? 0 : (i % 2 == 1 ? i + 1 : i - 1);
}

/// Index of the velocity c[i] with the components on the axes in `flip` negated (specular reflection).
constexpr int mirrored(int i, const std::array<bool, 3>& flip) {
  std::array<int, 3> target = c[static_cast<std::size_t>(i)];
  for (std::size_t a = 0; a < 3; ++a)
    if (flip[a]) target[a] = -target[a];
  for (int k = 0; k < q; ++k)
    if (c[static_cast<std::size_t>(k)] == target) return k;
  return -1; // unreachable: the velocity set is closed under reflections
}

} // namespace
} // namespace aniso::lbm::d3q19
