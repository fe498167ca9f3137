#include "dem/simulation.hpp"

#include "common/error.hpp"
#include "dem/forces.hpp"
#include "dem/integrator.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aniso::dem {

Simulation::Simulation(Particles particles, const h5::CellState& control, const SimulationSettings& settings,
                       double time, std::int64_t step, bool forces_valid)
    : particles_(std::move(particles)), cell_(control.lengths, control.reference_lengths), control_(control),
      settings_(settings), neighbors_(settings.skin), time_(time), step_(step) {
  require_stable_time_step(settings_.time_step,
                           critical_time_step(particles_, settings_.density, settings_.material));
  solid_volume_ = particles_.solid_volume();
  neighbors_.build(particles_, cell_);
  // A restored run keeps its stored forces; the caller restores per-pair records and history.
  if (!forces_valid) {
    compute_forces();
    stress_ = average_stress(particles_, cell_, neighbors_);
  }
}

void Simulation::compute_forces() {
  compute_contact_forces(particles_, cell_, control_.strain_rate, settings_.material, settings_.time_step,
                         neighbors_);
  // Explosion guard: an overlap this large means the step or the loading rate is far too large.
  const auto& records = neighbors_.records();
  const auto& pairs = neighbors_.pairs();
  for (std::size_t k = 0; k < records.size(); ++k) {
    const double smaller = std::min(particles_.radius[pairs[k].i], particles_.radius[pairs[k].j]);
    if (records[k].overlap > settings_.explosion_overlap * smaller || std::isnan(records[k].overlap)) {
      throw NumericalError(fmt::format("step {}: overlap of particles {} and {} is {:.3g} of the smaller "
                                       "radius (limit {}): the run exploded; "
                                       "lower the time step fraction or the loading rate",
                                       step_, particles_.id[pairs[k].i], particles_.id[pairs[k].j],
                                       records[k].overlap / smaller, settings_.explosion_overlap));
    }
  }
}

void Simulation::update_control() {
  stress_ = average_stress(particles_, cell_, neighbors_);
  if (!std::isfinite(stress_.sum())) {
    throw NumericalError(fmt::format("step {}: the stress is not finite: the run exploded", step_));
  }
  const double interval = static_cast<double>(settings_.control_interval) * settings_.time_step;
  update_strain_rates(control_, stress_, axial_stiffness(neighbors_, cell_.volume()), interval,
                      settings_.servo);
}

void Simulation::step() {
  const double dt = settings_.time_step;
  kick(particles_, 0.5 * dt);
  drift(particles_, cell_, control_.strain_rate, dt);
  if (neighbors_.needs_rebuild(particles_, cell_)) neighbors_.build(particles_, cell_);
  compute_forces();
  kick(particles_, 0.5 * dt);
  time_ += dt;
  ++step_;
  if (step_ % settings_.control_interval == 0) update_control();
}

StateMeasures Simulation::measure() const {
  return measure_state(particles_, cell_, neighbors_, solid_volume_);
}

void Simulation::restore_stress() {
  stress_ = average_stress(particles_, cell_, neighbors_);
}

double Simulation::servo_error() const {
  return dem::servo_error(control_, stress_);
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
