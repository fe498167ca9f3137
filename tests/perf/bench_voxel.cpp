// Voxel stage throughput: digitization and each opening family (spar, ball, disk: every size)
// and the Euler characteristic, on a checkpoint tiled periodically to the wanted size, at one
// resolution; medians of several repetitions; peak RSS. Never asserts a time; docs/performance.md
// records the results. Optionally writes the image for the scipy/scikit-image peer
// (bench_voxel_peer.py), which compares its openings with ours voxel count for voxel count.
//
// usage: bench_voxel CHECKPOINT.h5 [--tiles A B C] [--resolution R] [--repeats N] [--threads T]
//                    [--image OUT.h5] [--skip-families] [--radius-step S (default 0: every distinct element)]
#include "common/h5/checkpoint.hpp"
#include "common/h5/image.hpp"
#include "common/memory.hpp"
#include "common/mpi.hpp"
#include "voxel/digitize.hpp"
#include "voxel/euler.hpp"
#include "voxel/openings.hpp"
#include "voxel/void_analysis.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <omp.h>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace {

using namespace aniso;

// Wall and CPU (all threads) seconds of one run; medians over repetitions. The CPU time shows
// what the work costs when the machine is shared (wall > CPU / threads).
struct Seconds {
  double wall = 0;
  double cpu = 0;
};

double cpu_now() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_utime.tv_usec) +
         static_cast<double>(usage.ru_stime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_stime.tv_usec);
}

Seconds median_seconds(int repeats, const std::function<void()>& work) {
  std::vector<Seconds> runs;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = cpu_now();
    work();
    runs.push_back({std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                    cpu_now() - cpu_start});
  }
  std::sort(runs.begin(), runs.end(), [](const Seconds& a, const Seconds& b) { return a.wall < b.wall; });
  return runs[runs.size() / 2];
}

// Every size of one round family (ball: axes all; disk: a plane) after its distance map, with the
// radii aniso-voxel uses (voxel.radius_step = step). Returns the number of openings.
std::size_t round_family(const voxel::Grid& grid, const std::vector<std::uint8_t>& phase, voxel::Axes axes,
                         double step) {
  const auto distance = voxel::distance_to_solid(grid, phase, axes);
  std::uint32_t largest = 0;
  for (const auto d2 : distance)
    if (d2 != voxel::infinite_distance) largest = std::max(largest, d2);
  std::vector<std::uint32_t> work;
  const std::vector<double> radii = voxel::opening_radii(step, largest, axes.count);
  for (std::size_t k = 1; k < radii.size(); ++k)
    static_cast<void>(
        voxel::round_opening_volume(grid, distance, axes, voxel::squared_radius(radii[k]), work));
  return radii.size() - 1;
}

} // namespace

