#include "dem/protocol/load.hpp"

#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/stop_request.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/history.hpp"
#include "dem/io/settings.hpp"
#include "dem/measures.hpp"
#include "dem/protocol/relax.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace aniso::dem::protocol {
namespace {

using h5::AxisMode;

// The first multiple of `step` above `strain`.
double next_multiple(double strain, double step) {
  return (std::floor(strain / step) + 1) * step;
}

double compressive_strain(const Simulation& simulation) {
  return -simulation.cell().engineering_strain()[0];
}

std::vector<double> history_row(const Simulation& simulation, const DemConfig& config) {
  const StateMeasures m = simulation.measure();
  const Vec3 strain = simulation.cell().engineering_strain();
  const Vec3& reference = simulation.cell().reference_lengths();
  const double volumetric = simulation.cell().volume() / reference.prod() - 1.0;
  const Mat3& s = m.stress;
  // Paper Fig. 3a plots (sigma_11 - sigma_33)/p with compression positive.
  const double ratio = (-s(0, 0) + s(2, 2)) / m.mean_stress;
  const double inertial = inertial_number(simulation.control().strain_rate[0], config.particles.d50,
                                          config.particles.density, m.mean_stress);
  return {static_cast<double>(simulation.step_count()),
          simulation.time(),
          strain[0],
          strain[1],
          strain[2],
          volumetric,
          s(0, 0),
          s(1, 1),
          s(2, 2),
          s(1, 2),
          s(0, 2),
          s(0, 1),
          m.mean_stress,
          m.deviatoric_stress,
          ratio,
          m.void_ratio,
          m.coordination,
          m.coordination_no_rattlers,
          static_cast<double>(m.n_contacts),
          inertial,
          m.elastic_energy > 0 ? m.kinetic_energy / m.elastic_energy : 0.0,
          (m.mean_stress - config.load.mean_stress) / config.load.mean_stress,
          m.axis_orientation(0, 0),
          m.axis_orientation(1, 1),
          m.axis_orientation(2, 2),
          m.unbalanced_force_ratio};
}

// The loading's time step: dem.integration.time_step, or its fraction of the critical step.
double configured_time_step(const Simulation& simulation, const DemConfig& config) {
  return config.integration.time_step > 0
             ? config.integration.time_step
             : config.integration.time_step_fraction * simulation.critical_time_step();
}

// A resumed run continues the loading stored in its checkpoint; a configured setting that
// start_loading() would apply differently would be silently ignored, so it is refused.
void require_resume_matches(const Simulation& simulation, const DemConfig& config) {
  const auto& pc = config.particles;
  const double rate = io::strain_rate_for_inertial_number(config.load.inertial_number, pc.d50, pc.density,
                                                          config.load.mean_stress);
  const double stored_rate = -simulation.control().target[0];
  const auto differs = [](double configured, double stored) {
    return std::abs(configured - stored) > 1e-9 * std::max(std::abs(configured), std::abs(stored));
  };
  std::string mismatches;
  const auto check = [&](const char* key, double configured, double stored, double shown_configured,
                         const std::string& shown_stored) {
    if (differs(configured, stored))
      mismatches += fmt::format("\n  {} = {:.6g}, the checkpoint's loading has {}", key, shown_configured,
                                shown_stored);
  };
  check("dem.load.inertial_number", rate, stored_rate, config.load.inertial_number,
        fmt::format("{:.6g} (strain rate {:.6g} /s)",
                    inertial_number(stored_rate, pc.d50, pc.density, config.load.mean_stress), stored_rate));
  const double stored_p = simulation.control().mean_stress_target;
  check("dem.load.mean_stress", config.load.mean_stress, stored_p, config.load.mean_stress,
        fmt::format("{:.6g} Pa", stored_p));
  const auto& material = simulation.settings().material;
  const double stored_global = simulation.settings().global_damping;
  check("dem.material.friction", config.material.friction, material.friction, config.material.friction,
        fmt::format("{:.6g}", material.friction));
  check("dem.integration.damping", config.integration.damping, material.damping_ratio,
        config.integration.damping, fmt::format("{:.6g}", material.damping_ratio));
  check("dem.integration.global_damping", config.integration.global_damping, stored_global,
        config.integration.global_damping, fmt::format("{:.6g}", stored_global));
  check("dem.integration.control_interval", static_cast<double>(config.integration.control_interval),
        static_cast<double>(simulation.settings().control_interval),
        static_cast<double>(config.integration.control_interval),
        fmt::format("{}", simulation.settings().control_interval));
  check("dem.integration.servo_gain", config.integration.servo_gain, simulation.settings().servo.gain,
        config.integration.servo_gain, fmt::format("{:.6g}", simulation.settings().servo.gain));
  const double time_step = configured_time_step(simulation, config);
  const double stored_step = simulation.settings().time_step;
  check(config.integration.time_step > 0 ? "dem.integration.time_step" : "dem.integration.time_step_fraction",
        time_step, stored_step,
        config.integration.time_step > 0 ? config.integration.time_step
                                         : config.integration.time_step_fraction,
        // Full precision, so that the stored step can be given back with --set to resume.
        fmt::format("a time step of {:.17g} s ({:.6g} of critical)", stored_step,
                    stored_step / simulation.critical_time_step()));
  require_input(mismatches.empty(),
                fmt::format("load --resume: the configuration differs from the loading it would continue "
                            "(a resumed run keeps the stored settings, so these would be ignored):{}\n"
                            "Resume with the original settings, or start a new loading from the checkpoint "
                            "without --resume.",
                            mismatches));
}

// The history a resumed run continues must be its own and reach the checkpoint: another run's
// history would be truncated and mixed in, and a shorter one would leave a silent gap.
void require_history_continues(const io::History& history, const std::string& run_id, double step,
                               double strain, double history_interval, const std::string& output_dir,
                               const Logger& logger) {
  const std::string path = output_dir + "/history.h5";
  if (run_id.empty() && history.run_id().empty()) {
    logger->warn("load --resume: the checkpoint and {} carry no run id (written before run ids); only the "
                 "steps are checked",
                 path);
  } else {
    require_input(!run_id.empty(),
                  fmt::format("load --resume: the input is not a checkpoint of a loading run "
                              "(no run_id), but {} belongs to run {}",
                              path, history.run_id()));
    require_input(
        history.run_id() == run_id,
        fmt::format("load --resume: {} belongs to loading run '{}', the input checkpoint to run '{}': "
                    "resume into that run's own folder (dem.output_dir)",
                    path, history.run_id().empty() ? "(none)" : history.run_id(), run_id));
  }
  require_input(
      history.size() > 0 && step > history.column("step").front(),
      fmt::format("load --resume: the input is at the first step of {} ({}), the prepared assembly, not "
                  "a load checkpoint: start a loading without --resume",
                  path, step));
  // covers_step: the step at which the history was written, right after each checkpoint. Files
  // written before it existed hold rows up to the last sample before the stop, so they reach a
  // checkpoint less than one history interval of strain past their last row.
  double covered = static_cast<double>(history.covers_step());
  if (history.covers_step() < 0) {
    const double last_row_strain = -history.column("strain_11").back();
    covered = strain - last_row_strain < history_interval ? step : history.last_step();
  }
  require_input(covered >= step,
                fmt::format("load --resume: {} reaches step {}, before the input checkpoint's step {} (the "
                            "run stopped between writing the two): resume from an earlier checkpoint that "
                            "the history reaches",
                            path, covered, step));
}

} // namespace

