#include "dem/force_pass.hpp"

#include <algorithm>
#include <cmath>

namespace aniso::dem {

namespace {

// Forgets the history of a pair that has just come apart.
void open_contact(model::ContactHistory& history, data::ContactRecord& record) {
  if (record.overlap > 0 || history.sliding || !history.tangential_force.isZero(0.0) ||
      !history.normal.isZero(0.0)) {
    history = model::ContactHistory{};
    record = data::ContactRecord{};
  }
}

} // namespace

ForcePass compute_contact_forces(data::Particles& particles, const PeriodicCell& cell,
                                 const Vec3& strain_rate, const model::ContactMaterial& material,
                                 double time_step, const ContactInput& input, data::NeighborList& neighbors,
                                 std::vector<model::ConvexBody>& bodies, data::ContactSums* sums) {
  for (std::size_t k = 0; k < particles.size(); ++k) {
    particles.force[k].setZero();
    particles.torque[k].setZero();
  }
  input.shapes->world_bodies(particles, bodies);
  const Vec3& lengths = cell.lengths();
  const auto& pairs = neighbors.pairs();
  auto& history = neighbors.history();
  auto& records = neighbors.records();
  const auto& properties = neighbors.properties();
  auto& separating = neighbors.separating_normals();
  const model::ContactConstants constants = model::contact_constants(material);
  // Pairs proven apart stay apart while the particles' motion has not used up the gap they
  // had: those are skipped without reading the particles. The margin of a proof is far above
  // the round-off of the gap and of the bounds.
  auto& proofs = neighbors.proofs();
  const data::GapBounds bounds = neighbors.take_gap_bounds();
  const bool proofs_hold = bounds.known();
  const auto prove_apart = [&](std::size_t k, double gap, double radius_sum) {
    if (proofs_hold) proofs[k] = bounds.prove(gap, 1e-12 * radius_sum);
  };
  ForcePass pass;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (proofs_hold && bounds.hold(proofs[k])) { // its history was cleared when proven
      ++pass.n_skipped;
      continue;
    }
    // A pair with a proof, even one used up, was apart at its last evaluation and has nothing
    // to forget. An older proof must not outlive a contact: the pair may part again while it
    // holds, and then its history would not be cleared. A pair found apart proves itself anew.
    const bool forgotten = proofs[k].exists();
    proofs[k] = data::ApartProof{};
    const std::uint32_t i = pairs[k].i, j = pairs[k].j;
    const Vec3 d =
        PeriodicCell::minimum_image_of_wrapped(particles.position[j] - particles.position[i], lengths);
    const double radius_sum = particles.radius[i] + particles.radius[j];
    const double distance_squared = d.squaredNorm();
    data::ContactRecord& record = records[k];
    // Bounding spheres first: the radius is the half-width, the largest half-extent.
    if (distance_squared >= radius_sum * radius_sum) {
      if (!forgotten) open_contact(history[k], record);
      prove_apart(k, std::sqrt(distance_squared) - radius_sum, radius_sum);
      continue;
    }
    model::PairProperties pair = properties[k];
    model::ContactKinematics kinematics;
    kinematics.time_step = time_step;
    Vec3 arm_i, arm_j;                 // lever arms from each centre to the contact point
    double length_i = 0, length_j = 0; // their lengths, spheres only
    Vec3 branch;
    const bool spheres = particles.aspect_ratio[i] == 1.0 && particles.aspect_ratio[j] == 1.0;
    if (spheres) {
      // Fast path: the normal is the line of centres and the contact point sits mid-way
      // through the overlap, so both arms lie along the normal.
      const double distance = std::sqrt(distance_squared);
      const Vec3 normal = d * (1.0 / distance);
      const double overlap = radius_sum - distance;
      length_i = particles.radius[i] - 0.5 * overlap;
      length_j = particles.radius[j] - 0.5 * overlap;
      kinematics.normal = normal;
      kinematics.overlap = overlap;
      kinematics.relative_velocity =
          particles.velocity[j] - particles.velocity[i] + strain_rate.cwiseProduct(d) -
          (length_j * particles.angular_velocity[j] + length_i * particles.angular_velocity[i]).cross(normal);
      arm_i = length_i * normal;
      arm_j = -length_j * normal;
      branch = distance * normal;
    } else {
      const Vec3 guess = history[k].normal.isZero(0.0) ? d : history[k].normal;
      const model::OvoidPairGeometry geometry = model::ovoid_pair_geometry(
          bodies[i], bodies[j], d, guess, pair, input.hertz_radius, true, &separating[k]);
      pass.newton_iterations += geometry.contact.iterations;
      pass.n_unconverged += geometry.contact.converged ? 0 : 1;
      if (!(geometry.contact.overlap > 0)) {
        if (!forgotten) open_contact(history[k], record);
        // phi(n) < 0 along the returned normal: -phi bounds the distance between the bodies.
        if (geometry.contact.overlap < 0) prove_apart(k, -geometry.contact.overlap, radius_sum);
        continue;
      }
      kinematics.normal = geometry.contact.normal;
      kinematics.overlap = geometry.contact.overlap;
      arm_i = geometry.contact.point;
      arm_j = geometry.contact.point - d;
      kinematics.relative_velocity =
          particles.velocity[j] - particles.velocity[i] + strain_rate.cwiseProduct(d) +
          particles.angular_velocity[j].cross(arm_j) - particles.angular_velocity[i].cross(arm_i);
      pair.effective_radius = geometry.hertz_radius;
      branch = d;
      history[k].normal = geometry.contact.normal;
    }
    ++pass.n_touching;
    const double overlap = kinematics.overlap;
    const double smaller = std::min(model::half_height(particles.radius[i], particles.aspect_ratio[i]),
                                    model::half_height(particles.radius[j], particles.aspect_ratio[j]));
    if (!(overlap <= pass.worst_overlap * smaller)) { // also catches NaN
      pass.worst_overlap = overlap / smaller;
      pass.worst_pair = static_cast<std::int64_t>(k);
    }
    const model::ContactForce result = model::hertz_mindlin_force(constants, pair, kinematics, history[k]);
    particles.force[i] += result.force_on_i;
    particles.force[j] -= result.force_on_i;
    if (spheres) {
      const Vec3 moment_direction = kinematics.normal.cross(result.force_on_i);
      particles.torque[i] += length_i * moment_direction;
      particles.torque[j] += length_j * moment_direction;
    } else {
      particles.torque[i] += arm_i.cross(result.force_on_i);
      particles.torque[j] -= arm_j.cross(result.force_on_i);
    }
    record.normal = kinematics.normal;
    record.branch = branch;
    record.point = arm_i;
    record.overlap = overlap;
    record.force_on_i = result.force_on_i;
    record.normal_force = result.normal_force;
    record.tangential_stiffness = result.tangential_stiffness;
    if (sums != nullptr && i < particles.n_owned) sums->add(record);
  }
  return pass;
}

} // namespace aniso::dem
