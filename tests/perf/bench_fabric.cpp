// Fabric throughput: every measure of one checkpoint (aniso-fabric's measure_fabric), median
// of several repetitions on one process; the checkpoint read is timed apart. Never asserts a
// time; docs/performance.md records the results.
//
// usage: bench_fabric CHECKPOINT.h5 [REPEATS=9]
#include "common/h5/checkpoint.hpp"
#include "common/timer.hpp"
#include "fabric/measures.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

} // namespace

int main(int argc, char** argv) {
  using namespace aniso;
  mpi::Environment environment(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CHECKPOINT.h5 [REPEATS]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const int n_repeats = argc > 2 ? std::atoi(argv[2]) : 9;
  const mpi::Comm self(MPI_COMM_SELF);
  std::vector<double> read, measure;
  fabric::FabricMeasures m;
  for (int repeat = 0; repeat < n_repeats; ++repeat) {
    auto start = std::chrono::steady_clock::now();
    const h5::Checkpoint checkpoint = h5::read_checkpoint(path, self);
    read.push_back(seconds_since(start));
    start = std::chrono::steady_clock::now();
    m = fabric::measure_fabric(checkpoint, path, fabric::FabricConfig{}, self);
    measure.push_back(seconds_since(start));
  }
  std::printf("checkpoint %s: %lld particles, %lld contacts (%lld strong), N3 %lld, N4 %lld\n", path.c_str(),
              static_cast<long long>(m.n_particles), static_cast<long long>(m.n_contacts),
              static_cast<long long>(m.n_strong), static_cast<long long>(m.n_triples),
              static_cast<long long>(m.n_quadruples));
  std::printf("read_checkpoint: median %.4f s (min %.4f, max %.4f) over %d runs\n", median(read),
              *std::min_element(read.begin(), read.end()), *std::max_element(read.begin(), read.end()),
              n_repeats);
  std::printf("measure_fabric:  median %.4f s (min %.4f, max %.4f) over %d runs\n", median(measure),
              *std::min_element(measure.begin(), measure.end()),
              *std::max_element(measure.begin(), measure.end()), n_repeats);
  std::printf("F_11 %.6f  H_strong_11 %.6f  p %.6g Pa  chi_torus %.0f\n", m.F(0, 0), m.H_strong(0, 0),
              m.mean_stress, m.chi_torus);
  return 0;
}
