// `aniso-dem replicate` (dem/interop/replicate.hpp) on a hand-made checkpoint whose contacts cross
// the periodic boundary on every axis: each copy's contact joins the partner its branch vector
// reaches (the same branch vector, to 1e-15 of the cell), the pair is stored from the lower id
// with the signs of its vectors turned where the copies reverse it, contact points lie at the
// contact in the tiled cell, and 1 x 1 x 1 gives the input's bits. --copies is parsed strictly,
// and an image shift that does not match the positions is refused by name.
#include "common/error.hpp"
#include "dem/interop/replicate.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace aniso;
using aniso::dem::interop::Copies;
using aniso::dem::interop::parse_copies;
using aniso::dem::interop::replicate_checkpoint;

// Adds a contact (a, b) at the positions' minimum image, with made-up but distinct forces.
void add_contact(h5::Checkpoint& c, std::uint64_t a, std::uint64_t b) {
  const auto& p = c.particles;
  const Vec3& lengths = c.cell.lengths;
  const Vec3 raw = p.position[b] - p.position[a];
  Vec3i shift;
  for (int axis = 0; axis < 3; ++axis)
    shift[axis] = static_cast<int>(-std::round(raw[axis] / lengths[axis]));
  const Vec3 branch = raw + shift.cast<double>().cwiseProduct(lengths);
  const Vec3 normal = branch.normalized();
  Vec3 point = p.position[a] + 0.5 * branch;
  for (int axis = 0; axis < 3; ++axis)
    point[axis] -= lengths[axis] * std::floor(point[axis] / lengths[axis]);
  const double k = static_cast<double>(c.contacts.size() + 1);
  c.contacts.particles.push_back({a, b});
  c.contacts.image_shift.push_back(shift);
  c.contacts.normal.push_back(normal);
  c.contacts.point.push_back(point);
  c.contacts.overlap.push_back(0.5 * (p.diameter[a] + p.diameter[b]) - branch.norm());
  c.contacts.force.push_back(-k * normal + Vec3(0, 0.01 * k, 0));
  c.contacts.tangential_force.push_back(Vec3(0.001 * k, -0.0, 0.002));
  c.contacts.sliding.push_back(static_cast<std::uint8_t>(k > 2));
}

// Seven spheres of diameter 0.2 in a 1 x 1.5 x 2 cell: contacts inside the cell (0-2), across x
// (0-1), across y and z at once (3-4) and across all three (5-6); no contact point lies on a face.
h5::Checkpoint crossing_contacts() {
  h5::Checkpoint c = test::sample_checkpoint(11, 7, 0, 2);
  c.cell.lengths = Vec3(1.0, 1.5, 2.0);
  c.cell.reference_lengths = Vec3(1.1, 1.6, 2.1);
  const std::vector<Vec3> positions{{0.03, 0.5, 1.0},  {0.95, 0.5, 1.0},  {0.03, 0.62, 1.0},
                                    {0.5, 1.44, 1.93}, {0.5, 0.04, 0.05}, {0.02, 0.03, 0.04},
                                    {0.95, 1.46, 1.97}};
  for (std::size_t k = 0; k < positions.size(); ++k) {
    c.particles.position[k] = positions[k];
    c.particles.diameter[k] = 0.2;
  }
  c.particles.velocity[3] = Vec3(-0.0, 1e-300, 2.0); // bits a careless copy would change
  c.contacts = {};
  const std::array<std::array<std::uint64_t, 2>, 4> pairs{{{0, 1}, {0, 2}, {3, 4}, {5, 6}}};
  for (const auto& [a, b] : pairs)
    add_contact(c, a, b);
  return c;
}

Vec3 branch_of(const h5::Checkpoint& c, std::size_t row) {
  const auto [i, j] = c.contacts.particles[row];
  return c.particles.position[j] - c.particles.position[i] +
         c.contacts.image_shift[row].cast<double>().cwiseProduct(c.cell.lengths);
}

TEST(Replicate, OneCopyIsTheInputBitForBit) {
  const h5::Checkpoint original = crossing_contacts();
  test::expect_bit_identical(original, replicate_checkpoint(original, {1, 1, 1}, "x.h5"));
}

