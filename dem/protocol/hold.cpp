#include "dem/protocol/hold.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "dem/protocol/phase.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace aniso::dem::protocol {
namespace {

HoldSample sample(const Simulation& simulation) {
  HoldSample s;
  s.step = simulation.step_count();
  s.mean_stress = mean_stress_compression_positive(simulation.stress());
  s.deviatoric_stress = deviatoric_q(simulation.stress());
  s.unbalanced_force_ratio = simulation.equilibrium().unbalanced_force_ratio;
  s.kinetic_elastic_ratio = simulation.equilibrium().kinetic_elastic_ratio();
  return s;
}

} // namespace

double HoldReport::final_drift() const {
  return samples.back().mean_stress / samples.front().mean_stress - 1.0;
}

HoldReport hold_fixed_cell(Simulation& simulation, std::int64_t steps, const Logger& logger) {
  Phase phase(simulation, "hold", steps);
  simulation.watch_equilibrium(true);
  simulation.set_control(model::fixed_cell(simulation.control()));
  HoldReport report;
  report.samples.push_back(sample(simulation));
  const double p0 = report.samples.front().mean_stress;
  require_input(p0 > 0,
                fmt::format("hold: the state carries no compressive mean stress (p = {:.3g} Pa)", p0));
  Progress progress(logger, "hold", static_cast<double>(steps), 10.0);
  while (!phase.budget_spent()) {
    phase.advance_to_update();
    progress.update(static_cast<double>(phase.steps()));
    if (!simulation.at_control_update()) simulation.measure_stress_now(); // the last step's own stress
    report.samples.push_back(sample(simulation));
    report.largest_drift =
        std::max(report.largest_drift, std::abs(report.samples.back().mean_stress / p0 - 1.0));
  }
  return report;
}

void write_hold_csv(const HoldReport& report, const std::string& path) {
  std::string text = "step,p,q,unbalanced_force_ratio,kinetic_elastic_ratio\n";
  for (const HoldSample& s : report.samples)
    text += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g}\n", s.step, s.mean_stress, s.deviatoric_stress,
                        s.unbalanced_force_ratio, s.kinetic_elastic_ratio);
  h5::write_text_atomically(path, text);
}

} // namespace aniso::dem::protocol
