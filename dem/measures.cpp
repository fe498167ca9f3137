#include "dem/measures.hpp"

#include "common/exact_sum.hpp"
#include "common/exchange.hpp"
#include "dem/data/contact_sums.hpp"
#include "dem/equilibrium.hpp"
#include "dem/model/rotation.hpp"

#include <array>
#include <cmath>
#include <span>

namespace aniso::dem {
namespace {

// A contact is counted by the rank that owns its lower-id particle (pair.i).
bool counted_here(const data::Particles& particles, const data::Pair& pair,
                  const data::ContactRecord& record) {
  return record.overlap > 0 && pair.i < particles.n_owned;
}

} // namespace

Mat3 average_stress(const data::Particles& particles, const PeriodicCell& cell,
                    const data::NeighborList& neighbors, const mpi::Comm& comm) {
  return data::reduce_control_measures(data::sum_contacts(particles, neighbors), particles, cell, comm)
      .stress;
}

StateMeasures measure_state(const data::Particles& particles, const PeriodicCell& cell,
                            const data::NeighborList& neighbors, double solid_volume,
                            std::int64_t n_particles, const mpi::Comm& comm) {
  StateMeasures m;
  m.stress = average_stress(particles, cell, neighbors, comm);
  m.mean_stress = mean_stress_compression_positive(m.stress);
  m.deviatoric_stress = deviatoric_q(m.stress);
  m.void_ratio = (cell.volume() - solid_volume) / solid_volume;

  // The contact list by ids, counted once each.
  const auto& pairs = neighbors.pairs();
  const auto& records = neighbors.records();
  std::vector<char> contact_ids;
  ByteWriter writer(contact_ids);
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    if (!counted_here(particles, pairs[c], records[c])) continue;
    writer.put(particles.id[pairs[c].i]);
    writer.put(particles.id[pairs[c].j]);
  }
  const Equilibrium equilibrium = measure_equilibrium(particles, neighbors, comm);
  m.kinetic_energy = equilibrium.kinetic_energy;
  m.elastic_energy = equilibrium.elastic_energy;
  m.unbalanced_force_ratio = equilibrium.unbalanced_force_ratio;
  // Axis orientation tensor of the ovoids: 6 components and the count, summed exactly.
  std::array<ExactSum, 7> axes;
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    if (particles.aspect_ratio[k] == 1.0) continue;
    const Vec3 e = model::particle_axis(particles.orientation[k]);
    const std::array<double, 6> components{e.x() * e.x(), e.y() * e.y(), e.z() * e.z(),
                                           e.y() * e.z(), e.x() * e.z(), e.x() * e.y()};
    for (std::size_t c = 0; c < components.size(); ++c)
      axes[c].add(components[c]);
    axes[6].add(1.0);
  }
  const std::vector<ExactSum> axis_sums = comm.sum_exact(std::span<const ExactSum>(axes));
  if (const double n_ovoids = axis_sums[6].value(); n_ovoids > 0) {
    Eigen::Matrix<double, 6, 1> voigt;
    for (int c = 0; c < 6; ++c)
      voigt[c] = axis_sums[static_cast<std::size_t>(c)].value() / n_ovoids;
    m.axis_orientation = from_voigt(voigt);
  }

  // Rattlers need the whole contact graph: every rank assembles it from everyone's contacts.
  const auto n = static_cast<std::size_t>(n_particles);
  std::vector<std::vector<std::uint32_t>> partners(n);
  std::vector<int> degree(n, 0);
  for (const auto& buffer : all_gather_bytes(comm, contact_ids)) {
    ByteReader reader(buffer);
    while (!reader.done()) {
      const auto a = static_cast<std::uint32_t>(reader.get<std::uint64_t>());
      const auto b = static_cast<std::uint32_t>(reader.get<std::uint64_t>());
      partners[a].push_back(b);
      partners[b].push_back(a);
      ++degree[a];
      ++degree[b];
      ++m.n_contacts;
    }
  }
  m.coordination = n ? 2.0 * static_cast<double>(m.n_contacts) / static_cast<double>(n) : 0.0;
  // Rattlers: with friction a particle needs at least two contacts to carry load
  // (docs/methods/dem.md); removing one lowers its partners' counts, so peel them
  // off with a work list until none is left.
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
  for (std::size_t k = 0; k < n; ++k) {
    if (rattler[k]) continue;
    for (std::uint32_t other : partners[k])
      n_kept_contacts += (!rattler[other] && other > k) ? 1 : 0;
  }
  m.n_rattlers = static_cast<std::int64_t>(n) - n_kept;
  m.coordination_no_rattlers =
      n_kept ? 2.0 * static_cast<double>(n_kept_contacts) / static_cast<double>(n_kept) : 0.0;
  return m;
}

double inertial_number(double strain_rate, double d50, double density, double mean_stress) {
  return std::abs(strain_rate) * d50 * std::sqrt(density / mean_stress);
}

double strain_rate_for_inertial_number(double inertial_number, double d50, double density,
                                       double mean_stress) {
  return inertial_number / (d50 * std::sqrt(density / mean_stress));
}

} // namespace aniso::dem
