#pragma once
// Structure-of-arrays particle store. On one rank index == id; with domain
// decomposition the owned particles come first and ghosts after them.
// Velocities are the fluctuating (non-affine) part: the total velocity of a
// particle at x is velocity + D x, with D the cell's diagonal strain rate.

#include "common/tensor.hpp"

#include <cstdint>
#include <vector>

namespace aniso::dem {

struct Particles {
  std::vector<std::uint64_t> id;
  std::vector<double> radius;         ///< half the mid-plane diameter [m]
  std::vector<double> aspect_ratio;   ///< 1 for spheres
  std::vector<double> mass;           ///< [kg]
  std::vector<Vec3> inertia;          ///< principal moments, body frame [kg m^2]
  std::vector<Vec3> position;         ///< [m], wrapped into the cell
  std::vector<Quat> orientation;      ///< body to world
  std::vector<Vec3> velocity;         ///< fluctuating velocity [m/s]
  std::vector<Vec3> angular_velocity; ///< world frame [rad/s]
  std::vector<Vec3> force;            ///< [N]
  std::vector<Vec3> torque;           ///< [N m]

  /// Particles [0, n_owned) belong to this rank; the rest are ghost copies of other ranks' particles.
  std::size_t n_owned = 0;

  [[nodiscard]] std::size_t size() const { return id.size(); }
  /// Resizes every array; all n particles count as owned.
  void resize(std::size_t n);
  /// Keeps the first n entries (used to drop ghosts).
  void truncate(std::size_t n);
  /// Appends one particle at rest with identity orientation.
  void add(std::uint64_t particle_id, double particle_radius, double particle_aspect_ratio, double density,
           const Vec3& particle_position);
  /// Solid volume of the owned particles [m^3].
  [[nodiscard]] double solid_volume() const;
};

/// Volume of a particle of this radius and aspect ratio (sphere for aspect ratio 1).
double particle_volume(double radius, double aspect_ratio);

} // namespace aniso::dem
