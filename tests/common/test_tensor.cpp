// Tensor helpers against hand-computed values.
#include "common/tensor.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using aniso::Mat3;
using aniso::Vec3;

TEST(Tensor, MeanStressAndQOfTriaxialState) {
  // Tension-positive stress: compression 300, 100, 100 kPa.
  Mat3 sigma = Mat3::Zero();
  sigma.diagonal() << -300e3, -100e3, -100e3;
  EXPECT_DOUBLE_EQ(aniso::mean_stress_compression_positive(sigma), 500e3 / 3);
  EXPECT_NEAR(aniso::deviatoric_q(sigma), 200e3, 1e-9); // q = sigma1 - sigma3 for triaxial states
  EXPECT_NEAR(aniso::deviator(sigma).trace(), 0.0, 1e-9);
}

TEST(Tensor, QMatchesPaperJ2Definition) {
  Mat3 sigma = Mat3::Zero();
  sigma.diagonal() << 5.0, 2.0, -1.0;
  const double j2 = (std::pow(5 - 2, 2) + std::pow(5 + 1, 2) + std::pow(2 + 1, 2)) / 6.0;
  EXPECT_NEAR(aniso::deviatoric_q(sigma), std::sqrt(3 * j2), 1e-14);
}

TEST(Tensor, QOfANonSymmetricStressUsesItsPrincipalStresses) {
  // A contact-sum stress of ovoids has a skew part; q must come from the principal stresses of
  // the symmetric part (paper Fig. 3 caption), so the skew part must not change it.
  Mat3 symmetric;
  symmetric << -150, 20, 5, 20, -90, -8, 5, -8, -60;
  Mat3 skew;
  skew << 0, 30, -12, -30, 0, 7, 12, -7, 0;
  const auto principal = aniso::sorted_eigen(symmetric).values;
  const double j2 = (std::pow(principal[0] - principal[1], 2) + std::pow(principal[0] - principal[2], 2) +
                     std::pow(principal[1] - principal[2], 2)) /
                    6.0;
  EXPECT_NEAR(aniso::deviatoric_q(symmetric + skew), std::sqrt(3 * j2), 1e-12);
}

TEST(Tensor, SortedEigenOfRotatedDiagonal) {
  const Mat3 rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Mat3 diagonal = Mat3::Zero();
  diagonal.diagonal() << 1.0, 3.0, 2.0;
  const auto eigen = aniso::sorted_eigen(rotation * diagonal * rotation.transpose());
  EXPECT_NEAR(eigen.values[0], 3.0, 1e-14);
  EXPECT_NEAR(eigen.values[1], 2.0, 1e-14);
  EXPECT_NEAR(eigen.values[2], 1.0, 1e-14);
  // Column 0 is the rotated e2 up to sign; the sign rule makes the largest component positive.
  const Vec3 expected = rotation.col(1);
  EXPECT_NEAR(std::abs(eigen.vectors.col(0).dot(expected)), 1.0, 1e-12);
  Eigen::Index largest = 0;
  eigen.vectors.col(0).cwiseAbs().maxCoeff(&largest);
  EXPECT_GT(eigen.vectors(largest, 0), 0.0);
}

TEST(Tensor, AxisAnisotropyAndVoigt) {
  Mat3 a = Mat3::Zero();
  a.diagonal() << 1.2, 1.0, 0.8;
  const auto anisotropy = aniso::axis_anisotropy(a);
  EXPECT_NEAR(anisotropy[0], 0.4, 1e-15);
  EXPECT_NEAR(anisotropy[1], 0.2, 1e-15);
  Mat3 sym;
  sym << 1, 6, 5, 6, 2, 4, 5, 4, 3;
  const auto voigt = aniso::to_voigt(sym);
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(voigt[i], i + 1.0);
  EXPECT_EQ(aniso::from_voigt(voigt), sym);
}

} // namespace
