#include "dem/model/ovoid_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace aniso::dem::model {

namespace {

// The support of one body, inlined into the narrow phase: it runs twice per Newton iteration.
[[gnu::always_inline]] inline Support support_of(const ConvexBody& body, const Vec3& n) {
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
  const double inverse_width = 1.0 / width;
  const Vec3 radial = in_plane * inverse_width;
  s.point = body.tube_centre_radius * radial + body.tube_radius * n;
  s.value = body.tube_centre_radius * width + body.tube_radius;
  s.piece_radius = body.tube_radius;
  s.hoop_radius = body.tube_centre_radius * inverse_width;
  s.hoop = body.axis.cross(radial);
  return s;
}

} // namespace

Support support(const ConvexBody& body, const Vec3& n) {
  return support_of(body, n);
}

Vec3 radius_tensor_times(const Support& s, const Vec3& v) {
  return s.piece_radius * v + (s.hoop_radius * s.hoop.dot(v)) * s.hoop;
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

[[gnu::always_inline]] inline Evaluation evaluate(const ConvexBody& a, const ConvexBody& b, const Vec3& d,
                                                  const Vec3& n) {
  Evaluation e;
  e.a = support_of(a, n);
  e.b = support_of(b, -n);
  e.gap_function = e.a.value + e.b.value - d.dot(n);
  return e;
}

// The two surfaces' radius tensors on the tangent plane at n are r_A I + alpha u u^T and
// r_B I + beta v v^T (u, v the hoop directions, tangent to the sphere at n; alpha = 0 on a cap,
// whose hoop is zero). Sums and inverses of such tensors need no basis of the plane: only the
// scalars below and gamma = u.v.
struct PlaneTensors {
  double alpha = 0, beta = 0, gamma = 0;
};

PlaneTensors plane_tensors(const Support& a, const Support& b) {
  return {a.hoop_radius, b.hoop_radius, a.hoop.dot(b.hoop)};
}

// Newton step x = -H^-1 g on the tangent plane for the Riemannian Hessian
// H = c I + alpha u u^T + beta v v^T, c = r_A + r_B - phi, by Woodbury's identity:
// (c I + U D U^T)^-1 g = (g - U y) / c with (c I + D U^T U) y = D U^T g, U = [u v],
// D = diag(alpha, beta). alpha, beta >= 0, so H is positive definite whenever c > 0; false
// otherwise (overlaps beyond the smallest radii of curvature: steepest descent instead).
bool newton_step(const Support& a, const Support& b, double gap_function, const Vec3& gradient, Vec3& step) {
  const double c = a.piece_radius + b.piece_radius - gap_function;
  if (!(c > 0)) return false;
  const PlaneTensors p = plane_tensors(a, b);
  const double k00 = c + p.alpha, k01 = p.alpha * p.gamma, k10 = p.beta * p.gamma, k11 = c + p.beta;
  const double r0 = p.alpha * a.hoop.dot(gradient), r1 = p.beta * b.hoop.dot(gradient);
  const double determinant = k00 * k11 - k01 * k10;
  const double scale = 1.0 / (c * determinant); // one division for both 1/(c det) and 1/c
  const double y0 = (r0 * k11 - k01 * r1) * scale, y1 = (k00 * r1 - k10 * r0) * scale;
  step = y0 * a.hoop + y1 * b.hoop - gradient * (determinant * scale);
  return true;
}

// Relative principal radii of curvature at the contact: the two surfaces' curvature tensors,
// inverses of their radius tensors, add. With (r I + alpha u u^T)^-1 = (I - alpha/(r + alpha)
// u u^T)/r the sum is k I - p u u^T - q v v^T; the eigenvalues of p u u^T + q v v^T have sum
// p + q and product p q (1 - gamma^2). The smaller curvature as det / larger keeps its digits
// when the two differ by orders of magnitude.
Vec3 relative_principal_radii(const Support& a, const Support& b) {
  const PlaneTensors t = plane_tensors(a, b);
  const double k = 1.0 / a.piece_radius + 1.0 / b.piece_radius;
  const double p = t.alpha / (a.piece_radius * (a.piece_radius + t.alpha));
  const double q = t.beta / (b.piece_radius * (b.piece_radius + t.beta));
  const double sum = p + q, product = p * q * std::max(0.0, 1.0 - t.gamma * t.gamma);
  const double half_spread = std::sqrt(std::max(0.0, 0.25 * sum * sum - product));
  const double largest = k - (0.5 * sum - half_spread);
  const double determinant = k * k - k * sum + product;
  return {1.0 / largest, largest / determinant, 0.0};
}

} // namespace

