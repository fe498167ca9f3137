// The ovoid narrow phase (dem/model/ovoid_contact.hpp) against references that share none of its
// code: the shape's own support function, closest point and normals (common/shape/ovoid.hpp),
// and a brute-force search over directions (a dense spherical grid, then golden-section
// refinement) for the minimum of the support gap. 10,000 random pairs of the paper's shapes
// with overlaps up to 1% of D, and the degenerate configurations named in the issue.
#include "common/rng.hpp"
#include "common/shape/ovoid.hpp"
#include "dem/model/contact_law.hpp"
#include "dem/model/ovoid_contact.hpp"
#include "dem/model/particle_shape.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace {

using aniso::Mat3;
using aniso::OvoidShape;
using aniso::Quat;
using aniso::RandomStream;
using aniso::Vec3;
using aniso::dem::model::ContactGeometry;
using aniso::dem::model::ConvexBody;
using aniso::dem::model::ShapeTable;
constexpr double pi = std::numbers::pi;
constexpr double beta = pi / 4.0;

// One particle for both codes: the DEM body and the shape library's ovoid with its rotation.
struct Particle {
  double radius;
  double aspect_ratio;
  Quat orientation;
  ConvexBody body;
  OvoidShape shape;
};

Particle make_particle(const ShapeTable& table, double radius, double aspect_ratio, const Quat& orientation) {
  return {radius, aspect_ratio, orientation, table.body(radius, aspect_ratio, orientation),
          OvoidShape(2.0 * radius, aspect_ratio, beta)};
}

// Support value of the rotated shape from common/shape (the reference).
double reference_support(const Particle& p, const Vec3& n) {
  return p.shape.support(p.orientation.conjugate() * n).value;
}

// phi(n) = h_A(n) + h_B(-n) - d.n with the reference supports.
double reference_gap_function(const Particle& a, const Particle& b, const Vec3& d, const Vec3& n) {
  return reference_support(a, n) + reference_support(b, -n) - d.dot(n);
}

Vec3 direction(double polar, double azimuth) {
  return {std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)};
}

// The paper's four shapes (paper section 2).
constexpr std::array<double, 4> aspect_ratios{1.0, 0.8, 0.625, 0.5};
ShapeTable paper_shapes() {
  ShapeTable table(beta);
  for (double alpha : aspect_ratios)
    table.add(alpha);
  return table;
}

Quat random_rotation(RandomStream& stream) {
  const double w = stream.normal(), x = stream.normal(), y = stream.normal(), z = stream.normal();
  return Quat(w, x, y, z).normalized();
}

// Brute force: the smallest phi over a Fibonacci grid of directions, then golden-section line
// searches along the principal directions of a finite-difference Hessian (so that the narrow
// valleys of flat particles are searched along their axes), with shrinking brackets.
struct BruteForce {
  Vec3 normal;
  double gap_function;
};

