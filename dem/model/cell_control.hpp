#pragma once
// Per-axis control of the periodic cell: a prescribed strain rate, or a stress
// servo. The servo is stiffness-scaled: each update asks for the strain that
// would remove a fraction `gain` of the stress error if the assembly answered
// elastically with its current contact stiffness, spread over the update
// interval and capped at `max_rate`; an integral term learns the steady rate
// so that steady loading needs no standing error. Stiffness scaling keeps one gain usable
// from a loose packing to 100 kPa. Biaxial plane strain at constant mean
// stress: axis 1 strain rate, axis 2 rate 0, axis 3 servoed to hold p.
//
// The protocols build their control states here, by name (fixed_cell, strain_controlled,
// strain_axes_held, isotropic_stress, biaxial_plane_strain); nothing else assembles one by hand.

#include "common/tensor.hpp"

#include <array>
#include <cstdint>

namespace aniso::dem::model {

/// How one axis of the periodic cell is driven.
enum class AxisMode : std::uint8_t { strain_rate = 0, stress = 1 };

/// The controller of the periodic cell: its modes and targets, and its state (the rates it
/// asks for now and the servo's memory). A checkpoint stores all of it.
struct CellControl {
  Vec3 strain_rate = Vec3::Zero(); ///< current rate dL/dt / L per axis [1/s]
  std::array<AxisMode, 3> mode{AxisMode::strain_rate, AxisMode::strain_rate, AxisMode::strain_rate};
  Vec3 target = Vec3::Zero(); ///< per axis: strain rate [1/s] (strain_rate mode) or stress [Pa] (stress mode)
  bool hold_mean_stress = false;   ///< stress-mode axes together hold p = mean_stress_target
  double mean_stress_target = 0;   ///< [Pa], compression positive
  Vec3 servo_state = Vec3::Zero(); ///< controller memory (integral terms) per axis
};

/// Every axis at a prescribed strain rate (`rates`, tension positive [1/s]), no servo and no
/// servo memory; the mean-stress target of `from` is kept for the record.
CellControl strain_controlled(const CellControl& from, const Vec3& rates);

/// Every axis still: strain_controlled(from, 0). A static state keeps its stress in it.
CellControl fixed_cell(const CellControl& from);

/// The loading of `from` stopped: its strain-rate axes held still, its servoed axes still
/// servoed to their targets, the servo's memory cleared (the loading's steady rate would drive
/// the held cell).
CellControl strain_axes_held(const CellControl& from);

/// Every axis servoed to the isotropic stress -pressure (compression positive `pressure` [Pa]),
/// servo memory cleared.
CellControl isotropic_stress(const CellControl& from, double pressure);

/// Biaxial plane strain at constant mean stress (paper section 2): axis 1 shortened at `rate`
/// [1/s], axis 2 held, axis 3 servoed so that p stays at `mean_stress` [Pa]. The servo's memory
/// of `from` is kept.
CellControl biaxial_plane_strain(const CellControl& from, double rate, double mean_stress);

struct ServoSettings {
  double gain = 0.2;              ///< fraction of the stress error removed per update (0, 1]
  double max_rate = 0;            ///< cap on |strain rate| of servoed axes [1/s]
  double integral_intervals = 20; ///< integral time of the servo, in updates
};

/// New strain rates for every axis from the controller state, the measured stress
/// (tension positive) and the axial stiffness; `interval` is the time until the next update.
Vec3 update_strain_rates(CellControl& control, const Mat3& stress, const Vec3& stiffness, double interval,
                         const ServoSettings& settings);

/// Relative error of the controlled quantity: (p - p_target)/p_target in mean-stress mode,
/// else the largest |sigma_aa - target_a| / |target_a| over stress-controlled axes; 0 if none.
double servo_error(const CellControl& control, const Mat3& stress);

} // namespace aniso::dem::model
