#include "dem/rotation.hpp"

#include <cmath>

namespace aniso::dem {

Vec3 inverse_inertia_times(const Vec3& inertia, const Vec3& axis, const Vec3& v) {
  return v / inertia.x() + (1.0 / inertia.z() - 1.0 / inertia.x()) * v.dot(axis) * axis;
}

Vec3 inertia_times(const Vec3& inertia, const Vec3& axis, const Vec3& v) {
  return inertia.x() * v + (inertia.z() - inertia.x()) * v.dot(axis) * axis;
}

namespace {

// Unit quaternion of a rotation by `angle` about `unit_axis`.
Quat axis_angle(const Vec3& unit_axis, double angle) {
  const double half = 0.5 * angle;
  const Vec3 v = std::sin(half) * unit_axis;
  return Quat(std::cos(half), v.x(), v.y(), v.z());
}

} // namespace

void free_rotation(Quat& orientation, Vec3& angular_velocity, const Vec3& inertia, double dt) {
  const Vec3 axis = orientation * Vec3::UnitZ();
  const Vec3 momentum = inertia_times(inertia, axis, angular_velocity);
  const double momentum_norm = momentum.norm();
  if (momentum_norm == 0.0) return;
  const double axial_momentum = momentum.dot(axis);
  const Quat precession = axis_angle(momentum / momentum_norm, momentum_norm * dt / inertia.x());
  const Quat spin = axis_angle(Vec3::UnitZ(), (1.0 / inertia.z() - 1.0 / inertia.x()) * axial_momentum * dt);
  orientation = (precession * orientation * spin).normalized();
  angular_velocity = inverse_inertia_times(inertia, orientation * Vec3::UnitZ(), momentum);
}

} // namespace aniso::dem
