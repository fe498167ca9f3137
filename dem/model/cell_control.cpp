#include "dem/model/cell_control.hpp"

#include "common/exact_sum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

namespace aniso::dem::model {

CellControl strain_controlled(const CellControl& from, const Vec3& rates) {
  CellControl control = from;
  control.mode = {AxisMode::strain_rate, AxisMode::strain_rate, AxisMode::strain_rate};
  control.target = rates;
  control.hold_mean_stress = false;
  control.servo_state = Vec3::Zero();
  return control;
}

CellControl fixed_cell(const CellControl& from) {
  return strain_controlled(from, Vec3::Zero());
}

CellControl strain_axes_held(const CellControl& from) {
  CellControl control = from;
  for (std::size_t a = 0; a < 3; ++a)
    if (control.mode[a] == AxisMode::strain_rate) control.target[static_cast<int>(a)] = 0.0;
  control.servo_state = Vec3::Zero();
  return control;
}

CellControl isotropic_stress(const CellControl& from, double pressure) {
  CellControl control = from;
  control.mode = {AxisMode::stress, AxisMode::stress, AxisMode::stress};
  control.target = Vec3::Constant(-pressure);
  control.hold_mean_stress = false;
  control.servo_state = Vec3::Zero();
  return control;
}

CellControl biaxial_plane_strain(const CellControl& from, double rate, double mean_stress) {
  CellControl control = from;
  control.mode = {AxisMode::strain_rate, AxisMode::strain_rate, AxisMode::stress};
  control.target = Vec3(-rate, 0.0, -mean_stress);
  control.hold_mean_stress = true;
  control.mean_stress_target = mean_stress;
  return control;
}

Vec3 update_strain_rates(CellControl& state, const Mat3& stress, const Vec3& stiffness, double interval,
                         const ServoSettings& settings) {
  Vec3 rates = Vec3::Zero();
  const double mean_stress = -stress.trace() / 3.0;
  double servoed_stiffness = 0;
  for (int a = 0; a < 3; ++a) {
    if (state.mode[a] == AxisMode::stress) servoed_stiffness += stiffness[a];
  }
  for (int a = 0; a < 3; ++a) {
    if (state.mode[a] == AxisMode::strain_rate) {
      rates[a] = state.target[a];
      continue;
    }
    double strain_increment = 0;
    if (state.hold_mean_stress) {
      // Straining the servoed axes together by e changes p by -e * sum(M)/3.
      const double stiffness_sum = std::max(servoed_stiffness, 1e-12);
      strain_increment = settings.gain * 3.0 * (mean_stress - state.mean_stress_target) / stiffness_sum;
    } else {
      // Stretching by e adds M e of tension; too much compression (stress below target) expands.
      strain_increment = settings.gain * (state.target[a] - stress(a, a)) / std::max(stiffness[a], 1e-12);
    }
    // Proportional part plus an integral part (servo_state) that learns the steady
    // rate the axis needs, so a constant rate does not require a standing error.
    const double proportional = strain_increment / interval;
    state.servo_state[a] += proportional / settings.integral_intervals;
    if (settings.max_rate > 0) {
      state.servo_state[a] = std::clamp(state.servo_state[a], -settings.max_rate, settings.max_rate);
    }
    double rate = proportional + state.servo_state[a];
    if (settings.max_rate > 0) rate = std::clamp(rate, -settings.max_rate, settings.max_rate);
    rates[a] = rate;
  }
  state.strain_rate = rates;
  return rates;
}

double servo_error(const CellControl& state, const Mat3& stress) {
  if (state.hold_mean_stress)
    return (-stress.trace() / 3.0 - state.mean_stress_target) / state.mean_stress_target;
  double worst = 0;
  for (int a = 0; a < 3; ++a) {
    if (state.mode[a] == AxisMode::stress && state.target[a] != 0) {
      worst = std::max(worst, std::abs(stress(a, a) - state.target[a]) / std::abs(state.target[a]));
    }
  }
  return worst;
}

} // namespace aniso::dem::model
