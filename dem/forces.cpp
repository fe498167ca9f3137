#include "dem/forces.hpp"

#include <algorithm>
#include <cmath>

namespace aniso::dem {

ForcePass compute_contact_forces(Particles& particles, const PeriodicCell& cell, const Vec3& strain_rate,
                                 const ContactMaterial& material, double time_step, NeighborList& neighbors) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    particles.force[k].setZero();
    particles.torque[k].setZero();
  }
  const Vec3& lengths = cell.lengths();
  const auto& pairs = neighbors.pairs();
  auto& history = neighbors.history();
  auto& records = neighbors.records();
  const auto& properties = neighbors.properties();
  const ContactConstants constants = contact_constants(material);
  ForcePass pass;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::uint32_t i = pairs[k].i, j = pairs[k].j;
    const Vec3 d =
        PeriodicCell::minimum_image_of_wrapped(particles.position[j] - particles.position[i], lengths);
    const double radius_sum = particles.radius[i] + particles.radius[j];
    const double distance_squared = d.squaredNorm();
    ContactRecord& record = records[k];
    if (distance_squared >= radius_sum * radius_sum) {
      if (record.overlap > 0 || history[k].sliding || !history[k].tangential_force.isZero(0.0)) {
        history[k] = ContactHistory{}; // the contact has just opened
        record = ContactRecord{};
      }
      continue;
    }
    ++pass.n_touching;
    const double distance = std::sqrt(distance_squared);
    const Vec3 normal = d * (1.0 / distance);
    const double overlap = radius_sum - distance;
    const double smaller_radius = std::min(particles.radius[i], particles.radius[j]);
    if (!(overlap <= pass.worst_overlap * smaller_radius)) { // also catches NaN
      pass.worst_overlap = overlap / smaller_radius;
      pass.worst_pair = static_cast<std::int64_t>(k);
    }
    // Lever arms from each centre to the contact point, which sits mid-way through the overlap.
    const double arm_i = particles.radius[i] - 0.5 * overlap;
    const double arm_j = particles.radius[j] - 0.5 * overlap;
    ContactKinematics kinematics;
    kinematics.normal = normal;
    kinematics.overlap = overlap;
    kinematics.relative_velocity =
        particles.velocity[j] - particles.velocity[i] + strain_rate.cwiseProduct(d) -
        (arm_j * particles.angular_velocity[j] + arm_i * particles.angular_velocity[i]).cross(normal);
    kinematics.time_step = time_step;
    const ContactForce result = hertz_mindlin_force(constants, properties[k], kinematics, history[k]);
    const Vec3 moment_direction = normal.cross(result.force_on_i);
    particles.force[i] += result.force_on_i;
    particles.force[j] -= result.force_on_i;
    particles.torque[i] += arm_i * moment_direction;
    particles.torque[j] += arm_j * moment_direction;
    record.normal = normal;
    record.distance = distance;
    record.overlap = overlap;
    record.force_on_i = result.force_on_i;
    record.normal_force = result.normal_force;
    record.tangential_stiffness = result.tangential_stiffness;
  }
  return pass;
}

} // namespace aniso::dem
