#include "voxel/void_results.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

namespace aniso::voxel {
namespace {

constexpr const char* schema_name = "aniso-voids";
constexpr std::int64_t schema_version = 1;

const h5::Dims three{3};
const h5::Dims scalar{};

std::vector<double> fractions(const Curve& curve, std::uint64_t void_voxels) {
  std::vector<double> f(curve.kept.size());
  for (std::size_t k = 0; k < f.size(); ++k)
    f[k] = static_cast<double>(curve.kept[k]) / static_cast<double>(std::max<std::uint64_t>(void_voxels, 1));
  return f;
}

std::vector<double> scaled(const std::vector<double>& values, double factor) {
  std::vector<double> out(values);
  for (double& v : out)
    v *= factor;
  return out;
}

void write_curve(h5::Group& parent, const std::string& name, const Curve& curve, const VoidAnalysis& analysis,
                 double metres, double d50, bool spar) {
  h5::Group group = parent.create_group(name);
  const h5::Dims dims{curve.size.size()};
  const std::string size_name = spar ? "length" : "radius";
  group.write_dataset<double>(size_name, curve.size, dims, "voxel",
                              spar ? "spar length l (voxels in the row)"
                                   : "radius rho: digital set |z|^2 <= rho^2");
  group.write_dataset<double>(size_name + "_m", scaled(curve.size, metres), dims, "m", "the sizes in metres");
  group.write_dataset<double>(size_name + "_d50", scaled(curve.size, metres / d50), dims, "1",
                              "the sizes in d50");
  group.write_dataset<std::uint64_t>("kept", curve.kept, dims, "voxel", "void voxels kept by the opening");
  group.write_dataset<double>("fraction", fractions(curve, analysis.void_voxels), dims, "1",
                              "f = kept / void voxels (eqs. (fr), (fli), (fri))");
  group.write_dataset<double>("median", std::vector<double>{curve.median * metres}, scalar, "m",
                              "size where f crosses 0.5 (linear interpolation; inf if it never does)");
  group.write_attribute("infinite_kept", static_cast<std::uint64_t>(curve.infinite));
  group.write_attribute("last_value_holds_for_larger_sizes", std::string_view("yes"));
}

std::vector<double> medians_of(const std::array<Curve, 3>& curves, double scale0, double scale1,
                               double scale2) {
  return {curves[0].median * scale0, curves[1].median * scale1, curves[2].median * scale2};
}

void write_h5(const std::string& temp, const VoidAnalysis& analysis, const VoidContext& context,
              const h5::Provenance& provenance) {
  h5::File file = h5::File::create(temp);
  file.write_attribute("schema", std::string_view(schema_name));
  file.write_attribute("schema_version", schema_version);
  file.write_attribute("description",
                       std::string_view("aniso void morphology of a voxel image (Kuhn, Sun & Wang "
                                        "2015, section 3); layout: docs/formats/voids.md"));
  h5::write_provenance(file, provenance);
  h5::Group voids = file.create_group("voids");
  voids.write_attribute("source", std::string_view(context.source));
  voids.write_attribute("source_hash", std::string_view(context.source_hash));
  voids.write_attribute("image", std::string_view(context.image));
  voids.write_attribute_with_units("d50", context.d50, "m");
  voids.write_attribute_with_units("resolution", context.resolution, "voxel/d50");
  const double mean_edge = std::cbrt(context.voxel_edges.prod());
  voids.write_attribute_with_units("voxel_size", mean_edge, "m");
  voids.write_dataset<double>(
      "voxel_edges",
      std::vector<double>{context.voxel_edges[0], context.voxel_edges[1], context.voxel_edges[2]}, three, "m",
      "voxel edge L_a / n_a along x1, x2, x3");
  voids.write_dataset<std::uint64_t>(
      "shape", std::vector<std::uint64_t>{context.shape[0], context.shape[1], context.shape[2]}, three,
      "voxel", "n1, n2, n3");
  voids.write_dataset<double>(
      "porosity",
      std::vector<double>{static_cast<double>(analysis.void_voxels) / static_cast<double>(analysis.voxels)},
      scalar, "1", "void voxels / all voxels");

  const Vec3& e = context.voxel_edges;
  const std::vector<double> free_path = medians_of(analysis.spar, e[0], e[1], e[2]);
  const std::vector<double> breadth = medians_of(analysis.disk, mean_edge, mean_edge, mean_edge);
  voids.write_dataset<double>(
      "free_path_median", free_path, three, "m",
      "median spar length l_i along x_i (eq. (fli)); inf if f_l_i never falls below 0.5");
  voids.write_dataset<double>("breadth_median", breadth, three, "m",
                              "median disk radius r_i, disk axis x_i (eq. (fri))");
  voids.write_dataset<double>("void_size_median", std::vector<double>{analysis.ball.median * mean_edge},
                              scalar, "m", "median ball radius rho (eq. (fr))");
  const auto to_array = [](const std::vector<double>& v) { return std::array<double, 3>{v[0], v[1], v[2]}; };
  const auto l_v = normalized_medians(to_array(free_path));
  const auto r_v = normalized_medians(to_array(breadth));
  voids.write_dataset<double>("L_v", std::vector<double>(l_v.begin(), l_v.end()), three, "1",
                              "L^v_ii = 3 l_i / (l_1 + l_2 + l_3), eq. (Lambdaii)");
  voids.write_dataset<double>("R_v", std::vector<double>(r_v.begin(), r_v.end()), three, "1",
                              "R^v_ii = 3 r_i / (r_1 + r_2 + r_3), eq. (Rii)");

  write_curve(voids, "ball", analysis.ball, analysis, mean_edge, context.d50, false);
  for (std::size_t a = 0; a < 3; ++a) {
    write_curve(voids, fmt::format("spar_x{}", a + 1), analysis.spar[a], analysis,
                e[static_cast<Eigen::Index>(a)], context.d50, true);
    write_curve(voids, fmt::format("disk_x{}", a + 1), analysis.disk[a], analysis, mean_edge, context.d50,
                false);
  }

  h5::Group euler = voids.create_group("euler");
  euler.write_attribute(
      "description",
      std::string_view("Euler characteristic of the void: image = periodic image, 26-connected void "
                       "and 6-connected solid; counted = eq. (Chis1) from particles and contacts"));
  euler.write_attribute("image", analysis.euler);
  euler.write_attribute("counted_bounded", counted_euler_bounded(context));
  euler.write_attribute("counted_torus", counted_euler_torus(context));
  euler.write_attribute("n_particles", context.n_particles);
  euler.write_attribute("n_contacts", context.n_contacts);
  file.close();
}

void write_csv(const std::string& temp, const VoidAnalysis& analysis, const VoidContext& context) {
  std::ofstream out(temp, std::ios::trunc);
  out << "template,axis,size_voxels,size_m,size_d50,kept_voxels,fraction\n";
  const auto rows = [&](const char* name, int axis, const Curve& curve, double metres) {
    const std::vector<double> f = fractions(curve, analysis.void_voxels);
    for (std::size_t k = 0; k < curve.size.size(); ++k)
      out << fmt::format("{},{},{},{:.9g},{:.9g},{},{:.9g}\n", name, axis, curve.size[k],
                         curve.size[k] * metres, curve.size[k] * metres / context.d50, curve.kept[k], f[k]);
  };
  const double mean_edge = std::cbrt(context.voxel_edges.prod());
  rows("ball", 0, analysis.ball, mean_edge);
  for (std::size_t a = 0; a < 3; ++a) {
    rows("spar", static_cast<int>(a + 1), analysis.spar[a],
         context.voxel_edges[static_cast<Eigen::Index>(a)]);
    rows("disk", static_cast<int>(a + 1), analysis.disk[a], mean_edge);
  }
  out.close();
  if (!out) throw FileError(temp + ": cannot write the CSV");
}

} // namespace

std::int64_t counted_euler_bounded(const VoidContext& context) {
  return 1 + context.n_particles - context.n_contacts;
}

std::int64_t counted_euler_torus(const VoidContext& context) {
  return context.n_particles - context.n_contacts;
}

void write_void_results(const std::string& h5_path, const std::string& csv_path, const VoidAnalysis& analysis,
                        const VoidContext& context, const h5::Provenance& provenance) {
  {
    h5::AtomicFile atomic(h5_path);
    write_h5(atomic.temp_path(), analysis, context, provenance);
    atomic.commit();
  }
  h5::AtomicFile atomic(csv_path);
  write_csv(atomic.temp_path(), analysis, context);
  atomic.commit();
}

} // namespace aniso::voxel
