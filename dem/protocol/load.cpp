#include "dem/protocol/load.hpp"

#include "common/error.hpp"
#include "common/stop_request.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/history.hpp"
#include "dem/io/parameters.hpp"
#include "dem/measures.hpp"
#include "dem/protocol/phase.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/protocol/relax.hpp"
#include "dem/protocol/run_timing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace aniso::dem::protocol {
namespace {

// The first multiple of `step` above `strain`.
double next_multiple(double strain, double step) {
  return (std::floor(strain / step) + 1) * step;
}

double compressive_strain(const Simulation& simulation) {
  return -simulation.cell().engineering_strain()[0];
}

io::HistoryRow history_row(const Simulation& simulation, const DemConfig& config) {
  const StateMeasures m = simulation.measure();
  const Vec3 strain = simulation.cell().engineering_strain();
  const Mat3& s = m.stress;
  io::HistoryRow row;
  row.step = static_cast<double>(simulation.step_count());
  row.time = simulation.time();
  row.strain_11 = strain[0];
  row.strain_22 = strain[1];
  row.strain_33 = strain[2];
  row.volumetric_strain = simulation.cell().volume() / simulation.cell().reference_lengths().prod() - 1.0;
  row.stress_11 = s(0, 0);
  row.stress_22 = s(1, 1);
  row.stress_33 = s(2, 2);
  row.stress_23 = s(1, 2);
  row.stress_13 = s(0, 2);
  row.stress_12 = s(0, 1);
  row.p = m.mean_stress;
  row.q = m.deviatoric_stress;
  // Paper Fig. 3a plots (sigma_11 - sigma_33)/p with compression positive.
  row.stress_ratio = (-s(0, 0) + s(2, 2)) / m.mean_stress;
  row.void_ratio = m.void_ratio;
  row.coordination = m.coordination;
  row.coordination_no_rattlers = m.coordination_no_rattlers;
  row.n_contacts = static_cast<double>(m.n_contacts);
  row.inertial_number = inertial_number(simulation.control().strain_rate[0], config.particles.d50,
                                        config.particles.density, m.mean_stress);
  row.kinetic_elastic_ratio = m.elastic_energy > 0 ? m.kinetic_energy / m.elastic_energy : 0.0;
  row.servo_error = (m.mean_stress - config.load.mean_stress) / config.load.mean_stress;
  row.axis_orientation_11 = m.axis_orientation(0, 0);
  row.axis_orientation_22 = m.axis_orientation(1, 1);
  row.axis_orientation_33 = m.axis_orientation(2, 2);
  row.unbalanced_force_ratio = m.unbalanced_force_ratio;
  return row;
}

// The history a resumed run continues must be its own and reach the checkpoint: another run's
// history would be truncated and mixed in, and a shorter one would leave a silent gap.
void require_history_continues(const io::History& history, const std::string& run_id, double step,
                               const std::string& output_dir) {
  const std::string path = output_dir + "/history.h5";
  require_input(!run_id.empty(), fmt::format("load --resume: the input is not a checkpoint of a loading run "
                                             "(no run_id), but {} belongs to run {}",
                                             path, history.run_id()));
  require_input(
      history.run_id() == run_id,
      fmt::format("load --resume: {} belongs to loading run '{}', the input checkpoint to run '{}': "
                  "resume into that run's own folder (dem.output_dir)",
                  path, history.run_id(), run_id));
  require_input(
      history.size() > 0 && step > history.column("step").front(),
      fmt::format("load --resume: the input is at the first step of {} ({}), the prepared assembly, not "
                  "a load checkpoint: start a loading without --resume",
                  path, step));
  // covers_step: the step at which the history was written, right after each checkpoint.
  require_input(static_cast<double>(history.covers_step()) >= step,
                fmt::format("load --resume: {} reaches step {}, before the input checkpoint's step {} (the "
                            "run stopped between writing the two): resume from an earlier checkpoint that "
                            "the history reaches",
                            path, history.covers_step(), step));
}

} // namespace

std::string load_checkpoint_path(const std::string& folder, std::size_t index) {
  return fmt::format("{}/load_{:03d}.h5", folder, index);
}

