#include "lbm/io.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace aniso::lbm {
namespace {

std::vector<double> row_major(const Mat3& m) {
  std::vector<double> values;
  for (Eigen::Index i = 0; i < 3; ++i)
    for (Eigen::Index j = 0; j < 3; ++j)
      values.push_back(m(i, j));
  return values;
}

Mat3 from_row_major(const std::vector<double>& values) {
  Mat3 m;
  for (Eigen::Index i = 0; i < 3; ++i)
    for (Eigen::Index j = 0; j < 3; ++j)
      m(i, j) = values[static_cast<std::size_t>(3 * i + j)];
  return m;
}

std::string precision_name(Precision precision) {
  return precision == Precision::float32 ? "float" : "double";
}

std::string run_name(const FlowRun& run) {
  return fmt::format("x{}_{}", run.axis + 1, to_string(run.walls));
}

} // namespace

std::string result_path(const std::string& output_dir, const std::string& prefix,
                        const std::string& image_path) {
  const std::string stem = std::filesystem::path(image_path).stem().string();
  return (std::filesystem::path(output_dir) / (prefix + "_" + stem + ".h5")).string();
}

void write_permeability(const std::string& path, const PermeabilityResult& result,
                        const h5::VoxelImage& image, const PermeabilitySettings& settings,
                        const h5::Provenance& provenance) {
  h5::AtomicFile atomic(path);
  {
    h5::File file = h5::File::create(atomic.temp_path());
    h5::write_provenance(file, provenance);
    h5::Group group = file.create_group("permeability");
    group.write_attribute("schema_version", permeability_schema_version);
    group.write_attribute("source", std::string_view(image.source));
    group.write_attribute("source_hash", std::string_view(image.source_hash));
    group.write_attribute("method", std::string_view(to_string(result.method)));
    group.write_attribute_with_units("voxel_size", image.voxel_size, "m");
    group.write_attribute("porosity", result.porosity);
    group.write_attribute("fluid_voxels", result.fluid_voxels);
    group.write_attribute("symmetry_error", result.symmetry_error);
    group.write_attribute("inverse_residual", result.inverse_residual);
    group.write_attribute("tau", settings.flow.tau);
    group.write_attribute("magic", settings.flow.magic);
    group.write_attribute("precision", std::string_view(precision_name(settings.flow.precision)));
    group.write_attribute("body_force", settings.body_force);
    group.write_attribute("tolerance", settings.flow.tolerance);
    const double h2 = image.voxel_size * image.voxel_size;
    group.write_dataset<double>("K", row_major(result.k_lattice * h2), {3, 3}, "m^2",
                                "effective permeability tensor k_ij (eq. (permeability)); row i = flux "
                                "component, column j = driving direction");
    group.write_dataset<double>("K_lattice", row_major(result.k_lattice), {3, 3}, "voxel^2",
                                "the same tensor in lattice units (voxel edge = 1)");
    std::vector<std::int64_t> axis, steps;
    std::vector<double> momentum, gradient, seconds;
    std::string names;
    for (const FlowRun& run : result.runs) {
      axis.push_back(run.axis + 1);
      steps.push_back(run.result.steps);
      seconds.push_back(run.result.seconds);
      for (Eigen::Index a = 0; a < 3; ++a) {
        momentum.push_back(run.result.mean_momentum[a]);
        gradient.push_back(run.result.pressure_gradient[a]);
      }
      names += (names.empty() ? "" : ",") + run_name(run);
    }
    const auto n_runs = static_cast<hsize_t>(result.runs.size());
    h5::Group runs = group.create_group("runs");
    runs.write_attribute("names", std::string_view(names));
    runs.write_dataset<std::int64_t>("axis", axis, {n_runs}, "1", "direction of the driving force (1, 2, 3)");
    runs.write_dataset<std::int64_t>("steps", steps, {n_runs}, "1", "time steps to convergence");
    runs.write_dataset<double>("seconds", seconds, {n_runs}, "s", "wall time of the run");
    runs.write_dataset<double>("mean_momentum", momentum, {n_runs, 3}, "lattice",
                               "superficial momentum <j> (mean over all voxels) at convergence");
    runs.write_dataset<double>("pressure_gradient", gradient, {n_runs, 3}, "lattice",
                               "mean pressure gradient along wall-bounded axes (0 along periodic axes)");
    file.close();
  }
  atomic.commit();
}

