#pragma once
// Eigen aliases and the few symmetric-tensor helpers the paper's quantities
// need. Sign convention: stresses are stored as computed (tension positive);
// p and q below follow the paper, which reports compression as positive mean
// stress: p = -tr(sigma)/3 for a tension-positive sigma. See docs/methods/dem.md.

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <array>

namespace aniso {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Vec3i = Eigen::Vector3i;

/// Deviatoric part A - (tr A / 3) I.
Mat3 deviator(const Mat3& tensor);

/// Mean stress, compression positive: p = -tr(sigma)/3 for tension-positive sigma.
double mean_stress_compression_positive(const Mat3& sigma);

/// Deviatoric stress invariant q = sqrt(3 J2) = sqrt(3/2 s:s) (paper Fig. 3 caption), sign-free;
/// s is the deviator of the symmetric part, so q depends only on the principal stresses.
double deviatoric_q(const Mat3& sigma);

/// Eigen-decomposition of a symmetric tensor with eigenvalues sorted descending
/// and eigenvectors as the matching columns, each with a non-negative largest component
/// so that the result is unique and reproducible.
struct SortedEigen {
  Vec3 values;  ///< descending
  Mat3 vectors; ///< column k belongs to values[k]
};
SortedEigen sorted_eigen(const Mat3& symmetric);

/// The paper's anisotropy pair of a diagonal-dominant tensor:
/// (A11 - A33)/(tr A / 3) and (A22 - A33)/(tr A / 3), from the diagonal in the cell axes.
std::array<double, 2> axis_anisotropy(const Mat3& tensor);

/// Symmetric 3x3 as 6-vector in Voigt order (11, 22, 33, 23, 13, 12).
Eigen::Matrix<double, 6, 1> to_voigt(const Mat3& symmetric);
Mat3 from_voigt(const Eigen::Matrix<double, 6, 1>& voigt);

} // namespace aniso
