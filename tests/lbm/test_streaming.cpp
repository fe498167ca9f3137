// The in-place (AA) streaming of lbm/stream_collide.hpp: its slot table is a permutation of the
// population array under every kind of face, and alternating even and odd steps give the same
// moments, to the last bit, as a plain two-array pull scheme written here from the definition.
#include "common/log.hpp"
#include "lbm/geometry.hpp"
#include "lbm/partition.hpp"
#include "lbm/stream_collide.hpp"
#include "lbm/topology.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace aniso::lbm {
namespace {

const mpi::Comm world = mpi::Comm::world();

struct Lattice {
  h5::VoxelImage image;
  Topology topology;
};

Lattice make_lattice(const Faces& faces) {
  Lattice lattice;
  lattice.image = random_spheres({13, 11, 9}, 2.5, 0.45, 3);
  const Index3 shape{13, 11, 9};
  lattice.topology = build_topology(lattice.image.phase, make_partition(shape, {1, 1, 1}, 0), faces, world);
  return lattice;
}

TEST(Streaming, SlotTableIsAPermutationForEveryKindOfFace) {
  const std::vector<Faces> cases{all_periodic, walled_except(0, FaceKind::no_slip),
                                 walled_except(1, FaceKind::free_slip),
                                 Faces{FaceKind::periodic, FaceKind::no_slip, FaceKind::free_slip}};
  for (const Faces& faces : cases) {
    const Lattice lattice = make_lattice(faces);
    const Topology& t = lattice.topology;
    ASSERT_GT(t.n_fluid, 100);
    ASSERT_EQ(t.n_ghost, 0); // one rank: every slot is local
    // Each slot is read (and written) by exactly one (node, population) of an odd step: the rest
    // population in its own slot, the 18 moving ones through the table.
    std::vector<int> uses(t.array_size(), 0);
    for (std::int64_t node = 0; node < t.n_fluid; ++node)
      ++uses[static_cast<std::size_t>(node)];
    for (std::uint32_t slot : t.slot)
      ++uses[slot];
    // The padding after each population's n_fluid values (Topology::stride) is never touched.
    const auto stride = static_cast<std::size_t>(t.stride);
    for (std::size_t k = 0; k < uses.size(); ++k) {
      const bool padding = k < t.ghost_base() && k % stride >= static_cast<std::size_t>(t.n_fluid);
      ASSERT_EQ(uses[k], padding ? 0 : 1) << "slot " << k << " of faces " << to_string(faces[0]) << ", "
                                          << to_string(faces[1]) << ", " << to_string(faces[2]);
    }
  }
}

TEST(Streaming, PopulationArraysStartApartWithinAPage) {
  for (const std::int64_t n : {1, 24, 25, 511, 512, 536, 750727, 2097152}) {
    const std::int64_t stride = padded_stride(n);
    EXPECT_GE(stride, n);
    EXPECT_LT(stride - n, 512);
    // 19 arrays of doubles start in 19 different 64-byte lines of a 4 KiB page, floats in 19 different
    // 32-byte halves.
    std::vector<bool> line(64, false), half_line(128, false);
    for (std::int64_t i = 0; i < 19; ++i) {
      const auto d = static_cast<std::size_t>(i * stride * 8 % 4096 / 64);
      const auto f = static_cast<std::size_t>(i * stride * 4 % 4096 / 32);
      EXPECT_FALSE(line[d]) << "n = " << n << ", population " << i;
      EXPECT_FALSE(half_line[f]) << "n = " << n << ", population " << i;
      line[d] = half_line[f] = true;
    }
  }
}

/// One step of the textbook pull scheme: population i of fluid node x comes from x - c_i (periodic), or
/// bounces back from this node's opposite population when x - c_i is solid.
void pull_step(const h5::VoxelImage& image, const std::vector<std::int64_t>& node_of_cell,
               const std::vector<double>& in, std::vector<double>& out, std::vector<MomentsRecord>& moments,
               const std::array<double, 3>& force, double omega_plus, double omega_minus) {
  const auto nx = static_cast<int>(image.shape[0]), ny = static_cast<int>(image.shape[1]),
             nz = static_cast<int>(image.shape[2]);
  const auto n = static_cast<std::size_t>(moments.size());
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const std::int64_t node = node_of_cell[static_cast<std::size_t>(x + nx * (y + ny * z))];
        if (node < 0) continue;
        NodeBlock<double, 1> block;
        for (int i = 0; i < d3q19::q; ++i) {
          const auto& c = d3q19::c[static_cast<std::size_t>(i)];
          const int ux = (x - c[0] + nx) % nx, uy = (y - c[1] + ny) % ny, uz = (z - c[2] + nz) % nz;
          const std::int64_t up = node_of_cell[static_cast<std::size_t>(ux + nx * (uy + ny * uz))];
          const std::size_t from = up < 0
                                       ? static_cast<std::size_t>(d3q19::opposite(i)) * n + std::size_t(node)
                                       : static_cast<std::size_t>(i) * n + std::size_t(up);
          block.g[i][0] = in[from];
        }
        collide_trt<double, 1>(block, force, omega_plus, omega_minus);
        for (std::size_t i = 0; i < d3q19::q; ++i)
          out[i * n + std::size_t(node)] = block.g[i][0];
        moments[std::size_t(node)] = {block.delta_rho[0],
                                      {block.momentum[0][0], block.momentum[1][0], block.momentum[2][0]}};
      }
}

TEST(Streaming, AlternatingStepsMatchTheTwoArrayPullSchemeBitForBit) {
  const Lattice lattice = make_lattice(all_periodic);
  const Topology& t = lattice.topology;
  const auto n = static_cast<std::size_t>(t.n_fluid);
  std::vector<std::int64_t> node_of_cell(lattice.image.phase.size(), -1);
  for (std::size_t node = 0; node < n; ++node)
    node_of_cell[static_cast<std::size_t>(t.fluid_cell[node])] = static_cast<std::int64_t>(node);

  const std::array<double, 3> force{2e-5, -7e-6, 3e-6};
  const TrtRates rates = make_trt_rates(0.8, 3.0 / 16.0);
  std::vector<double> aa(t.array_size(), 0.0), a(19 * n, 0.0), b(19 * n, 0.0);
  std::vector<MomentsRecord> aa_moments(n), pull_moments(n);
  for (int step = 1; step <= 41; ++step) {
    const Parity parity = step % 2 == 1 ? Parity::even : Parity::odd;
    stream_collide<double, true>(parity, aa.data(), t.slot.data(), t.n_fluid, t.stride, force,
                                 rates.omega_plus, rates.omega_minus, aa_moments.data());
    pull_step(lattice.image, node_of_cell, a, b, pull_moments, force, rates.omega_plus, rates.omega_minus);
    std::swap(a, b);
    for (std::size_t node = 0; node < n; ++node) {
      ASSERT_EQ(aa_moments[node].delta_rho, pull_moments[node].delta_rho)
          << "step " << step << " node " << node;
      for (int d = 0; d < 3; ++d)
        ASSERT_EQ(aa_moments[node].momentum[d], pull_moments[node].momentum[d]) << "step " << step;
    }
  }
  // The flow is under way (the comparison is not between two states at rest).
  double j = 0;
  for (const MomentsRecord& m : aa_moments)
    j += m.momentum[0];
  EXPECT_GT(j / static_cast<double>(n), 1e-5);
}

} // namespace
} // namespace aniso::lbm
