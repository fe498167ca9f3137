// aniso-dem: periodic-cell DEM. `prepare` builds a dense isotropic assembly,
// `load` runs biaxial plane strain at constant mean stress from it, `hold` measures
// how static a checkpoint is and `relax` makes a loosely relaxed checkpoint static;
// `import` and `export` carry assemblies from and to other codes and ParaView.
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/memory.hpp"
#include "common/output_folder.hpp"
#include "common/stop_request.hpp"
#include "dem/config.hpp"
#include "dem/interop/transfer_commands.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/checkpoint_keys.hpp"
#include "dem/io/parameters.hpp"
#include "dem/io/run_folder.hpp"
#include "dem/io/settings.hpp"
#include "dem/protocol/hold.hpp"
#include "dem/protocol/load.hpp"
#include "dem/protocol/prepare.hpp"
#include "dem/protocol/relax.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace {

int run_hold(const aniso::h5::Checkpoint& checkpoint, const std::string& input, std::int64_t steps,
             const std::string& csv, double max_drift, const aniso::Logger& logger,
             const aniso::mpi::Comm& comm) {
  using namespace aniso;
  dem::Simulation simulation = dem::io::from_checkpoint(checkpoint, input, comm);
  const dem::protocol::HoldReport report = dem::protocol::hold_fixed_cell(simulation, steps, logger);
  const dem::protocol::HoldSample& first = report.samples.front();
  const dem::protocol::HoldSample& last = report.samples.back();
  logger->info("hold of '{}' for {} steps at fixed cell: p {:.6g} -> {:.6g} Pa (drift {:+.3e}, largest "
               "{:.3e}); q {:.6g} -> {:.6g} Pa; unbalanced-force ratio {:.2e} -> {:.2e}; kinetic/elastic "
               "{:.2e} -> {:.2e}",
               input, steps, first.mean_stress, last.mean_stress, report.final_drift(), report.largest_drift,
               first.deviatoric_stress, last.deviatoric_stress, first.unbalanced_force_ratio,
               last.unbalanced_force_ratio, first.kinetic_elastic_ratio, last.kinetic_elastic_ratio);
  if (!csv.empty() && comm.is_root()) dem::protocol::write_hold_csv(report, csv);
  if (max_drift > 0 && report.largest_drift > max_drift) {
    throw ConvergenceError(fmt::format("hold: p drifted by {:.3e} of its start, above --max-drift {:.3e}",
                                       report.largest_drift, max_drift));
  }
  return 0;
}

// Relaxes a checkpoint with its own loading control (strain axes held, the mean-stress servo on)
// to the verified equilibrium of dem.equilibrium and writes it to `output`: the static state that
// the probes' stiffness assumes (paper section 4), from a checkpoint written at OVAL's looser
// increment tolerance (docs/paper-comparison.md, section 4).
int run_relax(const aniso::h5::Checkpoint& checkpoint, const std::string& input, const std::string& output,
              const aniso::dem::DemConfig& config, const aniso::h5::Provenance& provenance,
              const aniso::Logger& logger, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  namespace fs = std::filesystem;
  require_input(
      fs::weakly_canonical(input) != fs::weakly_canonical(output),
      fmt::format("relax: --output '{}' is the input: write the relaxed state to a new file, so that "
                  "the loaded one is kept",
                  output));
  const fs::path folder = fs::path(output).parent_path();
  if (!folder.empty()) create_output_folder(folder.string());
  dem::Simulation simulation = dem::io::from_checkpoint(checkpoint, input, comm);
  const auto void_ratio = [&] { return simulation.cell().volume() / simulation.solid_volume() - 1.0; };
  const double p_before = mean_stress_compression_positive(simulation.stress());
  const double e_before = void_ratio();
  const dem::protocol::Relaxation relaxed = dem::protocol::relax_to_equilibrium(
      simulation, config.equilibrium, config.equilibrium.max_steps, logger, "relax");
  h5::Checkpoint result = dem::io::to_checkpoint(simulation, config.particles.d50, checkpoint.rng_state);
  result.run_id = checkpoint.run_id;
  h5::write_checkpoint(output, result, provenance, comm);
  logger->info(
      "relax of '{}': {} steps, p {:.6g} -> {:.6g} Pa, void ratio {:.5f} -> {:.5f}, unbalanced-force "
      "ratio {:.2e} -> {:.2e}, kinetic/elastic {:.2e}; wrote {}",
      input, relaxed.steps, p_before, mean_stress_compression_positive(simulation.stress()), e_before,
      void_ratio(), checkpoint.unbalanced_force_ratio, result.unbalanced_force_ratio,
      result.kinetic_elastic_ratio, output);
  return 0;
}

