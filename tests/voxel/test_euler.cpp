// Euler characteristic of the void (26-connected void, 6-connected solid) on the periodic image
// for sets of known topology: chi = components + cavities - tunnels (paper eq. (chiv1)).
#include "voxel/euler.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace {

using aniso::voxel::Grid;
using aniso::voxel::Mask;

// Phase image with void where is_void(x, y, z) at voxel centres (voxel units).
Mask paint(const Grid& grid, const std::function<bool(double, double, double)>& is_void) {
  Mask phase(grid.size(), 1);
  for (std::size_t k = 0; k < grid.n[2]; ++k)
    for (std::size_t j = 0; j < grid.n[1]; ++j)
      for (std::size_t i = 0; i < grid.n[0]; ++i)
        if (is_void(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5, static_cast<double>(k) + 0.5))
          phase[grid.index(i, j, k)] = 0;
  return phase;
}

const Grid grid{{32, 30, 28}};
constexpr double cx = 16, cy = 15, cz = 14;

std::int64_t chi(const std::function<bool(double, double, double)>& is_void) {
  return aniso::voxel::void_euler_characteristic(grid, paint(grid, is_void));
}

bool in_ball(double x, double y, double z, double x0, double y0, double z0, double r) {
  return (x - x0) * (x - x0) + (y - y0) * (y - y0) + (z - z0) * (z - z0) <= r * r;
}

TEST(Euler, BallIsOneAndTwoBallsAreTwo) {
  EXPECT_EQ(chi([](double x, double y, double z) { return in_ball(x, y, z, cx, cy, cz, 6.3); }), 1);
  EXPECT_EQ(chi([](double x, double y, double z) {
              return in_ball(x, y, z, 8, 8, 8, 4.2) || in_ball(x, y, z, 24, 22, 20, 5.1);
            }),
            2);
}

TEST(Euler, SolidTorusIsZero) {
  EXPECT_EQ(chi([](double x, double y, double z) {
              const double rho = std::hypot(x - cx, y - cy) - 9.0;
              return rho * rho + (z - cz) * (z - cz) <= 3.2 * 3.2;
            }),
            0);
}

TEST(Euler, PeriodicSlabAndChannelAreZero) {
  EXPECT_EQ(chi([](double, double, double z) { return std::abs(z - cz) < 3; }), 0);
  EXPECT_EQ(chi([](double, double y, double z) { return std::hypot(y - cy, z - cz) < 4.5; }), 0);
}

TEST(Euler, ChannelNetworkIsOneMinusThreeTunnels) {
  // Three orthogonal periodic channels crossing once: a wedge of three circles on the torus.
  EXPECT_EQ(chi([](double x, double y, double z) {
              return std::hypot(y - cy, z - cz) < 4.5 || std::hypot(x - cx, z - cz) < 4.5 ||
                     std::hypot(x - cx, y - cy) < 4.5;
            }),
            -2);
}

TEST(Euler, VoidAroundSolidBallsCountsTheBalls) {
  // T^3 minus k disjoint balls has chi = k (= N_p - N_c on the torus with no contacts).
  EXPECT_EQ(chi([](double x, double y, double z) { return !in_ball(x, y, z, cx, cy, cz, 7.4); }), 1);
  EXPECT_EQ(chi([](double x, double y, double z) {
              return !in_ball(x, y, z, 8, 8, 8, 5.5) && !in_ball(x, y, z, 24, 22, 20, 5.5);
            }),
            2);
}

TEST(Euler, WholeTorusAndEmptyVoidAreZero) {
  EXPECT_EQ(chi([](double, double, double) { return true; }), 0);
  EXPECT_EQ(chi([](double, double, double) { return false; }), 0);
}

TEST(Euler, VoidVoxelsTouchingAtACornerAreConnected) {
  Mask phase(grid.size(), 1);
  phase[grid.index(5, 5, 5)] = 0;
  phase[grid.index(6, 6, 6)] = 0;
  EXPECT_EQ(aniso::voxel::void_euler_characteristic(grid, phase), 1);
  phase[grid.index(20, 20, 20)] = 0;
  EXPECT_EQ(aniso::voxel::void_euler_characteristic(grid, phase), 2);
}

} // namespace
