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

/// Spheres: exact (fabric/ball_intersection.hpp). Ovoids: cyclic projections onto the bodies
/// (each a closed convex set, common/shape/ovoid.hpp closest_point), which reach a common point
/// when one exists; a point found inside every body is a certificate, so the answer "true" is
/// exact, and "false" means no common point was reached within the iteration limit (only an
/// intersection thinner than about 1e-9 D can be missed).
bool bodies_share_point(std::span<const PlacedBody> bodies);

} // namespace aniso::fabric
