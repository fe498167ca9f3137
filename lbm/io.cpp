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

namespace {

void write_common(h5::Group& group, const h5::VoxelImage& image, const PermeabilitySettings& settings,
                  Method method, double porosity, std::int64_t fluid_voxels) {
  group.write_attribute("schema_version", permeability_schema_version);
  group.write_attribute("source", std::string_view(image.source));
  group.write_attribute("source_hash", std::string_view(image.source_hash));
  group.write_attribute("method", std::string_view(to_string(method)));
  group.write_attribute_with_units("voxel_size", image.voxel_size, "m");
  group.write_attribute("porosity", porosity);
  group.write_attribute("fluid_voxels", fluid_voxels);
  group.write_attribute("tau", settings.flow.tau);
  group.write_attribute("magic", settings.flow.magic);
  group.write_attribute("precision", std::string_view(precision_name(settings.flow.precision)));
  group.write_attribute("body_force", settings.body_force);
  group.write_attribute("tolerance", settings.flow.tolerance);
  group.write_attribute("convergence_criterion", stop_criterion_name(settings.flow.criterion));
}

std::int64_t walls_code(FaceKind walls) {
  return walls == FaceKind::periodic ? 0 : (walls == FaceKind::no_slip ? 1 : 2);
}

void write_runs(h5::Group& group, const std::vector<FlowRun>& runs) {
  std::vector<std::int64_t> axis, walls, steps;
  std::vector<double> momentum, gradient, seconds, reynolds, throat, error;
  std::vector<std::uint8_t> crosses;
  std::string names;
  for (const FlowRun& run : runs) {
    throat.push_back(run.throat_width);
    crosses.push_back(run.percolates ? 1 : 0);
    axis.push_back(run.axis + 1);
    walls.push_back(walls_code(run.walls));
    steps.push_back(run.result.steps);
    seconds.push_back(run.result.seconds);
    reynolds.push_back(run.result.reynolds);
    error.push_back(run.result.estimated_error);
    for (Eigen::Index a = 0; a < 3; ++a) {
      momentum.push_back(run.result.mean_momentum[a]);
      gradient.push_back(run.result.pressure_gradient[a]);
    }
    names += (names.empty() ? "" : ",") + run_name(run);
  }
  const auto n_runs = static_cast<hsize_t>(runs.size());
  h5::Group group_runs = group.create_group("runs");
  group_runs.write_attribute("names", std::string_view(names));
  group_runs.write_dataset<std::int64_t>("axis", axis, {n_runs}, "1",
                                         "direction of the driving force (1, 2, 3)");
  group_runs.write_dataset<std::int64_t>("walls", walls, {n_runs}, "1",
                                         "side faces: 0 periodic, 1 no-slip, 2 free-slip");
  group_runs.write_dataset<std::int64_t>("steps", steps, {n_runs}, "1", "time steps to convergence");
  group_runs.write_dataset<double>("seconds", seconds, {n_runs}, "s", "wall time of the run");
  group_runs.write_dataset<double>("reynolds", reynolds, {n_runs}, "1",
                                   "permeability Reynolds number |<j>| sqrt(K) / nu, K = nu |<j>| / |F|");
  group_runs.write_dataset<double>(
      "estimated_error", error, {n_runs}, "1",
      "relative error of <j> left at the stop, estimated from the decay of its "
      "changes (inf: no steady decay seen; NaN: written before it was recorded)");
  group_runs.write_dataset<double>(
      "throat_width", throat, {n_runs}, "voxel",
      "narrowest throat along the run's axis: 2 r - 1 for the largest r such that "
      "voids at least r from the solid cross the cell (inf: no solid)");
  group_runs.write_dataset<std::uint8_t>(
      "percolates", crosses, {n_runs}, "1",
      "1: void voxels cross the cell along the axis; 0: none do, no flow was "
      "run and K is zero along the axis");
  group_runs.write_dataset<double>("mean_momentum", momentum, {n_runs, 3}, "lattice",
                                   "superficial momentum <j> (mean over all voxels) at convergence");
  group_runs.write_dataset<double>("pressure_gradient", gradient, {n_runs, 3}, "lattice",
                                   "mean pressure gradient along wall-bounded axes (0 along periodic axes)");
}

void check_schema(const h5::Group& group) {
  const auto version = group.read_attribute<std::int64_t>("schema_version");
  if (version != permeability_schema_version)
    group.fail(fmt::format("schema_version {} is not the supported {}: run aniso-lbm again on the image",
                           version, permeability_schema_version));
}

Method read_method(const h5::Group& group) {
  const std::string method = group.read_string_attribute("method");
  if (method != "periodic_body_force" && method != "paper_walls")
    group.fail(fmt::format("unknown method '{}'", method));
  return method == "paper_walls" ? Method::paper_walls : Method::periodic_body_force;
}

double read_voxel_size(const h5::Group& group) {
  const double h = group.read_attribute<double>("voxel_size");
  if (!(h > 0) || !std::isfinite(h)) group.fail(fmt::format("voxel_size {} is not a positive length", h));
  return h;
}

} // namespace

