// DEM throughput: particle-steps and contact-steps per second from a checkpoint,
// median of several repetitions, each from the same restored state. MODE `hold`
// (the default) keeps the cell fixed, the static box the peers of tests/perf/dem_peer
// integrate, so that every code does the same work on the same state; `load` runs
// the biaxial loading (deforming cell, servo). Never asserts a time;
// docs/performance.md records the results.
//
// usage: [mpiexec -n N] bench_dem_steps CHECKPOINT.h5 [STEPS=2000] [REPEATS=5] [hold|load]
#include "common/cli.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/protocol/load.hpp"
#include "dem/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

int run_bench(int argc, char** argv, const aniso::mpi::Comm& /*world*/) {
  using namespace aniso;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CHECKPOINT.h5 [STEPS] [REPEATS]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const long n_steps = argc > 2 ? std::atol(argv[2]) : 2000;
  const int n_repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  const std::string mode = argc > 4 ? argv[4] : "hold";
  if (mode != "hold" && mode != "load") {
    std::fprintf(stderr, "%s: MODE must be hold or load, not '%s'\n", argv[0], mode.c_str());
    return 2;
  }
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, mpi::Comm(MPI_COMM_SELF));
  dem::DemConfig config; // defaults: the paper's loading
  config.particles.d50 = h5::parameter(checkpoint, h5::parameter_name::d50, path);
  std::vector<double> seconds;
  double contacts = 0;
  for (int repeat = 0; repeat < n_repeats; ++repeat) {
    dem::Simulation simulation = dem::io::from_checkpoint(checkpoint, path, mpi::Comm::world());
    // hold: every axis at zero strain rate, as a loading's cell control would set it
    if (mode == "load")
      dem::protocol::start_loading(simulation, config);
    else
      simulation.set_control(dem::model::fixed_cell(simulation.control()));
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
  std::printf(
      "mode %s ranks %d particles %.0f contacts %.0f steps %ld repeats %d median %.4f s (min %.4f max %.4f): "
      "%.4g particle-steps/s, %.4g contact-steps/s\n",
      mode.c_str(), mpi::Comm::world().size(), n_particles, contacts, n_steps, n_repeats, median,
      seconds.front(), seconds.back(), n_particles * static_cast<double>(n_steps) / median,
      contacts * static_cast<double>(n_steps) / median);
  return 0;
}

} // namespace

// A missing or unreadable checkpoint ends with a message and an exit code, not an abort.
int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "bench_dem_steps", run_bench);
}
