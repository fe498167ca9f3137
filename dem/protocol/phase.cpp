#include "dem/protocol/phase.hpp"

#include "common/error.hpp"

namespace aniso::dem::protocol {

Phase::Phase(Simulation& simulation, std::string label, std::int64_t max_steps, GiveBack give_back)
    : simulation_(simulation), label_(std::move(label)), max_steps_(max_steps),
      give_back_(give_back == GiveBack::on_exit), control_(simulation.control()),
      settings_(simulation.settings()), watched_(simulation.watching_equilibrium()) {}

Phase::~Phase() {
  if (give_back_) simulation_.put_back(control_, settings_, watched_);
}

bool Phase::may_step() {
  if (steps_ < max_steps_) return true;
  if (failure_) throw ConvergenceError(failure_());
  return false;
}

void Phase::step() {
  if (!may_step()) return;
  simulation_.step();
  ++steps_;
}

void Phase::advance_to_update(const std::function<void()>& after_each_step) {
  do {
    if (!may_step()) return;
    simulation_.step();
    ++steps_;
    if (after_each_step) after_each_step();
  } while (!simulation_.at_control_update());
}

void Phase::advance(std::int64_t n) {
  for (std::int64_t k = 0; k < n && may_step(); ++k) {
    simulation_.step();
    ++steps_;
  }
}

double Phase::seconds() const {
  return std::chrono::duration<double>(SectionTimes::Clock::now() - start_).count();
}

void Phase::resume(const PhaseMemory& memory, std::int64_t steps) {
  control_ = memory.control;
  settings_ = memory.settings;
  watched_ = memory.watched;
  steps_ = steps;
}

void Phase::end() {
  if (!give_back_) return;
  give_back_ = false;
  simulation_.set_control(control_);
  simulation_.reconfigure(settings_);
  simulation_.watch_equilibrium(watched_);
}

} // namespace aniso::dem::protocol
