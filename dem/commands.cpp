#include "dem/commands.hpp"

#include "common/error.hpp"
#include "common/keep_clock.hpp"
#include "common/output_folder.hpp"
#include "common/stop_request.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/prepare_pieces.hpp"
#include "dem/io/relaxation_state.hpp"
#include "dem/io/run_folder.hpp"
#include "dem/protocol/hold.hpp"
#include "dem/protocol/load.hpp"
#include "dem/protocol/prepare.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/protocol/relax.hpp"
#include "dem/protocol/run_timing.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>

namespace aniso::dem {
namespace {

using Clock = std::chrono::steady_clock;

h5::Provenance provenance_of(const CommandContext& context, const std::string& subcommand) {
  return h5::make_provenance("aniso-dem " + subcommand, context.reader.effective_toml(), context.command_line,
                             context.comm);
}

// The lines under the timing table, then the halo volume's (collective).
std::vector<std::string> with_halo(std::vector<std::string> lines, const Simulation& simulation) {
  for (std::string& line : protocol::halo_lines(simulation))
    lines.push_back(std::move(line));
  return lines;
}

// A phase of the stepping as a line under the timing table.
std::string phase_line(const std::string& name, std::int64_t steps, std::int64_t total_steps, double seconds,
                       double wall_seconds) {
  return fmt::format(
      "{}: {} of {} steps ({:.1f}%), {:.3f} s ({:.1f}% of the wall time)", name, steps, total_steps,
      total_steps > 0 ? 100.0 * static_cast<double>(steps) / static_cast<double>(total_steps) : 0.0, seconds,
      wall_seconds > 0 ? 100.0 * seconds / wall_seconds : 0.0);
}

// The input's relaxation stopped on SIGTERM, which `command` --resume continues; a fresh run
// refuses such a file, whose control and settings are the relaxation's, not the state's own.
std::optional<io::InterruptedRelaxation> interrupted_input(const std::string& command,
                                                           const std::string& input, bool resume) {
  std::optional<io::InterruptedRelaxation> interrupted = io::read_interrupted_relaxation(input);
  if (resume) {
    require_input(interrupted.has_value() && interrupted->command == command,
                  fmt::format("{} --resume: '{}' holds no interrupted {} (the file a {} stopped on SIGTERM "
                              "writes, <output> with _interrupted before .h5)",
                              command, input, command, command));
  } else {
    require_input(!interrupted.has_value(),
                  fmt::format("{}: '{}' holds a relaxation of aniso-dem {} stopped on SIGTERM: continue "
                              "that with --resume",
                              command, input, interrupted ? interrupted->command : ""));
  }
  return interrupted;
}

// The state of a relax or consolidate in progress, beside `output` (`_interrupted` before the
// extension), from which the same command with --resume continues to the bits of an
// uninterrupted run; returns its path.
std::string write_relaxation_state(const Simulation& simulation, const std::string& command,
                                   const io::CheckpointLabels& labels, const h5::Provenance& provenance,
                                   const std::string& output, const protocol::RelaxationState& state) {
  const std::string path = io::interrupted_path(output);
  io::InterruptedRelaxation interrupted;
  interrupted.command = command;
  interrupted.purpose = command;
  interrupted.state = state;
  io::write_interrupted_checkpoint(path, simulation, labels, provenance, &interrupted);
  return path;
}

// What a relax or consolidate keeps every options.keep_every_minutes (KeepClock): its state, as a
// SIGTERM stop writes it. `kept` is set once it has written.
std::function<void(const protocol::RelaxationState&)>
keep_relaxation(const CommandContext& context, const Simulation& simulation, const std::string& command,
                const io::CheckpointLabels& labels, const h5::Provenance& provenance,
                const std::string& output, const RelaxOptions& options, bool& kept) {
  auto clock = std::make_shared<KeepClock>(60.0 * options.keep_every_minutes);
  return [&, clock, command, output](const protocol::RelaxationState& state) {
    if (!clock->due(simulation.comm())) return;
    const std::string path = write_relaxation_state(simulation, command, labels, provenance, output, state);
    kept = true;
    context.logger->info(
        "{}: kept at step {} ({} steps relaxed) in {}; after a kill, continue with --input {} "
        "--output {} --resume",
        command, simulation.step_count(), state.steps, path, path, output);
  };
}

// A finished relax or consolidate removes the state it kept (a SIGTERM stop's stays with the user).
void remove_kept_state(const CommandContext& context, const std::string& output, bool kept) {
  if (!kept || !context.comm.is_root()) return;
  std::error_code ignored; // a leftover is only an older state of a finished run
  std::filesystem::remove(io::interrupted_path(output), ignored);
}

// A relax or consolidate stopped on SIGTERM: its state beside `output`; exit 143.
int stop_relaxation(const CommandContext& context, const Simulation& simulation, const std::string& command,
                    const io::CheckpointLabels& labels, const h5::Provenance& provenance,
                    const std::string& output, const protocol::RelaxationState& state) {
  const std::string path = write_relaxation_state(simulation, command, labels, provenance, output, state);
  context.logger->warn("{}: stopped on SIGTERM at step {} ({} steps relaxed): wrote {}; continue with "
                       "--input {} --output {} --resume",
                       command, simulation.step_count(), state.steps, path, path, output);
  return static_cast<int>(ExitCode::interrupted);
}

// A prepare stopped on SIGTERM: the pieces it finished stay in its output folder, from which the
// same command with --resume continues; exit 143.
int stop_prepare(const CommandContext& context, const protocol::PrepareStop& stop) {
  const std::vector<std::string> kept = io::prepare_piece_files(context.config.output_dir);
  const bool resumed = context.command_line.ends_with(" --resume") ||
                       context.command_line.find(" --resume ") != std::string::npos;
  context.logger->warn("prepare: stopped on SIGTERM at step {} in the {}: wrote {}; kept in {}: {}; continue "
                       "with the same command and --resume: {}{}",
                       stop.step, stop.piece, stop.kept, context.config.output_dir, fmt::join(kept, ", "),
                       context.command_line, resumed ? "" : " --resume");
  return static_cast<int>(ExitCode::interrupted);
}

} // namespace

int run_prepare(const CommandContext& context, const PrepareOptions& options) {
  const bool resume = options.resume;
  const auto start = Clock::now();
  const DemConfig& config = context.config;
  create_output_folder(config.output_dir);
  const io::RunFolderLock lock(config.output_dir, context.comm); // one writer per folder
  const auto provenance = provenance_of(context, "prepare");
  const std::size_t kept = io::check_prepare_folder(config.output_dir, resume, context.comm);
  if (resume) {
    context.logger->info("prepare --resume: {} pieces kept in {}{}", kept, config.output_dir,
                         kept == 0 ? ": nothing to continue from, preparing from the start" : "");
  }
  const io::PreparePieces pieces(config.output_dir, provenance, context.comm,
                                 60.0 * options.keep_every_minutes);
  install_stop_handler();
  protocol::PreparedAssembly prepared =
      protocol::prepare_assembly(config, context.logger, context.comm, pieces);
  if (prepared.stopped) return stop_prepare(context, *prepared.stopped);
  const std::string path = config.output_dir + "/prepared.h5";
  SectionTimes output({"output"});
  {
    const ScopedSection writing(output, 0);
    io::write_checkpoint(path, *prepared.simulation, {prepared.rng_state, {}}, provenance);
  }
  pieces.remove_all(); // prepared.h5 supersedes them
  const auto& m = prepared.consolidated;
  context.logger->info("wrote {}: e = {:.4f}, Z = {:.3f}, Z without rattlers = {:.3f}, p = {:.4g} Pa", path,
                       m.void_ratio, m.coordination, m.coordination_no_rattlers, m.mean_stress);
  const double wall = seconds_since(start);
  protocol::log_timing(
      context.logger, protocol::run_timing(prepared.simulation->times(), output, wall, context.comm), wall,
      context.comm.size(),
      with_halo({fmt::format(
                    "compaction cycles: {:.3f} s; consolidation: {:.3f} s (both within the sections above)",
                    prepared.compaction_seconds, prepared.consolidation_seconds)},
                *prepared.simulation));
  return 0;
}

int run_load(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
             const LoadOptions& options) {
  const DemConfig& config = context.config;
  const Logger& logger = context.logger;
  create_output_folder(config.output_dir);
  const io::RunFolderLock lock(config.output_dir, context.comm); // one writer per folder
  const auto provenance = provenance_of(context, "load");
  Simulation simulation = io::from_checkpoint(checkpoint, input, context.comm);
  // Its control and settings are a relaxation's, not a state's own (as interrupted_input says).
  require_input(options.resume || !io::read_interrupted_relaxation(input).has_value(),
                fmt::format("load: '{}' holds a relaxation stopped on SIGTERM: continue that run with "
                            "--resume (in its own dem.output_dir), or start from one of its numbered "
                            "checkpoints",
                            input));
  if (!options.resume) {
    protocol::start_loading(simulation,
                            config); // refuses a loading that would never end: before removing anything
    io::clear_for_fresh_loading(config.output_dir, options.overwrite, input, context.comm);
    if (config.load.inertial_number > protocol::quasi_static_inertial_number)
      logger->warn("dem.load.inertial_number = {:g} is above {:g}: the loading is not quasi-static (inertia "
                   "carries part of the stress, the servo lags, the results depend on the rate; "
                   "docs/methods/dem.md, rate convergence)",
                   config.load.inertial_number, protocol::quasi_static_inertial_number);
  }
  require_input(!options.resume || !h5::File::open(input).has_attribute(protocol::relaxed_copy_attribute),
                fmt::format("load --resume: '{}' is a relaxed copy of the loading's state "
                            "(dem.equilibrium.fork_checkpoints), not a state the loading passed through: "
                            "resume from load_resume.h5 in its folder, the loading's own state at the newest "
                            "checkpoint",
                            input));
  require_input(!options.resume || !h5::File::open(input).has_attribute(io::replicated_from_attribute),
                fmt::format("load --resume: '{}' was written by aniso-dem replicate, not by the loading: "
                            "start a new loading from it (load without --resume)",
                            input));
  const std::string run_id = options.resume ? checkpoint.run_id : io::new_run_id(context.comm);
  const std::optional<io::InterruptedRelaxation> interrupted =
      options.resume ? io::read_interrupted_relaxation(input) : std::nullopt;
  install_stop_handler();
  const protocol::LoadSummary summary =
      protocol::run_loading(simulation, config, config.output_dir, provenance, logger, options.resume, run_id,
                            interrupted ? &*interrupted : nullptr, 60.0 * options.keep_every_minutes);
  protocol::log_timing(logger, summary.timing, summary.wall_seconds, context.comm.size(),
                       with_halo({phase_line("relaxation", summary.relaxation_steps, summary.steps,
                                             summary.relaxation_seconds, summary.wall_seconds),
                                  fmt::format("checkpoint copies relaxed: {} steps besides, {:.3f} s",
                                              summary.fork_steps, summary.fork_seconds)},
                                 simulation));
  if (!summary.interrupted_checkpoint.empty()) return static_cast<int>(ExitCode::interrupted);
  // The copies' steps are not the loading's, but they take the same wall time per step.
  const std::int64_t all_steps = summary.steps + summary.fork_steps;
  logger->info(
      "load done: strain {:.4g} in {} steps ({} of them relaxing, after increments and before "
      "checkpoints; {} more relaxing the checkpoints' copies), {:.1f} s wall ({:.3g} particle-steps/s); "
      "peak stress ratio {:.4f} at strain {:.4g}",
      summary.final_strain, summary.steps, summary.relaxation_steps, summary.fork_steps, summary.wall_seconds,
      static_cast<double>(all_steps) * static_cast<double>(simulation.n_particles()) / summary.wall_seconds,
      summary.peak_stress_ratio, summary.peak_strain);
  return 0;
}

int run_hold(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
             const HoldOptions& options) {
  const auto start = Clock::now();
  Simulation simulation = io::from_checkpoint(checkpoint, input, context.comm);
  const protocol::HoldReport report = protocol::hold_fixed_cell(simulation, options.steps, context.logger);
  const protocol::HoldSample& first = report.samples.front();
  const protocol::HoldSample& last = report.samples.back();
  context.logger->info("hold of '{}' for {} steps at fixed cell: p {:.6g} -> {:.6g} Pa (drift {:+.3e}, "
                       "largest {:.3e}); q {:.6g} -> "
                       "{:.6g} Pa; unbalanced-force ratio {:.2e} -> {:.2e}; kinetic/elastic {:.2e} -> {:.2e}",
                       input, options.steps, first.mean_stress, last.mean_stress, report.final_drift(),
                       report.largest_drift, first.deviatoric_stress, last.deviatoric_stress,
                       first.unbalanced_force_ratio, last.unbalanced_force_ratio, first.kinetic_elastic_ratio,
                       last.kinetic_elastic_ratio);
  SectionTimes output({"output"});
  if (!options.csv.empty() && context.comm.is_root()) {
    const ScopedSection writing(output, 0);
    protocol::write_hold_csv(report, options.csv);
  }
  const double wall = seconds_since(start);
  protocol::log_timing(context.logger, protocol::run_timing(simulation.times(), output, wall, context.comm),
                       wall, context.comm.size(), protocol::halo_lines(simulation));
  if (options.max_drift > 0 && report.largest_drift > options.max_drift) {
    throw ConvergenceError(fmt::format("hold: p drifted by {:.3e} of its start, above --max-drift {:.3e}",
                                       report.largest_drift, options.max_drift));
  }
  return 0;
}

int run_consolidate(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
                    const std::string& output, const RelaxOptions& options) {
  namespace fs = std::filesystem;
  const auto start = Clock::now();
  require_input(
      !fs::exists(output),
      fmt::format("consolidate: --output '{}' exists: give a new file (nothing is overwritten)", output));
  const fs::path folder = fs::path(output).parent_path();
  if (!folder.empty()) create_output_folder(folder.string());
  const auto provenance = provenance_of(context, "consolidate");
  const DemConfig& config = context.config;
  const auto interrupted = interrupted_input("consolidate", input, options.resume);
  Simulation simulation = io::from_checkpoint(checkpoint, input, context.comm);
  const double p_before = mean_stress_compression_positive(simulation.stress());
  const StateMeasures before = simulation.measure();
  // The rate of prepare's own consolidation (dem.prepare.inertial_number).
  const double rate =
      strain_rate_for_inertial_number(config.prepare.inertial_number, config.particles.d50,
                                      config.particles.density, config.prepare.confining_pressure);
  if (!interrupted) protocol::with_loading_contacts(simulation, config, rate);
  install_stop_handler();
  const io::CheckpointLabels labels{checkpoint.rng_state, {}};
  bool kept = false;
  const protocol::Relaxation relaxed =
      protocol::consolidate(simulation, config, rate, context.logger,
                            {.stoppable = true,
                             .resume = interrupted ? &interrupted->state : nullptr,
                             .keep = keep_relaxation(context, simulation, "consolidate", labels, provenance,
                                                     output, options, kept)});
  if (relaxed.interrupted)
    return stop_relaxation(context, simulation, "consolidate", labels, provenance, output,
                           *relaxed.interrupted);
  simulation.watch_equilibrium(false);
  SectionTimes writing_times({"output"});
  {
    const ScopedSection writing(writing_times, 0);
    io::write_checkpoint(output, simulation, labels, provenance);
  }
  remove_kept_state(context, output, kept);
  const StateMeasures m = simulation.measure();
  context.logger->info(
      "consolidate of '{}': {} steps ({} verifying, {} windows left), p {:.6g} -> {:.6g} Pa, "
      "e {:.5f} -> {:.5f}, Z {:.3f} -> {:.3f}, Z without rattlers {:.3f} ({} rattlers); wrote {}",
      input, relaxed.steps, relaxed.verifying_steps, relaxed.windows_left, p_before, m.mean_stress,
      before.void_ratio, m.void_ratio, before.coordination, m.coordination, m.coordination_no_rattlers,
      m.n_rattlers, output);
  const double wall = seconds_since(start);
  protocol::log_timing(context.logger,
                       protocol::run_timing(simulation.times(), writing_times, wall, context.comm), wall,
                       context.comm.size(), protocol::halo_lines(simulation));
  return 0;
}

// Relaxes a checkpoint with its own loading control (strain axes held, the mean-stress servo on)
// to the verified equilibrium of dem.equilibrium and writes it to `output`: the static state that
// the probes' stiffness assumes (paper section 4), from a checkpoint written at OVAL's looser
// increment tolerance (docs/paper-comparison.md, section 4).
int run_relax(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
              const std::string& output, const RelaxOptions& options) {
  namespace fs = std::filesystem;
  const auto start = Clock::now();
  require_input(
      fs::weakly_canonical(input) != fs::weakly_canonical(output),
      fmt::format("relax: --output '{}' is the input: write the relaxed state to a new file, so that "
                  "the loaded one is kept",
                  output));
  const fs::path folder = fs::path(output).parent_path();
  if (!folder.empty()) create_output_folder(folder.string());
  const auto provenance = provenance_of(context, "relax");
  const auto interrupted = interrupted_input("relax", input, options.resume);
  Simulation simulation = io::from_checkpoint(checkpoint, input, context.comm);
  const auto void_ratio = [&] { return simulation.cell().volume() / simulation.solid_volume() - 1.0; };
  const double p_before = mean_stress_compression_positive(simulation.stress());
  const double e_before = void_ratio();
  install_stop_handler();
  const io::CheckpointLabels labels{checkpoint.rng_state, checkpoint.run_id};
  bool kept = false;
  const protocol::Relaxation relaxed = protocol::relax_to_equilibrium(
      simulation, context.config.equilibrium, context.config.equilibrium.max_steps, context.logger, "relax",
      {.stoppable = true,
       .resume = interrupted ? &interrupted->state : nullptr,
       .keep = keep_relaxation(context, simulation, "relax", labels, provenance, output, options, kept)});
  if (relaxed.interrupted)
    return stop_relaxation(context, simulation, "relax", labels, provenance, output, *relaxed.interrupted);
  SectionTimes writing_times({"output"});
  h5::Checkpoint result;
  {
    const ScopedSection writing(writing_times, 0);
    result = io::write_checkpoint(output, simulation, labels, provenance, io::relaxation_record(relaxed));
  }
  remove_kept_state(context, output, kept);
  context.logger->info(
      "relax of '{}': {} steps ({} verifying, {} windows left), p {:.6g} -> {:.6g} Pa, void ratio {:.5f} -> "
      "{:.5f}, unbalanced-force ratio {:.2e} -> {:.2e}, kinetic/elastic {:.2e}; wrote {}",
      input, relaxed.steps, relaxed.verifying_steps, relaxed.windows_left, p_before,
      mean_stress_compression_positive(simulation.stress()), e_before, void_ratio(),
      checkpoint.unbalanced_force_ratio, result.unbalanced_force_ratio, result.kinetic_elastic_ratio, output);
  const double wall = seconds_since(start);
  protocol::log_timing(context.logger,
                       protocol::run_timing(simulation.times(), writing_times, wall, context.comm), wall,
                       context.comm.size(), protocol::halo_lines(simulation));
  return 0;
}

} // namespace aniso::dem
