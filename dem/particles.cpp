#include "dem/particles.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace aniso::dem {

void Particles::truncate(std::size_t n) {
  id.resize(n);
  radius.resize(n);
  aspect_ratio.resize(n);
  mass.resize(n);
  inertia.resize(n);
  position.resize(n);
  orientation.resize(n);
  velocity.resize(n);
  angular_velocity.resize(n);
  force.resize(n);
  torque.resize(n);
  n_owned = std::min(n_owned, n);
}

void Particles::resize(std::size_t n) {
  n_owned = n;
  id.resize(n);
  radius.resize(n);
  aspect_ratio.resize(n);
  mass.resize(n);
  inertia.resize(n);
  position.resize(n);
  orientation.resize(n, Quat::Identity());
  velocity.resize(n, Vec3::Zero());
  angular_velocity.resize(n, Vec3::Zero());
  force.resize(n, Vec3::Zero());
  torque.resize(n, Vec3::Zero());
}

double particle_volume(double radius, double aspect_ratio) {
  if (aspect_ratio != 1.0) throw InputError("ovoid particles (aspect ratio < 1) are not built yet (issue 4)");
  return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
}

void Particles::add(std::uint64_t particle_id, double particle_radius, double particle_aspect_ratio,
                    double density, const Vec3& particle_position) {
  const double volume = particle_volume(particle_radius, particle_aspect_ratio);
  const double particle_mass = density * volume;
  const double moment = 0.4 * particle_mass * particle_radius * particle_radius;
  n_owned = id.size() + 1;
  id.push_back(particle_id);
  radius.push_back(particle_radius);
  aspect_ratio.push_back(particle_aspect_ratio);
  mass.push_back(particle_mass);
  inertia.push_back(Vec3::Constant(moment));
  position.push_back(particle_position);
  orientation.push_back(Quat::Identity());
  velocity.push_back(Vec3::Zero());
  angular_velocity.push_back(Vec3::Zero());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
}

double Particles::solid_volume() const {
  double total = 0;
  for (std::size_t i = 0; i < n_owned; ++i)
    total += particle_volume(radius[i], aspect_ratio[i]);
  return total;
}

} // namespace aniso::dem
