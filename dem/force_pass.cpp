#include "dem/force_pass.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

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

// The sphere fast path's geometry: the normal is the line of centres and the contact point sits
// mid-way through the overlap, so both lever arms lie along the normal.
struct SphereContact {
  Vec3 normal;
  double distance = 0;
  double overlap = 0;
  double arm_i = 0, arm_j = 0; // lengths of the lever arms from each centre
};

SphereContact sphere_contact(const Vec3& d, double distance_squared, double radius_i, double radius_j) {
  SphereContact contact;
  contact.distance = std::sqrt(distance_squared);
  contact.normal = d * (1.0 / contact.distance);
  contact.overlap = (radius_i + radius_j) - contact.distance;
  contact.arm_i = radius_i - 0.5 * contact.overlap;
  contact.arm_j = radius_j - 0.5 * contact.overlap;
  return contact;
}

// The record a touching pair leaves for the stress, the servo, the equilibrium and the checkpoint.
void write_record(data::ContactRecord& record, const Vec3& normal, const Vec3& branch, const Vec3& arm_i,
                  double overlap, const Vec3& force_on_i, double normal_force, double tangential_stiffness) {
  record.normal = normal;
  record.branch = branch;
  record.point = arm_i;
  record.overlap = overlap;
  record.force_on_i = force_on_i;
  record.normal_force = normal_force;
  record.tangential_stiffness = tangential_stiffness;
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
      const SphereContact contact =
          sphere_contact(d, distance_squared, particles.radius[i], particles.radius[j]);
      const Vec3& normal = contact.normal;
      length_i = contact.arm_i;
      length_j = contact.arm_j;
      kinematics.normal = normal;
      kinematics.overlap = contact.overlap;
      kinematics.relative_velocity =
          particles.velocity[j] - particles.velocity[i] + strain_rate.cwiseProduct(d) -
          (length_j * particles.angular_velocity[j] + length_i * particles.angular_velocity[i]).cross(normal);
      arm_i = length_i * normal;
      arm_j = -length_j * normal;
      branch = contact.distance * normal;
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
    write_record(record, kinematics.normal, branch, arm_i, overlap, result.force_on_i, result.normal_force,
                 result.tangential_stiffness);
    if (sums != nullptr) sums->add(record, history[k], i, j, static_cast<std::uint32_t>(particles.n_owned));
  }
  return pass;
}

double pair_overlap(const data::Particles& particles, const PeriodicCell& cell, const ContactInput& input,
                    std::uint32_t i, std::uint32_t j, const Vec3& guess) {
  const Vec3 d =
      PeriodicCell::minimum_image_of_wrapped(particles.position[j] - particles.position[i], cell.lengths());
  const double radius_sum = particles.radius[i] + particles.radius[j];
  if (d.squaredNorm() >= radius_sum * radius_sum) return radius_sum - d.norm();
  if (particles.aspect_ratio[i] == 1.0 && particles.aspect_ratio[j] == 1.0) return radius_sum - d.norm();
  model::PairProperties properties;
  properties.effective_radius = particles.radius[i] * particles.radius[j] / radius_sum;
  const model::ConvexBody a =
      input.shapes->body(particles.radius[i], particles.aspect_ratio[i], particles.orientation[i]);
  const model::ConvexBody b =
      input.shapes->body(particles.radius[j], particles.aspect_ratio[j], particles.orientation[j]);
  return model::ovoid_pair_geometry(a, b, d, guess.isZero(0.0) ? d : guess, properties, input.hertz_radius,
                                    false)
      .contact.overlap;
}