std::string load_checkpoint_path(const std::string& folder, std::size_t index) {
  return fmt::format("{}/load_{:03d}.h5", folder, index);
}

void start_loading(Simulation& simulation, const DemConfig& config) {
  const auto& pc = config.particles;
  const double rate = io::strain_rate_for_inertial_number(config.load.inertial_number, pc.d50, pc.density,
                                                          config.load.mean_stress);
  simulation.reset_reference_lengths();
  simulation.set_time_step(configured_time_step(simulation, config));
  io::require_reachable_strain(config.load.final_strain, rate, simulation.settings().time_step, "load");
  simulation.set_control_interval(config.integration.control_interval, config.integration.servo_gain);
  simulation.set_friction(config.material.friction);
  simulation.set_damping(config.integration.damping);
  simulation.set_global_damping(config.integration.global_damping);
  // The servoed axis must outrun dilatancy but not the assembly's own response.
  simulation.set_servo_max_rate(20.0 * rate);
  h5::CellState state = simulation.cell_state();
  state.mode = {AxisMode::strain_rate, AxisMode::strain_rate, AxisMode::stress};
  state.target = Vec3(-rate, 0.0, -config.load.mean_stress);
  state.hold_mean_stress = true;
  state.mean_stress_target = config.load.mean_stress;
  simulation.set_control(state);
}

