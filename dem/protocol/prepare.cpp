#include "dem/protocol/prepare.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "common/keep_clock.hpp"
#include "common/stop_request.hpp"
#include "dem/data/spatial_order.hpp"
#include "dem/io/parameters.hpp"
#include "dem/model/rotation.hpp"
#include "dem/model/size_distribution.hpp"
#include "dem/protocol/phase.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/protocol/relax.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <span>

namespace aniso::dem::protocol {
namespace {

// Compacts at `rate` (negative) until the assembly seizes: a load-bearing
// network carries at least the seize stress while nearly at rest and with its
// forces balanced (unbalanced-force ratio below seize_force_ratio). Whenever p
// passes the seize stress the cell is held still, so that a hot, colliding
// assembly is not mistaken for a seized one: if the stress then decays as the
// motion is damped out, compaction resumes. On SIGTERM it stops at a control update with
// `stopped` set, from which `resume` continues (the simulation then being its state there).
struct Compaction {
  std::int64_t steps = 0;
  double seconds = 0; // wall time
  io::CompactionState state;
  bool stopped = false;
};

// `keep` sees the state at every control update where a SIGTERM stop could happen.
Compaction compact_until_seized(Simulation& simulation, double rate, const PrepareConfig& prepare,
                                const Logger& logger, const std::string& label, double expected_strain,
                                const io::CompactionState* resume,
                                const std::function<void(const io::CompactionState&)>& keep) {
  Phase phase(simulation, label);
  io::CompactionState state;
  if (resume != nullptr) {
    state = *resume;
    phase.resume(phase.memory(), state.steps);
  } else {
    state.start_volume = simulation.cell().volume();
    state.start_length = simulation.cell().lengths()[0];
    simulation.set_control(model::strain_controlled(simulation.control(), Vec3::Constant(rate)));
  }
  bool& holding = state.holding;
  const std::int64_t interval = simulation.settings().control_interval;
  // Compacting from the sparse state to a solid fraction of 0.74 is a strain of about
  // ln(0.74 / 0.05) / 3 at most; beyond that something is wrong.
  const double strain_limit = std::log(0.75 / 0.05) / 3.0;
  const std::int64_t max_hold_steps = 2000 * interval;
  std::int64_t& held_since = state.held_since;
  // The progress is the volumetric strain towards where the compaction is expected to seize, not
  // p: p stays near zero until the network jams and then rises within a few hundred steps, so an
  // estimate from p said "ETA 0 s" for most of the way. The pace includes the held phases, so the
  // estimate grows while the cell is held.
  const double start_volume = state.start_volume;
  // A stop void ratio ends the compaction at a chosen density instead of at seizure: below its
  // own jamming density a frictionless assembly never seizes (docs/methods/dem.md, "The preparation study").
  const double stop_void_ratio = prepare.compaction_stop_void_ratio;
  const double solid_volume = stop_void_ratio > 0 ? simulation.solid_volume() : 0.0;
  const double strain_to_seize = std::max(expected_strain, 1e-6);
  Progress progress(logger, label + " (volumetric strain to the expected seizure)", strain_to_seize, 10.0);
  for (;;) {
    phase.advance_to_update();
    const double p = mean_stress_compression_positive(simulation.stress());
    const double energy_ratio =
        simulation.equilibrium().kinetic_energy / (std::max(p, 1.0) * simulation.cell().volume());
    // Near the end the compaction alternates between compacting and holding the cell while the
    // seize test waits for the forces to balance; the line says which, and how far the test is.
    progress.update(std::min(std::log(start_volume / simulation.cell().volume()), strain_to_seize), [&] {
      return fmt::format(
          "p {:.3g} kPa (seized from {:.3g}), {}, unbalanced-force ratio {:.2g} (seized below {:.2g})",
          p / 1e3, prepare.seize_stress / 1e3, holding ? "cell held" : "compacting",
          simulation.equilibrium().unbalanced_force_ratio, prepare.seize_force_ratio);
    });
    if (stop_void_ratio > 0 && simulation.cell().volume() / solid_volume - 1.0 <= stop_void_ratio) {
      logger->info("{}: stopped at e = {:.4f} (dem.prepare.compaction_stop_void_ratio), p {:.3g} kPa", label,
                   simulation.cell().volume() / solid_volume - 1.0, p / 1e3);
      break;
    }
    const bool above = p >= prepare.seize_stress;
    // Only a held cell tells a load-bearing network from one that the compaction itself
    // loads: the viscous contact forces of a moving cell carry p of their own.
    // A network that carries p only while it still moves unloads once held; a seized one keeps
    // p with its forces balanced.
    if (holding && above && energy_ratio < 1e-4 &&
        simulation.equilibrium().unbalanced_force_ratio < prepare.seize_force_ratio)
      break;
    const bool stalled = holding && simulation.step_count() - held_since > max_hold_steps;
    if (above != holding || stalled) {
      // Stalled: still above the seize stress but never calm; compact on and look again.
      holding = above && !stalled;
      held_since = simulation.step_count();
      simulation.set_control(
          model::strain_controlled(simulation.control(), Vec3::Constant(holding ? 0.0 : rate)));
    }
    if (std::log(state.start_length / simulation.cell().lengths()[0]) > strain_limit) {
      throw ConvergenceError(
          fmt::format("{}: the assembly did not seize within a compaction strain of {:.2f} "
                      "(p = {:.3g} Pa, seize_stress {:.3g} Pa)",
                      label, strain_limit, p, prepare.seize_stress));
    }
    // Here, where the next update continues from the state above alone.
    state.steps = phase.steps();
    if (keep) keep(state);
    if (stop_requested(simulation.comm(), simulation.step_count()))
      return {phase.steps(), phase.seconds(), state, true};
  }
  simulation.set_control(model::fixed_cell(simulation.control()));
  return {phase.steps(), phase.seconds(), state, false};
}

// Random velocities of rms `rms_speed`, drawn in id order on every rank so that the
// result does not depend on the decomposition; the net momentum is removed.
void agitate(Simulation& simulation, double rms_speed, RandomStream& stream) {
  data::Particles& particles = simulation.particles();
  const double component = rms_speed / std::sqrt(3.0);
  const auto n_total = static_cast<std::size_t>(simulation.n_particles());
  std::vector<Vec3> drawn(n_total);
  for (auto& velocity : drawn) {
    const double x = stream.normal(), y = stream.normal(), z = stream.normal();
    velocity = Vec3(x, y, z) * component;
  }
  std::array<ExactSum, 4> sums; // momentum x, y, z and mass
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    particles.velocity[k] = drawn[particles.id[k]];
    for (int a = 0; a < 3; ++a)
      sums[static_cast<std::size_t>(a)].add(particles.mass[k] * particles.velocity[k][a]);
    sums[3].add(particles.mass[k]);
  }
  const std::vector<ExactSum> total = simulation.comm().sum_exact(std::span<const ExactSum>(sums));
  const Vec3 drift = Vec3(total[0].value(), total[1].value(), total[2].value()) / total[3].value();
  for (std::size_t k = 0; k < particles.n_owned; ++k)
    particles.velocity[k] -= drift;
}

// A uniformly distributed rotation: a normalised vector of four standard normals.
Quat random_orientation(RandomStream& stream) {
  for (;;) {
    const double w = stream.normal(), x = stream.normal(), y = stream.normal(), z = stream.normal();
    const Quat q(w, x, y, z); // drawn in sequence: argument evaluation order is unspecified
    const double norm = q.norm();
    if (norm > 1e-6) return Quat(q.coeffs() / norm);
  }
}

} // namespace

