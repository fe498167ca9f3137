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

/// Nodes collided together (SIMD lanes); the remainder goes through a block of one.
inline constexpr int block_width = 8;

template <class Real, int W, bool Measure>
inline void stream_collide_block(const Real* __restrict in, Real* __restrict out,
                                 const std::uint32_t* __restrict source, std::size_t n, std::size_t first,
                                 const std::array<Real, 3>& force, Real omega_plus, Real omega_minus,
                                 MomentsRecord* __restrict moments) {
  NodeBlock<Real, W> block;
  for (int l = 0; l < W; ++l)
    block.g[0][l] = in[first + static_cast<std::size_t>(l)];
  for (std::size_t i = 1; i < d3q19::q; ++i) {
    const std::uint32_t* row = source + (i - 1) * n + first;
    for (int l = 0; l < W; ++l)
      block.g[i][l] = in[row[l]];
  }
  collide_trt<Real, W>(block, force, omega_plus, omega_minus);
  for (std::size_t i = 0; i < d3q19::q; ++i)
    for (int l = 0; l < W; ++l)
      out[i * n + first + static_cast<std::size_t>(l)] = block.g[i][l];
  if constexpr (Measure) {
    for (int l = 0; l < W; ++l)
      moments[first + static_cast<std::size_t>(l)] = {
          double(block.delta_rho[l]),
          {double(block.momentum[0][l]), double(block.momentum[1][l]), double(block.momentum[2][l])}};
  }
}

template <class Real, bool Measure>
void stream_collide(const Real* __restrict in, Real* __restrict out, const std::uint32_t* __restrict source,
                    std::int64_t n_fluid, const std::array<Real, 3>& force, Real omega_plus, Real omega_minus,
                    MomentsRecord* __restrict moments) {
  const auto n = static_cast<std::size_t>(n_fluid);
  std::size_t node = 0;
  for (; node + block_width <= n; node += block_width)
    stream_collide_block<Real, block_width, Measure>(in, out, source, n, node, force, omega_plus, omega_minus,
                                                     moments);
  for (; node < n; ++node)
    stream_collide_block<Real, 1, Measure>(in, out, source, n, node, force, omega_plus, omega_minus, moments);
}

} // namespace aniso::lbm
