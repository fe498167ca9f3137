#include "dem/io/checkpoint.hpp"

#include "common/error.hpp"
#include "common/units.hpp"
#include "dem/io/parameter_ranges.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace aniso::dem::io {

h5::Checkpoint to_checkpoint(const Simulation& simulation, double d50,
                             const std::vector<std::array<std::uint64_t, 4>>& rng_state) {
  h5::Checkpoint c;
  c.time = simulation.time();
  c.step = simulation.step_count();
  const SimulationSettings& s = simulation.settings();
  c.time_step = s.time_step;
  c.cell = simulation.cell_state();
  const data::Particles& p = simulation.particles();
  const std::size_t n = p.n_owned; // each rank writes the particles it owns
  c.particles.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    c.particles.id[k] = p.id[k];
    c.particles.diameter[k] = 2 * p.radius[k];
    c.particles.aspect_ratio[k] = p.aspect_ratio[k];
    c.particles.mass[k] = p.mass[k];
    c.particles.inertia[k] = p.inertia[k];
    c.particles.position[k] = p.position[k];
    c.particles.orientation[k] = p.orientation[k];
    c.particles.velocity[k] = p.velocity[k];
    c.particles.angular_velocity[k] = p.angular_velocity[k];
    c.particles.force[k] = p.force[k];
    c.particles.torque[k] = p.torque[k];
  }
  const auto& pairs = simulation.neighbors().pairs();
  const auto& records = simulation.neighbors().records();
  const auto& history = simulation.neighbors().history();
  const Vec3& lengths = simulation.cell().lengths();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (records[k].overlap <= 0 || pairs[k].i >= p.n_owned) continue; // written by the owner of the lower id
    const auto i = pairs[k].i, j = pairs[k].j;
    const Vec3& branch = records[k].branch;
    const Vec3 raw = p.position[j] - p.position[i];
    Vec3i shift;
    for (int a = 0; a < 3; ++a)
      shift[a] = static_cast<int>(std::nearbyint((branch[a] - raw[a]) / lengths[a]));
    c.contacts.particles.push_back({p.id[i], p.id[j]});
    c.contacts.image_shift.push_back(shift);
    c.contacts.normal.push_back(records[k].normal);
    c.contacts.point.push_back(simulation.cell().wrap(p.position[i] + records[k].point));
    c.contacts.overlap.push_back(records[k].overlap);
    c.contacts.force.push_back(records[k].force_on_i);
    c.contacts.tangential_force.push_back(history[k].tangential_force);
    c.contacts.sliding.push_back(history[k].sliding ? 1 : 0);
  }
  c.parameters = {
      {"shear_modulus", s.material.shear_modulus, units::pascal},
      {"poisson_ratio", s.material.poisson_ratio, units::none},
      {"friction", s.material.friction, units::none},
      {"damping_ratio", s.material.damping_ratio, units::none},
      {"density", s.density, units::density},
      {"d50", d50, units::metre},
      {"skin", s.skin, units::metre},
      {"control_interval", static_cast<double>(s.control_interval), units::none},
      {"servo_gain", s.servo.gain, units::none},
      {"servo_max_rate", s.servo.max_rate, units::per_second},
      {"servo_integral_intervals", s.servo.integral_intervals, units::none},
      {"explosion_overlap", s.explosion_overlap, units::none},
      {"global_damping", s.global_damping, units::none},
      {"global_damping_rate", simulation.global_damping_rate(), units::per_second},
      {"ovoid_splice_angle", s.splice_angle, units::radian},
      {"hertz_radius_curvature", s.hertz_radius == model::HertzRadius::curvature ? 1.0 : 0.0, units::none},
  };
  c.rng_state = rng_state;
  // Fresh at the stored step (collective: every rank writes its part of the checkpoint).
  const Equilibrium equilibrium = measure_equilibrium(p, simulation.neighbors(), simulation.comm());
  c.unbalanced_force_ratio = equilibrium.unbalanced_force_ratio;
  c.kinetic_elastic_ratio = equilibrium.kinetic_elastic_ratio();
  return c;
}

