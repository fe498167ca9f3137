#include "lbm/halo.hpp"

#include <type_traits>

namespace aniso::lbm {
namespace {
constexpr int fill_tag = 19;
constexpr int give_back_tag = 20;

template <class Real> MPI_Datatype mpi_type() {
  return std::is_same_v<Real, double> ? MPI_DOUBLE : MPI_FLOAT;
}
} // namespace

template <class Real>
HaloExchange<Real>::HaloExchange(const Topology& topology, const mpi::Comm& comm)
    : topology_(&topology), comm_(comm.raw()) {
  for (const HaloPeer& peer : topology.peers)
    owned_buffers_.emplace_back(peer.send_index.size());
  requests_.reserve(2 * topology.peers.size());
}

template <class Real> void HaloExchange<Real>::fill(std::span<Real> populations) {
  const std::size_t ghost_base = topology_->ghost_base();
  requests_.clear();
  for (const HaloPeer& peer : topology_->peers) {
    if (peer.recv_count == 0) continue;
    requests_.emplace_back();
    MPI_Irecv(populations.data() + ghost_base + peer.recv_offset, static_cast<int>(peer.recv_count),
              mpi_type<Real>(), peer.rank, fill_tag, comm_, &requests_.back());
  }
  for (std::size_t p = 0; p < topology_->peers.size(); ++p) {
    const HaloPeer& peer = topology_->peers[p];
    if (peer.send_index.empty()) continue;
    std::vector<Real>& buffer = owned_buffers_[p];
    for (std::size_t k = 0; k < peer.send_index.size(); ++k)
      buffer[k] = populations[peer.send_index[k]];
    requests_.emplace_back();
    MPI_Isend(buffer.data(), static_cast<int>(buffer.size()), mpi_type<Real>(), peer.rank, fill_tag, comm_,
              &requests_.back());
  }
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
}

template <class Real> void HaloExchange<Real>::give_back(std::span<Real> populations) {
  const std::size_t ghost_base = topology_->ghost_base();
  requests_.clear();
  for (std::size_t p = 0; p < topology_->peers.size(); ++p) {
    const HaloPeer& peer = topology_->peers[p];
    if (peer.send_index.empty()) continue;
    requests_.emplace_back();
    MPI_Irecv(owned_buffers_[p].data(), static_cast<int>(owned_buffers_[p].size()), mpi_type<Real>(),
              peer.rank, give_back_tag, comm_, &requests_.back());
  }
  for (const HaloPeer& peer : topology_->peers) {
    if (peer.recv_count == 0) continue;
    requests_.emplace_back();
    MPI_Isend(populations.data() + ghost_base + peer.recv_offset, static_cast<int>(peer.recv_count),
              mpi_type<Real>(), peer.rank, give_back_tag, comm_, &requests_.back());
  }
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  for (std::size_t p = 0; p < topology_->peers.size(); ++p) {
    const HaloPeer& peer = topology_->peers[p];
    const std::vector<Real>& buffer = owned_buffers_[p];
    for (std::size_t k = 0; k < peer.send_index.size(); ++k)
      populations[peer.send_index[k]] = buffer[k];
  }
}

template <class Real> std::size_t HaloExchange<Real>::values_sent() const {
  std::size_t total = 0;
  for (const HaloPeer& peer : topology_->peers)
    total += peer.send_index.size();
  return total;
}

template class HaloExchange<float>;
template class HaloExchange<double>;

} // namespace aniso::lbm