TEST(Replicate, EachCopyJoinsThePartnerItsBranchVectorReaches) {
  const h5::Checkpoint original = crossing_contacts();
  const std::size_t n = original.particles.size();
  for (const Copies copies : {Copies{2, 1, 3}, Copies{3, 2, 2}, Copies{1, 2, 1}}) {
    SCOPED_TRACE(testing::Message() << copies[0] << "," << copies[1] << "," << copies[2]);
    const h5::Checkpoint tiled = replicate_checkpoint(original, copies, "x.h5");
    const auto n_copies = static_cast<std::size_t>(copies[0] * copies[1] * copies[2]);
    const Vec3 lengths = tiled.cell.lengths;
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(lengths[a], static_cast<double>(copies[a]) * original.cell.lengths[a]);
      EXPECT_EQ(tiled.cell.reference_lengths[a],
                static_cast<double>(copies[a]) * original.cell.reference_lengths[a]);
    }
    ASSERT_EQ(tiled.particles.size(), n_copies * n);
    for (std::size_t row = 0; row < tiled.particles.size(); ++row) {
      const std::size_t k = row % n;
      const auto copy = static_cast<std::int64_t>(row / n);
      const Vec3 cell(static_cast<double>(copy % copies[0]),
                      static_cast<double>(copy / copies[0] % copies[1]),
                      static_cast<double>(copy / (copies[0] * copies[1])));
      EXPECT_EQ(tiled.particles.id[row], row);
      EXPECT_LT((tiled.particles.position[row] - original.particles.position[k] -
                 cell.cwiseProduct(original.cell.lengths))
                    .norm(),
                1e-15 * lengths.maxCoeff());
      EXPECT_TRUE(test::same_bits(tiled.particles.velocity[row], original.particles.velocity[k]));
      EXPECT_EQ(tiled.particles.orientation[row].coeffs(), original.particles.orientation[k].coeffs());
    }
    // Every original contact once per copy, from the lower id, at the original's branch vector.
    ASSERT_EQ(tiled.contacts.size(), n_copies * original.contacts.size());
    std::map<std::array<std::uint64_t, 2>, std::size_t> rows_of_original;
    for (std::size_t row = 0; row < original.contacts.size(); ++row)
      rows_of_original[original.contacts.particles[row]] = row;
    std::vector<std::size_t> seen(original.contacts.size(), 0);
    for (std::size_t row = 0; row < tiled.contacts.size(); ++row) {
      const auto [i, j] = tiled.contacts.particles[row];
      ASSERT_LT(i, j);
      if (row > 0) {
        EXPECT_LT(tiled.contacts.particles[row - 1], tiled.contacts.particles[row]);
      }
      const bool reversed = i % n > j % n;
      const double sign = reversed ? -1.0 : 1.0;
      const auto found = rows_of_original.find({std::min(i % n, j % n), std::max(i % n, j % n)});
      ASSERT_NE(found, rows_of_original.end()) << "contact (" << i << ", " << j << ")";
      const std::size_t k = found->second;
      ++seen[k];
      EXPECT_LT((branch_of(tiled, row) - sign * branch_of(original, k)).norm(), 1e-15 * lengths.maxCoeff());
      EXPECT_EQ(tiled.contacts.normal[row], sign * original.contacts.normal[k]);
      EXPECT_EQ(tiled.contacts.force[row], sign * original.contacts.force[k]);
      EXPECT_EQ(tiled.contacts.tangential_force[row], sign * original.contacts.tangential_force[k]);
      EXPECT_EQ(tiled.contacts.overlap[row], original.contacts.overlap[k]);
      EXPECT_EQ(tiled.contacts.sliding[row], original.contacts.sliding[k]);
      // The point halfway along the branch vector, wrapped into the tiled cell.
      Vec3 point = tiled.particles.position[i] + 0.5 * branch_of(tiled, row);
      for (int a = 0; a < 3; ++a)
        point[a] -= lengths[a] * std::floor(point[a] / lengths[a]);
      EXPECT_LT((tiled.contacts.point[row] - point).norm(), 1e-15 * lengths.maxCoeff())
          << "contact (" << i << ", " << j << ")";
    }
    EXPECT_EQ(seen, std::vector<std::size_t>(original.contacts.size(), n_copies));
  }
}

