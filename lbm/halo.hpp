#pragma once
// Halo exchange of the in-place (AA) streaming pattern (lbm/topology.hpp).
// Before an odd step `fill` copies the owners' slots into this rank's ghost
// slots; after it `give_back` returns the ghost slots, which the odd step
// overwrote with the populations streaming the other way, to their owners.
// Ghost values travel straight from and into the ghost region of the
// population array; only the owners' side is packed and unpacked.

#include "common/mpi.hpp"
#include "lbm/topology.hpp"

#include <span>
#include <vector>

namespace aniso::lbm {

template <class Real> class HaloExchange {
public:
  HaloExchange(const Topology& topology, const mpi::Comm& comm);
  /// Fills the ghost slots of `populations` from their owners. Collective over peers.
  void fill(std::span<Real> populations);
  /// Sends the ghost slots back and stores what the peers return in this rank's slots. Collective over peers.
  void give_back(std::span<Real> populations);
  /// Values this rank sends per exchange (for the traffic estimate in benchmarks).
  [[nodiscard]] std::size_t values_sent() const;

private:
  const Topology* topology_;
  MPI_Comm comm_;
  std::vector<std::vector<Real>> owned_buffers_; ///< per peer: this rank's slots that the peer mirrors
  std::vector<MPI_Request> requests_;
};

extern template class HaloExchange<float>;
extern template class HaloExchange<double>;

} // namespace aniso::lbm
