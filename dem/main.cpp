// aniso-dem: periodic-cell DEM. `prepare` builds a dense isotropic assembly,
// `load` runs biaxial plane strain at constant mean stress from it.
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"

namespace {

int run_dem(int argc, char** argv, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  CLI::App app{"aniso-dem: periodic-cell DEM of spheres and ovoids (Kuhn, Sun & Wang 2015, section 2)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-dem");
  app.require_subcommand(1);
  auto* prepare = app.add_subcommand("prepare", "build a dense isotropic assembly consolidated to p0");
  auto* load = app.add_subcommand("load", "biaxial plane strain at constant mean stress from a prepared assembly");
  std::string input;
  load->add_option("--input", input, "prepared assembly (checkpoint HDF5)")->required();
  prepare->fallthrough();
  load->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"fabric", "probe", "voxel", "lbm", "workflow"});
  const dem::DemConfig config = dem::read_dem_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-dem", comm, options.log_level);

  if (load->parsed()) {
    const auto checkpoint = h5::read_checkpoint(input, comm);
    logger->info("input '{}' is a valid checkpoint: {} particles, {} contacts, step {}", input,
                 checkpoint.particles.size(), checkpoint.contacts.size(), checkpoint.step);
  }
  logger->info("configuration is valid ({} particles, seed {})", config.particles.count, config.seed);
  if (options.dry_run) return 0;
  throw Error(ExitCode::internal_error, "aniso-dem: the DEM engine is not built yet (issue 3); only --dry-run "
                                        "validation is available in this version");
}

} // namespace

int main(int argc, char** argv) { return aniso::cli::run(argc, argv, "aniso-dem", run_dem); }
