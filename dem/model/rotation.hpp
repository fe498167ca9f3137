#pragma once
// Rigid rotation of an axisymmetric particle (principal moments I1 = I2 about axes normal to
// the axis of revolution, I3 about it), with the world-frame angular velocity as the state.
// The drift is the exact torque-free motion (free precession), so a velocity-Verlet splitting
// "kick by the torque, rotate freely, kick" conserves energy and angular momentum to
// round-off for a free particle. Derivation: docs/methods/ovoid.md.

#include "common/tensor.hpp"

namespace aniso::dem::model {

/// The particle's axis of revolution in the world frame, q z for a unit quaternion q: the third
/// column of its rotation matrix (a third of the arithmetic of rotating a general vector).
inline Vec3 particle_axis(const Quat& q) {
  return {2.0 * (q.x() * q.z() + q.w() * q.y()), 2.0 * (q.y() * q.z() - q.w() * q.x()),
          1.0 - 2.0 * (q.x() * q.x() + q.y() * q.y())};
}

/// I_world^-1 v for body-frame principal moments `inertia` (x == y) and world axis `axis`.
inline Vec3 inverse_inertia_times(const Vec3& inertia, const Vec3& axis, const Vec3& v) {
  return v / inertia.x() + (1.0 / inertia.z() - 1.0 / inertia.x()) * v.dot(axis) * axis;
}
/// I_world v.
inline Vec3 inertia_times(const Vec3& inertia, const Vec3& axis, const Vec3& v) {
  return inertia.x() * v + (inertia.z() - inertia.x()) * v.dot(axis) * axis;
}

/// Rotational kinetic energy omega . I_world omega / 2.
inline double rotational_energy(const Vec3& inertia, const Quat& orientation, const Vec3& angular_velocity) {
  return 0.5 * angular_velocity.dot(inertia_times(inertia, particle_axis(orientation), angular_velocity));
}

/// Advances orientation and world angular velocity by dt of torque-free motion, exactly:
/// with L = I_world omega fixed, R(t) = Rot(L, |L| t / I1) R(0) Rot_body(z, (1/I3 - 1/I1) L.e t).
void free_rotation(Quat& orientation, Vec3& angular_velocity, const Vec3& inertia, double dt);

} // namespace aniso::dem::model
