#include "lbm/resume.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <utility>
#include <vector>

namespace aniso::lbm {
namespace {

// The runs in the direction file of `axis`, if they are runs of this image file and settings.
std::optional<std::vector<FlowRun>> reusable_direction(const std::string& path, int axis,
                                                       const DirectionFile& reference, const Logger& logger) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  try {
    DirectionFile file = read_direction(path);
    if (file.axis != axis || file.image_hash != reference.image_hash ||
        !differing_settings(file, reference).empty())
      return std::nullopt;
    return std::move(file.runs);
  } catch (const FileError& error) {
    logger->warn("{}: cannot be used ({}); the flows along x{} are run anew", path, error.what(), axis + 1);
    return std::nullopt;
  }
}

std::string axis_list(const DirectionRuns& runs, bool done) {
  std::string list;
  for (int axis = 0; axis < 3; ++axis)
    if (runs[static_cast<std::size_t>(axis)].has_value() == done)
      list += (list.empty() ? "x" : ", x") + std::to_string(axis + 1);
  return list.empty() ? "none" : list;
}

} // namespace

std::string differing_settings(const DirectionFile& file, const DirectionFile& reference) {
  // Every setting that changes the numbers: a tensor assembled from runs of different precision,
  // tolerance or image would look fine and be wrong.
  const DirectionFile& d = file;
  const DirectionFile& r = reference;
  const std::vector<std::pair<const char*, bool>> agreements{
      {"method", d.method == r.method},
      {"tau", d.settings.flow.tau == r.settings.flow.tau},
      {"magic", d.settings.flow.magic == r.settings.flow.magic},
      {"body force", d.settings.body_force == r.settings.body_force},
      {"precision", d.settings.flow.precision == r.settings.flow.precision},
      {"convergence tolerance", d.settings.flow.tolerance == r.settings.flow.tolerance},
      {"convergence criterion", d.settings.flow.criterion == r.settings.flow.criterion},
      {"voxel size", d.image.voxel_size == r.image.voxel_size},
      {"source hash", d.image.source_hash == r.image.source_hash},
      {"porosity", d.porosity == r.porosity && d.fluid_voxels == r.fluid_voxels},
  };
  std::string differing;
  for (const auto& [name, agrees] : agreements)
    if (!agrees) differing += (differing.empty() ? "" : ", ") + std::string(name);
  return differing;
}

DirectionRuns finished_directions(const std::string& output_dir, const std::string& input,
                                  const h5::VoxelImage& image, const std::string& image_hash,
                                  const PermeabilitySettings& settings, const mpi::Comm& comm,
                                  const Logger& logger) {
  DirectionFile reference;
  reference.method = settings.method;
  reference.settings = settings;
  reference.image.voxel_size = image.voxel_size;
  reference.image.source_hash = image.source_hash;
  reference.fluid_voxels = fluid_voxels(image);
  reference.porosity = static_cast<double>(reference.fluid_voxels) / static_cast<double>(image.size());
  reference.image_hash = image_hash;
  DirectionRuns finished;
  for (int axis = 0; axis < 3; ++axis) {
    // Every rank reads the file; it is used only if every rank could.
    auto runs = reusable_direction(direction_path(output_dir, input, axis), axis, reference, logger);
    if (!comm.any(!runs.has_value())) finished[static_cast<std::size_t>(axis)] = std::move(runs);
  }
  if (axis_list(finished, true) != "none")
    logger->info("directions already done by an earlier run: {} (direction files in '{}'); running the "
                 "others",
                 axis_list(finished, true), output_dir);
  return finished;
}

void keep_directions(const std::string& output_dir, const std::string& input, const h5::VoxelImage& image,
                     const std::string& image_hash, const PermeabilitySettings& settings,
                     const DirectionRuns& runs, const DirectionRuns& finished,
                     const h5::Provenance& provenance, const mpi::Comm& comm) {
  if (!comm.is_root()) return;
  for (int axis = 0; axis < 3; ++axis) {
    const auto k = static_cast<std::size_t>(axis);
    if (runs[k] && !finished[k])
      write_direction(direction_path(output_dir, input, axis), *runs[k], axis, image, image_hash, settings,
                      provenance);
  }
}

void remove_finished(const std::string& output_dir, const std::string& input, const DirectionRuns& finished,
                     const mpi::Comm& comm) {
  if (!comm.is_root()) return;
  for (int axis = 0; axis < 3; ++axis)
    if (finished[static_cast<std::size_t>(axis)])
      std::filesystem::remove(direction_path(output_dir, input, axis));
}

std::string stop_message(const std::string& output_dir, const std::string& input, const DirectionRuns& runs,
                         bool kept, const std::string& command) {
  if (!kept)
    return fmt::format("stopped on SIGTERM: directions done: {}; directions left: {}; the velocity fields "
                       "(lbm.write_velocity) are not kept, so nothing was written and the same command "
                       "starts every direction anew: {}",
                       axis_list(runs, true), axis_list(runs, false), command);
  const std::string files =
      (std::filesystem::path(output_dir) /
       fmt::format("permeability_{}_direction<D>.h5", std::filesystem::path(input).stem().string()))
          .string();
  return fmt::format("stopped on SIGTERM: directions done: {} (kept as {}); directions left: {}; continue "
                     "with the same command, which runs only the directions left: {}",
                     axis_list(runs, true), files, axis_list(runs, false), command);
}

} // namespace aniso::lbm
