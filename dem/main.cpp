// aniso-dem: periodic-cell DEM. `prepare` builds a dense isotropic assembly,
// `load` runs biaxial plane strain at constant mean stress from it.
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"
#include "dem/io.hpp"
#include "dem/load.hpp"
#include "dem/prepare.hpp"

#include <filesystem>

namespace {

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
  std::string input;
  bool resume = false;
  load->add_option("--input", input, "prepared assembly, or with --resume a load checkpoint (HDF5)")
      ->required();
  load->add_flag("--resume", resume, "continue a loading run from one of its checkpoints");
  prepare->fallthrough();
  load->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"fabric", "probe", "voxel", "lbm", "workflow"});
  const dem::DemConfig config = dem::read_dem_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-dem", comm, options.log_level);

  std::optional<h5::Checkpoint> checkpoint;
  if (load->parsed()) {
    checkpoint = h5::read_checkpoint(input, comm);
    logger->info("input '{}': {} particles, {} contacts, step {}", input, checkpoint->particles.size(),
                 checkpoint->contacts.size(), checkpoint->step);
  }
  logger->info("configuration is valid ({} particles, seed {})", config.particles.count, config.seed);
  if (options.dry_run) return 0;

  std::filesystem::create_directories(config.output_dir);
  const std::string command = cli::join_command_line(argc, argv);
  if (prepare->parsed()) {
    const auto provenance = h5::make_provenance("aniso-dem prepare", reader.effective_toml(), command, comm);
    dem::PreparedAssembly prepared = dem::prepare_assembly(config, logger, comm);
    const std::string path = config.output_dir + "/prepared.h5";
    h5::write_checkpoint(path,
                         dem::to_checkpoint(*prepared.simulation, config.particles.d50, prepared.rng_state),
                         provenance, comm);
    logger->info("wrote {}: e = {:.4f}, Z = {:.3f}, Z without rattlers = {:.3f}, p = {:.4g} Pa", path,
                 prepared.consolidated.void_ratio, prepared.consolidated.coordination,
                 prepared.consolidated.coordination_no_rattlers, prepared.consolidated.mean_stress);
    return 0;
  }
  const auto provenance = h5::make_provenance("aniso-dem load", reader.effective_toml(), command, comm);
  dem::Simulation simulation = dem::from_checkpoint(*checkpoint, input, comm);
  if (!resume) dem::start_loading(simulation, config);
  const dem::LoadSummary summary =
      dem::run_loading(simulation, config, config.output_dir, provenance, logger, resume);
  logger->info(
      "load done: strain {:.4g} in {} steps, {:.1f} s wall ({:.3g} particle-steps/s); peak stress ratio "
      "{:.4f} at strain {:.4g}",
      summary.final_strain, summary.steps, summary.wall_seconds,
      static_cast<double>(summary.steps) * static_cast<double>(simulation.n_particles()) /
          summary.wall_seconds,
      summary.peak_stress_ratio, summary.peak_strain);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-dem", run_dem);
}
