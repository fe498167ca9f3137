#include "lbm/force_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace aniso::lbm {

namespace {

/// Porosity and specific surface [1/voxel] (voxel faces / 1.5, see kozeny_carman_permeability).
struct PoreSpace {
  double porosity = 0;
  double surface = 0;
};

PoreSpace measure_pore_space(const h5::VoxelImage& image) {
  const std::array<std::size_t, 3> n = image.shape;
  std::int64_t void_voxels = 0, faces = 0;
  for (std::size_t k = 0; k < n[2]; ++k)
    for (std::size_t j = 0; j < n[1]; ++j)
      for (std::size_t i = 0; i < n[0]; ++i) {
        const std::uint8_t here = image.phase[image.index(i, j, k)];
        void_voxels += here == 0 ? 1 : 0;
        // Each face once: towards the next voxel along every axis, periodically.
        faces += here != image.phase[image.index((i + 1) % n[0], j, k)] ? 1 : 0;
        faces += here != image.phase[image.index(i, (j + 1) % n[1], k)] ? 1 : 0;
        faces += here != image.phase[image.index(i, j, (k + 1) % n[2])] ? 1 : 0;
      }
  const auto volume = static_cast<double>(image.size());
  return {static_cast<double>(void_voxels) / volume, static_cast<double>(faces) / 1.5 / volume};
}

} // namespace

double kozeny_carman_permeability(const h5::VoxelImage& image) {
  const PoreSpace pores = measure_pore_space(image);
  if (pores.surface == 0) return std::numeric_limits<double>::infinity();
  return pores.porosity * pores.porosity * pores.porosity / (5.0 * pores.surface * pores.surface);
}

double hydraulic_diameter(const h5::VoxelImage& image) {
  const PoreSpace pores = measure_pore_space(image);
  if (pores.surface == 0) return std::numeric_limits<double>::infinity();
  return 4.0 * pores.porosity / pores.surface;
}

double resolve_tau(const h5::VoxelImage& image, const PermeabilitySettings& settings, const Logger& logger) {
  if (settings.flow.tau > 0) return settings.flow.tau;
  const double length = std::cbrt(static_cast<double>(image.size()));
  // A pore cannot be wider than the cell it repeats in (dilute images: d_h exceeds L).
  const double pore = std::min(hydraulic_diameter(image), length);
  const double nu = kTauBalance * pore * pore / length;
  const double tau = std::clamp(0.5 + 3.0 * nu, kAutoTauMin, kAutoTauMax);
  logger->info(
      "lbm.tau = 0 (automatic): pore hydraulic diameter {:.3g} voxels in a cell of {:.3g} voxels; tau "
      "{:.3g} (balances viscous settling in the pores against pressure settling over the cell)",
      pore, length, tau);
  return tau;
}

double resolve_body_force(const h5::VoxelImage& image, const PermeabilitySettings& settings,
                          const Logger& logger) {
  if (settings.body_force > 0) return settings.body_force;
  const double k = kozeny_carman_permeability(image);
  const double nu = settings.flow.viscosity();
  const auto void_voxels = static_cast<double>(std::count(image.phase.begin(), image.phase.end(), 0));
  const double porosity = void_voxels / static_cast<double>(image.size());
  if (!std::isfinite(k) || !(k > 0)) {
    constexpr double fallback = 1e-5; // no solid or no void: the flow stage refuses or reports it
    logger->info("lbm.body_force = 0 (automatic): no Kozeny-Carman estimate for this image, force {:g}",
                 fallback);
    return fallback;
  }
  const double sound_speed = 1.0 / std::sqrt(3.0);
  const double for_reynolds = settings.target_reynolds * nu * nu / std::pow(k, 1.5);
  const double for_mach = kTargetPoreMach * sound_speed * porosity * nu / k;
  const double force = std::min({for_reynolds, for_mach, 1e-1});
  logger->info("lbm.body_force = 0 (automatic): Kozeny-Carman K = {:.3g} voxel^2 at porosity {:.3f}; force "
               "{:.3g} ({} bound: Re {:.2g} at the estimate)",
               k, porosity, force, for_reynolds <= for_mach ? "Reynolds" : "pore Mach",
               std::pow(k, 1.5) * force / (nu * nu));
  return force;
}

} // namespace aniso::lbm