SimulationSettings settings_from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path) {
  // Each stored setting within the range its config key allows (dem/io/parameter_ranges.hpp): a
  // file is refused for what the configuration would refuse (control_interval 0 divided by zero,
  // a Poisson ratio of 0.7 gave a NaN critical step that passed the stability check).
  const auto get = [&](const char* name, const config::Range& range) {
    const double value = h5::parameter(checkpoint, name, path);
    if (!range.contains(value)) {
      throw FileError(fmt::format("{}: /parameters (attribute '{}'): value {:g} is out of range, expected {}",
                                  path, name, value, range.describe()));
    }
    return value;
  };
  SimulationSettings s;
  s.material.shear_modulus = get("shear_modulus", ranges::shear_modulus());
  s.material.poisson_ratio = get("poisson_ratio", ranges::poisson_ratio());
  s.material.friction = get("friction", ranges::friction());
  s.material.damping_ratio = get("damping_ratio", ranges::contact_damping());
  s.density = get("density", ranges::density());
  if (!(checkpoint.time_step > 0.0))
    throw FileError(
        fmt::format("{}: / (attribute time_step): value {:g}, expected > 0", path, checkpoint.time_step));
  s.time_step = checkpoint.time_step;
  s.skin = get("skin", ranges::length());
  s.control_interval = static_cast<std::int64_t>(get("control_interval", ranges::control_interval()));
  s.servo.gain = get("servo_gain", ranges::servo_gain());
  s.servo.max_rate = get("servo_max_rate", config::Range::non_negative()); // 0: no cap
  s.servo.integral_intervals = get("servo_integral_intervals", config::Range::positive());
  s.explosion_overlap = get("explosion_overlap", ranges::explosion_overlap());
  // Checkpoints written before ovoids landed hold spheres only: the defaults are exact for them.
  if (h5::has_parameter(checkpoint, "ovoid_splice_angle")) {
    const config::Range radians{0.0, ranges::splice_angle_degrees().max * std::numbers::pi / 180.0, false,
                                false};
    s.splice_angle = get("ovoid_splice_angle", radians);
  }
  if (h5::has_parameter(checkpoint, "hertz_radius_curvature") &&
      get("hertz_radius_curvature", config::Range::closed(0.0, 1.0)) != 0.0)
    s.hertz_radius = model::HertzRadius::curvature;
  // Checkpoints written before the global damping landed ran without it.
  if (h5::has_parameter(checkpoint, "global_damping"))
    s.global_damping = get("global_damping", ranges::global_damping());
  return s;
}

namespace {

// The particle rows a simulation can start from: at least one particle, positive sizes, masses
// and inertias, and aspect ratios the shapes support (h5::read_checkpoint has already refused
// positions outside the cell, for every stage).
void check_particle_rows(const h5::Checkpoint& checkpoint, const std::string& path) {
  const auto& rows = checkpoint.particles;
  if (rows.size() == 0) throw FileError(path + ": /particles: no particles");
  const config::Range aspect = ranges::aspect_ratio();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto refuse = [&](const char* dataset, const std::string& what) {
      throw FileError(
          fmt::format("{}: /particles/{}: row {} (particle id {}): {}", path, dataset, k, rows.id[k], what));
    };
    if (!(rows.diameter[k] > 0.0)) refuse("diameter", fmt::format("{:g}, expected > 0", rows.diameter[k]));
    if (!(rows.mass[k] > 0.0)) refuse("mass", fmt::format("{:g}, expected > 0", rows.mass[k]));
    if (!(rows.inertia[k].minCoeff() > 0.0)) refuse("inertia", "a principal moment is not > 0");
    if (!aspect.contains(rows.aspect_ratio[k]))
      refuse("aspect_ratio", fmt::format("{:g}, expected {}", rows.aspect_ratio[k], aspect.describe()));
  }
}

} // namespace

Simulation from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path, const mpi::Comm& comm) {
  check_particle_rows(checkpoint, path);
  const auto& rows = checkpoint.particles;
  data::Particles particles;
  particles.resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    particles.id[k] = rows.id[k];
    particles.radius[k] = 0.5 * rows.diameter[k];
    particles.aspect_ratio[k] = rows.aspect_ratio[k];
    particles.mass[k] = rows.mass[k];
    particles.inertia[k] = rows.inertia[k];
    particles.position[k] = rows.position[k];
    particles.orientation[k] = rows.orientation[k];
    particles.velocity[k] = rows.velocity[k];
    particles.angular_velocity[k] = rows.angular_velocity[k];
    particles.force[k] = rows.force[k];
    particles.torque[k] = rows.torque[k];
  }
  const SimulationSettings settings = settings_from_checkpoint(checkpoint, path);
  Simulation simulation(std::move(particles), checkpoint.cell, settings, checkpoint.time, checkpoint.step,
                        true, comm);
  simulation.restore_contacts(checkpoint.contacts, path);
  simulation.restore_stress();
  if (h5::has_parameter(checkpoint, "global_damping_rate"))
    simulation.restore_global_damping_rate(h5::parameter(checkpoint, "global_damping_rate", path));
  return simulation;
}

} // namespace aniso::dem::io
