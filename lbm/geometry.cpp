#include "lbm/geometry.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace aniso::lbm {
namespace {

h5::VoxelImage empty_image(const Index3& shape) {
  h5::VoxelImage image;
  for (std::size_t a = 0; a < 3; ++a)
    image.shape[a] = static_cast<std::size_t>(shape[a]);
  image.voxel_size = 1.0;
  image.phase.assign(image.size(), 0);
  return image;
}

/// Marks voxels whose centre is within `radius` of `centre`, with periodic images.
void add_sphere(h5::VoxelImage& image, const Vec3& centre, double radius) {
  const double r2 = radius * radius;
  const int reach = static_cast<int>(std::ceil(radius)) + 1;
  std::array<int, 3> n{};
  for (std::size_t a = 0; a < 3; ++a)
    n[a] = static_cast<int>(image.shape[a]);
  const auto base = [&](int a) { return static_cast<int>(std::floor(centre[a])); };
  for (int dk = -reach; dk <= reach; ++dk)
    for (int dj = -reach; dj <= reach; ++dj)
      for (int di = -reach; di <= reach; ++di) {
        const int i = base(0) + di, j = base(1) + dj, k = base(2) + dk;
        const Vec3 d = Vec3(i + 0.5, j + 0.5, k + 0.5) - centre;
        if (d.squaredNorm() > r2) continue;
        const auto wrap = [](int v, int m) { return static_cast<std::size_t>(((v % m) + m) % m); };
        image.phase[image.index(wrap(i, n[0]), wrap(j, n[1]), wrap(k, n[2]))] = 1;
      }
}

} // namespace

h5::VoxelImage plane_channel(int width, int length, int normal_axis) {
  require_input(width >= 1 && length >= 1 && normal_axis >= 0 && normal_axis < 3, "bad channel geometry");
  Index3 shape{length, length, length};
  shape[static_cast<std::size_t>(normal_axis)] = width + 1;
  h5::VoxelImage image = empty_image(shape);
  for (std::size_t k = 0; k < image.shape[2]; ++k)
    for (std::size_t j = 0; j < image.shape[1]; ++j)
      for (std::size_t i = 0; i < image.shape[0]; ++i) {
        const std::array<std::size_t, 3> x{i, j, k};
        if (x[static_cast<std::size_t>(normal_axis)] == 0) image.phase[image.index(i, j, k)] = 1;
      }
  return image;
}

h5::VoxelImage square_duct(int width, int length, int axis) {
  require_input(width >= 1 && length >= 1 && axis >= 0 && axis < 3, "bad duct geometry");
  Index3 shape{width + 1, width + 1, width + 1};
  shape[static_cast<std::size_t>(axis)] = length;
  h5::VoxelImage image = empty_image(shape);
  for (std::size_t k = 0; k < image.shape[2]; ++k)
    for (std::size_t j = 0; j < image.shape[1]; ++j)
      for (std::size_t i = 0; i < image.shape[0]; ++i) {
        const std::array<std::size_t, 3> x{i, j, k};
        bool wall = false;
        for (std::size_t a = 0; a < 3; ++a)
          wall = wall || (static_cast<int>(a) != axis && x[a] == 0);
        if (wall) image.phase[image.index(i, j, k)] = 1;
      }
  return image;
}

h5::VoxelImage sphere_array(int side, double radius) {
  require_input(side >= 2 && radius > 0 && 2 * radius <= side * std::sqrt(2.0), "bad sphere array geometry");
  h5::VoxelImage image = empty_image({side, side, side});
  add_sphere(image, Vec3::Constant(0.5 * side), radius);
  return image;
}

h5::VoxelImage sphere_array_matching(int side, double phi) {
  const double nominal = sphere_radius_for_solid_fraction(side, phi);
  double low = 0.5 * nominal, high = std::min(1.5 * nominal, 0.5 * side * std::sqrt(2.0));
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double mid = 0.5 * (low + high);
    (solid_fraction(sphere_array(side, mid)) < phi ? low : high) = mid;
  }
  // The voxel count is a step function of the radius: take the closer of the two sides.
  h5::VoxelImage below = sphere_array(side, low), above = sphere_array(side, high);
  return std::abs(solid_fraction(below) - phi) <= std::abs(solid_fraction(above) - phi) ? below : above;
}

double sphere_radius_for_solid_fraction(int side, double phi) {
  return side * std::cbrt(3.0 * phi / (4.0 * std::numbers::pi));
}

h5::VoxelImage random_spheres(const Index3& shape, double radius, double phi, std::uint64_t seed) {
  require_input(phi > 0 && phi < 0.9 && radius > 0, "bad random sphere packing");
  h5::VoxelImage image = empty_image(shape);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Add spheres in batches until the voxel solid fraction reaches phi.
  while (solid_fraction(image) < phi)
    for (int k = 0; k < 16; ++k)
      add_sphere(image, Vec3(unit(rng) * shape[0], unit(rng) * shape[1], unit(rng) * shape[2]), radius);
  return image;
}

double solid_fraction(const h5::VoxelImage& image) {
  std::size_t solid = 0;
  for (std::uint8_t v : image.phase)
    solid += v;
  return static_cast<double>(solid) / static_cast<double>(image.size());
}

} // namespace aniso::lbm
