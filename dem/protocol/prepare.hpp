#pragma once
// Dense isotropic assembly by the paper's protocol (section 2): a sparse random
// arrangement, slow isotropic compaction with reduced friction until the
// assembly seizes, then cycles of random velocities and further compaction,
// keeping the seized assembly whose void ratio is nearest the target, then
// isotropic consolidation to p0 with the loading friction. Where consolidation
// compacts the kept cycle past the tolerance, the cycle that steps across the
// target (plus that compaction) is run again with a weaker agitation.

#include "common/log.hpp"
#include "common/rng.hpp"
#include "dem/config.hpp"
#include "dem/io/prepare_pieces.hpp"
#include "dem/protocol/relax.hpp"
#include "dem/simulation.hpp"

#include <optional>
#include <span>
#include <vector>

namespace aniso::dem::protocol {

/// Where a prepare stopped on SIGTERM.
struct PrepareStop {
  std::string piece; ///< the piece in progress
  std::int64_t step = 0;
  std::string kept; ///< the file its state went to
};

struct PreparedAssembly {
  std::optional<PrepareStop> stopped; ///< set when stopped on SIGTERM: nothing else is
  std::optional<Simulation> simulation;
  std::vector<double> cycle_void_ratios;      ///< void ratio at each cycle's seizure
  std::vector<double> refinement_void_ratios; ///< and at each refinement cycle's, in order
  int chosen_cycle = 0;                       ///< 1-based
  int chosen_refinement = 0;                  ///< 0: the cycle itself, else which refinement of it
  StateMeasures consolidated;                 ///< after consolidation to p0
  std::vector<std::array<std::uint64_t, 4>> rng_state;
  double compaction_seconds = 0;    ///< wall time of the compaction cycles and refinements
  double consolidation_seconds = 0; ///< and of the consolidations
};

/// A run of a compaction cycle: the agitation energy before it (a fraction of the configured
/// one) and the void ratio it seized at.
struct AgitationRun {
  double energy = 0;
  double void_ratio = 0;
};

/// The agitation energy at which a re-run of a cycle should seize at `aim`: linear between the
/// run of the largest energy that seized above the aim and the run of the next larger energy
/// that seized at or below it, kept within the middle 80% of that bracket. `runs` holds energy
/// 0 (the predecessor's seized state) and 1 (the cycle as run). Throws InputError when no such
/// bracket exists.
double refinement_energy(std::span<const AgitationRun> runs, double aim);

/// Sparse random arrangement without overlaps in a cell of the configured proportions,
/// generated identically on every rank and decomposed over `comm` (collective).
Simulation sparse_assembly(const DemConfig& config, RandomStream& sizes, RandomStream& placement,
                           const mpi::Comm& comm);

/// Isotropic consolidation to p0 (dem.prepare.confining_pressure): the stress servo on all three
/// axes at strain rates up to `rate`, relaxed to the verified equilibrium of dem.equilibrium with p
/// within dem.prepare.consolidation_tolerance (collective); `start` as for relax_to_equilibrium
/// (a resumed consolidation keeps the control it stopped with).
Relaxation consolidate(Simulation& simulation, const DemConfig& config, double rate, const Logger& logger,
                       const RelaxationStart& start = {});

/// Gives the simulation the contacts loading will use (dem.material.friction, the contact and
/// global damping of dem.integration) and the servo's rate limit `rate`: a state consolidated
/// with them is static under them.
void with_loading_contacts(Simulation& simulation, const DemConfig& config, double rate);

/// The whole preparation protocol (collective); the result does not depend on the rank count.
/// Each seized and consolidated state is kept in `pieces` as it is reached, and a piece that
/// `pieces` already holds is taken from there, not run: a prepare stopped on SIGTERM (checked at
/// every control update; it keeps the state of the compaction or consolidation in progress)
/// continues to the bits of an uninterrupted one.
PreparedAssembly prepare_assembly(const DemConfig& config, const Logger& logger, const mpi::Comm& comm,
                                  const io::PreparePieces& pieces);
/// The same, keeping nothing.
PreparedAssembly prepare_assembly(const DemConfig& config, const Logger& logger, const mpi::Comm& comm);

} // namespace aniso::dem::protocol
