#pragma once
// The effective permeability tensor of a voxel image (paper section 6,
// eq. (permeability)): k_ij = -mu <v_i> / p_,j, i.e. in lattice units with a
// body force density F standing for the pressure gradient, k_ij = nu <j_i> / F_j
// with <j> the superficial momentum (mean over all voxels, solid included).
//
// Two methods:
//  - periodic_body_force: fully periodic image, force along x_j gives column j;
//    three runs give the whole tensor, whose asymmetry measures the error.
//  - paper_walls (the paper's procedure): along each axis, a driving gradient
//    with no-slip walls on the four side faces gives k_ii; then free-slip side
//    walls, on which transverse pressure gradients build up, and the inverse
//    problem of eqs. (kij1)-(kijsolver) give k_12, k_13, k_23. The driving
//    pressure drop is applied as the equivalent body force with the flow axis
//    periodic (identical for incompressible Stokes flow, and free of inlet
//    artefacts on a periodic image).

#include "common/h5/image.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "common/tensor.hpp"
#include "lbm/flow.hpp"

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace aniso::lbm {

enum class Method { periodic_body_force, paper_walls };
std::string to_string(Method method);

struct PermeabilitySettings {
  Method method = Method::periodic_body_force;
  FlowSettings flow;             ///< force is set per run from body_force
  double body_force = 1e-5;      ///< magnitude of the driving force density [lattice]; 0: from the image
  double target_reynolds = 0.05; ///< the automatic force's permeability Reynolds number (force_choice.hpp)
};

struct FlowRun {
  int axis = 0; ///< direction of the driving force
  FaceKind walls = FaceKind::periodic;
  FlowResult result;
  /// False: no path of void voxels crosses the cell along `axis` (periodic method), so no flow was
  /// run and K is zero along it.
  bool percolates = true;
  /// The narrowest throat along `axis`, in voxels (throat_widths; NaN: not recorded).
  double throat_width = std::numeric_limits<double>::quiet_NaN();
};

/// Throat widths (voxels) below which the periodic method's K strays, measured on simple cubic
/// sphere arrays against Zick & Homsy (docs/charts/lbm_throat_error.png, docs/methods/lbm.md,
/// "Where the method fails"): below kResolvedThroatWidth errors reach 8% (beyond the 2% of a
/// resolved flow), below kCoarseThroatWidth from -45% to +65%. A warning names the width, the
/// axis and the band.
inline constexpr double kResolvedThroatWidth = 17.0;
inline constexpr double kCoarseThroatWidth = 6.0;

/// Above this permeability Reynolds number (FlowResult::reynolds) inertia biases K by more than
/// about 0.05% (-2e-3 Re^2, measured on a dilute sphere array): a warning names the run.
inline constexpr double kStokesReynoldsLimit = 0.5;

struct PermeabilityResult {
  Method method = Method::periodic_body_force;
  Mat3 k_lattice = Mat3::Zero(); ///< [voxel^2]
  double symmetry_error = 0;     ///< periodic: |K - K^T| / |K| (Frobenius)
  double inverse_residual = 0;   ///< paper: relative residual of the least-squares inverse problem
  double porosity = 0;
  std::int64_t fluid_voxels = 0;
  std::vector<FlowRun> runs;
  std::vector<std::vector<double>> velocity; ///< rank 0, keep_velocity only: one field per run
};

/// The flow runs along one axis: one periodic run, or (paper method) the no-slip and the free-slip run.
std::vector<FlowRun> run_direction(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                                   int axis, const mpi::Comm& comm, const Logger& logger);

/// The tensor of `method` from the runs of all three axes, in any order (InputError if one is missing).
/// Shared by compute_permeability and `aniso-lbm collect`; porosity and velocity are left to the caller.
PermeabilityResult assemble_permeability(Method method, std::vector<FlowRun> runs,
                                         const PermeabilitySettings& settings);

/// The runs of each axis (run_direction), empty where not (yet) done.
using DirectionRuns = std::array<std::optional<std::vector<FlowRun>>, 3>;

/// Runs the directions that `finished` lacks and returns them with the finished ones (collective;
/// identical image on every rank; PETSc initialized). Once any rank has received SIGTERM (polled at
/// each convergence check) the direction in progress is dropped and no other started: the
/// directions not done stay empty.
DirectionRuns run_directions(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                             const mpi::Comm& comm, const Logger& logger, const DirectionRuns& finished = {});

/// The tensor of all three directions' runs, with the image's porosity and (keep_velocity) the
/// runs' velocity fields; InputError if a direction is missing.
PermeabilityResult permeability_of(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                                   DirectionRuns runs);

/// Void voxels of the image.
std::int64_t fluid_voxels(const h5::VoxelImage& image);

/// Runs the method's flows on the image (collective; identical image on every rank; PETSc
/// initialized); Interrupted on SIGTERM.
PermeabilityResult compute_permeability(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                                        const mpi::Comm& comm, const Logger& logger);

/// One flow with the force along `axis` and `walls` on the side faces (periodic: none).
FlowRun run_axis(const h5::VoxelImage& image, const PermeabilitySettings& settings, int axis, FaceKind walls,
                 const mpi::Comm& comm, const Logger& logger);

/// Solves eq. (kijsolver) in the least-squares sense over several runs: nu J = K G with the diagonal of K
/// known, for the off-diagonal (k12, k13, k23). Returns K and writes the relative residual.
Mat3 solve_off_diagonal(const Vec3& diagonal, const std::vector<Vec3>& driving, const std::vector<Vec3>& flux,
                        double& relative_residual);

} // namespace aniso::lbm
