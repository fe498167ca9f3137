#include "dem/simulation.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "dem/force_pass.hpp"
#include "dem/model/integrator.hpp"
#include "dem/parallel/contact_routing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

namespace aniso::dem {

namespace {

// The distinct aspect ratios, in the order each first appears (by rank, then by row: id order
// for a distributed read's slabs), the same list on every rank of `comm` (collective).
std::vector<double> aspect_ratios_in_id_order(const data::Particles& particles, const mpi::Comm& comm) {
  std::vector<double> seen;
  const auto note = [&](double aspect_ratio) {
    if (std::find(seen.begin(), seen.end(), aspect_ratio) == seen.end()) seen.push_back(aspect_ratio);
  };
  for (std::size_t k = 0; k < particles.size(); ++k)
    note(particles.aspect_ratio[k]);
  if (comm.size() == 1) return seen;
  std::vector<char> mine;
  ByteWriter out(mine);
  for (const double aspect_ratio : seen)
    out.put(aspect_ratio);
  seen.clear();
  for (const auto& buffer : all_gather_bytes(comm, mine)) {
    ByteReader in(buffer);
    while (!in.done())
      note(in.get<double>());
  }
  return seen;
}

} // namespace

Simulation::Simulation(data::Particles particles, const PeriodicCell& cell, const model::CellControl& control,
                       const SimulationSettings& settings, double time, std::int64_t step, bool dealt,
                       const mpi::Comm& comm)
    : particles_(std::move(particles)), shapes_(settings.splice_angle), cell_(cell), control_(control),
      settings_(settings), neighbors_(settings.skin), domain_(comm), time_(time), step_(step) {
  // Every rank holds every particle, or (dealt) its share: then the reductions make these global.
  const mpi::Comm self(MPI_COMM_SELF);
  const mpi::Comm& holders = dealt ? comm : self;
  model::require_stable_time_step(
      settings_.time_step,
      holders.min(model::critical_time_step(particles_, settings_.density, settings_.material)));
  n_particles_ = holders.sum(static_cast<std::int64_t>(particles_.size()));
  ExactSum solid, mass;
  double max_radius = 0;
  for (std::size_t k = 0; k < particles_.size(); ++k) {
    mass.add(particles_.mass[k]);
    solid.add(
        model::particle_volume(particles_.radius[k], particles_.aspect_ratio[k], settings_.splice_angle));
    max_radius = std::max(max_radius, particles_.radius[k]);
  }
  solid_volume_ = holders.sum_exact(solid).value();
  mean_mass_ = holders.sum_exact(mass).value() / static_cast<double>(n_particles_);
  for (const double aspect_ratio : aspect_ratios_in_id_order(particles_, holders))
    shapes_.add(aspect_ratio);
  max_radius = holders.max(max_radius);
  neighbors_.set_max_radius(max_radius);
  reach_ = 2 * max_radius + settings_.skin;
  // Deal particles round-robin, then let the first decomposition send each to the rank of its bin.
  if (comm.size() > 1 && !dealt) {
    data::Particles share;
    for (std::size_t k = static_cast<std::size_t>(comm.rank()); k < particles_.size();
         k += static_cast<std::size_t>(comm.size())) {
      share.append(particles_, k);
    }
    share.n_owned = share.size();
    particles_ = std::move(share);
  }
  rebuild_decomposition();
}

Simulation::Simulation(data::Particles particles, const PeriodicCell& cell, const model::CellControl& control,
                       const SimulationSettings& settings, const mpi::Comm& comm)
    : Simulation(std::move(particles), cell, control, settings, 0.0, 0, false, comm) {
  compute_forces();
  stress_ = average_stress(particles_, cell_, neighbors_, comm);
  update_equilibrium();
}

Simulation::Simulation(data::Particles particles, const PeriodicCell& cell, const model::CellControl& control,
                       const SimulationSettings& settings, const RestartState& restart, const mpi::Comm& comm)
    : Simulation(std::move(particles), cell, control, settings, restart.time, restart.step, restart.dealt,
                 comm) {
  // Dealt contacts go to the ranks that own either particle, now that the particles are there.
  const std::vector<StoredContact> routed =
      restart.dealt ? parallel::route_contacts(restart.contacts, particles_, n_particles_, comm)
                    : std::vector<StoredContact>{};
  restore_contact_records(restart.dealt ? routed : restart.contacts, particles_, cell_, settings_.material,
                          contact_input(), neighbors_, restart.source);
  measure_stress_now();
  damping_rate_ = restart.global_damping_rate;
}

void Simulation::rebuild_decomposition() {
  std::vector<Vec3> owned(particles_.position.begin(),
                          particles_.position.begin() + static_cast<std::ptrdiff_t>(particles_.n_owned));
  if (domain_.needs_partition(cell_, reach_, particles_.n_owned, 1.2))
    domain_.partition(cell_, reach_, owned);
  const std::vector<data::HistoryRecord> carried = halo_.migrate(particles_, cell_, domain_, neighbors_);
  halo_.exchange_ghosts(particles_, cell_, domain_);
  neighbors_.build(particles_, cell_, carried);
}

void Simulation::compute_forces(bool measure) {
  if (measure) contact_sums_.reset(measures_equilibrium(), particles_.n_owned);
  const ForcePass pass =
      compute_contact_forces(particles_, cell_, control_.strain_rate, settings_.material, settings_.time_step,
                             contact_input(), neighbors_, bodies_, measure ? &contact_sums_ : nullptr);
  contact_sums_step_ = measure ? step_ + 1 : -1; // the forces of the step being taken
  // Explosion guard: an overlap this large means the step or the loading rate is far too large.
  // Every rank must stop together, so the verdict is shared before anyone throws.
  const bool exploded = !(pass.worst_overlap <= settings_.explosion_overlap);
  if (comm().size() > 1 ? comm().any(exploded) : exploded) {
    if (!exploded) throw NumericalError(fmt::format("step {}: the run exploded on another rank", step_ + 1));
    const data::Pair& pair = neighbors_.pairs()[static_cast<std::size_t>(pass.worst_pair)];
    throw NumericalError(
        fmt::format("step {}: overlap of particles {} and {} is {:.3g} of the smaller radius "
                    "(limit {}): the run exploded; lower the time step fraction or the loading rate",
                    step_ + 1, particles_.id[pair.i], particles_.id[pair.j], pass.worst_overlap,
                    settings_.explosion_overlap));
  }
}

void Simulation::update_control() {
  // The force pass of this step summed the contacts if it knew a control update would follow;
  // otherwise (a control update outside step()) one traversal does: the same exact sums.
  const data::ControlMeasures measures = data::reduce_control_measures(
      contact_sums_step_ == step_ ? contact_sums_ : data::sum_contacts(particles_, neighbors_), particles_,
      cell_, comm());
  stress_ = measures.stress;
  if (!std::isfinite(stress_.sum())) {
    throw NumericalError(fmt::format("step {}: the stress is not finite: the run exploded", step_));
  }
  if (measures_equilibrium()) {
    // The force pass summed the contacts' part if it knew this update would follow.
    const bool summed = contact_sums_step_ == step_ && contact_sums_.balance.has_value();
    equilibrium_ = summed ? measure_equilibrium(particles_, *contact_sums_.balance, comm())
                          : measure_equilibrium(particles_, neighbors_, comm());
    update_damping_rate();
  }
  const double interval = static_cast<double>(settings_.control_interval) * settings_.time_step;
  model::update_strain_rates(control_, stress_, measures.stiffness, interval, settings_.servo);
}

void Simulation::update_equilibrium() {
  equilibrium_ = measure_equilibrium(particles_, neighbors_, comm());
  update_damping_rate();
}

void Simulation::watch_equilibrium(bool on) {
  watch_equilibrium_ = on;
  if (on) update_equilibrium();
}

double Simulation::critical_time_step() const {
  return comm().min(model::critical_time_step(particles_, settings_.density, settings_.material));
}

void Simulation::reconfigure(const SimulationSettings& settings) {
  const auto fixed_part = [](const SimulationSettings& s) {
    return std::tuple(s.material.shear_modulus, s.material.poisson_ratio, s.density, s.skin,
                      s.servo.integral_intervals, s.explosion_overlap, s.splice_angle, s.hertz_radius);
  };
  check_invariant(fixed_part(settings) == fixed_part(settings_),
                  "reconfigure keeps the material, shape and neighbour-list settings of the assembly");
  model::require_stable_time_step(settings.time_step, critical_time_step());
  settings_ = settings;
  if (settings_.global_damping > 0) {
    update_equilibrium(); // the rate needs the present contact stiffness, not a stale one
  } else {
    update_damping_rate();
  }
}

void Simulation::update_damping_rate() {
  // Critical damping of a particle of mean mass on one contact of mean stiffness is
  // gamma = 2 sqrt(k/m); without contacts there is nothing to scale by and nothing to damp.
  damping_rate_ = equilibrium_.n_contacts > 0 ? 2.0 * settings_.global_damping *
                                                    std::sqrt(equilibrium_.mean_normal_stiffness / mean_mass_)
                                              : 0.0;
}

void Simulation::step() {
  const double dt = settings_.time_step;
  const double damping_factor = std::exp(-0.5 * dt * damping_rate_);
  const double spin_damping_factor =
      std::exp(-0.5 * dt * damping_rate_ * settings_.global_damping_spin_factor);
  auto clock = SectionTimes::Clock::now();
  model::kick(particles_, 0.5 * dt);
  if (damping_rate_ > 0) model::damp_velocities(particles_, damping_factor, spin_damping_factor);
  model::drift(particles_, cell_, control_.strain_rate, dt);
  clock = times_->add_since(integration, clock);
  data::ListMotion motion = neighbors_.measure_motion(particles_, cell_);
  if (comm().size() > 1) {
    const std::array<double, 3> local{motion.separation, motion.gap, motion.step_gap};
    const std::vector<double> global = comm().max(local);
    motion = {global[0], global[1], global[2]};
  }
  if (neighbors_.needs_rebuild(motion)) {
    rebuild_decomposition();
    clock = times_->add_since(list_update, clock);
  } else {
    neighbors_.set_motion(motion);
    clock = times_->add_since(list_update, clock);
    halo_.update_ghosts(particles_, domain_);
    clock = times_->add_since(halo, clock);
  }
  compute_forces((step_ + 1) % settings_.control_interval == 0);
  clock = times_->add_since(force_pass, clock);
  model::kick(particles_, 0.5 * dt);
  if (damping_rate_ > 0) model::damp_velocities(particles_, damping_factor, spin_damping_factor);
  time_ += dt;
  ++step_;
  clock = times_->add_since(integration, clock, 0); // the step's second half: one call per step
  if (at_control_update()) {
    update_control();
    times_->add_since(control_update, clock);
  }
}

StateMeasures Simulation::measure() const {
  return measure_state(particles_, cell_, neighbors_, solid_volume_, n_particles_, comm());
}

void Simulation::measure_stress_now() {
  stress_ = average_stress(particles_, cell_, neighbors_, comm());
  equilibrium_ = measure_equilibrium(particles_, neighbors_, comm());
}

double Simulation::geometric_overlap(std::uint32_t i, std::uint32_t j, const Vec3& guess) const {
  return pair_overlap(particles_, cell_, contact_input(), i, j, guess);
}

double Simulation::servo_error() const {
  return dem::model::servo_error(control_, stress_);
}

void Simulation::set_control(const model::CellControl& control) {
  control_ = control;
  update_control();
}

} // namespace aniso::dem
