// Kernels: the ball-intersection test behind N_3, N_4, and the Minkowski tensor W_3^{2,0}
// against the paper's closed forms (eq. (blocka) and the pierced block) and a sphere.
#include "common/shape/ovoid.hpp"
#include "fabric/ball_intersection.hpp"
#include "fabric/body_intersection.hpp"
#include "fabric/minkowski.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace aniso::fabric {
namespace {

constexpr double pi = std::numbers::pi;

double triangle_power(double side, double radius) {
  const std::array<Vec3, 3> c{Vec3(0, 0, 0), Vec3(side, 0, 0),
                              Vec3(0.5 * side, 0.5 * std::sqrt(3.0) * side, 0)};
  const std::array<double, 3> r{radius, radius, radius};
  return min_max_power(c, r);
}

TEST(BallIntersection, EquilateralTripleSharesAPointUpToItsCircumradius) {
  // Three balls of radius R on a triangle of side d meet iff the circumradius d / sqrt(3) <= R;
  // the minimiser is the circumcentre, so the value is d^2/3 - R^2 exactly.
  const double R = 0.5;
  for (double d : {0.80, 0.85, 0.866, 0.867, 0.95}) {
    EXPECT_NEAR(triangle_power(d, R), d * d / 3.0 - R * R, 1e-15) << "side " << d;
  }
  EXPECT_TRUE(triangle_power(std::sqrt(3.0) * R * (1 - 1e-9), R) <= 0);
  EXPECT_FALSE(triangle_power(std::sqrt(3.0) * R * (1 + 1e-9), R) <= 0);
}

TEST(BallIntersection, RegularTetrahedronOfBallsUpToItsCircumradius) {
  const double R = 0.5;
  for (double d : {0.80, 0.81, 0.82, 0.85}) {
    const double s = d / std::sqrt(2.0); // vertices of a cube with edge s
    const std::array<Vec3, 4> c{Vec3(0, 0, 0), Vec3(s, s, 0), Vec3(s, 0, s), Vec3(0, s, s)};
    const std::array<double, 4> r{R, R, R, R};
    const double circumradius = d * std::sqrt(6.0) / 4.0;
    EXPECT_NEAR(min_max_power(c, r), circumradius * circumradius - R * R, 1e-15) << "edge " << d;
    EXPECT_EQ(balls_share_point(c, r), circumradius <= R) << "edge " << d;
  }
}

TEST(BallIntersection, UnequalAndDegenerateCases) {
  // A small ball inside a big one: the minimiser is the small ball's centre.
  const std::array<Vec3, 2> nested{Vec3(0, 0, 0), Vec3(0.1, 0, 0)};
  EXPECT_NEAR(min_max_power(nested, std::array<double, 2>{1.0, 0.2}), -0.04, 1e-15);
  // Two disjoint balls: gap power at the radical point.
  EXPECT_FALSE(
      balls_share_point(std::array<Vec3, 2>{Vec3(0, 0, 0), Vec3(2.1, 0, 0)}, std::array<double, 2>{1, 1}));
  // Three collinear balls, the middle one reaching both outer ones but the outer ones not each other.
  const std::array<Vec3, 3> line{Vec3(0, 0, 0), Vec3(0.9, 0, 0), Vec3(1.8, 0, 0)};
  EXPECT_FALSE(balls_share_point(line, std::array<double, 3>{0.5, 0.5, 0.5}));
  EXPECT_TRUE(balls_share_point(line, std::array<double, 3>{0.95, 0.5, 0.95}));
}

TEST(BodyIntersection, OvoidsAgreeWithSpheresAndFindOverlapsOfFlatParticles) {
  // Spheres through the ovoid path (aspect ratio 1 would take the ball path, so use 0.999999):
  // the projection test gives the same answers as the exact ball test on the triangle.
  for (double d : {0.84, 0.86, 0.87, 0.90}) {
    const std::array<Vec3, 3> c{Vec3(0, 0, 0), Vec3(d, 0, 0), Vec3(0.5 * d, 0.5 * std::sqrt(3.0) * d, 0)};
    std::vector<PlacedBody> bodies;
    for (const Vec3& x : c)
      bodies.push_back({1.0, 0.999999, OvoidShape::default_splice_angle, x, Quat::Identity()});
    EXPECT_EQ(bodies_share_point(bodies), d <= std::sqrt(3.0) * 0.5 - 1e-4) << "side " << d;
  }
  // Three flat ovoids (alpha 0.5) lying in the plane z = 0 meet at the centre of their triangle
  // when their mid-plane radius reaches it, but not when they stand on edge facing away.
  const double d = 0.8;
  const std::array<Vec3, 3> c{Vec3(0, 0, 0), Vec3(d, 0, 0), Vec3(0.5 * d, 0.5 * std::sqrt(3.0) * d, 0)};
  std::vector<PlacedBody> flat, standing;
  for (const Vec3& x : c) {
    flat.push_back({1.0, 0.5, OvoidShape::default_splice_angle, x, Quat::Identity()});
    const Vec3 outward = (x - Vec3(0.4, 0.4 / std::sqrt(3.0), 0)).normalized();
    standing.push_back(
        {1.0, 0.5, OvoidShape::default_splice_angle, x, Quat::FromTwoVectors(Vec3::UnitZ(), outward)});
  }
  EXPECT_TRUE(bodies_share_point(flat));
  EXPECT_FALSE(bodies_share_point(standing));
}

// An ovoid of shape (D = 1, alpha) and random orientation placed so that its surface point with
// outward world normal n lies at P + offset n: P is inside at depth offset (offset > 0, below the
// smallest radius of curvature) or outside at distance -offset from the tangent plane there.
PlacedBody body_touching_at(const Vec3& P, const Vec3& n, double offset, double alpha, const Quat& q) {
  const OvoidShape shape(1.0, alpha);
  const Mat3 r = q.toRotationMatrix();
  const Vec3 support = shape.support(r.transpose() * n).point;
  return {1.0, alpha, OvoidShape::default_splice_angle, P + offset * n - r * support, q};
}

Quat random_orientation(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  return Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized();
}

TEST(BodyIntersection, ThinCommonRegionsOfOvoidsAreFoundAndNearMissesRejected) {
  // Bodies whose outward normals at P sum to zero (three at 120 degrees in a plane, or four
  // tetrahedral) share a region of depth `offset` about P when it is inside them all, a thin
  // needle for the planar triple, where cyclic projections need thousands of sweeps; and none
  // when P is outside them all (their tangent half-spaces already exclude each other).
  // Both answers are certain by construction, for every alpha and orientation.
  std::mt19937_64 rng(2015);
  int cases = 0;
  for (double alpha : {0.5, 0.625, 0.8}) {
    for (double depth : {1e-3, 1e-5, 1e-7}) {
      for (int trial = 0; trial < 8; ++trial) {
        const Mat3 frame = random_orientation(rng).toRotationMatrix();
        const Vec3 P(0.3, -0.2, 0.1);
        std::vector<Vec3> normals;
        for (int k = 0; k < 3; ++k)
          normals.push_back(frame * Vec3(std::cos(2 * pi * k / 3), std::sin(2 * pi * k / 3), 0));
        std::vector<Vec3> tetrahedral;
        for (const Vec3& v : {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)})
          tetrahedral.push_back(frame * v.normalized());
        for (const auto* set : {&normals, &tetrahedral}) {
          std::vector<PlacedBody> sharing, apart;
          for (const Vec3& n : *set) {
            const Quat q = random_orientation(rng);
            sharing.push_back(body_touching_at(P, n, depth, alpha, q));
            apart.push_back(body_touching_at(P, n, -depth, alpha, q));
          }
          EXPECT_TRUE(bodies_share_point(sharing))
              << "alpha " << alpha << " depth " << depth << " trial " << trial << " bodies " << set->size();
          EXPECT_FALSE(bodies_share_point(apart))
              << "alpha " << alpha << " depth " << depth << " trial " << trial << " bodies " << set->size();
          cases += 2;
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * 3 * 8 * 4);
}

TEST(Minkowski, BoxCornersGiveEquationBlocka) {
  const Vec3 L(3.0, 2.0, 1.5);
  const Mat3 expected = (4.0 * pi / 3.0) * Vec3(1.5 * 1.5, 1.0, 0.75 * 0.75).asDiagonal().toDenseMatrix();
  EXPECT_LT((box_w320(L) - expected).norm(), 1e-14 * expected.norm());
}

TEST(Minkowski, PiercedBlockGivesThePapersClosedForm) {
  // Block 2a1 x 2a2 x 2a3 pierced along x3 by a square tunnel 2b x 2b: eight outer corners with
  // deficit pi/2 and eight inner corners (+-b, +-b, +-a3) with deficit -pi/2.
  const double a1 = 1.5, a2 = 1.0, a3 = 0.7, b = 0.4;
  std::vector<Corner> corners;
  for (int k = 0; k < 8; ++k) {
    const Vec3 s((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
    corners.push_back({Vec3(a1, a2, a3).cwiseProduct(s), pi / 2});
    corners.push_back({Vec3(b, b, a3).cwiseProduct(s), -pi / 2});
  }
  const Mat3 expected =
      (4.0 * pi / 3.0) * Vec3(a1 * a1 - b * b, a2 * a2 - b * b, 0.0).asDiagonal().toDenseMatrix();
  EXPECT_LT((corners_w320(corners) - expected).norm(), 1e-14 * expected.norm());
}

TEST(Minkowski, SphereLocalTensorAndParallelAxisAgainstQuadrature) {
  // (1/3) integral of K x (x) x dA over a sphere of radius R centred at t, by Gauss-Legendre in
  // cos(theta) and the trapezoidal rule in phi (exact for these polynomials), against
  // particle_w320 of the closed-form local tensor (4 pi / 9) R^2 I (eq. (W203all)).
  const double R = 0.3;
  const Vec3 t(0.2, -0.5, 1.1);
  const std::array<double, 4> nodes{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                    0.8611363115940526};
  const std::array<double, 4> weights{0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                      0.3478548451374538};
  Mat3 integral = Mat3::Zero();
  const int n_phi = 16;
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    const double ct = nodes[a], st = std::sqrt(1 - ct * ct);
    for (int k = 0; k < n_phi; ++k) {
      const double phi = 2 * pi * k / n_phi;
      const Vec3 x = t + R * Vec3(st * std::cos(phi), st * std::sin(phi), ct);
      // dA = R^2 d(cos theta) d phi, K = 1 / R^2
      integral += weights[a] * (2 * pi / n_phi) * x * x.transpose();
    }
  }
  integral /= 3.0;
  const Mat3 local = (4.0 * pi / 9.0) * R * R * Mat3::Identity();
  EXPECT_LT((particle_w320(local, t) - integral).norm(), 1e-13 * integral.norm());
  // The ovoid library's Gaussian-weighted tensor of a sphere is the same local tensor (times 3).
  const OvoidSurfaceTensors s = OvoidShape(2 * R, 1.0).surface_tensors();
  EXPECT_LT((s.gaussian_position / 3.0 - local).norm(), 1e-13 * local.norm());
}

} // namespace
} // namespace aniso::fabric
