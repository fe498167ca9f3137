// aniso-lbm: D3Q19 lattice Boltzmann permeability tensor of a voxel image (paper section 6).
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/image.hpp"
#include "lbm/config.hpp"
#include "lbm/io.hpp"
#include "lbm/permeability.hpp"
#include "lbm/petsc_session.hpp"

#include <algorithm>
#include <filesystem>

namespace {

int run_lbm(int argc, char** argv, const aniso::mpi::Comm& comm) {
  using namespace aniso;
  CLI::App app{"aniso-lbm: permeability tensor of a voxel image by D3Q19 TRT lattice Boltzmann "
               "(Kuhn, Sun & Wang 2015, section 6)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-lbm");
  std::string input;
  app.add_option("--input", input, "voxel image written by aniso-voxel (HDF5)")->required();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"dem", "fabric", "probe", "voxel", "workflow"});
  const lbm::LbmConfig config = lbm::read_lbm_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-lbm", comm, options.log_level);

  const h5::VoxelImage image = h5::read_voxel_image(input);
  logger->info("input '{}': {}x{}x{} voxels of {:.4g} m, porosity {:.4f}", input, image.shape[0],
               image.shape[1], image.shape[2], image.voxel_size,
               1.0 - static_cast<double>(std::count(image.phase.begin(), image.phase.end(), 1)) /
                         static_cast<double>(image.size()));
  const std::string path = lbm::result_path(config.output_dir, "permeability", input);
  logger->info("configuration is valid: method {}, tau {}, {} precision; result goes to {}",
               lbm::to_string(config.permeability.method), config.permeability.flow.tau,
               config.permeability.flow.precision == lbm::Precision::float32 ? "single" : "double", path);
  if (options.dry_run) return 0;

  const lbm::PetscSession petsc(config.petsc_options);
  const auto provenance =
      h5::make_provenance("aniso-lbm", reader.effective_toml(), cli::join_command_line(argc, argv), comm);
  // A run that diverges or does not converge throws here: nothing is written.
  const lbm::PermeabilityResult result = lbm::compute_permeability(image, config.permeability, comm, logger);
  const double h2 = image.voxel_size * image.voxel_size;
  const Mat3 k = result.k_lattice * h2;
  logger->info("K [m^2] = [{:.4e} {:.4e} {:.4e}; {:.4e} {:.4e} {:.4e}; {:.4e} {:.4e} {:.4e}]", k(0, 0),
               k(0, 1), k(0, 2), k(1, 0), k(1, 1), k(1, 2), k(2, 0), k(2, 1), k(2, 2));
  if (result.method == lbm::Method::periodic_body_force)
    logger->info("symmetry error |K - K^T| / |K| = {:.3e}", result.symmetry_error);
  else
    logger->info("inverse problem (kijsolver) relative residual = {:.3e}", result.inverse_residual);
  if (comm.is_root()) {
    std::filesystem::create_directories(config.output_dir);
    lbm::write_permeability(path, result, image, config.permeability, provenance);
    logger->info("wrote {}", path);
    if (config.write_velocity) {
      const std::string velocity_path = lbm::result_path(config.output_dir, "velocity", input);
      lbm::write_velocity(velocity_path, result, image, provenance);
      logger->info("wrote {} and {}", velocity_path, h5::xdmf_sidecar_path(velocity_path));
    }
  }
  comm.barrier();
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-lbm", run_lbm);
}
