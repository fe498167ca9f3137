#pragma once
// Fluid-only lattice of one rank: which voxels it updates, where each of their
// populations streams from, and which populations it must exchange with other
// ranks.
//
// Only fluid voxels are stored (about 40% of a dense packing), in one array:
// the in-place "AA" streaming pattern (Bailey et al. 2009) alternates two
// kinds of step (lbm/stream_collide.hpp). An even step reads a node's own 19
// values and writes each post-collision population i into the node's slot of
// the opposite population. An odd step reads population i where the even step
// left the post-collision value that streams into it, and writes its own
// post-collision population opp(i) back into that same slot, where the next
// even step finds it already streamed. Every fluid node keeps, for each of its
// 18 moving populations i, that slot's absolute index: if i streams from
// population j of voxel y, the slot is (y, opp(j)). The boundary rules are
// folded into the table once, at set-up:
//   - the neighbour upstream is fluid: pull its population (local or ghost);
//   - it is solid, or a no-slip wall face lies in between: halfway
//     bounce-back, j = opp(i) of this node: the slot is the node's own slot i;
//   - a free-slip wall face lies in between: specular reflection, the
//     mirrored population of the node beside the wall.
// Each of these rules is its own inverse under time reversal, so the 18 slots
// a node reads in an odd step are exactly those it writes: the odd step is a
// branch-free gather and scatter, in place, with no race between nodes.
//
// Halo: a rank holds ghost slots for exactly the (voxel, population) pairs its
// odd steps read from other ranks, i.e. only populations that cross a face of
// its box into a fluid node. Receivers send their sorted request lists to the
// owners once. Before each odd step the owners fill the ghost slots; after it
// the ghost slots, overwritten by the odd step with the populations streaming
// the other way, go back to their owners. Even steps are local. Against the
// two-array pull scheme this halves the memory of the populations and leaves
// no write-allocate traffic; the collision sees the same values in the same
// order, so the results are the same to the last bit.

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
  std::vector<std::uint32_t> send_index; ///< slots of the population array the peer mirrors, in its order
  std::uint32_t recv_offset = 0; ///< first ghost slot (relative to the ghost region) filled by the peer
  std::uint32_t recv_count = 0;
};

struct Topology {
  Partition partition;
  Faces faces = all_periodic;
  std::int64_t n_fluid = 0;             ///< fluid nodes of this rank
  std::int64_t stride = 0;              ///< distance between two populations' arrays (padded_stride)
  std::int64_t n_fluid_global = 0;      ///< fluid nodes of the whole image
  std::int64_t n_voxels_global = 0;     ///< all voxels of the image
  std::int64_t n_ghost = 0;             ///< ghost slots (filled before, returned after each odd step)
  std::vector<std::int64_t> fluid_cell; ///< global voxel index (x1 fastest) of each local fluid node
  std::vector<std::uint32_t> slot;      ///< [n * 18 + i - 1]: odd-step slot of population i of node n
  std::vector<HaloPeer> peers;          ///< ranks this rank exchanges with, by rank

  /// Length of the population array: 19 arrays of `stride` values (the first n_fluid used), then the
  /// ghosts.
  [[nodiscard]] std::size_t array_size() const {
    return static_cast<std::size_t>(d3q19::q * stride + n_ghost);
  }
  /// First ghost slot.
  [[nodiscard]] std::size_t ghost_base() const { return static_cast<std::size_t>(d3q19::q * stride); }
};

/// The population arrays' stride for n fluid nodes: n padded (by fewer than 512) to 24 modulo 512, so
/// that the 19 arrays start 192 bytes apart modulo 4 KiB in double (96 in float). With a stride that
/// is a multiple of 512 they all start at the same offset in a page, loads and stores of different
/// populations alias, and an even step ran 1.7x slower (docs/performance.md).
std::int64_t padded_stride(std::int64_t n);

/// Builds the local topology from the whole image (identical on every rank; 1 = solid, x1 fastest).
/// Collective: ranks exchange their halo requests. InputError if the image has no fluid voxel or a
/// rank's share exceeds the 32-bit index range.
Topology build_topology(std::span<const std::uint8_t> phase, const Partition& partition, const Faces& faces,
                        const mpi::Comm& comm);

} // namespace aniso::lbm
