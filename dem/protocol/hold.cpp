#include "dem/protocol/hold.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

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
  h5::CellState fixed = simulation.control();
  fixed.mode = {h5::AxisMode::strain_rate, h5::AxisMode::strain_rate, h5::AxisMode::strain_rate};
  fixed.target = Vec3::Zero();
  fixed.hold_mean_stress = false;
  fixed.servo_state = Vec3::Zero();
  simulation.watch_equilibrium(true);
  simulation.set_control(fixed);
  HoldReport report;
  report.samples.push_back(sample(simulation));
  const double p0 = report.samples.front().mean_stress;
  require_input(p0 > 0,
                fmt::format("hold: the state carries no compressive mean stress (p = {:.3g} Pa)", p0));
  const std::int64_t interval = simulation.settings().control_interval;
  Progress progress(logger, "hold", static_cast<double>(steps), 10.0);
  for (std::int64_t n = 1; n <= steps; ++n) {
    simulation.step();
    progress.update(static_cast<double>(n));
    if (simulation.step_count() % interval != 0 && n != steps) continue;
    if (simulation.step_count() % interval != 0) simulation.restore_stress(); // the last step's own stress
    report.samples.push_back(sample(simulation));
    report.largest_drift =
        std::max(report.largest_drift, std::abs(report.samples.back().mean_stress / p0 - 1.0));
  }
  return report;
}

void write_hold_csv(const HoldReport& report, const std::string& path) {
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp);
    out << "step,p,q,unbalanced_force_ratio,kinetic_elastic_ratio\n";
    for (const HoldSample& s : report.samples) {
      out << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g}\n", s.step, s.mean_stress, s.deviatoric_stress,
                         s.unbalanced_force_ratio, s.kinetic_elastic_ratio);
    }
    if (!out) throw FileError(fmt::format("cannot write '{}'", temp));
  }
  std::filesystem::rename(temp, path);
}

} // namespace aniso::dem::protocol
