#include "common/tensor.hpp"

#include "common/error.hpp"

#include <cmath>

namespace aniso {

Mat3 deviator(const Mat3& tensor) {
  return tensor - (tensor.trace() / 3.0) * Mat3::Identity();
}

double mean_stress_compression_positive(const Mat3& sigma) {
  return -sigma.trace() / 3.0;
}

double deviatoric_q(const Mat3& sigma) {
  // J2 is defined from the principal stresses (paper Fig. 3 caption), i.e. of the symmetric part:
  // the skew part of a contact-sum stress of non-spherical particles is not a stress.
  const Mat3 s = deviator(0.5 * (sigma + sigma.transpose()));
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}

SortedEigen sorted_eigen(const Mat3& symmetric) {
  const Mat3 sym = 0.5 * (symmetric + symmetric.transpose());
  Eigen::SelfAdjointEigenSolver<Mat3> solver(sym);
  if (solver.info() != Eigen::Success)
    throw NumericalError("eigen-decomposition of a symmetric tensor failed");
  SortedEigen result;
  // Eigen returns ascending order.
  for (int k = 0; k < 3; ++k) {
    result.values[k] = solver.eigenvalues()[2 - k];
    Vec3 vector = solver.eigenvectors().col(2 - k);
    Eigen::Index largest = 0;
    vector.cwiseAbs().maxCoeff(&largest);
    if (vector[largest] < 0) vector = -vector;
    result.vectors.col(k) = vector;
  }
  return result;
}

std::array<double, 2> axis_anisotropy(const Mat3& tensor) {
  const double mean = tensor.trace() / 3.0;
  if (mean == 0.0) throw NumericalError("anisotropy of a tensor with zero trace is undefined");
  return {(tensor(0, 0) - tensor(2, 2)) / mean, (tensor(1, 1) - tensor(2, 2)) / mean};
}

Eigen::Matrix<double, 6, 1> to_voigt(const Mat3& symmetric) {
  Eigen::Matrix<double, 6, 1> voigt;
  voigt << symmetric(0, 0), symmetric(1, 1), symmetric(2, 2), symmetric(1, 2), symmetric(0, 2),
      symmetric(0, 1);
  return voigt;
}

Mat3 from_voigt(const Eigen::Matrix<double, 6, 1>& voigt) {
  Mat3 tensor;
  tensor << voigt[0], voigt[5], voigt[4], voigt[5], voigt[1], voigt[3], voigt[4], voigt[3], voigt[2];
  return tensor;
}

} // namespace aniso
