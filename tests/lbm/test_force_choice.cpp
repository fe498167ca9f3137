// The automatic body force and relaxation time (lbm/force_choice.hpp): the Kozeny-Carman estimate
// against exact channel permeabilities, a given force or tau kept, the Reynolds and pore-Mach bounds,
// and the tau that balances the pore and cell relaxations.
#include "common/log.hpp"
#include "lbm/force_choice.hpp"
#include "lbm/geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aniso::lbm {
namespace {

TEST(ForceChoice, KozenyCarmanWithinAFactorOfThreeOfAChannel) {
  // Plane channel of width w in a period of w + 1: superficial K = phi w^2 / 12 along the plates.
  for (int width : {4, 8, 16}) {
    const double porosity = width / (width + 1.0);
    const double exact = porosity * width * width / 12.0;
    const double estimate = kozeny_carman_permeability(plane_channel(width, 8, 2));
    EXPECT_GT(estimate / exact, 1.0 / 3.0) << "width " << width;
    EXPECT_LT(estimate / exact, 3.0) << "width " << width;
  }
}

TEST(ForceChoice, AGivenForceIsKept) {
  PermeabilitySettings settings;
  settings.body_force = 3e-6;
  EXPECT_EQ(resolve_body_force(plane_channel(8, 8, 2), settings, make_silent_logger()), 3e-6);
}

TEST(ForceChoice, BoundsOfTheAutomaticForce) {
  PermeabilitySettings settings;
  settings.body_force = 0;
  const double nu = settings.flow.viscosity();
  const double cs = 1.0 / std::sqrt(3.0);
  // A dense random packing: the pore-Mach bound, far above the old fixed 1e-5.
  const h5::VoxelImage dense = random_spheres({32, 32, 32}, 4.0, 0.6, 1);
  const double k = kozeny_carman_permeability(dense);
  const double force = resolve_body_force(dense, settings, make_silent_logger());
  double porosity = 0;
  for (const auto v : dense.phase)
    porosity += v == 0 ? 1.0 : 0.0;
  porosity /= static_cast<double>(dense.size());
  EXPECT_NEAR(k * force / (nu * porosity) / cs, kTargetPoreMach, 1e-12);
  EXPECT_GT(force, 1e-5);
  EXPECT_LE(std::pow(k, 1.5) * force / (nu * nu), settings.target_reynolds * (1 + 1e-12));
  // A dilute array: the Reynolds bound, Re at the estimate equal to the target.
  const h5::VoxelImage dilute = sphere_array_matching(32, 0.02);
  const double k_dilute = kozeny_carman_permeability(dilute);
  const double f_dilute = resolve_body_force(dilute, settings, make_silent_logger());
  EXPECT_NEAR(std::pow(k_dilute, 1.5) * f_dilute / (nu * nu), settings.target_reynolds, 1e-12);
}

TEST(TauChoice, AGivenTauIsKept) {
  PermeabilitySettings settings;
  settings.flow.tau = 0.9;
  EXPECT_EQ(resolve_tau(plane_channel(8, 8, 2), settings, make_silent_logger()), 0.9);
}

TEST(TauChoice, HydraulicDiameterOfAChannel) {
  // Plates of width w in a period of w + 1: 4 phi / S with S = 2 faces / 1.5 per period.
  const double d = hydraulic_diameter(plane_channel(8, 8, 2));
  EXPECT_NEAR(d, 4.0 * (8.0 / 9.0) / (2.0 / 1.5 / 9.0), 1e-12);
}

TEST(TauChoice, TheAutomaticTauFollowsThePoreToCellRatio) {
  PermeabilitySettings settings;
  settings.flow.tau = 0;
  const Logger silent = make_silent_logger();
  // nu = 0.1 d_h^2 / L on a packing image: tau below 1, where the chart's packings converged fastest.
  const h5::VoxelImage packing = random_spheres({48, 48, 48}, 5.0, 0.6, 7);
  const double d = hydraulic_diameter(packing);
  const double tau = resolve_tau(packing, settings, silent);
  EXPECT_NEAR(tau, 0.5 + 3.0 * kTauBalance * d * d / 48.0, 1e-12);
  EXPECT_GT(tau, 0.6);
  EXPECT_LT(tau, 1.0);
  // The same pores in a cell twice as wide: the pressure settles over a longer distance, so a smaller tau.
  const double wide = resolve_tau(random_spheres({96, 96, 96}, 5.0, 0.6, 7), settings, silent);
  EXPECT_LT(wide, tau);
  EXPECT_GE(wide, kAutoTauMin);
  // A dilute array: pores as wide as the cell, the upper bound.
  EXPECT_EQ(resolve_tau(sphere_array_matching(26, 0.125), settings, silent), kAutoTauMax);
}

} // namespace
} // namespace aniso::lbm
