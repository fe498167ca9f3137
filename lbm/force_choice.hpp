#pragma once
// The driving force from the image (lbm.body_force = 0, the default): one fixed force gave Re 1.5
// (K biased by -0.5%) on a dilute image and Mach numbers near the limit on others, while a dense
// packing image flowed at Re 5e-5, far below what Stokes flow needs. The force is chosen for a
// target permeability Reynolds number from a Kozeny-Carman estimate of K, capped by a target
// Mach number of the mean pore velocity.

#include "common/h5/image.hpp"
#include "common/log.hpp"
#include "lbm/permeability.hpp"

namespace aniso::lbm {

/// Kozeny-Carman estimate K = phi^3 / (5 S^2) [voxel^2], with S the solid-void surface per unit
/// volume from the voxel faces divided by 3/2 (the mean ratio of a staircase's face area to the
/// smooth surface it samples). Infinite without solid or without void.
double kozeny_carman_permeability(const h5::VoxelImage& image);

/// The body force of the runs: `settings.body_force` when given (> 0), else the force that gives
/// Re = settings.target_reynolds at the estimated K, F = Re nu^2 / K^(3/2), but no more than makes
/// the mean pore velocity kTargetPoreMach of the sound speed (F = Ma c_s phi nu / K). Logged.
double resolve_body_force(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                          const Logger& logger);

/// Mean pore velocity over the sound speed that the automatic force aims below: local peaks in
/// throats run about ten times the mean, so this keeps them near Mach 0.03, a third of the limit.
inline constexpr double kTargetPoreMach = 3e-3;

} // namespace aniso::lbm
