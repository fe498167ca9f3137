// Tests of the binned Verlet neighbour list (dem/data/neighbors.hpp) against the
// brute-force pair search, on random periodic configurations of the paper's
// size range (radii 0.0375-0.14 mm) in a cube and in a cell as elongated as
// the minimum-image rule allows; the rebuild criterion under particle motion
// and cell strain; and contact history across rebuilds.
#include "common/cell.hpp"
#include "common/error.hpp"
#include "common/rng.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/model/integrator.hpp"
#include "tests/dem/paper_sizes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace {

using aniso::NumericalError;
using aniso::PeriodicCell;
using aniso::RandomStream;
using aniso::Vec3;
using namespace aniso::dem;
using namespace aniso::dem::data;
using namespace aniso::dem::model;

using namespace aniso::dem::test;

/// Twice the list's interaction range, 2 (2 r_max + skin): the shortest cell length allowed.
double shortest_allowed_length(double skin) {
  return 2.0 * (2.0 * kRadiusMax + skin);
}

/// `count` particles with radii uniform in [kRadiusMin, kRadiusMax] (the largest
/// exactly kRadiusMax) at uniform random positions; overlaps are allowed. With
/// `shuffle_ids` the ids are a random permutation of the indices.
Particles random_particles(const PeriodicCell& cell, std::size_t count, std::uint64_t seed,
                           bool shuffle_ids) {
  RandomStream stream(seed, 0);
  std::vector<std::uint64_t> ids(count);
  std::iota(ids.begin(), ids.end(), std::uint64_t{0});
  if (shuffle_ids) {
    for (std::size_t k = count - 1; k > 0; --k)
      std::swap(ids[k], ids[stream.below(k + 1)]);
  }
  Particles particles;
  const Vec3& lengths = cell.lengths();
  for (std::size_t k = 0; k < count; ++k) {
    const double radius = k == 0 ? kRadiusMax : stream.uniform(kRadiusMin, kRadiusMax);
    const Vec3 x(stream.uniform(0, lengths[0]), stream.uniform(0, lengths[1]), stream.uniform(0, lengths[2]));
    particles.add(ids[k], radius, 1.0, 0.7853981633974483, kDensity, x);
  }
  return particles;
}

/// Number of pairs whose raw separation is not the minimum image on some axis (pairs across a face).
int count_across_faces(const Particles& particles, const PeriodicCell& cell, const std::vector<Pair>& pairs) {
  int across = 0;
  for (const Pair& pair : pairs) {
    const Vec3 raw = particles.position[pair.j] - particles.position[pair.i];
    if ((raw - cell.minimum_image(raw)).cwiseAbs().maxCoeff() > 0) ++across;
  }
  return across;
}

void expect_same_pairs(const std::vector<Pair>& actual, const std::vector<Pair>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    ASSERT_EQ(actual[k].i, expected[k].i) << "pair " << k;
    ASSERT_EQ(actual[k].j, expected[k].j) << "pair " << k;
  }
}

struct CellCase {
  const char* name;
  Vec3 lengths;
  std::size_t count;
};

// The binned list finds exactly the brute-force pairs (same pairs, same order),
// including pairs across periodic faces, in a cube and in a cell of proportions
// 0.3 : 1 : 2.7 whose short side is the minimum-image limit itself (two bins).
TEST(NeighborList, EqualsBruteForceInCubeAndElongatedCells) {
  const double shortest = shortest_allowed_length(kSkin);
  const std::vector<CellCase> cases = {
      {"cube", Vec3::Constant(1.6e-3), 400},
      {"0.3:1:2.7 at the limit", Vec3(shortest, shortest / 0.3, 2.7 * shortest / 0.3), 600},
      {"0.3:1:2.7 just above", Vec3(1.0001 * shortest, 1.0001 * shortest / 0.3, 2.7001 * shortest / 0.3),
       600},
  };
  for (const CellCase& c : cases) {
    for (const bool shuffle : {false, true}) {
      SCOPED_TRACE(std::string(c.name) + (shuffle ? ", shuffled ids" : ", ids = indices"));
      // A strongly deformed cell: the reference is a cube of the same volume.
      const PeriodicCell cell(c.lengths, Vec3::Constant(std::cbrt(c.lengths.prod())));
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const Particles particles = random_particles(cell, c.count, seed, shuffle);
        NeighborList list(kSkin);
        ASSERT_NO_THROW(list.build(particles, cell));
        const std::vector<Pair> expected = brute_force_pairs(particles, cell, kSkin);
        ASSERT_GT(expected.size(), c.count / 2) << "too few pairs for a meaningful test";
        expect_same_pairs(list.pairs(), expected);
        EXPECT_GT(count_across_faces(particles, cell, expected), 10) << "no pairs across periodic faces";
        EXPECT_EQ(list.history().size(), list.pairs().size());
        EXPECT_EQ(list.records().size(), list.pairs().size());
        // Sorted by (id_i, id_j) with id_i < id_j, and find() locates every pair.
        for (std::size_t k = 0; k < list.pairs().size(); ++k) {
          const Pair& pair = list.pairs()[k];
          ASSERT_LT(particles.id[pair.i], particles.id[pair.j]);
          if (k > 0) {
            const Pair& prev = list.pairs()[k - 1];
            ASSERT_TRUE(particles.id[prev.i] < particles.id[pair.i] ||
                        (particles.id[prev.i] == particles.id[pair.i] &&
                         particles.id[prev.j] < particles.id[pair.j]));
          }
          ASSERT_EQ(list.find(particles, pair.i, pair.j), static_cast<std::int64_t>(k));
        }
      }
    }
  }
}

