#include "common/stage_stub.hpp"

#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <filesystem>

namespace aniso::cli {

int run_pending_stage(int argc, char** argv, const mpi::Comm& comm, const PendingStage& stage) {
  CLI::App app{stage.program + ": " + stage.description};
  CommonOptions options;
  add_common_options(app, options, stage.program);
  std::string input;
  app.add_option("--input", input,
                 stage.input_kind == InputKind::checkpoint ? "checkpoint written by aniso-dem (HDF5)"
                                                           : "input file (HDF5)")
      ->required();
  if (auto code = parse(app, argc, argv, comm)) return *code;

  const auto source = load_config(options);
  config::Reader reader(source.table, source.name);
  std::vector<std::string> others{"dem", "fabric", "probe", "voxel", "lbm", "workflow"};
  others.erase(std::remove(others.begin(), others.end(), stage.section), others.end());
  reader.tolerate_sections(others);
  if (finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger(stage.program, comm, options.log_level);

  if (stage.input_kind == InputKind::checkpoint) {
    const auto checkpoint = h5::read_checkpoint(input, comm);
    logger->info("input '{}' is a valid checkpoint: {} particles, {} contacts", input,
                 checkpoint.particles.size(), checkpoint.contacts.size());
  } else {
    require_file(std::filesystem::is_regular_file(input), fmt::format("input '{}' does not exist", input));
    require_file(H5Fis_hdf5(input.c_str()) > 0, fmt::format("input '{}' is not an HDF5 file", input));
    logger->info("input '{}' is an HDF5 file", input);
  }
  if (options.dry_run) return 0;
  throw Error(
      ExitCode::internal_error,
      fmt::format("{}: this stage is not built yet (issue {}); only --dry-run validation is available in "
                  "this version",
                  stage.program, stage.issue));
}

} // namespace aniso::cli
