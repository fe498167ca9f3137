// Periodic cell: minimum image, wrapping and strain against hand-computed values,
// and a brute-force check of the minimum image over neighbouring images.
#include "common/cell.hpp"
#include "common/error.hpp"
#include "common/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using aniso::PeriodicCell;
using aniso::Vec3;

TEST(PeriodicCell, StrainFromLengths) {
  PeriodicCell cell(Vec3(1.5, 1.0, 1.0));
  cell.set_lengths(Vec3(0.6, 1.0, 2.0));
  EXPECT_NEAR(cell.engineering_strain()[0], -0.6, 1e-15);
  EXPECT_EQ(cell.engineering_strain()[1], 0.0);
  EXPECT_NEAR(cell.engineering_strain()[2], 1.0, 1e-15);
  EXPECT_NEAR(cell.logarithmic_strain()[0], std::log(0.4), 1e-15);
  EXPECT_NEAR(cell.volume(), 1.2, 1e-15);
}

TEST(PeriodicCell, WrapIntoCell) {
  const PeriodicCell cell(Vec3(2.0, 3.0, 4.0));
  const Vec3 wrapped = cell.wrap(Vec3(-0.5, 7.0, 4.0));
  EXPECT_DOUBLE_EQ(wrapped[0], 1.5);
  EXPECT_DOUBLE_EQ(wrapped[1], 1.0);
  EXPECT_DOUBLE_EQ(wrapped[2], 0.0);
  const Vec3 tiny_negative = cell.wrap(Vec3(-1e-18, 0, 0));
  EXPECT_GE(tiny_negative[0], 0.0);
  EXPECT_LT(tiny_negative[0], 2.0);
}

TEST(PeriodicCell, MinimumImageIsShortestOfAllImages) {
  const PeriodicCell cell(Vec3(0.3, 1.0, 2.7)); // strongly deformed proportions
  aniso::RandomStream stream(4, 0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 a(stream.uniform(0, 0.3), stream.uniform(0, 1.0), stream.uniform(0, 2.7));
    const Vec3 b(stream.uniform(0, 0.3), stream.uniform(0, 1.0), stream.uniform(0, 2.7));
    const Vec3 image = cell.minimum_image(b - a);
    double best = INFINITY;
    for (int i = -2; i <= 2; ++i)
      for (int j = -2; j <= 2; ++j)
        for (int k = -2; k <= 2; ++k)
          best = std::min(best, (b - a + Vec3(i * 0.3, j * 1.0, k * 2.7)).norm());
    ASSERT_NEAR(image.norm(), best, 1e-14);
    const auto shift = cell.image_shift(b - a);
    ASSERT_NEAR((b - a + shift.cast<double>().cwiseProduct(cell.lengths()) - image).norm(), 0.0, 1e-14);
  }
}

TEST(PeriodicCell, RejectsNonPositiveLengths) {
  EXPECT_THROW(PeriodicCell(Vec3(1.0, 0.0, 1.0)), aniso::InputError);
  PeriodicCell cell(Vec3(1, 1, 1));
  EXPECT_THROW(cell.set_lengths(Vec3(1, 1, std::nan(""))), aniso::InputError);
}

} // namespace