// A pair of particles straddling the face, at distance just inside and just
// outside the reach, is found or not found across the face.
TEST(NeighborList, FindsPairAcrossEveryFace) {
  const PeriodicCell cell(Vec3(0.6e-3, 2.0e-3, 5.4e-3));
  for (int axis = 0; axis < 3; ++axis) {
    for (const double factor : {0.999, 1.001}) {
      Particles particles;
      const double reach = 2 * kRadiusMax + kSkin;
      Vec3 a = 0.5 * cell.lengths(), b = 0.5 * cell.lengths();
      a[axis] = 0.25 * factor * reach;
      b[axis] = cell.lengths()[axis] - 0.75 * factor * reach;
      particles.add(0, kRadiusMax, 1.0, 0.7853981633974483, kDensity, a);
      particles.add(1, kRadiusMax, 1.0, 0.7853981633974483, kDensity, b);
      NeighborList list(kSkin);
      list.build(particles, cell);
      EXPECT_EQ(list.pairs().size(), factor < 1 ? 1u : 0u) << "axis " << axis << ", factor " << factor;
      EXPECT_EQ(brute_force_pairs(particles, cell, kSkin).size(), list.pairs().size());
    }
  }
}

// A cell length below twice the interaction range would let a pair interact
// through two images: build() refuses it, naming the length.
TEST(NeighborList, RefusesCellShorterThanTwiceTheRange) {
  const double shortest = shortest_allowed_length(kSkin);
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 lengths = Vec3::Constant(1.6e-3);
    lengths[axis] = 0.999 * shortest;
    const PeriodicCell cell(lengths);
    const Particles particles = random_particles(cell, 50, 11, false);
    NeighborList list(kSkin);
    try {
      list.build(particles, cell);
      ADD_FAILURE() << "no NumericalError for axis " << axis;
    } catch (const NumericalError& error) {
      EXPECT_NE(std::string(error.what()).find("axis " + std::to_string(axis + 1)), std::string::npos)
          << error.what();
    }
  }
  // Exactly at the limit is allowed.
  const PeriodicCell cell(Vec3(shortest, 1.6e-3, 1.6e-3));
  NeighborList list(kSkin);
  EXPECT_NO_THROW(list.build(random_particles(cell, 50, 11, false), cell));
}

