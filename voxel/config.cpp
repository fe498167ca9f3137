#include "voxel/config.hpp"

namespace aniso::voxel {

VoxelConfig read_voxel_config(config::Reader& reader) {
  using config::Range;
  VoxelConfig c;
  c.output_dir =
      reader.text("voxel.output_dir", c.output_dir, "folder for image_<stem>.h5 and voids_<stem>.h5/.csv");
  c.resolution =
      reader.real("voxel.resolution", c.resolution, "voxel/d50", Range::closed(2, 200),
                  "voxels per median diameter d50 (paper: 20; see docs/charts/voxel_resolution.png)");
  c.radius_step = reader.real("voxel.radius_step", c.radius_step, "voxel", Range::closed(0, 10),
                              "step between the ball and disk radii of successive openings; 0 = every "
                              "distinct digital ball and disk (sqrt of every sum of 3 or 2 squares)");
  c.threads = static_cast<int>(reader.integer("voxel.threads", c.threads, Range::closed(0, 1024),
                                              "OpenMP threads per rank (0: OMP_NUM_THREADS or all cores)"));
  c.write_image =
      reader.boolean("voxel.write_image", c.write_image, "write the voxel image and its XDMF sidecar");
  return c;
}

} // namespace aniso::voxel
