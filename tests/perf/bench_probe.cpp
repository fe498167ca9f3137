// Cost of one probe (seven forks at the default settings) against its peer, the same
// number of plain DEM steps of biaxial loading from the same restored state: the ratio is
// the probe's overhead (seven restores, controller switches, stress readings). Medians of
// several repetitions measured in the same run; never asserts a time (docs/performance.md).
//
// usage: [mpiexec -n N] bench_probe CHECKPOINT.h5 [REPEATS=5]
#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/timer.hpp"
#include "dem/config.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/protocol/load.hpp"
#include "probe/schedule.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
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
  const int n_repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  const mpi::Comm comm = mpi::Comm::world();
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, comm);
  const probe::ProbeConfig config; // the defaults
  dem::DemConfig load_config;
  load_config.particles.d50 = h5::parameter(checkpoint, h5::parameter_name::d50, path);
  std::vector<double> probe_seconds, peer_seconds;
  std::int64_t steps = 0;
  for (int repeat = 0; repeat < n_repeats; ++repeat) {
    auto start = std::chrono::steady_clock::now();
    const auto forks = probe::run_all_forks(checkpoint, path, config, comm, make_silent_logger());
    probe_seconds.push_back(seconds_since(start));
    steps = probe::n_fork_files * 2 * (forks[1].half_steps + forks[1].hold_steps);
    // The peer: one restore and the same number of loading steps.
    start = std::chrono::steady_clock::now();
    dem::Simulation simulation = dem::io::from_checkpoint(checkpoint, path, comm);
    dem::protocol::start_loading(simulation, load_config);
    for (std::int64_t step = 0; step < steps; ++step)
      simulation.step();
    peer_seconds.push_back(seconds_since(start));
  }
  if (!comm.is_root()) return 0;
  const double probe_median = median(probe_seconds), peer_median = median(peer_seconds);
  std::printf("ranks %d particles %zu: probe (7 forks, %lld steps) median %.3f s (min %.3f max %.3f); "
              "peer (%lld loading steps) median %.3f s (min %.3f max %.3f); ratio %.2f\n",
              comm.size(), checkpoint.particles.size(), static_cast<long long>(steps), probe_median,
              *std::min_element(probe_seconds.begin(), probe_seconds.end()),
              *std::max_element(probe_seconds.begin(), probe_seconds.end()), static_cast<long long>(steps),
              peer_median, *std::min_element(peer_seconds.begin(), peer_seconds.end()),
              *std::max_element(peer_seconds.begin(), peer_seconds.end()), probe_median / peer_median);
  return 0;
}
