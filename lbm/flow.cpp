#include "lbm/flow.hpp"

#include "common/error.hpp"
#include "common/exact_sum.hpp"
#include "common/stop_request.hpp"
#include "lbm/halo.hpp"
#include "lbm/petsc_log.hpp"
#include "lbm/trt.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace aniso::lbm {
namespace {

/// Exact global totals of the node moments.
struct Totals {
  double delta_rho = 0;
  Vec3 momentum = Vec3::Zero();
  double max_speed = 0;
  bool finite = true;
};

Totals reduce_moments(const std::vector<MomentsRecord>& moments, const mpi::Comm& comm) {
  std::vector<ExactSum> sums(4);
  double max_u2 = 0;
  for (const MomentsRecord& m : moments) {
    sums[0].add(m.delta_rho);
    double u2 = 0;
    for (std::size_t a = 0; a < 3; ++a) {
      sums[a + 1].add(m.momentum[a]);
      u2 += m.momentum[a] * m.momentum[a];
    }
    // NaN compares false: fold it into the maximum explicitly.
    const double rho = 1.0 + m.delta_rho;
    const double speed2 = u2 / (rho * rho);
    max_u2 = std::isnan(speed2) ? speed2 : std::max(max_u2, speed2);
  }
  const std::vector<ExactSum> global = comm.sum_exact(std::span<const ExactSum>(sums));
  Totals totals;
  totals.delta_rho = global[0].value();
  for (std::size_t a = 0; a < 3; ++a)
    totals.momentum[static_cast<Eigen::Index>(a)] = global[a + 1].value();
  const bool local_nan = std::isnan(max_u2);
  totals.max_speed = std::sqrt(comm.max(local_nan ? 0.0 : max_u2));
  totals.finite = !comm.any(local_nan) && std::isfinite(totals.delta_rho) && totals.momentum.allFinite();
  return totals;
}

/// Least-squares slope of the plane-averaged pressure c_s^2 delta rho along each wall-bounded axis.
Vec3 pressure_gradient(const Topology& topology, const std::vector<MomentsRecord>& moments,
                       const mpi::Comm& comm) {
  Vec3 gradient = Vec3::Zero();
  const Index3& shape = topology.partition.global_shape;
  for (std::size_t a = 0; a < 3; ++a) {
    if (topology.faces[a] == FaceKind::periodic) continue;
    const auto n_planes = static_cast<std::size_t>(shape[a]);
    std::vector<ExactSum> plane_rho(n_planes);
    std::vector<std::int64_t> plane_count(n_planes, 0);
    for (std::size_t node = 0; node < moments.size(); ++node) {
      std::int64_t cell = topology.fluid_cell[node];
      for (std::size_t b = 0; b < a; ++b)
        cell /= shape[b];
      const auto plane = static_cast<std::size_t>(cell % shape[a]);
      plane_rho[plane].add(moments[node].delta_rho);
      ++plane_count[plane];
    }
    const std::vector<ExactSum> rho = comm.sum_exact(std::span<const ExactSum>(plane_rho));
    const std::vector<std::int64_t> count = comm.sum(std::span<const std::int64_t>(plane_count));
    double s_x = 0, s_y = 0, s_xx = 0, s_xy = 0, s_n = 0;
    for (std::size_t p = 0; p < n_planes; ++p) {
      if (count[p] == 0) continue;
      const double x = static_cast<double>(p);
      const double y = d3q19::cs2 * rho[p].value() / static_cast<double>(count[p]);
      s_n += 1;
      s_x += x;
      s_y += y;
      s_xx += x * x;
      s_xy += x * y;
    }
    const double denominator = s_n * s_xx - s_x * s_x;
    if (s_n >= 2 && denominator > 0)
      gradient[static_cast<Eigen::Index>(a)] = (s_n * s_xy - s_x * s_y) / denominator;
  }
  return gradient;
}

std::vector<double> gather_velocity(const Topology& topology, const std::vector<MomentsRecord>& moments,
                                    const mpi::Comm& comm) {
  std::vector<double> local;
  local.reserve(4 * moments.size());
  for (std::size_t node = 0; node < moments.size(); ++node) {
    const double rho = 1.0 + moments[node].delta_rho;
    local.push_back(static_cast<double>(topology.fluid_cell[node]));
    for (double j : moments[node].momentum)
      local.push_back(j / rho);
  }
  const std::vector<std::int64_t> counts64 = comm.all_gather(static_cast<std::int64_t>(local.size()));
  std::vector<int> counts, displacements;
  int total = 0;
  for (std::int64_t c : counts64) {
    counts.push_back(static_cast<int>(c));
    displacements.push_back(total);
    total += static_cast<int>(c);
  }
  std::vector<double> all(comm.is_root() ? static_cast<std::size_t>(total) : 0);
  MPI_Gatherv(local.data(), static_cast<int>(local.size()), MPI_DOUBLE, all.data(), counts.data(),
              displacements.data(), MPI_DOUBLE, 0, comm.raw());
  std::vector<double> velocity;
  if (!comm.is_root()) return velocity;
  velocity.assign(3 * static_cast<std::size_t>(topology.n_voxels_global), 0.0);
  for (std::size_t k = 0; k + 3 < all.size(); k += 4) {
    const auto cell = static_cast<std::size_t>(all[k]);
    for (std::size_t a = 0; a < 3; ++a)
      velocity[3 * cell + a] = all[k + 1 + a];
  }
  return velocity;
}

double permeability_reynolds(double flux, double force, double viscosity) {
  if (!(force > 0)) return 0;
  return flux * std::sqrt(viscosity * flux / force) / viscosity;
}

/// A flux below this fraction of the run's largest one has decayed: no steady flow exists.
constexpr double kDecayedFraction = 1e-3;

/// moments = (moments + before) / 2, node by node: the two-step mean of the fields.
void average_into(std::vector<MomentsRecord>& moments, const std::vector<MomentsRecord>& before) {
  for (std::size_t node = 0; node < moments.size(); ++node) {
    moments[node].delta_rho = 0.5 * (moments[node].delta_rho + before[node].delta_rho);
    for (std::size_t a = 0; a < 3; ++a)
      moments[node].momentum[a] = 0.5 * (moments[node].momentum[a] + before[node].momentum[a]);
  }
}

void check_divergence(const Totals& totals, double mach, double drift, std::int64_t step,
                      const FlowSettings& s) {
  const std::string where = fmt::format("{}: step {}", s.label, step);
  if (!totals.finite)
    throw NumericalError(
        fmt::format("{}: the flow diverged (non-finite populations). The collision is unstable: "
                    "raise lbm.tau away from 0.5 or lower lbm.body_force",
                    where));
  if (mach > s.max_mach)
    throw NumericalError(
        fmt::format("{}: the Mach number max|u|/c_s reached {:.3g}, above the limit {:.3g} "
                    "(lbm.divergence.max_mach): the flow is no longer Stokes flow and is "
                    "heading for instability. Lower lbm.body_force (velocity scales with it) "
                    "or raise lbm.tau",
                    where, mach, s.max_mach));
  if (drift > s.mass_drift)
    throw NumericalError(
        fmt::format("{}: the mean density drifted by {:.3g}, above the limit {:.3g} "
                    "(lbm.divergence.mass_drift): mass is not conserved, the run is unstable "
                    "or round-off dominates. Lower lbm.body_force, raise lbm.tau, or use "
                    "lbm.precision = \"double\"",
                    where, drift, s.mass_drift));
}

template <class Real>
FlowResult run_typed(const Topology& topology, const FlowSettings& s, const mpi::Comm& comm,
                     const Logger& logger) {
  const LogEvents events = lbm_log_events();
  ScopedStage stage(events, events.time_loop);
  const auto start = std::chrono::steady_clock::now();
  const TrtRates rates = make_trt_rates(s.tau, s.magic);
  const InstructionSet level = resolve_instruction_set(s.instruction_set);
  const StepKernel<Real> step_only = step_kernels(level).template step<Real>(false);
  const StepKernel<Real> measured_step = step_kernels(level).template step<Real>(true);
  logger->info("{}: the step runs at the {} instruction-set level (lbm.instruction_set)", s.label,
               instruction_set_name(level));
  const std::array<Real, 3> force{Real(s.force[0]), Real(s.force[1]), Real(s.force[2])};
  // Rest state, delta rho = 0, u = 0: all shifted populations are zero, so the array is in the layout of
  // either kind of step. One array, updated in place (lbm/topology.hpp).
  std::vector<Real> f(topology.array_size(), Real(0));
  // Each check measures two consecutive steps (moments_before, then moments) and uses their mean:
  // at a node where every link with a component along the force ends in solid, the force's
  // momentum bounces back every step and never damps (+-F/2 in turn), so one step alone would
  // count -F/2 per such node and make K depend on tau. The two-step mean is zero there
  // and leaves steady flow elsewhere unchanged.
  std::vector<MomentsRecord> moments(static_cast<std::size_t>(topology.n_fluid));
  std::vector<MomentsRecord> moments_before(moments.size());
  Totals totals_before;
  HaloExchange<Real> halo(topology, comm);
  const auto n_voxels = static_cast<double>(topology.n_voxels_global);
  const auto n_fluid = static_cast<double>(topology.n_fluid_global);

  FlowResult result;
  // Progress in decades of what the tolerance is compared with (the estimated error, or the
  // change until a steady decay gives an estimate): the flux converges about exponentially, so
  // decades come at a steady pace and the ETA holds (the LBM printed nothing for minutes).
  const double decades_to_go = -std::log10(s.tolerance);
  Progress progress(logger, s.label, decades_to_go, 30.0);
  ConvergenceTest convergence(s.criterion, s.tolerance);
  Vec3 previous = Vec3::Zero();
  bool have_previous = false;
  double peak = 0; // largest |<j>| of the run's checks
  std::int64_t peak_step = 0;
  for (std::int64_t step = 1;; ++step) {
    // Step 1 is even: it reads each node's own slots. Odd steps stream across rank boundaries through
    // the ghost slots: filled before, given back after.
    const Parity parity = step % 2 == 1 ? Parity::even : Parity::odd;
    if (parity == Parity::odd) {
      ScopedEvent event(events, events.halo);
      halo.fill(f);
    }
    const bool check = step % s.check_interval == 0;
    const bool before_check = (step + 1) % s.check_interval == 0;
    const bool measure = check || before_check;
    {
      ScopedEvent event(events, events.stream_collide);
      (measure ? measured_step
               : step_only)(parity, f.data(), topology.slot.data(), topology.n_fluid, topology.stride, force,
                            Real(rates.omega_plus), Real(rates.omega_minus),
                            measure ? (check ? moments.data() : moments_before.data()) : nullptr);
    }
    if (parity == Parity::odd) {
      ScopedEvent event(events, events.halo);
      halo.give_back(f);
    }
    if (!measure) continue;
    ScopedEvent event(events, events.monitor);
    const Totals totals = reduce_moments(check ? moments : moments_before, comm);
    const double mach = totals.max_speed / std::sqrt(d3q19::cs2);
    const double drift = std::abs(totals.delta_rho) / n_fluid;
    check_divergence(totals, mach, drift, step, s);
    if (!check) {
      totals_before = totals;
      continue;
    }
    const Vec3 mean = 0.5 * (totals.momentum + totals_before.momentum) / n_voxels;
    const double change = (mean - previous).norm() / std::max(mean.norm(), 1e-300);
    previous = mean;
    if (mean.norm() > peak) {
      peak = mean.norm();
      peak_step = step;
    }
    // The change is relative to <j>, so a flux that decays to round-off changes by the same
    // fraction forever and never converged (it ran to lbm.max_steps). A steady flow from rest
    // never falls far below its largest value: one that does carries no flow.
    if (!s.fixed_steps && mean.norm() < kDecayedFraction * peak)
      throw ConvergenceError(fmt::format(
          "{}: step {}: the mean flux has decayed to {:.3g} of its largest value (step {}): the force "
          "drives no steady flow, so no permeability can be measured along it (the pore space carries "
          "no flow along the force between the faces of the cell, or walls cut its paths)",
          s.label, step, mean.norm() / peak, peak_step));
    logger->debug("{}: step {}: <j> = ({:.6e}, {:.6e}, {:.6e}), relative change {:.3e}, Mach {:.3e}", s.label,
                  step, mean[0], mean[1], mean[2], change, mach);
    const bool converged = have_previous && convergence.converged_after(change) && !s.fixed_steps;
    const double towards = std::isfinite(convergence.measure()) ? convergence.measure() : change;
    if (have_previous && !s.fixed_steps &&
        progress.update(std::clamp(-std::log10(std::max(towards, 1e-300)), 0.0, decades_to_go)))
      logger->info("{}: step {}, <j> changes by {:.2e} per {} steps, error left {:.1e} ({} criterion, "
                   "converged at {:.1e})",
                   s.label, step, change, s.check_interval, convergence.estimated_error(),
                   stop_criterion_name(s.criterion), s.tolerance);
    have_previous = true;
    if (converged || step + s.check_interval > s.max_steps) {
      if (!converged && !s.fixed_steps)
        throw ConvergenceError(fmt::format(
            "{}: not converged after {} steps (lbm.max_steps): the mean velocity still changes by {:.3g} per "
            "{} steps (estimated error left {:.3g}), above lbm.convergence.tolerance = {:.3g} on the {}. "
            "Raise lbm.max_steps or loosen the tolerance; a pore space that does not percolate along the "
            "force never converges",
            s.label, step, change, s.check_interval, convergence.estimated_error(), s.tolerance,
            s.criterion == StopCriterion::error ? "estimated error" : "change"));
      result.mean_momentum = mean;
      result.steps = step;
      result.relative_change = change;
      result.estimated_error = convergence.estimated_error();
      result.max_mach = mach;
      result.reynolds = permeability_reynolds(mean.norm(), s.force.norm(), s.viscosity());
      result.mass_drift = drift;
      average_into(moments, moments_before);
      result.pressure_gradient = pressure_gradient(topology, moments, comm);
      if (s.keep_velocity) result.velocity = gather_velocity(topology, moments, comm);
      break;
    }
    // SLURM's SIGTERM before a time limit: every rank drops the run at the same check.
    if (stop_requested(comm))
      throw Interrupted(fmt::format("{}: stopped on SIGTERM at step {}", s.label, step));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace

FlowResult run_flow(const Topology& topology, const FlowSettings& settings, const mpi::Comm& comm,
                    const Logger& logger) {
  require_input(settings.tau > 0.5, fmt::format("lbm.tau = {} must be above 1/2", settings.tau));
  require_input(settings.check_interval >= 2,
                "lbm.convergence.check_interval must be at least 2 (each check averages two steps)");
  return settings.precision == Precision::float32 ? run_typed<float>(topology, settings, comm, logger)
                                                  : run_typed<double>(topology, settings, comm, logger);
}

} // namespace aniso::lbm
