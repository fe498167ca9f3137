// LBM throughput: MLUPS (all voxels) and MFLUPS (fluid voxels) of the D3Q19 TRT
// step on a packing image, median of several repetitions, next to the memory
// bandwidth measured in the same run by a STREAM-like triad and the
// bandwidth-bound limit it implies (D3Q19: 19 values read and 19 written per
// fluid node = 304 bytes in double, 152 in float). Never asserts a time;
// docs/performance.md records the results.
//
// usage: [mpiexec -n N] bench_lbm [--image IMAGE.h5 | --side N --radius R --solid-fraction PHI]
//                                 [--steps S] [--repeats K] [--precision double|float]
//                                 [--instruction-set auto|baseline|x86-64-v3|x86-64-v4]
#include "common/error.hpp"
#include "common/h5/image.hpp"
#include "common/log.hpp"
#include "lbm/flow.hpp"
#include "lbm/geometry.hpp"
#include "lbm/partition.hpp"
#include "lbm/petsc_session.hpp"
#include "lbm/topology.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <vector>

namespace {

/// STREAM triad a = b + s c over arrays far larger than the caches; bytes/s of this rank (3 x 8 bytes per
/// element, write-allocate not counted, as STREAM reports it). Median of `repeats`.
double triad_bandwidth(std::size_t n, int repeats) {
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const double s = 3.0 + r;
    for (std::size_t i = 0; i < n; ++i)
      a[i] = b[i] + s * c[i];
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    b[r % n] = a[(r * 7) % n]; // keeps the loop from being optimized away
  }
  std::sort(seconds.begin(), seconds.end());
  return 3.0 * 8.0 * static_cast<double>(n) / seconds[seconds.size() / 2];
}

} // namespace

void run_benchmark(const std::string& image_path, int side, double radius, double phi, int steps, int repeats,
                   const std::string& precision, aniso::lbm::InstructionSet level,
                   const aniso::mpi::Comm& comm);

int main(int argc, char** argv) {
  using namespace aniso;
  mpi::Environment environment(argc, argv);
  const mpi::Comm comm = mpi::Comm::world();
  CLI::App app{"bench_lbm: D3Q19 TRT throughput against the triad bandwidth limit"};
  std::string image_path, precision = "double";
  int side = 128, steps = 200, repeats = 5;
  double radius = 10.0, phi = 0.6;
  app.add_option("--image", image_path, "voxel image (default: random spheres)");
  app.add_option("--side", side, "random-sphere cube side [voxels]")->check(CLI::Range(8, 2048));
  app.add_option("--radius", radius, "sphere radius [voxels] (20 voxels per D50: 10)")
      ->check(CLI::PositiveNumber);
  app.add_option("--solid-fraction", phi, "solid fraction of the random spheres")
      ->check(CLI::Range(0.05, 0.85));
  app.add_option("--steps", steps, "timed steps per repetition")->check(CLI::Range(1, 1000000));
  app.add_option("--repeats", repeats, "repetitions (median reported)")->check(CLI::Range(1, 100));
  app.add_option("--precision", precision, "double or float")->check(CLI::IsMember({"double", "float"}));
  const std::map<std::string, lbm::InstructionSet> levels{{"auto", lbm::InstructionSet::automatic},
                                                          {"baseline", lbm::InstructionSet::baseline},
                                                          {"x86-64-v3", lbm::InstructionSet::x86_64_v3},
                                                          {"x86-64-v4", lbm::InstructionSet::x86_64_v4}};
  lbm::InstructionSet level = lbm::InstructionSet::automatic;
  app.add_option("--instruction-set", level, "x86-64 level of the step (lbm.instruction_set)")
      ->transform(CLI::CheckedTransformer(levels));
  CLI11_PARSE(app, argc, argv);
  try {
    run_benchmark(image_path, side, radius, phi, steps, repeats, precision, level, comm);
  } catch (const Error& error) {
    std::fprintf(stderr, "bench_lbm: %s\n", error.what());
    return static_cast<int>(error.code());
  }
  return 0;
}

void run_benchmark(const std::string& image_path, int side, double radius, double phi, int steps, int repeats,
                   const std::string& precision, aniso::lbm::InstructionSet level,
                   const aniso::mpi::Comm& comm) {
  using namespace aniso;
  const lbm::PetscSession petsc;

  const h5::VoxelImage image = image_path.empty() ? lbm::random_spheres({side, side, side}, radius, phi, 7)
                                                  : h5::read_voxel_image(image_path);
  const lbm::Index3 shape{static_cast<int>(image.shape[0]), static_cast<int>(image.shape[1]),
                          static_cast<int>(image.shape[2])};
  const lbm::Partition partition = lbm::make_partition(shape, lbm::all_periodic, comm);
  const lbm::Topology topology = lbm::build_topology(image.phase, partition, lbm::all_periodic, comm);

  lbm::FlowSettings settings;
  settings.precision = precision == "float" ? lbm::Precision::float32 : lbm::Precision::float64;
  settings.force = Vec3(1e-6, 0, 0);
  settings.instruction_set = lbm::resolve_instruction_set(level);
  settings.fixed_steps = true;
  settings.max_steps = steps;
  settings.check_interval = steps;
  std::vector<double> seconds, cpu_seconds;
  for (int r = 0; r < repeats; ++r) {
    comm.barrier();
    const std::clock_t cpu_start = std::clock();
    const lbm::FlowResult result = lbm::run_flow(topology, settings, comm, make_silent_logger());
    seconds.push_back(comm.max(result.seconds));
    cpu_seconds.push_back(comm.max(static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC));
  }
  // CPU time tells how much of the wall time the process actually ran (shared machines).
  std::sort(cpu_seconds.begin(), cpu_seconds.end());
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  comm.barrier();
  const double bandwidth = comm.sum_exact(triad_bandwidth(std::size_t{1} << 25, 7));
  const double bytes_per_node = settings.precision == lbm::Precision::float32 ? 152.0 : 304.0;
  const double mflups = static_cast<double>(topology.n_fluid_global) * steps / median * 1e-6;
  const double mlups = static_cast<double>(topology.n_voxels_global) * steps / median * 1e-6;
  const double limit = bandwidth / bytes_per_node * 1e-6;
  if (comm.is_root())
    std::printf(
        "ranks %d image %dx%dx%d fluid %.4f precision %s level %s steps %d repeats %d median %.4f s (min "
        "%.4f max "
        "%.4f): %.2f MLUPS, %.2f MFLUPS (cpu median %.4f s); triad %.2f GB/s -> limit %.1f MFLUPS; %.1f%% of "
        "the limit\n",
        comm.size(), shape[0], shape[1], shape[2],
        static_cast<double>(topology.n_fluid_global) / static_cast<double>(topology.n_voxels_global),
        precision.c_str(), std::string(lbm::instruction_set_name(settings.instruction_set)).c_str(), steps,
        repeats, median, seconds.front(), seconds.back(), mlups, mflups, cpu_seconds[cpu_seconds.size() / 2],
        bandwidth * 1e-9, limit, 100.0 * mflups / limit);
}
