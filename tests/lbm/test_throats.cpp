// The narrowest throat along each axis (lbm/throats.hpp) on images whose throats are known: plane
// channels and square ducts of every small width, a channel that crosses the cell only along a
// diagonal, images without solid or without a path.
#include "lbm/geometry.hpp"
#include "lbm/throats.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aniso::lbm {
namespace {

TEST(Throats, PlaneChannelOfOddWidthIsItsWidth) {
  // The void voxels across a slit of odd width w: the middle one lies (w + 1) / 2 from the solid.
  for (int width : {1, 3, 5, 7}) {
    const auto widths = throat_widths(plane_channel(width, 8, 2));
    EXPECT_EQ(widths[0], width) << "width " << width;
    EXPECT_EQ(widths[1], width) << "width " << width;
    EXPECT_EQ(widths[2], 0.0) << "no path crosses the plates";
  }
}

TEST(Throats, PlaneChannelOfEvenWidthIsOneLess) {
  for (int width : {2, 4, 6}) {
    const auto widths = throat_widths(plane_channel(width, 8, 0));
    EXPECT_EQ(widths[1], width - 1) << "width " << width;
    EXPECT_EQ(widths[0], 0.0);
  }
}

TEST(Throats, SquareDuctAlongItsAxisOnly) {
  for (int width : {1, 3, 5}) {
    const auto widths = throat_widths(square_duct(width, 10, 1));
    EXPECT_EQ(widths[1], width) << "width " << width;
    EXPECT_EQ(widths[0], 0.0);
    EXPECT_EQ(widths[2], 0.0);
  }
}

TEST(Throats, AChannelThatCrossesOnlyAlongADiagonal) {
  // Void voxels on the diagonal staircase x1 = x2 (D3Q19 edge links join them) in an 8 x 8 x 4
  // cell: the path winds around the cell along x1 and x2 together, so both axes are crossed.
  h5::VoxelImage image;
  image.shape = {8, 8, 4};
  image.voxel_size = 1;
  image.phase.assign(image.size(), 1);
  for (std::size_t i = 0; i < 8; ++i)
    for (std::size_t k = 0; k < 4; ++k)
      image.phase[image.index(i, i, k)] = 0;
  const auto widths = throat_widths(image);
  EXPECT_EQ(widths[0], 1.0);
  EXPECT_EQ(widths[1], 1.0);
  EXPECT_EQ(widths[2], 1.0);
  // Cut the staircase once: nothing crosses x1 or x2 any more, x3 still.
  for (std::size_t k = 0; k < 4; ++k)
    image.phase[image.index(3, 3, k)] = 1;
  const auto cut = throat_widths(image);
  EXPECT_EQ(cut[0], 0.0);
  EXPECT_EQ(cut[1], 0.0);
  EXPECT_EQ(cut[2], 1.0);
}

TEST(Throats, SphereArrayThroatGrowsWithResolution) {
  // The window between the spheres of a simple cubic array scales with the cell: twice the
  // voxels per cell, about twice the throat radius (w + 1) / 2, the same along every axis by symmetry.
  const auto coarse = throat_widths(sphere_array_matching(12, 0.343));
  const auto fine = throat_widths(sphere_array_matching(24, 0.343));
  EXPECT_EQ(coarse[0], coarse[1]);
  EXPECT_EQ(coarse[0], coarse[2]);
  EXPECT_GT(coarse[0], 0.0);
  EXPECT_NEAR((fine[0] + 1) / (coarse[0] + 1), 2.0, 0.3)
      << "throat radii " << (coarse[0] + 1) / 2 << ", " << (fine[0] + 1) / 2;
}

TEST(Throats, NoSolidHasNoThroat) {
  h5::VoxelImage image = plane_channel(4, 4, 2);
  std::fill(image.phase.begin(), image.phase.end(), std::uint8_t{0});
  const auto widths = throat_widths(image);
  EXPECT_TRUE(std::isinf(widths[0]) && std::isinf(widths[1]) && std::isinf(widths[2]));
}

TEST(Throats, AllSolidHasNoPath) {
  h5::VoxelImage image = plane_channel(4, 4, 2);
  std::fill(image.phase.begin(), image.phase.end(), std::uint8_t{1});
  const auto widths = throat_widths(image);
  EXPECT_EQ(widths[0], 0.0);
  EXPECT_EQ(widths[2], 0.0);
}

} // namespace
} // namespace aniso::lbm
