#pragma once
// The settings of the bit-comparison tests: a fixed number of steps under an oblique force, with
// the velocity field kept, so that two runs compare in every component.
#include "lbm/flow.hpp"

namespace aniso::lbm {

inline FlowSettings fixed_flow_settings(Precision precision) {
  FlowSettings settings;
  settings.force = Vec3(2e-5, 1e-5, -5e-6);
  settings.precision = precision;
  settings.fixed_steps = true;
  settings.max_steps = 120;
  settings.check_interval = 40;
  settings.keep_velocity = true;
  return settings;
}

} // namespace aniso::lbm
