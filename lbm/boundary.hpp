#pragma once
// What lies beyond each face of the image box. The periodic body-force method
// treats every axis as periodic; the paper's method (section 6) closes the
// four faces parallel to the flow with no-slip or free-slip walls. Walls sit
// halfway between the last voxel layer and its (absent) periodic image.

#include <array>
#include <string>

namespace aniso::lbm {

enum class FaceKind {
  periodic,  ///< the image tiles space along this axis
  no_slip,   ///< halfway bounce-back wall: zero velocity at the face
  free_slip, ///< specular reflection wall: zero normal velocity, no tangential stress
};

/// One kind per axis (both faces of an axis are alike).
using Faces = std::array<FaceKind, 3>;

inline constexpr Faces all_periodic{FaceKind::periodic, FaceKind::periodic, FaceKind::periodic};

/// Periodic along `flow_axis`, `walls` on the two other axes.
inline Faces walled_except(int flow_axis, FaceKind walls) {
  Faces faces{walls, walls, walls};
  faces[static_cast<std::size_t>(flow_axis)] = FaceKind::periodic;
  return faces;
}

inline std::string to_string(FaceKind kind) {
  switch (kind) {
  case FaceKind::periodic: return "periodic";
  case FaceKind::no_slip: return "no-slip";
  case FaceKind::free_slip: return "free-slip";
  }
  return "?";
}

} // namespace aniso::lbm
