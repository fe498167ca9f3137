#include "dem/protocol/load.hpp"

#include "common/error.hpp"
#include "common/keep_clock.hpp"
#include "common/stop_request.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/history.hpp"
#include "dem/io/parameters.hpp"
#include "dem/io/relaxation_state.hpp"
#include "dem/measures.hpp"
#include "dem/protocol/phase.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/protocol/relax.hpp"
#include "dem/protocol/run_timing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace aniso::dem::protocol {
namespace {

// The first multiple of `step` above `strain`.
double next_multiple(double strain, double step) {
  return (std::floor(strain / step) + 1) * step;
}

double compressive_strain(const Simulation& simulation) {
  return -simulation.cell().engineering_strain()[0];
}

// A quasi-static run's strain as its schedule made it: the end of an increment (a multiple of the
// increment, or a checkpoint strain), of which the cell's own strain is the rounding.
double nominal_strain(const LoadConfig& load, double strain) {
  for (const double checkpoint_strain : load.checkpoint_strains)
    if (std::abs(strain - checkpoint_strain) <= 1e-9 * load.increment) return checkpoint_strain;
  const double multiple = std::round(strain / load.increment) * load.increment;
  return std::abs(strain - multiple) <= 1e-9 * load.increment ? multiple : strain;
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
                               double strain, double history_interval, const std::string& output_dir) {
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
  // The rows themselves, not only the attribute that claims them: the last row at or before the
  // checkpoint must be less than one history_interval of strain behind it (1e-6 of an interval
  // absorbs the cell's rounding of a quasi-static run's nominal strains).
  const auto& steps = history.column("step");
  const auto& strains = history.column("strain_11");
  std::size_t last = 0;
  for (std::size_t r = 0; r < steps.size() && steps[r] <= step; ++r)
    last = r;
  const double slack = 1e-6 * history_interval;
  const double next_row = next_multiple(-strains[last] + slack, history_interval);
  require_input(steps[last] == step || strain <= next_row + slack,
                fmt::format("load --resume: {} holds rows up to strain {:.6g} (step {}) before the input "
                            "checkpoint's strain {:.6g} (step {}), although its covers_step claims step {}: "
                            "rows are missing (the history was replaced or edited); resume from a "
                            "checkpoint that its rows reach, or start the loading anew",
                            path, -strains[last], steps[last], strain, step, history.covers_step()));
}

} // namespace

std::string load_checkpoint_path(const std::string& folder, std::size_t index) {
  return fmt::format("{}/load_{:03d}.h5", folder, index);
}

std::string load_resume_path(const std::string& folder) {
  return folder + "/load_resume.h5";
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
  settings.global_damping_spin_factor = config.integration.global_damping_spin_factor;
  // The servoed axis must outrun dilatancy but not the assembly's own response.
  settings.servo.max_rate = 20.0 * rate;
  simulation.reconfigure(settings);
  protocol::require_reachable_strain(config.load.final_strain, rate, simulation.settings().time_step, "load");
  simulation.set_control(model::biaxial_plane_strain(simulation.control(), rate, config.load.mean_stress));
}

