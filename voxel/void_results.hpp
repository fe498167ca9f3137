#pragma once
// voids_<checkpoint stem>.h5 and .csv: the void analysis of one image (layout in
// docs/formats/voids.md). Written atomically, serially (rank 0).

#include "common/h5/provenance.hpp"
#include "common/tensor.hpp"
#include "voxel/void_analysis.hpp"

#include <string>

namespace aniso::voxel {

/// What the numbers refer to: the image and the checkpoint it came from.
struct VoidContext {
  std::string source;              ///< checkpoint path
  std::string source_hash;         ///< its content hash
  std::string image;               ///< path of the voxel image written beside the results
  double d50 = 0;                  ///< [m]
  double resolution = 0;           ///< voxels per d50 asked for
  Vec3 voxel_edges = Vec3::Zero(); ///< e_a = L_a / n_a [m]
  std::array<std::size_t, 3> shape{};
  std::int64_t n_particles = 0;
  std::int64_t n_contacts = 0;
};

/// Counted Euler characteristics of the assembly (paper eq. (Chis1)): 1 + N_p - N_c for a body in
/// R^3, and N_p - N_c for the void of a periodic assembly on the 3-torus (chi(T^3) = 0).
std::int64_t counted_euler_bounded(const VoidContext& context);
std::int64_t counted_euler_torus(const VoidContext& context);

void write_void_results(const std::string& h5_path, const std::string& csv_path, const VoidAnalysis& analysis,
                        const VoidContext& context, const h5::Provenance& provenance);

} // namespace aniso::voxel
