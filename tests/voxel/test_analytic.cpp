// Void analysis on images with known answers: a straight periodic slit channel (free path infinite
// along it, breadth = half-width), a simple cubic lattice of spheres (straight open lines, the
// largest pore ball, cubic symmetry, chi), a single cavity of known radius; and digitization:
// the solid volume fraction converges to the analytic value (sphere and ovoid), ovoids are
// oriented body to world, periodic images are painted.
#include "common/mpi.hpp"
#include "common/shape/ovoid.hpp"
#include "voxel/digitize.hpp"
#include "voxel/openings.hpp"
#include "voxel/void_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace {

using aniso::Quat;
using aniso::Vec3;
using aniso::voxel::Body;
using aniso::voxel::Grid;
using aniso::voxel::Mask;
using aniso::voxel::VoidAnalysis;

constexpr double inf = std::numeric_limits<double>::infinity();

// Radius step 0: every distinct digital ball and disk; 1: integer radii.
VoidAnalysis analyze(const Grid& grid, const Mask& phase, double radius_step = 0) {
  aniso::voxel::VoidAnalysisOptions options;
  options.radius_step = radius_step;
  return aniso::voxel::analyze_voids(grid, phase, options, aniso::mpi::Comm(MPI_COMM_SELF));
}

double solid_fraction(const Mask& phase) {
  return static_cast<double>(std::count(phase.begin(), phase.end(), 1)) / static_cast<double>(phase.size());
}

TEST(Analytic, SlitChannelHasInfiniteFreePathAlongItAndBreadthHalfItsWidth) {
  const Grid grid{{24, 20, 16}};
  constexpr std::size_t width = 7; // void layers k = 5 .. 11
  Mask phase(grid.size(), 1);
  for (std::size_t k = 5; k < 5 + width; ++k)
    for (std::size_t j = 0; j < grid.n[1]; ++j)
      for (std::size_t i = 0; i < grid.n[0]; ++i)
        phase[grid.index(i, j, k)] = 0;
  const VoidAnalysis a = analyze(grid, phase, 1.0);
  EXPECT_EQ(a.void_voxels, 24U * 20U * width);
  EXPECT_EQ(a.spar[0].median, inf);
  EXPECT_EQ(a.spar[1].median, inf);
  EXPECT_EQ(a.spar[0].infinite, a.void_voxels);
  // Runs of exactly `width` voxels across: f = 1 up to l = 7, 0 from l = 8; interpolated 7.5.
  EXPECT_DOUBLE_EQ(a.spar[2].median, 7.5);
  // A digital ball or disk of radius r spans 2r + 1 voxels: it fits for r <= 3, so 3.5 = width / 2.
  EXPECT_DOUBLE_EQ(a.ball.median, 0.5 * width);
  EXPECT_DOUBLE_EQ(a.disk[0].median, 0.5 * width);
  EXPECT_DOUBLE_EQ(a.disk[1].median, 0.5 * width);
  EXPECT_EQ(a.disk[2].median, inf); // disks in the slit's own plane never stop fitting
  // The default step 0 takes every distinct digital element: balls up to r^2 = 14 (sums of three
  // squares) and disks up to 13 (of two) still span 7 voxels; r = 4 spans 9. The medians lie
  // half-way between those radii (docs/methods/voxel.md, "Medians").
  const VoidAnalysis every = analyze(grid, phase);
  EXPECT_DOUBLE_EQ(every.ball.median, 0.5 * (std::sqrt(14.0) + 4.0));
  EXPECT_DOUBLE_EQ(every.disk[0].median, 0.5 * (std::sqrt(13.0) + 4.0));
  EXPECT_DOUBLE_EQ(every.disk[1].median, 0.5 * (std::sqrt(13.0) + 4.0));
  EXPECT_EQ(a.euler, 0);

  // Every distinct element: the last ball that fits is r^2 = 14 (15 is no sum of three squares,
  // r^2 = 16 spans 9 voxels), the last disk r^2 = 13; the medians lie between those and 4.
  const VoidAnalysis all = analyze(grid, phase);
  EXPECT_DOUBLE_EQ(all.ball.median, 0.5 * (std::sqrt(14.0) + 4));
  EXPECT_DOUBLE_EQ(all.disk[0].median, 0.5 * (std::sqrt(13.0) + 4));
  EXPECT_EQ(all.spar[2].median, 7.5);
}

