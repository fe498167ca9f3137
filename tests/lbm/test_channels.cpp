// Plane Poiseuille and square-duct flow against their analytic permeabilities
// (shared/reference/permeability.md): error below 0.5% at 16 to 32 cells across.
#include "common/log.hpp"
#include "lbm/geometry.hpp"
#include "lbm/permeability.hpp"
#include "tests/lbm/petsc_environment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

namespace aniso::lbm {
namespace {

/// k of a square duct of side a: (a^2/12) [1 - (192/pi^5) sum_{n odd} tanh(n pi/2)/n^5].
double duct_permeability(double side) {
  double sum = 0;
  for (int n = 1; n < 200; n += 2)
    sum += std::tanh(n * std::numbers::pi / 2) / std::pow(n, 5);
  return side * side / 12.0 * (1.0 - 192.0 / std::pow(std::numbers::pi, 5) * sum);
}

PermeabilitySettings channel_settings() {
  PermeabilitySettings settings;
  settings.body_force = 1e-6;
  settings.flow.tolerance = 1e-8;
  settings.flow.check_interval = 50;
  return settings;
}

/// k along one axis from one periodic run (the superficial flux is over the fluid gap only, so rescale).
double axis_permeability(const h5::VoxelImage& image, int axis, const PermeabilitySettings& settings) {
  const FlowRun run =
      run_axis(image, settings, axis, FaceKind::periodic, mpi::Comm::world(), make_silent_logger());
  const double porosity = 1.0 - solid_fraction(image);
  const double nu = (settings.flow.tau - 0.5) / 3.0;
  return nu * run.result.mean_momentum[axis] / settings.body_force / porosity;
}

TEST(Channels, PlanePoiseuilleIsExactWithMagicTrt) {
  for (int width : {16, 32}) {
    const h5::VoxelImage image = plane_channel(width, 4, 2);
    const double k = axis_permeability(image, 0, channel_settings());
    const double error = k / (width * width / 12.0) - 1.0;
    std::cout << "plane Poiseuille, " << width << " cells: relative error " << error << "\n";
    EXPECT_LT(std::abs(error), 5e-3) << "width " << width;
  }
}

TEST(Channels, SquareDuctWithinHalfPercent) {
  for (int width : {16, 24}) {
    const h5::VoxelImage image = square_duct(width, 4, 0);
    const double k = axis_permeability(image, 0, channel_settings());
    const double error = k / duct_permeability(width) - 1.0;
    std::cout << "square duct, " << width << " cells: relative error " << error << "\n";
    EXPECT_LT(std::abs(error), 5e-3) << "width " << width;
  }
}

} // namespace
} // namespace aniso::lbm
