#include "dem/interop/particle_xdmf.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/units.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

namespace aniso::dem::interop {
namespace {

constexpr std::string_view vis_schema_name = "aniso-particle-xdmf";
constexpr std::int64_t vis_schema_version = 1;
constexpr std::string_view xmf_extension = ".xmf";
constexpr std::string_view vis_extension = ".vis.h5";

// Arrays of the contact grid, derived from the checkpoint's contact rows.
struct ContactVisArrays {
  std::vector<double> points;             ///< 2M x 3: centre of i, centre of j's image
  std::vector<double> normal_force;       ///< |f . n| [N]
  std::vector<double> tangential_force;   ///< |f - (f . n) n| [N]
  std::vector<std::uint8_t> strong;       ///< normal force above the mean
  std::vector<std::int64_t> connectivity; ///< 2M: point 2k to point 2k+1
  std::vector<std::uint64_t> particles;   ///< 2M: (id_i, id_j)
  double mean_normal_force = 0;
  std::size_t strong_count = 0;
};

// The data file is named after the .xmf, so the file name needs a stem before ".xmf".
void check_xmf_path(const std::string& xdmf_path) {
  const std::string name = std::filesystem::path(xdmf_path).filename().string();
  require_input(name.size() > xmf_extension.size() && name.ends_with(xmf_extension),
                xdmf_path + ": the particle XDMF output must be a file name ending in \".xmf\"");
}

std::string data_path_for(const std::string& xdmf_path) {
  return xdmf_path.substr(0, xdmf_path.size() - xmf_extension.size()) + std::string(vis_extension);
}

// The rows must agree in length and contacts must name existing particles (row = id): a
// hand-built checkpoint is not validated by read_checkpoint.
void check_vis_rows(const h5::Checkpoint& c, const std::string& xdmf_path) {
  const h5::ParticleRows& p = c.particles;
  const std::size_t n = p.size();
  const std::string where = xdmf_path + ": checkpoint rows: ";
  require_input(n > 0, where + "no particles"); // an XDMF grid of zero points is not read reliably
  for (const std::size_t size :
       {p.diameter.size(), p.aspect_ratio.size(), p.position.size(), p.orientation.size(), p.velocity.size(),
        p.angular_velocity.size(), p.force.size()})
    require_input(size == n, where + fmt::format("particle arrays of {} and {} rows", n, size));
  for (std::size_t row = 0; row < n; ++row)
    require_input(p.id[row] == row,
                  where +
                      fmt::format("particle row {} has id {}, expected rows in id order", row, p.id[row]));
  const h5::ContactRows& k = c.contacts;
  const std::size_t m = k.size();
  for (const std::size_t size : {k.image_shift.size(), k.normal.size(), k.force.size()})
    require_input(size == m, where + fmt::format("contact arrays of {} and {} rows", m, size));
  for (std::size_t row = 0; row < m; ++row)
    require_input(k.particles[row][0] < n && k.particles[row][1] < n,
                  where + fmt::format("contact {} joins particles {} and {}, expected ids below {}", row,
                                      k.particles[row][0], k.particles[row][1], n));
}

std::vector<double> flatten_vec3(std::span<const Vec3> rows) {
  std::vector<double> flat;
  flat.reserve(3 * rows.size());
  for (const Vec3& v : rows)
    flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  return flat;
}

// The body z axis (the axis of revolution) in the world frame; a sphere has none, so it gets z.
std::vector<Vec3> revolution_axes(const h5::ParticleRows& p) {
  std::vector<Vec3> axes(p.size(), Vec3::UnitZ());
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.aspect_ratio[k] != 1.0) axes[k] = p.orientation[k].normalized() * Vec3::UnitZ();
  return axes;
}

// 0 .. n-1: ParaView's Xdmf3 readers make no vertex cells from a Polyvertex without connectivity.
std::vector<std::int64_t> vertex_ids(std::size_t n) {
  std::vector<std::int64_t> ids(n);
  for (std::size_t k = 0; k < n; ++k)
    ids[k] = static_cast<std::int64_t>(k);
  return ids;
}

// Mean over all contacts, summed exactly so that it does not depend on the row order (as fabric's).
double mean_of(std::span<const double> values) {
  if (values.empty()) return 0.0;
  ExactSum sum;
  for (const double v : values)
    sum.add(v);
  return sum.value() / static_cast<double>(values.size());
}

ContactVisArrays contact_vis_arrays(const h5::Checkpoint& c) {
  const h5::ContactRows& k = c.contacts;
  const std::size_t m = k.size();
  ContactVisArrays a;
  a.points.reserve(6 * m);
  a.connectivity.reserve(2 * m);
  for (std::size_t row = 0; row < m; ++row) {
    const auto [i, j] = k.particles[row];
    const Vec3& from = c.particles.position[i];
    const Vec3 to = c.particles.position[j] + k.image_shift[row].cast<double>().cwiseProduct(c.cell.lengths);
    a.points.insert(a.points.end(), {from.x(), from.y(), from.z(), to.x(), to.y(), to.z()});
    const double along = k.force[row].dot(k.normal[row]);
    a.normal_force.push_back(std::abs(along));
    a.tangential_force.push_back((k.force[row] - along * k.normal[row]).norm());
    a.connectivity.insert(a.connectivity.end(),
                          {static_cast<std::int64_t>(2 * row), static_cast<std::int64_t>(2 * row + 1)});
    a.particles.insert(a.particles.end(), {i, j});
  }
  a.mean_normal_force = mean_of(a.normal_force);
  for (const double f : a.normal_force) {
    a.strong.push_back(f > a.mean_normal_force ? 1 : 0);
    a.strong_count += a.strong.back();
  }
  return a;
}

void write_vis_root_attributes(h5::File& file, const h5::Checkpoint& c, const std::string& checkpoint_path) {
  file.write_attribute("schema", vis_schema_name);
  file.write_attribute("schema_version", vis_schema_version);
  file.write_attribute("description",
                       std::string_view("particles and contact force chains of one aniso checkpoint, for "
                                        "ParaView through the .xmf beside it; layout: "
                                        "docs/formats/particle-xdmf.md"));
  file.write_attribute("source", std::string_view(checkpoint_path));
  file.write_attribute("step", c.step);
  file.write_attribute_with_units("time", c.time, units::second);
  for (int axis = 0; axis < 3; ++axis)
    file.write_attribute_with_units(fmt::format("cell_length_{}", axis + 1), c.cell.lengths[axis],
                                    units::metre);
}

void write_particle_datasets(h5::File& file, const h5::ParticleRows& p) {
  h5::Group group = file.create_group("particles");
  const hsize_t n = p.size();
  const h5::Dims rows3{n, 3}, rows1{n};
  group.write_dataset<double>("position", flatten_vec3(p.position), rows3, units::metre, "particle centre");
  group.write_dataset<double>("diameter", p.diameter, rows1, units::metre, "mid-plane diameter");
  group.write_dataset<double>("aspect_ratio", p.aspect_ratio, rows1, units::none,
                              "axial height / mid-plane diameter; 1 = sphere");
  group.write_dataset<double>("velocity", flatten_vec3(p.velocity), rows3, units::velocity, "velocity");
  group.write_dataset<double>("angular_velocity", flatten_vec3(p.angular_velocity), rows3,
                              units::angular_velocity, "angular velocity, world frame");
  group.write_dataset<double>("force", flatten_vec3(p.force), rows3, units::newton, "total force");
  group.write_dataset<double>("axis", flatten_vec3(revolution_axes(p)), rows3, units::none,
                              "axis of revolution (body z) in the world frame, unit vector; (0, 0, 1) "
                              "for spheres");
  group.write_dataset<std::uint64_t>("id", p.id, rows1, units::none, "particle id");
  group.write_dataset<std::int64_t>("connectivity", vertex_ids(p.size()), rows1, units::none,
                                    "XDMF Polyvertex connectivity: row k is vertex k");
}

void write_contact_datasets(h5::File& file, const ContactVisArrays& a) {
  h5::Group group = file.create_group("contacts");
  const hsize_t m = a.normal_force.size();
  group.write_dataset<double>("points", a.points, {2 * m, 3}, units::metre,
                              "rows 2k and 2k+1: centre of particle i and of the periodic image of j "
                              "(position_j + image_shift * cell lengths) of contact k");
  group.write_dataset<double>("normal_force", a.normal_force, {m}, units::newton, "|force . normal|");
  group.write_dataset<double>("tangential_force", a.tangential_force, {m}, units::newton,
                              "|force - (force . normal) normal|");
  group.write_dataset<std::uint8_t>("strong", a.strong, {m}, units::none,
                                    "1 if the normal force is above the mean normal force over all "
                                    "contacts (Kuhn, Sun & Wang 2015, section 3)");
  group.write_dataset<std::int64_t>("connectivity", a.connectivity, {m, 2}, units::none,
                                    "XDMF Polyline connectivity: contact k joins points 2k and 2k+1");
  group.write_dataset<std::uint64_t>("particles", a.particles, {m, 2}, units::none, "(id_i, id_j)");
  group.write_attribute_with_units("mean_normal_force", a.mean_normal_force, units::newton);
}

void write_vis_hdf5(const std::string& path, const h5::Checkpoint& c, const std::string& checkpoint_path,
                    const ContactVisArrays& contacts) {
  h5::AtomicFile atomic(path);
  {
    h5::File file = h5::File::create(atomic.temp_path());
    write_vis_root_attributes(file, c, checkpoint_path);
    write_particle_datasets(file, c.particles);
    write_contact_datasets(file, contacts);
    file.close();
  }
  atomic.commit();
}

// The data file's name goes into XML text.
std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
    case '&': out += "&amp;"; break;
    case '<': out += "&lt;"; break;
    case '>': out += "&gt;"; break;
    case '"': out += "&quot;"; break;
    default: out += ch;
    }
  }
  return out;
}

