#pragma once
// Body-frame geometry of each particle that the particle and surface measures need, from
// common/shape/ovoid.hpp (spheres take a closed-form fast path), and its rotation to the world.

#include "common/tensor.hpp"

#include <vector>

namespace aniso::fabric {

/// Body-frame integrals of one particle shape (axis of revolution z), for mid-plane diameter D.
struct BodyTensors {
  Mat3 position = Mat3::Zero();          ///< integral of x (x) x dA [m^4], eq. (Ibari)
  Mat3 normal = Mat3::Zero();            ///< integral of n (x) n dA [m^2], eq. (Sbar)
  Mat3 gaussian_position = Mat3::Zero(); ///< integral of K x (x) x dA [m^2], eq. (W202)
  Mat3 widths = Mat3::Zero();            ///< A^p = diag(D, D, alpha D) in the body frame, eq. (Jbari)
  double area = 0;                       ///< surface area [m^2]
  double volume = 0;                     ///< [m^3]
};

/// Shape tensors per distinct (aspect ratio) at unit diameter, computed once and scaled by D.
class ShapeCatalogue {
public:
  /// splice_angle: the ovoid splice angle of the checkpoint [rad] (used when aspect ratio < 1).
  explicit ShapeCatalogue(double splice_angle) : splice_angle_(splice_angle) {}
  /// Tensors of a particle of diameter D [m] and aspect ratio alpha in (0, 1].
  [[nodiscard]] BodyTensors body(double diameter, double aspect_ratio);

private:
  struct Entry {
    double aspect_ratio;
    BodyTensors unit; ///< at D = 1
  };
  double splice_angle_;
  std::vector<Entry> entries_;
};

} // namespace aniso::fabric
