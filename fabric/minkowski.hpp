#pragma once
// The Minkowski tensor W_3^{2,0} (paper eqs. (W202), (blocka), (W320), (MinkNormal)).

#include "common/tensor.hpp"

#include <numbers>
#include <span>

namespace aniso::fabric {

/// W_3 of a convex body without holes (4 pi / 3, Gauss-Bonnet) and of a contact bridge (-4 pi / 3).
inline constexpr double w3_body = 4.0 * std::numbers::pi / 3.0;

/// A corner of a polyhedron: its position and Descartes angular deficit [rad].
struct Corner {
  Vec3 position;
  double deficit;
};

/// W_3^{2,0} of a polyhedron from its corners: sum of (deficit / 3) x (x) x (eq. (blocka)).
Mat3 corners_w320(std::span<const Corner> corners);

/// W_3^{2,0} of the boundary of a box of the given edge lengths centred at the origin: its eight
/// square corners (deficit pi/2) at (+-L1/2, +-L2/2, +-L3/2) (eq. (blocka) with a_i = L_i / 2).
Mat3 box_w320(const Vec3& lengths);

/// A particle's term in eq. (W320): its local tensor (1/3) integral K x (x) x dA about its
/// centre plus W_3 t (x) t for the centre t relative to the assembly's centre (eq. (W203all);
/// the local Minkowski vector vanishes for centrally symmetric particles).
inline Mat3 particle_w320(const Mat3& local, const Vec3& centre) {
  return local + w3_body * centre * centre.transpose();
}

/// A contact bridge's term in eq. (W320): -(4 pi / 3) x (x) x at the contact point.
inline Mat3 contact_w320(const Vec3& point) {
  return -w3_body * point * point.transpose();
}

/// Eq. (MinkNormal): (W_3^{2,0} of the boundaries)^{-1} . W_3^{2,0} of the assembly.
inline Mat3 normalized_w320(const Mat3& boundary, const Mat3& assembly) {
  return boundary.inverse() * assembly;
}

} // namespace aniso::fabric
