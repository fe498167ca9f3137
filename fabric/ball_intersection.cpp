#include "fabric/ball_intersection.hpp"

#include "common/error.hpp"

#include <array>
#include <cstddef>
#include <limits>

namespace aniso::fabric {
namespace {

// f_k(x) = |x - c_k|^2 - r_k^2 is strictly convex, so max_k f_k has one minimiser x*. Its KKT
// conditions: x* = sum of lambda_k c_k over the active balls (lambda >= 0, sum 1), the active
// powers equal, the others no larger. Every subset of balls is tried as the active set; the one
// that meets the conditions gives the minimum.
struct Candidate {
  bool valid = false;
  double value = 0;
};

Candidate try_active_set(std::span<const Vec3> c, std::span<const double> r, unsigned mask) {
  std::array<std::size_t, 4> active{};
  std::size_t s = 0;
  for (std::size_t k = 0; k < c.size(); ++k)
    if ((mask >> k) & 1U) active[s++] = k;
  const Vec3& c0 = c[active[0]];
  Vec3 x = c0;
  double lambda0 = 1.0;
  if (s > 1) {
    // x = c0 + sum_m mu_m d_m with d_m = c_m - c0; equal powers give (d_m . d_n) mu_n = b_m.
    const auto m = static_cast<Eigen::Index>(s - 1);
    Eigen::MatrixXd gram(m, m);
    Eigen::VectorXd rhs(m);
    for (Eigen::Index a = 0; a < m; ++a) {
      const Vec3 da = c[active[static_cast<std::size_t>(a) + 1]] - c0;
      for (Eigen::Index b = 0; b < m; ++b)
        gram(a, b) = da.dot(c[active[static_cast<std::size_t>(b) + 1]] - c0);
      const double ra = r[active[static_cast<std::size_t>(a) + 1]];
      rhs(a) = 0.5 * (da.squaredNorm() - ra * ra + r[active[0]] * r[active[0]]);
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(gram);
    if (!lu.isInvertible()) return {}; // centres affinely dependent: another subset covers this case
    const Eigen::VectorXd mu = lu.solve(rhs);
    for (Eigen::Index a = 0; a < m; ++a) {
      if (mu(a) < 0) return {};
      x += mu(a) * (c[active[static_cast<std::size_t>(a) + 1]] - c0);
      lambda0 -= mu(a);
    }
    if (lambda0 < 0) return {};
  }
  const double value = (x - c0).squaredNorm() - r[active[0]] * r[active[0]];
  // Inactive balls must not have a larger power; a relative slack absorbs round-off.
  const double slack = 1e-12 * (r[active[0]] * r[active[0]] + std::abs(value));
  for (std::size_t k = 0; k < c.size(); ++k) {
    if ((mask >> k) & 1U) continue;
    if ((x - c[k]).squaredNorm() - r[k] * r[k] > value + slack) return {};
  }
  return {true, value};
}

} // namespace

double min_max_power(std::span<const Vec3> centres, std::span<const double> radii) {
  check_invariant(centres.size() == radii.size() && !centres.empty() && centres.size() <= 4,
                  "min_max_power takes 1 to 4 balls");
  // Work relative to the first centre so that products keep their precision.
  std::array<Vec3, 4> local;
  for (std::size_t k = 0; k < centres.size(); ++k)
    local[k] = centres[k] - centres[0];
  const std::span<const Vec3> c(local.data(), centres.size());
  double best = std::numeric_limits<double>::infinity();
  const unsigned n_subsets = 1U << centres.size();
  for (unsigned mask = 1; mask < n_subsets; ++mask) {
    const Candidate candidate = try_active_set(c, radii, mask);
    if (candidate.valid && candidate.value < best) best = candidate.value;
  }
  check_invariant(best < std::numeric_limits<double>::infinity(), "min_max_power found no KKT point");
  return best;
}

} // namespace aniso::fabric
