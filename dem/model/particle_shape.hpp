#pragma once
// The shapes of an assembly's particles as the contact code needs them: one ovoid of unit
// half-width per distinct aspect ratio (all particles share the splice angle), scaled by each
// particle's half-width and turned by its orientation. Sphere pairs take the sphere fast path
// of the force loop; a sphere meeting an ovoid takes the convex narrow phase with its body.

#include "common/tensor.hpp"
#include "dem/data/particles.hpp"
#include "dem/model/ovoid_contact.hpp"

#include <vector>

namespace aniso::dem::model {

/// Volume of a particle of half-width `radius` (sphere for aspect ratio 1) [m^3].
double particle_volume(double radius, double aspect_ratio, double splice_angle);
/// Principal moments of inertia in the body frame (axis of revolution = z) [kg m^2].
Vec3 particle_inertia(double radius, double aspect_ratio, double splice_angle, double density);
/// Half the axial height, the smallest half-extent of an oblate particle [m].
inline double half_height(double radius, double aspect_ratio) {
  return radius * aspect_ratio;
}

/// Radius of the sphere of the same volume, the size that sets the time step: a particle's
/// contact period goes as sqrt(mass / stiffness), and its mass as its volume (docs/methods/dem.md,
/// "Time step"). For a sphere it is the radius.
double volume_equivalent_radius(double radius, double aspect_ratio, double splice_angle);

class ShapeTable {
public:
  explicit ShapeTable(double splice_angle) : splice_angle_(splice_angle) {}
  /// Makes the shape of this aspect ratio known (every rank must add the same set).
  void add(double aspect_ratio);
  /// The particle's geometry in the world frame; its aspect ratio must have been added.
  [[nodiscard]] ConvexBody body(double radius, double aspect_ratio, const Quat& orientation) const;
  /// Every particle's world-frame body (ghosts included), once per force pass: a particle
  /// meets several candidate partners, and rebuilding both bodies per pair cost 8% of an
  /// ovoid step. An assembly of spheres alone needs none (the sphere fast path) and gets none.
  void world_bodies(const data::Particles& particles, std::vector<ConvexBody>& bodies) const;
  [[nodiscard]] double splice_angle() const { return splice_angle_; }

private:
  struct Entry {
    double aspect_ratio;
    ConvexBody unit; ///< half-width 1, axis z
  };
  double splice_angle_;
  std::vector<Entry> entries_;
};

} // namespace aniso::dem::model
