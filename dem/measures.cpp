#include "dem/measures.hpp"

#include "common/exact_sum.hpp"

#include <array>
#include <cmath>

namespace aniso::dem {

Mat3 average_stress(const Particles& particles, const PeriodicCell& cell, const NeighborList& neighbors) {
  std::array<ExactSum, 9> sums;
  const auto& records = neighbors.records();
  for (const ContactRecord& record : records) {
    if (record.overlap <= 0) continue;
    const Vec3 branch = record.distance * record.normal;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        sums[static_cast<std::size_t>(3 * a + b)].add(branch[a] * record.force_on_i[b]);
  }
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const Vec3& v = particles.velocity[k];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        sums[static_cast<std::size_t>(3 * a + b)].add(-particles.mass[k] * v[a] * v[b]);
  }
  Mat3 stress;
  const double volume = cell.volume();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      stress(a, b) = sums[static_cast<std::size_t>(3 * a + b)].value() / volume;
  return stress;
}

StateMeasures measure_state(const Particles& particles, const PeriodicCell& cell,
                            const NeighborList& neighbors, double solid_volume) {
  StateMeasures m;
  m.stress = average_stress(particles, cell, neighbors);
  m.mean_stress = mean_stress_compression_positive(m.stress);
  m.deviatoric_stress = deviatoric_q(m.stress);
  m.void_ratio = (cell.volume() - solid_volume) / solid_volume;

  const std::size_t n = particles.size();
  std::vector<int> degree(n, 0);
  const auto& pairs = neighbors.pairs();
  const auto& records = neighbors.records();
  const auto& history = neighbors.history();
  ExactSum elastic;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (records[k].overlap <= 0) continue;
    ++m.n_contacts;
    ++degree[pairs[k].i];
    ++degree[pairs[k].j];
    elastic.add(0.4 * records[k].normal_force * records[k].overlap); // integral of the Hertz force
    // Incremental Mindlin: the spring holds the elastic tangential force F_t; its energy is F_t^2 / (2 k_t).
    elastic.add(0.5 * history[k].tangential_force.squaredNorm() / records[k].tangential_stiffness);
  }
  m.elastic_energy = elastic.value();
  m.coordination = n ? 2.0 * static_cast<double>(m.n_contacts) / static_cast<double>(n) : 0.0;
  // Rattlers: with friction a particle needs at least two contacts to carry load
  // (docs/methods/dem.md); removing one lowers its partners' counts, so peel them
  // off with a work list until none is left.
  std::vector<std::vector<std::uint32_t>> partners(n);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (records[k].overlap <= 0) continue;
    partners[pairs[k].i].push_back(pairs[k].j);
    partners[pairs[k].j].push_back(pairs[k].i);
  }
  constexpr int min_contacts = 2;
  std::vector<bool> rattler(n, false);
  std::vector<std::uint32_t> work;
  for (std::uint32_t k = 0; k < n; ++k) {
    if (degree[k] < min_contacts) {
      rattler[k] = true;
      work.push_back(k);
    }
  }
  while (!work.empty()) {
    const std::uint32_t k = work.back();
    work.pop_back();
    for (std::uint32_t other : partners[k]) {
      if (!rattler[other] && --degree[other] < min_contacts) {
        rattler[other] = true;
        work.push_back(other);
      }
    }
  }
  std::int64_t n_kept = 0, n_kept_contacts = 0;
  for (std::size_t k = 0; k < n; ++k)
    n_kept += rattler[k] ? 0 : 1;
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    if (records[c].overlap > 0 && !rattler[pairs[c].i] && !rattler[pairs[c].j]) ++n_kept_contacts;
  }
  m.n_rattlers = static_cast<std::int64_t>(n) - n_kept;
  m.coordination_no_rattlers =
      n_kept ? 2.0 * static_cast<double>(n_kept_contacts) / static_cast<double>(n_kept) : 0.0;

  ExactSum kinetic;
  for (std::size_t k = 0; k < n; ++k) {
    kinetic.add(0.5 * particles.mass[k] * particles.velocity[k].squaredNorm());
    kinetic.add(0.5 * particles.angular_velocity[k].dot(
                          particles.inertia[k].cwiseProduct(particles.angular_velocity[k])));
  }
  m.kinetic_energy = kinetic.value();
  return m;
}

double inertial_number(double strain_rate, double d50, double density, double mean_stress) {
  return std::abs(strain_rate) * d50 * std::sqrt(density / mean_stress);
}

} // namespace aniso::dem
