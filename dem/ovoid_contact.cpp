#include "dem/ovoid_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace aniso::dem {

Support support(const ConvexBody& body, const Vec3& n) {
  Support s;
  const double axial = n.dot(body.axis);
  if (axial >= body.cos_splice || axial <= -body.cos_splice) {
    // A cap: the sphere of radius R_c about the point z_c on the axis, on the side of n.
    const double height = axial >= 0 ? body.cap_centre_height : -body.cap_centre_height;
    s.point = height * body.axis + body.cap_radius * n;
    s.value = height * axial + body.cap_radius;
    s.piece_radius = body.cap_radius;
    s.piece = axial >= 0 ? 1 : -1;
    return s;
  }
  // The band: the tube-centre circle (radius rho0, in the mid-plane) offset by r_t. The
  // circle's support point lies along the in-plane part of n; its Hessian rho0/|n_plane| u u^T
  // acts along the hoop direction u only.
  const Vec3 in_plane = n - axial * body.axis;
  const double width = in_plane.norm(); // > sin(beta) > 0 on the band
  const Vec3 radial = in_plane / width;
  s.point = body.tube_centre_radius * radial + body.tube_radius * n;
  s.value = body.tube_centre_radius * width + body.tube_radius;
  s.piece_radius = body.tube_radius;
  s.hoop_radius = body.tube_centre_radius / width;
  s.hoop = body.axis.cross(radial);
  return s;
}

Eigen::Matrix2d tangent_radii(const Support& s, const std::array<Vec3, 2>& t) {
  Eigen::Matrix2d radii = s.piece_radius * Eigen::Matrix2d::Identity();
  if (s.hoop_radius != 0) {
    const Eigen::Vector2d u(t[0].dot(s.hoop), t[1].dot(s.hoop));
    radii += s.hoop_radius * (u * u.transpose());
  }
  return radii;
}

double support_value(const ConvexBody& body, const Vec3& n) {
  const double axial = n.dot(body.axis);
  if (axial >= body.cos_splice || axial <= -body.cos_splice) {
    return (axial >= 0 ? body.cap_centre_height : -body.cap_centre_height) * axial + body.cap_radius;
  }
  return body.tube_centre_radius * (n - axial * body.axis).norm() + body.tube_radius;
}

namespace {

struct Evaluation {
  double gap_function = 0; ///< phi(n) = h_A(n) + h_B(-n) - d.n
  Support a;
  Support b; ///< support of B at -n
};

Evaluation evaluate(const ConvexBody& a, const ConvexBody& b, const Vec3& d, const Vec3& n) {
  Evaluation e;
  e.a = support(a, n);
  e.b = support(b, -n);
  e.gap_function = e.a.value + e.b.value - d.dot(n);
  return e;
}

// An orthonormal pair spanning the plane normal to the unit vector n.
std::array<Vec3, 2> tangent_basis(const Vec3& n) {
  const Vec3 helper =
      std::abs(n.x()) < 0.57 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57 ? Vec3::UnitY() : Vec3::UnitZ());
  const Vec3 t1 = n.cross(helper).normalized();
  return {t1, n.cross(t1)};
}

// Relative principal radii of curvature at the contact: the two surfaces' curvature tensors
// (inverses of their radius tensors on the tangent plane) add. The eigenvalues of the 2x2
// symmetric sum in closed form: mean +- hypot(half difference, off-diagonal); the smaller as
// det / larger, which keeps its digits when the two differ by orders of magnitude.
Vec3 relative_principal_radii(const Support& a, const Support& b, const std::array<Vec3, 2>& t) {
  const Eigen::Matrix2d curvature = tangent_radii(a, t).inverse() + tangent_radii(b, t).inverse();
  const double mean = 0.5 * (curvature(0, 0) + curvature(1, 1));
  const double largest = mean + std::hypot(0.5 * (curvature(0, 0) - curvature(1, 1)), curvature(0, 1));
  const double smallest = curvature.determinant() / largest;
  return {1.0 / largest, 1.0 / smallest, 0.0};
}

// Newton step -H^-1 g of a symmetric 2x2 H in closed form; false where H is not positive
// definite (the test of a Cholesky factorisation: both pivots positive).
bool newton_step(const Eigen::Matrix2d& h, const Eigen::Vector2d& g, Eigen::Vector2d& step) {
  const double det = h(0, 0) * h(1, 1) - h(0, 1) * h(0, 1);
  if (!(h(0, 0) > 0) || !(det > 0)) return false;
  step = Eigen::Vector2d(h(0, 1) * g[1] - h(1, 1) * g[0], h(0, 1) * g[0] - h(0, 0) * g[1]) / det;
  return true;
}

} // namespace

