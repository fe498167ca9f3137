#include "dem/data/contact_sums.hpp"

#include <span>
#include <vector>

namespace aniso::dem::data {

ContactSums sum_contacts(const Particles& particles, const NeighborList& neighbors) {
  ContactSums sums;
  const auto& records = neighbors.records();
  const auto& pairs = neighbors.pairs();
  for (std::size_t c = 0; c < records.size(); ++c)
    if (records[c].overlap > 0 && pairs[c].i < particles.n_owned) sums.add(records[c]);
  return sums;
}

ControlMeasures reduce_control_measures(const ContactSums& local, const Particles& particles,
                                        const PeriodicCell& cell, const mpi::Comm& comm) {
  // Twelve accumulators in one reduction: the stress with its kinetic part, then the stiffness.
  std::vector<ExactSum> sums(local.stress.begin(), local.stress.end());
  sums.insert(sums.end(), local.stiffness.begin(), local.stiffness.end());
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    const Vec3& v = particles.velocity[k];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        sums[static_cast<std::size_t>(3 * a + b)].add(-particles.mass[k] * v[a] * v[b]);
  }
  const std::vector<ExactSum> total = comm.sum_exact(std::span<const ExactSum>(sums));
  ControlMeasures measures;
  const double volume = cell.volume();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b)
      measures.stress(a, b) = total[static_cast<std::size_t>(3 * a + b)].value() / volume;
    measures.stiffness[a] = total[static_cast<std::size_t>(9 + a)].value() / volume;
  }
  return measures;
}

} // namespace aniso::dem::data
