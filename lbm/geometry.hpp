#pragma once
// Analytic test geometries as voxel images (1 = solid): plane channel, square
// duct, simple cubic sphere array, random sphere packing. They validate the
// solver against exact or published permeabilities and feed the benchmarks.

#include "common/h5/image.hpp"
#include "lbm/partition.hpp"

#include <cstdint>

namespace aniso::lbm {

/// Fluid gap of `width` voxels between solid plates normal to `normal_axis` (one solid layer, so the
/// periodic image has one plate per period). Shape: width + 1 across, `length` along the others.
h5::VoxelImage plane_channel(int width, int length, int normal_axis);

/// Square duct of `width` x `width` fluid voxels along `axis`, one solid layer around it.
h5::VoxelImage square_duct(int width, int length, int axis);

/// One sphere of `radius` voxels (centre at the cube's centre) in a periodic cube of `side` voxels:
/// the simple cubic array of Zick & Homsy. A voxel is solid if its centre lies inside the sphere.
h5::VoxelImage sphere_array(int side, double radius);

/// The sphere array whose voxelized solid fraction is closest to `phi` (the radius is adjusted by
/// bisection, so the voxel solid volume matches the continuous one of Zick & Homsy's cell).
h5::VoxelImage sphere_array_matching(int side, double phi);

/// Sphere radius giving solid fraction `phi` in a cube of `side` (continuous, before voxelization).
double sphere_radius_for_solid_fraction(int side, double phi);

/// Random overlapping spheres of `radius` voxels placed until the solid fraction reaches `phi`
/// (periodic, seeded): a stand-in packing for benchmarks.
h5::VoxelImage random_spheres(const Index3& shape, double radius, double phi, std::uint64_t seed);

/// Solid fraction of an image.
double solid_fraction(const h5::VoxelImage& image);

} // namespace aniso::lbm