int main(int argc, char** argv) {
  mpi::Environment environment(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s CHECKPOINT.h5 [--tiles A B C] [--resolution R] [--repeats N] [--threads T] "
                 "[--image OUT.h5] [--skip-families]\n",
                 argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  std::array<int, 3> tiles{1, 1, 1};
  double resolution = 20;
  int repeats = 3;
  std::string image_path;
  bool families = true;
  double radius_step = 0;
  for (int a = 2; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--tiles" && a + 3 < argc) {
      for (int t = 0; t < 3; ++t)
        tiles[static_cast<std::size_t>(t)] = std::atoi(argv[++a]);
    } else if (arg == "--resolution" && a + 1 < argc) {
      resolution = std::atof(argv[++a]);
    } else if (arg == "--repeats" && a + 1 < argc) {
      repeats = std::atoi(argv[++a]);
    } else if (arg == "--threads" && a + 1 < argc) {
      omp_set_num_threads(std::atoi(argv[++a]));
    } else if (arg == "--image" && a + 1 < argc) {
      image_path = argv[++a];
    } else if (arg == "--radius-step" && a + 1 < argc) {
      radius_step = std::atof(argv[++a]);
    } else if (arg == "--skip-families") {
      families = false;
    } else {
      std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
      return 2;
    }
  }
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, mpi::Comm(MPI_COMM_SELF));
  const double d50 = h5::parameter(checkpoint, h5::parameter_name::d50, path);
  const double splice =
      voxel::find_parameter(checkpoint, h5::parameter_name::splice_angle).value_or(0.785398163397448);
  // The assembly repeated tiles[a] times along each axis: still exactly periodic.
  std::vector<voxel::Body> bodies;
  const std::vector<voxel::Body> cell_bodies = voxel::bodies_of(checkpoint);
  const Vec3 cell = checkpoint.cell.lengths;
  for (int i = 0; i < tiles[0]; ++i)
    for (int j = 0; j < tiles[1]; ++j)
      for (int k = 0; k < tiles[2]; ++k)
        for (voxel::Body body : cell_bodies) {
          body.position += Vec3(i * cell[0], j * cell[1], k * cell[2]);
          bodies.push_back(body);
        }
  const Vec3 lengths(tiles[0] * cell[0], tiles[1] * cell[1], tiles[2] * cell[2]);
  const auto shape = voxel::grid_shape(lengths, d50, resolution);
  const voxel::Grid grid{shape};
  const double voxels = static_cast<double>(grid.size());
  std::printf(
      "checkpoint %s x %d x %d x %d: %zu particles, image %zu x %zu x %zu = %.4g voxels at %g voxels/d50, "
      "%d threads, median of %d\n",
      path.c_str(), tiles[0], tiles[1], tiles[2], bodies.size(), shape[0], shape[1], shape[2], voxels,
      resolution, omp_get_max_threads(), repeats);

  // One line per measured step: wall time, throughput, CPU time of the median run.
  const auto report = [&](const char* name, const Seconds& t, const std::string& extra) {
    std::printf("%-15s %8.3f s  %10.4g voxels/s  cpu %7.3f s  %s\n", name, t.wall, voxels / t.wall, t.cpu,
                extra.c_str());
  };
  std::vector<std::uint8_t> phase;
  report("digitize",
         median_seconds(repeats, [&] { phase = voxel::digitize_bodies(bodies, lengths, shape, splice); }),
         "");
  if (!image_path.empty()) {
    h5::VoxelImage image;
    image.shape = shape;
    image.voxel_size = std::cbrt(lengths.prod() / voxels);
    image.phase = phase;
    h5::Provenance provenance;
    provenance.program = "bench_voxel";
    h5::write_voxel_image(image_path, image, provenance);
  }
  const auto per_size = [&](std::size_t sizes, const Seconds& t) {
    return std::to_string(sizes) + " sizes, " +
           std::to_string(voxels * static_cast<double>(sizes) / t.wall / 1e6) + " M voxel-openings/s";
  };
  if (families) {
    report("euler",
           median_seconds(repeats, [&] { static_cast<void>(voxel::void_euler_characteristic(grid, phase)); }),
           "");
    report("spar x1..x3",
           median_seconds(repeats,
                          [&] {
                            for (int axis = 0; axis < 3; ++axis)
                              static_cast<void>(voxel::void_run_lengths(grid, phase, axis));
                          }),
           "all lengths, three axes");
    std::size_t ball_sizes = 0;
    const Seconds t_ball = median_seconds(
        repeats, [&] { ball_sizes = round_family(grid, phase, voxel::Axes::all(), radius_step); });
    report("ball", t_ball, per_size(ball_sizes, t_ball));
    std::size_t disk_sizes = 0;
    const Seconds t_disk = median_seconds(repeats, [&] {
      disk_sizes = 0;
      for (int axis = 0; axis < 3; ++axis)
        disk_sizes += round_family(grid, phase, voxel::Axes::plane(axis), radius_step);
    });
    report("disk x1..x3", t_disk, per_size(disk_sizes, t_disk));
  }
  voxel::VoidAnalysis analysis;
  voxel::VoidAnalysisOptions options;
  options.radius_step = radius_step;
  const Seconds t_all = median_seconds(
      repeats, [&] { analysis = voxel::analyze_voids(grid, phase, options, mpi::Comm(MPI_COMM_SELF)); });
  report("whole analysis", t_all,
         "ball median " + std::to_string(analysis.ball.median) + " voxels, Euler " +
             std::to_string(analysis.euler));
  std::printf("peak RSS %.0f MiB\n", static_cast<double>(peak_resident_bytes()) / 1048576.0);
  return 0;
}
