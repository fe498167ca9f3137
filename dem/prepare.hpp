#pragma once
// Dense isotropic assembly by the paper's protocol (section 2): a sparse random
// arrangement, slow isotropic compaction with reduced friction until the
// assembly seizes, then cycles of random velocities and further compaction,
// keeping the seized assembly whose void ratio is nearest the target, then
// isotropic consolidation to p0 with the loading friction.

#include "common/log.hpp"
#include "common/rng.hpp"
#include "dem/config.hpp"
#include "dem/simulation.hpp"

#include <optional>
#include <vector>

namespace aniso::dem {

struct PreparedAssembly {
  std::optional<Simulation> simulation;
  std::vector<double> cycle_void_ratios; ///< void ratio at each seizure
  int chosen_cycle = 0;                  ///< 1-based
  StateMeasures consolidated;            ///< after consolidation to p0
  std::vector<std::array<std::uint64_t, 4>> rng_state;
};

/// Sparse random arrangement without overlaps in a cell of the configured proportions,
/// generated identically on every rank and decomposed over `comm` (collective).
Simulation sparse_assembly(const DemConfig& config, RandomStream& sizes, RandomStream& placement,
                           const mpi::Comm& comm);

/// The whole preparation protocol (collective); the result does not depend on the rank count.
PreparedAssembly prepare_assembly(const DemConfig& config, const Logger& logger, const mpi::Comm& comm);

} // namespace aniso::dem