PermeabilityFile read_permeability(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("permeability");
  const auto version = group.read_attribute<std::int64_t>("schema_version");
  if (version != permeability_schema_version)
    group.fail(
        fmt::format("schema_version {} is not the supported {}", version, permeability_schema_version));
  PermeabilityFile result;
  result.k = from_row_major(group.read_dataset<double>("K", {3, 3}));
  result.k_lattice = from_row_major(group.read_dataset<double>("K_lattice", {3, 3}));
  if (!result.k.allFinite() || !result.k_lattice.allFinite()) group.fail("K holds non-finite values");
  result.method = group.read_string_attribute("method");
  if (result.method != "periodic_body_force" && result.method != "paper_walls")
    group.fail(fmt::format("unknown method '{}'", result.method));
  result.source = group.read_string_attribute("source");
  result.source_hash = group.read_string_attribute("source_hash");
  result.voxel_size = group.read_attribute<double>("voxel_size");
  if (!(result.voxel_size > 0) || !std::isfinite(result.voxel_size))
    group.fail(fmt::format("voxel_size {} is not a positive length", result.voxel_size));
  return result;
}

void write_velocity(const std::string& path, const PermeabilityResult& result, const h5::VoxelImage& image,
                    const h5::Provenance& provenance) {
  check_invariant(result.velocity.size() == result.runs.size(), "one velocity field per run");
  const auto [n1, n2, n3] = image.shape;
  {
    h5::AtomicFile atomic(path);
    h5::File file = h5::File::create(atomic.temp_path());
    h5::write_provenance(file, provenance);
    h5::Group group = file.create_group("velocity");
    group.write_attribute_with_units("voxel_size", image.voxel_size, "m");
    for (std::size_t r = 0; r < result.runs.size(); ++r)
      group.write_dataset<double>(run_name(result.runs[r]), result.velocity[r], {n3, n2, n1, 3}, "lattice",
                                  "fluid velocity u (lattice units, voxel per step) at the voxel centres, 0 "
                                  "in solid; x1 fastest");
    file.close();
    atomic.commit();
  }
  // ParaView: one cell-centred vector per run on a 3DCoRectMesh (XDMF lists dimensions slowest first).
  const std::string h5_name = std::filesystem::path(path).filename().string();
  std::string attributes;
  for (const FlowRun& run : result.runs)
    attributes +=
        fmt::format("      <Attribute Name=\"u_{0}\" AttributeType=\"Vector\" Center=\"Cell\">\n"
                    "        <DataItem Dimensions=\"{1} {2} {3} 3\" NumberType=\"Float\" Precision=\"8\" "
                    "Format=\"HDF\">{4}:/velocity/{0}</DataItem>\n      </Attribute>\n",
                    run_name(run), n3, n2, n1, h5_name);
  const std::string xdmf = fmt::format(
      "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n    <Grid Name=\"velocity\" "
      "GridType=\"Uniform\">\n      <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"{0} {1} {2}\"/>\n"
      "      <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n        <DataItem Dimensions=\"3\" "
      "Format=\"XML\">{3:.17g} "
      "{4:.17g} {5:.17g}</DataItem>\n        <DataItem Dimensions=\"3\" Format=\"XML\">{6:.17g} {6:.17g} "
      "{6:.17g}</DataItem>\n      </Geometry>\n{7}    </Grid>\n  </Domain>\n</Xdmf>\n",
      n3 + 1, n2 + 1, n1 + 1, image.origin.z(), image.origin.y(), image.origin.x(), image.voxel_size,
      attributes);
  h5::AtomicFile sidecar(h5::xdmf_sidecar_path(path));
  {
    std::ofstream out(sidecar.temp_path(), std::ios::binary | std::ios::trunc);
    out << xdmf;
    if (!out) throw FileError(sidecar.final_path() + ": cannot write");
  }
  sidecar.commit();
}

} // namespace aniso::lbm
