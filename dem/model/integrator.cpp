#include "dem/model/integrator.hpp"

#include "common/error.hpp"
#include "dem/model/particle_shape.hpp"
#include "dem/model/rotation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace aniso::dem::model {

Vec3 inverse_inertia_world_times(const data::Particles& particles, std::size_t k, const Vec3& v) {
  if (particles.aspect_ratio[k] == 1.0) return v.cwiseQuotient(particles.inertia[k]);
  return inverse_inertia_times(particles.inertia[k], particle_axis(particles.orientation[k]), v);
}

void kick(data::Particles& particles, double dt) {
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    particles.velocity[k] += (dt / particles.mass[k]) * particles.force[k];
    if (particles.aspect_ratio[k] == 1.0) {
      particles.angular_velocity[k] += inverse_inertia_world_times(particles, k, particles.torque[k]) * dt;
    } else {
      particles.angular_velocity[k] += dt * inverse_inertia_world_times(particles, k, particles.torque[k]);
    }
  }
}

MotionSums motion_sums(const data::Particles& particles) {
  MotionSums sums;
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    const Vec3& force = particles.force[k];
    const Vec3& torque = particles.torque[k];
    const Vec3& velocity = particles.velocity[k];
    const Vec3& spin = particles.angular_velocity[k];
    sums.power.add(force.dot(velocity) + torque.dot(spin));
    sums.speed_squared.add(particles.mass[k] * velocity.squaredNorm() +
                           2.0 * rotational_energy(particles.inertia[k], particles.orientation[k], spin));
    sums.force_squared.add(force.squaredNorm() / particles.mass[k] +
                           torque.dot(inverse_inertia_world_times(particles, k, torque)));
  }
  return sums;
}

void steer_velocities(data::Particles& particles, double keep, double toward) {
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    particles.velocity[k] = keep * particles.velocity[k] + (toward / particles.mass[k]) * particles.force[k];
    particles.angular_velocity[k] = keep * particles.angular_velocity[k] +
                                    toward * inverse_inertia_world_times(particles, k, particles.torque[k]);
  }
}

void damp_velocities(data::Particles& particles, double factor, double spin_factor) {
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    particles.velocity[k] *= factor;
    particles.angular_velocity[k] *= spin_factor;
  }
}

void drift(data::Particles& particles, PeriodicCell& cell, const Vec3& strain_rate, double dt) {
  const Vec3 old_lengths = cell.lengths();
  const Vec3 new_lengths = old_lengths.cwiseProduct(Vec3::Ones() + dt * strain_rate);
  const Vec3 scale = new_lengths.cwiseQuotient(old_lengths);
  cell.set_lengths(new_lengths);
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    const Vec3 moved = (particles.position[k] + dt * particles.velocity[k]).cwiseProduct(scale);
    particles.position[k] = cell.wrap_nearby(moved);
    if (particles.aspect_ratio[k] != 1.0) {
      free_rotation(particles.orientation[k], particles.angular_velocity[k], particles.inertia[k], dt);
    }
  }
}

double critical_time_step(const data::Particles& particles, double density, const ContactMaterial& material) {
  double smallest = std::numeric_limits<double>::infinity();
  // The volume-equivalent radius (dem/model/particle_shape.hpp), from the mass for ovoids.
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const double radius = particles.aspect_ratio[k] == 1.0
                              ? particles.radius[k]
                              : std::cbrt(3.0 * particles.mass[k] / (4.0 * std::numbers::pi * density));
    smallest = std::min(smallest, radius);
  }
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

} // namespace aniso::dem::model
