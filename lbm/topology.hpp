#pragma once
// Fluid-only lattice of one rank: which voxels it updates, where each of their
// populations streams from, and which populations it must receive from and
// send to other ranks every step.
//
// Only fluid voxels are stored (about 40% of a dense packing). Every fluid
// node keeps, for each of its 18 moving populations, the absolute index of
// the post-collision value it pulls in the next step. The boundary rules are
// folded into that table once, at set-up:
//   - the neighbour upstream is fluid: pull its population (local or ghost);
//   - it is solid, or a no-slip wall face lies in between: halfway
//     bounce-back, pull this node's own opposite population;
//   - a free-slip wall face lies in between: specular reflection, pull the
//     mirrored population from the node beside the wall.
// So the time loop is one branch-free gather per population.
//
// Halo: a rank receives exactly the (voxel, population) pairs its table
// pulls from other ranks, i.e. only populations that cross a face of its box
// into a fluid node. Receivers send their sorted request lists to the owners
// once; afterwards each step is one message per neighbouring rank each way,
// received straight into the ghost part of the population array.

#include "common/mpi.hpp"
#include "lbm/boundary.hpp"
#include "lbm/d3q19.hpp"
#include "lbm/partition.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aniso::lbm {

/// The populations exchanged with one other rank each step.
struct HaloPeer {
  int rank = 0;
  std::vector<std::uint32_t> send_index; ///< indices into the population array, in the peer's request order
  std::uint32_t recv_offset = 0; ///< first ghost slot (relative to the ghost region) filled by the peer
  std::uint32_t recv_count = 0;
};

struct Topology {
  Partition partition;
  Faces faces = all_periodic;
  std::int64_t n_fluid = 0;             ///< fluid nodes of this rank
  std::int64_t n_fluid_global = 0;      ///< fluid nodes of the whole image
  std::int64_t n_voxels_global = 0;     ///< all voxels of the image
  std::int64_t n_ghost = 0;             ///< ghost values received per step
  std::vector<std::int64_t> fluid_cell; ///< global voxel index (x1 fastest) of each local fluid node
  std::vector<std::uint32_t> source;    ///< [(i - 1) * n_fluid + n]: where population i of node n pulls from
  std::vector<HaloPeer> peers;          ///< ranks this rank exchanges with, by rank

  /// Length of a population array: 19 values per fluid node, then the ghosts.
  [[nodiscard]] std::size_t array_size() const {
    return static_cast<std::size_t>(d3q19::q * n_fluid + n_ghost);
  }
};

/// Builds the local topology from the whole image (identical on every rank; 1 = solid, x1 fastest).
/// Collective: ranks exchange their halo requests. InputError if the image has no fluid voxel or a
/// rank's share exceeds the 32-bit index range.
Topology build_topology(std::span<const std::uint8_t> phase, const Partition& partition, const Faces& faces,
                        const mpi::Comm& comm);

} // namespace aniso::lbm