BruteForce brute_force_contact(const Particle& a, const Particle& b, const Vec3& d) {
  constexpr int n_grid = 4000;
  BruteForce best{Vec3::UnitX(), INFINITY};
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int k = 0; k < n_grid; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n_grid;
    const Vec3 n = direction(std::acos(z), pi * (3.0 - std::sqrt(5.0)) * k);
    const double value = reference_gap_function(a, b, d, n);
    if (value < best.gap_function) best = {n, value};
  }
  double bracket = 0.1; // radians, larger than the grid spacing (about 0.056)
  for (int round = 0; round < 16; ++round) {
    const Vec3 helper = std::abs(best.normal.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 t1 = best.normal.cross(helper).normalized();
    const Vec3 t2 = best.normal.cross(t1);
    const Vec3 origin = best.normal;
    const auto at = [&](double s1, double s2) { return (origin + s1 * t1 + s2 * t2).normalized(); };
    const auto phi = [&](double s1, double s2) { return reference_gap_function(a, b, d, at(s1, s2)); };
    const double h = std::max(0.05 * bracket, 1e-5);
    Eigen::Matrix2d hessian;
    hessian(0, 0) = phi(h, 0) - 2 * phi(0, 0) + phi(-h, 0);
    hessian(1, 1) = phi(0, h) - 2 * phi(0, 0) + phi(0, -h);
    hessian(0, 1) = hessian(1, 0) = 0.25 * (phi(h, h) - phi(h, -h) - phi(-h, h) + phi(-h, -h));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(hessian);
    for (int pass = 0; pass < 2; ++pass) {
      for (int axis = 0; axis < 2; ++axis) {
        const Eigen::Vector2d e = axes.eigenvectors().col(axis);
        const Vec3 start = best.normal;
        const Vec3 t = (e[0] * t1 + e[1] * t2).normalized();
        const auto along = [&](double s) { return (start + s * t).normalized(); };
        const auto f = [&](double s) { return reference_gap_function(a, b, d, along(s)); };
        double low = -bracket, high = bracket;
        double x1 = high - golden * (high - low), x2 = low + golden * (high - low);
        double f1 = f(x1), f2 = f(x2);
        while (high - low > 1e-12) {
          if (f1 < f2) {
            high = x2, x2 = x1, f2 = f1, x1 = high - golden * (high - low), f1 = f(x1);
          } else {
            low = x1, x1 = x2, f1 = f2, x2 = low + golden * (high - low), f2 = f(x2);
          }
        }
        const double s = 0.5 * (low + high);
        if (f(s) <= best.gap_function) best = {along(s), f(s)};
      }
    }
    bracket = std::max(bracket * 0.3, 1e-6);
  }
  return best;
}