// Consolidates to p0 with the stress servo on all three axes and relaxes to static
// equilibrium there (dem/protocol/relax.hpp): p within consolidation_tolerance and the
// unbalanced-force ratio below dem.equilibrium.tolerance.
Relaxation consolidate(Simulation& simulation, const DemConfig& config, double rate, const Logger& logger,
                       const RelaxationStart& start) {
  if (start.resume == nullptr)
    simulation.set_control(model::isotropic_stress(simulation.control(), config.prepare.confining_pressure));
  EquilibriumConfig tolerances = config.equilibrium;
  tolerances.stress_tolerance = config.prepare.consolidation_tolerance;
  // Every run starts from this state: it is verified static, however many windows that takes
  // (dem.equilibrium.max_windows is for the checkpoints of a loading in flow).
  tolerances.max_windows = 0;
  // The run's own time step: a relaxation stopped within FIRE holds FIRE's.
  const double time_step =
      start.resume != nullptr ? start.resume->memory.settings.time_step : simulation.settings().time_step;
  const std::int64_t max_steps =
      config.equilibrium.max_steps + 200 * static_cast<std::int64_t>(0.05 / (rate * time_step));
  return relax_to_equilibrium(simulation, tolerances, max_steps, logger, "consolidation to p0", start);
}

void with_loading_contacts(Simulation& simulation, const DemConfig& config, double rate) {
  SimulationSettings settings = simulation.settings();
  settings.material.friction = config.material.friction;
  settings.material.damping_ratio = config.integration.damping;
  settings.servo.max_rate = rate;
  settings.global_damping = config.integration.global_damping;
  settings.global_damping_spin_factor = config.integration.global_damping_spin_factor;
  simulation.reconfigure(settings);
}

