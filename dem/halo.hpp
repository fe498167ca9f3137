#pragma once
// Particle traffic between ranks (on top of common/exchange): migration of
// owned particles to the rank of their new bin, with the history of their
// contacts; ghost copies of the particles next to a rank's bins; and the
// per-step refresh of those ghosts. With one rank all three do nothing.

#include "common/exchange.hpp"
#include "dem/domain.hpp"
#include "dem/neighbors.hpp"
#include "dem/particles.hpp"

#include <cstdint>
#include <vector>

namespace aniso::dem {

class Halo {
public:
  /// Drops ghosts, sends owned particles whose bin belongs to another rank to that rank with the
  /// histories of their touching pairs, and receives the same (collective). Returns the
  /// histories that arrived, for NeighborList::build.
  std::vector<HistoryRecord> migrate(Particles& particles, const PeriodicCell& cell, const Domain& domain,
                                     const NeighborList& neighbors);
  /// Appends ghost copies of every particle in bins next to this rank's (collective) and
  /// remembers who sent what, for update_ghosts.
  void exchange_ghosts(Particles& particles, const PeriodicCell& cell, const Domain& domain);
  /// Refreshes ghost positions, orientations and velocities from their owners (collective).
  void update_ghosts(Particles& particles, const Domain& domain);

private:
  std::vector<std::vector<std::uint32_t>> send_lists_; ///< owned indices sent to each rank
  FixedExchange refresh_;                              ///< the per-step refresh, sized by exchange_ghosts
};

} // namespace aniso::dem
