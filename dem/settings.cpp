#include "dem/settings.hpp"

#include "dem/integrator.hpp"
#include "dem/particle_shape.hpp"

#include <cmath>

namespace aniso::dem {

SimulationSettings settings_from_config(const DemConfig& config, double smallest_diameter) {
  SimulationSettings s;
  s.material.shear_modulus = config.material.shear_modulus;
  s.material.poisson_ratio = config.material.poisson_ratio;
  s.material.friction = config.material.friction;
  s.material.damping_ratio = config.integration.damping;
  s.density = config.particles.density;
  s.splice_angle = config.particles.splice_angle;
  s.hertz_radius = config.material.hertz_radius;
  const double critical = rayleigh_time_step(
      volume_equivalent_radius(0.5 * smallest_diameter, config.particles.aspect_ratio, s.splice_angle),
      s.density, s.material);
  s.time_step = config.integration.time_step > 0 ? config.integration.time_step
                                                 : config.integration.time_step_fraction * critical;
  require_stable_time_step(s.time_step, critical);
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

} // namespace aniso::dem