TEST(Replicate, ContactAcrossTheBoundaryReachesTheNeighbouringCopy) {
  // Particle 0 at x = 0.03 touches particle 1 at x = 0.95 through the x boundary (shift -1). In
  // two copies along x, copy 0's particle 0 (id 0) touches copy 1's particle 1 (id 8) through the
  // tiled cell's boundary, and copy 1's particle 0 (id 7) touches copy 0's particle 1 (id 1) inside
  // it, stored from id 1 with the normal turned, at x = 0.99.
  const h5::Checkpoint original = crossing_contacts();
  ASSERT_EQ(original.contacts.image_shift[0], Vec3i(-1, 0, 0));
  const h5::Checkpoint tiled = replicate_checkpoint(original, {2, 1, 1}, "x.h5");
  const auto row_of = [&](std::uint64_t i, std::uint64_t j) {
    const auto& pairs = tiled.contacts.particles;
    return static_cast<std::size_t>(std::find(pairs.begin(), pairs.end(), std::array{i, j}) - pairs.begin());
  };
  const std::size_t across = row_of(0, 8), inside = row_of(1, 7);
  ASSERT_LT(across, tiled.contacts.size());
  ASSERT_LT(inside, tiled.contacts.size());
  EXPECT_EQ(tiled.contacts.image_shift[across], Vec3i(-1, 0, 0));
  EXPECT_EQ(tiled.contacts.image_shift[inside], Vec3i(0, 0, 0));
  EXPECT_EQ(tiled.contacts.normal[inside], -original.contacts.normal[0]);
  EXPECT_NEAR(tiled.contacts.point[inside].x(), 0.99, 1e-15);
  EXPECT_NEAR(tiled.contacts.point[across].x(), 1.99, 1e-15);
  EXPECT_EQ(row_of(0, 1), tiled.contacts.size()) << "no contact with the far copy";
}

TEST(Replicate, ImportedSourceIdsAreKeptForOneCopyOnly) {
  h5::Checkpoint original = crossing_contacts();
  original.particles.source_id = {10, 11, 12, 13, 14, 15, 16};
  EXPECT_EQ(replicate_checkpoint(original, {1, 1, 1}, "x.h5").particles.source_id,
            original.particles.source_id);
  EXPECT_TRUE(replicate_checkpoint(original, {1, 2, 1}, "x.h5").particles.source_id.empty());
}

TEST(Replicate, ImageShiftThatMissesThePartnerIsRefused) {
  h5::Checkpoint original = crossing_contacts();
  original.contacts.image_shift[2] += Vec3i(1, 0, 0);
  try {
    static_cast<void>(replicate_checkpoint(original, {2, 2, 2}, "bad.h5"));
    FAIL() << "no error";
  } catch (const FileError& error) {
    EXPECT_THAT(error.what(), testing::HasSubstr("bad.h5: /contacts/image_shift: contact (3, 4) at row 2"));
    EXPECT_THAT(error.what(), testing::HasSubstr("the image shift does not match the positions"));
  }
}

TEST(Replicate, CopiesAreThreeWholeNumbersOfAtLeastOne) {
  EXPECT_EQ(parse_copies("2,2,2"), (Copies{2, 2, 2}));
  EXPECT_EQ(parse_copies("1,2,3"), (Copies{1, 2, 3}));
  for (const std::string bad : {"", "2", "2,2", "2,2,2,2", "0,2,2", "2,-1,2", "2,x,2", "2,,2", "2.5,2,2",
                                " 2,2,2", "2,2,2,", "+2,2,2", "99999999999999999999,1,1"}) {
    SCOPED_TRACE("'" + bad + "'");
    try {
      static_cast<void>(parse_copies(bad));
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_THAT(error.what(), testing::HasSubstr("--copies '" + bad + "': expected three whole numbers"));
    }
  }
}

} // namespace
