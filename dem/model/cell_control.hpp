#pragma once
// Per-axis control of the periodic cell: a prescribed strain rate, or a stress
// servo. The servo is stiffness-scaled: each update asks for the strain that
// would remove a fraction `gain` of the stress error if the assembly answered
// elastically with its current contact stiffness, spread over the update
// interval and capped at `max_rate`; an integral term learns the steady rate
// so that steady loading needs no standing error. Stiffness scaling keeps one gain usable
// from a loose packing to 100 kPa. Biaxial plane strain at constant mean
// stress: axis 1 strain rate, axis 2 rate 0, axis 3 servoed to hold p.

#include "common/h5/checkpoint.hpp"
#include "common/mpi.hpp"
#include "common/tensor.hpp"
#include "dem/data/neighbors.hpp"

namespace aniso::dem::model {

struct ServoSettings {
  double gain = 0.2;              ///< fraction of the stress error removed per update (0, 1]
  double max_rate = 0;            ///< cap on |strain rate| of servoed axes [1/s]
  double integral_intervals = 20; ///< integral time of the servo, in updates
};

/// New strain rates for every axis from the controller state, the measured stress
/// (tension positive) and the axial stiffness; `interval` is the time until the next update.
Vec3 update_strain_rates(h5::CellState& state, const Mat3& stress, const Vec3& stiffness, double interval,
                         const ServoSettings& settings);

/// Relative error of the controlled quantity: (p - p_target)/p_target in mean-stress mode,
/// else the largest |sigma_aa - target_a| / |target_a| over stress-controlled axes; 0 if none.
double servo_error(const h5::CellState& state, const Mat3& stress);

} // namespace aniso::dem::model
