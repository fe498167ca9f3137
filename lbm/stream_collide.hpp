#pragma once
// One lattice Boltzmann step over a rank's fluid nodes: pull each node's 19
// populations through the streaming table (boundaries folded in, see
// topology.hpp), collide them with TRT and store them in the other array.
// With `Measure`, also records each node's density deviation and momentum
// for the convergence and divergence checks. Stateless and MPI-free.

#include "lbm/d3q19.hpp"
#include "lbm/trt.hpp"

#include <cstdint>

namespace aniso::lbm {

/// Moments of one node kept in double for exact reductions.
struct MomentsRecord {
  double delta_rho;
  double momentum[3];
};

template <class Real, bool Measure>
void stream_collide(const Real* __restrict in, Real* __restrict out, const std::uint32_t* __restrict source,
                    std::int64_t n_fluid, const std::array<Real, 3>& force, Real omega_plus, Real omega_minus,
                    MomentsRecord* __restrict moments) {
  const auto n = static_cast<std::size_t>(n_fluid);
  for (std::size_t node = 0; node < n; ++node) {
    std::array<Real, d3q19::q> g;
    g[0] = in[node];
    for (std::size_t i = 1; i < d3q19::q; ++i)
      g[i] = in[source[(i - 1) * n + node]];
    const NodeMoments<Real> m = collide_trt<Real>(g, force, omega_plus, omega_minus);
    for (std::size_t i = 0; i < d3q19::q; ++i)
      out[i * n + node] = g[i];
    if constexpr (Measure) {
      moments[node] = {double(m.delta_rho),
                       {double(m.momentum[0]), double(m.momentum[1]), double(m.momentum[2])}};
    }
  }
}

} // namespace aniso::lbm
