#include "dem/data/particles.hpp"

#include "common/error.hpp"
#include "dem/model/particle_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace aniso::dem::data {

void Particles::resize_arrays(std::size_t n) {
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

void Particles::truncate(std::size_t n) {
  resize_arrays(n);
  n_owned = std::min(n_owned, n);
}

void Particles::resize(std::size_t n) {
  resize_arrays(n);
  n_owned = n;
}

void Particles::append(const Particles& source, std::size_t k) {
  id.push_back(source.id[k]);
  radius.push_back(source.radius[k]);
  aspect_ratio.push_back(source.aspect_ratio[k]);
  mass.push_back(source.mass[k]);
  inertia.push_back(source.inertia[k]);
  position.push_back(source.position[k]);
  orientation.push_back(source.orientation[k]);
  velocity.push_back(source.velocity[k]);
  angular_velocity.push_back(source.angular_velocity[k]);
  force.push_back(source.force[k]);
  torque.push_back(source.torque[k]);
}

void Particles::move(std::size_t to, std::size_t from) {
  id[to] = id[from];
  radius[to] = radius[from];
  aspect_ratio[to] = aspect_ratio[from];
  mass[to] = mass[from];
  inertia[to] = inertia[from];
  position[to] = position[from];
  orientation[to] = orientation[from];
  velocity[to] = velocity[from];
  angular_velocity[to] = angular_velocity[from];
  force[to] = force[from];
  torque[to] = torque[from];
}

void Particles::add(std::uint64_t particle_id, double particle_radius, double particle_aspect_ratio,
                    double splice_angle, double density, const Vec3& particle_position,
                    const Quat& particle_orientation) {
  n_owned = id.size() + 1;
  id.push_back(particle_id);
  radius.push_back(particle_radius);
  aspect_ratio.push_back(particle_aspect_ratio);
  mass.push_back(density * model::particle_volume(particle_radius, particle_aspect_ratio, splice_angle));
  inertia.push_back(model::particle_inertia(particle_radius, particle_aspect_ratio, splice_angle, density));
  position.push_back(particle_position);
  orientation.push_back(particle_orientation);
  velocity.push_back(Vec3::Zero());
  angular_velocity.push_back(Vec3::Zero());
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
}

} // namespace aniso::dem::data
