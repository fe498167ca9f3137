// aniso-lbm: D3Q19 lattice Boltzmann permeability tensor of a voxel image (paper section 6).
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/content_hash.hpp"
#include "common/h5/image.hpp"
#include "common/output_folder.hpp"
#include "common/stop_request.hpp"
#include "common/timer.hpp"
#include "lbm/config.hpp"
#include "lbm/force_choice.hpp"
#include "lbm/io.hpp"
#include "lbm/permeability.hpp"
#include "lbm/petsc_session.hpp"
#include "lbm/resume.hpp"

#include <algorithm>
#include <filesystem>

namespace {

void log_tensor(const aniso::lbm::PermeabilityResult& result, double voxel_size,
                const aniso::Logger& logger) {
  const aniso::Mat3 k = result.k_lattice * voxel_size * voxel_size;
  logger->info("K [m^2] = [{:.4e} {:.4e} {:.4e}; {:.4e} {:.4e} {:.4e}; {:.4e} {:.4e} {:.4e}]", k(0, 0),
               k(0, 1), k(0, 2), k(1, 0), k(1, 1), k(1, 2), k(2, 0), k(2, 1), k(2, 2));
  if (result.method == aniso::lbm::Method::periodic_body_force)
    logger->info("symmetry error |K - K^T| / |K| = {:.3e}", result.symmetry_error);
  else
    logger->info("inverse problem (kijsolver) relative residual = {:.3e}", result.inverse_residual);
}

/// `aniso-lbm collect`: the tensor from three direction files, which must agree on image and settings.
int collect_directions(const std::string& input, const aniso::lbm::LbmConfig& config,
                       const aniso::cli::CommonOptions& options, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  const Logger logger = make_logger("aniso-lbm", comm, options.log_level);
  std::vector<lbm::DirectionFile> files;
  std::vector<lbm::FlowRun> runs;
  for (int axis = 0; axis < 3; ++axis) {
    const std::string path = lbm::direction_path(config.output_dir, input, axis);
    files.push_back(lbm::read_direction(path));
    const lbm::DirectionFile& d = files.back();
    const lbm::DirectionFile& first = files.front();
    require_file(d.axis == axis, fmt::format("{}: holds direction {}, expected {}", path, d.axis, axis));
    const std::string differing = lbm::differing_settings(d, first);
    require_file(differing.empty(),
                 fmt::format("{}: {} differ(s) from direction 0's ({}); rerun the "
                             "directions with one configuration on one image",
                             path, differing, lbm::direction_path(config.output_dir, input, 0)));
    runs.insert(runs.end(), d.runs.begin(), d.runs.end());
  }
  const lbm::DirectionFile& first = files.front();
  lbm::PermeabilityResult result = lbm::assemble_permeability(first.method, runs, first.settings);
  result.porosity = first.porosity;
  result.fluid_voxels = first.fluid_voxels;
  log_tensor(result, first.image.voxel_size, logger);
  const std::string path = lbm::result_path(config.output_dir, "permeability", input);
  const auto provenance =
      h5::make_provenance("aniso-lbm collect", "", "aniso-lbm collect --input " + input, comm);
  if (comm.is_root()) {
    lbm::write_permeability(path, result, first.image, first.settings, provenance);
    logger->info("wrote {}", path);
  }
  comm.barrier();
  return 0;
}

int run_lbm(int argc, char** argv, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  const auto start = SectionTimes::Clock::now();
  CLI::App app{"aniso-lbm: permeability tensor of a voxel image by D3Q19 TRT lattice Boltzmann "
               "(Kuhn, Sun & Wang 2015, section 6)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-lbm");
  std::string input;
  int direction = -1;
  app.add_option("--input", input, "voxel image written by aniso-voxel (HDF5)");
  app.add_option("--direction", direction,
                 "run only the flows along x_(D+1), D = 0, 1, 2, and write permeability_<stem>_directionD.h5 "
                 "(job arrays; then `collect`)")
      ->check(CLI::Range(0, 2));
  auto* collect = app.add_subcommand("collect", "assemble permeability_<stem>.h5 from the three "
                                                "permeability_<stem>_directionD.h5 of --direction runs");
  collect->add_option("--input", input, "the voxel image the direction runs used (names the files)");
  collect->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"dem", "fabric", "probe", "voxel", "workflow"});
  const lbm::LbmConfig config = lbm::read_lbm_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  require_input(!input.empty(), "--input is required (the voxel image, HDF5)");
  const Logger logger = make_logger("aniso-lbm", comm, options.log_level);

  if (collect->parsed()) return collect_directions(input, config, options, comm);
  const h5::VoxelImage image = h5::read_voxel_image(input);
  logger->info("input '{}': {}x{}x{} voxels of {:.4g} m, porosity {:.4f}", input, image.shape[0],
               image.shape[1], image.shape[2], image.voxel_size,
               1.0 - static_cast<double>(std::count(image.phase.begin(), image.phase.end(), 1)) /
                         static_cast<double>(image.size()));
  const std::string path = lbm::result_path(config.output_dir, "permeability", input);
  logger->info("configuration is valid: method {}, tau {}, {} precision; result goes to {}",
               lbm::to_string(config.permeability.method),
               config.permeability.flow.tau > 0 ? fmt::format("{}", config.permeability.flow.tau)
                                                : "automatic",
               config.permeability.flow.precision == lbm::Precision::float32 ? "single" : "double", path);
  if (options.dry_run) return 0;

  // tau and the force are resolved once per image, so that direction files of one image agree on them.
  lbm::PermeabilitySettings settings = config.permeability;
  settings.flow.tau = lbm::resolve_tau(image, settings, logger);
  settings.body_force = lbm::resolve_body_force(image, settings, logger);
  const lbm::PetscSession petsc(config.petsc_options);
  const std::string command = cli::join_command_line(argc, argv);
  const auto provenance = h5::make_provenance("aniso-lbm", reader.effective_toml(), command, comm);
  // SLURM's SIGTERM before a time limit: the flows poll it at their convergence checks (lbm/flow.hpp).
  install_stop_handler();
  // Direction files record the image file they ran on, so that a resumed run reuses only its own.
  const std::string image_hash = h5::content_hash(input, comm);
  if (direction >= 0) {
    // A run that diverges or does not converge throws here: nothing is written.
    std::vector<lbm::FlowRun> runs;
    try {
      runs = lbm::run_direction(image, settings, direction, comm, logger);
    } catch (const Interrupted& stop) {
      logger->warn("{}: nothing written; the same command runs the flows along x{} anew: {}", stop.what(),
                   direction + 1, command);
      return static_cast<int>(ExitCode::interrupted);
    }
    const std::string direction_file = lbm::direction_path(config.output_dir, input, direction);
    if (comm.is_root()) {
      create_output_folder(config.output_dir);
      lbm::write_direction(direction_file, runs, direction, image, image_hash, settings, provenance);
      logger->info("wrote {}", direction_file);
    }
    comm.barrier();
    logger->info(wall_time_line(seconds_since(start), comm.size()));
    return 0;
  }
  // Velocity fields are not kept in direction files: with them every direction runs each time.
  const bool resumable = !config.write_velocity;
  const lbm::DirectionRuns finished = resumable ? lbm::finished_directions(config.output_dir, input, image,
                                                                           image_hash, settings, comm, logger)
                                                : lbm::DirectionRuns{};
  // A run that diverges or does not converge throws here: nothing more is written.
  lbm::DirectionRuns runs = lbm::run_directions(image, settings, comm, logger, finished);
  if (std::any_of(runs.begin(), runs.end(), [](const auto& axis) { return !axis; })) {
    if (resumable) {
      if (comm.is_root()) create_output_folder(config.output_dir);
      lbm::keep_directions(config.output_dir, input, image, image_hash, settings, runs, finished, provenance,
                           comm);
    }
    logger->warn("{}", lbm::stop_message(config.output_dir, input, runs, resumable, command));
    comm.barrier();
    return static_cast<int>(ExitCode::interrupted);
  }
  const lbm::PermeabilityResult result = lbm::permeability_of(image, settings, std::move(runs));
  log_tensor(result, image.voxel_size, logger);
  if (comm.is_root()) {
    create_output_folder(config.output_dir);
    lbm::write_permeability(path, result, image, settings, provenance);
    lbm::remove_finished(config.output_dir, input, finished, comm);
    logger->info("wrote {}", path);
    if (config.write_velocity) {
      const std::string velocity_path = lbm::result_path(config.output_dir, "velocity", input);
      lbm::write_velocity(velocity_path, result, image, provenance);
      logger->info("wrote {} and {}", velocity_path, h5::xdmf_sidecar_path(velocity_path));
    }
  }
  comm.barrier();
  logger->info(wall_time_line(seconds_since(start), comm.size()));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-lbm", run_lbm);
}
