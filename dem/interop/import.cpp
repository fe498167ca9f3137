#include "dem/interop/import.hpp"

#include "common/cell.hpp"
#include "common/error.hpp"
#include "dem/data/spatial_order.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/parameters.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>

namespace aniso::dem::interop {
namespace {

// One density for the assembly (aniso's time step and inertial number use it).
double assembly_density(const ImportedAssembly& assembly, const DemConfig& config,
                        const config::Reader& reader) {
  if (assembly.density.empty()) return config.particles.density;
  const auto [low, high] = std::minmax_element(assembly.density.begin(), assembly.density.end());
  require_input(*high - *low <= 1e-12 * *high,
                fmt::format("import of '{}': densities from {:g} to {:g} kg/m^3: aniso holds one density "
                            "per assembly (its time step and inertial number use it)",
                            assembly.source, *low, *high));
  require_input(!reader.given("dem.particles.density") ||
                    std::abs(config.particles.density - *high) <= 1e-9 * *high,
                fmt::format("import of '{}': dem.particles.density = {:g} kg/m^3, the file has {:g}: remove "
                            "the key (the file's density is used)",
                            assembly.source, config.particles.density, *high));
  return *high;
}

// Sets the config's particle keys to what the file holds, for the settings and the provenance.
void adopt_particles(DemConfig& config, config::Reader& reader, const ImportedAssembly& assembly, double d50,
                     double density) {
  auto& pc = config.particles;
  const auto [smallest, largest] = std::minmax_element(assembly.diameter.begin(), assembly.diameter.end());
  const std::string note = "from the imported file " + assembly.source;
  pc.count = static_cast<std::int64_t>(assembly.size());
  pc.diameter_min = *smallest;
  pc.diameter_max = *largest;
  pc.d50 = d50;
  pc.density = density;
  pc.aspect_ratio = assembly.aspect_ratio;
  if (assembly.aspect_ratio != 1.0) {
    const double limit = 2.0 * std::atan(assembly.aspect_ratio);
    require_input(
        assembly.splice_angle > 0 && assembly.splice_angle < limit,
        fmt::format("import of '{}': splice angle {:.6g} degrees, expected between 0 and 2 atan(aspect "
                    "ratio) = {:.6g} degrees for aspect ratio {}",
                    assembly.source, assembly.splice_angle * 180 / std::numbers::pi,
                    limit * 180 / std::numbers::pi, assembly.aspect_ratio));
    pc.splice_angle = assembly.splice_angle;
    reader.replace("dem.particles.splice_angle_degrees",
                   fmt::format("{:.17g}", assembly.splice_angle * 180 / std::numbers::pi), note);
  }
  reader.replace("dem.particles.count", std::to_string(pc.count), note);
  reader.replace("dem.particles.diameter_min", fmt::format("{}", pc.diameter_min), note);
  reader.replace("dem.particles.diameter_max", fmt::format("{}", pc.diameter_max), note);
  reader.replace("dem.particles.d50", fmt::format("{}", d50), note);
  reader.replace("dem.particles.density", fmt::format("{}", density), note);
  reader.replace("dem.particles.aspect_ratio", fmt::format("{:.17g}", assembly.aspect_ratio), note);
}

// Particles numbered in spatial order of the source rows taken in source-id order, so that the
// numbering depends on the assembly, not on the order of the file's rows.
data::Particles numbered_particles(const ImportedAssembly& assembly, double density, double splice_angle,
                                   double d50, std::vector<std::uint64_t>& source_id) {
  std::vector<std::size_t> by_id(assembly.size());
  std::iota(by_id.begin(), by_id.end(), std::size_t{0});
  std::sort(by_id.begin(), by_id.end(),
            [&](std::size_t a, std::size_t b) { return assembly.id[a] < assembly.id[b]; });
  const PeriodicCell cell(assembly.lengths);
  std::vector<Vec3> positions(assembly.size());
  for (std::size_t r = 0; r < by_id.size(); ++r)
    positions[r] = cell.wrap(assembly.position[by_id[r]]);
  const std::vector<std::size_t> order = data::spatial_order(positions, assembly.lengths, 2.0 * d50);
  data::Particles particles;
  source_id.resize(order.size());
  for (std::size_t id = 0; id < order.size(); ++id) {
    const std::size_t row = by_id[order[id]];
    // An ovoid's body z turned onto its axis (the turn about the axis does not matter: the shape is
    // a solid of revolution).
    const Quat orientation =
        assembly.axis.empty() ? Quat::Identity() : Quat::FromTwoVectors(Vec3::UnitZ(), assembly.axis[row]);
    particles.add(id, 0.5 * assembly.diameter[row], assembly.aspect_ratio, splice_angle, density,
                  positions[order[id]], orientation.normalized());
    particles.velocity[id] = assembly.velocity[row];
    particles.angular_velocity[id] = assembly.angular_velocity[row];
    source_id[id] = assembly.id[row];
  }
  return particles;
}

// Gives each contact the dumped tangential force of its pair, on the tangent plane and within
// the Coulomb limit, and sums the particles' forces and torques again from the contact forces.
void adopt_dumped_forces(h5::Checkpoint& checkpoint, const std::vector<DumpedContact>& dumped,
                         double friction, ImportSummary& summary) {
  auto& p = checkpoint.particles;
  auto& c = checkpoint.contacts;
  std::map<std::uint64_t, std::uint64_t> id_of_source;
  for (std::size_t k = 0; k < p.size(); ++k)
    id_of_source.emplace(p.source_id[k], p.id[k]);
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::size_t> row_of_pair;
  for (std::size_t k = 0; k < c.size(); ++k)
    row_of_pair.emplace(std::make_pair(c.particles[k][0], c.particles[k][1]), k);
  std::vector<char> given(c.size(), 0);
  for (const DumpedContact& contact : dumped) {
    const auto i = id_of_source.find(contact.id_i), j = id_of_source.find(contact.id_j);
    require_input(i != id_of_source.end() && j != id_of_source.end(),
                  fmt::format("import: the contact dump names particle {}, which the assembly does not have",
                              i == id_of_source.end() ? contact.id_i : contact.id_j));
    const bool swapped = i->second > j->second; // rows hold the force on the lower aniso id
    const auto row = row_of_pair.find(swapped ? std::make_pair(j->second, i->second)
                                              : std::make_pair(i->second, j->second));
    if (row == row_of_pair.end()) {
      ++summary.dumped_apart;
      continue;
    }
    const std::size_t k = row->second;
    given[k] = 1;
    ++summary.dumped_matched;
    const Vec3& n = c.normal[k];
    const Vec3 normal_part = c.force[k].dot(n) * n;
    Vec3 tangential = swapped ? Vec3(-contact.tangential_force) : contact.tangential_force;
    // Onto the tangent plane and within the Coulomb limit; a force already there to round-off (an
    // aniso export) is kept bit for bit, so that import -> export -> import changes nothing.
    constexpr double round_off = 1e-9;
    if (std::abs(tangential.dot(n)) > round_off * tangential.norm()) tangential -= tangential.dot(n) * n;
    const double limit = friction * normal_part.norm();
    if (tangential.norm() > (1 + round_off) * limit) {
      tangential *= limit / tangential.norm();
      ++summary.sliding;
    }
    c.sliding[k] = tangential.norm() >= (1 - round_off) * limit ? 1 : 0;
    c.tangential_force[k] = tangential;
    c.force[k] = normal_part + tangential;
  }
  summary.without_dumped = static_cast<std::size_t>(std::count(given.begin(), given.end(), 0));
  // Forces and torques from the contacts alone: the sum the force pass makes (lever arms from
  // each centre to the contact point).
  const PeriodicCell cell(checkpoint.cell.lengths);
  std::fill(p.force.begin(), p.force.end(), Vec3::Zero());
  std::fill(p.torque.begin(), p.torque.end(), Vec3::Zero());
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto i = c.particles[k][0], j = c.particles[k][1];
    const Vec3 arm_i = cell.minimum_image(c.point[k] - p.position[i]);
    const Vec3 arm_j = cell.minimum_image(c.point[k] - p.position[j]);
    p.force[i] += c.force[k];
    p.force[j] -= c.force[k];
    p.torque[i] += arm_i.cross(c.force[k]);
    p.torque[j] -= arm_j.cross(c.force[k]);
  }
}

} // namespace

