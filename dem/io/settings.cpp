#include "dem/io/settings.hpp"

#include "common/error.hpp"
#include "dem/model/integrator.hpp"
#include "dem/model/particle_shape.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aniso::dem::io {

SimulationSettings settings_from_config(const DemConfig& config, double smallest_diameter) {
  SimulationSettings s;
  s.material.shear_modulus = config.material.shear_modulus;
  s.material.poisson_ratio = config.material.poisson_ratio;
  s.material.friction = config.material.friction;
  s.material.damping_ratio = config.integration.damping;
  s.density = config.particles.density;
  s.splice_angle = config.particles.splice_angle;
  s.hertz_radius = config.material.hertz_radius;
  const double critical = model::rayleigh_time_step(
      model::volume_equivalent_radius(0.5 * smallest_diameter, config.particles.aspect_ratio, s.splice_angle),
      s.density, s.material);
  s.time_step = config.integration.time_step > 0 ? config.integration.time_step
                                                 : config.integration.time_step_fraction * critical;
  model::require_stable_time_step(s.time_step, critical);
  s.skin = config.integration.skin * config.particles.d50;
  s.control_interval = config.integration.control_interval;
  s.servo.gain = config.integration.servo_gain;
  s.explosion_overlap = config.integration.explosion_overlap;
  s.global_damping = config.integration.global_damping;
  return s;
}

double strain_rate_for_inertial_number(double inertial_number, double d50, double density,
                                       double mean_stress) {
  return inertial_number / (d50 * std::sqrt(density / mean_stress));
}

void require_reachable_strain(double strain, double rate, double time_step, const std::string& what) {
  const double steps = strain / (rate * time_step);
  require_input(
      steps <= max_run_steps,
      fmt::format("{}: a strain of {:.3g} at {:.3g} /s with a time step of {:.3g} s takes {:.3g} steps "
                  "(more than {:.0e}): the rate (set by the inertial number and the mean stress) or the "
                  "time step (set by the shear modulus, the density and the smallest particle) is too small",
                  what, strain, rate, time_step, steps, max_run_steps));
}

} // namespace aniso::dem::io
