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

namespace aniso::dem::data {

struct ContactSums {
  std::array<ExactSum, 9> stress;    ///< sum over contacts of d_a f_b (d: branch i -> j, f: force on i)
  std::array<ExactSum, 3> stiffness; ///< sum of k_n n_a^2 d_a^2, k_n = dF/d delta = 3 F / (2 delta) (Hertz)

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