LoadSummary run_loading(Simulation& simulation, const DemConfig& config, const std::string& output_dir,
                        const h5::Provenance& provenance, const Logger& logger, bool resuming,
                        const std::string& run_id) {
  const auto& load = config.load;
  const auto start_wall = std::chrono::steady_clock::now();
  io::History history;
  if (resuming) {
    history = io::History::read(output_dir);
    require_history_continues(history, run_id, static_cast<double>(simulation.step_count()),
                              compressive_strain(simulation), load.history_interval, output_dir, logger);
    require_resume_matches(simulation, config);
    history.truncate_after_step(static_cast<double>(simulation.step_count()));
  } else {
    history.set_run_id(run_id);
    history.append(history_row(simulation, config));
  }
  const auto checkpoint_of_run = [&] {
    h5::Checkpoint checkpoint = io::to_checkpoint(simulation, config.particles.d50, {});
    checkpoint.run_id = run_id;
    return checkpoint;
  };
  LoadSummary summary;
  const std::int64_t start_step = simulation.step_count();
  double next_history =
      (std::floor(compressive_strain(simulation) / load.history_interval) + 1) * load.history_interval;
  EquilibriumConfig increment_tolerances = config.equilibrium;
  increment_tolerances.tolerance = load.increment_tolerance;
  increment_tolerances.verify_steps = 0;
  std::size_t next_checkpoint = 0;
  while (next_checkpoint < load.checkpoint_strains.size() &&
         load.checkpoint_strains[next_checkpoint] <= compressive_strain(simulation)) {
    ++next_checkpoint;
  }
  // Increments end at multiples of load.increment and at every checkpoint strain, so that
  // each checkpoint is a relaxed state; both follow from the strain alone, so a resumed run
  // ends them where the uninterrupted one did.
  const auto increment_end = [&](double strain) {
    double end = next_multiple(strain, load.increment);
    for (const double checkpoint_strain : load.checkpoint_strains)
      if (checkpoint_strain > strain) end = std::min(end, checkpoint_strain);
    return end;
  };
  double next_increment = load.increment > 0 ? increment_end(compressive_strain(simulation)) : 0;
  const double rate = -simulation.control().target[0];
  logger->info(
      "load: rate {:.4g} /s, inertial number {:.3g}, from strain {:.5g} to {:.5g}, time step {:.3g} s", rate,
      load.inertial_number, compressive_strain(simulation), load.final_strain,
      simulation.settings().time_step);
  Progress progress(logger, "load", load.final_strain, 10.0, {}, compressive_strain(simulation));
  for (double strain = compressive_strain(simulation); strain < load.final_strain;
       strain = compressive_strain(simulation)) {
    simulation.step();
    strain = compressive_strain(simulation);
    progress.update(strain);
    if (load.increment > 0 && strain >= next_increment) {
      // OVAL's loading: each strain increment is followed by a relaxation to a small force
      // imbalance, so the path is a sequence of near-static states (docs/methods/dem.md).
      summary.relaxation_steps +=
          relax_to_equilibrium(simulation, increment_tolerances, config.equilibrium.max_steps, logger,
                               fmt::format("relaxation after the increment to strain {:.5g}", strain))
              .steps;
      next_increment = increment_end(strain);
    }
    if (strain >= next_history || strain >= load.final_strain) {
      history.append(history_row(simulation, config));
      while (next_history <= strain)
        next_history += load.history_interval;
    }
    if (next_checkpoint < load.checkpoint_strains.size() &&
        strain >= load.checkpoint_strains[next_checkpoint]) {
      const std::string path = load_checkpoint_path(output_dir, next_checkpoint);
      if (config.equilibrium.at_checkpoints) {
        const Relaxation relaxed =
            relax_to_equilibrium(simulation, config.equilibrium, config.equilibrium.max_steps, logger,
                                 fmt::format("relaxation before checkpoint {}", next_checkpoint));
        summary.relaxation_steps += relaxed.steps;
        history.append(history_row(simulation, config)); // the relaxed state, at the same strain
      }
      // The log reports the ratios measured for the file: simulation.equilibrium() is stale
      // when equilibrium is not watched (no relaxation at checkpoints).
      const h5::Checkpoint checkpoint = checkpoint_of_run();
      h5::write_checkpoint(path, checkpoint, provenance, simulation.comm());
      if (simulation.comm().is_root()) history.write(output_dir, provenance, simulation.step_count());
      logger->info("checkpoint {} at strain {:.6g}: {} (p = {:.4g} Pa, servo error {:.2e}, unbalanced-force "
                   "ratio {:.2e}, kinetic/elastic {:.2e})",
                   next_checkpoint, strain, path, mean_stress_compression_positive(simulation.stress()),
                   simulation.servo_error(), checkpoint.unbalanced_force_ratio,
                   checkpoint.kinetic_elastic_ratio);
      summary.checkpoints.push_back(path);
      ++next_checkpoint;
    }
    // SIGTERM (a SLURM time limit or scancel) ends the run at a control update, every rank at
    // the same step, with a checkpoint from which --resume continues exactly: the increments,
    // history rows and checkpoints ahead all follow from the strain.
    if (simulation.step_count() % simulation.settings().control_interval == 0 &&
        stop_requested(simulation.comm())) {
      summary.interrupted_checkpoint = output_dir + "/load_interrupted.h5";
      h5::write_checkpoint(summary.interrupted_checkpoint, checkpoint_of_run(), provenance,
                           simulation.comm());
      logger->warn("load: stopped on SIGTERM at strain {:.6g} (step {}): wrote {}; continue with --input {} "
                   "--resume",
                   strain, simulation.step_count(), summary.interrupted_checkpoint,
                   summary.interrupted_checkpoint);
      break;
    }
  }
  if (simulation.comm().is_root()) history.write(output_dir, provenance, simulation.step_count());
  simulation.comm().barrier(); // the history is on disk before anyone reports success
  const auto& ratio = history.column("stress_ratio");
  const auto& strain_11 = history.column("strain_11");
  for (std::size_t r = 0; r < ratio.size(); ++r) {
    if (ratio[r] > summary.peak_stress_ratio) {
      summary.peak_stress_ratio = ratio[r];
      summary.peak_strain = -strain_11[r];
    }
  }
  summary.final_strain = compressive_strain(simulation);
  summary.steps = simulation.step_count() - start_step;
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_wall).count();
  return summary;
}

} // namespace aniso::dem::protocol
