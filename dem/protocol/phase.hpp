#pragma once
// One phase of a protocol (prepare's compaction, a relaxation, a hold, a loading, a probe's
// fork): the simulation stepped one step or one control update at a time within a step budget.
// A protocol sets the phase's control state (model/cell_control.hpp names them) and dynamics,
// then reads as its algorithm:
//
//   Phase phase(simulation, "relaxation", max_steps, Phase::GiveBack::on_exit);
//   phase.fail_beyond_budget([&] { return "not in equilibrium after ..."; });
//   simulation.set_control(model::strain_axes_held(simulation.control()));
//   while (!balanced(simulation)) phase.advance_to_update();
//   phase.end(); // the loading's control, damping and watching back
//
// A phase that gives back does so in end(), collectively, as the protocol's last act. If an
// exception leaves it instead, the destructor gives back by assignment alone: no collective call,
// so that a failure seen on one rank cannot hang the others while the run ends.

#include "dem/simulation.hpp"

#include <cstdint>
#include <functional>
#include <limits>
#include <string>

namespace aniso::dem::protocol {

/// What a phase that gives back remembers: the control, settings and equilibrium watching the
/// simulation had when it began.
struct PhaseMemory {
  model::CellControl control;
  SimulationSettings settings;
  bool watched = false;
};

class Phase {
public:
  enum class GiveBack : std::uint8_t { nothing, on_exit };
  static constexpr std::int64_t unlimited = std::numeric_limits<std::int64_t>::max();

  /// A phase of at most `max_steps` steps; with GiveBack::on_exit it remembers the control, the
  /// settings and the equilibrium watching that `simulation` has now.
  Phase(Simulation& simulation, std::string label, std::int64_t max_steps = unlimited,
        GiveBack give_back = GiveBack::nothing);
  ~Phase();
  Phase(const Phase&) = delete;
  Phase& operator=(const Phase&) = delete;

  /// A step asked for beyond the budget throws ConvergenceError with this message (made when
  /// thrown, from the state then). Without one, stepping stops at the budget (budget_spent()).
  void fail_beyond_budget(std::function<std::string()> message) { failure_ = std::move(message); }
  /// One time step.
  void step();
  /// Steps until a step ends with a control update (stress and servo fresh), or the budget ends;
  /// `after_each_step` (if any) runs after every step (a minimiser's turn of the velocities).
  void advance_to_update(const std::function<void()>& after_each_step = {});
  /// `n` steps, or until the budget ends.
  void advance(std::int64_t n);

  [[nodiscard]] std::int64_t steps() const { return steps_; }
  [[nodiscard]] bool budget_spent() const { return steps_ >= max_steps_; }
  [[nodiscard]] const std::string& label() const { return label_; }
  /// Wall time since the phase began [s].
  [[nodiscard]] double seconds() const;

  /// Gives back what the phase remembered, in the order control, settings, watching
  /// (collective: the servo's rates and the damping's rate are measured anew). Nothing without
  /// GiveBack::on_exit.
  void end();

  /// What the phase will give back.
  [[nodiscard]] PhaseMemory memory() const { return {control_, settings_, watched_}; }
  /// Continues a phase interrupted after `steps` steps (a checkpoint holds it): it gives back
  /// `memory`, what the phase remembered then, not what the simulation has now.
  void resume(const PhaseMemory& memory, std::int64_t steps);
  /// Leaves the simulation as it is, mid-phase, and gives nothing back: an interrupted phase is
  /// written as it stands (memory() and steps() then, for resume()).
  void suspend() { give_back_ = false; }

private:
  [[nodiscard]] bool may_step();

  Simulation& simulation_;
  std::string label_;
  std::int64_t max_steps_;
  std::int64_t steps_ = 0;
  bool give_back_;
  model::CellControl control_;
  SimulationSettings settings_;
  bool watched_;
  std::function<std::string()> failure_;
  SectionTimes::Clock::time_point start_ = SectionTimes::Clock::now();
};

} // namespace aniso::dem::protocol
