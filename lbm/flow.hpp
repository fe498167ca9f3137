#pragma once
// Runs one steady Stokes flow to convergence on a rank's topology: the time
// loop, the convergence criterion and the divergence checks.
//
// Convergence: every `check_interval` steps the mean momentum J (superficial,
// over all voxels) is reduced exactly, as the mean of two consecutive steps (a
// node whose every link along the force ends in solid flips its momentum every
// step and never damps; the mean removes it); the run has converged when
// |J(t) - J(t - check_interval)| <= tolerance |J(t)| (StopCriterion::change) or the
// error left in J that the changes estimate is (StopCriterion::error, lbm/convergence.hpp).
// The result's fields are the same two-step means.
// Divergence: non-finite populations, a Mach number max|u|/c_s above
// max_mach, or a drift of the mean density above mass_drift stop the run
// with NumericalError naming the cause and the remedy. Reaching max_steps
// first is a ConvergenceError. In neither case is a result returned.
// SIGTERM: once any rank has received it (stop_requested, polled at every check), every rank
// throws Interrupted at the same check.

#include "common/log.hpp"
#include "common/mpi.hpp"
#include "common/tensor.hpp"
#include "lbm/convergence.hpp"
#include "lbm/step_kernels.hpp"
#include "lbm/topology.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::lbm {

enum class Precision { float32, float64 };

struct FlowSettings {
  double tau = 1.0;          ///< relaxation time of the symmetric moments (viscosity (tau - 1/2) / 3)
  double magic = 3.0 / 16.0; ///< TRT magic parameter Lambda
  Vec3 force = Vec3::Zero(); ///< body force density on the fluid [lattice units]
  Precision precision = Precision::float64;
  InstructionSet instruction_set = InstructionSet::automatic; ///< of the step (same bits at every level)
  StopCriterion criterion = StopCriterion::change;
  double tolerance = 1e-6;           ///< on the relative change of J per check, or its estimated error
  std::int64_t check_interval = 100; ///< steps between checks
  std::int64_t max_steps = 200000;
  double max_mach = 0.1;
  double mass_drift = 1e-6;   ///< limit on |mean delta rho| drift
  bool keep_velocity = false; ///< gather the velocity field on rank 0 at the end
  bool fixed_steps = false;   ///< benchmarks: run exactly max_steps steps, no convergence test
  std::string label = "flow"; ///< names the run in messages

  [[nodiscard]] double viscosity() const { return (tau - 0.5) / 3.0; }
};

struct FlowResult {
  Vec3 mean_momentum = Vec3::Zero();     ///< sum of j over fluid nodes / all voxels [lattice]
  Vec3 pressure_gradient = Vec3::Zero(); ///< mean dp/dx along wall-bounded axes (0 along periodic ones)
  std::int64_t steps = 0;
  double relative_change = 0;
  double estimated_error = 0; ///< relative error of J left at the stop (infinite: no steady decay seen)
  double max_mach = 0;
  /// Permeability Reynolds number |<j>| sqrt(K) / nu with K = nu |<j>| / |F| (Darcy velocity and
  /// sqrt(K) as length): inertia biases K by about -2e-3 Re^2 (docs/methods/lbm.md).
  double reynolds = 0;
  double mass_drift = 0;
  double seconds = 0;
  std::vector<double> velocity; ///< rank 0, keep_velocity only: u per voxel, 3 values, x1 fastest, 0 in solid
};

/// Runs to convergence (collective). Throws NumericalError / ConvergenceError as described above.
FlowResult run_flow(const Topology& topology, const FlowSettings& settings, const mpi::Comm& comm,
                    const Logger& logger);

} // namespace aniso::lbm
