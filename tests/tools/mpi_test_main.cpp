// GoogleTest main for every aniso test: initializes MPI (a single process is a
// valid MPI job) and lets only rank 0 print, so that mpiexec -n N output stays readable.
#include "common/mpi.hpp"

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  aniso::mpi::Environment environment(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Death tests fork; "threadsafe" re-executes the binary, which is safer under MPI.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  if (!aniso::mpi::Comm::world().is_root()) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int failed = RUN_ALL_TESTS();
  // Every rank must agree: a failure on rank 1 fails the whole test.
  const bool any_failed = aniso::mpi::Comm::world().any(failed != 0);
  return any_failed ? 1 : 0;
}