TEST(Analytic, SingleCavityOfKnownRadius) {
  const Grid grid{{21, 23, 22}};
  constexpr int radius = 6;
  Mask phase(grid.size(), 1);
  for (std::size_t k = 0; k < grid.n[2]; ++k)
    for (std::size_t j = 0; j < grid.n[1]; ++j)
      for (std::size_t i = 0; i < grid.n[0]; ++i) {
        const auto d = [](std::size_t v, int c) { return static_cast<int>(v) - c; };
        if (d(i, 10) * d(i, 10) + d(j, 11) * d(j, 11) + d(k, 11) * d(k, 11) <= radius * radius)
          phase[grid.index(i, j, k)] = 0;
      }
  const VoidAnalysis a = analyze(grid, phase, 1.0);
  ASSERT_EQ(a.ball.size.size(), static_cast<std::size_t>(radius) + 2);
  EXPECT_EQ(a.ball.kept[radius], a.void_voxels); // the cavity itself is the ball of radius 6
  EXPECT_EQ(a.ball.kept[radius + 1], 0U);
  EXPECT_GE(a.ball.median, radius);
  EXPECT_LT(a.ball.median, radius + 1);
  // Chords through a ball: the longest along each axis is 2R + 1 voxels, and the three are equal.
  for (std::size_t l = 0; l <= 2 * radius + 2; ++l) {
    EXPECT_EQ(a.spar[0].kept[l], a.spar[1].kept[l]) << l;
    EXPECT_EQ(a.spar[0].kept[l], a.spar[2].kept[l]) << l;
  }
  EXPECT_EQ(a.spar[0].kept[2 * radius + 1], 2 * radius + 1);
  EXPECT_EQ(a.spar[0].kept[2 * radius + 2], 0U);
  EXPECT_EQ(a.euler, 1);
}

TEST(Analytic, SimpleCubicLatticeOfSpheres) {
  // 2 x 2 x 2 lattice cells of a = 15 voxels, sphere radius R = 6 voxels, centres on voxel centres.
  constexpr double a = 15, R = 6;
  std::vector<Body> bodies;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        bodies.push_back({Vec3(7.5 + a * i, 7.5 + a * j, 7.5 + a * k), 2 * R, 1.0, Quat::Identity()});
  const Grid grid{{30, 30, 30}};
  const Mask phase = aniso::voxel::digitize_bodies(bodies, Vec3(30, 30, 30), grid.n, 0.7);
  const double analytic = 4.0 / 3.0 * std::numbers::pi * R * R * R / (a * a * a);
  EXPECT_NEAR(solid_fraction(phase), analytic, 0.03 * analytic); // R = 6 voxels: 2.2% high

  const VoidAnalysis v = analyze(grid, phase);
  // Cubic symmetry of the digital image: the three directions agree bit for bit.
  EXPECT_EQ(v.spar[0].kept, v.spar[1].kept);
  EXPECT_EQ(v.spar[0].kept, v.spar[2].kept);
  EXPECT_EQ(v.disk[0].kept, v.disk[1].kept);
  EXPECT_EQ(v.disk[0].kept, v.disk[2].kept);
  // Lines missing every sphere are void for ever: a fraction 1 - pi R^2 / a^2 of the lines.
  const double open_lines = (1 - std::numbers::pi * R * R / (a * a)) / (1 - analytic);
  EXPECT_NEAR(static_cast<double>(v.spar[0].infinite) / static_cast<double>(v.void_voxels), open_lines, 0.03);
  EXPECT_EQ(v.spar[0].median, inf);
  // The largest pore ball sits at a lattice corner: radius sqrt(3) a / 2 - R = 6.99 in the
  // continuum; digital centres sit half a voxel off the corner: sqrt(3) (a / 2 - 0.5) - R = 6.12.
  const auto distance = aniso::voxel::distance_to_solid(grid, phase, aniso::voxel::Axes::all());
  const double largest = std::sqrt(static_cast<double>(*std::max_element(distance.begin(), distance.end())));
  EXPECT_NEAR(largest, std::sqrt(3.0) * (a / 2 - 0.5) - R, 0.5);
  EXPECT_EQ(v.ball.kept.back(), 0U);
  EXPECT_EQ(v.euler, 8); // T^3 minus 8 disjoint balls; N_p - N_c = 8 - 0
}

