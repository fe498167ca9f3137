#include "fabric/body_intersection.hpp"

#include "common/shape/ovoid.hpp"
#include "fabric/ball_intersection.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace aniso::fabric {
namespace {

// Iteration and step-size limits of the prox-linear minimisation below; the limit is reached
// only when the deepest common point lies within about 1e-12 D of the surfaces (touching).
constexpr int max_iterations = 400;
constexpr int max_step_halvings = 60;

struct Frame {
  OvoidShape shape;
  Vec3 centre;
  Mat3 to_world;
};

bool all_spheres(std::span<const PlacedBody> bodies) {
  return std::all_of(bodies.begin(), bodies.end(), [](const PlacedBody& b) { return b.aspect_ratio == 1.0; });
}

// Signed distances d_k(x) and outward unit normals n_k (gradients) of the bodies at x.
struct Linearisation {
  std::vector<double> distance;
  std::vector<Vec3> normal;
  [[nodiscard]] double max_distance() const { return *std::max_element(distance.begin(), distance.end()); }
};

Linearisation linearise(const std::vector<Frame>& frames, const Vec3& x) {
  Linearisation l;
  for (const Frame& f : frames) {
    const OvoidSurfacePoint nearest = f.shape.closest_point(f.to_world.transpose() * (x - f.centre));
    l.distance.push_back(nearest.signed_distance);
    l.normal.push_back(f.to_world * nearest.normal);
  }
  return l;
}

// Dual of the prox-linear step min_y max_k [d_k + n_k.(y - x)] + (rho/2)|y - x|^2:
// maximise sum lambda_k d_k - |sum lambda_k n_k|^2 / (2 rho) over the simplex. With at most
// four bodies every support set is tried; the best KKT point of any support is the optimum.
std::vector<double> step_weights(const Linearisation& l, double rho) {
  const std::size_t m = l.distance.size();
  std::vector<double> best(m, 0.0);
  double best_value = -std::numeric_limits<double>::infinity();
  for (unsigned mask = 1; mask < (1u << m); ++mask) {
    std::vector<std::size_t> support;
    for (std::size_t k = 0; k < m; ++k)
      if (mask & (1u << k)) support.push_back(k);
    const auto s = static_cast<Eigen::Index>(support.size());
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(s + 1, s + 1);
    Eigen::VectorXd rhs(s + 1);
    for (Eigen::Index a = 0; a < s; ++a) {
      for (Eigen::Index b = 0; b < s; ++b)
        kkt(a, b) = l.normal[support[a]].dot(l.normal[support[b]]) / rho;
      kkt(a, s) = kkt(s, a) = 1.0;
      rhs[a] = l.distance[support[a]];
    }
    rhs[s] = 1.0;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(kkt);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd solution = lu.solve(rhs);
    if ((solution.head(s).array() < 0.0).any()) continue;
    std::vector<double> lambda(m, 0.0);
    Vec3 g = Vec3::Zero();
    double value = 0;
    for (Eigen::Index a = 0; a < s; ++a) {
      lambda[support[a]] = solution[a];
      g += solution[a] * l.normal[support[a]];
      value += solution[a] * l.distance[support[a]];
    }
    value -= g.squaredNorm() / (2.0 * rho);
    if (value > best_value) {
      best_value = value;
      best = lambda;
    }
  }
  return best;
}

} // namespace

bool bodies_share_point(std::span<const PlacedBody> bodies) {
  // Each body lies in its ball of radius D/2 (alpha <= 1): for spheres that is the exact test,
  // for ovoids a rigorous rejection before the iterative one.
  std::array<Vec3, 4> centres;
  std::array<double, 4> radii{};
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    centres[k] = bodies[k].centre;
    radii[k] = 0.5 * bodies[k].diameter;
  }
  const bool balls_meet = balls_share_point(std::span<const Vec3>(centres.data(), bodies.size()),
                                            std::span<const double>(radii.data(), bodies.size()));
  if (!balls_meet || all_spheres(bodies)) return balls_meet;

  // Ovoids: minimise f(x) = max_k d_k(x), the largest signed distance to the bodies. Each d_k is
  // convex (a maximum of the affine functions u.x - h_k(u)), so f is convex and the bodies share
  // a point iff min f <= 0. Prox-linear steps (a minimax SQP with a backtracked proximal weight
  // rho) converge to the minimum where cyclic projections crawl along thin intersections.
  // Both answers carry a certificate: "true" a point inside every body; "false" a lower bound
  // of f over a ball holding every common point, from the convexity d_k(y) >= d_k(x) + n_k.(y-x).
  std::vector<Frame> frames;
  double smallest = bodies[0].diameter;
  double smallest_radius_of_curvature = std::numeric_limits<double>::infinity();
  std::size_t smallest_body = 0;
  Vec3 x = Vec3::Zero();
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const PlacedBody& b = bodies[k];
    frames.push_back({OvoidShape(b.diameter, b.aspect_ratio, b.splice_angle), b.centre,
                      b.orientation.normalized().toRotationMatrix()});
    if (b.diameter < bodies[smallest_body].diameter) smallest_body = k;
    smallest = std::min(smallest, b.diameter);
    smallest_radius_of_curvature = std::min(
        {smallest_radius_of_curvature, frames.back().shape.cap_radius(), frames.back().shape.tube_radius()});
    x += b.centre / static_cast<double>(bodies.size());
  }
  const Vec3 ball_centre = bodies[smallest_body].centre;
  const double ball_radius = 0.5 * bodies[smallest_body].diameter;
  const double rho_floor = 1.0 / smallest_radius_of_curvature;
  const double resolution = 1e-13 * smallest;
  const auto inside_all = [&frames](const Vec3& point) {
    return std::all_of(frames.begin(), frames.end(), [&](const Frame& f) {
      return f.shape.inside(f.to_world.transpose() * (point - f.centre));
    });
  };

  double rho = rho_floor;
  Linearisation here = linearise(frames, x);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    if (here.max_distance() <= 0.0 && inside_all(x)) return true;
    bool accepted = false;
    for (int halving = 0; halving < max_step_halvings && !accepted; ++halving) {
      const std::vector<double> lambda = step_weights(here, rho);
      Vec3 g = Vec3::Zero();
      double weighted_distance = 0;
      for (std::size_t k = 0; k < lambda.size(); ++k) {
        g += lambda[k] * here.normal[k];
        weighted_distance += lambda[k] * (here.distance[k] + here.normal[k].dot(ball_centre - x));
      }
      // Certificate of disjointness: min over the ball of the lambda-weighted lower model.
      if (weighted_distance - ball_radius * g.norm() > resolution) return false;
      const Vec3 step = -g / rho;
      if (step.norm() < resolution) return inside_all(x);
      double model = -std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < lambda.size(); ++k)
        model = std::max(model, here.distance[k] + here.normal[k].dot(step));
      const Vec3 y = x + step;
      Linearisation there = linearise(frames, y);
      if (there.max_distance() <= model + 0.5 * rho * step.squaredNorm() + resolution) {
        x = y;
        here = std::move(there);
        rho = std::max(rho_floor, 0.5 * rho);
        accepted = true;
      } else {
        rho *= 4.0;
      }
    }
    if (!accepted) break;
  }
  return inside_all(x);
}

} // namespace aniso::fabric
