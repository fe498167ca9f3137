#pragma once
// What a control update sums over the contacts: the contact part of the average stress and the
// servo's axial stiffness, exactly (ExactSum: the order of the terms and the split over ranks
// cannot change the bits). The sums are filled on control steps inside the force pass, where each
// contact's record is already in cache (a second traversal of every candidate pair's record cost
// about a fifth of a loading step), or by one traversal where no force pass precedes; the terms
// are the same, so both give the same bits.

#include "common/cell.hpp"
#include "common/exact_sum.hpp"
#include "common/mpi.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace aniso::dem::data {

/// The contact part of the equilibrium measure (dem/equilibrium.hpp): what a particle's contacts
/// and their springs hold. Summed inside the force pass on control steps that measure the
/// equilibrium (a second traversal of every pair's record and history cost 5-9% of a step),
/// or by measure_equilibrium's own traversal: the same terms, so the same bits.
struct BalanceSums {
  ExactSum contact_force; ///< |f| of every contact
  ExactSum contacts;      ///< 1 per contact
  ExactSum stiffness;     ///< k_n = 3 F / (2 delta) (Hertz)
  ExactSum elastic;       ///< Hertz 0.4 F delta plus Mindlin F_t^2 / (2 k_t)
  /// Per owned particle, 1 if a contact touches it: the particles whose net force counts.
  std::vector<char> touching;

  explicit BalanceSums(std::size_t n_owned = 0) : touching(n_owned, 0) {}
  /// Empties the sums for `n_owned` particles, keeping the flags' storage.
  void reset(std::size_t n_owned) {
    contact_force = contacts = stiffness = elastic = ExactSum{};
    touching.assign(n_owned, 0);
  }

  /// Adds the touching contact of pair (i, j), counted by the owner of its lower-id particle i;
  /// marks each owned particle as touched.
  void add(const ContactRecord& record, const model::ContactHistory& history, std::uint32_t i,
           std::uint32_t j) {
    const std::size_t n_owned = touching.size();
    if (i < n_owned) touching[i] = 1;
    if (j < n_owned) touching[j] = 1;
    if (i >= n_owned) return;
    contact_force.add(record.force_on_i.norm());
    contacts.add(1.0);
    stiffness.add(1.5 * record.normal_force / record.overlap);
    elastic.add(0.4 * record.normal_force * record.overlap); // integral of the Hertz force
    // Incremental Mindlin: the history holds the elastic tangential force F_t; its energy is F_t^2 / (2 k_t).
    elastic.add(0.5 * history.tangential_force.squaredNorm() / record.tangential_stiffness);
  }
};

struct ContactSums {
  std::array<ExactSum, 9> stress;     ///< sum over contacts of d_a f_b (d: branch i -> j, f: force on i)
  std::array<ExactSum, 3> stiffness;  ///< sum of k_n n_a^2 d_a^2, k_n = dF/d delta = 3 F / (2 delta) (Hertz)
  std::optional<BalanceSums> balance; ///< with the equilibrium measure's contact part when set

  /// Empties the sums, with a balance part for `n_owned` particles or none (its storage is kept
  /// between control steps, so that a step allocates nothing).
  void reset(bool with_balance, std::size_t n_owned) {
    stress = {};
    stiffness = {};
    if (!with_balance) {
      balance.reset();
      return;
    }
    if (!balance) balance.emplace();
    balance->reset(n_owned);
  }

  /// Adds the touching contact of pair (i, j) with its history after this step's force.
  void add(const ContactRecord& record, const model::ContactHistory& history, std::uint32_t i,
           std::uint32_t j, std::uint32_t n_owned) {
    if (balance) balance->add(record, history, i, j);
    if (i < n_owned) add(record);
  }

  /// Adds one touching contact. Call it on the rank that counts the contact: the owner of its
  /// lower-id particle (pair.i).
  void add(const ContactRecord& record) {
    const Vec3& d = record.branch;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        stress[static_cast<std::size_t>(3 * a + b)].add(d[a] * record.force_on_i[b]);
    const double normal_stiffness = 1.5 * record.normal_force / record.overlap;
    for (int a = 0; a < 3; ++a)
      stiffness[static_cast<std::size_t>(a)].add(normal_stiffness * record.normal[a] * record.normal[a] *
                                                 d[a] * d[a]);
  }
};

/// The sums of this rank's contacts by one traversal of the records.
ContactSums sum_contacts(const Particles& particles, const NeighborList& neighbors);

/// The average stress and the axial stiffness of a control update (collective: one exact reduction).
struct ControlMeasures {
  Mat3 stress = Mat3::Zero(); ///< tension positive [Pa], kinetic part included (average_stress)
  /// Constrained modulus of the contact network per axis, M_a = (1/V) sum_c k_n n_a^2 d_a^2 [Pa]:
  /// the servo's stiffness (cell_control.hpp).
  Vec3 stiffness = Vec3::Zero();
};
ControlMeasures reduce_control_measures(const ContactSums& local, const Particles& particles,
                                        const PeriodicCell& cell, const mpi::Comm& comm);

} // namespace aniso::dem::data
