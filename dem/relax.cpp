#include "dem/relax.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aniso::dem {

bool in_equilibrium(const Simulation& simulation, const EquilibriumConfig& config) {
  // NaN (no contacts at all) never counts as static.
  const Equilibrium& e = simulation.equilibrium();
  return e.unbalanced_force_ratio < config.tolerance && e.unbalanced_torque_ratio < config.tolerance &&
         std::abs(simulation.servo_error()) < config.stress_tolerance;
}

Relaxation relax_to_equilibrium(Simulation& simulation, const EquilibriumConfig& config,
                                std::int64_t max_steps, const Logger& logger, const std::string& label) {
  const h5::CellState loading = simulation.control();
  const double loading_damping = simulation.settings().global_damping;
  h5::CellState held = loading;
  for (int a = 0; a < 3; ++a) {
    if (held.mode[static_cast<std::size_t>(a)] == h5::AxisMode::strain_rate) held.target[a] = 0.0;
  }
  held.servo_state = Vec3::Zero(); // the loading's steady servo rate would drive the held cell

  simulation.set_control(held);
  const std::int64_t interval = simulation.settings().control_interval;
  const std::int64_t start = simulation.step_count();
  int left_equilibrium = 0; // verification windows that the state did not stay balanced through
  const auto fail = [&] {
    throw ConvergenceError(fmt::format(
        "{}: not in equilibrium after {} steps (dem.equilibrium.max_steps): unbalanced-force ratio "
        "{:.3g}, torque ratio {:.3g} (tolerance {:.3g}), stress error {:.3g} (tolerance {:.3g}); the state "
        "left equilibrium within dem.equilibrium.verify_steps = {} steps {} times. Raise "
        "dem.equilibrium.max_steps or dem.equilibrium.tolerance (assemblies of a few hundred particles "
        "creep near 1e-4)",
        label, max_steps, simulation.equilibrium().unbalanced_force_ratio,
        simulation.equilibrium().unbalanced_torque_ratio, config.tolerance,
        std::abs(simulation.servo_error()), config.stress_tolerance, config.verify_steps, left_equilibrium));
  };
  // Steps until the next control update, failing once the budget is spent.
  const auto advance_to_update = [&] {
    do {
      if (simulation.step_count() - start >= max_steps) fail();
      simulation.step();
    } while (simulation.step_count() % interval != 0);
  };
  // The tolerances must hold at consecutive updates, so that a passing swing does not count.
  constexpr int required_checks = 3;
  Progress progress(logger, label, -std::log10(config.tolerance), 10.0);
  for (;;) {
    simulation.set_global_damping(config.damping);
    int passed = in_equilibrium(simulation, config) ? 1 : 0;
    while (passed < required_checks) {
      advance_to_update();
      passed = in_equilibrium(simulation, config) ? passed + 1 : 0;
      const double ratio = simulation.equilibrium().unbalanced_force_ratio;
      progress.update(std::isfinite(ratio) && ratio > 0
                          ? std::min(-std::log10(ratio), -std::log10(config.tolerance))
                          : 0.0);
    }
    // A balanced state may still be unstable (a saddle that the damping only slows the way
    // out of): it counts as static once it stays balanced for verify_steps with the damping it
    // will run with afterwards.
    simulation.set_global_damping(loading_damping);
    bool stable = true;
    for (std::int64_t n = 0; n < config.verify_steps && stable; n += interval) {
      advance_to_update();
      stable = in_equilibrium(simulation, config);
    }
    if (stable) break;
    ++left_equilibrium;
  }
  Relaxation result;
  result.steps = simulation.step_count() - start;
  result.equilibrium = simulation.equilibrium();
  result.stress_error = std::abs(simulation.servo_error());
  simulation.set_control(loading);
  simulation.set_global_damping(loading_damping);
  return result;
}

} // namespace aniso::dem
