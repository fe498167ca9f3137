#include "lbm/permeability.hpp"

#include "common/error.hpp"
#include "lbm/partition.hpp"
#include "lbm/percolation.hpp"
#include "lbm/petsc_log.hpp"
#include "lbm/throats.hpp"
#include "lbm/topology.hpp"
#include "lbm/trt.hpp"

#include <Eigen/QR>
#include <fmt/format.h>

#include <cmath>

namespace aniso::lbm {
namespace {

Index3 shape_of(const h5::VoxelImage& image) {
  Index3 shape{};
  for (std::size_t a = 0; a < 3; ++a)
    shape[a] = static_cast<int>(image.shape[a]);
  return shape;
}

} // namespace

FlowRun run_axis(const h5::VoxelImage& image, const PermeabilitySettings& settings, int axis, FaceKind walls,
                 const mpi::Comm& comm, const Logger& logger) {
  const LogEvents events = lbm_log_events();
  const Faces faces = walls == FaceKind::periodic ? all_periodic : walled_except(axis, walls);
  const std::string image_name = image.source.empty() ? "the image" : "the image of " + image.source;
  const double throat = throat_widths(image)[static_cast<std::size_t>(axis)];
  if (walls == FaceKind::periodic && throat == 0) {
    // No path crosses the cell along the axis: K is zero along it, and no flow needs running.
    logger->warn("{}: its pore space does not connect across the cell along x{} (no path of void voxels, "
                 "joined by the D3Q19 links, wraps around it): K{}{} = 0 and the x{} row and column of K "
                 "are zero. A coarse image closes throats: check voxel.resolution",
                 image_name, axis + 1, axis + 1, axis + 1, axis + 1);
    FlowRun closed{axis, walls, FlowResult{}};
    closed.percolates = false;
    closed.throat_width = 0;
    return closed;
  }
  if (throat < kResolvedThroatWidth)
    logger->warn(
        "{}: the narrowest throat along x{} is {:.1f} voxels wide, below {:g}: bounce-back resolves "
        "it coarsely and K{}{} may be off by {} (sphere arrays, docs/methods/lbm.md, where the method "
        "fails); a finer voxel.resolution widens it",
        image_name, axis + 1, throat, throat < kCoarseThroatWidth ? kCoarseThroatWidth : kResolvedThroatWidth,
        axis + 1, axis + 1, throat < kCoarseThroatWidth ? "tens of per cent" : "up to 8%");
  require_input(percolates(image, axis, faces),
                fmt::format("{}: its pore space does not connect across the cell along x{} (no path of "
                            "void voxels, joined by the D3Q19 links, wraps around it): the permeability "
                            "along x{} is zero and cannot be measured by flow. A coarse image closes "
                            "throats: check voxel.resolution",
                            image_name, axis + 1, axis + 1));
  Topology topology;
  {
    ScopedStage stage(events, events.setup);
    const Partition partition = make_partition(shape_of(image), faces, comm);
    topology = build_topology(image.phase, partition, faces, comm);
  }
  FlowSettings flow = settings.flow;
  flow.force = Vec3::Zero();
  flow.force[axis] = settings.body_force;
  flow.label = fmt::format("flow along x{} ({} side faces)", axis + 1, to_string(walls));
  FlowRun run{axis, walls, run_flow(topology, flow, comm, logger)};
  run.throat_width = throat;
  logger->info(
      "{}: converged in {} steps ({:.1f} s, {:.3g} MFLUPS), <j> = ({:.4e}, {:.4e}, {:.4e}), Mach {:.2e}, "
      "Reynolds number {:.2e}",
      flow.label, run.result.steps, run.result.seconds,
      static_cast<double>(run.result.steps) * static_cast<double>(topology.n_fluid_global) /
          run.result.seconds * 1e-6,
      run.result.mean_momentum[0], run.result.mean_momentum[1], run.result.mean_momentum[2],
      run.result.max_mach, run.result.reynolds);
  if (run.result.reynolds > kStokesReynoldsLimit)
    logger->warn(
        "{}: the Reynolds number |<j>| sqrt(K) / nu is {:.3g}, above {:.2g}: inertia biases K by about "
        "{:.2g}% (-2e-3 Re^2, docs/methods/lbm.md); lower lbm.body_force by {:.0f}x for Stokes flow",
        flow.label, run.result.reynolds, kStokesReynoldsLimit,
        -0.2 * run.result.reynolds * run.result.reynolds,
        std::ceil(run.result.reynolds / (0.2 * kStokesReynoldsLimit)));
  return run;
}

namespace {

/// The driving gradient of a run: the body force minus the pressure gradient that walls built up.
Vec3 driving(const FlowRun& run, double body_force) {
  Vec3 g = -run.result.pressure_gradient;
  g[run.axis] += body_force;
  return g;
}

} // namespace

std::string to_string(Method method) {
  return method == Method::periodic_body_force ? "periodic_body_force" : "paper_walls";
}

Mat3 solve_off_diagonal(const Vec3& diagonal, const std::vector<Vec3>& driving, const std::vector<Vec3>& flux,
                        double& relative_residual) {
  // Per run, eq. (kijsolver): rows [G2 G3 0; G1 0 G3; 0 G1 G2] (k12, k13, k23)^T = nu J - diag(K) G.
  const auto n_rows = static_cast<Eigen::Index>(3 * driving.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n_rows, 3);
  Eigen::VectorXd b(n_rows);
  for (std::size_t r = 0; r < driving.size(); ++r) {
    const Vec3& g = driving[r];
    const auto row = static_cast<Eigen::Index>(3 * r);
    a.row(row) << g[1], g[2], 0;
    a.row(row + 1) << g[0], 0, g[2];
    a.row(row + 2) << 0, g[0], g[1];
    for (Eigen::Index i = 0; i < 3; ++i)
      b[row + i] = flux[r][i] - diagonal[i] * g[i];
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
  Eigen::VectorXd rhs_scale(n_rows);
  for (std::size_t r = 0; r < driving.size(); ++r)
    for (Eigen::Index i = 0; i < 3; ++i)
      rhs_scale[static_cast<Eigen::Index>(3 * r) + i] = flux[r][i];
  relative_residual = (a * x - b).norm() / std::max(rhs_scale.norm(), 1e-300);
  Mat3 k = diagonal.asDiagonal();
  k(0, 1) = k(1, 0) = x[0];
  k(0, 2) = k(2, 0) = x[1];
  k(1, 2) = k(2, 1) = x[2];
  return k;
}

std::vector<FlowRun> run_direction(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                                   int axis, const mpi::Comm& comm, const Logger& logger) {
  require_input(axis >= 0 && axis < 3, fmt::format("flow direction {} is not 0, 1 or 2", axis));
  std::vector<FlowRun> runs;
  if (settings.method == Method::periodic_body_force) {
    runs.push_back(run_axis(image, settings, axis, FaceKind::periodic, comm, logger));
  } else {
    runs.push_back(run_axis(image, settings, axis, FaceKind::no_slip, comm, logger));
    runs.push_back(run_axis(image, settings, axis, FaceKind::free_slip, comm, logger));
  }
  return runs;
}

PermeabilityResult assemble_permeability(Method method, std::vector<FlowRun> runs,
                                         const PermeabilitySettings& settings) {
  PermeabilityResult result;
  result.method = method;
  const double nu = make_trt_rates(settings.flow.tau, settings.flow.magic).viscosity();
  const auto find = [&](int axis, FaceKind walls) -> const FlowRun& {
    for (const FlowRun& run : runs)
      if (run.axis == axis && run.walls == walls) return run;
    throw InputError(fmt::format("the {} flow along x{} is missing", to_string(walls), axis + 1));
  };
  if (method == Method::periodic_body_force) {
    for (int axis = 0; axis < 3; ++axis)
      result.k_lattice.col(axis) =
          nu * find(axis, FaceKind::periodic).result.mean_momentum / settings.body_force;
    // An axis no path crosses carries no flux whatever drives it: its row and column are zero.
    for (int axis = 0; axis < 3; ++axis)
      if (!find(axis, FaceKind::periodic).percolates) {
        result.k_lattice.row(axis).setZero();
        result.k_lattice.col(axis).setZero();
      }
    result.symmetry_error =
        (result.k_lattice - result.k_lattice.transpose()).norm() / std::max(result.k_lattice.norm(), 1e-300);
  } else {
    Vec3 diagonal = Vec3::Zero();
    std::vector<Vec3> drive, flux;
    for (int axis = 0; axis < 3; ++axis) {
      const FlowRun& walled = find(axis, FaceKind::no_slip);
      diagonal[axis] = nu * walled.result.mean_momentum[axis] / driving(walled, settings.body_force)[axis];
      const FlowRun& slip = find(axis, FaceKind::free_slip);
      drive.push_back(driving(slip, settings.body_force));
      flux.push_back(nu * slip.result.mean_momentum);
    }
    result.k_lattice = solve_off_diagonal(diagonal, drive, flux, result.inverse_residual);
  }
  // Each diagonal is a flux along the push: a non-positive one is a run that did not measure a
  // flow, never a permeability (the percolation check above makes it a bug, not an input).
  for (int axis = 0; axis < 3; ++axis)
    if (!(result.k_lattice(axis, axis) > 0) &&
        !(method == Method::periodic_body_force && !find(axis, FaceKind::periodic).percolates))
      throw NumericalError(fmt::format("K{}{} = {:.4g} (lattice units) is not positive: the flow along x{} "
                                       "carries no net flux",
                                       axis + 1, axis + 1, result.k_lattice(axis, axis), axis + 1));
  result.runs = std::move(runs);
  return result;
}

DirectionRuns run_directions(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                             const mpi::Comm& comm, const Logger& logger, const DirectionRuns& finished) {
  require_input(settings.body_force > 0, "lbm.body_force must be positive");
  DirectionRuns runs = finished;
  try {
    for (int axis = 0; axis < 3; ++axis) {
      auto& slot = runs[static_cast<std::size_t>(axis)];
      if (!slot) slot = run_direction(image, settings, axis, comm, logger);
    }
  } catch (const Interrupted& stop) {
    logger->debug("{}", stop.what()); // every rank stops at the same check; later axes stay empty
  }
  return runs;
}

std::int64_t fluid_voxels(const h5::VoxelImage& image) {
  std::size_t solid = 0;
  for (std::uint8_t v : image.phase)
    solid += v;
  return static_cast<std::int64_t>(image.size() - solid);
}

PermeabilityResult permeability_of(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                                   DirectionRuns directions) {
  std::vector<FlowRun> runs;
  std::vector<std::vector<double>> velocity;
  for (int axis = 0; axis < 3; ++axis) {
    auto& slot = directions[static_cast<std::size_t>(axis)];
    require_input(slot.has_value(), fmt::format("the flows along x{} are missing", axis + 1));
    for (FlowRun& run : *slot) {
      if (settings.flow.keep_velocity) velocity.push_back(std::move(run.result.velocity));
      run.result.velocity.clear();
      runs.push_back(std::move(run));
    }
  }
  PermeabilityResult result = assemble_permeability(settings.method, std::move(runs), settings);
  result.velocity = std::move(velocity);
  result.fluid_voxels = fluid_voxels(image);
  result.porosity = static_cast<double>(result.fluid_voxels) / static_cast<double>(image.size());
  return result;
}

PermeabilityResult compute_permeability(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                                        const mpi::Comm& comm, const Logger& logger) {
  DirectionRuns runs = run_directions(image, settings, comm, logger);
  for (int axis = 0; axis < 3; ++axis)
    if (!runs[static_cast<std::size_t>(axis)])
      throw Interrupted(fmt::format("stopped on SIGTERM before the flows along x{} were done", axis + 1));
  return permeability_of(image, settings, std::move(runs));
}

} // namespace aniso::lbm