namespace {

// Where the loading's events fall, each from the strain alone, so that a resumed run meets them
// where the uninterrupted one did: the next history row (every history_interval), the end of
// the next increment (at multiples of load.increment and at every checkpoint strain, so that
// each checkpoint is a relaxed state) and the next checkpoint.
class StrainSchedule {
public:
  StrainSchedule(const LoadConfig& load, double strain)
      : load_(load), next_history_(next_multiple(strain, load.history_interval)),
        next_increment_(load.increment > 0 ? increment_end(strain) : 0) {
    while (next_checkpoint_ < load.checkpoint_strains.size() &&
           load.checkpoint_strains[next_checkpoint_] <= strain)
      ++next_checkpoint_;
  }
  [[nodiscard]] bool increment_ends(double strain) const {
    return load_.increment > 0 && strain >= next_increment_;
  }
  void increment_relaxed(double strain) { next_increment_ = increment_end(strain); }
  /// Where the increment under way ends.
  [[nodiscard]] double next_increment() const { return next_increment_; }
  [[nodiscard]] bool history_due(double strain) const {
    return strain >= next_history_ || strain >= load_.final_strain;
  }
  void history_written(double strain) {
    while (next_history_ <= strain)
      next_history_ += load_.history_interval;
  }
  [[nodiscard]] bool checkpoint_due(double strain) const {
    return next_checkpoint_ < load_.checkpoint_strains.size() &&
           strain >= load_.checkpoint_strains[next_checkpoint_];
  }
  [[nodiscard]] std::size_t checkpoint() const { return next_checkpoint_; }
  void checkpoint_written() { ++next_checkpoint_; }
  /// Where the history and checkpoints stood, for a relaxation stopped on SIGTERM: a resume takes
  /// them back exactly (its events at the relaxation's strain are still ahead of it).
  [[nodiscard]] double next_history() const { return next_history_; }
  void resume(double next_history, std::size_t next_checkpoint) {
    next_history_ = next_history;
    next_checkpoint_ = next_checkpoint;
  }

private:
  // The next multiple k x increment above the strain (k an integer: a strain on a multiple, as a
  // quasi-static run's is, goes on to the next one), or the next checkpoint strain if nearer.
  [[nodiscard]] double increment_end(double strain) const {
    double end = (std::floor(strain / load_.increment + 1e-9) + 1) * load_.increment;
    for (const double checkpoint_strain : load_.checkpoint_strains)
      if (checkpoint_strain > strain) end = std::min(end, checkpoint_strain);
    if (load_.quasi_static) end = std::min(end, load_.final_strain); // no affine step past the end
    return end;
  }

  const LoadConfig& load_;
  double next_history_;
  double next_increment_;
  std::size_t next_checkpoint_ = 0;
};

// One loading run: the simulation, its history and files, and what the summary counts.
class LoadingRun {
public:
  LoadingRun(Simulation& simulation, const DemConfig& config, const std::string& output_dir,
             const h5::Provenance& provenance, const Logger& logger, const std::string& run_id)
      : simulation_(simulation), config_(config), output_dir_(output_dir), provenance_(provenance),
        logger_(logger), labels_{{}, run_id} {}

