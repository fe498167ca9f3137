// lbm/percolation.cpp: which axes the pore space of an image connects across, on images whose
// answer is known by construction.
#include "lbm/geometry.hpp"
#include "lbm/percolation.hpp"

#include <gtest/gtest.h>

namespace aniso::lbm {
namespace {

std::array<bool, 3> percolating(const h5::VoxelImage& image, const Faces& faces = all_periodic) {
  return {percolates(image, 0, faces), percolates(image, 1, faces), percolates(image, 2, faces)};
}

h5::VoxelImage solid_cube(std::size_t side) {
  h5::VoxelImage image;
  image.shape = {side, side, side};
  image.voxel_size = 1.0;
  image.phase.assign(side * side * side, 1);
  return image;
}

void set_void(h5::VoxelImage& image, std::size_t i, std::size_t j, std::size_t k) {
  image.phase[i + image.shape[0] * (j + image.shape[1] * k)] = 0;
}

TEST(Percolation, ChannelsConnectAlongTheirAxesOnly) {
  // A plane channel normal to x2 connects along x1 and x3, not across the plates.
  EXPECT_EQ(percolating(plane_channel(4, 8, 1)), (std::array<bool, 3>{true, false, true}));
  // A square duct along x3 connects along x3 only.
  EXPECT_EQ(percolating(square_duct(3, 8, 2)), (std::array<bool, 3>{false, false, true}));
  // The sphere array's pore space connects everywhere.
  EXPECT_EQ(percolating(sphere_array_matching(12, 0.2)), (std::array<bool, 3>{true, true, true}));
}

TEST(Percolation, EdgeLinksConnectAsD3Q19StreamsButCornersDoNot) {
  // A staircase of void voxels along x1 that meet only at edges (i, i, 0): D3Q19 streams along
  // (1, 1, 0), so it connects along x1 and x2 (it winds once around both).
  h5::VoxelImage edges = solid_cube(6);
  for (std::size_t i = 0; i < 6; ++i)
    set_void(edges, i, i, 0);
  EXPECT_EQ(percolating(edges), (std::array<bool, 3>{true, true, false}));
  // The same along the body diagonal (i, i, i) meets only at corners: (1, 1, 1) is no D3Q19 link.
  h5::VoxelImage corners = solid_cube(6);
  for (std::size_t i = 0; i < 6; ++i)
    set_void(corners, i, i, i);
  EXPECT_EQ(percolating(corners), (std::array<bool, 3>{false, false, false}));
}

TEST(Percolation, AWallFaceCutsThePathsThatCrossIt) {
  // The staircase winds around x2 as it crosses x1: with walls on the x2 faces it cannot close.
  h5::VoxelImage edges = solid_cube(6);
  for (std::size_t i = 0; i < 6; ++i)
    set_void(edges, i, i, 0);
  EXPECT_FALSE(percolates(edges, 0, walled_except(0, FaceKind::no_slip)));
  // A straight duct along x1 does not need the side faces.
  EXPECT_TRUE(percolates(square_duct(3, 8, 0), 0, walled_except(0, FaceKind::no_slip)));
  // A sealed plane across x1 blocks it, whatever else is open.
  h5::VoxelImage walled = sphere_array_matching(12, 0.2);
  for (std::size_t j = 0; j < 12; ++j)
    for (std::size_t k = 0; k < 12; ++k)
      walled.phase[5 + 12 * (j + 12 * k)] = 1;
  EXPECT_EQ(percolating(walled), (std::array<bool, 3>{false, true, true}));
}

} // namespace
} // namespace aniso::lbm
