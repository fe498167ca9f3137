#include "voxel/digitize.hpp"

#include "common/error.hpp"
#include "common/shape/ovoid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>

namespace aniso::voxel {
namespace {

// Index range of voxel centres (i + 1/2) e within [low, high], unwrapped (may leave [0, n)).
std::pair<std::int64_t, std::int64_t> centre_range(double low, double high, double edge) {
  return {static_cast<std::int64_t>(std::ceil(low / edge - 0.5)),
          static_cast<std::int64_t>(std::floor(high / edge - 0.5))};
}

std::size_t wrap(std::int64_t index, std::size_t n) {
  const auto size = static_cast<std::int64_t>(n);
  const std::int64_t r = index % size;
  return static_cast<std::size_t>(r < 0 ? r + size : r);
}

} // namespace

std::array<std::size_t, 3> grid_shape(const Vec3& lengths, double d50, double resolution) {
  require_input(d50 > 0 && std::isfinite(d50), fmt::format("voxel: d50 {} m is not a positive length", d50));
  const double h = d50 / resolution;
  std::array<std::size_t, 3> shape{};
  for (int a = 0; a < 3; ++a)
    shape[static_cast<std::size_t>(a)] = static_cast<std::size_t>(std::max(1.0, std::round(lengths[a] / h)));
  return shape;
}

std::vector<std::uint8_t> digitize_bodies(std::span<const Body> bodies, const Vec3& lengths,
                                          const std::array<std::size_t, 3>& shape, double splice_angle) {
  const auto [n0, n1, n2] = shape;
  const Vec3 edge(lengths[0] / static_cast<double>(n0), lengths[1] / static_cast<double>(n1),
                  lengths[2] / static_cast<double>(n2));
  std::vector<std::uint8_t> phase(n0 * n1 * n2, 0);
  // Shapes are built (and validated: OvoidShape throws on a bad splice angle) before the parallel
  // loop, which must not throw.
  std::vector<std::optional<OvoidShape>> ovoids(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].aspect_ratio == 1.0) continue;
    try {
      ovoids[b].emplace(bodies[b].diameter, bodies[b].aspect_ratio, splice_angle);
    } catch (const InputError& error) {
      throw InputError(fmt::format("particle {}: {}", b, error.what()));
    }
  }
  const auto count = static_cast<std::int64_t>(bodies.size());
  // Bodies may overlap (contacts): two threads may both set a voxel to 1, hence atomic stores.
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t b = 0; b < count; ++b) {
    const Body& body = bodies[static_cast<std::size_t>(b)];
    const double radius = 0.5 * body.diameter; // bounds the oblate ovoid too (half-height <= D/2)
    const std::optional<OvoidShape>& ovoid = ovoids[static_cast<std::size_t>(b)];
    const bool sphere = !ovoid.has_value();
    const Mat3 to_body = body.orientation.conjugate().toRotationMatrix();
    std::array<std::pair<std::int64_t, std::int64_t>, 3> range;
    for (int a = 0; a < 3; ++a)
      range[static_cast<std::size_t>(a)] =
          centre_range(body.position[a] - radius, body.position[a] + radius, edge[a]);
    for (std::int64_t k = range[2].first; k <= range[2].second; ++k) {
      const double dz = (static_cast<double>(k) + 0.5) * edge[2] - body.position[2];
      for (std::int64_t j = range[1].first; j <= range[1].second; ++j) {
        const double dy = (static_cast<double>(j) + 0.5) * edge[1] - body.position[1];
        const double dyz2 = dy * dy + dz * dz;
        if (dyz2 > radius * radius) continue;
        const std::size_t row = n0 * (wrap(j, n1) + n1 * wrap(k, n2));
        for (std::int64_t i = range[0].first; i <= range[0].second; ++i) {
          const double dx = (static_cast<double>(i) + 0.5) * edge[0] - body.position[0];
          if (dx * dx + dyz2 > radius * radius) continue;
          if (!sphere && !ovoid->inside(to_body * Vec3(dx, dy, dz))) continue;
          std::atomic_ref<std::uint8_t>(phase[row + wrap(i, n0)]).store(1, std::memory_order_relaxed);
        }
      }
    }
  }
  return phase;
}

std::vector<Body> bodies_of(const h5::Checkpoint& checkpoint) {
  const auto& particles = checkpoint.particles;
  std::vector<Body> bodies(particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p)
    bodies[p] = Body{particles.position[p], particles.diameter[p], particles.aspect_ratio[p],
                     particles.orientation[p].normalized()};
  return bodies;
}

std::optional<double> find_parameter(const h5::Checkpoint& checkpoint, const std::string& name) {
  for (const auto& parameter : checkpoint.parameters)
    if (parameter.name == name) return parameter.value;
  return std::nullopt;
}

h5::VoxelImage digitize_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path,
                                   const std::string& hash, double resolution) {
  const double d50 = h5::parameter(checkpoint, h5::parameter_name::d50, path);
  const double splice =
      find_parameter(checkpoint, h5::parameter_name::splice_angle).value_or(OvoidShape::default_splice_angle);
  const Vec3& lengths = checkpoint.cell.lengths;
  h5::VoxelImage image;
  image.shape = grid_shape(lengths, d50, resolution);
  const std::vector<Body> bodies = bodies_of(checkpoint);
  try {
    image.phase = digitize_bodies(bodies, lengths, image.shape, splice);
  } catch (const InputError& error) {
    throw FileError(
        fmt::format("{}: {} (ovoid_splice_angle {} rad{})", path, error.what(), splice,
                    find_parameter(checkpoint, h5::parameter_name::splice_angle) ? "" : ", the default"));
  }
  const double cells = static_cast<double>(image.shape[0] * image.shape[1] * image.shape[2]);
  image.voxel_size = std::cbrt(lengths.prod() / cells);
  image.origin = Vec3::Zero();
  image.source = path;
  image.source_hash = hash;
  return image;
}

} // namespace aniso::voxel