  // `memory`: what an interrupted relaxation gives back, the loading's own control and settings.
  void start_history(bool resuming, const PhaseMemory* memory);
  // Athermal quasi-static loading: the strain to `end` in one affine step of the cell (axis 1 to
  // its length there, axis 2 held, axis 3 servoed), then the minimisation of relax_increment.
  void affine_increment(double end, Phase& loading);
  // OVAL's loading: each strain increment is followed by a relaxation to a small force
  // imbalance, so the path is a sequence of near-static states (docs/methods/dem.md).
  // Each relaxation returns false when it stopped on SIGTERM (kept for write_interrupted); a
  // relaxation interrupted before (`resume`) continues where it stopped.
  bool relax_increment(double strain, const RelaxationState* resume, const StrainSchedule& schedule);
  void append_history_row() { history_.append(history_row(simulation_, config_)); }
  bool write_checkpoint(double strain, const RelaxationState* resume, const StrainSchedule& schedule);
  void write_state(std::size_t index, double strain, const Simulation& state);
  // SIGTERM (a SLURM time limit or scancel) ends the run at a control update, every rank at
  // the same step, with a checkpoint from which --resume continues exactly: the increments,
  // history rows and checkpoints ahead all follow from the strain, and a relaxation stopped in
  // from its /relaxation group (dem/io/relaxation_state.hpp).
  void write_interrupted(double strain, const std::string& why = "stopped on SIGTERM");
  // The same file and the history, written between relaxations without stopping (the keep
  // clock): what --resume continues from after a kill. Removed when the run ends.
  void keep_state(double strain);
  bool relax(Simulation& simulation, const EquilibriumConfig& tolerances, const std::string& label,
             const RelaxationState* resume, io::InterruptedRelaxation where);
  // dem.equilibrium.fork_checkpoints: a copy of the state relaxed and written; false when it
  // stopped on SIGTERM, the copy dropped (a resume relaxes a new one from the same state).
  bool write_fork(std::size_t index, double strain, const StrainSchedule& schedule);
  LoadSummary finish(std::int64_t start_step, double wall_seconds);

private:
  Simulation& simulation_;
  const DemConfig& config_;
  const std::string& output_dir_;
  const h5::Provenance& provenance_;
  const Logger& logger_;
  const io::CheckpointLabels labels_;
  io::History history_;
  SectionTimes output_{{"output"}}; // checkpoints and the history written, for the timing table
  LoadSummary summary_;
  std::optional<io::InterruptedRelaxation> interrupted_; // a relaxation stopped on SIGTERM
  bool kept_ = false;                                    // keep_state wrote load_interrupted.h5
  Relaxation last_relaxation_;                           // recorded in a checkpoint relaxed for it
};

void LoadingRun::start_history(bool resuming, const PhaseMemory* memory) {
  if (resuming) {
    history_ = io::History::read(output_dir_);
    const auto step = static_cast<double>(simulation_.step_count());
    require_history_continues(history_, labels_.run_id, step, compressive_strain(simulation_),
                              config_.load.history_interval, output_dir_);
    io::require_resume_matches(config_, memory != nullptr ? memory->settings : simulation_.settings(),
                               memory != nullptr ? memory->control : simulation_.control(),
                               simulation_.critical_time_step());
    history_.truncate_after_step(step);
  } else {
    history_.set_run_id(labels_.run_id);
    append_history_row();
  }
}

void LoadingRun::affine_increment(double end, Phase& loading) {
  const model::CellControl loading_control = simulation_.control();
  const PeriodicCell& cell = simulation_.cell();
  model::CellControl jump = loading_control;
  jump.target[0] = ((1.0 - end) * cell.reference_lengths()[0] / cell.lengths()[0] - 1.0) /
                   simulation_.settings().time_step;
  // The step is an affine map, not a motion: contact damping would read the jump's rate
  // (increment / time step) on every branch vector as a relative velocity and kick each
  // particle with an impulse that grows with the increment (the whole increment's viscous
  // impulse in one step), so it is off for this step.
  const SimulationSettings settings = simulation_.settings();
  SimulationSettings undamped = settings;
  undamped.material.damping_ratio = 0.0;
  simulation_.reconfigure(undamped);
  simulation_.set_control(jump);
  loading.step();
  simulation_.set_control(loading_control);
  simulation_.reconfigure(settings);
}

// The purpose of an interrupted file whose checkpoint copy was being relaxed: the file holds the
// loading's state, and a resume relaxes a new copy of it (the same bits: the copy starts from it).
constexpr const char* fork_purpose = "checkpoint_fork";

// Which of the load's relaxations is under way, for a resume to continue it in its place.
io::InterruptedRelaxation where_in_load(const std::string& purpose, double strain,
                                        const StrainSchedule& schedule) {
  io::InterruptedRelaxation where;
  where.command = "load";
  where.purpose = purpose;
  where.strain = strain;
  where.next_history = schedule.next_history();
  where.next_checkpoint = static_cast<std::int64_t>(schedule.checkpoint());
  return where;
}

bool LoadingRun::relax(Simulation& simulation, const EquilibriumConfig& tolerances, const std::string& label,
                       const RelaxationState* resume, io::InterruptedRelaxation where) {
  const Relaxation relaxed =
      relax_to_equilibrium(simulation, tolerances, config_.equilibrium.max_steps, logger_, label,
                           {.stoppable = true, .resume = resume, .keep = {}});
  last_relaxation_ = relaxed;
  // A resumed relaxation's steps before the stop were counted by the run that stopped.
  const std::int64_t earlier = resume != nullptr ? resume->steps : 0;
  summary_.relaxation_steps += relaxed.steps - earlier;
  summary_.relaxation_seconds += relaxed.seconds;
  if (!relaxed.interrupted) return true;
  where.state = *relaxed.interrupted;
  interrupted_ = std::move(where);
  return false;
}

bool LoadingRun::relax_increment(double strain, const RelaxationState* resume,
                                 const StrainSchedule& schedule) {
  EquilibriumConfig tolerances = config_.equilibrium;
  tolerances.tolerance = config_.load.increment_tolerance;
  tolerances.verify_steps = 0;
  return relax(simulation_, tolerances,
               fmt::format("relaxation after the increment to strain {:.5g}", strain), resume,
               where_in_load("increment", strain, schedule));
}

bool LoadingRun::write_checkpoint(double strain, const RelaxationState* resume,
                                  const StrainSchedule& schedule) {
  const std::size_t index = schedule.checkpoint();
  if (config_.equilibrium.fork_checkpoints) return write_fork(index, strain, schedule);
  if (config_.equilibrium.at_checkpoints) {
    if (!relax(simulation_, config_.equilibrium, fmt::format("relaxation before checkpoint {}", index),
               resume, where_in_load("checkpoint", strain, schedule)))
      return false;
    append_history_row(); // the relaxed state, at the same strain
  }
  write_state(index, strain, simulation_);
  return true;
}

bool LoadingRun::write_fork(std::size_t index, double strain, const StrainSchedule& schedule) {
  // The copy shares nothing the loading reads on: relaxing it leaves the loading's bits alone.
  Simulation copy = simulation_;
  const std::int64_t before = summary_.relaxation_steps;
  const double seconds_before = summary_.relaxation_seconds;
  // What the interrupted file holds, whether a SIGTERM or the step budget ends the copy's
  // relaxation: the loading's own state, from which a resume relaxes a new copy.
  const auto keep_loading = [&] {
    interrupted_ = where_in_load(fork_purpose, strain, schedule);
    interrupted_->state.memory = {simulation_.control(), simulation_.settings(),
                                  simulation_.watching_equilibrium()};
  };
  bool relaxed = false;
  try {
    relaxed = relax(copy, config_.equilibrium, fmt::format("relaxation of checkpoint {}'s copy", index),
                    nullptr, where_in_load(fork_purpose, strain, schedule));
  } catch (const ConvergenceError& error) {
    // Every rank fails at the same step (the budget is counted alike), so all write the file.
    keep_loading();
    write_interrupted(strain, fmt::format("checkpoint {}'s copy did not reach equilibrium", index));
    if (simulation_.comm().is_root()) history_.write(output_dir_, provenance_, simulation_.step_count());
    throw ConvergenceError(fmt::format("{}. The loading's own state is kept in {}: --resume it with a larger "
                                       "dem.equilibrium.max_steps or a looser tolerance to relax a new copy",
                                       error.what(), summary_.interrupted_checkpoint));
  }
  summary_.fork_steps += summary_.relaxation_steps - before;
  summary_.fork_seconds += summary_.relaxation_seconds - seconds_before;
  summary_.relaxation_steps = before;
  summary_.relaxation_seconds = seconds_before;
  if (!relaxed) {
    keep_loading(); // the copy's progress is dropped
    return false;
  }
  write_state(index, strain, copy);
  // After the history, which therefore always reaches the resume point: a kill between the two
  // leaves the previous checkpoint's state there, from which the history is truncated.
  io::write_checkpoint(load_resume_path(output_dir_), simulation_, labels_, provenance_);
  return true;
}

void LoadingRun::write_state(std::size_t index, double strain, const Simulation& state) {
  const std::string path = load_checkpoint_path(output_dir_, index);
  // The log reports the ratios measured for the file: simulation.equilibrium() is stale
  // when equilibrium is not watched (no relaxation at checkpoints).
  const ScopedSection writing(output_, 0);
  const auto relaxation = config_.equilibrium.at_checkpoints ? io::relaxation_record(last_relaxation_)
                                                             : std::function<void(h5::File&)>{};
  const bool copy = &state != &simulation_;
  const std::int64_t loading_step = simulation_.step_count();
  const h5::Checkpoint checkpoint =
      io::write_checkpoint(path, state, labels_, provenance_, [&](h5::File& file) {
        if (relaxation) relaxation(file);
        if (copy) file.write_attribute<std::int64_t>(relaxed_copy_attribute, loading_step);
      });
  if (simulation_.comm().is_root()) history_.write(output_dir_, provenance_, simulation_.step_count());
  logger_->info("checkpoint {} at strain {:.6g}: {} (p = {:.4g} Pa, servo error {:.2e}, unbalanced-force "
                "ratio {:.2e}, kinetic/elastic {:.2e})",
                index, strain, path, mean_stress_compression_positive(state.stress()), state.servo_error(),
                checkpoint.unbalanced_force_ratio, checkpoint.kinetic_elastic_ratio);
  summary_.checkpoints.push_back(path);
}

void LoadingRun::write_interrupted(double strain, const std::string& why) {
  summary_.interrupted_checkpoint = output_dir_ + "/load_interrupted.h5";
  const ScopedSection writing(output_, 0);
  io::write_interrupted_checkpoint(summary_.interrupted_checkpoint, simulation_, labels_, provenance_,
                                   interrupted_ ? &*interrupted_ : nullptr);
  logger_->warn("load: {} at strain {:.6g} (step {}): wrote {}; continue with --input {} --resume", why,
                strain, simulation_.step_count(), summary_.interrupted_checkpoint,
                summary_.interrupted_checkpoint);
}

void LoadingRun::keep_state(double strain) {
  const std::string path = output_dir_ + "/load_interrupted.h5";
  {
    const ScopedSection writing(output_, 0);
    io::write_interrupted_checkpoint(path, simulation_, labels_, provenance_, nullptr);
    // After the state, so that the history always reaches it (workflows/campaign.py load-input
    // takes the file only when the history is newer).
    if (simulation_.comm().is_root()) history_.write(output_dir_, provenance_, simulation_.step_count());
  }
  kept_ = true;
  logger_->info(
      "load: kept at strain {:.6g} (step {}) in {}; after a kill, continue with --input {} --resume", strain,
      simulation_.step_count(), path, path);
}

LoadSummary LoadingRun::finish(std::int64_t start_step, double wall_seconds) {
  summary_.final_strain = compressive_strain(simulation_);
  summary_.steps = simulation_.step_count() - start_step;
  summary_.wall_seconds = wall_seconds;
  summary_.timing = run_timing(simulation_.times(), output_, wall_seconds, simulation_.comm());
  history_.set_timing(summary_.timing, wall_seconds);
  if (simulation_.comm().is_root()) history_.write(output_dir_, provenance_, simulation_.step_count());
  simulation_.comm().barrier(); // the history is on disk before anyone reports success
  std::error_code ignored;      // a kept file left behind is only older than the history
  if (kept_ && summary_.interrupted_checkpoint.empty() && simulation_.comm().is_root())
    std::filesystem::remove(output_dir_ + "/load_interrupted.h5", ignored); // the finished run supersedes it
  const auto& ratio = history_.column("stress_ratio");
  const auto& strain_11 = history_.column("strain_11");
  for (std::size_t r = 0; r < ratio.size(); ++r) {
    if (ratio[r] > summary_.peak_stress_ratio) {
      summary_.peak_stress_ratio = ratio[r];
      summary_.peak_strain = -strain_11[r];
    }
  }
  return summary_;
}

} // namespace

