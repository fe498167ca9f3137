#pragma once
// Per-step halo exchange of the populations that cross into this rank's
// fluid nodes (the lists are built by build_topology). Values arrive straight
// in the ghost region of the population array; only sends are packed.

#include "common/mpi.hpp"
#include "lbm/topology.hpp"

#include <span>
#include <vector>

namespace aniso::lbm {

template <class Real> class HaloExchange {
public:
  HaloExchange(const Topology& topology, const mpi::Comm& comm);
  /// Fills the ghost values of `populations` (post-collision state) from the peers. Collective over peers.
  void exchange(std::span<Real> populations);
  /// Values this rank sends per step (for the traffic estimate in benchmarks).
  [[nodiscard]] std::size_t values_sent() const;

private:
  const Topology* topology_;
  MPI_Comm comm_;
  std::vector<std::vector<Real>> send_buffers_;
  std::vector<MPI_Request> requests_;
};

extern template class HaloExchange<float>;
extern template class HaloExchange<double>;

} // namespace aniso::lbm
