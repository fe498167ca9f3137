#pragma once
// Structure-of-arrays particle store. On one rank index == id; with domain
// decomposition the owned particles come first and ghosts after them.
// Velocities are the fluctuating (non-affine) part: the total velocity of a
// particle at x is velocity + D x, with D the cell's diagonal strain rate.

#include "common/tensor.hpp"

#include <cstdint>
#include <vector>

namespace aniso::dem::data {

struct Particles {
  std::vector<std::uint64_t> id;
  std::vector<double> radius;         ///< half the mid-plane diameter, a [m]
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
  /// Appends particle k of `source` (all its fields).
  void append(const Particles& source, std::size_t k);
  /// Overwrites entry `to` with entry `from` (compacting after migration).
  void move(std::size_t to, std::size_t from);
  /// Appends one particle at rest with the given orientation (body to world); mass and
  /// inertia follow from the shape (ovoids: splice angle beta, assembly-wide).
  void add(std::uint64_t particle_id, double particle_radius, double particle_aspect_ratio,
           double splice_angle, double density, const Vec3& particle_position,
           const Quat& particle_orientation = Quat::Identity());

private:
  void resize_arrays(std::size_t n);
};

} // namespace aniso::dem::data
