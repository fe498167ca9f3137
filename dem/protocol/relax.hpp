#pragma once
// Relaxation to static equilibrium (docs/decisions.md, "Quasi-static control"):
// the strain-controlled axes of the cell stop, the stress-controlled ones keep
// their servo, and the fluctuating motion is damped globally until the
// unbalanced-force ratio (dem/equilibrium.hpp) and the servo error are both
// below half their tolerances; then, with every axis of the cell fixed and the run's
// own damping, the state must stay balanced and keep p for verify_steps. Kuhn's OVAL cycles each strain
// increment the same way until the mean force imbalance is small (shared/reference/ovoid.md).

#include "common/log.hpp"
#include "dem/config.hpp"
#include "dem/simulation.hpp"

#include <cstdint>
#include <string>

namespace aniso::dem::protocol {

struct Relaxation {
  std::int64_t steps = 0;
  std::int64_t verifying_steps = 0; ///< of `steps`, in the verification windows (passed or left)
  int windows_left = 0;             ///< verification windows the state did not stay static through
  double seconds = 0;               ///< wall time
  Equilibrium equilibrium;          ///< at the end
  double stress_error = 0;          ///< |servo error| at the end
};

/// True when the last control update meets `margin` times the tolerances: force and torque ratios
/// below margin x config.tolerance, |servo error| below margin x config.stress_tolerance.
bool in_equilibrium(const Simulation& simulation, const EquilibriumConfig& config, double margin = 1.0);

/// Relaxes with the cell's strain-rate axes held, global damping `config.damping`, for at most
/// `max_steps`; then gives back the controller (its targets and servo memory) and the damping
/// the simulation had, so that loading continues from the relaxed state. Throws
/// ConvergenceError (exit 5) naming the ratio reached when the tolerances are not met in time.
Relaxation relax_to_equilibrium(Simulation& simulation, const EquilibriumConfig& config,
                                std::int64_t max_steps, const Logger& logger, const std::string& label);

} // namespace aniso::dem::protocol
