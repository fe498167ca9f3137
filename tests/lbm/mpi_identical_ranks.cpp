// 1 and 2 ranks give identical bits: the same flow on the whole communicator (DMDA layout, and
// explicit splits along each axis) and on rank 0 alone must agree to the last bit in every
// velocity component, for the periodic method and with free-slip and no-slip walls.
#include "common/log.hpp"
#include "lbm/flow.hpp"
#include "lbm/geometry.hpp"
#include "lbm/topology.hpp"
#include "tests/lbm/fixed_flow.hpp"
#include "tests/lbm/petsc_environment.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace aniso::lbm {
namespace {

const mpi::Comm world = mpi::Comm::world();

FlowResult run(const h5::VoxelImage& image, const Partition& partition, const Faces& faces,
               const mpi::Comm& comm, Precision precision) {
  const Topology topology = build_topology(image.phase, partition, faces, comm);
  return run_flow(topology, fixed_flow_settings(precision), comm, make_silent_logger());
}

Index3 shape_of(const h5::VoxelImage& image) {
  return {static_cast<int>(image.shape[0]), static_cast<int>(image.shape[1]),
          static_cast<int>(image.shape[2])};
}

/// Runs on rank 0 alone and on all ranks with `partition`, and compares the bits on rank 0.
void expect_identical(const h5::VoxelImage& image, const Partition& partition, const Faces& faces,
                      Precision precision) {
  const FlowResult parallel = run(image, partition, faces, world, precision);
  const mpi::Comm self(MPI_COMM_SELF);
  if (!world.is_root()) return;
  const FlowResult serial =
      run(image, make_partition(shape_of(image), Index3{1, 1, 1}, 0), faces, self, precision);
  ASSERT_EQ(serial.velocity.size(), parallel.velocity.size());
  EXPECT_EQ(
      std::memcmp(serial.velocity.data(), parallel.velocity.data(), serial.velocity.size() * sizeof(double)),
      0);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(serial.mean_momentum[a], parallel.mean_momentum[a]);
    EXPECT_EQ(serial.pressure_gradient[a], parallel.pressure_gradient[a]);
  }
  EXPECT_NE(serial.mean_momentum.norm(), 0.0);
}

const h5::VoxelImage packing = random_spheres({18, 14, 16}, 3.0, 0.45, 11);

TEST(IdenticalRanks, DmdaLayoutPeriodic) {
  const Faces faces = all_periodic;
  expect_identical(packing, make_partition(shape_of(packing), faces, world), faces, Precision::float64);
  expect_identical(packing, make_partition(shape_of(packing), faces, world), faces, Precision::float32);
}

TEST(IdenticalRanks, SplitAlongEachAxisWithWalls) {
  for (int axis = 0; axis < 3; ++axis) {
    Index3 procs{1, 1, 1};
    procs[static_cast<std::size_t>(axis)] = world.size();
    const Partition partition = make_partition(shape_of(packing), procs, world.rank());
    expect_identical(packing, partition, all_periodic, Precision::float64);
    expect_identical(packing, partition, walled_except(axis, FaceKind::free_slip), Precision::float64);
    expect_identical(packing, partition, walled_except((axis + 1) % 3, FaceKind::no_slip),
                     Precision::float64);
  }
}

TEST(Halo, SendsOnlyPopulationsCrossingTheFaces) {
  // An all-fluid periodic box split in two along x1: each rank receives, through each of its two
  // x1 faces, the 5 populations with c_x = +-1 of every node of the face (8 x 6 nodes).
  h5::VoxelImage open;
  open.shape = {10, 8, 6};
  open.phase.assign(open.size(), 0);
  const Partition partition = make_partition(shape_of(open), Index3{world.size(), 1, 1}, world.rank());
  const Topology topology = build_topology(open.phase, partition, all_periodic, world);
  const std::int64_t expected = world.size() == 1 ? 0 : 2 * 5 * 8 * 6;
  EXPECT_EQ(topology.n_ghost, expected);
}

} // namespace
} // namespace aniso::lbm
