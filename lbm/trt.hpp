#pragma once
// Two-relaxation-time (TRT) collision for D3Q19 with Guo's forcing, one node
// at a time (Ginzburg, Verhaeghe & d'Humieres 2008; Guo, Zheng & Shi 2002).
// Populations are stored shifted by their rest-state weight, g_i = f_i - w_i,
// so that single precision keeps the small deviations that carry the flow.
//
// The symmetric part of each pair relaxes with omega+ (sets the viscosity
// nu = (1/omega+ - 1/2) / 3), the antisymmetric part with omega-, chosen so
// that the "magic" product Lambda = (1/omega+ - 1/2)(1/omega- - 1/2) is fixed.
// With Lambda = 3/16 halfway bounce-back puts a plane wall exactly half a
// link outside the last fluid node, and the steady Stokes solution (hence the
// permeability) does not depend on the viscosity.
//
// Stateless and MPI-free: a GPU port recompiles this header unchanged.

#include "lbm/d3q19.hpp"

#include <array>
#include <cstddef>

namespace aniso::lbm {

/// Relaxation rates of the TRT collision.
struct TrtRates {
  double omega_plus = 1.0;  ///< 1 / tau, symmetric moments
  double omega_minus = 1.0; ///< antisymmetric moments
  [[nodiscard]] double viscosity() const { return (1.0 / omega_plus - 0.5) / 3.0; }
};

/// Rates for relaxation time tau (> 1/2) and magic parameter Lambda (> 0).
inline TrtRates make_trt_rates(double tau, double magic) {
  const double lambda_plus = tau - 0.5;
  const double lambda_minus = magic / lambda_plus;
  return {1.0 / tau, 1.0 / (lambda_minus + 0.5)};
}

/// Moments of one node before collision: density deviation and momentum j = sum f c + F/2.
template <class Real> struct NodeMoments {
  Real delta_rho;
  std::array<Real, 3> momentum;
};

/// Collides the shifted populations g (pre-collision, in place -> post-collision) under the body force
/// density `force`. Returns the node's moments (velocity u = momentum / (1 + delta_rho)).
template <class Real>
inline NodeMoments<Real> collide_trt(std::array<Real, d3q19::q>& g, const std::array<Real, 3>& force,
                                     Real omega_plus, Real omega_minus) {
  using d3q19::c;
  Real delta_rho = 0;
  std::array<Real, 3> m{0, 0, 0};
  for (std::size_t i = 0; i < d3q19::q; ++i) {
    delta_rho += g[i];
    m[0] += g[i] * Real(c[i][0]);
    m[1] += g[i] * Real(c[i][1]);
    m[2] += g[i] * Real(c[i][2]);
  }
  const Real half = Real(0.5);
  const std::array<Real, 3> j{m[0] + half * force[0], m[1] + half * force[1], m[2] + half * force[2]};
  const Real rho = Real(1) + delta_rho;
  const Real inv_rho = Real(1) / rho;
  const std::array<Real, 3> u{j[0] * inv_rho, j[1] * inv_rho, j[2] * inv_rho};
  const Real uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const Real uf = u[0] * force[0] + u[1] * force[1] + u[2] * force[2];
  const Real source_plus = Real(1) - half * omega_plus;
  const Real source_minus = Real(1) - half * omega_minus;

  const Real w0 = Real(d3q19::w[0]);
  const Real eq0 = w0 * (delta_rho - Real(1.5) * rho * uu);
  g[0] += -omega_plus * (g[0] - eq0) + source_plus * w0 * Real(-3) * uf;
  for (std::size_t i = 1; i < d3q19::q; i += 2) {
    const Real wi = Real(d3q19::w[i]);
    const Real cu = Real(c[i][0]) * u[0] + Real(c[i][1]) * u[1] + Real(c[i][2]) * u[2];
    const Real cf = Real(c[i][0]) * force[0] + Real(c[i][1]) * force[1] + Real(c[i][2]) * force[2];
    const Real eq_plus = wi * (delta_rho + rho * (Real(4.5) * cu * cu - Real(1.5) * uu));
    const Real eq_minus = wi * rho * Real(3) * cu;
    const Real g_plus = half * (g[i] + g[i + 1]);
    const Real g_minus = half * (g[i] - g[i + 1]);
    // Guo's source split into its even part, w (9 (c.u)(c.F) - 3 u.F), and its odd part, 3 w c.F.
    const Real even =
        -omega_plus * (g_plus - eq_plus) + source_plus * wi * (Real(9) * cu * cf - Real(3) * uf);
    const Real odd = -omega_minus * (g_minus - eq_minus) + source_minus * wi * Real(3) * cf;
    g[i] += even + odd;
    g[i + 1] += even - odd;
  }
  return {delta_rho, j};
}

} // namespace aniso::lbm
