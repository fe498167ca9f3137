#pragma once
// The relaxation time and the driving force from the image (lbm.tau = 0 and lbm.body_force = 0, the
// defaults).
//
// tau: K does not depend on it, but the steps to a steady flow do, in opposite ways on the two
// relaxations of a start from rest (docs/charts/lbm_tau.png): the flow in a pore settles by
// viscous diffusion in about d_h^2 / nu steps, while the pressure settles over the cell by Darcy
// diffusion, D = K c_s^2 / (nu phi), in about L^2 nu phi / (K c_s^2) steps. A fixed tau = 1 suits
// neither a dilute image (tau = 5 took 6x fewer steps) nor a packing image (tau = 0.6-0.8 took
// 1.6-3x fewer). The two times balance at nu ~ d_h^2 / L (with K ~ d_h^2 phi / 80, Kozeny-Carman),
// the cheapest tau.
//
// Force: one fixed force gave Re 1.5 (K biased by -0.5%) on a dilute image and Mach numbers near
// the limit on others, while a dense packing image flowed at Re 5e-5, far below what Stokes flow
// needs. The force is chosen for a target permeability Reynolds number from a Kozeny-Carman
// estimate of K, capped by a target Mach number of the mean pore velocity.

#include "common/h5/image.hpp"
#include "common/log.hpp"
#include "lbm/permeability.hpp"

namespace aniso::lbm {

/// Kozeny-Carman estimate K = phi^3 / (5 S^2) [voxel^2], with S the solid-void surface per unit
/// volume from the voxel faces divided by 3/2 (the mean ratio of a staircase's face area to the
/// smooth surface it samples). Infinite without solid or without void.
double kozeny_carman_permeability(const h5::VoxelImage& image);

/// Hydraulic diameter d_h = 4 phi / S [voxel] of the pore space, S as in kozeny_carman_permeability.
/// Infinite without solid-void faces.
double hydraulic_diameter(const h5::VoxelImage& image);

/// The relaxation time of the runs: `settings.flow.tau` when given (> 0), else
/// tau = 1/2 + 3 nu with nu = kTauBalance min(d_h, L)^2 / L, L the cube root of the voxel count,
/// within [kAutoTauMin, kAutoTauMax]. Logged.
double resolve_tau(const h5::VoxelImage& image, const PermeabilitySettings& settings, const Logger& logger);

/// nu L / d_h^2 of the automatic tau, measured: the cheapest tau of the chart's packing images
/// (0.8 on a 64^3 packing, 0.6-0.7 on a dense 48^3 one) gives 0.08-0.11; Darcy's balance 0.13.
inline constexpr double kTauBalance = 0.1;
/// Below 0.55 the TRT K drifts by more than 4e-4 (validation) and the steps grow as 1/nu.
inline constexpr double kAutoTauMin = 0.55;
/// Above 5 no image of the chart converged faster; the error of a stopped run grows with tau.
inline constexpr double kAutoTauMax = 5.0;

/// The body force of the runs: `settings.body_force` when given (> 0), else the force that gives
/// Re = settings.target_reynolds at the estimated K, F = Re nu^2 / K^(3/2), but no more than makes
/// the mean pore velocity kTargetPoreMach of the sound speed (F = Ma c_s phi nu / K). Logged.
double resolve_body_force(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                          const Logger& logger);

/// Mean pore velocity over the sound speed that the automatic force aims below: local peaks in
/// throats run about ten times the mean, so this keeps them near Mach 0.03, a third of the limit.
inline constexpr double kTargetPoreMach = 3e-3;

} // namespace aniso::lbm
