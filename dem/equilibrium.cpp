#include "dem/equilibrium.hpp"

#include "common/error.hpp"
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
  // A particle's contacts are all in the list of the rank that owns it, so "has a contact" is
  // decided by its owner alone.
  data::BalanceSums contacts(particles.n_owned);
  const auto& pairs = neighbors.pairs();
  const auto& records = neighbors.records();
  const auto& history = neighbors.history();
  for (std::size_t c = 0; c < pairs.size(); ++c)
    if (records[c].overlap > 0) contacts.add(records[c], history[c], pairs[c].i, pairs[c].j);
  return measure_equilibrium(particles, contacts, comm);
}

Equilibrium measure_equilibrium(const data::Particles& particles, const data::BalanceSums& contacts,
                                const mpi::Comm& comm) {
  check_invariant(contacts.touching.size() == particles.n_owned,
                  "the equilibrium's contact sums cover this rank's owned particles");
  enum : std::size_t {
    net_force,
    net_torque,
    loaded_radius,
    loaded_particles,
    contact_force,
    n_contacts,
    stiffness,
    kinetic,
    elastic,
    count
  };
  std::array<ExactSum, count> sums;
  sums[contact_force] = contacts.contact_force;
  sums[n_contacts] = contacts.contacts;
  sums[stiffness] = contacts.stiffness;
  sums[elastic] = contacts.elastic;
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    sums[kinetic].add(0.5 * particles.mass[k] * particles.velocity[k].squaredNorm());
    sums[kinetic].add(model::rotational_energy(particles.inertia[k], particles.orientation[k],
                                               particles.angular_velocity[k]));
    if (contacts.touching[k] == 0) continue;
    sums[net_force].add(particles.force[k].norm());
    sums[net_torque].add(particles.torque[k].norm());
    sums[loaded_radius].add(particles.radius[k]);
    sums[loaded_particles].add(1.0);
  }
  const std::vector<ExactSum> total = comm.sum_exact(std::span<const ExactSum>(sums));
  const auto value = [&](std::size_t k) { return total[k].value(); };
  Equilibrium e;
  e.n_contacts = static_cast<std::int64_t>(value(n_contacts));
  e.kinetic_energy = value(kinetic);
  e.elastic_energy = value(elastic);
  if (e.n_contacts == 0) {
    e.unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
    e.unbalanced_torque_ratio = e.unbalanced_force_ratio;
    return e;
  }
  const double mean_contact_force = value(contact_force) / value(n_contacts);
  e.unbalanced_force_ratio = (value(net_force) / value(loaded_particles)) / mean_contact_force;
  e.unbalanced_torque_ratio = (value(net_torque) / value(loaded_particles)) /
                              (mean_contact_force * value(loaded_radius) / value(loaded_particles));
  e.mean_normal_stiffness = value(stiffness) / value(n_contacts);
  return e;
}

} // namespace aniso::dem
