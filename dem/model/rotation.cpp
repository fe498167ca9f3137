#include "dem/model/rotation.hpp"

#include <cmath>

namespace aniso::dem::model {

namespace {

// sin and cos of half of `angle`. A particle turns by far less than 1e-3 rad in a time step;
// there the series to x^7 and x^8 is exact to round-off (the first term left out is below
// 1e-28 of the result) for a few multiplications instead of the library's sincos. Larger
// angles take the library's.
struct HalfAngle {
  double sine, cosine;
};
inline HalfAngle half_angle(double angle) {
  const double half = 0.5 * angle;
  if (std::abs(half) >= 1e-3) return {std::sin(half), std::cos(half)};
  const double h2 = half * half;
  return {half * (1.0 - h2 / 6.0 * (1.0 - h2 / 20.0 * (1.0 - h2 / 42.0))),
          1.0 - h2 / 2.0 * (1.0 - h2 / 12.0 * (1.0 - h2 / 30.0 * (1.0 - h2 / 56.0)))};
}

} // namespace

void free_rotation(Quat& orientation, Vec3& angular_velocity, const Vec3& inertia, double dt) {
  const Vec3 axis = particle_axis(orientation);
  const Vec3 momentum = inertia_times(inertia, axis, angular_velocity);
  const double momentum_norm = momentum.norm();
  if (momentum_norm == 0.0) return;
  // Precession about L by |L| dt / I1, and spin about the body axis z.
  const HalfAngle p = half_angle(momentum_norm * dt / inertia.x());
  const Vec3 p_vector = (p.sine / momentum_norm) * momentum;
  const Quat precession(p.cosine, p_vector.x(), p_vector.y(), p_vector.z());
  const HalfAngle s = half_angle((1.0 / inertia.z() - 1.0 / inertia.x()) * momentum.dot(axis) * dt);
  const Quat spin(s.cosine, 0.0, 0.0, s.sine);
  orientation = (precession * orientation * spin).normalized();
  angular_velocity = inverse_inertia_times(inertia, particle_axis(orientation), momentum);
}

} // namespace aniso::dem::model
