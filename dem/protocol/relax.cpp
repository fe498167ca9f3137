#include "dem/protocol/relax.hpp"

#include "common/error.hpp"
#include "common/stop_request.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/model/integrator.hpp"
#include "dem/protocol/fire.hpp"
#include "dem/protocol/phase.hpp"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>

namespace aniso::dem::protocol {

namespace {
// A debug line of the relaxation's state, to see whether a slow relaxation creeps
// (e and p moving), oscillates (the servo) or rattles (kinetic energy only).
void trace(const Simulation& simulation, const Logger& logger, const std::string& label, std::int64_t steps) {
  const Equilibrium& e = simulation.equilibrium();
  logger->debug("{}: step {}: ratio {:.2e}, torque ratio {:.2e}, kinetic/elastic {:.2e}, servo error {:.2e}, "
                "e = {:.5f}, contacts {}",
                label, steps, e.unbalanced_force_ratio, e.unbalanced_torque_ratio, e.kinetic_elastic_ratio(),
                simulation.servo_error(), simulation.cell().volume() / simulation.solid_volume() - 1.0,
                e.n_contacts);
}
} // namespace

bool in_equilibrium(const Simulation& simulation, const EquilibriumConfig& config, double margin) {
  // NaN (no contacts at all) never counts as static.
  const Equilibrium& e = simulation.equilibrium();
  return e.unbalanced_force_ratio < margin * config.tolerance &&
         e.unbalanced_torque_ratio < margin * config.tolerance &&
         std::abs(simulation.servo_error()) < margin * config.stress_tolerance;
}

Relaxation relax_to_equilibrium(Simulation& simulation, const EquilibriumConfig& config,
                                std::int64_t max_steps, const Logger& logger, const std::string& label,
                                const RelaxationStart& start) {
  Phase phase(simulation, label, max_steps, Phase::GiveBack::on_exit);
  // Where the relaxation stands; an interrupted one continues from its own.
  RelaxationState state;
  if (start.resume != nullptr) {
    state = *start.resume;
    phase.resume(state.memory, state.steps);
  }
  // A passed window is rewound, so the step count at the end is not the first plus the steps.
  const std::int64_t first_step = simulation.step_count() - state.steps;
  const model::CellControl loading = phase.memory().control;
  const double loading_damping = phase.memory().settings.global_damping;
  const model::CellControl held = model::strain_axes_held(loading);
  const model::CellControl fixed = model::fixed_cell(held);
  phase.fail_beyond_budget([&] {
    return fmt::format(
        "{}: not in equilibrium after {} steps (dem.equilibrium.max_steps): unbalanced-force ratio "
        "{:.3g}, torque ratio {:.3g} (tolerance {:.3g}), stress error {:.3g} (tolerance {:.3g}); the state "
        "left equilibrium within dem.equilibrium.verify_steps = {} steps {} times. Raise "
        "dem.equilibrium.max_steps or dem.equilibrium.tolerance (assemblies of a few hundred particles "
        "creep near 1e-4)",
        label, max_steps, simulation.equilibrium().unbalanced_force_ratio,
        simulation.equilibrium().unbalanced_torque_ratio, config.tolerance,
        std::abs(model::servo_error(loading, simulation.stress())), config.stress_tolerance,
        config.verify_steps, state.windows_left);
  });
  const auto with_damping = [&](double ratio) {
    SimulationSettings settings = simulation.settings();
    settings.global_damping = ratio;
    simulation.reconfigure(settings);
  };
  // Checked at the control updates where the state above says all there is to continue from.
  const auto stop_here = [&](const std::optional<Fire>& minimiser) {
    const auto record = [&] {
      state.steps = phase.steps();
      state.memory = phase.memory();
      state.fire = minimiser ? std::optional<FireState>(minimiser->state()) : std::nullopt;
    };
    if (start.keep) {
      record();
      start.keep(state);
    }
    if (!start.stoppable || !stop_requested(simulation.comm(), simulation.step_count())) return false;
    record();
    phase.suspend();
    return true;
  };
  const auto interrupted = [&] {
    Relaxation result;
    result.steps = phase.steps();
    result.seconds = phase.seconds();
    result.interrupted = state;
    return result;
  };
  // After a failed window: the run's own dynamics with the servo on, so that an unstable balance
  // falls (a small slip, p kept) rather than being minimised back to where it was. False when
  // stopped on request.
  const auto escape = [&] {
    if (state.escaped == 0)
      logger->debug("{}: escaping for {} steps from step {}", label, config.escape_steps,
                    simulation.step_count());
    while (state.escaped < config.escape_steps) {
      phase.advance_to_update();
      state.escaped += simulation.settings().control_interval;
      if (stop_here(std::nullopt)) return false;
    }
    state.escaping = false;
    return true;
  };
  simulation.watch_equilibrium(true);
  if (start.resume == nullptr) simulation.set_control(held);
  // The tolerances must hold at consecutive updates, so that a passing swing does not count.
  constexpr int required_checks = 3;
  // A state verified afterwards is first relaxed to half the tolerances: one that only just met
  // them left them within a few hundred steps of the undamped window, at the first fluctuation
  // (the demo's checkpoints: 1.00e-4 against 1e-4, again and again).
  const double margin = config.verify_steps > 0 ? config.margin : 1.0;
  Progress progress(logger, label, -std::log10(margin * config.tolerance), 10.0);
  const bool fire = config.method == Relaxer::fire;
  // A resumed relaxation enters the stage it stopped in with the settings it stopped with.
  bool resumed = start.resume != nullptr;
  require_input(
      !resumed || state.verifying || state.escaping || fire == state.fire.has_value(),
      fmt::format("{}: the relaxation to resume was minimising {} FIRE, and dem.equilibrium.method is "
                  "now '{}': resume with the method it ran with",
                  label, fire ? "without" : "with", fire ? "fire" : "damped"));
  std::int64_t held_steps = 0; // by the state handed on
  bool verified = true;
  for (;;) {
    if (resumed && state.escaping) {
      resumed = false;
      if (!escape()) return interrupted();
      continue;
    }
    if (!(resumed && state.verifying)) {
      std::optional<Fire> minimiser;
      if (!resumed) {
        with_damping(fire ? 0.0 : config.damping);
        if (fire) minimiser.emplace(simulation, config.fire_time_step_factor);
        state.passed = in_equilibrium(simulation, config, margin) ? 1 : 0;
      } else if (fire) {
        minimiser.emplace(simulation, *state.fire);
      }
      resumed = false;
      const std::function<void()> turn = [&] { minimiser->update(); };
      while (state.passed < required_checks) {
        phase.advance_to_update(minimiser ? turn : std::function<void()>{});
        state.passed = in_equilibrium(simulation, config, margin) ? state.passed + 1 : 0;
        const double ratio = simulation.equilibrium().unbalanced_force_ratio;
        if (phase.steps() % 5000 == 0) trace(simulation, logger, label, phase.steps());
        progress.update(std::isfinite(ratio) && ratio > 0
                            ? std::min(-std::log10(ratio), -std::log10(margin * config.tolerance))
                            : 0.0);
        if (stop_here(minimiser)) return interrupted();
      }
      // A balanced state may still be unstable (a saddle that the damping only slows the way
      // out of, or a creep that the servo would feed): it counts as static once, with the cell
      // fixed and the damping it will run with afterwards, it stays balanced and keeps its mean
      // stress for verify_steps.
      if (minimiser) minimiser->end(); // the run's own time step again
      if (config.verify_steps == 0) break;
      simulation.set_control(fixed);
      with_damping(loading_damping);
      // A static state is at rest: the window starts from the balance without the velocities
      // the minimiser's path left in it, and so does the state handed on (an export to a
      // format without spins then loses nothing).
      model::damp_velocities(simulation.particles(), 0.0, 0.0);
      simulation.measure_stress_now();
      state.verifying = true;
      state.start_stress = mean_stress_compression_positive(simulation.stress());
      state.verified = 0;
    } else if (state.verified > 0) {
      // A window stored mid-way (files written before windows were rewound on SIGTERM):
      // it begins again here, so that the state it verifies is the one it started from.
      state.start_stress = mean_stress_compression_positive(simulation.stress());
      state.verified = 0;
    }
    resumed = false;
    // The window tests the state it starts from, and that state is the one the relaxation
    // gives: a hold of the written state replays the window step for step. Handing on the
    // window's end instead handed on a state nobody had verified; in the critical state it
    // was already on its way out (paper-size spheres at 15%: balanced through its window, then
    // lost all its stress in the next 30,000 steps at the fixed cell).
    const Simulation window_start = simulation;
    bool stable = true;    // a window is only ever interrupted while stable
    bool speeding = false; // left on the growth of its kinetic energy
    double drift = 0;
    double calmest = std::numeric_limits<double>::infinity(); // lowest kinetic/elastic ratio so far
    // A window of a large assembly takes minutes to hours (20,000 steps of a million particles: two
    // hours on one core): it says how far it is, as the minimisation does.
    Progress window_progress(logger, label + " (verifying at a fixed cell)",
                             static_cast<double>(config.verify_steps), 10.0);
    while (state.verified < config.verify_steps && stable) {
      phase.advance_to_update();
      if (phase.steps() % 5000 == 0) trace(simulation, logger, label + " (verifying)", phase.steps());
      const Equilibrium& e = simulation.equilibrium();
      drift = mean_stress_compression_positive(simulation.stress()) / state.start_stress - 1.0;
      // A balance that speeds up by itself is unstable, however small its forces are yet: the
      // paper-size spheres' critical state, minimised to a force ratio of 1e-6, gained kinetic
      // energy tenfold every 4,000 steps of the window and lost all its stress at 30,000. The
      // window's first tenth is not counted: the residual forces of any balance set the particles
      // moving from rest (tenfold within 100 steps) before the damping takes that back.
      bool calm = true;
      if (config.kinetic_growth > 0 && state.verified >= config.verify_steps / 10) {
        calmest = std::min(calmest, std::max(e.kinetic_elastic_ratio(), config.kinetic_floor));
        calm = !(e.kinetic_elastic_ratio() > config.kinetic_growth * calmest);
      }
      speeding = !calm;
      stable = e.unbalanced_force_ratio < config.tolerance && e.unbalanced_torque_ratio < config.tolerance &&
               std::abs(drift) < config.stress_tolerance && calm;
      state.verified += simulation.settings().control_interval;
      window_progress.update(static_cast<double>(state.verified), [&] {
        return fmt::format("p drift {:+.2e}, unbalanced-force ratio {:.2e}", drift, e.unbalanced_force_ratio);
      });
      if (stable && start.stoppable && stop_requested(simulation.comm(), simulation.step_count())) {
        // Stored at the window's start, to verify again on resume: the same bits as going on.
        const std::int64_t replayed = state.verified;
        simulation = window_start;
        state.verified = 0;
        state.steps = phase.steps() - replayed;
        state.memory = phase.memory();
        state.fire = std::nullopt;
        phase.suspend();
        return interrupted();
      }
    }
    state.verifying_steps += state.verified;
    state.verifying = false;
    if (stable) {
      logger->info("{}: static through the {}-step verification at a fixed cell (p drift {:+.3e}, "
                   "unbalanced-force ratio {:.2e}); the state it began from is the relaxed one",
                   label, state.verified, drift, simulation.equilibrium().unbalanced_force_ratio);
      simulation = window_start;
      held_steps = state.verified;
      break;
    }
    ++state.windows_left;
    if (config.max_windows > 0 && state.windows_left >= config.max_windows) {
      // A creeping state (ovoids in flow lose 0.1% of p in 10,000-20,000 steps at the fixed cell,
      // again and again): the balance the last window began from, said to be unverified.
      logger->warn("{}: left the verification {} times (dem.equilibrium.max_windows): ends unverified at "
                   "the balance the last window began from, which held p within {:.3g} for {} of its {} "
                   "steps",
                   label, state.windows_left, config.stress_tolerance, state.verified, config.verify_steps);
      held_steps = state.verified;
      verified = false;
      simulation = window_start;
      break;
    }
    // Said, so that a progress that falls back from 100% is explained.
    logger->info(
        "{}: left equilibrium {} steps into the {}-step verification (unbalanced-force ratio {:.2e}, "
        "torque ratio {:.2e}, p drift {:.2e}{}); relaxing again ({} so far)",
        label, state.verified, config.verify_steps, simulation.equilibrium().unbalanced_force_ratio,
        simulation.equilibrium().unbalanced_torque_ratio, drift,
        speeding ? fmt::format(", kinetic/elastic {:.2e}, {:.3g} times its lowest",
                               simulation.equilibrium().kinetic_elastic_ratio(),
                               simulation.equilibrium().kinetic_elastic_ratio() / calmest)
                 : "",
        state.windows_left);
    simulation.set_control(held);
    // Minimised at once, an unstable balance comes back to where it was (the paper-size spheres
    // at 15%: 23 windows in a row, each left within 4,000 steps on the same growth).
    if (!speeding) continue;
    state.escaping = true;
    state.escaped = 0;
    if (!escape()) return interrupted();
  }
  Relaxation result;
  result.steps = phase.steps();
  result.verifying_steps = state.verifying_steps;
  result.windows_left = state.windows_left;
  result.held_steps = held_steps;
  result.verified = verified;
  result.seconds = phase.seconds();
  result.equilibrium = simulation.equilibrium();
  result.stress_error = std::abs(model::servo_error(loading, simulation.stress()));
  logger->debug("{}: {} steps, from step {}; the relaxed state is that of step {}", label, result.steps,
                first_step, simulation.step_count());
  phase.end();
  return result;
}

} // namespace aniso::dem::protocol
