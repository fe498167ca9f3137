#pragma once
// How far an assembly is from static equilibrium, measured exactly (ExactSum)
// so that every rank count gives the same bits:
//   - the unbalanced-force ratio, mean |net contact force| over particles with
//     contacts divided by the mean |contact force| (YADE's unbalancedForce,
//     the "mean force imbalance" of Kuhn's OVAL, shared/reference/ovoid.md);
//   - the kinetic energy of the fluctuating motion over the elastic energy
//     stored in the contacts;
//   - the mean normal contact stiffness, which sets the rate of the global
//     damping (dem/model/integrator.hpp, damp_velocities).

#include "common/mpi.hpp"
#include "dem/data/contact_sums.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"

#include <cstdint>

namespace aniso::dem {

struct Equilibrium {
  double unbalanced_force_ratio = 0; ///< NaN when no particle touches another
  /// Mean |net contact torque| / (mean |contact force| x mean radius), same particles; a sphere
  /// whose forces balance but whose torques do not spins up and lets its contacts slip.
  double unbalanced_torque_ratio = 0;
  double kinetic_energy = 0;        ///< fluctuating translation plus rotation [J]
  double elastic_energy = 0;        ///< Hertz normal plus Mindlin tangential springs [J]
  double mean_normal_stiffness = 0; ///< mean dF_n/d delta = 3 F_n / (2 delta) over contacts [N/m]
  std::int64_t n_contacts = 0;

  /// Kinetic over elastic energy; NaN without elastic energy.
  [[nodiscard]] double kinetic_elastic_ratio() const;
};

/// Collective. Uses the forces and contact records of the last force pass.
Equilibrium measure_equilibrium(const data::Particles& particles, const data::NeighborList& neighbors,
                                const mpi::Comm& comm);

/// Collective. The same measure from the contact part the last force pass summed (its
/// ContactSums::balance) and the particles' forces: the same bits as measure_equilibrium.
Equilibrium measure_equilibrium(const data::Particles& particles, const data::BalanceSums& contacts,
                                const mpi::Comm& comm);

} // namespace aniso::dem