double refinement_energy(std::span<const AgitationRun> runs, double aim) {
  double x_lo = 0, e_lo = INFINITY, x_hi = INFINITY, e_hi = 0;
  for (const AgitationRun& run : runs)
    if (run.void_ratio > aim && (e_lo == INFINITY || run.energy > x_lo))
      x_lo = run.energy, e_lo = run.void_ratio;
  for (const AgitationRun& run : runs)
    if (run.void_ratio <= aim && run.energy > x_lo && run.energy < x_hi)
      x_hi = run.energy, e_hi = run.void_ratio;
  require_input(e_lo != INFINITY && x_hi != INFINITY,
                "refinement_energy: the runs do not bracket the aim (a run above it at a lower energy "
                "than one below it)");
  // Kept a tenth of the bracket away from its ends, where the noise of the seized e could pin it.
  const double fraction = std::clamp((e_lo - aim) / (e_lo - e_hi), 0.1, 0.9);
  return x_lo + fraction * (x_hi - x_lo);
}

Simulation sparse_assembly(const DemConfig& config, RandomStream& sizes, RandomStream& placement,
                           const mpi::Comm& comm) {
  const auto& pc = config.particles;
  RandomStream orientations(config.seed, 3);
  const model::Grading grading{pc.diameter_min, pc.d50, pc.diameter_max};
  const std::vector<double> diameters =
      model::sample_diameters(grading, static_cast<std::size_t>(pc.count), sizes);
  // The sparse start places bounding spheres (radius = half-width), so their volume sets the
  // cell: for ovoids the particles themselves fill less (about alpha times as much).
  double solid = 0;
  for (double d : diameters)
    solid += model::particle_volume(0.5 * d, 1.0, pc.splice_angle);
  const auto& aspect = config.prepare.cell_aspect;
  const double volume = solid / config.prepare.initial_solid_fraction;
  const double unit = std::cbrt(volume / (aspect[0] * aspect[1] * aspect[2]));
  const Vec3 lengths(aspect[0] * unit, aspect[1] * unit, aspect[2] * unit);
  const PeriodicCell cell(lengths);
  // Random sequential addition, largest first, so that no two particles overlap.
  std::vector<Vec3> positions;
  std::vector<double> radii;
  std::vector<Quat> orientations_drawn;
  for (std::size_t k = 0; k < diameters.size(); ++k) {
    const double radius = 0.5 * diameters[k];
    // Ovoids get uniformly random orientations; spheres keep the identity (it carries nothing).
    const Quat orientation = pc.aspect_ratio == 1.0 ? Quat::Identity() : random_orientation(orientations);
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      const Vec3 x(placement.uniform(0, lengths[0]), placement.uniform(0, lengths[1]),
                   placement.uniform(0, lengths[2]));
      placed = true;
      for (std::size_t other = 0; other < positions.size() && placed; ++other) {
        const double reach = radius + radii[other];
        placed = cell.minimum_image(x - positions[other]).squaredNorm() > reach * reach;
      }
      if (placed) {
        positions.push_back(x);
        radii.push_back(radius);
        orientations_drawn.push_back(orientation);
      }
    }
    if (!placed) {
      throw ConvergenceError(fmt::format("could not place particle {} of {} without overlap: lower "
                                         "dem.prepare.initial_solid_fraction ({})",
                                         k + 1, diameters.size(), config.prepare.initial_solid_fraction));
    }
  }
  // Ids in spatial order (dem/data/spatial_order.hpp): the compaction is nearly affine, so
  // neighbours at the sparse start stay neighbours in the dense assembly.
  data::Particles particles;
  const std::vector<std::size_t> order = data::spatial_order(positions, lengths, 2.0 * pc.d50);
  for (std::size_t id = 0; id < order.size(); ++id) {
    const std::size_t k = order[id];
    particles.add(id, radii[k], pc.aspect_ratio, pc.splice_angle, pc.density, positions[k],
                  orientations_drawn[k]);
  }
  SimulationSettings settings = io::settings_from_config(config, diameters.back());
  settings.material.friction = config.material.friction_prepare;
  settings.material.damping_ratio = config.prepare.damping;
  settings.global_damping = config.prepare.global_damping;
  // The compaction's own: the loading behaviour's spin factor (oval: 6, a rolling resistance in
  // effect) loosened alpha = 0.625's first jam from e = 0.569 to 0.604, out of the cycles' reach.
  settings.global_damping_spin_factor = config.prepare.global_damping_spin_factor;
  return Simulation(std::move(particles), cell, model::CellControl{}, settings, comm);
}