void restore_contact_records(std::span<const StoredContact> contacts, const data::Particles& particles,
                             const PeriodicCell& cell, const model::ContactMaterial& material,
                             const ContactInput& input, data::NeighborList& neighbors,
                             const std::string& source) {
  std::unordered_map<std::uint64_t, std::uint32_t> local;
  for (std::uint32_t k = 0; k < particles.size(); ++k)
    local.emplace(particles.id[k], k);
  // The file was written from these very positions, so the overlaps agree to the narrow phase's round-off.
  const auto tolerance = [&](std::uint32_t i, std::uint32_t j, double overlap) {
    return 1e-6 * std::abs(overlap) + 1e-9 * (particles.radius[i] + particles.radius[j]);
  };
  const model::ContactConstants constants = model::contact_constants(material);
  const Vec3& lengths = cell.lengths();
  std::vector<char> restored(neighbors.pairs().size(), 0);
  for (const StoredContact& stored : contacts) {
    const auto found_i = local.find(stored.ids[0]);
    const auto found_j = local.find(stored.ids[1]);
    if (found_i == local.end() || found_j == local.end()) continue; // held by other ranks
    const std::uint32_t i = found_i->second, j = found_j->second;
    if (i >= particles.n_owned && j >= particles.n_owned) continue;
    const std::int64_t k = neighbors.find(particles, i, j);
    if (k < 0) {
      throw FileError(fmt::format("{}: contact ({}, {}) is not within reach of the restored positions",
                                  source, stored.ids[0], stored.ids[1]));
    }
    const double geometric = pair_overlap(particles, cell, input, i, j, stored.normal);
    if (!(std::abs(geometric - stored.overlap) <= tolerance(i, j, stored.overlap))) {
      throw FileError(fmt::format("{}: contact ({}, {}) stores an overlap of {:.6g} m where the stored "
                                  "positions give {:.6g} m (the file was edited or damaged)",
                                  source, stored.ids[0], stored.ids[1], stored.overlap, geometric));
    }
    const auto slot = static_cast<std::size_t>(k);
    restored[slot] = 1;
    const Vec3 d =
        PeriodicCell::minimum_image_of_wrapped(particles.position[j] - particles.position[i], lengths);
    model::ContactHistory& history = neighbors.history()[slot];
    history.tangential_force = stored.tangential_force;
    history.sliding = stored.sliding;
    const bool spheres = particles.aspect_ratio[i] == 1.0 && particles.aspect_ratio[j] == 1.0;
    if (spheres) {
      const SphereContact contact =
          sphere_contact(d, d.squaredNorm(), particles.radius[i], particles.radius[j]);
      const model::HertzMindlinSprings springs = model::hertz_mindlin_springs(
          constants, neighbors.properties()[slot].effective_radius, contact.overlap);
      write_record(neighbors.records()[slot], contact.normal, contact.distance * contact.normal,
                   contact.arm_i * contact.normal, contact.overlap, stored.force, springs.normal_force,
                   springs.tangential_stiffness);
      continue;
    }
    // An ovoid pair's normal is where its Newton iteration converged from the previous step's
    // normal: another start gives other last bits, so the stored normal, overlap and point stand.
    history.normal = stored.normal;
    double hertz_radius = neighbors.properties()[slot].effective_radius;
    if (input.hertz_radius != model::HertzRadius::halfwidth) {
      const model::ConvexBody a =
          input.shapes->body(particles.radius[i], particles.aspect_ratio[i], particles.orientation[i]);
      const model::ConvexBody b =
          input.shapes->body(particles.radius[j], particles.aspect_ratio[j], particles.orientation[j]);
      hertz_radius = model::ovoid_pair_geometry(a, b, d, stored.normal, neighbors.properties()[slot],
                                                input.hertz_radius, false)
                         .hertz_radius;
    }
    const model::HertzMindlinSprings springs =
        model::hertz_mindlin_springs(constants, hertz_radius, stored.overlap);
    write_record(neighbors.records()[slot], stored.normal, d,
                 PeriodicCell::minimum_image_of_wrapped(stored.point - particles.position[i], lengths),
                 stored.overlap, stored.force, springs.normal_force, springs.tangential_stiffness);
  }
  for (std::size_t k = 0; k < restored.size(); ++k) {
    const auto [i, j] = neighbors.pairs()[k];
    if (restored[k] || (i >= particles.n_owned && j >= particles.n_owned)) continue;
    const double geometric = pair_overlap(particles, cell, input, i, j, Vec3::Zero());
    if (geometric > tolerance(i, j, geometric)) {
      throw FileError(
          fmt::format("{}: particles {} and {} overlap by {:.6g} m in the stored positions, "
                      "but /contacts has no row for them (a row was dropped, or the file was edited)",
                      source, particles.id[i], particles.id[j], geometric));
    }
  }
}

} // namespace aniso::dem
