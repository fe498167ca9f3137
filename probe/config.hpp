#pragma once
// Typed configuration of aniso-probe, read from the [probe] table. Every key has a
// unit, a default chosen from the stability sweep (docs/methods/probe.md,
// docs/charts/probe_stability.png) and an allowed range.

#include "common/config.hpp"
#include "probe/tolerances.hpp"

#include <cstdint>
#include <string>

namespace aniso::probe {

struct ProbeConfig {
  std::string output_dir = "."; ///< folder for probe_<stem>.h5/.csv and fork files
  double increment = 5e-5;      ///< |d eps_ii| of each fork (paper: 0.005% = 5e-5)
  /// Rate of the increment as an inertial number I = rate D50 sqrt(rho / p) at the checkpoint's p.
  double inertial_number = 1e-3;
  std::int64_t hold_steps = 500;   ///< steps held after each half increment before the stress is read
  std::int64_t window_steps = 250; ///< the stress is averaged over the last window_steps of each hold
  IncrementTolerances tolerances;  ///< of the increment checks
  bool check_increment = true;     ///< refuse increments found too large or too small
};

/// Reads every [probe] key through `reader` (which records and range-checks them).
ProbeConfig read_probe_config(config::Reader& reader);

} // namespace aniso::probe