namespace {

// The seized states of the protocol: one per compaction cycle, and the refinements of a cycle
// (the same cycle run again from the previous one's seized state with a weaker agitation).
struct Seized {
  Simulation state;
  double void_ratio = 0;
  int cycle = 0;               // 1-based
  int refinement = 0;          // 0: the cycle itself
  double agitation_energy = 1; // of the agitation that led to it, as a fraction of the configured one
  bool consolidated = false;
};

struct Consolidated {
  Simulation state;
  StateMeasures measures;
  Relaxation relaxation;
  double seized_void_ratio = 0;
  int cycle = 0, refinement = 0; // of the seized state
};

std::string seized_name(int cycle, int refinement) {
  return refinement == 0 ? fmt::format("cycle {}", cycle)
                         : fmt::format("refinement {} of cycle {}", refinement, cycle);
}

// Thrown on every rank at once when the protocol stops on SIGTERM; prepare_assembly catches it.
struct Stopped {
  PrepareStop stop;
};

class Protocol {
public:
  Protocol(const DemConfig& config, const Logger& logger, const mpi::Comm& comm,
           const io::PreparePieces& pieces)
      : config_(config), logger_(logger), pieces_(pieces), keep_clock_(pieces.keep_interval_seconds()),
        sizes_(config.seed, 0), placement_(config.seed, 1), agitation_(config.seed, 2),
        refinement_stream_(config.seed, 4), sparse_(sparse_assembly(config, sizes_, placement_, comm)) {
    sparse_.watch_equilibrium(true); // the seize test reads it at every control update
    const auto& pc = config.particles;
    rate_ = strain_rate_for_inertial_number(config.prepare.inertial_number, pc.d50, pc.density,
                                            config.prepare.confining_pressure);
    // Compaction to the target takes a volumetric strain of order one.
    protocol::require_reachable_strain(0.3, rate_, sparse_.settings().time_step, "prepare");
    rms_speed_ = config.prepare.agitation_speed * std::sqrt(config.prepare.confining_pressure / pc.density);
    logger->info("prepare: {} particles, cell {:.4g} x {:.4g} x {:.4g} mm, time step {:.3g} s, compaction "
                 "rate {:.3g} /s",
                 pc.count, 1e3 * sparse_.cell().lengths()[0], 1e3 * sparse_.cell().lengths()[1],
                 1e3 * sparse_.cell().lengths()[2], sparse_.settings().time_step, rate_);
  }

  PreparedAssembly run();

private:
  const DemConfig& config_;
  const Logger& logger_;
  const io::PreparePieces& pieces_;
  KeepClock keep_clock_; ///< when the piece in progress is kept
  RandomStream sizes_, placement_, agitation_, refinement_stream_;
  Simulation sparse_;
  double rate_ = 0, rms_speed_ = 0;
  double stop_void_ratio_ = 0;      ///< where the compaction in progress stops (0: at seizure)
  std::vector<Seized> seized_;      // cycles in order, refinements appended as they run
  std::vector<std::size_t> cycles_; // indices into seized_ of the cycles themselves
  int refinements_ = 0;
  double last_compaction_strain_ = 0; ///< volumetric strain of the last cycle's compaction
  double compaction_seconds_ = 0, consolidation_seconds_ = 0; ///< wall time, for the timing table

