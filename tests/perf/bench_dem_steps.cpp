// DEM throughput: particle-steps and contact-steps per second of biaxial loading
// from a checkpoint, median of several repetitions, each from the same restored
// state. Never asserts a time; docs/performance.md records the results.
//
// usage: [mpiexec -n N] bench_dem_steps CHECKPOINT.h5 [STEPS=2000] [REPEATS=5]
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/protocol/load.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
  using namespace aniso;
  mpi::Environment environment(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CHECKPOINT.h5 [STEPS] [REPEATS]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const long n_steps = argc > 2 ? std::atol(argv[2]) : 2000;
  const int n_repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, mpi::Comm(MPI_COMM_SELF));
  dem::DemConfig config; // defaults: the paper's loading
  config.particles.d50 = h5::parameter(checkpoint, h5::parameter_name::d50, path);
  std::vector<double> seconds;
  double contacts = 0;
  for (int repeat = 0; repeat < n_repeats; ++repeat) {
    dem::Simulation simulation = dem::io::from_checkpoint(checkpoint, path, mpi::Comm::world());
    dem::protocol::start_loading(simulation, config);
    const auto start = std::chrono::steady_clock::now();
    for (long step = 0; step < n_steps; ++step)
      simulation.step();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    contacts = static_cast<double>(simulation.measure().n_contacts);
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  const double n_particles = static_cast<double>(checkpoint.particles.size());
  if (!mpi::Comm::world().is_root()) return 0;
  std::printf("ranks %d particles %.0f contacts %.0f steps %ld repeats %d median %.4f s (min %.4f max %.4f): "
              "%.4g particle-steps/s, %.4g contact-steps/s\n",
              mpi::Comm::world().size(), n_particles, contacts, n_steps, n_repeats, median, seconds.front(),
              seconds.back(), n_particles * static_cast<double>(n_steps) / median,
              contacts * static_cast<double>(n_steps) / median);
  return 0;
}