ContactGeometry convex_contact(const ConvexBody& a, const ConvexBody& b, const Vec3& d, const Vec3& guess,
                               bool stop_if_separated, bool with_curvature) {
  constexpr int max_iterations = 60;
  constexpr int max_halvings = 40;
  const double scale = a.bounding_radius + b.bounding_radius;
  ContactGeometry result;
  // The previous normal of a touching pair is unit to round-off already.
  const double guess_length_squared = guess.squaredNorm();
  Vec3 n = std::abs(guess_length_squared - 1.0) <= 1e-15 ? guess : guess / std::sqrt(guess_length_squared);
  Evaluation current = evaluate(a, b, d, n);
  // phi(n) < 0 for any n proves the bodies apart (a separating direction).
  const auto separated = [&] {
    result.overlap = current.gap_function;
    result.normal = n;
    result.converged = true;
    return result;
  };
  if (stop_if_separated && current.gap_function < 0) return separated();
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    // Riemannian gradient of phi on the unit sphere: the residual's part normal to n.
    const Vec3 residual = current.a.point - current.b.point - d;
    const Vec3 gradient = residual - residual.dot(n) * n;
    if (gradient.squaredNorm() <= 1e-30 * scale * scale) {
      result.converged = true;
      break;
    }
    Vec3 step;
    const bool newton = newton_step(current.a, current.b, current.gap_function, gradient, step);
    if (newton) {
      // A Newton step below round-off of a unit vector: n is the minimiser to machine precision.
      // (Without this test the backtracking below spends its 40 halvings failing to lower phi
      // by round-off, at every contact and every time step.)
      if (step.squaredNorm() <= 1e-30) {
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
      const Vec3 trial_normal = (n + step).normalized();
      const Evaluation trial = evaluate(a, b, d, trial_normal);
      const double moved_squared = (trial_normal - n).squaredNorm();
      // A short full Newton step ends it. Within one smooth piece of each surface Newton
      // converges quadratically, so after a step of 1e-5 rad the normal is within about
      // 1e-10 rad of the minimiser; where a step crosses a splice circle the curvature jumps
      // and the error may be as large as the step, so there it must be below 1e-8 rad. Both
      // are far below the 1e-6 rad the contact law needs, and with the warm start from the
      // last normal most contacts take a single iteration per time step.
      const bool same_pieces = trial.a.piece == current.a.piece && trial.b.piece == current.b.piece;
      const double short_step_squared = same_pieces ? 1e-10 : 1e-16;
      const bool short_newton = newton && halving == 0 && moved_squared <= short_step_squared;
      // Such a step is taken without the descent test: H is positive definite, so it lowers phi
      // by g.H^-1.g / 2, which for a static contact (a step of 1e-12 rad) lies below phi's
      // round-off. Tested, half of those steps "failed" on round-off and the 40 halvings ran
      // in vain: 17 evaluations per touching contact per step instead of 2, at rest.
      if (short_newton || trial.gap_function <= current.gap_function) {
        n = trial_normal;
        accepted = true;
        if (moved_squared <= 1e-30 || short_newton) result.converged = true;
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
    if (result.converged) break;
  }
  result.overlap = current.gap_function;
  result.normal = n;
  result.point = 0.5 * (current.a.point + d + current.b.point);
  if (with_curvature) result.principal_radii = relative_principal_radii(current.a, current.b);
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

double mean_semi_axis(const ConvexBody& body) {
  // The axial half-height alpha a is where the cap reaches the axis: z_c + R_c.
  return (2 * body.bounding_radius + body.cap_centre_height + body.cap_radius) / 3;
}

OvoidPairGeometry ovoid_pair_geometry(const ConvexBody& a, const ConvexBody& b, const Vec3& d,
                                      const Vec3& guess, const PairProperties& properties,
                                      HertzRadius hertz_radius, bool stop_if_separated, Vec3* separating) {
  OvoidPairGeometry result;
  if (separating != nullptr && !separating->isZero(0.0)) {
    // phi(n) < 0 proves the pair apart, whatever n: the answer is the one Newton would give.
    const double gap_function =
        support_value(a, *separating) + support_value(b, -*separating) - d.dot(*separating);
    if (gap_function < 0) {
      result.contact.overlap = gap_function;
      result.contact.normal = *separating;
      result.contact.converged = true;
      result.hertz_radius = properties.effective_radius;
      return result;
    }
  }
  result.contact = convex_contact(a, b, d, guess, stop_if_separated, hertz_radius == HertzRadius::curvature);
  if (separating != nullptr)
    *separating = result.contact.overlap > 0 ? Vec3::Zero() : Vec3(result.contact.normal);
  result.hertz_radius = properties.effective_radius;
  if (result.contact.overlap > 0 && hertz_radius == HertzRadius::curvature)
    result.hertz_radius =
        elliptic_hertz_radius(result.contact.principal_radii[0], result.contact.principal_radii[1]);
  if (result.contact.overlap > 0 && hertz_radius == HertzRadius::mean_semi_axis) {
    const double radius_a = mean_semi_axis(a), radius_b = mean_semi_axis(b);
    result.hertz_radius = radius_a * radius_b / (radius_a + radius_b);
  }
  return result;
}

} // namespace aniso::dem::model