// One XDMF attribute read from the data file; `dims` as XDMF lists them ("N 3").
std::string xdmf_attribute(std::string_view h5_name, std::string_view dataset, std::string_view center,
                           std::string_view type, const std::string& dims, std::string_view number) {
  const std::string_view name = dataset.substr(dataset.rfind('/') + 1);
  return fmt::format(R"(      <Attribute Name="{1}" AttributeType="{3}" Center="{2}">
        <DataItem Dimensions="{4}" {5} Format="HDF">{0}:{6}</DataItem>
      </Attribute>
)",
                     h5_name, name, center, type, dims, number, dataset);
}

constexpr std::string_view xdmf_float = R"(NumberType="Float" Precision="8")";

// Polyvertex: one vertex cell per particle (ParaView's Glyph filter draws a sphere on each).
std::string particles_grid(std::string_view h5_name, const h5::Checkpoint& c) {
  const std::size_t n = c.particles.size();
  const std::string vec = fmt::format("{} 3", n), scalar = fmt::format("{}", n);
  std::string xml = fmt::format(R"(    <Grid Name="particles" GridType="Uniform">
      <Time Value="{2:.17g}"/>
      <Topology TopologyType="Polyvertex" NumberOfElements="{1}" NodesPerElement="1">
        <DataItem Dimensions="{1}" NumberType="Int" Precision="8" Format="HDF">{0}:/particles/connectivity</DataItem>
      </Topology>
      <Geometry GeometryType="XYZ">
        <DataItem Dimensions="{1} 3" NumberType="Float" Precision="8" Format="HDF">{0}:/particles/position</DataItem>
      </Geometry>
)",
                                h5_name, n, c.time);
  xml += xdmf_attribute(h5_name, "/particles/diameter", "Node", "Scalar", scalar, xdmf_float);
  xml += xdmf_attribute(h5_name, "/particles/aspect_ratio", "Node", "Scalar", scalar, xdmf_float);
  xml += xdmf_attribute(h5_name, "/particles/velocity", "Node", "Vector", vec, xdmf_float);
  xml += xdmf_attribute(h5_name, "/particles/angular_velocity", "Node", "Vector", vec, xdmf_float);
  xml += xdmf_attribute(h5_name, "/particles/force", "Node", "Vector", vec, xdmf_float);
  xml += xdmf_attribute(h5_name, "/particles/axis", "Node", "Vector", vec, xdmf_float);
  xml += xdmf_attribute(h5_name, "/particles/id", "Node", "Scalar", scalar,
                        R"(NumberType="UInt" Precision="8")");
  return xml + "    </Grid>\n";
}

