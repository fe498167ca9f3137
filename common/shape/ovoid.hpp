#pragma once
// Kuhn's ovoid ("kshape 5", Kuhn, Sun & Wang 2015, section 2): a solid of revolution whose
// meridian is three circular arcs with a common tangent where they meet: a top cap (sphere
// piece), a central band (torus piece) and a bottom cap. The splice angle beta, between the
// axis and the surface normal on the circle where cap meets band, fixes the free parameter.
// Formulas, validity range and validation: docs/methods/ovoid.md; the choice of beta:
// /work/shared/reference/ovoid.md.
//
// Body frame throughout: the axis of revolution is z, the centre is the origin. A meridian
// point is written (rho, z) with rho >= 0 the distance from the axis; the normal angle theta
// is measured from +z, so theta in [0, beta] is the top cap, [beta, pi - beta] the band and
// [pi - beta, pi] the bottom cap.

#include "common/tensor.hpp"

#include <cstdint>
#include <numbers>

namespace aniso {

/// The three surface pieces; each is a core (a point or a circle) offset by a radius.
enum class OvoidPiece : std::uint8_t {
  top_cap = 0,    ///< sphere of radius R_c about (0, 0, +z_c), normals within beta of +z
  band = 1,       ///< torus: tube radius r_t about the circle rho = rho0, z = 0
  bottom_cap = 2, ///< sphere of radius R_c about (0, 0, -z_c), normals within beta of -z
};

/// Nearest surface point to a query point x: x = point + signed_distance * normal.
struct OvoidSurfacePoint {
  Vec3 point;             ///< on the surface
  Vec3 normal;            ///< outward unit normal at point
  double signed_distance; ///< > 0 outside, < 0 inside
  OvoidPiece piece;       ///< the piece holding point
};

/// The support function h(n) = max over the body of x.n, and the point that attains it.
struct OvoidSupport {
  double value; ///< h(n) for the unit vector n
  Vec3 point;   ///< surface point whose outward normal is n
  OvoidPiece piece;
};

/// Principal curvatures (1/length, > 0 for the convex surface) and their unit directions.
struct OvoidCurvatures {
  double meridian; ///< along the meridian: 1/R_c on a cap, 1/r_t on the band
  double hoop;     ///< along the parallel circle: sin(theta)/rho (Meusnier)
  Vec3 meridian_direction;
  Vec3 hoop_direction;
};

/// Body-frame surface integrals (all diagonal, with xx == yy by symmetry).
struct OvoidSurfaceTensors {
  Mat3 position;          ///< integral of x (x) x dA
  Mat3 normal;            ///< integral of n (x) n dA
  Mat3 gaussian_position; ///< integral of K x (x) x dA, K the Gaussian curvature
};

class OvoidShape {
public:
  static constexpr double default_splice_angle = std::numbers::pi / 4.0;

  /// Ovoid of mid-plane diameter D > 0, aspect ratio alpha = height / D in (0, 1] and splice
  /// angle beta (radians) with 0 < beta < 2 atan(alpha) when alpha < 1; alpha == 1 is the
  /// sphere for every beta in (0, pi/2). Throws InputError naming the numbers otherwise.
  OvoidShape(double diameter, double aspect_ratio, double splice_angle = default_splice_angle);

  [[nodiscard]] double diameter() const { return diameter_; }
  [[nodiscard]] double aspect_ratio() const { return aspect_ratio_; }
  [[nodiscard]] double splice_angle() const { return splice_angle_; }
  [[nodiscard]] double half_width() const { return 0.5 * diameter_; }                  ///< a = D/2
  [[nodiscard]] double half_height() const { return 0.5 * aspect_ratio_ * diameter_; } ///< alpha a
  [[nodiscard]] double cap_radius() const { return cap_radius_; }                      ///< R_c
  [[nodiscard]] double tube_radius() const { return tube_radius_; }                    ///< r_t
  [[nodiscard]] double tube_centre_radius() const { return tube_centre_radius_; }      ///< rho0
  [[nodiscard]] double cap_centre_height() const { return cap_centre_height_; }        ///< z_c (< 0 oblate)
  [[nodiscard]] double splice_radius() const { return cap_radius_ * std::sin(splice_angle_); }
  [[nodiscard]] double splice_height() const { return tube_radius_ * std::cos(splice_angle_); }
  /// Centre of the cap sphere of a cap piece (band: the origin, centre of its core circle).
  [[nodiscard]] Vec3 core_centre(OvoidPiece piece) const;
  /// Offset radius of a piece: R_c for a cap, r_t for the band.
  [[nodiscard]] double piece_radius(OvoidPiece piece) const;

  /// The piece whose range of outward normals holds the unit body-frame normal n.
  [[nodiscard]] OvoidPiece piece_of_normal(const Vec3& normal) const;

  /// True when x lies in the closed body.
  [[nodiscard]] bool inside(const Vec3& x) const;
  /// Exact nearest surface point, outward normal and signed distance (reduced to the meridian
  /// plane; the nearest stationary point over the three arcs).
  [[nodiscard]] OvoidSurfacePoint closest_point(const Vec3& x) const;
  [[nodiscard]] double signed_distance(const Vec3& x) const { return closest_point(x).signed_distance; }
  /// Distance from the centre to the surface along the ray of the given direction (nonzero).
  [[nodiscard]] double radial_distance(const Vec3& direction) const;

  /// Principal curvatures at the surface point nearest to x (x should be on the surface).
  [[nodiscard]] OvoidCurvatures principal_curvatures(const Vec3& x) const;

  /// Support function and support point for a nonzero direction (normalised here).
  [[nodiscard]] OvoidSupport support(const Vec3& direction) const;

  /// Closed-form volume and surface area.
  [[nodiscard]] double volume() const;
  [[nodiscard]] double surface_area() const;
  /// Inertia tensor about the centre for unit density (mass = volume); diag(I_xx, I_xx, I_zz).
  [[nodiscard]] Mat3 inertia_unit_density() const;
  /// Surface tensors, by 32-point Gauss-Legendre on each arc in theta (integrands are entire
  /// trigonometric polynomials, so the rule is exact to round-off).
  [[nodiscard]] OvoidSurfaceTensors surface_tensors() const;

private:
  double diameter_;
  double aspect_ratio_;
  double splice_angle_;
  double cos_splice_;
  double cap_radius_;
  double tube_radius_;
  double tube_centre_radius_;
  double cap_centre_height_;
};

/// How the ovoid is matched to the oblate spheroid of the same D and alpha.
enum class SpheroidMatch : std::uint8_t {
  max_radial_difference, ///< minimise max over directions of |r_ovoid - r_spheroid| (along rays)
  volume,                ///< equal volumes
};

/// Distance of an ovoid from the spheroid of semi-axes (a, a, alpha a).
struct SpheroidComparison {
  double volume_relative_difference; ///< (V_ovoid - V_spheroid) / V_spheroid
  double max_radial_difference;      ///< max over rays of |r_ovoid - r_spheroid|, in units of D
  double polar_angle_at_max;         ///< angle from the axis (radians) where it occurs
};
SpheroidComparison compare_with_spheroid(const OvoidShape& shape);

/// The splice angle (radians) that best matches the spheroid of the same alpha in (0, 1).
double best_splice_angle(double aspect_ratio, SpheroidMatch criterion);

} // namespace aniso
