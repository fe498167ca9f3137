#pragma once
// Particle traffic between ranks (on top of common/exchange): migration of
// owned particles to the rank of their new bin, with the history of their
// contacts; ghost copies of the particles next to a rank's bins; and the
// per-step refresh of those ghosts. With one rank all three do nothing.

#include "common/exchange.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/parallel/domain.hpp"

#include <cstdint>
#include <vector>

namespace aniso::dem::parallel {

class Halo {
public:
  /// Drops ghosts, sends owned particles whose bin belongs to another rank to that rank with the
  /// histories of their touching pairs, and receives the same (collective). Returns the
  /// histories that arrived, for NeighborList::build.
  std::vector<data::HistoryRecord> migrate(data::Particles& particles, const PeriodicCell& cell,
                                           const Domain& domain, const data::NeighborList& neighbors);
  /// Appends ghost copies of every particle in bins next to this rank's (collective) and
  /// remembers who sent what, for update_ghosts.
  void exchange_ghosts(data::Particles& particles, const PeriodicCell& cell, const Domain& domain);
  /// Refreshes ghost positions, orientations and velocities from their owners (collective).
  void update_ghosts(data::Particles& particles, const Domain& domain);
  /// Particle states one refresh sends (a particle counts once per rank it goes to), and the
  /// ranks it sends to: the halo volume of this rank.
  [[nodiscard]] std::size_t n_sent() const;
  [[nodiscard]] int n_partners() const;
  /// Bytes of one particle's state in a refresh.
  [[nodiscard]] static std::size_t state_bytes();

private:
  std::vector<std::vector<std::uint32_t>> send_lists_; ///< owned indices sent to each rank
  FixedExchange refresh_;                              ///< the per-step refresh, sized by exchange_ghosts
};

} // namespace aniso::dem::parallel
