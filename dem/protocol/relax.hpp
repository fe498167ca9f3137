#pragma once
// Relaxation to static equilibrium (docs/decisions.md, "Quasi-static control"):
// the strain-controlled axes of the cell stop, the stress-controlled ones keep
// their servo, and the fluctuating motion is damped globally until the
// unbalanced-force ratio (dem/equilibrium.hpp) and the servo error are both
// below half their tolerances; then, with every axis of the cell fixed and the run's
// own damping, the state must stay balanced and keep p for verify_steps (and, with
// kinetic_growth, not speed up; a state that does runs escape_steps with the servo on before
// minimising again). Kuhn's OVAL cycles each strain
// increment the same way until the mean force imbalance is small (shared/reference/ovoid.md).

#include "common/log.hpp"
#include "dem/config.hpp"
#include "dem/protocol/fire.hpp"
#include "dem/protocol/phase.hpp"
#include "dem/simulation.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace aniso::dem::protocol {

/// Where a relaxation stopped at a control update (SIGTERM): with the simulation's state there,
/// all it needs to continue to the bits of an uninterrupted one (a checkpoint's /relaxation
/// group, dem/io/relaxation_state.hpp).
struct RelaxationState {
  std::int64_t steps = 0;           ///< taken so far
  bool verifying = false;           ///< in a verification window, else minimising or escaping
  bool escaping = false;            ///< after a failed window, letting the state fall with the servo on
  std::int64_t escaped = 0;         ///< escaping: steps of it so far
  int passed = 0;                   ///< minimising: consecutive control updates within the tolerances
  double start_stress = 0;          ///< verifying: p when the window began [Pa]
  std::int64_t verified = 0;        ///< verifying: steps of the window so far
  std::int64_t verifying_steps = 0; ///< in the windows before this one
  int windows_left = 0;             ///< windows the state did not stay static through
  std::optional<FireState> fire;    ///< minimising with FIRE: its state
  PhaseMemory memory;               ///< what the relaxation gives back when it ends
};

/// How a relaxation begins: afresh or continuing an interrupted one, and whether it may stop.
struct RelaxationStart {
  bool stoppable = false;                  ///< stop at a control update once stop_requested()
  const RelaxationState* resume = nullptr; ///< continue this one (the simulation is its state)
  /// Sees the state at every control update where it could stop (outside the verification
  /// windows): a caller may write it, as a stop would, for a resume after a kill.
  std::function<void(const RelaxationState&)> keep;
};

struct Relaxation {
  std::int64_t steps = 0;
  std::int64_t verifying_steps = 0; ///< of `steps`, in the verification windows (passed or left)
  int windows_left = 0;             ///< verification windows the state did not stay static through
  /// Steps the handed-on state stayed static at the fixed cell: verify_steps when verified, fewer
  /// when it ended on dem.equilibrium.max_windows (0 when there was no window).
  std::int64_t held_steps = 0;
  bool verified = true;    ///< false when it ended on dem.equilibrium.max_windows
  double seconds = 0;      ///< wall time
  Equilibrium equilibrium; ///< at the end
  double stress_error = 0; ///< |servo error| at the end
  /// Set when it stopped on request: the simulation is left as it stood, mid-relaxation.
  std::optional<RelaxationState> interrupted;
};

/// True when the last control update meets `margin` times the tolerances: force and torque ratios
/// below margin x config.tolerance, |servo error| below margin x config.stress_tolerance.
bool in_equilibrium(const Simulation& simulation, const EquilibriumConfig& config, double margin = 1.0);

/// Relaxes with the cell's strain-rate axes held, global damping `config.damping`, for at most
/// `max_steps`; then gives back the controller (its targets and servo memory) and the damping
/// the simulation had, so that loading continues from the relaxed state. Throws
/// ConvergenceError (exit 5) naming the ratio reached when the tolerances are not met in time.
/// A stoppable relaxation checks stop_requested (collective) at every control update and, asked
/// to, returns at once with `interrupted` set and nothing given back.
Relaxation relax_to_equilibrium(Simulation& simulation, const EquilibriumConfig& config,
                                std::int64_t max_steps, const Logger& logger, const std::string& label,
                                const RelaxationStart& start = {});

} // namespace aniso::dem::protocol
