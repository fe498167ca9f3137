#pragma once
// Results of other stages that `aniso-fabric series` correlates with fabric (formats agreed in
// docs/formats/: probe, permeability, voids). Each is linked to its checkpoint by content hash.

#include "common/tensor.hpp"

#include <string>

namespace aniso::fabric {

/// probe_<stem>.h5: /stiffness/C [3, 3] and attribute K_C [Pa], source_hash of the checkpoint.
struct ProbeStiffness {
  std::string path;
  std::string checkpoint_hash;
  Mat3 C = Mat3::Zero();     ///< [Pa]
  double K_C = 0;            ///< [Pa]
  bool checks_passed = true; ///< the probe's own linearity/noise checks (attribute checks_passed, if present)
};
ProbeStiffness read_probe_stiffness(const std::string& path);

/// permeability_<image stem>.h5: /permeability/K [3, 3] [m^2] with attributes source and
/// source_hash. aniso-lbm records the checkpoint there (the image's own source); when `source` is
/// instead a voxel image, the checkpoint is the one its /image/phase attribute source_hash names.
struct Permeability {
  std::string path;
  std::string checkpoint_hash;
  Mat3 K = Mat3::Zero(); ///< [m^2]
};
Permeability read_permeability(const std::string& path);

/// voids_<stem>.h5: /voids/free_path_median [3] and breadth_median [3] [m] (L^v_ii and R^v_ii).
struct VoidMedians {
  std::string path;
  std::string checkpoint_hash;
  Vec3 free_path = Vec3::Zero(); ///< [m]
  Vec3 breadth = Vec3::Zero();   ///< [m]
};
VoidMedians read_void_medians(const std::string& path);

} // namespace aniso::fabric
