#include "voxel/stage.hpp"

#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/content_hash.hpp"
#include "common/h5/image.hpp"
#include "common/memory.hpp"
#include "common/output_folder.hpp"
#include "common/timer.hpp"
#include "voxel/config.hpp"
#include "voxel/digitize.hpp"
#include "voxel/void_analysis.hpp"
#include "voxel/void_results.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <omp.h>

namespace aniso::voxel {
namespace {

constexpr double bytes_per_voxel = 21;

} // namespace

int run_voxel_stage(int argc, char** argv, const mpi::Comm& comm) {
  const auto run_start = SectionTimes::Clock::now();
  CLI::App app{
      "aniso-voxel: digitize a checkpoint and measure the void space by ball, spar and disk openings "
      "(Kuhn, Sun & Wang 2015, section 3)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-voxel");
  std::string input;
  app.add_option("--input", input, "checkpoint (HDF5) to digitize")->required();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"dem", "fabric", "probe", "lbm", "workflow"});
  const VoxelConfig config = read_voxel_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-voxel", comm, options.log_level);
  if (config.threads > 0) omp_set_num_threads(config.threads);

  const h5::Checkpoint checkpoint = h5::read_checkpoint(input, comm);
  const double d50 = h5::parameter(checkpoint, h5::parameter_name::d50, input);
  if (!(std::isfinite(d50) && d50 > 0))
    throw FileError(fmt::format("{}: /parameters d50 = {} m is not a positive length", input, d50));
  const auto shape = grid_shape(checkpoint.cell.lengths, d50, config.resolution);
  const double voxels =
      static_cast<double>(shape[0]) * static_cast<double>(shape[1]) * static_cast<double>(shape[2]);
  // Per rank: the image (1 byte), four distance maps and a work map (4 bytes each) per voxel.
  const double needed = bytes_per_voxel * voxels;
  require_memory(needed,
                 fmt::format("voxel: {} x {} x {} voxels at resolution {} (per rank)", shape[0], shape[1],
                             shape[2], config.resolution),
                 "lower voxel.resolution");
  logger->info(
      "input '{}': {} particles, {} contacts; image {} x {} x {} = {} voxels at {} voxels per d50 (about "
      "{:.2f} GiB per rank)",
      input, checkpoint.particles.size(), checkpoint.contacts.size(), shape[0], shape[1], shape[2],
      shape[0] * shape[1] * shape[2], config.resolution, needed / 1073741824.0);
  require_file(checkpoint.particles.size() != 0,
               fmt::format("{}: /particles holds no particle: there is no void space to measure", input));
  if (options.dry_run) return 0;

  const auto start = std::chrono::steady_clock::now();
  const std::string stem = std::filesystem::path(input).stem().string();
  const std::string image_path = config.output_dir + "/image_" + stem + ".h5";
  const std::string hash = h5::content_hash(input);
  const h5::VoxelImage image = digitize_checkpoint(checkpoint, input, hash, config.resolution);
  const double digitize_seconds = seconds_since(start);
  // A fully solid or fully void image has no void morphology: every median would be NaN or inf.
  const auto solid_voxels = static_cast<std::size_t>(std::count(image.phase.begin(), image.phase.end(), 1));
  if (solid_voxels == 0 || solid_voxels == image.phase.size()) {
    throw NumericalError(fmt::format(
        "voxel: the image of '{}' at {} voxels per d50 is {} (the void morphology is undefined); {}", input,
        config.resolution, solid_voxels == 0 ? "all void" : "all solid",
        solid_voxels == 0 ? "raise voxel.resolution so that the particles are resolved"
                          : "the particles fill the cell: check the checkpoint"));
  }
  create_output_folder(config.output_dir);
  const std::string command = cli::join_command_line(argc, argv);
  const auto provenance = h5::make_provenance("aniso-voxel", reader.effective_toml(), command, comm);
  if (config.write_image && comm.is_root()) h5::write_voxel_image(image_path, image, provenance);

  const auto analysis_start = std::chrono::steady_clock::now();
  VoidAnalysisOptions analysis_options;
  analysis_options.radius_step = config.radius_step;
  const VoidAnalysis analysis = analyze_voids(Grid{image.shape}, image.phase, analysis_options, comm);
  const double analysis_seconds = seconds_since(analysis_start);

  VoidContext context;
  context.source = input;
  context.source_hash = hash;
  context.image = config.write_image ? image_path : "";
  context.d50 = d50;
  context.resolution = config.resolution;
  for (int a = 0; a < 3; ++a)
    context.voxel_edges[a] =
        checkpoint.cell.lengths[a] / static_cast<double>(image.shape[static_cast<std::size_t>(a)]);
  context.shape = image.shape;
  context.n_particles = static_cast<std::int64_t>(checkpoint.particles.size());
  context.n_contacts = static_cast<std::int64_t>(checkpoint.contacts.size());
  const std::string results = config.output_dir + "/voids_" + stem;
  if (comm.is_root()) write_void_results(results + ".h5", results + ".csv", analysis, context, provenance);
  comm.barrier();

  const double porosity = static_cast<double>(analysis.void_voxels) / static_cast<double>(analysis.voxels);
  logger->info(
      "porosity {:.4f}; medians [d50]: ball {:.4f}; spar {:.4f} {:.4f} {:.4f}; disk {:.4f} {:.4f} {:.4f}",
      porosity, analysis.ball.median * image.voxel_size / d50,
      analysis.spar[0].median * context.voxel_edges[0] / d50,
      analysis.spar[1].median * context.voxel_edges[1] / d50,
      analysis.spar[2].median * context.voxel_edges[2] / d50,
      analysis.disk[0].median * image.voxel_size / d50, analysis.disk[1].median * image.voxel_size / d50,
      analysis.disk[2].median * image.voxel_size / d50);
  logger->info(
      "Euler characteristic of the void: image {} (26-void/6-solid); counted 1 + Np - Nc = {}, on the "
      "torus Np - Nc = {}",
      analysis.euler, counted_euler_bounded(context), counted_euler_torus(context));
  logger->info(
      "wrote {}.h5 and .csv{}; digitize {:.2f} s, analysis {:.2f} s on {} rank(s) x {} thread(s); peak "
      "RSS {:.0f} MiB (rank 0)",
      results, config.write_image ? " and " + image_path : "", digitize_seconds, analysis_seconds,
      comm.size(), omp_get_max_threads(), static_cast<double>(peak_resident_bytes()) / 1048576.0);
  logger->info(wall_time_line(seconds_since(run_start), comm.size()));
  return 0;
}

} // namespace aniso::voxel
