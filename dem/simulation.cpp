#include "dem/simulation.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "dem/force_pass.hpp"
#include "dem/model/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace aniso::dem {

Simulation::Simulation(data::Particles particles, const h5::CellState& control,
                       const SimulationSettings& settings, double time, std::int64_t step, bool forces_valid,
                       const mpi::Comm& comm)
    : particles_(std::move(particles)), shapes_(settings.splice_angle),
      cell_(control.lengths, control.reference_lengths), control_(control), settings_(settings),
      neighbors_(settings.skin), domain_(comm), time_(time), step_(step) {
  // Every rank holds every particle here, so these are global without communication.
  model::require_stable_time_step(
      settings_.time_step, dem::model::critical_time_step(particles_, settings_.density, settings_.material));
  n_particles_ = static_cast<std::int64_t>(particles_.size());
  ExactSum solid, mass;
  for (std::size_t k = 0; k < particles_.size(); ++k) {
    mass.add(particles_.mass[k]);
    solid.add(
        model::particle_volume(particles_.radius[k], particles_.aspect_ratio[k], settings_.splice_angle));
    shapes_.add(particles_.aspect_ratio[k]);
  }
  solid_volume_ = solid.value();
  mean_mass_ = mass.value() / static_cast<double>(n_particles_);
  const double max_radius = *std::max_element(particles_.radius.begin(), particles_.radius.end());
  neighbors_.set_max_radius(max_radius);
  reach_ = 2 * max_radius + settings_.skin;
  // Deal particles round-robin, then let the first decomposition send each to the rank of its bin.
  if (comm.size() > 1) {
    data::Particles dealt;
    for (std::size_t k = static_cast<std::size_t>(comm.rank()); k < particles_.size();
         k += static_cast<std::size_t>(comm.size())) {
      dealt.append(particles_, k);
    }
    dealt.n_owned = dealt.size();
    particles_ = std::move(dealt);
  }
  rebuild_decomposition();
  if (!forces_valid) {
    compute_forces();
    stress_ = average_stress(particles_, cell_, neighbors_, comm);
    update_equilibrium();
  }
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
  if (measure) contact_sums_ = data::ContactSums{};
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
  if (watch_equilibrium_ || settings_.global_damping > 0) update_equilibrium();
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
  return comm().min(dem::model::critical_time_step(particles_, settings_.density, settings_.material));
}

void Simulation::set_time_step(double time_step) {
  model::require_stable_time_step(time_step, critical_time_step());
  settings_.time_step = time_step;
}

