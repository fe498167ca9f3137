#pragma once
// A fixed-cell hold: every axis of the cell at zero strain rate, the state's own
// material and damping, for a number of steps. A static state keeps its stress;
// the drift of p measures how far from equilibrium a checkpoint was written.

#include "common/log.hpp"
#include "dem/simulation.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::dem::protocol {

struct HoldSample {
  std::int64_t step = 0;
  double mean_stress = 0;            ///< p [Pa]
  double deviatoric_stress = 0;      ///< q [Pa]
  double unbalanced_force_ratio = 0; ///< dem/equilibrium.hpp
  double kinetic_elastic_ratio = 0;
};

struct HoldReport {
  std::vector<HoldSample> samples; ///< at the start and at every control update
  double largest_drift = 0;        ///< max |p - p_start| / p_start over the samples
  /// (p_end - p_start) / p_start
  [[nodiscard]] double final_drift() const;
};

/// Holds the cell fixed for `steps` time steps (collective). Samples every control interval.
HoldReport hold_fixed_cell(Simulation& simulation, std::int64_t steps, const Logger& logger);

/// Writes the samples as CSV (rank 0 only), atomically.
void write_hold_csv(const HoldReport& report, const std::string& path);

} // namespace aniso::dem::protocol
