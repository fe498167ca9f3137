#pragma once
// Digitization of a periodic particle assembly (paper section 3: "each average particle was
// covered by a 20x20x20 grid"): voxel (i, j, k) is solid when its centre lies inside a particle or
// inside one of the particle's periodic images (closed bodies: a centre on the surface is solid).
// Spheres take a distance test; ovoids use OvoidShape::inside() in the body frame, reached with the
// inverse of the body-to-world orientation.
//
// The grid has n_a = round(L_a / h) voxels along axis a, h = d50 / resolution, so that the image
// is exactly periodic; the voxel edge along axis a is then e_a = L_a / n_a, within 1/(2 n_a) of h.
// The image stores one voxel size, the geometric mean of the e_a (docs/methods/voxel.md).

#include "common/h5/checkpoint.hpp"
#include "common/h5/image.hpp"
#include "common/tensor.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace aniso::voxel {

/// What digitization needs to know of one particle.
struct Body {
  Vec3 position = Vec3::Zero();        ///< centre [m], any periodic image
  double diameter = 0;                 ///< mid-plane diameter [m]
  double aspect_ratio = 1;             ///< 1 = sphere
  Quat orientation = Quat::Identity(); ///< body to world
};

/// Voxel counts for a cell of `lengths` at `resolution` voxels per d50 (at least 1 per axis).
std::array<std::size_t, 3> grid_shape(const Vec3& lengths, double d50, double resolution);

/// Solid (1) / void (0) voxels of the bodies in the periodic cell [0, L1) x [0, L2) x [0, L3)
/// on a grid of `shape` voxels. `splice_angle` is the ovoids' beta (OvoidShape).
std::vector<std::uint8_t> digitize_bodies(std::span<const Body> bodies, const Vec3& lengths,
                                          const std::array<std::size_t, 3>& shape, double splice_angle);

/// The checkpoint's particles as bodies.
std::vector<Body> bodies_of(const h5::Checkpoint& checkpoint);

/// The checkpoint digitized at `resolution` voxels per d50 (its /parameters d50), with its
/// ovoid_splice_angle (default OvoidShape::default_splice_angle when absent). `path` and `hash`
/// are recorded as the image's source.
h5::VoxelImage digitize_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path,
                                   const std::string& hash, double resolution);

/// Value of an optional /parameters entry.
std::optional<double> find_parameter(const h5::Checkpoint& checkpoint, const std::string& name);

} // namespace aniso::voxel
