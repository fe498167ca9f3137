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

/// Populations of W nodes, population-major so that each statement of the collision is a loop over
/// lanes that the compiler turns into SIMD instructions.
// Internal linkage, as the kernels of stream_collide.hpp that use it (compiled per instruction set).
namespace {

template <class Real, int W> struct NodeBlock {
  Real g[d3q19::q][W]; ///< shifted populations, in: pre-collision, out: post-collision
  Real delta_rho[W];   ///< out: density deviation
  Real momentum[3][W]; ///< out: j = sum f c + F/2
};

/// Collides the W nodes of `block` in place under the body force density `force` (Guo's scheme:
/// u = j / rho with j = m + F/2, and source terms weighted by 1 - omega/2).
template <class Real, int W>
inline void collide_trt(NodeBlock<Real, W>& block, const std::array<Real, 3>& force, Real omega_plus,
                        Real omega_minus) {
  using d3q19::c;
  const Real half = Real(0.5);
  const Real source_plus = Real(1) - half * omega_plus;
  const Real source_minus = Real(1) - half * omega_minus;
  Real(&g)[d3q19::q][W] = block.g;
  // Every statement below is a loop over the W lanes (nodes): straight-line bodies that vectorize.
  Real rho[W], u0[W], u1[W], u2[W], uu[W], uf[W];
  // Moments in local accumulators: summed into the block's members the lanes did not vectorize
  // (the compiler kept them scalar, a third of the collision's time). Same order of sums per lane.
  Real delta_rho[W], m0[W], m1[W], m2[W];
  for (int l = 0; l < W; ++l) {
    delta_rho[l] = 0;
    m0[l] = half * force[0];
    m1[l] = half * force[1];
    m2[l] = half * force[2];
  }
  for (std::size_t i = 0; i < d3q19::q; ++i) {
    const Real cx = Real(c[i][0]), cy = Real(c[i][1]), cz = Real(c[i][2]);
    for (int l = 0; l < W; ++l) {
      const Real gi = g[i][l];
      delta_rho[l] += gi;
      m0[l] += gi * cx;
      m1[l] += gi * cy;
      m2[l] += gi * cz;
    }
  }
  for (int l = 0; l < W; ++l) {
    block.delta_rho[l] = delta_rho[l];
    block.momentum[0][l] = m0[l];
    block.momentum[1][l] = m1[l];
    block.momentum[2][l] = m2[l];
  }
  for (int l = 0; l < W; ++l) {
    rho[l] = Real(1) + block.delta_rho[l];
    const Real inv_rho = Real(1) / rho[l];
    u0[l] = block.momentum[0][l] * inv_rho;
    u1[l] = block.momentum[1][l] * inv_rho;
    u2[l] = block.momentum[2][l] * inv_rho;
    uu[l] = u0[l] * u0[l] + u1[l] * u1[l] + u2[l] * u2[l];
    uf[l] = u0[l] * force[0] + u1[l] * force[1] + u2[l] * force[2];
  }
  const Real w0 = Real(d3q19::w[0]);
  for (int l = 0; l < W; ++l) {
    const Real eq0 = w0 * (block.delta_rho[l] - Real(1.5) * rho[l] * uu[l]);
    g[0][l] += -omega_plus * (g[0][l] - eq0) + source_plus * w0 * Real(-3) * uf[l];
  }
  for (std::size_t i = 1; i < d3q19::q; i += 2) {
    const Real wi = Real(d3q19::w[i]);
    const Real cx = Real(c[i][0]), cy = Real(c[i][1]), cz = Real(c[i][2]);
    const Real cf = cx * force[0] + cy * force[1] + cz * force[2];
    for (int l = 0; l < W; ++l) {
      const Real cu = cx * u0[l] + cy * u1[l] + cz * u2[l];
      const Real eq_plus = wi * (block.delta_rho[l] + rho[l] * (Real(4.5) * cu * cu - Real(1.5) * uu[l]));
      const Real eq_minus = wi * rho[l] * Real(3) * cu;
      const Real g_plus = half * (g[i][l] + g[i + 1][l]);
      const Real g_minus = half * (g[i][l] - g[i + 1][l]);
      // Guo's source split into its even part, w (9 (c.u)(c.F) - 3 u.F), and its odd part, 3 w c.F.
      const Real even =
          -omega_plus * (g_plus - eq_plus) + source_plus * wi * (Real(9) * cu * cf - Real(3) * uf[l]);
      const Real odd = -omega_minus * (g_minus - eq_minus) + source_minus * wi * Real(3) * cf;
      g[i][l] += even + odd;
      g[i + 1][l] += even - odd;
    }
  }
}

} // namespace
} // namespace aniso::lbm
