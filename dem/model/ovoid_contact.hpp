#pragma once
// Narrow phase for convex particles of revolution: Kuhn's ovoid (paper section 2, Fig. 1) and
// the sphere as its degenerate case. Each ovoid is three pieces, a core offset by a radius:
// two caps (a point offset by R_c) and a band (the tube-centre circle offset by r_t). The
// contact is the minimum over unit normals n of the support-function gap
//     phi(n) = h_A(n) + h_B(-n) - d.n ,  d = x_B - x_A,
// whose minimum is the penetration depth (> 0: overlap) and whose minimiser is the contact
// normal. On each piece h is the support of its core plus the piece radius, so the
// stationarity condition is OVAL's "line between the cores is normal to both cores" for the
// cap-cap, cap-band and band-band pairs (/work/shared/reference/ovoid.md); the minimisation
// picks the valid pair by itself. Newton on the sphere, with the exact Hessian of h (the
// radius-of-curvature tensor) and a backtracking line search, warm-started from the previous
// normal, converges in a few iterations. Method and tests: docs/methods/ovoid.md.

#include "common/tensor.hpp"
#include "dem/model/contact_law.hpp"

#include <cstdint>

namespace aniso::dem::model {

/// One particle's geometry in the world frame, centre excluded. A sphere is a cap with
/// cap_centre_height = 0, cap_radius = its radius and cos_splice = -1 (every normal is cap).
struct ConvexBody {
  Vec3 axis = Vec3::UnitZ();     ///< unit axis of revolution, world frame
  double cap_radius = 0;         ///< R_c [m]
  double cap_centre_height = 0;  ///< z_c, cap-sphere centre on the axis (< 0 for oblate ovoids) [m]
  double tube_radius = 0;        ///< r_t [m]
  double tube_centre_radius = 0; ///< rho0, radius of the tube-centre circle [m]
  double cos_splice = -1;        ///< cos(beta); normals with |n.axis| >= cos(beta) are on a cap
  double bounding_radius = 0;    ///< half the mid-plane diameter, a [m]
};

/// The support point at a unit direction n, and what the Hessian of h there is made of.
struct Support {
  double value = 0;          ///< h(n) = max over the body of x.n (centre at the origin)
  Vec3 point = Vec3::Zero(); ///< the surface point with outward normal n
  int piece = 0;            ///< smooth piece of the surface: +1 / -1 the cap on the +/- axis side, 0 the band
  double piece_radius = 0;  ///< R_c on a cap, r_t on the band
  double hoop_radius = 0;   ///< band only: rho0 / |n_plane|, the extra radius along the hoop
  Vec3 hoop = Vec3::Zero(); ///< band only: the unit hoop direction
};

/// Support of `body` in the unit direction n.
Support support(const ConvexBody& body, const Vec3& n);
/// Hessian of h at the support's direction n (the radius-of-curvature tensor, on the plane
/// normal to n) times a vector v of that plane: piece_radius v + hoop_radius (u.v) u.
Vec3 radius_tensor_times(const Support& s, const Vec3& v);
/// h(n) alone (the cheap separation test of the force loop).
double support_value(const ConvexBody& body, const Vec3& n);

struct ContactGeometry {
  double overlap = 0;          ///< penetration depth (> 0 touching) [m]
  Vec3 normal = Vec3::UnitX(); ///< unit, from A to B
  Vec3 point = Vec3::Zero(); ///< contact point relative to A's centre: mid-way between the two support points
  Vec3 principal_radii = Vec3::Zero(); ///< relative principal radii R' <= R'' (with_curvature), third entry 0
  int iterations = 0;                  ///< Newton iterations taken
  bool converged = false;
};

/// Contact of A (centre at the origin) and B (centre at d). `guess` is a unit normal to start
/// from (the previous normal, or d normalised). When `stop_if_separated` and phi(guess) < 0 the
/// bodies are certainly apart and the function returns at once with overlap = phi(guess) < 0.
/// The relative principal radii are computed only when `with_curvature`.
ContactGeometry convex_contact(const ConvexBody& a, const ConvexBody& b, const Vec3& d, const Vec3& guess,
                               bool stop_if_separated, bool with_curvature = false);

/// Equivalent Hertz radius of an elliptic contact with relative principal radii R' <= R'':
/// the radius a sphere-on-sphere contact needs to give the same force-overlap law, from the
/// approximations of Johnson (1985, Contact Mechanics, eqs. 4.37-4.40 and Fig. 4.4).
double elliptic_hertz_radius(double radius_small, double radius_large);

/// How the Hertz radius of an ovoid contact is chosen (/work/shared/reference/ovoid.md).
enum class HertzRadius : std::uint8_t {
  halfwidth = 0,      ///< R* from the particles' half-widths a_i, as Kuhn's OVAL code does (the paper's)
  curvature = 1,      ///< elliptic Hertz from both surfaces' principal curvatures at the contact
  mean_semi_axis = 2, ///< R* from each particle's mean semi-axis a (2 + alpha) / 3, as DEMPLA 0.2.5 does
};

/// The mean of a body's three semi-axes, (a + a + alpha a) / 3: DEMPLA 0.2.5's Hertz radius of an ovoid.
double mean_semi_axis(const ConvexBody& body);

/// Geometry of the pair of world-frame bodies a and b with centre separation d (minimum image,
/// from a to b), for an ovoid on either side; `guess` is the normal to start from. The Hertz radius follows
/// `hertz_radius`. With `separating` (the pair's cached separating direction, zero for none), a pair
/// that this direction still proves apart is answered at once; the cache is then updated: the new separating
/// direction if the pair is apart, zero if it touches.
struct OvoidPairGeometry {
  model::ContactGeometry contact;
  double hertz_radius = 0;
};
OvoidPairGeometry ovoid_pair_geometry(const ConvexBody& a, const ConvexBody& b, const Vec3& d,
                                      const Vec3& guess, const PairProperties& properties,
                                      HertzRadius hertz_radius, bool stop_if_separated,
                                      Vec3* separating = nullptr);

} // namespace aniso::dem::model