void write_permeability(const std::string& path, const PermeabilityResult& result,
                        const h5::VoxelImage& image, const PermeabilitySettings& settings,
                        const h5::Provenance& provenance) {
  h5::AtomicFile atomic(path);
  {
    h5::File file = h5::File::create(atomic.temp_path());
    h5::write_provenance(file, provenance);
    h5::Group group = file.create_group("permeability");
    write_common(group, image, settings, result.method, result.porosity, result.fluid_voxels);
    group.write_attribute("symmetry_error", result.symmetry_error);
    group.write_attribute("inverse_residual", result.inverse_residual);
    const double h2 = image.voxel_size * image.voxel_size;
    group.write_dataset<double>("K", row_major(result.k_lattice * h2), {3, 3}, "m^2",
                                "effective permeability tensor k_ij (eq. (permeability)); row i = flux "
                                "component, column j = driving direction");
    group.write_dataset<double>("K_lattice", row_major(result.k_lattice), {3, 3}, "voxel^2",
                                "the same tensor in lattice units (voxel edge = 1)");
    write_runs(group, result.runs);
    file.close();
  }
  atomic.commit();
}

std::string direction_path(const std::string& output_dir, const std::string& image_path, int axis) {
  const std::string stem = std::filesystem::path(image_path).stem().string();
  return (std::filesystem::path(output_dir) / fmt::format("permeability_{}_direction{}.h5", stem, axis))
      .string();
}

void write_direction(const std::string& path, const std::vector<FlowRun>& runs, int axis,
                     const h5::VoxelImage& image, const std::string& image_hash,
                     const PermeabilitySettings& settings, const h5::Provenance& provenance) {
  const std::int64_t fluid = fluid_voxels(image);
  h5::AtomicFile atomic(path);
  {
    h5::File file = h5::File::create(atomic.temp_path());
    h5::write_provenance(file, provenance);
    h5::Group group = file.create_group("direction");
    write_common(group, image, settings, settings.method,
                 static_cast<double>(fluid) / static_cast<double>(image.size()), fluid);
    group.write_attribute("axis", std::int64_t{axis});
    group.write_attribute("image_hash", std::string_view(image_hash));
    write_runs(group, runs);
    file.close();
  }
  atomic.commit();
}

