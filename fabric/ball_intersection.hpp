#pragma once
// Whether up to four closed balls share a point: the test behind N_3 and N_4, the
// triple and quadruple overlaps in the void's Euler characteristic on the 3-torus.

#include "common/tensor.hpp"

#include <span>

namespace aniso::fabric {

/// The largest power |x - c_k|^2 - r_k^2 at the point x that minimises it: the balls share
/// a point exactly when this is <= 0. Between 1 and 4 balls; centres and radii of equal length.
double min_max_power(std::span<const Vec3> centres, std::span<const double> radii);

/// True when the closed balls have a common point.
inline bool balls_share_point(std::span<const Vec3> centres, std::span<const double> radii) {
  return min_max_power(centres, radii) <= 0.0;
}

} // namespace aniso::fabric
