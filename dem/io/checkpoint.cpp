#include "dem/io/checkpoint.hpp"

#include "common/error.hpp"
#include "common/mpi.hpp"
#include "common/units.hpp"
#include "dem/io/parameters.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

namespace aniso::dem::io {

h5::Checkpoint to_checkpoint(const Simulation& simulation, const CheckpointLabels& labels) {
  h5::Checkpoint c;
  c.time = simulation.time();
  c.step = simulation.step_count();
  const SimulationSettings& s = simulation.settings();
  c.time_step = s.time_step;
  c.cell = cell_state(simulation.cell(), simulation.control());
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
  c.parameters = stored_parameters(s);
  // The engine's state, not a parameter: a restart between control updates needs it.
  c.parameters.push_back({"global_damping_rate", simulation.global_damping_rate(), units::per_second});
  c.rng_state = labels.rng_state;
  c.run_id = labels.run_id;
  // Fresh at the stored step (collective: every rank writes its part of the checkpoint).
  const Equilibrium equilibrium = measure_equilibrium(p, simulation.neighbors(), simulation.comm());
  c.unbalanced_force_ratio = equilibrium.unbalanced_force_ratio;
  c.kinetic_elastic_ratio = equilibrium.kinetic_elastic_ratio();
  return c;
}

h5::Checkpoint write_checkpoint(const std::string& path, const Simulation& simulation,
                                const CheckpointLabels& labels, const h5::Provenance& provenance,
                                const std::function<void(h5::File&)>& add) {
  h5::Checkpoint checkpoint = to_checkpoint(simulation, labels);
  h5::write_checkpoint(path, checkpoint, provenance, simulation.comm(), add);
  return checkpoint;
}

namespace {

// The particle rows a simulation can start from: at least one particle, positive sizes, masses
// and inertias, and aspect ratios the shapes support (h5::read_checkpoint has already refused
// positions outside the cell, for every stage). Of a slab read each rank checks its own rows, so
// the ranks agree on the first bad row (the lowest rank's) and all fail with it.
std::optional<std::string> first_bad_particle_row(const h5::Checkpoint& checkpoint, const std::string& path) {
  const auto& rows = checkpoint.particles;
  const bool slab = checkpoint.share == h5::RowShare::slab; // rows of a slab: row number = id
  if (!slab && rows.size() == 0) return path + ": /particles: no particles";
  const config::Range aspect = key_range("dem.particles.aspect_ratio");
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto refusal = [&](const char* dataset, const std::string& what) {
      return fmt::format("{}: /particles/{}: row {} (particle id {}): {}", path, dataset,
                         slab ? rows.id[k] : k, rows.id[k], what);
    };
    if (!(rows.diameter[k] > 0.0))
      return refusal("diameter", fmt::format("{:g}, expected > 0", rows.diameter[k]));
    if (!(rows.mass[k] > 0.0)) return refusal("mass", fmt::format("{:g}, expected > 0", rows.mass[k]));
    if (!(rows.inertia[k].minCoeff() > 0.0)) return refusal("inertia", "a principal moment is not > 0");
    if (!aspect.contains(rows.aspect_ratio[k]))
      return refusal("aspect_ratio",
                     fmt::format("{:g}, expected {}", rows.aspect_ratio[k], aspect.describe()));
  }
  return std::nullopt;
}

void check_particle_rows(const h5::Checkpoint& checkpoint, const std::string& path, const mpi::Comm& comm) {
  const std::optional<std::string> problem = first_bad_particle_row(checkpoint, path);
  if (checkpoint.share != h5::RowShare::slab) {
    if (problem) throw FileError(*problem); // every rank holds every row and finds the same one
    return;
  }
  if (const auto first = mpi::first_problem(comm, problem))
    throw FileError(first->text + (comm.size() > 1 ? fmt::format(" (found on rank {})", first->rank) : ""));
}

} // namespace

Simulation from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path, const mpi::Comm& comm) {
  check_particle_rows(checkpoint, path, comm);
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
  RestartState restart;
  restart.time = checkpoint.time;
  restart.step = checkpoint.step;
  restart.source = fmt::format("checkpoint '{}'", path);
  const h5::ContactRows& rows_c = checkpoint.contacts;
  restart.contacts.resize(rows_c.size());
  for (std::size_t c = 0; c < rows_c.size(); ++c) {
    StoredContact& stored = restart.contacts[c];
    stored.ids = rows_c.particles[c];
    stored.normal = rows_c.normal[c];
    stored.point = rows_c.point[c];
    stored.overlap = rows_c.overlap[c];
    stored.force = rows_c.force[c];
    stored.tangential_force = rows_c.tangential_force[c];
    stored.sliding = rows_c.sliding[c] != 0;
  }
  restart.global_damping_rate = h5::parameter(checkpoint, "global_damping_rate", path);
  restart.dealt = checkpoint.share == h5::RowShare::slab;
  const auto [cell, control] = cell_and_control(checkpoint.cell);
  Simulation simulation(std::move(particles), cell, control, settings_from_checkpoint(checkpoint, path),
                        restart, comm);
  return simulation;
}

h5::CellState cell_state(const PeriodicCell& cell, const model::CellControl& control) {
  h5::CellState state;
  state.lengths = cell.lengths();
  state.reference_lengths = cell.reference_lengths();
  state.strain_rate = control.strain_rate;
  for (std::size_t a = 0; a < 3; ++a)
    state.mode[a] =
        control.mode[a] == model::AxisMode::stress ? h5::AxisMode::stress : h5::AxisMode::strain_rate;
  state.target = control.target;
  state.hold_mean_stress = control.hold_mean_stress;
  state.mean_stress_target = control.mean_stress_target;
  state.servo_state = control.servo_state;
  return state;
}

std::pair<PeriodicCell, model::CellControl> cell_and_control(const h5::CellState& state) {
  model::CellControl control;
  control.strain_rate = state.strain_rate;
  for (std::size_t a = 0; a < 3; ++a)
    control.mode[a] =
        state.mode[a] == h5::AxisMode::stress ? model::AxisMode::stress : model::AxisMode::strain_rate;
  control.target = state.target;
  control.hold_mean_stress = state.hold_mean_stress;
  control.mean_stress_target = state.mean_stress_target;
  control.servo_state = state.servo_state;
  return {PeriodicCell(state.lengths, state.reference_lengths), control};
}

} // namespace aniso::dem::io
