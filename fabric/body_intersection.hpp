#pragma once
// Whether up to four particles (spheres or ovoids) share a point, for N_3 and N_4.

#include "common/tensor.hpp"

#include <span>

namespace aniso::fabric {

/// A particle placed in the world: shape, centre and body-to-world rotation.
struct PlacedBody {
  double diameter;
  double aspect_ratio; ///< 1 = sphere
  double splice_angle; ///< ovoid splice angle [rad]
  Vec3 centre;
  Quat orientation;
};

/// Spheres: exact (fabric/ball_intersection.hpp). Ovoids: minimises the largest signed distance
/// to the bodies (convex) by prox-linear steps; "true" is certified by a point inside every body,
/// "false" by a positive lower bound of that distance over a ball holding every common point.
/// Only when the deepest common point lies within about 1e-13 D of the surfaces (bodies touching
/// at a point) can the iteration limit end undecided; it then answers false.
bool bodies_share_point(std::span<const PlacedBody> bodies);

} // namespace aniso::fabric
