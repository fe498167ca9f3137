#pragma once
// FIRE, the fast inertial relaxation engine (Bitzek, Koskinen, Gaehler, Moseler & Gumbsch 2006,
// Phys. Rev. Lett. 97, 170201), on the fluctuating translational and rotational motion of the
// particles, with the parameters of its 2020 revision (Guenole et al., Comput. Mater. Sci. 175,
// 109584). The assembly runs downhill undamped, its velocities turned a little toward the forces
// at each step; as soon as the forces' power on the motion turns negative (it would climb), every
// particle stops, the turning restarts strong and the time step shrinks. A damped relaxation
// slows the soft modes of a marginal packing as much as the fast ones; FIRE lets them run.
//
// The forces stay those of the force pass (Hertz-Mindlin with its tangential history and the
// Coulomb limit), and the cell keeps its control (held axes, servoed p), so a frictional packing
// relaxes as the DEM would, only faster. Mass-weighted coordinates u = sqrt(M) v, f = F / sqrt(M)
// put translations and rotations on one footing: P = F.v + T.omega, |u|^2 = 2 E_kin,
// |f|^2 = F.F/m + T.I^-1 T, summed exactly at every step (model::motion_sums): checked only at
// the control updates, every few steps, the fastest modes (a sphere's spin on its tangential
// springs) turned around between checks and every check found the power negative.

#include "dem/simulation.hpp"

#include <cstdint>

namespace aniso::dem::protocol {

/// FIRE's state between two steps: an interrupted minimisation continues from it.
struct FireState {
  double min_step = 0; ///< [s]
  double max_step = 0; ///< [s]
  double alpha = 0;
  int n_downhill = 0;
  std::int64_t stops = 0;
};

class Fire {
public:
  /// FIRE over `simulation`, whose time step now is the smallest it takes; the largest is
  /// `max_step_factor` times that, and below the Rayleigh step.
  Fire(Simulation& simulation, double max_step_factor);
  /// FIRE continued from `state` (the time step it had is the simulation's own now).
  Fire(Simulation& simulation, const FireState& state);

  /// After every time step: steers the velocities toward the forces while the power is positive,
  /// else stops every particle (collective: one exact reduction of three sums).
  void update();
  /// Gives the simulation its own time step back (collective).
  void end() { set_time_step(min_step_); }
  /// Times the particles were stopped.
  [[nodiscard]] std::int64_t n_stops() const { return stops_; }
  [[nodiscard]] FireState state() const { return {min_step_, max_step_, alpha_, n_downhill_, stops_}; }

private:
  void set_time_step(double time_step);

  Simulation& simulation_;
  double min_step_;
  double max_step_;
  double alpha_;
  int n_downhill_ = 0;
  std::int64_t stops_ = 0;
};

} // namespace aniso::dem::protocol
