#include "dem/protocol/fire.hpp"

#include "dem/model/integrator.hpp"

#include <algorithm>
#include <cmath>

namespace aniso::dem::protocol {
namespace {

// Guenole et al. 2020, Table 1: N_delay, f_inc, f_dec, alpha_start, f_alpha.
constexpr int delay = 5;
constexpr double grow = 1.1;
constexpr double shrink = 0.5;
constexpr double alpha_start = 0.25;
constexpr double alpha_shrink = 0.99;

} // namespace

Fire::Fire(Simulation& simulation, double max_step_factor)
    : simulation_(simulation), min_step_(simulation.settings().time_step),
      max_step_(std::min(max_step_factor * min_step_, simulation.critical_time_step())), alpha_(alpha_start) {
}

void Fire::set_time_step(double time_step) {
  if (time_step == simulation_.settings().time_step) return;
  SimulationSettings settings = simulation_.settings();
  settings.time_step = time_step;
  simulation_.reconfigure(settings);
}

void Fire::update() {
  const Equilibrium& e = simulation_.equilibrium();
  if (e.power > 0) {
    const double speed = std::sqrt(2.0 * e.kinetic_energy);
    const double force = std::sqrt(e.force_norm_squared);
    if (force > 0) model::steer_velocities(simulation_.particles(), 1.0 - alpha_, alpha_ * speed / force);
    if (++n_downhill_ > delay) {
      set_time_step(std::min(simulation_.settings().time_step * grow, max_step_));
      alpha_ *= alpha_shrink;
    }
    return;
  }
  model::damp_velocities(simulation_.particles(), 0.0);
  ++stops_;
  n_downhill_ = 0;
  alpha_ = alpha_start;
  set_time_step(std::max(simulation_.settings().time_step * shrink, min_step_));
}

} // namespace aniso::dem::protocol
