// Results do not depend on the number of ranks: the measures computed on every rank of the
// world communicator are bit-identical to those computed by one process alone.
#include "fabric/measures.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "synthetic.hpp"

namespace aniso::fabric {
namespace {

TEST(FabricRanks, WorldAndSelfGiveIdenticalBits) {
  const mpi::Comm world = mpi::Comm::world(), self(MPI_COMM_SELF);
  test::LatticeSpec spec;
  spec.kind = test::Lattice::fcc;
  spec.cells = 3;
  spec.spacing = 0.86e-3;
  spec.stretch = Vec3(0.99, 1.0, 1.01);
  spec.jitter = 0.01;
  spec.random_orientations = true;
  const h5::Checkpoint c = test::lattice_checkpoint(spec);
  // Every rank writes its own copy so that the content hash can be read locally.
  const std::string path = ::testing::TempDir() + "ranks_" + std::to_string(world.rank()) + ".h5";
  h5::write_checkpoint(path, c, test::test_provenance(), self);
  const FabricMeasures parallel = measure_fabric(c, path, FabricConfig{}, world);
  const FabricMeasures serial = measure_fabric(c, path, FabricConfig{}, self);
  ASSERT_GT(parallel.n_triples, 0);
  const auto ts = serial.tensors(), tp = parallel.tensors();
  for (std::size_t k = 0; k < ts.size(); ++k)
    EXPECT_EQ(std::memcmp(ts[k].value.data(), tp[k].value.data(), sizeof(double) * 9), 0) << ts[k].name;
  const auto ss = serial.scalars(), sp = parallel.scalars();
  for (std::size_t k = 0; k < ss.size(); ++k)
    EXPECT_EQ(std::memcmp(&ss[k].value, &sp[k].value, sizeof(double)), 0) << ss[k].name;
}

} // namespace
} // namespace aniso::fabric
