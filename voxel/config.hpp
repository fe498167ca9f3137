#pragma once
// The [voxel] configuration section (docs/methods/voxel.md lists every key).

#include "common/config.hpp"

#include <string>

namespace aniso::voxel {

struct VoxelConfig {
  std::string output_dir = ".";
  double resolution = 20;  ///< voxels per d50 (the paper: 20)
  double radius_step = 0;  ///< ball and disk radii step [voxels]; 0 = every distinct digital element
  int threads = 0;         ///< OpenMP threads per rank; 0 = OMP_NUM_THREADS or all cores
  bool write_image = true; ///< write image_<stem>.h5 + .xmf (the LBM stage reads it)
};

VoxelConfig read_voxel_config(config::Reader& reader);

} // namespace aniso::voxel
