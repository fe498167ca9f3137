#include "probe/fork.hpp"

#include "common/error.hpp"
#include "common/stop_request.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/parameters.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/protocol/phase.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

namespace aniso::probe {
namespace {

struct ContactCount {
  std::int64_t contacts = 0;
  std::int64_t sliding = 0;
};

// Touching pairs and those at the Coulomb limit, each counted by the owner of its lower id.
ContactCount count_contacts(const dem::Simulation& simulation) {
  const auto& pairs = simulation.neighbors().pairs();
  const auto& records = simulation.neighbors().records();
  const auto& history = simulation.neighbors().history();
  const std::size_t n_owned = simulation.particles().n_owned;
  std::int64_t counts[2] = {0, 0};
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (records[k].overlap <= 0 || pairs[k].i >= n_owned) continue;
    ++counts[0];
    if (history[k].sliding) ++counts[1];
  }
  const auto total = simulation.comm().sum(std::span<const std::int64_t>(counts, 2));
  return {total[0], total[1]};
}

Vec3 log_strain_from(const dem::Simulation& simulation, const Vec3& start_lengths) {
  return simulation.cell().lengths().cwiseQuotient(start_lengths).array().log().matrix();
}

// SIGTERM is polled (collectively on the fork's ranks) once per this many steps: within seconds at
// paper size, and at no measurable cost. A stopped fork is dropped whole and run anew later.
constexpr std::int64_t stop_poll_steps = 100;

class StopPoll {
public:
  StopPoll(const dem::Simulation& simulation, int fork) : simulation_(simulation), fork_(fork) {}
  /// Throws Interrupted on every rank of the fork once any has received SIGTERM, at most every
  /// stop_poll_steps steps.
  void operator()() {
    if (simulation_.step_count() < next_) return;
    next_ = simulation_.step_count() + stop_poll_steps;
    if (stop_requested(simulation_.comm()))
      throw Interrupted(
          fmt::format("fork {} stopped on SIGTERM at step {}", fork_, simulation_.step_count()));
  }

private:
  const dem::Simulation& simulation_;
  int fork_;
  std::int64_t next_ = 0;
};

// `n` steps of `phase`, polling for SIGTERM between chunks (the same steps as one advance(n)).
void advance_polling(dem::protocol::Phase& phase, std::int64_t n, StopPoll& poll) {
  for (std::int64_t done = 0; done < n;) {
    poll();
    const std::int64_t chunk = std::min(stop_poll_steps, n - done);
    phase.advance(chunk);
    done += chunk;
  }
}

// Half an increment at `rate` on `axis` (every other strain held, no servo), then a hold of the
// cell; returns the stresses of the hold's last window.
std::vector<Mat3> half_increment(dem::Simulation& simulation, int axis, double rate, std::int64_t half_steps,
                                 const ProbeConfig& config, StopPoll& poll) {
  dem::protocol::Phase phase(simulation, "half increment", half_steps + config.hold_steps);
  Vec3 rates = Vec3::Zero();
  rates[axis] = rate;
  simulation.set_control(dem::model::strain_controlled(simulation.control(), rates));
  advance_polling(phase, half_steps, poll);
  simulation.set_control(dem::model::fixed_cell(simulation.control()));
  advance_polling(phase, config.hold_steps - config.window_steps, poll);
  // stress() is fresh at every control update; those in the last window are the reading.
  std::vector<Mat3> samples;
  while (!phase.budget_spent()) {
    poll();
    phase.advance_to_update();
    if (simulation.at_control_update()) samples.push_back(simulation.stress());
  }
  require_input(!samples.empty(),
                fmt::format("probe.window_steps = {} holds no stress update (every {} steps): "
                            "raise it",
                            config.window_steps, simulation.settings().control_interval));
  return samples;
}

} // namespace

ForkSpec fork_spec(int index) {
  require_input(
      index >= reference_fork && index <= n_forks,
      fmt::format("fork number {} is out of range: forks are numbered 0 (reference) to {}", index, n_forks));
  if (index == reference_fork) return {index, 0, 0};
  return {index, (index - 1) / 2, index % 2 == 1 ? 1 : -1};
}

Mat3 mean_of(const std::vector<Mat3>& samples) {
  require_input(!samples.empty(), "no stress samples to average");
  Mat3 sum = Mat3::Zero();
  for (const Mat3& s : samples)
    sum += s;
  return sum / static_cast<double>(samples.size());
}

ForkResult run_fork(const h5::Checkpoint& checkpoint, const std::string& path, int index,
                    const ProbeConfig& config, const mpi::Comm& comm, const Logger& logger,
                    ForkTimes* times) {
  const ForkSpec spec = fork_spec(index);
  const auto restart_start = SectionTimes::Clock::now();
  dem::Simulation simulation = dem::io::from_checkpoint(checkpoint, path, comm);
  if (times != nullptr) times->restart.add_since(0, restart_start);
  const double p0 = mean_stress_compression_positive(simulation.stress());
  require_file(p0 > 0, fmt::format("checkpoint '{}': mean stress {:.4g} Pa is not compressive; the probe "
                                   "needs a confined assembly",
                                   path, p0));
  const double rate = dem::strain_rate_for_inertial_number(config.inertial_number, simulation.settings().d50,
                                                           simulation.settings().density, p0);
  const double dt = simulation.settings().time_step;
  // Every fork, the reference included, takes the same steps so that their samples line up.
  const auto half_steps =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(0.5 * config.increment / (rate * dt))));
  // The integrator scales L by (1 + rate dt) per step: this rate makes ln(L/L0) exactly sign * delta/2
  // per half; the reference applies none.
  const double applied =
      std::expm1(spec.sign * 0.5 * config.increment / static_cast<double>(half_steps)) / dt;

  ForkResult result;
  result.index = index;
  result.time_step = dt;
  result.half_steps = half_steps;
  result.hold_steps = config.hold_steps;
  result.strain_rate = std::expm1(0.5 * config.increment / static_cast<double>(half_steps)) / dt;
  result.stress_start = simulation.stress();
  const Vec3 start_lengths = simulation.cell().lengths();
  const ContactCount before = count_contacts(simulation);
  result.contacts_start = before.contacts;
  result.sliding_start = before.sliding;

  StopPoll poll(simulation, index);
  result.samples_half = half_increment(simulation, spec.axis, applied, half_steps, config, poll);
  result.strain_half = log_strain_from(simulation, start_lengths);
  result.samples_final = half_increment(simulation, spec.axis, applied, half_steps, config, poll);
  result.strain_final = log_strain_from(simulation, start_lengths);
  const ContactCount after = count_contacts(simulation);
  result.contacts_final = after.contacts;
  result.sliding_final = after.sliding;
  const Mat3 final_stress = mean_of(result.samples_final);
  logger->info(
      "fork {} ({}): 2 x ({} + {}) steps, p from {:.5g} to {:.5g} Pa, sliding contacts {} -> {} of {}", index,
      spec.sign == 0 ? std::string("reference")
                     : fmt::format("{}{} on x{}", spec.sign > 0 ? "+" : "-", config.increment, spec.axis + 1),
      half_steps, config.hold_steps, p0, mean_stress_compression_positive(final_stress), result.sliding_start,
      result.sliding_final, result.contacts_final);
  if (times != nullptr) times->engine.merge(simulation.times());
  return result;
}

} // namespace aniso::probe