// Polyline of two nodes per contact, cell-centred forces. Absent when there are no contacts:
// an XDMF grid of zero cells is not read reliably.
std::string contacts_grid(std::string_view h5_name, const h5::Checkpoint& c) {
  const std::size_t m = c.contacts.size();
  if (m == 0) return "";
  const std::string scalar = fmt::format("{}", m);
  std::string xml = fmt::format(R"(    <Grid Name="contacts" GridType="Uniform">
      <Time Value="{3:.17g}"/>
      <Topology TopologyType="Polyline" NumberOfElements="{1}" NodesPerElement="2">
        <DataItem Dimensions="{1} 2" NumberType="Int" Precision="8" Format="HDF">{0}:/contacts/connectivity</DataItem>
      </Topology>
      <Geometry GeometryType="XYZ">
        <DataItem Dimensions="{2} 3" NumberType="Float" Precision="8" Format="HDF">{0}:/contacts/points</DataItem>
      </Geometry>
)",
                                h5_name, m, 2 * m, c.time);
  xml += xdmf_attribute(h5_name, "/contacts/normal_force", "Cell", "Scalar", scalar, xdmf_float);
  xml += xdmf_attribute(h5_name, "/contacts/tangential_force", "Cell", "Scalar", scalar, xdmf_float);
  xml += xdmf_attribute(h5_name, "/contacts/strong", "Cell", "Scalar", scalar,
                        R"(NumberType="UChar" Precision="1")");
  return xml + "    </Grid>\n";
}

