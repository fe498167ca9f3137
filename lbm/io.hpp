#pragma once
// Permeability results file, permeability_<image stem>.h5 (docs/formats/permeability.md), and the optional
// velocity fields, velocity_<image stem>.h5 with an XDMF sidecar for ParaView. Both written atomically by
// rank 0.

#include "common/h5/image.hpp"
#include "common/h5/provenance.hpp"
#include "lbm/permeability.hpp"

#include <string>

namespace aniso::lbm {

/// Version 2 made /runs/reynolds, throat_width and percolates required (version 1 files may lack them).
inline constexpr std::int64_t permeability_schema_version = 2;

/// "dir/name.h5" -> "<output_dir>/<prefix>_name.h5".
std::string result_path(const std::string& output_dir, const std::string& prefix,
                        const std::string& image_path);

/// Writes the permeability tensor in m^2 and lattice units with the run details. Serial (rank 0).
void write_permeability(const std::string& path, const PermeabilityResult& result,
                        const h5::VoxelImage& image, const PermeabilitySettings& settings,
                        const h5::Provenance& provenance);

/// What a reader of a permeability file gets (validated).
struct PermeabilityFile {
  Mat3 k = Mat3::Zero();         ///< [m^2]
  Mat3 k_lattice = Mat3::Zero(); ///< [voxel^2]
  std::string method;
  std::string source;
  std::string source_hash;
  double voxel_size = 0;
};

/// Reads and validates a permeability file; FileError naming the file and the problem.
PermeabilityFile read_permeability(const std::string& path);

/// The runs of one flow direction (`aniso-lbm --direction D`), collected later by `aniso-lbm collect`.
struct DirectionFile {
  int axis = 0;
  Method method = Method::periodic_body_force;
  PermeabilitySettings settings; ///< tau, magic, body_force, precision, tolerance as run
  std::vector<FlowRun> runs;
  h5::VoxelImage image; ///< metadata only (no phase): shape, voxel_size, source, source_hash
  double porosity = 0;
  std::int64_t fluid_voxels = 0;
  std::string image_hash; ///< content hash of the image file itself ("" in files written before it)
};

/// "<output_dir>/permeability_<stem>_direction<D>.h5".
std::string direction_path(const std::string& output_dir, const std::string& image_path, int axis);

/// Writes the runs of one direction of the image whose file has content hash `image_hash`. Serial (rank 0).
void write_direction(const std::string& path, const std::vector<FlowRun>& runs, int axis,
                     const h5::VoxelImage& image, const std::string& image_hash,
                     const PermeabilitySettings& settings, const h5::Provenance& provenance);

/// Reads and validates a direction file; FileError naming the file and the problem.
DirectionFile read_direction(const std::string& path);

/// Writes one velocity field per run [n3, n2, n1, 3] in lattice units and its XDMF sidecar. Serial (rank 0).
void write_velocity(const std::string& path, const PermeabilityResult& result, const h5::VoxelImage& image,
                    const h5::Provenance& provenance);

} // namespace aniso::lbm
