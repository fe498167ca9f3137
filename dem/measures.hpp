#pragma once
// State measures reported in the history file and used by the cell servo:
// average stress from contacts (plus the kinetic part), p, q, void ratio,
// coordination numbers with and without rattlers, energies.

#include "common/cell.hpp"
#include "common/mpi.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"

namespace aniso::dem {

/// Average Cauchy stress, tension positive [Pa]: sigma = (1/V) sum_c d (x) f_i - (1/V) sum_p m v (x) v,
/// with d the branch vector from i to j and f_i the force on i (so compression is negative).
/// Summed exactly (ExactSum), so the result does not depend on the order of contacts.
/// Each contact counts on the rank that owns its lower-id particle (collective).
Mat3 average_stress(const data::Particles& particles, const PeriodicCell& cell,
                    const data::NeighborList& neighbors, const mpi::Comm& comm);

struct StateMeasures {
  Mat3 stress = Mat3::Zero();   ///< tension positive [Pa]
  double mean_stress = 0;       ///< p, compression positive [Pa]
  double deviatoric_stress = 0; ///< q = sqrt(3 J2) [Pa]
  double void_ratio = 0;        ///< (V - V_s) / V_s
  std::int64_t n_contacts = 0;
  double coordination = 0; ///< 2 N_c / N
  double coordination_no_rattlers =
      0; ///< the same without rattlers (fewer than 2 contacts, removed iteratively)
  std::int64_t n_rattlers = 0;
  double kinetic_energy = 0;         ///< fluctuating translational plus rotational [J]
  double elastic_energy = 0;         ///< Hertz normal plus tangential spring energy [J]
  double unbalanced_force_ratio = 0; ///< mean |net force| / mean |contact force| (dem/equilibrium.hpp)
  /// Mean e (x) e of the ovoids' axes e; I/3 when there are no ovoids (a sphere has no axis).
  Mat3 axis_orientation = Mat3::Identity() / 3.0;
};

/// Collective; `n_particles` and `solid_volume` are global.
StateMeasures measure_state(const data::Particles& particles, const PeriodicCell& cell,
                            const data::NeighborList& neighbors, double solid_volume,
                            std::int64_t n_particles, const mpi::Comm& comm);

/// Inertial number I = strain rate * D50 * sqrt(density / p) (paper: quasi-static when small).
double inertial_number(double strain_rate, double d50, double density, double mean_stress);
/// The strain rate of an inertial number at a mean stress: rate = I / (D50 sqrt(rho / p)).
double strain_rate_for_inertial_number(double inertial_number, double d50, double density,
                                       double mean_stress);

} // namespace aniso::dem