double angle_between(const Vec3& u, const Vec3& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

TEST(OvoidContact, RandomPairsAgreeWithBruteForceAndTheShapeLibrary) {
  const ShapeTable table = paper_shapes();
  RandomStream stream(2015, 4);
  constexpr int n_pairs = 10000;
  int n_touching = 0, max_iterations = 0, n_reported = 0;
  double worst_angle = 0, worst_overlap = 0, worst_surface = 0, worst_normal = 0;
  for (int pair = 0; pair < n_pairs; ++pair) {
    const double alpha_a = aspect_ratios[static_cast<std::size_t>(pair % 4)];
    const double alpha_b = aspect_ratios[static_cast<std::size_t>((pair / 4) % 4)];
    const double radius_a = stream.uniform(0.5, 1.0), radius_b = stream.uniform(0.5, 1.0);
    const Particle a = make_particle(table, radius_a, alpha_a, random_rotation(stream));
    const Particle b = make_particle(table, radius_b, alpha_b, random_rotation(stream));
    // Put B along a random direction u so that the gap along u is -target: the overlap is then
    // at most target (the true normal may do better), with target up to 1% of the smaller D.
    const Vec3 u = direction(std::acos(stream.uniform(-1.0, 1.0)), stream.uniform(0.0, 2.0 * pi));
    const double diameter = 2.0 * std::min(radius_a, radius_b);
    const double target = stream.uniform(1e-6, 1e-2) * diameter;
    Vec3 d = (reference_support(a, u) + reference_support(b, -u) - target) * u;
    // Slide B along the contact normal until the overlap is the target.
    for (int adjust = 0; adjust < 4; ++adjust) {
      const ContactGeometry trial = aniso::dem::model::convex_contact(a.body, b.body, d, d, false);
      d += (trial.overlap - target) * trial.normal;
    }

    const ContactGeometry g = aniso::dem::model::convex_contact(a.body, b.body, d, d, false);
    ASSERT_TRUE(g.converged) << "pair " << pair;
    max_iterations = std::max(max_iterations, g.iterations);
    const BruteForce reference = brute_force_contact(a, b, d);
    worst_angle = std::max(worst_angle, angle_between(g.normal, reference.normal));
    if (angle_between(g.normal, reference.normal) > 1e-6 && n_reported++ < 5) {
      std::printf("pair %d: alpha %g %g, overlap %.6g vs brute %.6g, angle %.3g, iterations %d\n", pair,
                  alpha_a, alpha_b, g.overlap, reference.gap_function,
                  angle_between(g.normal, reference.normal), g.iterations);
    }
    worst_overlap = std::max(worst_overlap, std::abs(g.overlap - reference.gap_function) / diameter);
    if (g.overlap > 0) ++n_touching;
    // The contact point sits between the two surface points where the normals are +n and -n.
    for (const auto& [particle, centre, sign] :
         {std::tuple<const Particle&, Vec3, double>{a, Vec3::Zero(), 1.0}, {b, d, -1.0}}) {
      const aniso::OvoidSupport s =
          particle.shape.support(particle.orientation.conjugate() * (sign * g.normal));
      const Vec3 surface_point = centre + particle.orientation * s.point;
      const aniso::OvoidSurfacePoint check =
          particle.shape.closest_point(particle.orientation.conjugate() * (surface_point - centre));
      worst_surface = std::max(worst_surface, std::abs(check.signed_distance) / diameter);
      worst_normal =
          std::max(worst_normal, angle_between(particle.orientation * check.normal, sign * g.normal));
      // Mid-way: the point is half the overlap inside each surface along the normal.
      EXPECT_NEAR((g.point - surface_point).dot(sign * g.normal), -0.5 * g.overlap, 1e-12 * diameter);
    }
  }
  std::printf(
      "[ measured ] %d pairs (%d touching): worst normal angle %.3g rad, worst overlap error %.3g D, "
      "Newton iterations at most %d; support points on the surface within %.3g D, normals within %.3g rad\n",
      n_pairs, n_touching, worst_angle, worst_overlap, max_iterations, worst_surface, worst_normal);
  EXPECT_GT(n_touching, n_pairs * 9 / 10);
  EXPECT_LT(worst_angle, 1e-6);
  EXPECT_LT(worst_overlap, 1e-9);
  EXPECT_LT(worst_surface, 1e-12);
  EXPECT_LT(worst_normal, 1e-9);
}

// A contact at rest: B moved by 1e-12 D since the last step, the solve warm-started from the
// last normal. The Newton step is then below phi's round-off, and it must end the solve at
// once (one iteration, two evaluations) instead of failing the descent test on round-off and
// halving in vain, which at rest cost 17 evaluations per contact and step (docs/performance.md).
TEST(OvoidContact, AContactAtRestTakesOneIterationFromItsLastNormal) {
  const ShapeTable table = paper_shapes();
  RandomStream stream(2026, 12);
  constexpr int n_pairs = 2000;
  int n_one_iteration = 0;
  double worst_angle = 0, worst_overlap = 0;
  for (int pair = 0; pair < n_pairs; ++pair) {
    const double alpha_a = aspect_ratios[static_cast<std::size_t>(1 + pair % 3)];
    const double alpha_b = aspect_ratios[static_cast<std::size_t>(1 + (pair / 3) % 3)];
    const Particle a = make_particle(table, stream.uniform(0.5, 1.0), alpha_a, random_rotation(stream));
    const Particle b = make_particle(table, stream.uniform(0.5, 1.0), alpha_b, random_rotation(stream));
    const Vec3 u = direction(std::acos(stream.uniform(-1.0, 1.0)), stream.uniform(0.0, 2.0 * pi));
    const double diameter = 2.0 * std::min(a.radius, b.radius);
    Vec3 d = (reference_support(a, u) + reference_support(b, -u) - 1e-4 * diameter) * u;
    for (int adjust = 0; adjust < 4; ++adjust) { // slide B along the normal to an overlap of 1e-4 D
      const ContactGeometry trial = aniso::dem::model::convex_contact(a.body, b.body, d, d, false);
      d += (trial.overlap - 1e-4 * diameter) * trial.normal;
    }
    const ContactGeometry last = aniso::dem::model::convex_contact(a.body, b.body, d, d, false);
    ASSERT_GT(last.overlap, 0) << "pair " << pair;
    const Vec3 moved =
        d + 1e-12 * diameter * direction(stream.uniform(0.0, pi), stream.uniform(0.0, 2.0 * pi));
    const ContactGeometry now = aniso::dem::model::convex_contact(a.body, b.body, moved, last.normal, true);
    const ContactGeometry cold = aniso::dem::model::convex_contact(a.body, b.body, moved, moved, false);
    ASSERT_TRUE(now.converged) << "pair " << pair;
    if (now.iterations == 1) ++n_one_iteration;
    worst_angle = std::max(worst_angle, angle_between(now.normal, cold.normal));
    worst_overlap = std::max(worst_overlap, std::abs(now.overlap - cold.overlap) / diameter);
  }
  std::printf("[ measured ] %d contacts at rest: %d solved in one iteration; against a cold start the normal "
              "within %.3g rad, the overlap within %.3g D\n",
              n_pairs, n_one_iteration, worst_angle, worst_overlap);
  EXPECT_EQ(n_one_iteration, n_pairs);
  EXPECT_LT(worst_angle, 1e-9);
  EXPECT_LT(worst_overlap, 1e-14);
}

// Two particles, B at d with the given orientations; the exact overlap and normal known.
void expect_contact(double alpha_a, const Quat& orientation_a, double alpha_b, const Quat& orientation_b,
                    const Vec3& d, double overlap, const Vec3& normal, const Vec3& guess,
                    double angle_tolerance = 1e-9) {
  ShapeTable table(beta);
  table.add(alpha_a);
  table.add(alpha_b);
  const ConvexBody a = table.body(1.0, alpha_a, orientation_a), b = table.body(1.0, alpha_b, orientation_b);
  const ContactGeometry g = aniso::dem::model::convex_contact(a, b, d, guess, false);
  EXPECT_TRUE(g.converged);
  EXPECT_NEAR(g.overlap, overlap, 1e-13);
  EXPECT_LT(angle_between(g.normal, normal), angle_tolerance) << g.normal.transpose();
}

constexpr double overlap = 1e-3; // of a = 1

TEST(OvoidContact, ParallelAxesSideBySide) {
  // Bands at the equator, axes parallel: overlap 2a - |d|, normal along d, from any start.
  for (const Vec3& guess : {Vec3(1, 0, 0), Vec3(1, 0.3, 0.4), Vec3(0.2, 1, 0)}) {
    expect_contact(0.5, Quat::Identity(), 0.5, Quat::Identity(), Vec3(2.0 - overlap, 0, 0), overlap,
                   Vec3::UnitX(), guess);
  }
  // Axes parallel up to 1e-9 rad: the same answer, no loss of robustness.
  const Quat tilted(Eigen::AngleAxisd(1e-9, Vec3::UnitY()));
  expect_contact(0.5, Quat::Identity(), 0.5, tilted, Vec3(2.0 - overlap, 0, 0), overlap, Vec3::UnitX(),
                 Vec3::UnitX(), 1e-8);
}

TEST(OvoidContact, RelativePrincipalRadiiAtTheEquator) {
  // Two equal ovoids side by side touch band to band: the curvatures 1/r_t (meridian) and 1/a
  // (hoop) of both add, so R' = r_t / 2 and R'' = a / 2.
  ShapeTable table(beta);
  table.add(0.5);
  const ConvexBody a = table.body(1.0, 0.5, Quat::Identity());
  const ContactGeometry g =
      aniso::dem::model::convex_contact(a, a, Vec3(2.0 - overlap, 0, 0), Vec3::UnitX(), false, true);
  EXPECT_NEAR(g.principal_radii[0], 0.5 * a.tube_radius, 1e-12);
  EXPECT_NEAR(g.principal_radii[1], 0.5, 1e-12);
  // Spheres of radii 1 and 2: R' = R'' = 2/3.
  table.add(1.0);
  const ContactGeometry s = aniso::dem::model::convex_contact(
      table.body(1.0, 1.0, Quat::Identity()), table.body(2.0, 1.0, Quat::Identity()),
      Vec3(0, 3.0 - overlap, 0), Vec3::UnitY(), false, true);
  EXPECT_NEAR(s.principal_radii[0], 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.principal_radii[1], 2.0 / 3.0, 1e-12);
}

// DEMPLA 0.2.5's Hertz radius of an ovoid is the mean of its semi-axes, a (2 + alpha) / 3, whatever
// the splice angle and the orientation; a pair's is R_i R_j / (R_i + R_j) of those.
TEST(OvoidContact, MeanSemiAxisHertzRadius) {
  ShapeTable table(beta);
  for (double alpha : {1.0, 0.8, 0.5})
    table.add(alpha);
  const Quat turned(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  for (double alpha : {1.0, 0.8, 0.5})
    EXPECT_NEAR(aniso::dem::model::mean_semi_axis(table.body(1.5, alpha, turned)), 1.5 * (2 + alpha) / 3,
                1e-12);
  aniso::dem::model::PairProperties properties;
  properties.effective_radius = 1.5 * 1.0 / 2.5; // the half-widths' R*
  const ConvexBody a = table.body(1.5, 0.5, Quat::Identity()), b = table.body(1.0, 0.8, Quat::Identity());
  const Vec3 d(1.5 + 1.0 - overlap, 0, 0); // band against band
  const double ra = 1.5 * 2.5 / 3, rb = 2.8 / 3;
  EXPECT_NEAR(aniso::dem::model::ovoid_pair_geometry(a, b, d, Vec3::UnitX(), properties,
                                                     aniso::dem::model::HertzRadius::mean_semi_axis, false)
                  .hertz_radius,
              ra * rb / (ra + rb), 1e-12);
  EXPECT_EQ(aniso::dem::model::ovoid_pair_geometry(a, b, d, Vec3::UnitX(), properties,
                                                   aniso::dem::model::HertzRadius::halfwidth, false)
                .hertz_radius,
            properties.effective_radius);
}

// The Hessian of the support function (the radius-of-curvature tensor) that Newton's step and
// the Hertz radius use is the derivative of the support point: a central difference of the
// point along a tangent direction, away from the splice circles where it jumps.
TEST(OvoidSupport, RadiusTensorIsTheDerivativeOfTheSupportPoint) {
  ShapeTable table(beta);
  for (double alpha : {1.0, 0.8, 0.5})
    table.add(alpha);
  RandomStream stream(7, 3);
  const double step = 1e-6;
  int n_checked = 0, n_band = 0;
  double worst = 0;
  for (int sample = 0; sample < 3000; ++sample) {
    const double alpha = std::array<double, 3>{1.0, 0.8, 0.5}[static_cast<std::size_t>(sample % 3)];
    const ConvexBody body = table.body(stream.uniform(0.5, 1.0), alpha, random_rotation(stream));
    const Vec3 n = direction(std::acos(stream.uniform(-1.0, 1.0)), stream.uniform(0.0, 2.0 * pi));
    if (std::abs(std::abs(n.dot(body.axis)) - body.cos_splice) < 1e-3) continue;
    const Vec3 helper =
        n.cross(direction(std::acos(stream.uniform(-1.0, 1.0)), stream.uniform(0.0, 2.0 * pi)));
    const Vec3 v = helper.normalized();
    const aniso::dem::model::Support s = aniso::dem::model::support(body, n);
    const Vec3 difference = (aniso::dem::model::support(body, (n + step * v).normalized()).point -
                             aniso::dem::model::support(body, (n - step * v).normalized()).point) /
                            (2.0 * step);
    const Vec3 tensor_times = aniso::dem::model::radius_tensor_times(s, v);
    worst = std::max(worst, (difference - tensor_times).norm() / body.bounding_radius);
    ++n_checked;
    n_band += s.piece == 0 ? 1 : 0;
  }
  std::printf("[ measured ] %d directions (%d on the band): worst |dp/dn v - R v| %.3g a\n", n_checked,
              n_band, worst);
  EXPECT_GT(n_band, 500);
  EXPECT_LT(worst, 1e-8);
}

// The relative principal radii, computed without a basis of the tangent plane (Woodbury-type
// closed forms of the two radius tensors), against the explicit 2x2 matrices in an orthonormal
// basis, inverted, summed and diagonalised by Eigen, at the contact of random pairs.
TEST(OvoidContact, RelativePrincipalRadiiAgreeWithAnExplicitBasis) {
  const ShapeTable table = paper_shapes();
  RandomStream stream(11, 5);
  double worst = 0;
  for (int pair = 0; pair < 2000; ++pair) {
    const ConvexBody a = table.body(
        stream.uniform(0.5, 1.0), aspect_ratios[static_cast<std::size_t>(pair % 4)], random_rotation(stream));
    const ConvexBody b =
        table.body(stream.uniform(0.5, 1.0), aspect_ratios[static_cast<std::size_t>((pair / 4) % 4)],
                   random_rotation(stream));
    const Vec3 u = direction(std::acos(stream.uniform(-1.0, 1.0)), stream.uniform(0.0, 2.0 * pi));
    const Vec3 d =
        (aniso::dem::model::support_value(a, u) + aniso::dem::model::support_value(b, -u) - 1e-3) * u;
    const ContactGeometry g = aniso::dem::model::convex_contact(a, b, d, d, false, true);
    const Vec3 t0 = g.normal.unitOrthogonal(), t1 = g.normal.cross(t0);
    const auto plane_matrix = [&](const aniso::dem::model::Support& s) {
      Eigen::Matrix2d m;
      for (int c = 0; c < 2; ++c) {
        const Vec3 column = aniso::dem::model::radius_tensor_times(s, c == 0 ? t0 : t1);
        m(0, c) = column.dot(t0);
        m(1, c) = column.dot(t1);
      }
      return m;
    };
    const Eigen::Matrix2d curvature = plane_matrix(aniso::dem::model::support(a, g.normal)).inverse() +
                                      plane_matrix(aniso::dem::model::support(b, -g.normal)).inverse();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(curvature);
    const double explicit_small = 1.0 / solver.eigenvalues()[1],
                 explicit_large = 1.0 / solver.eigenvalues()[0];
    worst = std::max({worst, std::abs(g.principal_radii[0] / explicit_small - 1.0),
                      std::abs(g.principal_radii[1] / explicit_large - 1.0)});
  }
  std::printf("[ measured ] 2000 contacts: relative principal radii within %.3g of the explicit basis\n",
              worst);
  EXPECT_LT(worst, 1e-10);
}

TEST(OvoidContact, CoaxialCapAgainstCap) {
  for (double alpha : {0.8, 0.625, 0.5}) {
    expect_contact(alpha, Quat::Identity(), alpha, Quat::Identity(), Vec3(0, 0, 2.0 * alpha - overlap),
                   overlap, Vec3::UnitZ(), Vec3(0.1, -0.2, 1.0));
  }
}

TEST(OvoidContact, PerpendicularAxes) {
  // A's equator (band) against B's pole (cap): B's axis along x.
  const Quat axis_x(Eigen::AngleAxisd(pi / 2, Vec3::UnitY()));
  expect_contact(0.5, Quat::Identity(), 0.5, axis_x, Vec3(1.0 + 0.5 - overlap, 0, 0), overlap, Vec3::UnitX(),
                 Vec3(1.0, 0.2, 0.1));
}

TEST(OvoidContact, TorusAgainstTorusAtTheEquatorWithCrossedAxes) {
  const Quat axis_y(Eigen::AngleAxisd(pi / 2, Vec3::UnitX()));
  expect_contact(0.625, Quat::Identity(), 0.625, axis_y, Vec3(2.0 - overlap, 0, 0), overlap, Vec3::UnitX(),
                 Vec3(1.0, 0.3, -0.3));
}

TEST(OvoidContact, SeparatedPairsReturnAtOnceWhenAsked) {
  ShapeTable table(beta);
  table.add(0.5);
  const ConvexBody a = table.body(1.0, 0.5, Quat::Identity());
  const ContactGeometry g = aniso::dem::model::convex_contact(a, a, Vec3(2.1, 0, 0), Vec3::UnitX(), true);
  EXPECT_EQ(g.iterations, 0);
  EXPECT_NEAR(g.overlap, -0.1, 1e-15);
}

TEST(OvoidContact, AspectRatioOneIsTheSphere) {
  ShapeTable table(beta);
  table.add(1.0);
  RandomStream stream(7, 1);
  for (int k = 0; k < 100; ++k) {
    const double ra = stream.uniform(0.5, 1.0), rb = stream.uniform(0.5, 1.0);
    const Vec3 u = direction(std::acos(stream.uniform(-1.0, 1.0)), stream.uniform(0.0, 2.0 * pi));
    const Vec3 d = (ra + rb - 1e-3) * u;
    const ContactGeometry g =
        aniso::dem::model::convex_contact(table.body(ra, 1.0, random_rotation(stream)),
                                          table.body(rb, 1.0, random_rotation(stream)), d, d, false);
    EXPECT_NEAR(g.overlap, ra + rb - d.norm(), 1e-15);
    EXPECT_LT(angle_between(g.normal, u), 1e-15);
    EXPECT_NEAR((g.point - (ra - 0.5e-3) * u).norm(), 0.0, 1e-15);
  }
}

TEST(OvoidContact, NearlySphericalOvoidGivesTheSphereForce) {
  // alpha -> 1: the ovoid's contact and Hertz force converge to the sphere's.
  const aniso::dem::model::ContactMaterial material;
  for (double alpha : {1.0 - 1e-6, 1.0 - 1e-9}) {
    ShapeTable table(beta);
    table.add(alpha);
    table.add(1.0);
    const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    const Vec3 d = Vec3(0.3, -0.5, 0.8).normalized() * (2.0 - 1e-3);
    const ContactGeometry ovoid =
        aniso::dem::model::convex_contact(table.body(1.0, alpha, q), table.body(1.0, 1.0, q), d, d, false);
    const double sphere_overlap = 2.0 - d.norm();
    EXPECT_NEAR(ovoid.overlap, sphere_overlap, 3.0 * (1.0 - alpha));
    const double e_star = aniso::dem::model::contact_modulus(material);
    EXPECT_NEAR(aniso::dem::model::hertz_normal_force(e_star, 0.5, ovoid.overlap) /
                    aniso::dem::model::hertz_normal_force(e_star, 0.5, sphere_overlap),
                1.0, 1e4 * (1.0 - alpha));
  }
}

TEST(EllipticHertz, CircleLimitAndExactTheory) {
  EXPECT_NEAR(aniso::dem::model::elliptic_hertz_radius(0.3, 0.3), 0.3, 1e-14);
  // Independent evaluation of Johnson's exact relations at ratios between table nodes.
  for (const double ratio : {1.7, 5.3, 41.0}) {
    double low = 1e-6, high = 1.0 - 1e-15;
    const auto curvature_ratio = [](double e) {
      const double k = std::comp_ellint_1(e), big_e = std::comp_ellint_2(e);
      return (big_e / (1.0 - e * e) - k) / (k - big_e);
    };
    for (int i = 0; i < 200; ++i) {
      const double m = 0.5 * (low + high);
      (curvature_ratio(m) < ratio ? low : high) = m;
    }
    const double e = 0.5 * (low + high);
    const double k = std::comp_ellint_1(e), big_e = std::comp_ellint_2(e);
    const double radius_large = 2.0, curvature_a = 0.5 / radius_large;
    const double expected = pi * pi * (k - big_e) / (4.0 * k * k * k * e * e) / curvature_a;
    EXPECT_NEAR(aniso::dem::model::elliptic_hertz_radius(radius_large / ratio, radius_large) / expected, 1.0,
                1e-5)
        << "ratio " << ratio;
    // Between the geometric mean of the radii (small ellipticity) and the larger radius.
    EXPECT_GT(expected, std::sqrt(radius_large * radius_large / ratio) * 0.99);
  }
}

} // namespace