ContactGeometry convex_contact(const ConvexBody& a, const ConvexBody& b, const Vec3& d, const Vec3& guess,
                               bool stop_if_separated, bool with_curvature) {
  constexpr int max_iterations = 60;
  constexpr int max_halvings = 40;
  const double scale = a.bounding_radius + b.bounding_radius;
  ContactGeometry result;
  Vec3 n = guess.normalized();
  Evaluation current = evaluate(a, b, d, n);
  // phi(n) < 0 for any n proves the bodies apart (a separating direction).
  const auto separated = [&] {
    result.overlap = current.gap_function;
    result.normal = n;
    result.converged = true;
    return result;
  };
  if (stop_if_separated && current.gap_function < 0) return separated();
  std::array<Vec3, 2> t = tangent_basis(n);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    // Riemannian gradient and Hessian of phi on the unit sphere, in the tangent basis.
    const Vec3 residual = current.a.point - current.b.point - d;
    const Eigen::Vector2d gradient(t[0].dot(residual), t[1].dot(residual));
    if (gradient.norm() <= 1e-15 * scale) {
      result.converged = true;
      break;
    }
    const Eigen::Matrix2d hessian = tangent_radii(current.a, t) + tangent_radii(current.b, t) -
                                    current.gap_function * Eigen::Matrix2d::Identity();
    Eigen::Vector2d step;
    const bool newton = newton_step(hessian, gradient, step);
    if (newton) {
      // A Newton step below round-off of a unit vector: n is the minimiser to machine precision.
      // (Without this test the backtracking below spends its 40 halvings failing to lower phi
      // by round-off, at every contact and every time step.)
      if (step.norm() <= 1e-15) {
        result.converged = true;
        break;
      }
    } else {
      step = -gradient / scale; // not convex here (deep overlap): steepest descent
    }
    // Backtracking: accept the first step that lowers phi; a step that cannot lower it any
    // further means phi is flat to round-off, i.e. converged.
    bool accepted = false;
    for (int halving = 0; halving < max_halvings; ++halving) {
      const Vec3 trial_normal = (n + step[0] * t[0] + step[1] * t[1]).normalized();
      const Evaluation trial = evaluate(a, b, d, trial_normal);
      if (trial.gap_function <= current.gap_function) {
        const double moved = (trial_normal - n).norm();
        n = trial_normal;
        accepted = true;
        // A short full Newton step ends it. Within one smooth piece of each surface Newton
        // converges quadratically, so after a step of 1e-5 rad the normal is within about
        // 1e-10 rad of the minimiser; where a step crosses a splice circle the curvature jumps
        // and the error may be as large as the step, so there it must be below 1e-8 rad. Both
        // are far below the 1e-6 rad the contact law needs, and with the warm start from the
        // last normal most contacts take a single iteration per time step.
        const bool same_pieces = trial.a.piece == current.a.piece && trial.b.piece == current.b.piece;
        const double short_step = same_pieces ? 1e-5 : 1e-8;
        if (moved <= 1e-15 || (newton && halving == 0 && moved <= short_step)) result.converged = true;
        current = trial;
        break;
      }
      step *= 0.5;
    }
    // Once phi < 0 the pair is proven apart; where it lies below zero no longer matters.
    if (stop_if_separated && current.gap_function < 0) return separated();
    if (!accepted) {
      result.converged = true;
      break;
    }
    t = tangent_basis(n);
    if (result.converged) break;
  }
  result.overlap = current.gap_function;
  result.normal = n;
  result.point = 0.5 * (current.a.point + d + current.b.point);
  if (with_curvature) result.principal_radii = relative_principal_radii(current.a, current.b, t);
  return result;
}

namespace {

// Exact Hertz theory for an elliptic contact (Johnson 1985, section 4.2): with relative
// curvatures A <= B (gap A x^2 + B y^2) and e the eccentricity of the contact ellipse,
//   B/A = (E(e)/(1 - e^2) - K(e)) / (K(e) - E(e)),
// and the force-approach law equals a sphere's of radius
//   R_eq = pi^2 (K - E) / (4 K^3 e^2 A).
// The table holds R_eq A against log(B/A) (R_eq A = 1/2 for a circle).
struct EllipticTable {
  static constexpr int n_points = 1201;
  static constexpr double max_log_ratio = 12.0; // B/A up to e^12, far past any ovoid contact
  std::array<double, n_points> radius_times_a{};

  EllipticTable() {
    radius_times_a[0] = 0.5;
    for (int k = 1; k < n_points; ++k) {
      const double target = std::exp(max_log_ratio * k / (n_points - 1));
      const auto ratio = [](double e) {
        const double big_k = std::comp_ellint_1(e);
        const double big_e = std::comp_ellint_2(e);
        return (big_e / (1.0 - e * e) - big_k) / (big_k - big_e);
      };
      double low = 1e-6;
      double high = 1.0 - 1e-15;
      for (int bisection = 0; bisection < 200 && high - low > 1e-16; ++bisection) {
        const double middle = 0.5 * (low + high);
        (ratio(middle) < target ? low : high) = middle;
      }
      const double e = 0.5 * (low + high);
      const double big_k = std::comp_ellint_1(e);
      const double big_e = std::comp_ellint_2(e);
      radius_times_a[static_cast<std::size_t>(k)] =
          std::numbers::pi * std::numbers::pi * (big_k - big_e) / (4.0 * big_k * big_k * big_k * e * e);
    }
  }
};

} // namespace

double elliptic_hertz_radius(double radius_small, double radius_large) {
  static const EllipticTable table;              // immutable after construction
  const double curvature_a = 0.5 / radius_large; // the smaller relative curvature
  const double log_ratio = std::log(radius_large / radius_small);
  const double position = std::clamp(log_ratio, 0.0, EllipticTable::max_log_ratio) /
                          EllipticTable::max_log_ratio * (EllipticTable::n_points - 1);
  const auto lower = std::min(static_cast<std::size_t>(position), std::size_t{EllipticTable::n_points - 2});
  const double fraction = position - static_cast<double>(lower);
  const double value =
      (1.0 - fraction) * table.radius_times_a[lower] + fraction * table.radius_times_a[lower + 1];
  return value / curvature_a;
}

} // namespace aniso::dem