  double target() const { return config_.prepare.target_void_ratio; }
  double tolerance() const { return config_.prepare.void_ratio_tolerance; }
  bool stops_at_void_ratio() const { return config_.prepare.compaction_stop_void_ratio > 0; }
  bool cycles_left() const { return static_cast<std::int64_t>(cycles_.size()) < config_.prepare.cycles; }
  PreparedAssembly run_cycles();
  PreparedAssembly run_stopped();
  PreparedAssembly finish(Consolidated best, double aim);
  void run_cycle();
  bool refine(double aim);
  // A seized state and how it was reached ("after N steps", or the file it was taken from).
  struct Seizure {
    Simulation state;
    std::string how;
  };
  Seizure seize(Simulation simulation, const io::PieceName& name, const std::string& label, double expected);
  std::vector<RandomStream::State> streams() const {
    return {sizes_.state(), placement_.state(), agitation_.state(), refinement_stream_.state()};
  }
  Consolidated consolidate_seized(Seized& seized);
  std::string failure_hint(const Consolidated& best, double aim) const;
};

// A compaction of `simulation` (agitated) until it seizes, kept as the piece `name`; or the piece
// that a stopped prepare kept, with the random streams as they were after it; a compaction stopped
// on SIGTERM is continued. Throws Stopped, keeping the compaction's state.
Protocol::Seizure Protocol::seize(Simulation simulation, const io::PieceName& name, const std::string& label,
                                  double expected) {
  if (std::optional<io::KeptPiece> kept = pieces_.find(name)) {
    const auto& rng = kept->record.rng_state;
    sizes_ = RandomStream::from_state(rng[0]);
    placement_ = RandomStream::from_state(rng[1]);
    agitation_ = RandomStream::from_state(rng[2]);
    refinement_stream_ = RandomStream::from_state(rng[3]);
    last_compaction_strain_ = kept->record.compaction_strain;
    // Watched, as every state descended from the sparse assembly is (the seize test reads it);
    // by assignment alone, so that the damping rate stays the stored one.
    kept->simulation.put_back(kept->simulation.control(), kept->simulation.settings(), true);
    return {std::move(kept->simulation), "as kept in " + kept->path};
  }
  std::optional<io::KeptCompaction> stopped = pieces_.find_stopped_compaction(name);
  if (stopped) {
    logger_->info("{}: continued from {}", label, stopped->path);
    simulation = std::move(stopped->simulation);
    simulation.put_back(simulation.control(), simulation.settings(), true); // as kept pieces
  }
  PrepareConfig compaction_settings = config_.prepare;
  compaction_settings.compaction_stop_void_ratio = stop_void_ratio_;
  const auto keep = [&](const io::CompactionState& state) {
    if (!keep_clock_.due(simulation.comm())) return;
    const std::string path = pieces_.keep_stopped_compaction(name, simulation, streams(), state);
    logger_->info("{}: kept at step {} in {} (--resume continues from it)", label, simulation.step_count(),
                  path);
  };
  const Compaction compaction = compact_until_seized(simulation, -rate_, compaction_settings, logger_, label,
                                                     expected, stopped ? &stopped->state : nullptr, keep);
  compaction_seconds_ += compaction.seconds;
  if (compaction.stopped) {
    const std::string path = pieces_.keep_stopped_compaction(name, simulation, streams(), compaction.state);
    throw Stopped{{label, simulation.step_count(), path}};
  }
  if (name.refinement == 0)
    last_compaction_strain_ = std::log(compaction.state.start_volume / simulation.cell().volume());
  pieces_.keep(name, simulation, {streams(), last_compaction_strain_});
  return {std::move(simulation), fmt::format("after {} steps", compaction.steps)};
}

void Protocol::run_cycle() {
  const int cycle = static_cast<int>(cycles_.size()) + 1;
  Simulation simulation = cycles_.empty() ? sparse_ : seized_[cycles_.back()].state;
  if (cycle > 1) agitate(simulation, rms_speed_, agitation_);
  // Expected: the first cycle seizes at most at random close packing (solid fraction 0.64); a later
  // one about where the cycle before it did, from its own start.
  constexpr double random_close_packing = 0.64;
  const double expected =
      cycle == 1 ? std::log(random_close_packing * simulation.cell().volume() / simulation.solid_volume())
                 : last_compaction_strain_;
  Seizure seized = seize(std::move(simulation), {io::PieceKind::seized, cycle, 0},
                         fmt::format("compaction cycle {}", cycle), expected);
  const StateMeasures m = seized.state.measure();
  logger_->info("cycle {:2d}: seized {} at e = {:.4f}, Z = {:.3f}", cycle, seized.how, m.void_ratio,
                m.coordination);
  cycles_.push_back(seized_.size());
  seized_.push_back(Seized{std::move(seized.state), m.void_ratio, cycle, 0, 1.0, false});
}

// Runs cycle k + 1 again from the state cycle k seized in, with the agitation energy chosen so
// that it seizes at `aim`: interpolated, linearly in the energy, between the runs of that cycle
// that seized nearest above and below the aim (energy 0 leaves cycle k's e). Returns false
// when no cycle brackets the aim.
bool Protocol::refine(double aim) {
  std::size_t k = 0;
  while (k + 1 < cycles_.size() &&
         !(seized_[cycles_[k]].void_ratio > aim && seized_[cycles_[k + 1]].void_ratio <= aim))
    ++k;
  if (k + 1 >= cycles_.size()) return false;
  const Seized& base = seized_[cycles_[k]];
  const int cycle = base.cycle + 1;
  std::vector<AgitationRun> runs{{0.0, base.void_ratio}, {1.0, seized_[cycles_[k + 1]].void_ratio}};
  for (const Seized& s : seized_)
    if (s.cycle == cycle && s.refinement > 0) runs.push_back({s.agitation_energy, s.void_ratio});
  const double energy = refinement_energy(runs, aim);
  ++refinements_;
  Simulation simulation = base.state;
  agitate(simulation, rms_speed_ * std::sqrt(energy), refinement_stream_);
  Seizure seized = seize(std::move(simulation), {io::PieceKind::seized, cycle, refinements_},
                         seized_name(cycle, refinements_), last_compaction_strain_);
  const StateMeasures m = seized.state.measure();
  logger_->info(
      "refinement {} of cycle {} (agitation energy x {:.3f}, aiming at e = {:.4f}): seized {} at e = "
      "{:.4f}",
      refinements_, cycle, energy, aim, seized.how, m.void_ratio);
  seized_.push_back(Seized{std::move(seized.state), m.void_ratio, cycle, refinements_, energy, false});
  return true;
}

// Consolidates the seized state, kept as a piece; or takes the piece a stopped prepare kept, or
// continues its consolidation stopped on SIGTERM. Throws Stopped, keeping the consolidation's state.
Consolidated Protocol::consolidate_seized(Seized& seized) {
  seized.consolidated = true;
  const std::string name = seized_name(seized.cycle, seized.refinement);
  const io::PieceName piece{io::PieceKind::consolidated, seized.cycle, seized.refinement};
  std::optional<io::KeptPiece> kept = pieces_.find(piece);
  std::optional<io::KeptRelaxation> stopped = kept ? std::nullopt : pieces_.find_stopped_consolidation(piece);
  Simulation start = [&]() -> Simulation {
    if (kept) return std::move(kept->simulation);
    if (stopped) return std::move(stopped->simulation);
    return seized.state;
  }();
  Consolidated result{std::move(start), {}, {}, seized.void_ratio, seized.cycle, seized.refinement};
  Simulation& chosen = result.state;
  if (kept) {
    logger_->info("consolidation of {}: taken from {}", name, kept->path);
  } else {
    logger_->info("consolidating {} (seized at e = {:.4f}) to p0{}", name, seized.void_ratio,
                  stopped ? ", continued from " + stopped->path : "");
    // Consolidated with the friction and damping that loading will use, so that the relaxation
    // proves the state static with them (a state verified with heavier damping can creep without it).
    if (!stopped) with_loading_contacts(chosen, config_, rate_);
    const auto keep = [&](const RelaxationState& state) {
      if (!keep_clock_.due(chosen.comm())) return;
      const std::string path = pieces_.keep_stopped_consolidation(piece, chosen, streams(), state);
      logger_->info("consolidation of {}: kept at step {} in {} (--resume continues from it)", name,
                    chosen.step_count(), path);
    };
    result.relaxation =
        consolidate(chosen, config_, rate_, logger_,
                    {.stoppable = true, .resume = stopped ? &stopped->state : nullptr, .keep = keep});
    consolidation_seconds_ += result.relaxation.seconds;
    if (result.relaxation.interrupted) {
      const std::string path =
          pieces_.keep_stopped_consolidation(piece, chosen, streams(), *result.relaxation.interrupted);
      throw Stopped{{"consolidation of " + name, chosen.step_count(), path}};
    }
    chosen.watch_equilibrium(false);
    pieces_.keep(piece, chosen, {streams(), last_compaction_strain_});
    logger_->info("consolidation took {} steps; unbalanced-force ratio {:.2e}, kinetic/elastic {:.2e}",
                  result.relaxation.steps, result.relaxation.equilibrium.unbalanced_force_ratio,
                  result.relaxation.equilibrium.kinetic_elastic_ratio());
  }
  result.measures = chosen.measure();
  const StateMeasures& m = result.measures;
  logger_->info("consolidated to p = {:.4g} Pa: e = {:.4f} (compacted by {:.4f}), Z = {:.3f}, Z without "
                "rattlers = {:.3f} ({} rattlers, {:.1f}%)",
                m.mean_stress, m.void_ratio, seized.void_ratio - m.void_ratio, m.coordination,
                m.coordination_no_rattlers, m.n_rattlers,
                100.0 * static_cast<double>(m.n_rattlers) / static_cast<double>(config_.particles.count));
  return result;
}

std::string Protocol::failure_hint(const Consolidated& best, double aim) const {
  if (stops_at_void_ratio()) {
    return fmt::format("the compaction stopped at e = {:.4f} and consolidation to p0 compacted it to {:.4f} "
                       "({} of at most {} corrections of the stop ran): set "
                       "dem.prepare.compaction_stop_void_ratio to about {:.4f} or raise "
                       "dem.prepare.refinement_cycles",
                       best.seized_void_ratio, best.measures.void_ratio, refinements_,
                       config_.prepare.refinement_cycles,
                       stop_void_ratio_ + target() - best.measures.void_ratio);
  }
  if (best.measures.void_ratio > target())
    return "raise dem.prepare.cycles or dem.prepare.agitation_speed, or lower dem.material.friction_prepare "
           "(docs/methods/dem.md, 'Reaching the target void ratio')";
  const double compaction = best.seized_void_ratio - best.measures.void_ratio;
  const double first = seized_[cycles_.front()].void_ratio;
  if (first < target() - tolerance())
    return "the first cycle already packs denser: raise dem.material.friction_prepare";
  const std::string what =
      fmt::format("consolidation to p0 compacted the kept {} from e = {:.4f} by {:.4f}",
                  seized_name(best.cycle, best.refinement), best.seized_void_ratio, compaction);
  if (first <= aim)
    return what +
           fmt::format(", and no cycle seized above e = {:.4f} (the first at {:.4f}): raise "
                       "dem.material.friction_prepare or dem.prepare.target_void_ratio by about {:.4f}",
                       aim, first, compaction);
  return what +
         fmt::format(", and {} of at most {} refinement cycles did not seize within half the tolerance "
                     "of e = {:.4f}: raise dem.prepare.refinement_cycles or widen "
                     "dem.prepare.void_ratio_tolerance",
                     refinements_, config_.prepare.refinement_cycles, aim);
}

PreparedAssembly Protocol::run() {
  return stops_at_void_ratio() ? run_stopped() : run_cycles();
}

// One compaction from the sparse state, stopped at a void ratio, then consolidated at the loading
// friction. Consolidation compacts a state that was not load-bearing, by an amount the stop
// cannot know in advance, so a miss moves the stop by it and the compaction runs again from the
// sparse state (at most refinement_cycles times, each kept as a refinement of cycle 1).
PreparedAssembly Protocol::run_stopped() {
  stop_void_ratio_ = config_.prepare.compaction_stop_void_ratio;
  const double sparse_void_ratio = sparse_.cell().volume() / sparse_.solid_volume() - 1.0;
  require_input(
      stop_void_ratio_ < sparse_void_ratio,
      fmt::format("dem.prepare.compaction_stop_void_ratio = {:g} is not below the sparse start's e = "
                  "{:.4f}: nothing would be compacted",
                  stop_void_ratio_, sparse_void_ratio));
  run_cycle();
  std::optional<Consolidated> best;
  for (;;) {
    Consolidated candidate = consolidate_seized(seized_.back());
    const double miss = target() - candidate.measures.void_ratio;
    if (!best || std::abs(miss) < std::abs(best->measures.void_ratio - target())) best = std::move(candidate);
    if (std::abs(miss) <= tolerance() || refinements_ >= config_.prepare.refinement_cycles) break;
    stop_void_ratio_ += miss;
    ++refinements_;
    const std::string label =
        fmt::format("compaction stopped at e = {:.4f} (correction {})", stop_void_ratio_, refinements_);
    Seizure seized = seize(sparse_, {io::PieceKind::seized, 1, refinements_}, label, last_compaction_strain_);
    const StateMeasures m = seized.state.measure();
    logger_->info("correction {}: stopped {} at e = {:.4f}, Z = {:.3f}", refinements_, seized.how,
                  m.void_ratio, m.coordination);
    seized_.push_back(Seized{std::move(seized.state), m.void_ratio, 1, refinements_, 0.0, false});
  }
  return finish(std::move(*best), target());
}

// The cycles run until one seizes at or below the target; the one nearest the target is
// consolidated to p0. Consolidation compacts (flat ovoids by up to 0.005 at demo size), so when
// the consolidated e misses the target, the compaction it measured moves the aim for the seized
// e to target + compaction: the cycle nearest that aim is consolidated if it lies within half
// the tolerance of it, else the cycle that steps across the aim is run again from its
// predecessor with a weaker agitation, chosen to seize at the aim (refinement cycles).
PreparedAssembly Protocol::run_cycles() {
  const auto& pr = config_.prepare;
  std::optional<Consolidated> best;
  double aim = target();
  bool compaction_known = false;
  for (;;) {
    while ((cycles_.empty() || seized_[cycles_.back()].void_ratio > aim) && cycles_left())
      run_cycle();
    if (cycles_.size() < static_cast<std::size_t>(pr.cycles) && !compaction_known &&
        seized_[cycles_.back()].void_ratio <= aim)
      logger_->info("cycle {} reached the target: no further cycles", cycles_.size());
    std::optional<std::size_t> nearest;
    for (std::size_t k = 0; k < seized_.size(); ++k) {
      if (seized_[k].consolidated) continue;
      if (!nearest || std::abs(seized_[k].void_ratio - aim) < std::abs(seized_[*nearest].void_ratio - aim))
        nearest = k;
    }
    const double miss = nearest ? std::abs(seized_[*nearest].void_ratio - aim) : INFINITY;
    if (compaction_known && miss > 0.5 * tolerance()) {
      if (refinements_ < pr.refinement_cycles && refine(aim)) continue;
      if (miss > tolerance()) break;
    }
    if (!nearest) break;
    Consolidated candidate = consolidate_seized(seized_[*nearest]);
    const double distance = std::abs(candidate.measures.void_ratio - target());
    const bool better = !best || distance < std::abs(best->measures.void_ratio - target());
    aim = target() + (candidate.seized_void_ratio - candidate.measures.void_ratio);
    compaction_known = true;
    if (better) best = std::move(candidate);
    if (distance <= tolerance()) break;
  }
  return finish(std::move(*best), aim);
}

PreparedAssembly Protocol::finish(Consolidated best_assembly, double aim) {
  const auto& pr = config_.prepare;
  Consolidated* best = &best_assembly;
  const StateMeasures& m = best->measures;
  if (std::abs(m.void_ratio - target()) > tolerance()) {
    std::vector<double> cycle_void_ratios;
    for (std::size_t k : cycles_)
      cycle_void_ratios.push_back(seized_[k].void_ratio);
    throw ConvergenceError(fmt::format(
        "prepare: the assembly reached e = {:.4f}, {} the target dem.prepare.target_void_ratio = {:.4f} by "
        "more than dem.prepare.void_ratio_tolerance = {:.4f} after {} of at most {} cycles (cycle void "
        "ratios {:.4f}); {}",
        m.void_ratio, m.void_ratio > target() ? "above" : "below", target(), tolerance(), cycles_.size(),
        pr.cycles, fmt::join(cycle_void_ratios, ", "), failure_hint(*best, aim)));
  }
  PreparedAssembly result;
  for (std::size_t k : cycles_)
    result.cycle_void_ratios.push_back(seized_[k].void_ratio);
  for (const Seized& s : seized_)
    if (s.refinement > 0) result.refinement_void_ratios.push_back(s.void_ratio);
  result.chosen_cycle = best->cycle;
  result.chosen_refinement = best->refinement;
  logger_->info("kept {} (seized at e = {:.4f}, consolidated to {:.4f}, target {:.4f})",
                seized_name(best->cycle, best->refinement), best->seized_void_ratio, m.void_ratio, target());
  result.consolidated = m;
  result.simulation = std::move(best->state);
  result.rng_state = {sizes_.state(), placement_.state(), agitation_.state(), refinement_stream_.state()};
  result.compaction_seconds = compaction_seconds_;
  result.consolidation_seconds = consolidation_seconds_;
  return result;
}

} // namespace

PreparedAssembly prepare_assembly(const DemConfig& config, const Logger& logger, const mpi::Comm& comm,
                                  const io::PreparePieces& pieces) {
  Protocol protocol(config, logger, comm, pieces);
  try {
    return protocol.run();
  } catch (const Stopped& stopped) {
    PreparedAssembly result;
    result.stopped = stopped.stop;
    return result;
  }
}

PreparedAssembly prepare_assembly(const DemConfig& config, const Logger& logger, const mpi::Comm& comm) {
  return prepare_assembly(config, logger, comm, io::PreparePieces(comm));
}

} // namespace aniso::dem::protocol