LoadSummary run_loading(Simulation& simulation, const DemConfig& config, const std::string& output_dir,
                        const h5::Provenance& provenance, const Logger& logger, bool resuming,
                        const std::string& run_id, const io::InterruptedRelaxation* interrupted,
                        double keep_every_seconds) {
  const auto& load = config.load;
  KeepClock keep_clock(keep_every_seconds);
  const auto start_wall = std::chrono::steady_clock::now();
  const std::int64_t start_step = simulation.step_count();
  LoadingRun run(simulation, config, output_dir, provenance, logger, run_id);
  // A run stopped inside a relaxation continues it, then what followed it in that pass of the loop.
  const RelaxationState* pending = resuming && interrupted != nullptr ? &interrupted->state : nullptr;
  require_input(pending == nullptr || interrupted->command == "load",
                fmt::format("load --resume: the input holds an interrupted '{}' relaxation, not a load's: "
                            "continue it with aniso-dem {} --resume",
                            pending != nullptr ? interrupted->command : "",
                            pending != nullptr ? interrupted->command : ""));
  const bool pending_fork = pending != nullptr && interrupted->purpose == fork_purpose;
  const bool pending_checkpoint =
      pending != nullptr && (interrupted->purpose == "checkpoint" || pending_fork);
  require_input(pending_fork == config.equilibrium.fork_checkpoints || !pending_checkpoint,
                pending_fork
                    ? "load --resume: the input stopped while relaxing a checkpoint's copy, so its run "
                      "had dem.equilibrium.fork_checkpoints = true; resume it with the same setting"
                    : "load --resume: the input stopped while relaxing the loading's own state before "
                      "a checkpoint, so its run had dem.equilibrium.fork_checkpoints = false; resume "
                      "it with the same setting");
  run.start_history(resuming, pending != nullptr ? &pending->memory : nullptr);
  // A quasi-static run's events follow its schedule's strains, which the cell's strain rounds.
  const auto strain_now = [&] {
    const double strain = compressive_strain(simulation);
    return load.quasi_static ? nominal_strain(load, strain) : strain;
  };
  StrainSchedule schedule(load, strain_now());
  if (pending != nullptr)
    schedule.resume(interrupted->next_history, static_cast<std::size_t>(interrupted->next_checkpoint));
  logger->info(
      "load: rate {:.4g} /s, inertial number {:.3g}, from strain {:.5g} to {:.5g}, time step {:.3g} s",
      -simulation.control().target[0], load.inertial_number, compressive_strain(simulation),
      load.final_strain, simulation.settings().time_step);
  Progress progress(logger, "load", load.final_strain, 10.0, {}, compressive_strain(simulation));
  Phase loading(simulation, "load");
  // The relaxation stopped in continues once, in its place, at the strain it stopped at (also
  // past the final strain: the last checkpoint's relaxation may be the one stopped in).
  const auto resumed = [&pending]() {
    const RelaxationState* state = pending;
    pending = nullptr;
    return state;
  };
  for (double strain = strain_now(); strain < load.final_strain || pending != nullptr;
       strain = strain_now()) {
    if (pending_checkpoint && pending != nullptr) {
      strain = interrupted->strain; // the increment and the history row before it are done
    } else if (load.quasi_static) {
      const double end = pending != nullptr ? interrupted->strain : schedule.next_increment();
      if (pending == nullptr) run.affine_increment(end, loading);
      if (!run.relax_increment(end, resumed(), schedule)) {
        run.write_interrupted(end);
        break;
      }
      schedule.increment_relaxed(end);
      strain = end;
    } else {
      if (pending == nullptr) {
        loading.step();
        strain = compressive_strain(simulation);
      } else {
        strain = interrupted->strain;
      }
      if (pending != nullptr || schedule.increment_ends(strain)) {
        if (!run.relax_increment(strain, resumed(), schedule)) {
          run.write_interrupted(strain);
          break;
        }
        schedule.increment_relaxed(strain);
      }
    }
    if (pending == nullptr) {
      progress.update(strain);
      if (schedule.history_due(strain)) {
        run.append_history_row();
        schedule.history_written(strain);
      }
    }
    if (schedule.checkpoint_due(strain)) {
      if (!run.write_checkpoint(strain, resumed(), schedule)) {
        run.write_interrupted(strain);
        break;
      }
      schedule.checkpoint_written();
    }
    if (load.quasi_static || simulation.at_control_update()) {
      if (keep_clock.due(simulation.comm())) run.keep_state(strain);
      if (stop_requested(simulation.comm(), simulation.step_count())) {
        run.write_interrupted(strain);
        break;
      }
    }
  }
  return run.finish(start_step,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start_wall).count());
}

} // namespace aniso::dem::protocol
