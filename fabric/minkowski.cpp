#include "fabric/minkowski.hpp"

#include <array>

namespace aniso::fabric {

Mat3 corners_w320(std::span<const Corner> corners) {
  Mat3 sum = Mat3::Zero();
  for (const Corner& corner : corners)
    sum += (corner.deficit / 3.0) * corner.position * corner.position.transpose();
  return sum;
}

Mat3 box_w320(const Vec3& lengths) {
  std::array<Corner, 8> corners;
  for (int k = 0; k < 8; ++k) {
    const Vec3 sign((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
    corners[static_cast<std::size_t>(k)] = {0.5 * sign.cwiseProduct(lengths), std::numbers::pi / 2.0};
  }
  return corners_w320(corners);
}

} // namespace aniso::fabric