DirectionFile read_direction(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("direction");
  check_schema(group);
  DirectionFile d;
  d.axis = static_cast<int>(group.read_attribute<std::int64_t>("axis"));
  if (d.axis < 0 || d.axis > 2) group.fail(fmt::format("axis {} is not 0, 1 or 2", d.axis));
  d.method = read_method(group);
  d.settings.method = d.method;
  d.settings.flow.tau = group.read_attribute<double>("tau");
  d.settings.flow.magic = group.read_attribute<double>("magic");
  d.settings.body_force = group.read_attribute<double>("body_force");
  d.settings.flow.tolerance = group.read_attribute<double>("tolerance");
  // Files from before the error criterion stopped on the change.
  const std::string criterion = group.has_attribute("convergence_criterion")
                                    ? group.read_string_attribute("convergence_criterion")
                                    : std::string(stop_criterion_name(StopCriterion::change));
  if (criterion != "error" && criterion != "change")
    group.fail(fmt::format("convergence_criterion '{}' is not 'error' or 'change'", criterion));
  d.settings.flow.criterion = criterion == "error" ? StopCriterion::error : StopCriterion::change;
  const std::string precision = group.read_string_attribute("precision");
  if (precision != "float" && precision != "double")
    group.fail(fmt::format("precision '{}' is not 'float' or 'double'", precision));
  d.settings.flow.precision = precision == "float" ? Precision::float32 : Precision::float64;
  if (!(d.settings.flow.tau > 0.5) || !(d.settings.body_force > 0) || !(d.settings.flow.magic > 0))
    group.fail("tau, magic or body_force out of range");
  d.image.voxel_size = read_voxel_size(group);
  d.image.source = group.read_string_attribute("source");
  d.image.source_hash = group.read_string_attribute("source_hash");
  d.porosity = group.read_attribute<double>("porosity");
  d.fluid_voxels = group.read_attribute<std::int64_t>("fluid_voxels");
  if (group.has_attribute("image_hash")) d.image_hash = group.read_string_attribute("image_hash");
  const h5::Group runs = group.open_group("runs");
  const auto n = static_cast<hsize_t>(runs.open_dataset("axis").dims().at(0));
  const auto axis = runs.read_dataset<std::int64_t>("axis", {n});
  const auto walls = runs.read_dataset<std::int64_t>("walls", {n});
  const auto steps = runs.read_dataset<std::int64_t>("steps", {n});
  const auto seconds = runs.read_dataset<double>("seconds", {n});
  const auto reynolds = runs.read_dataset<double>("reynolds", {n});
  const auto error = runs.has_child("estimated_error") ? runs.read_dataset<double>("estimated_error", {n})
                                                       : std::vector<double>(n, std::nan(""));
  const auto throat = runs.read_dataset<double>("throat_width", {n});
  const auto crosses = runs.read_dataset<std::uint8_t>("percolates", {n});
  const auto momentum = runs.read_dataset<double>("mean_momentum", {n, 3});
  const auto gradient = runs.read_dataset<double>("pressure_gradient", {n, 3});
  for (std::size_t r = 0; r < n; ++r) {
    FlowRun run;
    run.axis = static_cast<int>(axis[r]) - 1;
    if (run.axis != d.axis || walls[r] < 0 || walls[r] > 2)
      runs.fail(
          fmt::format("run {} has axis {} and walls {}, expected axis {}", r, axis[r], walls[r], d.axis + 1));
    run.walls =
        walls[r] == 0 ? FaceKind::periodic : (walls[r] == 1 ? FaceKind::no_slip : FaceKind::free_slip);
    run.result.steps = steps[r];
    run.result.seconds = seconds[r];
    run.result.reynolds = reynolds[r];
    run.result.estimated_error = error[r];
    run.throat_width = throat[r];
    run.percolates = crosses[r] != 0;
    for (std::size_t a = 0; a < 3; ++a) {
      run.result.mean_momentum[static_cast<Eigen::Index>(a)] = momentum[3 * r + a];
      run.result.pressure_gradient[static_cast<Eigen::Index>(a)] = gradient[3 * r + a];
    }
    if (!run.result.mean_momentum.allFinite() || !run.result.pressure_gradient.allFinite())
      runs.fail(fmt::format("run {} holds non-finite values", r));
    d.runs.push_back(run);
  }
  return d;
}

PermeabilityFile read_permeability(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("permeability");
  const auto version = group.read_attribute<std::int64_t>("schema_version");
  if (version != permeability_schema_version)
    group.fail(fmt::format("schema_version {} is not the supported {}: run aniso-lbm again on the image",
                           version, permeability_schema_version));
  PermeabilityFile result;
  result.k = from_row_major(group.read_dataset<double>("K", {3, 3}));
  result.k_lattice = from_row_major(group.read_dataset<double>("K_lattice", {3, 3}));
  if (!result.k.allFinite() || !result.k_lattice.allFinite()) group.fail("K holds non-finite values");
  result.method = to_string(read_method(group));
  result.source = group.read_string_attribute("source");
  result.source_hash = group.read_string_attribute("source_hash");
  result.voxel_size = read_voxel_size(group);
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