int run_dem(int argc, char** argv, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  CLI::App app{"aniso-dem: periodic-cell DEM of spheres and ovoids (Kuhn, Sun & Wang 2015, section 2)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-dem");
  app.require_subcommand(1);
  auto* prepare = app.add_subcommand("prepare", "build a dense isotropic assembly consolidated to p0 "
                                                "(writes <output_dir>/prepared.h5)");
  auto* load =
      app.add_subcommand("load", "biaxial plane strain at constant mean stress from a prepared assembly "
                                 "(writes <output_dir>/load_NNN.h5 and history.h5)");
  auto* hold = app.add_subcommand("hold", "hold a checkpoint's cell fixed for --steps time steps and report "
                                          "the drift of p (a static state keeps its stress)");
  auto* relax = app.add_subcommand(
      "relax", "relax a checkpoint at its own loading control to the verified equilibrium of "
               "dem.equilibrium and write it to --output (a static state for the probes)");
  auto* import = app.add_subcommand(
      "import", "a sphere assembly from a LAMMPS/LIGGGHTS data file or YADE's text export, with the "
                "tangential forces of a contact dump, as a checkpoint (--output)");
  auto* export_ = app.add_subcommand(
      "export", "a checkpoint as a LAMMPS data file (and contact dump), or as XDMF for ParaView "
                "(particles and force chains)");
  dem::interop::ImportOptions import_options;
  import->add_option("--input", import_options.input, "LAMMPS data file, or YADE text export")->required();
  import->add_option("--format", import_options.format, "lammps (default) or yade")
      ->check(CLI::IsMember({"lammps", "yade"}));
  import->add_option("--cell", import_options.cell, "yade: the periodic cell's lengths LX,LY,LZ [m]")
      ->expected(3)
      ->delimiter(',');
  import->add_option("--contacts", import_options.contacts,
                     "LAMMPS `dump local` file with each contact's tangential force (keeps a static state "
                     "static)");
  import->add_option(
      "--contact-columns", import_options.contact_columns,
      "1-based columns I,J,T of the two ids and the first tangential force component in "
      "--contacts; T < 0: force on the second id (aniso's export: 1,2,6; LIGGGHTS pair/gran/local "
      "id force_tangential: 1,2,4)");
  import->add_option("--output", import_options.output, "checkpoint to write (HDF5; must not exist)")
      ->required();
  import->fallthrough();
  dem::interop::ExportOptions export_options;
  export_->add_option("--input", export_options.input, "checkpoint (HDF5)")->required();
  export_->add_option("--format", export_options.format, "lammps (default) or xdmf")
      ->check(CLI::IsMember({"lammps", "xdmf"}));
  export_->add_option("--output", export_options.output, "LAMMPS data file, or .xmf for xdmf")->required();
  export_->add_option(
      "--contacts", export_options.contacts,
      "lammps: also write every contact as a `dump local` file (id1 id2 fnx fny fnz ftx fty ftz)");
  export_->fallthrough();
  std::string input;
  std::string output;
  relax->add_option("--input", input, "checkpoint to relax (HDF5)")->required();
  relax->add_option("--output", output, "relaxed checkpoint to write (HDF5; not the input)")->required();
  relax->fallthrough();
  bool resume = false;
  std::int64_t hold_steps = 0;
  std::string hold_csv;
  double max_drift = 0;
  hold->add_option("--input", input, "checkpoint to hold (HDF5)")->required();
  hold->add_option("--steps", hold_steps, "time steps to hold")->required()->check(CLI::Range(1, 2000000000));
  hold->add_option("--csv", hold_csv, "write p, q and the equilibrium ratios at every control update here");
  hold->add_option("--max-drift", max_drift,
                   "exit 5 if |p - p_start| / p_start exceeds this at any sample (0: report only)")
      ->check(CLI::NonNegativeNumber);
  hold->fallthrough();
  load->add_option("--input", input, "prepared assembly, or with --resume a load checkpoint (HDF5)")
      ->required();
  bool overwrite = false;
  load->add_flag("--resume", resume, "continue a loading run from one of its checkpoints");
  load->add_flag(
      "--overwrite", overwrite,
      "replace the loading run already in dem.output_dir (its history and load_NNN.h5 are removed)");
  prepare->fallthrough();
  load->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"fabric", "probe", "voxel", "lbm", "workflow"});
  dem::DemConfig config = dem::io::read_dem_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-dem", comm, options.log_level);

  std::optional<h5::Checkpoint> checkpoint;
  if (load->parsed() || hold->parsed() || relax->parsed()) {
    checkpoint = h5::read_checkpoint(input, comm);
    logger->info("input '{}': {} particles, {} contacts, step {}", input, checkpoint->particles.size(),
                 checkpoint->contacts.size(), checkpoint->step);
    dem::io::adopt_checkpoint_values(config, reader, *checkpoint, input);
  }
  require_input(!(resume && overwrite), "load: --resume continues the run in dem.output_dir and --overwrite "
                                        "replaces it; give one of them");
  // The particle arrays alone hold 26 doubles per particle; contacts, neighbour lists and the
  // checkpoint copy at least as much again, so 512 bytes is a floor, not an estimate.
  constexpr double min_bytes_per_particle = 512;
  require_memory(min_bytes_per_particle * static_cast<double>(config.particles.count) / comm.size(),
                 fmt::format("dem: {} particles on {} rank(s) (at least {:.0f} bytes each)",
                             config.particles.count, comm.size(), min_bytes_per_particle),
                 "lower dem.particles.count or spread the run over more nodes");
  logger->info("configuration is valid ({} particles, seed {})", config.particles.count, config.seed);
  if (options.dry_run) return 0;

  if (export_->parsed()) return dem::interop::run_export(export_options, logger, comm);
  if (hold->parsed()) return run_hold(*checkpoint, input, hold_steps, hold_csv, max_drift, logger, comm);
  const std::string command = cli::join_command_line(argc, argv);
  if (import->parsed())
    return dem::interop::run_import(import_options, config, reader, command, logger, comm);
  if (relax->parsed()) {
    const auto provenance = h5::make_provenance("aniso-dem relax", reader.effective_toml(), command, comm);
    return run_relax(*checkpoint, input, output, config, provenance, logger, comm);
  }
  create_output_folder(config.output_dir);
  const dem::io::RunFolderLock lock(config.output_dir, comm); // one writer per folder
  if (prepare->parsed()) {
    const auto provenance = h5::make_provenance("aniso-dem prepare", reader.effective_toml(), command, comm);
    dem::protocol::PreparedAssembly prepared = dem::protocol::prepare_assembly(config, logger, comm);
    const std::string path = config.output_dir + "/prepared.h5";
    h5::write_checkpoint(
        path, dem::io::to_checkpoint(*prepared.simulation, config.particles.d50, prepared.rng_state),
        provenance, comm);
    logger->info("wrote {}: e = {:.4f}, Z = {:.3f}, Z without rattlers = {:.3f}, p = {:.4g} Pa", path,
                 prepared.consolidated.void_ratio, prepared.consolidated.coordination,
                 prepared.consolidated.coordination_no_rattlers, prepared.consolidated.mean_stress);
    return 0;
  }
  const auto provenance = h5::make_provenance("aniso-dem load", reader.effective_toml(), command, comm);
  dem::Simulation simulation = dem::io::from_checkpoint(*checkpoint, input, comm);
  if (!resume) {
    dem::protocol::start_loading(simulation,
                                 config); // refuses a loading that would never end: before removing anything
    dem::io::clear_for_fresh_loading(config.output_dir, overwrite, input, comm);
    if (config.load.inertial_number > dem::io::quasi_static_inertial_number)
      logger->warn("dem.load.inertial_number = {:g} is above {:g}: the loading is not quasi-static (inertia "
                   "carries part of the stress, the servo lags, the results depend on the rate; "
                   "docs/methods/dem.md, rate convergence)",
                   config.load.inertial_number, dem::io::quasi_static_inertial_number);
  }
  const std::string run_id = resume ? checkpoint->run_id : dem::io::new_run_id(comm);
  install_stop_handler();
  const dem::protocol::LoadSummary summary =
      dem::protocol::run_loading(simulation, config, config.output_dir, provenance, logger, resume, run_id);
  if (!summary.interrupted_checkpoint.empty()) return static_cast<int>(ExitCode::interrupted);
  logger->info("load done: strain {:.4g} in {} steps ({} of them relaxing, after increments and before "
               "checkpoints), {:.1f} s wall ({:.3g} "
               "particle-steps/s); peak stress ratio {:.4f} at strain {:.4g}",
               summary.final_strain, summary.steps, summary.relaxation_steps, summary.wall_seconds,
               static_cast<double>(summary.steps) * static_cast<double>(simulation.n_particles()) /
                   summary.wall_seconds,
               summary.peak_stress_ratio, summary.peak_strain);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-dem", run_dem);
}
