#pragma once
// The periodic voxel image, schema version 1 (contract between the voxel and LBM stages; on-disk
// layout in docs/formats/image.md). One byte per voxel, x1 fastest, 1 = solid, 0 = void. The image
// tiles space periodically with period shape * voxel_size along each axis.

#include "common/h5/provenance.hpp"
#include "common/tensor.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace aniso::h5 {

inline constexpr std::int64_t image_schema_version = 1;

struct VoxelImage {
  std::array<std::size_t, 3> shape{}; ///< voxels along x1, x2, x3 (n1, n2, n3)
  double voxel_size = 0;              ///< edge length [m]
  Vec3 origin = Vec3::Zero();         ///< world position of the corner of voxel (0,0,0) [m]
  std::vector<std::uint8_t>
      phase;               ///< n1*n2*n3 values, x1 fastest: index = i + n1*(j + n2*k); 1 solid, 0 void
  std::string source;      ///< path of the checkpoint it came from ("" for synthetic images)
  std::string source_hash; ///< content hash of that checkpoint ("" for synthetic)

  [[nodiscard]] std::size_t size() const { return shape[0] * shape[1] * shape[2]; }
  [[nodiscard]] std::size_t index(std::size_t i, std::size_t j, std::size_t k) const {
    return i + shape[0] * (j + shape[1] * k);
  }
};

/// Writes `path` (HDF5) and its XDMF sidecar (xdmf_sidecar_path(path)) atomically, each under a
/// temporary name renamed when complete. Serial: call on one rank only (rank 0).
/// InputError if the image is inconsistent (phase size, values other than 0/1, voxel size).
void write_voxel_image(const std::string& path, const VoxelImage& image, const Provenance& provenance);

/// Reads and validates an image; FileError naming the file and the problem (schema, missing
/// dataset or attribute, shape, phase values, non-finite or non-positive geometry).
VoxelImage read_voxel_image(const std::string& path);

/// "dir/name.h5" -> "dir/name.xmf" (a path without ".h5" gets ".xmf" appended).
std::string xdmf_sidecar_path(const std::string& path);

} // namespace aniso::h5
