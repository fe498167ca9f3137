#include "lbm/topology.hpp"

#include "common/error.hpp"
#include "common/memory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>

namespace aniso::lbm {
namespace {

using d3q19::q;

/// A population a node pulls from another rank, and the table entry waiting for it.
struct Request {
  std::int64_t key;        ///< global voxel index * 19 + population: sorts by voxel, then population
  std::size_t table_entry; ///< index into Topology::slot to patch once the ghost slot is known
};

struct Geometry {
  std::span<const std::uint8_t> phase;
  Index3 shape;
  [[nodiscard]] std::int64_t linear(const Index3& cell) const {
    return cell[0] +
           static_cast<std::int64_t>(shape[0]) * (cell[1] + static_cast<std::int64_t>(shape[1]) * cell[2]);
  }
  [[nodiscard]] bool solid(const Index3& cell) const {
    return phase[static_cast<std::size_t>(linear(cell))] != 0;
  }
};

/// Where population i of the fluid node at `x` streams from: a voxel and a population, or
/// bounce-back (voxel = x, population = opposite) when a no-slip wall or a solid voxel is upstream.
struct Upstream {
  Index3 cell;
  int population;
};

Upstream find_upstream(const Index3& x, int i, const Faces& faces, const Geometry& geometry) {
  const auto& c = d3q19::c[static_cast<std::size_t>(i)];
  const Upstream bounce_back{x, d3q19::opposite(i)};
  Index3 y{};
  std::array<bool, 3> crossed{false, false, false};
  bool no_slip_crossed = false;
  for (std::size_t a = 0; a < 3; ++a) {
    y[a] = x[a] - c[a];
    if (y[a] >= 0 && y[a] < geometry.shape[a]) continue;
    if (faces[a] == FaceKind::periodic) {
      y[a] = (y[a] + geometry.shape[a]) % geometry.shape[a];
    } else {
      crossed[a] = true;
      no_slip_crossed = no_slip_crossed || faces[a] == FaceKind::no_slip;
    }
  }
  if (no_slip_crossed) return bounce_back;
  if (crossed[0] || crossed[1] || crossed[2]) {
    // Specular reflection at a free-slip face: the population left the node beside the wall with its
    // normal component reversed; that node is x moved along the uncrossed axes only.
    for (std::size_t a = 0; a < 3; ++a)
      if (crossed[a]) y[a] = x[a];
    if (geometry.solid(y)) return bounce_back;
    return {y, d3q19::mirrored(i, crossed)};
  }
  if (geometry.solid(y)) return bounce_back;
  return {y, i};
}

void check_index_range(std::int64_t n_fluid) {
  const auto limit = static_cast<std::int64_t>(std::numeric_limits<std::uint32_t>::max() / (q + 1));
  require_input(padded_stride(n_fluid) < limit,
                fmt::format("one rank holds {} fluid voxels, more than the {} its 32-bit "
                            "streaming table addresses; run on more MPI ranks",
                            n_fluid, limit));
}

} // namespace

Topology build_topology(std::span<const std::uint8_t> phase, const Partition& partition, const Faces& faces,
                        const mpi::Comm& comm) {
  const Geometry geometry{phase, partition.global_shape};
  Topology topology;
  topology.partition = partition;
  topology.faces = faces;
  topology.n_voxels_global = static_cast<std::int64_t>(phase.size());
  check_invariant(topology.n_voxels_global == geometry.linear({0, 0, geometry.shape[2]}),
                  "phase size matches shape");

  // Local fluid nodes, x1 fastest, and a dense map from local box voxel to fluid index.
  const Index3& lo = partition.lo;
  const Index3& n = partition.count;
  std::vector<std::int32_t> local_fluid(
      static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(n[2]), -1);
  const auto box_index = [&](const Index3& cell) {
    return static_cast<std::size_t>(cell[0] - lo[0]) +
           static_cast<std::size_t>(n[0]) *
               (static_cast<std::size_t>(cell[1] - lo[1]) +
                static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(cell[2] - lo[2]));
  };
  std::vector<Index3> cells;
  for (int k = lo[2]; k < lo[2] + n[2]; ++k)
    for (int j = lo[1]; j < lo[1] + n[1]; ++j)
      for (int i = lo[0]; i < lo[0] + n[0]; ++i) {
        const Index3 cell{i, j, k};
        if (geometry.solid(cell)) continue;
        local_fluid[box_index(cell)] = static_cast<std::int32_t>(cells.size());
        cells.push_back(cell);
        topology.fluid_cell.push_back(geometry.linear(cell));
      }
  topology.n_fluid = static_cast<std::int64_t>(cells.size());
  check_index_range(topology.n_fluid);
  topology.n_fluid_global = comm.sum(topology.n_fluid);
  require_input(topology.n_fluid_global > 0,
                "the image has no void voxel: there is no pore space to flow through");

  // The streaming table (18 indices), the population array (19 values, double at most) and the two
  // moments records (lbm/flow.cpp) per fluid voxel, before any of them is allocated.
  constexpr double bytes_per_fluid_voxel = 18 * 4 + 19 * 8 + 2 * 4 * 8;
  require_memory(bytes_per_fluid_voxel * static_cast<double>(topology.n_fluid),
                 fmt::format("lbm: {} fluid voxels on this rank", topology.n_fluid),
                 "use a coarser image or more ranks");

  // Streaming table: population i streaming from population j of voxel y reads and writes the slot
  // (y, opp(j)) in odd steps (topology.hpp). Remote slots become requests to their owners.
  const auto n_fluid = static_cast<std::size_t>(topology.n_fluid);
  topology.stride = padded_stride(topology.n_fluid);
  const auto stride = static_cast<std::size_t>(topology.stride);
  topology.slot.resize(static_cast<std::size_t>(q - 1) * n_fluid);
  std::map<int, std::vector<Request>> requests;
  for (std::size_t node = 0; node < n_fluid; ++node)
    for (int i = 1; i < q; ++i) {
      const Upstream up = find_upstream(cells[node], i, faces, geometry);
      const int population = d3q19::opposite(up.population);
      const std::size_t entry = node * (q - 1) + static_cast<std::size_t>(i - 1);
      if (partition.is_local(up.cell)) {
        topology.slot[entry] =
            static_cast<std::uint32_t>(static_cast<std::size_t>(population) * stride +
                                       static_cast<std::size_t>(local_fluid[box_index(up.cell)]));
      } else {
        requests[partition.owner(up.cell)].push_back({geometry.linear(up.cell) * q + population, entry});
      }
    }

  // Ghost slots in (peer rank, voxel, population) order; tell each owner what to send.
  const int n_ranks = comm.size();
  std::vector<int> send_counts(static_cast<std::size_t>(n_ranks), 0);
  std::vector<std::int64_t> outgoing;
  std::vector<int> outgoing_displacements(static_cast<std::size_t>(n_ranks), 0);
  const std::size_t ghost_base = topology.ghost_base();
  std::uint32_t next_slot = 0;
  for (auto& [peer, list] : requests) {
    std::sort(list.begin(), list.end(), [](const Request& a, const Request& b) { return a.key < b.key; });
    HaloPeer halo;
    halo.rank = peer;
    halo.recv_offset = next_slot;
    halo.recv_count = static_cast<std::uint32_t>(list.size());
    outgoing_displacements[static_cast<std::size_t>(peer)] = static_cast<int>(outgoing.size());
    send_counts[static_cast<std::size_t>(peer)] = static_cast<int>(list.size());
    for (const Request& request : list) {
      topology.slot[request.table_entry] = static_cast<std::uint32_t>(ghost_base + next_slot++);
      outgoing.push_back(request.key);
    }
    topology.peers.push_back(std::move(halo));
  }
  topology.n_ghost = next_slot;
  check_index_range(topology.stride + topology.n_ghost / q + 1);

  std::vector<int> recv_counts(static_cast<std::size_t>(n_ranks), 0);
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm.raw());
  std::vector<int> incoming_displacements(static_cast<std::size_t>(n_ranks), 0);
  int total_incoming = 0;
  for (std::size_t r = 0; r < recv_counts.size(); ++r) {
    incoming_displacements[r] = total_incoming;
    total_incoming += recv_counts[r];
  }
  std::vector<std::int64_t> incoming(static_cast<std::size_t>(total_incoming));
  MPI_Alltoallv(outgoing.data(), send_counts.data(), outgoing_displacements.data(), MPI_INT64_T,
                incoming.data(), recv_counts.data(), incoming_displacements.data(), MPI_INT64_T, comm.raw());

