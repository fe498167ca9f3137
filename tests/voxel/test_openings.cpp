// Every opening equals the brute-force opening (erosion then dilation with the same structuring
// element, periodic wrap) bit for bit, on random periodic images, for all three templates, all
// axes and several sizes; the distance transforms equal brute-force minima (3D, in-plane, capped);
// thread count does not change any bit.
#include "common/distance_transform.hpp"
#include "tests/voxel/reference.hpp"
#include "voxel/openings.hpp"

#include <gtest/gtest.h>

#include <omp.h>
#include <string>

namespace {

using aniso::test::blob_phase;
using aniso::test::brute_force_opening;
using aniso::test::random_phase;
using aniso::voxel::Axes;
using aniso::voxel::Grid;
using aniso::voxel::Mask;

struct Case {
  Grid grid;
  Mask phase;
  std::string name;
};

// Odd and even extents, one smaller than the element (the ball wraps onto itself), i.i.d. noise
// and blobby pores.
std::vector<Case> cases() {
  return {{Grid{{9, 7, 8}}, random_phase(Grid{{9, 7, 8}}, 0.25, 1), "noise 9x7x8"},
          {Grid{{12, 10, 5}}, random_phase(Grid{{12, 10, 5}}, 0.1, 2), "sparse noise 12x10x5"},
          {Grid{{16, 14, 13}}, blob_phase(Grid{{16, 14, 13}}, 14, 2.5, 3), "blobs 16x14x13"},
          {Grid{{20, 6, 18}}, blob_phase(Grid{{20, 6, 18}}, 10, 2.0, 4), "thin blobs 20x6x18"}};
}

std::vector<std::uint32_t> as_values(const Mask& mask) {
  return {mask.begin(), mask.end()};
}

TEST(Distance, EqualsBruteForceIn3DAndInPlanes) {
  for (const Case& c : cases()) {
    const bool all[3] = {true, true, true};
    EXPECT_EQ(aniso::voxel::squared_distance(c.grid, c.phase, Axes::all()),
              aniso::test::brute_force_distance(c.grid, c.phase, all))
        << c.name;
    for (int normal = 0; normal < 3; ++normal) {
      bool use[3] = {true, true, true};
      use[normal] = false;
      EXPECT_EQ(aniso::voxel::squared_distance(c.grid, c.phase, Axes::plane(normal)),
                aniso::test::brute_force_distance(c.grid, c.phase, use))
          << c.name << ", plane normal to x" << normal + 1;
    }
  }
}

TEST(Distance, CapKeepsValuesUpToTheCapExact) {
  const Case c = cases()[2];
  const bool all[3] = {true, true, true};
  const auto exact = aniso::test::brute_force_distance(c.grid, c.phase, all);
  for (const std::uint32_t cap : {0U, 1U, 2U, 5U, 11U}) {
    std::vector<std::uint32_t> capped;
    aniso::voxel::squared_distance(c.grid, aniso::voxel::Target::of_mask(c.phase), Axes::all(), cap, capped);
    for (std::size_t p = 0; p < exact.size(); ++p)
      ASSERT_EQ(capped[p], exact[p] <= cap ? exact[p] : aniso::voxel::infinite_distance) << "cap " << cap;
  }
}

TEST(Distance, EmptyTargetIsInfiniteEverywhere) {
  const Grid grid{{5, 4, 3}};
  const Mask none(grid.size(), 0);
  for (const auto d2 : aniso::voxel::squared_distance(grid, none, Axes::all()))
    EXPECT_EQ(d2, aniso::voxel::infinite_distance);
}

TEST(Openings, BallEqualsBruteForceBitForBit) {
  for (const Case& c : cases()) {
    const auto distance = aniso::voxel::distance_to_solid(c.grid, c.phase, Axes::all());
    std::vector<std::uint32_t> work;
    for (const int r2 : {0, 1, 2, 3, 4, 5, 8, 9, 13}) {
      const Mask fast =
          aniso::voxel::round_opening(c.grid, distance, Axes::all(), static_cast<std::uint32_t>(r2), work);
      const Mask slow = brute_force_opening(c.grid, c.phase, aniso::test::round_element(r2, -1));
      ASSERT_EQ(as_values(fast), as_values(slow)) << c.name << ", ball r^2 = " << r2;
      EXPECT_EQ(aniso::voxel::round_opening_volume(c.grid, distance, Axes::all(),
                                                   static_cast<std::uint32_t>(r2), work),
                static_cast<std::uint64_t>(std::count(slow.begin(), slow.end(), 1)));
    }
  }
}

TEST(Openings, DiskEqualsBruteForceBitForBitOnEveryAxis) {
  for (const Case& c : cases())
    for (int axis = 0; axis < 3; ++axis) {
      const Axes plane = Axes::plane(axis);
      const auto distance = aniso::voxel::distance_to_solid(c.grid, c.phase, plane);
      std::vector<std::uint32_t> work;
      for (const int r2 : {1, 2, 4, 5, 8, 10}) {
        const Mask fast =
            aniso::voxel::round_opening(c.grid, distance, plane, static_cast<std::uint32_t>(r2), work);
        const Mask slow = brute_force_opening(c.grid, c.phase, aniso::test::round_element(r2, axis));
        ASSERT_EQ(as_values(fast), as_values(slow))
            << c.name << ", disk axis x" << axis + 1 << " r^2 = " << r2;
      }
    }
}

TEST(Openings, SparEqualsBruteForceBitForBitOnEveryAxis) {
  for (const Case& c : cases())
    for (int axis = 0; axis < 3; ++axis) {
      const auto runs = aniso::voxel::void_run_lengths(c.grid, c.phase, axis);
      const auto n = static_cast<int>(c.grid.n[static_cast<std::size_t>(axis)]);
      for (int length = 1; length <= n + 2; ++length) {
        const Mask fast = aniso::voxel::spar_opening(c.grid, c.phase, axis, static_cast<std::size_t>(length));
        const Mask slow = brute_force_opening(c.grid, c.phase, aniso::test::spar_element(length, axis));
        ASSERT_EQ(as_values(fast), as_values(slow))
            << c.name << ", spar x" << axis + 1 << " length " << length;
        EXPECT_EQ(runs.opening_volume(static_cast<std::size_t>(length)),
                  static_cast<std::uint64_t>(std::count(slow.begin(), slow.end(), 1)));
      }
    }
}

TEST(Openings, ThreadCountChangesNoBit) {
  const Grid grid{{40, 33, 29}};
  const Mask phase = blob_phase(grid, 60, 4.0, 9);
  const auto run = [&](int threads) {
    omp_set_num_threads(threads);
    std::vector<std::uint64_t> volumes;
    std::vector<std::uint32_t> work;
    for (int family = 0; family < 4; ++family) {
      const Axes axes = family == 0 ? Axes::all() : Axes::plane(family - 1);
      const auto distance = aniso::voxel::distance_to_solid(grid, phase, axes);
      for (std::uint32_t r2 = 1; r2 < 30; r2 += 3)
        volumes.push_back(aniso::voxel::round_opening_volume(grid, distance, axes, r2, work));
    }
    return volumes;
  };
  const auto one = run(1);
  EXPECT_EQ(run(2), one);
  EXPECT_EQ(run(3), one);
  omp_set_num_threads(1);
}

} // namespace