void start_loading(Simulation& simulation, const DemConfig& config) {
  const auto& pc = config.particles;
  const double rate = strain_rate_for_inertial_number(config.load.inertial_number, pc.d50, pc.density,
                                                      config.load.mean_stress);
  simulation.reset_reference_lengths();
  SimulationSettings settings = simulation.settings();
  settings.time_step = io::configured_time_step(config, simulation.critical_time_step());
  settings.control_interval = config.integration.control_interval;
  settings.servo.gain = config.integration.servo_gain;
  settings.material.friction = config.material.friction;
  settings.material.damping_ratio = config.integration.damping;
  settings.global_damping = config.integration.global_damping;
  // The servoed axis must outrun dilatancy but not the assembly's own response.
  settings.servo.max_rate = 20.0 * rate;
  simulation.reconfigure(settings);
  protocol::require_reachable_strain(config.load.final_strain, rate, simulation.settings().time_step, "load");
  simulation.set_control(model::biaxial_plane_strain(simulation.control(), rate, config.load.mean_stress));
}

LoadSummary run_loading(Simulation& simulation, const DemConfig& config, const std::string& output_dir,
                        const h5::Provenance& provenance, const Logger& logger, bool resuming,
                        const std::string& run_id) {
  const auto& load = config.load;
  const auto start_wall = std::chrono::steady_clock::now();
  io::History history;
  if (resuming) {
    history = io::History::read(output_dir);
    require_history_continues(history, run_id, static_cast<double>(simulation.step_count()), output_dir);
    io::require_resume_matches(config, simulation.settings(), simulation.control(),
                               simulation.critical_time_step());
    history.truncate_after_step(static_cast<double>(simulation.step_count()));
  } else {
    history.set_run_id(run_id);
    history.append(history_row(simulation, config));
  }
  const io::CheckpointLabels labels{{}, run_id};
  // Checkpoints and the history written, for the timing table.
  SectionTimes output({"output"});
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
  Phase loading(simulation, "load");
  for (double strain = compressive_strain(simulation); strain < load.final_strain;
       strain = compressive_strain(simulation)) {
    loading.step();
    strain = compressive_strain(simulation);
    progress.update(strain);
    if (load.increment > 0 && strain >= next_increment) {
      // OVAL's loading: each strain increment is followed by a relaxation to a small force
      // imbalance, so the path is a sequence of near-static states (docs/methods/dem.md).
      const Relaxation relaxed =
          relax_to_equilibrium(simulation, increment_tolerances, config.equilibrium.max_steps, logger,
                               fmt::format("relaxation after the increment to strain {:.5g}", strain));
      summary.relaxation_steps += relaxed.steps;
      summary.relaxation_seconds += relaxed.seconds;
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
        summary.relaxation_seconds += relaxed.seconds;
        history.append(history_row(simulation, config)); // the relaxed state, at the same strain
      }
      // The log reports the ratios measured for the file: simulation.equilibrium() is stale
      // when equilibrium is not watched (no relaxation at checkpoints).
      const ScopedSection writing(output, 0);
      const h5::Checkpoint checkpoint = io::write_checkpoint(path, simulation, labels, provenance);
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
    if (simulation.at_control_update() && stop_requested(simulation.comm())) {
      summary.interrupted_checkpoint = output_dir + "/load_interrupted.h5";
      const ScopedSection writing(output, 0);
      io::write_checkpoint(summary.interrupted_checkpoint, simulation, labels, provenance);
      logger->warn("load: stopped on SIGTERM at strain {:.6g} (step {}): wrote {}; continue with --input {} "
                   "--resume",
                   strain, simulation.step_count(), summary.interrupted_checkpoint,
                   summary.interrupted_checkpoint);
      break;
    }
  }
  summary.final_strain = compressive_strain(simulation);
  summary.steps = simulation.step_count() - start_step;
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_wall).count();
  summary.timing = run_timing(simulation.times(), output, summary.wall_seconds, simulation.comm());
  history.set_timing(summary.timing, summary.wall_seconds);
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
  return summary;
}

} // namespace aniso::dem::protocol