  // Requests addressed to this rank become pack lists (a peer may ask without being asked).
  for (int r = 0; r < n_ranks; ++r) {
    const auto count = static_cast<std::size_t>(recv_counts[static_cast<std::size_t>(r)]);
    if (count == 0) continue;
    auto peer = std::find_if(topology.peers.begin(), topology.peers.end(),
                             [r](const HaloPeer& p) { return p.rank == r; });
    if (peer == topology.peers.end()) {
      topology.peers.push_back(HaloPeer{r, {}, 0, 0});
      peer = std::prev(topology.peers.end());
    }
    peer->send_index.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::int64_t key =
          incoming[static_cast<std::size_t>(incoming_displacements[static_cast<std::size_t>(r)]) + k];
      const std::int64_t voxel = key / q;
      const auto population = static_cast<std::size_t>(key % q);
      const Index3 cell{
          static_cast<int>(voxel % geometry.shape[0]),
          static_cast<int>((voxel / geometry.shape[0]) % geometry.shape[1]),
          static_cast<int>(voxel / (static_cast<std::int64_t>(geometry.shape[0]) * geometry.shape[1]))};
      check_invariant(partition.is_local(cell) && local_fluid[box_index(cell)] >= 0,
                      "a halo request names a local fluid voxel");
      peer->send_index.push_back(static_cast<std::uint32_t>(
          population * stride + static_cast<std::size_t>(local_fluid[box_index(cell)])));
    }
  }
  std::sort(topology.peers.begin(), topology.peers.end(),
            [](const HaloPeer& a, const HaloPeer& b) { return a.rank < b.rank; });
  return topology;
}

std::int64_t padded_stride(std::int64_t n) {
  constexpr std::int64_t period = 512, offset = 24;
  return n + ((offset - n) % period + period) % period;
}

} // namespace aniso::lbm
