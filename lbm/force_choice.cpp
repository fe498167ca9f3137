#include "lbm/force_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace aniso::lbm {

double kozeny_carman_permeability(const h5::VoxelImage& image) {
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
  if (faces == 0) return std::numeric_limits<double>::infinity();
  const auto volume = static_cast<double>(image.size());
  const double porosity = static_cast<double>(void_voxels) / volume;
  const double surface = static_cast<double>(faces) / 1.5 / volume;
  return porosity * porosity * porosity / (5.0 * surface * surface);
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