void Simulation::set_global_damping(double ratio) {
  settings_.global_damping = ratio;
  if (ratio > 0) {
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
  model::kick(particles_, 0.5 * dt);
  if (damping_rate_ > 0) model::damp_velocities(particles_, damping_factor);
  model::drift(particles_, cell_, control_.strain_rate, dt);
  data::ListMotion motion = neighbors_.measure_motion(particles_, cell_);
  if (comm().size() > 1) {
    const std::array<double, 3> local{motion.separation, motion.gap, motion.step_gap};
    const std::vector<double> global = comm().max(local);
    motion = {global[0], global[1], global[2]};
  }
  if (neighbors_.needs_rebuild(motion)) {
    rebuild_decomposition();
  } else {
    halo_.update_ghosts(particles_, domain_);
    neighbors_.set_motion(motion);
  }
  compute_forces((step_ + 1) % settings_.control_interval == 0);
  model::kick(particles_, 0.5 * dt);
  if (damping_rate_ > 0) model::damp_velocities(particles_, damping_factor);
  time_ += dt;
  ++step_;
  if (step_ % settings_.control_interval == 0) update_control();
}

StateMeasures Simulation::measure() const {
  return measure_state(particles_, cell_, neighbors_, solid_volume_, n_particles_, comm());
}

void Simulation::restore_stress() {
  stress_ = average_stress(particles_, cell_, neighbors_, comm());
  equilibrium_ = measure_equilibrium(particles_, neighbors_, comm());
}

double Simulation::geometric_overlap(std::uint32_t i, std::uint32_t j, const Vec3& guess) const {
  const Vec3 d = PeriodicCell::minimum_image_of_wrapped(particles_.position[j] - particles_.position[i],
                                                        cell_.lengths());
  const double radius_sum = particles_.radius[i] + particles_.radius[j];
  if (d.squaredNorm() >= radius_sum * radius_sum) return radius_sum - d.norm();
  if (particles_.aspect_ratio[i] == 1.0 && particles_.aspect_ratio[j] == 1.0) return radius_sum - d.norm();
  model::PairProperties properties;
  properties.effective_radius = particles_.radius[i] * particles_.radius[j] / radius_sum;
  const model::ConvexBody a =
      shapes_.body(particles_.radius[i], particles_.aspect_ratio[i], particles_.orientation[i]);
  const model::ConvexBody b =
      shapes_.body(particles_.radius[j], particles_.aspect_ratio[j], particles_.orientation[j]);
  return model::ovoid_pair_geometry(a, b, d, guess.isZero(0.0) ? d : guess, properties,
                                    settings_.hertz_radius, false)
      .contact.overlap;
}

void Simulation::restore_contacts(const h5::ContactRows& contacts, const std::string& path) {
  std::unordered_map<std::uint64_t, std::uint32_t> local;
  for (std::uint32_t k = 0; k < particles_.size(); ++k)
    local.emplace(particles_.id[k], k);
  // Each stored contact must be the one its particles' positions give (an edited or damaged
  // file otherwise restarts with forces the geometry does not have), and every overlapping pair
  // must have its row (a dropped row would come back without its tangential force). The file
  // was written from these very positions, so the overlaps agree to the narrow phase's round-off.
  const auto tolerance = [&](std::uint32_t i, std::uint32_t j, double overlap) {
    return 1e-6 * std::abs(overlap) + 1e-9 * (particles_.radius[i] + particles_.radius[j]);
  };
  std::vector<char> restored(neighbors_.pairs().size(), 0);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto found_i = local.find(contacts.particles[c][0]);
    const auto found_j = local.find(contacts.particles[c][1]);
    if (found_i == local.end() || found_j == local.end()) continue; // held by other ranks
    const std::uint32_t i = found_i->second, j = found_j->second;
    if (i >= particles_.n_owned && j >= particles_.n_owned) continue;
    const std::int64_t k = neighbors_.find(particles_, i, j);
    if (k < 0) {
      throw FileError(
          fmt::format("checkpoint '{}': contact ({}, {}) is not within reach of the restored positions", path,
                      contacts.particles[c][0], contacts.particles[c][1]));
    }
    const double geometric = geometric_overlap(i, j, contacts.normal[c]);
    if (!(std::abs(geometric - contacts.overlap[c]) <= tolerance(i, j, contacts.overlap[c]))) {
      throw FileError(fmt::format(
          "checkpoint '{}': contact ({}, {}) stores an overlap of {:.6g} m where the stored "
          "positions give {:.6g} m (the file was edited or damaged)",
          path, contacts.particles[c][0], contacts.particles[c][1], contacts.overlap[c], geometric));
    }
    restored[static_cast<std::size_t>(k)] = 1;
    auto& record = neighbors_.records()[static_cast<std::size_t>(k)];
    const Vec3& lengths = cell_.lengths();
    record.normal = contacts.normal[c];
    record.overlap = contacts.overlap[c];
    // The same arithmetic as the force pass, so that the restored stress has the same bits.
    const Vec3 d =
        PeriodicCell::minimum_image_of_wrapped(particles_.position[j] - particles_.position[i], lengths);
    const bool spheres = particles_.aspect_ratio[i] == 1.0 && particles_.aspect_ratio[j] == 1.0;
    record.branch = spheres ? d.norm() * (d * (1.0 / d.norm())) : d;
    record.point =
        PeriodicCell::minimum_image_of_wrapped(contacts.point[c] - particles_.position[i], lengths);
    record.force_on_i = contacts.force[c];
    const double effective_radius = restored_hertz_radius(i, j, record);
    record.normal_force = model::hertz_normal_force(model::contact_modulus(settings_.material),
                                                    effective_radius, record.overlap);
    record.tangential_stiffness =
        model::mindlin_tangential_stiffness(settings_.material, effective_radius, record.overlap);
    auto& history = neighbors_.history()[static_cast<std::size_t>(k)];
    history.tangential_force = contacts.tangential_force[c];
    history.sliding = contacts.sliding[c] != 0;
    if (!spheres) history.normal = contacts.normal[c];
  }
  for (std::size_t k = 0; k < restored.size(); ++k) {
    const auto [i, j] = neighbors_.pairs()[k];
    if (restored[k] || (i >= particles_.n_owned && j >= particles_.n_owned)) continue;
    const double geometric = geometric_overlap(i, j, Vec3::Zero());
    if (geometric > tolerance(i, j, geometric)) {
      throw FileError(
          fmt::format("checkpoint '{}': particles {} and {} overlap by {:.6g} m in the stored positions, "
                      "but /contacts has no row for them (a row was dropped, or the file was edited)",
                      path, particles_.id[i], particles_.id[j], geometric));
    }
  }
}

double Simulation::restored_hertz_radius(std::uint32_t i, std::uint32_t j,
                                         const data::ContactRecord& record) const {
  const double radius_i = particles_.radius[i], radius_j = particles_.radius[j];
  const double halfwidth = radius_i * radius_j / (radius_i + radius_j);
  const bool spheres = particles_.aspect_ratio[i] == 1.0 && particles_.aspect_ratio[j] == 1.0;
  if (spheres || settings_.hertz_radius == model::HertzRadius::halfwidth) return halfwidth;
  model::PairProperties properties;
  properties.effective_radius = halfwidth;
  const model::ConvexBody a = shapes_.body(radius_i, particles_.aspect_ratio[i], particles_.orientation[i]);
  const model::ConvexBody b = shapes_.body(radius_j, particles_.aspect_ratio[j], particles_.orientation[j]);
  return model::ovoid_pair_geometry(a, b, record.branch, record.normal, properties, settings_.hertz_radius,
                                    false)
      .hertz_radius;
}

double Simulation::servo_error() const {
  return dem::model::servo_error(control_, stress_);
}

void Simulation::set_control(const h5::CellState& control) {
  const Vec3 lengths = cell_.lengths(), reference = cell_.reference_lengths();
  control_ = control;
  control_.lengths = lengths;
  control_.reference_lengths = reference;
  update_control();
}

h5::CellState Simulation::cell_state() const {
  h5::CellState state = control_;
  state.lengths = cell_.lengths();
  state.reference_lengths = cell_.reference_lengths();
  return state;
}

} // namespace aniso::dem
