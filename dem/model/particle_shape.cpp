#include "dem/model/particle_shape.hpp"

#include "common/error.hpp"
#include "common/shape/ovoid.hpp"
#include "dem/model/rotation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace aniso::dem::model {

double particle_volume(double radius, double aspect_ratio, double splice_angle) {
  if (aspect_ratio == 1.0) return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  return OvoidShape(2.0 * radius, aspect_ratio, splice_angle).volume();
}

double volume_equivalent_radius(double radius, double aspect_ratio, double splice_angle) {
  if (aspect_ratio == 1.0) return radius;
  return std::cbrt(3.0 * particle_volume(radius, aspect_ratio, splice_angle) / (4.0 * std::numbers::pi));
}

Vec3 particle_inertia(double radius, double aspect_ratio, double splice_angle, double density) {
  if (aspect_ratio == 1.0) {
    const double mass = density * particle_volume(radius, 1.0, splice_angle);
    return Vec3::Constant(0.4 * mass * radius * radius);
  }
  return density * OvoidShape(2.0 * radius, aspect_ratio, splice_angle).inertia_unit_density().diagonal();
}

void ShapeTable::add(double aspect_ratio) {
  for (const Entry& entry : entries_)
    if (entry.aspect_ratio == aspect_ratio) return;
  ConvexBody unit;
  unit.bounding_radius = 1.0;
  if (aspect_ratio == 1.0) {
    unit.cap_radius = 1.0;
    unit.tube_radius = 1.0;
  } else {
    const OvoidShape shape(2.0, aspect_ratio, splice_angle_);
    unit.cap_radius = shape.cap_radius();
    unit.cap_centre_height = shape.cap_centre_height();
    unit.tube_radius = shape.tube_radius();
    unit.tube_centre_radius = shape.tube_centre_radius();
    unit.cos_splice = std::cos(splice_angle_);
  }
  entries_.push_back({aspect_ratio, unit});
}

ConvexBody ShapeTable::body(double radius, double aspect_ratio, const Quat& orientation) const {
  for (const Entry& entry : entries_) {
    if (entry.aspect_ratio != aspect_ratio) continue;
    ConvexBody b = entry.unit;
    b.axis = particle_axis(orientation);
    b.cap_radius *= radius;
    b.cap_centre_height *= radius;
    b.tube_radius *= radius;
    b.tube_centre_radius *= radius;
    b.bounding_radius = radius;
    return b;
  }
  check_invariant(false, "every particle's aspect ratio is in the shape table");
  return entries_.front().unit;
}

void ShapeTable::world_bodies(const data::Particles& particles, std::vector<ConvexBody>& bodies) const {
  // Sphere-sphere pairs take the fast path; a sphere meeting an ovoid needs its body too.
  const bool all_spheres =
      std::all_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.aspect_ratio == 1.0; });
  if (all_spheres) return;
  bodies.resize(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k)
    bodies[k] = body(particles.radius[k], particles.aspect_ratio[k], particles.orientation[k]);
}

} // namespace aniso::dem::model
