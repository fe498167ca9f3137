#include "dem/commands.hpp"

#include "common/error.hpp"
#include "common/output_folder.hpp"
#include "common/stop_request.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/run_folder.hpp"
#include "dem/protocol/hold.hpp"
#include "dem/protocol/load.hpp"
#include "dem/protocol/prepare.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/protocol/relax.hpp"
#include "dem/protocol/run_timing.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>

namespace aniso::dem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

h5::Provenance provenance_of(const CommandContext& context, const std::string& subcommand) {
  return h5::make_provenance("aniso-dem " + subcommand, context.reader.effective_toml(), context.command_line,
                             context.comm);
}

// A phase of the stepping as a line under the timing table.
std::string phase_line(const std::string& name, std::int64_t steps, std::int64_t total_steps, double seconds,
                       double wall_seconds) {
  return fmt::format(
      "{}: {} of {} steps ({:.1f}%), {:.3f} s ({:.1f}% of the wall time)", name, steps, total_steps,
      total_steps > 0 ? 100.0 * static_cast<double>(steps) / static_cast<double>(total_steps) : 0.0, seconds,
      wall_seconds > 0 ? 100.0 * seconds / wall_seconds : 0.0);
}

} // namespace

int run_prepare(const CommandContext& context) {
  const auto start = Clock::now();
  const DemConfig& config = context.config;
  create_output_folder(config.output_dir);
  const io::RunFolderLock lock(config.output_dir, context.comm); // one writer per folder
  const auto provenance = provenance_of(context, "prepare");
  protocol::PreparedAssembly prepared = protocol::prepare_assembly(config, context.logger, context.comm);
  const std::string path = config.output_dir + "/prepared.h5";
  SectionTimes output({"output"});
  {
    const ScopedSection writing(output, 0);
    io::write_checkpoint(path, *prepared.simulation, {prepared.rng_state, {}}, provenance);
  }
  const auto& m = prepared.consolidated;
  context.logger->info("wrote {}: e = {:.4f}, Z = {:.3f}, Z without rattlers = {:.3f}, p = {:.4g} Pa", path,
                       m.void_ratio, m.coordination, m.coordination_no_rattlers, m.mean_stress);
  const double wall = seconds_since(start);
  protocol::log_timing(
      context.logger, protocol::run_timing(prepared.simulation->times(), output, wall, context.comm), wall,
      context.comm.size(),
      {fmt::format("compaction cycles: {:.3f} s; consolidation: {:.3f} s (both within the sections above)",
                   prepared.compaction_seconds, prepared.consolidation_seconds)});
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
  const std::string run_id = options.resume ? checkpoint.run_id : io::new_run_id(context.comm);
  install_stop_handler();
  const protocol::LoadSummary summary = protocol::run_loading(simulation, config, config.output_dir,
                                                              provenance, logger, options.resume, run_id);
  protocol::log_timing(logger, summary.timing, summary.wall_seconds, context.comm.size(),
                       {phase_line("relaxation", summary.relaxation_steps, summary.steps,
                                   summary.relaxation_seconds, summary.wall_seconds)});
  if (!summary.interrupted_checkpoint.empty()) return static_cast<int>(ExitCode::interrupted);
  logger->info(
      "load done: strain {:.4g} in {} steps ({} of them relaxing, after increments and before "
      "checkpoints), {:.1f} s wall ({:.3g} particle-steps/s); peak stress ratio {:.4f} at strain {:.4g}",
      summary.final_strain, summary.steps, summary.relaxation_steps, summary.wall_seconds,
      static_cast<double>(summary.steps) * static_cast<double>(simulation.n_particles()) /
          summary.wall_seconds,
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
                       wall, context.comm.size());
  if (options.max_drift > 0 && report.largest_drift > options.max_drift) {
    throw ConvergenceError(fmt::format("hold: p drifted by {:.3e} of its start, above --max-drift {:.3e}",
                                       report.largest_drift, options.max_drift));
  }
  return 0;
}

int run_consolidate(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
                    const std::string& output) {
  namespace fs = std::filesystem;
  const auto start = Clock::now();
  require_input(
      !fs::exists(output),
      fmt::format("consolidate: --output '{}' exists: give a new file (nothing is overwritten)", output));
  const fs::path folder = fs::path(output).parent_path();
  if (!folder.empty()) create_output_folder(folder.string());
  const auto provenance = provenance_of(context, "consolidate");
  const DemConfig& config = context.config;
  Simulation simulation = io::from_checkpoint(checkpoint, input, context.comm);
  const double p_before = mean_stress_compression_positive(simulation.stress());
  const StateMeasures before = simulation.measure();
  // The rate of prepare's own consolidation (dem.prepare.inertial_number).
  const double rate =
      strain_rate_for_inertial_number(config.prepare.inertial_number, config.particles.d50,
                                      config.particles.density, config.prepare.confining_pressure);
  protocol::with_loading_contacts(simulation, config, rate);
  const protocol::Relaxation relaxed = protocol::consolidate(simulation, config, rate, context.logger);
  simulation.watch_equilibrium(false);
  SectionTimes writing_times({"output"});
  {
    const ScopedSection writing(writing_times, 0);
    io::write_checkpoint(output, simulation, {checkpoint.rng_state, {}}, provenance);
  }
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
                       context.comm.size());
  return 0;
}

// Relaxes a checkpoint with its own loading control (strain axes held, the mean-stress servo on)
// to the verified equilibrium of dem.equilibrium and writes it to `output`: the static state that
// the probes' stiffness assumes (paper section 4), from a checkpoint written at OVAL's looser
// increment tolerance (docs/paper-comparison.md, section 4).
int run_relax(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
              const std::string& output) {
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
  Simulation simulation = io::from_checkpoint(checkpoint, input, context.comm);
  const auto void_ratio = [&] { return simulation.cell().volume() / simulation.solid_volume() - 1.0; };
  const double p_before = mean_stress_compression_positive(simulation.stress());
  const double e_before = void_ratio();
  const protocol::Relaxation relaxed = protocol::relax_to_equilibrium(
      simulation, context.config.equilibrium, context.config.equilibrium.max_steps, context.logger, "relax");
  SectionTimes writing_times({"output"});
  h5::Checkpoint result;
  {
    const ScopedSection writing(writing_times, 0);
    result = io::write_checkpoint(output, simulation, {checkpoint.rng_state, checkpoint.run_id}, provenance);
  }
  context.logger->info(
      "relax of '{}': {} steps ({} verifying, {} windows left), p {:.6g} -> {:.6g} Pa, void ratio {:.5f} -> "
      "{:.5f}, unbalanced-force ratio {:.2e} -> {:.2e}, kinetic/elastic {:.2e}; wrote {}",
      input, relaxed.steps, relaxed.verifying_steps, relaxed.windows_left, p_before,
      mean_stress_compression_positive(simulation.stress()), e_before, void_ratio(),
      checkpoint.unbalanced_force_ratio, result.unbalanced_force_ratio, result.kinetic_elastic_ratio, output);
  const double wall = seconds_since(start);
  protocol::log_timing(context.logger,
                       protocol::run_timing(simulation.times(), writing_times, wall, context.comm), wall,
                       context.comm.size());
  return 0;
}

} // namespace aniso::dem
