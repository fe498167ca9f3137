// Particle ids in Morton order of bins (dem/data/spatial_order.hpp): a permutation, the Z-curve on a
// known grid, and neighbours in id close in space.
#include "common/rng.hpp"
#include "dem/data/spatial_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using namespace aniso;
using aniso::dem::data::spatial_order;

TEST(SpatialOrder, AGridOfEightBinsFollowsTheZCurveWithXFastest) {
  // Bin centres of a 2 x 2 x 2 grid, listed in reverse Z order.
  std::vector<Vec3> points;
  for (int k = 7; k >= 0; --k)
    points.emplace_back(0.5 + (k & 1), 0.5 + ((k >> 1) & 1), 0.5 + ((k >> 2) & 1));
  const std::vector<std::size_t> order = spatial_order(points, Vec3(2, 2, 2), 1.0);
  const std::vector<std::size_t> expected{7, 6, 5, 4, 3, 2, 1, 0};
  EXPECT_EQ(order, expected);
}

TEST(SpatialOrder, TiesKeepTheirOrderAndBinsNeverExceedTheCell) {
  // Bins wider than the cell: one bin, so the order is the given one.
  const std::vector<Vec3> points{Vec3(0.9, 0.1, 0.1), Vec3(0.1, 0.9, 0.9), Vec3(0.5, 0.5, 0.5)};
  const std::vector<std::size_t> order = spatial_order(points, Vec3(1, 1, 1), 10.0);
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2}));
}

TEST(SpatialOrder, ConsecutiveIdsAreNeighboursInSpace) {
  RandomStream stream(5, 0);
  const Vec3 lengths(18, 12, 12);
  std::vector<Vec3> points(6400);
  for (auto& x : points)
    x = Vec3(stream.uniform(0, lengths[0]), stream.uniform(0, lengths[1]), stream.uniform(0, lengths[2]));
  const std::vector<std::size_t> order = spatial_order(points, lengths, 2.0);
  std::vector<std::size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k)
    ASSERT_EQ(sorted[k], k);
  auto mean_step = [&](const std::vector<std::size_t>& sequence) {
    double sum = 0;
    for (std::size_t k = 1; k < sequence.size(); ++k)
      sum += (points[sequence[k]] - points[sequence[k - 1]]).norm();
    return sum / static_cast<double>(sequence.size() - 1);
  };
  std::vector<std::size_t> given(points.size());
  for (std::size_t k = 0; k < given.size(); ++k)
    given[k] = k;
  // Random points are 9.4 apart on average in this cell; along the Z-curve of its 324 bins
  // (about 20 points each) 1.42.
  EXPECT_GT(mean_step(given), 8.0);
  EXPECT_LT(mean_step(order), 2.0);
}

} // namespace
