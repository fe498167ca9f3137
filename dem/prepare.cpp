#include "dem/prepare.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "dem/relax.hpp"
#include "dem/rotation.hpp"
#include "dem/settings.hpp"
#include "dem/size_distribution.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <numbers>
#include <span>

namespace aniso::dem {
namespace {

using h5::AxisMode;

h5::CellState isotropic_strain_control(const Simulation& simulation, double rate) {
  h5::CellState state = simulation.cell_state();
  state.mode = {AxisMode::strain_rate, AxisMode::strain_rate, AxisMode::strain_rate};
  state.target = Vec3::Constant(rate);
  state.hold_mean_stress = false;
  return state;
}

// Compacts at `rate` (negative) until the assembly seizes: a load-bearing
// network carries at least the seize stress while nearly at rest and with its
// forces balanced (unbalanced-force ratio below seize_force_ratio). Whenever p
// passes the seize stress the cell is held still, so that a hot, colliding
// assembly is not mistaken for a seized one: if the stress then decays as the
// motion is damped out, compaction resumes. Returns the steps taken.
std::int64_t compact_until_seized(Simulation& simulation, double rate, const PrepareConfig& prepare,
                                  const Logger& logger, const std::string& label) {
  simulation.set_control(isotropic_strain_control(simulation, rate));
  bool holding = false;
  const std::int64_t interval = simulation.settings().control_interval;
  const std::int64_t start = simulation.step_count();
  // Compacting from the sparse state to a solid fraction of 0.74 is a strain of about
  // ln(0.74 / 0.05) / 3 at most; beyond that something is wrong.
  const double strain_limit = std::log(0.75 / 0.05) / 3.0;
  const std::int64_t max_hold_steps = 2000 * interval;
  std::int64_t held_since = 0;
  Progress progress(logger, label, prepare.seize_stress, 10.0);
  const Vec3 start_lengths = simulation.cell().lengths();
  for (;;) {
    simulation.step();
    if (simulation.step_count() % interval != 0) continue;
    const double p = mean_stress_compression_positive(simulation.stress());
    const double energy_ratio =
        simulation.equilibrium().kinetic_energy / (std::max(p, 1.0) * simulation.cell().volume());
    progress.update(std::clamp(p, 0.0, prepare.seize_stress));
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
      simulation.set_control(isotropic_strain_control(simulation, holding ? 0.0 : rate));
    }
    if (std::log(start_lengths[0] / simulation.cell().lengths()[0]) > strain_limit) {
      throw ConvergenceError(
          fmt::format("{}: the assembly did not seize within a compaction strain of {:.2f} "
                      "(p = {:.3g} Pa, seize_stress {:.3g} Pa)",
                      label, strain_limit, p, prepare.seize_stress));
    }
  }
  simulation.set_control(isotropic_strain_control(simulation, 0.0));
  return simulation.step_count() - start;
}

// Random velocities of rms `rms_speed`, drawn in id order on every rank so that the
// result does not depend on the decomposition; the net momentum is removed.
void agitate(Simulation& simulation, double rms_speed, RandomStream& stream) {
  Particles& particles = simulation.particles();
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

// Consolidates to p0 with the stress servo on all three axes and relaxes to static
// equilibrium there (dem/relax.hpp): p within consolidation_tolerance and the
// unbalanced-force ratio below dem.equilibrium.tolerance.
Relaxation consolidate(Simulation& simulation, const DemConfig& config, double rate, const Logger& logger) {
  h5::CellState state = simulation.cell_state();
  state.mode = {AxisMode::stress, AxisMode::stress, AxisMode::stress};
  state.target = Vec3::Constant(-config.prepare.confining_pressure);
  state.hold_mean_stress = false;
  state.servo_state = Vec3::Zero();
  simulation.set_control(state);
  EquilibriumConfig tolerances = config.equilibrium;
  tolerances.stress_tolerance = config.prepare.consolidation_tolerance;
  const std::int64_t max_steps =
      config.equilibrium.max_steps +
      200 * static_cast<std::int64_t>(0.05 / (rate * simulation.settings().time_step));
  return relax_to_equilibrium(simulation, tolerances, max_steps, logger, "consolidation to p0");
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

Simulation sparse_assembly(const DemConfig& config, RandomStream& sizes, RandomStream& placement,
                           const mpi::Comm& comm) {
  const auto& pc = config.particles;
  RandomStream orientations(config.seed, 3);
  const Grading grading{pc.diameter_min, pc.d50, pc.diameter_max};
  const std::vector<double> diameters = sample_diameters(grading, static_cast<std::size_t>(pc.count), sizes);
  // The sparse start places bounding spheres (radius = half-width), so their volume sets the
  // cell: for ovoids the particles themselves fill less (about alpha times as much).
  double solid = 0;
  for (double d : diameters)
    solid += particle_volume(0.5 * d, 1.0, pc.splice_angle);
  const auto& aspect = config.prepare.cell_aspect;
  const double volume = solid / config.prepare.initial_solid_fraction;
  const double unit = std::cbrt(volume / (aspect[0] * aspect[1] * aspect[2]));
  const Vec3 lengths(aspect[0] * unit, aspect[1] * unit, aspect[2] * unit);
  const PeriodicCell cell(lengths);
  // Random sequential addition, largest first, so that no two particles overlap.
  Particles particles;
  for (std::size_t k = 0; k < diameters.size(); ++k) {
    const double radius = 0.5 * diameters[k];
    // Ovoids get uniformly random orientations; spheres keep the identity (it carries nothing).
    const Quat orientation = pc.aspect_ratio == 1.0 ? Quat::Identity() : random_orientation(orientations);
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      const Vec3 x(placement.uniform(0, lengths[0]), placement.uniform(0, lengths[1]),
                   placement.uniform(0, lengths[2]));
      placed = true;
      for (std::size_t other = 0; other < particles.size() && placed; ++other) {
        const double reach = radius + particles.radius[other];
        placed = cell.minimum_image(x - particles.position[other]).squaredNorm() > reach * reach;
      }
      if (placed) particles.add(k, radius, pc.aspect_ratio, pc.splice_angle, pc.density, x, orientation);
    }
    if (!placed) {
      throw ConvergenceError(fmt::format("could not place particle {} of {} without overlap: lower "
                                         "dem.prepare.initial_solid_fraction ({})",
                                         k + 1, diameters.size(), config.prepare.initial_solid_fraction));
    }
  }
  h5::CellState state;
  state.lengths = lengths;
  state.reference_lengths = lengths;
  SimulationSettings settings = settings_from_config(config, diameters.back());
  settings.material.friction = config.material.friction_prepare;
  settings.material.damping_ratio = config.prepare.damping;
  settings.global_damping = config.prepare.global_damping;
  return Simulation(std::move(particles), state, settings, 0.0, 0, false, comm);
}

PreparedAssembly prepare_assembly(const DemConfig& config, const Logger& logger, const mpi::Comm& comm) {
  RandomStream sizes(config.seed, 0), placement(config.seed, 1), agitation(config.seed, 2);
  const auto& pc = config.particles;
  const auto& pr = config.prepare;
  Simulation simulation = sparse_assembly(config, sizes, placement, comm);
  simulation.watch_equilibrium(true); // the seize test reads it at every control update
  const double rate =
      strain_rate_for_inertial_number(pr.inertial_number, pc.d50, pc.density, pr.confining_pressure);
  logger->info("prepare: {} particles, cell {:.4g} x {:.4g} x {:.4g} mm, time step {:.3g} s, compaction rate "
               "{:.3g} /s",
               pc.count, 1e3 * simulation.cell().lengths()[0], 1e3 * simulation.cell().lengths()[1],
               1e3 * simulation.cell().lengths()[2], simulation.settings().time_step, rate);
  PreparedAssembly result;
  std::optional<Simulation> best;
  double best_distance = INFINITY;
  const double rms_speed = pr.agitation_speed * std::sqrt(pr.confining_pressure / pc.density);
  for (int cycle = 1; cycle <= pr.cycles; ++cycle) {
    if (cycle > 1) agitate(simulation, rms_speed, agitation);
    const std::int64_t steps =
        compact_until_seized(simulation, -rate, pr, logger, fmt::format("compaction cycle {}", cycle));
    const StateMeasures m = simulation.measure();
    result.cycle_void_ratios.push_back(m.void_ratio);
    logger->info("cycle {:2d}: seized after {} steps at e = {:.4f}, Z = {:.3f}", cycle, steps, m.void_ratio,
                 m.coordination);
    const double distance = std::abs(m.void_ratio - pr.target_void_ratio);
    if (distance < best_distance) {
      best_distance = distance;
      best = simulation;
      result.chosen_cycle = cycle;
    }
    // Each cycle packs denser (agitation then compaction), so once one seizes at or below
    // the target the later ones only move away from it: `cycles` is a maximum.
    if (m.void_ratio <= pr.target_void_ratio) {
      if (cycle < pr.cycles) logger->info("cycle {} reached the target: no further cycles", cycle);
      break;
    }
  }
  logger->info("keeping cycle {} (e = {:.4f}, target {:.4f})", result.chosen_cycle,
               result.cycle_void_ratios[static_cast<std::size_t>(result.chosen_cycle - 1)],
               pr.target_void_ratio);
  Simulation chosen = std::move(*best);
  chosen.set_friction(config.material.friction);
  // Consolidated with the damping that loading will use, so that the relaxation proves the
  // state static with it (a state verified with heavier damping can creep without it).
  chosen.set_damping(config.integration.damping);
  chosen.set_servo_max_rate(rate);
  chosen.set_global_damping(config.integration.global_damping);
  const Relaxation consolidation = consolidate(chosen, config, rate, logger);
  chosen.watch_equilibrium(false);
  result.consolidated = chosen.measure();
  logger->info("consolidation took {} steps; unbalanced-force ratio {:.2e}, kinetic/elastic {:.2e}",
               consolidation.steps, consolidation.equilibrium.unbalanced_force_ratio,
               consolidation.equilibrium.kinetic_elastic_ratio());
  logger->info(
      "consolidated to p = {:.4g} Pa: e = {:.4f}, Z = {:.3f}, Z without rattlers = {:.3f} ({} rattlers, "
      "{:.1f}%)",
      result.consolidated.mean_stress, result.consolidated.void_ratio, result.consolidated.coordination,
      result.consolidated.coordination_no_rattlers, result.consolidated.n_rattlers,
      100.0 * static_cast<double>(result.consolidated.n_rattlers) / static_cast<double>(pc.count));
  const double miss = result.consolidated.void_ratio - pr.target_void_ratio;
  const double kept = result.cycle_void_ratios[static_cast<std::size_t>(result.chosen_cycle - 1)];
  // Below the target: either the cycles were already too dense, or consolidation to p0
  // compacted a cycle that was within the tolerance (flat ovoids: by 0.005 at demo size).
  const std::string denser_hint =
      result.cycle_void_ratios.front() < pr.target_void_ratio - pr.void_ratio_tolerance
          ? std::string("the first cycle already packs denser: raise dem.material.friction_prepare")
          : fmt::format("consolidation to p0 compacted the kept cycle {} from e = {:.4f} by {:.4f}: raise "
                        "dem.prepare.target_void_ratio by about that much, so that the cycles stop "
                        "earlier, or widen dem.prepare.void_ratio_tolerance",
                        result.chosen_cycle, kept, kept - result.consolidated.void_ratio);
  if (std::abs(miss) > pr.void_ratio_tolerance) {
    throw ConvergenceError(fmt::format(
        "prepare: the assembly reached e = {:.4f}, {} the target dem.prepare.target_void_ratio = {:.4f} by "
        "more than dem.prepare.void_ratio_tolerance = {:.4f} after {} of at most {} cycles (cycle void "
        "ratios "
        "{:.4f}); {}",
        result.consolidated.void_ratio, miss > 0 ? "above" : "below", pr.target_void_ratio,
        pr.void_ratio_tolerance, result.cycle_void_ratios.size(), pr.cycles,
        fmt::join(result.cycle_void_ratios, ", "),
        miss > 0 ? "raise dem.prepare.cycles or dem.prepare.agitation_speed, or lower "
                   "dem.material.friction_prepare (docs/methods/dem.md, 'Reaching the target void ratio')"
                 : denser_hint));
  }
  result.simulation = std::move(chosen);
  result.rng_state = {sizes.state(), placement.state(), agitation.state()};
  return result;
}

} // namespace aniso::dem
