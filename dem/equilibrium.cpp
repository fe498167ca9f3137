#include "dem/equilibrium.hpp"

#include "common/exact_sum.hpp"
#include "dem/model/rotation.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <span>

namespace aniso::dem {

double Equilibrium::kinetic_elastic_ratio() const {
  return elastic_energy > 0 ? kinetic_energy / elastic_energy : std::numeric_limits<double>::quiet_NaN();
}

Equilibrium measure_equilibrium(const data::Particles& particles, const data::NeighborList& neighbors,
                                const mpi::Comm& comm) {
  enum : std::size_t {
    net_force,
    net_torque,
    loaded_radius,
    loaded_particles,
    contact_force,
    contacts,
    stiffness,
    kinetic,
    elastic,
    count
  };
  std::array<ExactSum, count> sums;
  const auto& pairs = neighbors.pairs();
  const auto& records = neighbors.records();
  const auto& history = neighbors.history();
  // A particle's contacts are all in the list of the rank that owns it, so "has a contact" is
  // decided by its owner alone.
  std::vector<char> touching(particles.n_owned, 0);
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    const data::ContactRecord& record = records[c];
    if (!(record.overlap > 0)) continue;
    const data::Pair& pair = pairs[c];
    if (pair.i < particles.n_owned) touching[pair.i] = 1;
    if (pair.j < particles.n_owned) touching[pair.j] = 1;
    if (pair.i >= particles.n_owned) continue; // the rest counted once, by the owner of pair.i
    sums[contact_force].add(record.force_on_i.norm());
    sums[contacts].add(1.0);
    sums[stiffness].add(1.5 * record.normal_force / record.overlap); // Hertz: dF/d delta = 3F/(2 delta)
    sums[elastic].add(0.4 * record.normal_force * record.overlap);   // integral of the Hertz force
    // Incremental Mindlin: the history holds the elastic tangential force F_t; its energy is F_t^2 / (2 k_t).
    sums[elastic].add(0.5 * history[c].tangential_force.squaredNorm() / record.tangential_stiffness);
  }
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    sums[kinetic].add(0.5 * particles.mass[k] * particles.velocity[k].squaredNorm());
    sums[kinetic].add(model::rotational_energy(particles.inertia[k], particles.orientation[k],
                                               particles.angular_velocity[k]));
    if (touching[k] == 0) continue;
    sums[net_force].add(particles.force[k].norm());
    sums[net_torque].add(particles.torque[k].norm());
    sums[loaded_radius].add(particles.radius[k]);
    sums[loaded_particles].add(1.0);
  }
  const std::vector<ExactSum> total = comm.sum_exact(std::span<const ExactSum>(sums));
  const auto value = [&](std::size_t k) { return total[k].value(); };
  Equilibrium e;
  e.n_contacts = static_cast<std::int64_t>(value(contacts));
  e.kinetic_energy = value(kinetic);
  e.elastic_energy = value(elastic);
  if (e.n_contacts == 0) {
    e.unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
    e.unbalanced_torque_ratio = e.unbalanced_force_ratio;
    return e;
  }
  const double mean_contact_force = value(contact_force) / value(contacts);
  e.unbalanced_force_ratio = (value(net_force) / value(loaded_particles)) / mean_contact_force;
  e.unbalanced_torque_ratio = (value(net_torque) / value(loaded_particles)) /
                              (mean_contact_force * value(loaded_radius) / value(loaded_particles));
  e.mean_normal_stiffness = value(stiffness) / value(contacts);
  return e;
}

} // namespace aniso::dem
