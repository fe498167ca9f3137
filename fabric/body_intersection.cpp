#include "fabric/body_intersection.hpp"

#include "common/shape/ovoid.hpp"
#include "fabric/ball_intersection.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace aniso::fabric {
namespace {

constexpr int max_sweeps = 200;

struct Frame {
  OvoidShape shape;
  Vec3 centre;
  Mat3 to_world;
};

bool all_spheres(std::span<const PlacedBody> bodies) {
  return std::all_of(bodies.begin(), bodies.end(), [](const PlacedBody& b) { return b.aspect_ratio == 1.0; });
}

} // namespace

bool bodies_share_point(std::span<const PlacedBody> bodies) {
  // Each body lies in its ball of radius D/2 (alpha <= 1): for spheres that is the exact test,
  // for ovoids a rigorous rejection before the iterative one.
  std::array<Vec3, 4> centres;
  std::array<double, 4> radii{};
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    centres[k] = bodies[k].centre;
    radii[k] = 0.5 * bodies[k].diameter;
  }
  const bool balls_meet = balls_share_point(std::span<const Vec3>(centres.data(), bodies.size()),
                                            std::span<const double>(radii.data(), bodies.size()));
  if (!balls_meet || all_spheres(bodies)) return balls_meet;
  std::vector<Frame> frames;
  double smallest = bodies[0].diameter;
  Vec3 x = Vec3::Zero();
  for (const PlacedBody& b : bodies) {
    frames.push_back({OvoidShape(b.diameter, b.aspect_ratio, b.splice_angle), b.centre,
                      b.orientation.normalized().toRotationMatrix()});
    smallest = std::min(smallest, b.diameter);
    x += b.centre / static_cast<double>(bodies.size());
  }
  // Project onto each body shrunk by a small depth, so that a common point of the true bodies
  // is reached in finitely many sweeps; the certificate is checked on the true bodies.
  const double depth = 1e-9 * smallest;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    const Vec3 start = x;
    bool inside_all = true;
    for (const Frame& f : frames) {
      const Vec3 local = f.to_world.transpose() * (x - f.centre);
      const OvoidSurfacePoint nearest = f.shape.closest_point(local);
      if (nearest.signed_distance > -depth) {
        inside_all = false;
        x = f.centre + f.to_world * (nearest.point - depth * nearest.normal);
      }
    }
    if (inside_all) return true;
    // Disjoint bodies: the projections settle into a fixed cycle, the sweep stops moving.
    if ((x - start).norm() < 1e-12 * smallest) break;
  }
  return std::all_of(frames.begin(), frames.end(),
                     [&](const Frame& f) { return f.shape.inside(f.to_world.transpose() * (x - f.centre)); });
}

} // namespace aniso::fabric
