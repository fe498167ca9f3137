#pragma once
// One lattice Boltzmann step over a rank's fluid nodes in the in-place "AA"
// pattern (Bailey, Myre, Walsh, Lilja & Saar 2009; lbm/topology.hpp): the two
// kinds of step alternate on a single population array, and collide the 19
// values each node receives with TRT. With `Measure`, also records each node's
// density deviation and momentum for the convergence and divergence checks.
// Stateless and MPI-free.

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

/// Which of the two alternating steps.
enum class Parity { even, odd };

// The kernels below (and trt.hpp's collision) have internal linkage: lbm/step_kernels_*.cpp compile
// them for different instruction sets into one binary, and the inline linkage of a template would
// let the linker keep one of those copies for every caller (an AVX-512 copy on a CPU without it).
namespace {

template <class Real, int W, bool Measure>
inline void record_moments(const NodeBlock<Real, W>& block, std::size_t first, MomentsRecord* moments) {
  if constexpr (Measure) {
    for (int l = 0; l < W; ++l)
      moments[first + static_cast<std::size_t>(l)] = {
          double(block.delta_rho[l]),
          {double(block.momentum[0][l]), double(block.momentum[1][l]), double(block.momentum[2][l])}};
  }
}

/// Even step of W nodes: each node's own slots in, post-collision population i into its slot opp(i).
template <class Real, int W, bool Measure>
inline void collide_even_block(Real* f, std::size_t stride, std::size_t first,
                               const std::array<Real, 3>& force, Real omega_plus, Real omega_minus,
                               MomentsRecord* moments) {
  NodeBlock<Real, W> block;
  for (std::size_t i = 0; i < d3q19::q; ++i)
    for (int l = 0; l < W; ++l)
      block.g[i][l] = f[i * stride + first + static_cast<std::size_t>(l)];
  collide_trt<Real, W>(block, force, omega_plus, omega_minus);
  for (std::size_t i = 0; i < d3q19::q; ++i) {
    const auto slot = static_cast<std::size_t>(d3q19::opposite(static_cast<int>(i))) * stride + first;
    for (int l = 0; l < W; ++l)
      f[slot + static_cast<std::size_t>(l)] = block.g[i][l];
  }
  record_moments<Real, W, Measure>(block, first, moments);
}

/// Odd step of W nodes: population i from its table slot, post-collision population opp(i) back into it.
template <class Real, int W, bool Measure>
inline void collide_odd_block(Real* f, const std::uint32_t* __restrict slot, std::size_t table_nodes,
                              std::size_t first, const std::array<Real, 3>& force, Real omega_plus,
                              Real omega_minus, MomentsRecord* moments) {
  NodeBlock<Real, W> block;
  for (int l = 0; l < W; ++l)
    block.g[0][l] = f[first + static_cast<std::size_t>(l)];
  // The table is node-major (18 entries per node): one memory stream, where population-major rows
  // made 18 beside the 19 of the populations (measured 1.2x; blocking the populations the same way,
  // 8 nodes x 19 populations together, was 1.3x slower: each direction's gather became a strided stream).
  const std::uint32_t* table = slot + first * (d3q19::q - 1);
  if constexpr (W > 1) {
    // The first lane's slot of each population 4 blocks ahead: on a packing the 18 gathered streams
    // jump where the pore space does and the hardware prefetchers lose them (measured 1.2x on the
    // packing, 2-4 blocks ahead; 16 ahead, or also the last lane, gained less; docs/performance.md).
    // Near the end the look-ahead would read past the table (table_nodes nodes): none there.
    if (first + static_cast<std::size_t>(5 * W) <= table_nodes) {
      const std::uint32_t* ahead = table + 4 * W * (d3q19::q - 1);
      for (std::size_t i = 1; i < d3q19::q; ++i)
        __builtin_prefetch(f + ahead[i - 1], 1, 3);
    }
  }
  for (std::size_t i = 1; i < d3q19::q; ++i)
    for (int l = 0; l < W; ++l)
      block.g[i][l] = f[table[static_cast<std::size_t>(l) * (d3q19::q - 1) + i - 1]];
  collide_trt<Real, W>(block, force, omega_plus, omega_minus);
  for (int l = 0; l < W; ++l)
    f[first + static_cast<std::size_t>(l)] = block.g[0][l];
  for (std::size_t i = 1; i < d3q19::q; ++i) {
    const auto entry = static_cast<std::size_t>(d3q19::opposite(static_cast<int>(i)) - 1);
    for (int l = 0; l < W; ++l)
      f[table[static_cast<std::size_t>(l) * (d3q19::q - 1) + entry]] = block.g[i][l];
  }
  record_moments<Real, W, Measure>(block, first, moments);
}

/// One step over all `n_fluid` nodes of the population array `f`, whose populations lie `stride` apart
/// (odd steps need the ghost slots filled).
template <class Real, bool Measure>
void stream_collide(Parity parity, Real* f, const std::uint32_t* slot, std::int64_t n_fluid,
                    std::int64_t stride, const std::array<Real, 3>& force, Real omega_plus, Real omega_minus,
                    MomentsRecord* moments) {
  const auto n = static_cast<std::size_t>(n_fluid);
  const auto s = static_cast<std::size_t>(stride);
  std::size_t node = 0;
  if (parity == Parity::even) {
    for (; node + block_width <= n; node += block_width)
      collide_even_block<Real, block_width, Measure>(f, s, node, force, omega_plus, omega_minus, moments);
    for (; node < n; ++node)
      collide_even_block<Real, 1, Measure>(f, s, node, force, omega_plus, omega_minus, moments);
  } else {
    for (; node + block_width <= n; node += block_width)
      collide_odd_block<Real, block_width, Measure>(f, slot, n, node, force, omega_plus, omega_minus,
                                                    moments);
    for (; node < n; ++node)
      collide_odd_block<Real, 1, Measure>(f, slot, n, node, force, omega_plus, omega_minus, moments);
  }
}

} // namespace
} // namespace aniso::lbm
