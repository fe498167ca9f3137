#include "dem/integrator.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace aniso::dem {

void kick(Particles& particles, double dt) {
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    particles.velocity[k] += (dt / particles.mass[k]) * particles.force[k];
    particles.angular_velocity[k] += particles.torque[k].cwiseQuotient(particles.inertia[k]) * dt;
  }
}

void drift(Particles& particles, PeriodicCell& cell, const Vec3& strain_rate, double dt) {
  const Vec3 old_lengths = cell.lengths();
  const Vec3 new_lengths = old_lengths.cwiseProduct(Vec3::Ones() + dt * strain_rate);
  const Vec3 scale = new_lengths.cwiseQuotient(old_lengths);
  cell.set_lengths(new_lengths);
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    const Vec3 moved = (particles.position[k] + dt * particles.velocity[k]).cwiseProduct(scale);
    particles.position[k] = cell.wrap_nearby(moved);
  }
}

double critical_time_step(const Particles& particles, double density, const ContactMaterial& material) {
  const double smallest = *std::min_element(particles.radius.begin(), particles.radius.end());
  return rayleigh_time_step(smallest, density, material);
}

void require_stable_time_step(double time_step, double critical) {
  if (!(time_step > 0) || time_step > critical) {
    throw NumericalError(
        fmt::format("time step {:.4g} s is above the Rayleigh critical step {:.4g} s of the smallest "
                    "particle: lower dem.integration.time_step_fraction (now {:.3g} of critical)",
                    time_step, critical, time_step / critical));
  }
}

} // namespace aniso::dem