h5::Checkpoint import_assembly(const ImportedAssembly& assembly, const std::vector<DumpedContact>* dumped,
                               DemConfig& config, config::Reader& reader, ImportSummary& summary) {
  require_input(assembly.size() > 0, fmt::format("import of '{}': no particles", assembly.source));
  const double density = assembly_density(assembly, config, reader);
  const double d50 = median_by_volume(assembly.diameter);
  adopt_particles(config, reader, assembly, d50, density);
  std::vector<std::uint64_t> source_id;
  data::Particles particles =
      numbered_particles(assembly, density, config.particles.splice_angle, d50, source_id);
  const SimulationSettings settings = io::settings_from_config(config, config.particles.diameter_min);
  // Every rank builds the same whole assembly (one force pass; rank counts cannot change it).
  const mpi::Comm self(MPI_COMM_SELF);
  const Simulation simulation(std::move(particles), PeriodicCell(assembly.lengths), model::CellControl{},
                              settings, self);
  h5::Checkpoint checkpoint = io::to_checkpoint(simulation);
  checkpoint.particles.source_id = source_id;
  summary.contacts = checkpoint.contacts.size();
  summary.d50 = d50;
  summary.density = density;
  summary.mean_stress = mean_stress_compression_positive(simulation.stress());
  if (dumped == nullptr) return checkpoint;
  adopt_dumped_forces(checkpoint, *dumped, config.material.friction, summary);
  // A simulation restored from the new rows checks them (overlaps, every touching pair has its
  // row) and measures the equilibrium of the forces they give.
  const Simulation restored = io::from_checkpoint(checkpoint, assembly.source, self);
  summary.mean_stress = mean_stress_compression_positive(restored.stress());
  h5::Checkpoint result = io::to_checkpoint(restored);
  result.particles.source_id = source_id;
  return result;
}

h5::Checkpoint rows_for_rank(const h5::Checkpoint& whole, const mpi::Comm& comm) {
  if (comm.is_root()) return whole;
  h5::Checkpoint none = whole;
  none.particles = {};
  none.contacts = {};
  return none;
}

} // namespace aniso::dem::interop