// The periodic cell [0, L1] x [0, L2] x [0, L3] as one hexahedron; XDMF lists z y x.
std::string cell_grid(const h5::Checkpoint& c) {
  const Vec3& l = c.cell.lengths;
  return fmt::format(R"(    <Grid Name="cell" GridType="Uniform">
      <Time Value="{3:.17g}"/>
      <Topology TopologyType="3DCoRectMesh" Dimensions="2 2 2"/>
      <Geometry GeometryType="ORIGIN_DXDYDZ">
        <DataItem Name="Origin" Dimensions="3" NumberType="Float" Precision="8" Format="XML">0 0 0</DataItem>
        <DataItem Name="Spacing" Dimensions="3" NumberType="Float" Precision="8" Format="XML">{2:.17g} {1:.17g} {0:.17g}</DataItem>
      </Geometry>
    </Grid>
)",
                     l.x(), l.y(), l.z(), c.time);
}

std::string particle_xdmf_text(const std::string& h5_name, const h5::Checkpoint& c) {
  const std::string name = xml_escaped(h5_name);
  return R"(<?xml version="1.0" ?>
<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>
<Xdmf Version="3.0">
  <Domain>
)" + particles_grid(name, c) +
         contacts_grid(name, c) + cell_grid(c) + "  </Domain>\n</Xdmf>\n";
}

} // namespace

ParticleXdmfSummary write_particle_xdmf(const h5::Checkpoint& checkpoint, const std::string& checkpoint_path,
                                        const std::string& xdmf_path) {
  check_xmf_path(xdmf_path);
  check_vis_rows(checkpoint, xdmf_path);
  ParticleXdmfSummary summary;
  summary.xdmf_path = xdmf_path;
  summary.data_path = data_path_for(xdmf_path);
  const ContactVisArrays contacts = contact_vis_arrays(checkpoint);
  // Data first, then the description that points at it: a reader never finds a dangling .xmf.
  write_vis_hdf5(summary.data_path, checkpoint, checkpoint_path, contacts);
  h5::write_text_atomically(
      xdmf_path,
      particle_xdmf_text(std::filesystem::path(summary.data_path).filename().string(), checkpoint));
  summary.particles = checkpoint.particles.size();
  summary.contacts = checkpoint.contacts.size();
  summary.strong_contacts = contacts.strong_count;
  summary.mean_normal_force = contacts.mean_normal_force;
  return summary;
}

} // namespace aniso::dem::interop
