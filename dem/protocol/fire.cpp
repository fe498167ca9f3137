#include "dem/protocol/fire.hpp"

#include "dem/model/integrator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

namespace aniso::dem::protocol {
namespace {

// Guenole et al. 2020, Table 1: N_delay, f_inc, f_dec, alpha_start, f_alpha.
constexpr int delay = 20;
constexpr double grow = 1.1;
constexpr double shrink = 0.5;
constexpr double alpha_start = 0.25;
constexpr double alpha_shrink = 0.99;

} // namespace

Fire::Fire(Simulation& simulation, double max_step_factor)
    : simulation_(simulation), min_step_(simulation.settings().time_step),
      max_step_(std::min(max_step_factor * min_step_, simulation.critical_time_step())), alpha_(alpha_start) {
}

Fire::Fire(Simulation& simulation, const FireState& state)
    : simulation_(simulation), min_step_(state.min_step), max_step_(state.max_step), alpha_(state.alpha),
      n_downhill_(state.n_downhill), stops_(state.stops) {}

void Fire::set_time_step(double time_step) {
  if (time_step == simulation_.settings().time_step) return;
  SimulationSettings settings = simulation_.settings();
  settings.time_step = time_step;
  simulation_.reconfigure(settings);
}

void Fire::update() {
  const model::MotionSums local = model::motion_sums(simulation_.particles());
  const std::array<ExactSum, 3> terms{local.power, local.speed_squared, local.force_squared};
  const std::vector<ExactSum> sums = simulation_.comm().sum_exact(std::span<const ExactSum>(terms));
  if (sums[0].value() > 0) {
    const double speed = std::sqrt(sums[1].value());
    const double force = std::sqrt(sums[2].value());
    if (force > 0) model::steer_velocities(simulation_.particles(), 1.0 - alpha_, alpha_ * speed / force);
    if (++n_downhill_ > delay) {
      set_time_step(std::min(simulation_.settings().time_step * grow, max_step_));
      alpha_ *= alpha_shrink;
    }
    return;
  }
  model::damp_velocities(simulation_.particles(), 0.0, 0.0);
  ++stops_;
  n_downhill_ = 0;
  alpha_ = alpha_start;
  set_time_step(std::max(simulation_.settings().time_step * shrink, min_step_));
}

} // namespace aniso::dem::protocol