// Under random particle motion and a straining cell, whenever needs_rebuild()
// says no, every touching pair is in the list; the list is rebuilt when it says yes.
TEST(NeighborList, RebuildCriterionNeverMissesATouchingPair) {
  const PeriodicCell start_cell(Vec3(1.0e-3, 1.4e-3, 1.8e-3));
  Particles particles = random_particles(start_cell, 500, 5, true);
  RandomStream stream(5, 1);
  const double dt = 1e-8;
  // Per-step random displacements up to about skin/25 per axis, and a strain of
  // 1e-3 per step (shortening axis 1, stretching axis 3): both the fluctuation
  // and the strain term of the criterion matter.
  const double speed = kSkin / 25.0 / dt;
  const Vec3 strain_rate(-1e-3 / dt, 0.3e-3 / dt, 0.6e-3 / dt);
  PeriodicCell cell = start_cell;
  NeighborList list(kSkin);
  list.build(particles, cell);
  int checks = 0, rebuilds = 0;
  std::size_t touching_total = 0;
  for (int step = 0; step < 400; ++step) {
    for (auto& v : particles.velocity)
      v = speed * Vec3(stream.normal(), stream.normal(), stream.normal());
    drift(particles, cell, strain_rate, dt);
    if (list.needs_rebuild(particles, cell)) {
      list.build(particles, cell);
      ++rebuilds;
      // Freshly built: still equal to brute force in the strained cell.
      expect_same_pairs(list.pairs(), brute_force_pairs(particles, cell, kSkin));
    }
    ++checks;
    const std::vector<Pair> touching = brute_force_pairs(particles, cell, 0.0);
    touching_total += touching.size();
    for (const Pair& pair : touching) {
      ASSERT_GE(list.find(particles, pair.i, pair.j), 0)
          << "step " << step << ": touching pair (" << particles.id[pair.i] << ", " << particles.id[pair.j]
          << ") missing from a list that needs no rebuild";
    }
  }
  std::printf("[ measured ] %d steps, %d rebuilds, %zu touching pairs checked, strain (%.3f, %.3f, %.3f)\n",
              checks, rebuilds, touching_total, cell.engineering_strain()[0], cell.engineering_strain()[1],
              cell.engineering_strain()[2]);
  EXPECT_GT(touching_total, 10000u);
  // Neither trivially rebuilding every step nor never rebuilding.
  EXPECT_GT(rebuilds, 5);
  EXPECT_LT(rebuilds, checks / 2);
}

// Contact history (the tangential spring) follows its pair through a rebuild
// in which pairs are lost, gained and re-indexed; new pairs start from zero.
TEST(NeighborList, HistoryCarriesOverForSurvivingPairs) {
  const PeriodicCell start_cell(Vec3(1.0e-3, 1.2e-3, 1.4e-3));
  Particles particles = random_particles(start_cell, 400, 9, true);
  PeriodicCell cell = start_cell;
  NeighborList list(kSkin);
  list.build(particles, cell);
  const auto key = [&](const Pair& pair) {
    return Vec3(static_cast<double>(particles.id[pair.i]), static_cast<double>(particles.id[pair.j]), 0.5);
  };
  for (std::size_t k = 0; k < list.pairs().size(); ++k) {
    list.history()[k].tangential_force = key(list.pairs()[k]);
    list.history()[k].sliding = (k % 3 == 0);
  }
  const std::vector<Pair> old_pairs = list.pairs();
  std::vector<bool> old_sliding;
  for (const auto& h : list.history())
    old_sliding.push_back(h.sliding);
  // Strain the cell by 1 % (affine), then move every particle by up to a skin per axis.
  drift(particles, cell, Vec3(-0.01, 0.005, 0.005), 1.0);
  RandomStream stream(9, 1);
  for (auto& v : particles.velocity) {
    v = kSkin * Vec3(stream.uniform(-1, 1), stream.uniform(-1, 1), stream.uniform(-1, 1));
  }
  drift(particles, cell, Vec3::Zero(), 1.0);
  list.build(particles, cell);
  expect_same_pairs(list.pairs(), brute_force_pairs(particles, cell, kSkin));

  int survived = 0, lost = 0, gained = 0;
  for (std::size_t k = 0; k < old_pairs.size(); ++k) {
    const std::int64_t now = list.find(particles, old_pairs[k].i, old_pairs[k].j);
    if (now < 0) {
      ++lost;
      continue;
    }
    ++survived;
    const auto& h = list.history()[static_cast<std::size_t>(now)];
    EXPECT_EQ(h.tangential_force, key(old_pairs[k]));
    EXPECT_EQ(h.sliding, old_sliding[k]);
  }
  for (std::size_t k = 0; k < list.pairs().size(); ++k) {
    if (list.history()[k].tangential_force[2] == 0.5) continue;
    ++gained;
    EXPECT_EQ(list.history()[k].tangential_force, Vec3::Zero());
    EXPECT_FALSE(list.history()[k].sliding);
  }
  std::printf("[ measured ] %d pairs survived, %d lost, %d gained\n", survived, lost, gained);
  EXPECT_GT(survived, 100);
  EXPECT_GT(lost, 10);
  EXPECT_GT(gained, 10);
  EXPECT_EQ(survived + gained, static_cast<int>(list.pairs().size()));
}

} // namespace