TEST(Digitize, SolidFractionConvergesToTheAnalyticValue) {
  // One sphere of diameter 1 crossing the periodic boundary, d50 = 1, cell 1.7^3.
  const std::vector<Body> sphere{{Vec3(0.31, 1.57, 0.83), 1.0, 1.0, Quat::Identity()}};
  const Vec3 lengths(1.7, 1.7, 1.7);
  const double analytic = std::numbers::pi / 6 / lengths.prod();
  std::vector<double> errors;
  for (const double resolution : {6.0, 12.0, 24.0, 48.0}) {
    const auto shape = aniso::voxel::grid_shape(lengths, 1.0, resolution);
    errors.push_back(
        std::abs(solid_fraction(aniso::voxel::digitize_bodies(sphere, lengths, shape, 0.7)) - analytic) /
        analytic);
  }
  EXPECT_LT(errors.back(), 0.003);
  EXPECT_LT(errors.back(), errors.front());
  EXPECT_LT(errors[2], 0.01);

  // An ovoid (alpha = 0.6) in a general orientation: its closed-form volume.
  const aniso::OvoidShape ovoid(1.0, 0.6, aniso::OvoidShape::default_splice_angle);
  const std::vector<Body> body{
      {Vec3(0.9, 0.2, 1.6), 1.0, 0.6, Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()))}};
  const auto shape = aniso::voxel::grid_shape(lengths, 1.0, 48.0);
  const double ovoid_fraction = solid_fraction(
      aniso::voxel::digitize_bodies(body, lengths, shape, aniso::OvoidShape::default_splice_angle));
  EXPECT_NEAR(ovoid_fraction, ovoid.volume() / lengths.prod(), 0.005 * ovoid.volume() / lengths.prod());
}

// Solid extent (in voxels) along each axis of a single body.
std::array<std::size_t, 3> extents(const Mask& phase, const Grid& grid) {
  std::array<std::size_t, 3> count{};
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<bool> hit(grid.n[static_cast<std::size_t>(axis)], false);
    for (std::size_t index = 0; index < grid.size(); ++index)
      if (phase[index] != 0) {
        const std::size_t c[3] = {index % grid.n[0], (index / grid.n[0]) % grid.n[1],
                                  index / (grid.n[0] * grid.n[1])};
        hit[c[axis]] = true;
      }
    count[static_cast<std::size_t>(axis)] =
        static_cast<std::size_t>(std::count(hit.begin(), hit.end(), true));
  }
  return count;
}

TEST(Digitize, OvoidAxisFollowsTheBodyToWorldOrientation) {
  const Grid grid{{40, 40, 40}};
  const Vec3 lengths(40, 40, 40);
  // Body axis z; a quarter turn about x1 takes body z to world -x2.
  const Body upright{Vec3(20, 20, 20), 30, 0.4, Quat::Identity()};
  const Body turned{Vec3(20, 20, 20), 30, 0.4, Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()))};
  const auto upright_extent =
      extents(aniso::voxel::digitize_bodies(std::vector<Body>{upright}, lengths, grid.n, 0.6), grid);
  const auto turned_extent =
      extents(aniso::voxel::digitize_bodies(std::vector<Body>{turned}, lengths, grid.n, 0.6), grid);
  EXPECT_EQ(upright_extent[0], 30U);
  EXPECT_EQ(upright_extent[2], 12U); // height alpha D = 12
  EXPECT_EQ(turned_extent[1], 12U);
  EXPECT_EQ(turned_extent[2], 30U);
}

TEST(Digitize, PeriodicImagesArePainted) {
  // A sphere centred on the cell corner appears as eight pieces that add up to one sphere.
  const Grid grid{{20, 20, 20}};
  const std::vector<Body> corner{{Vec3(0, 0, 0), 10, 1.0, Quat::Identity()}};
  const std::vector<Body> middle{{Vec3(10, 10, 10), 10, 1.0, Quat::Identity()}};
  const Vec3 lengths(20, 20, 20);
  const Mask split = aniso::voxel::digitize_bodies(corner, lengths, grid.n, 0.7);
  const Mask whole = aniso::voxel::digitize_bodies(middle, lengths, grid.n, 0.7);
  EXPECT_GT(std::count(whole.begin(), whole.end(), 1), 400);
  EXPECT_EQ(std::count(split.begin(), split.end(), 1), std::count(whole.begin(), whole.end(), 1));
  EXPECT_EQ(split[grid.index(0, 0, 0)], 1);
  EXPECT_EQ(split[grid.index(19, 19, 19)], 1);
}

} // namespace
