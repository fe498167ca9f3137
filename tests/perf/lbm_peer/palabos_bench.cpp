// Palabos peer benchmark (Debian libplb-dev, Palabos 1.5): D3Q19 TRT with
// bounce-back solid nodes on the same periodic image aniso's bench_lbm times,
// timed collideAndStream() steps; prints MLUPS (all nodes) and MFLUPS (fluid
// nodes). Built by build.sh against the Debian package; see README.md.
//
// usage: [mpiexec -n N] palabos_bench GEOMETRY.txt NX NY NZ STEPS REPEATS [double|float]
//   GEOMETRY.txt: NX*NY*NZ integers 0 (fluid) / 1 (solid), x slowest, z fastest (Palabos order).
#include <algorithm>
#include <cstdlib>
#include <vector>

#include "palabos3D.h"
#include "palabos3D.hh"

using namespace plb;

template <typename T> int run(const std::string& path, plint nx, plint ny, plint nz, int steps, int repeats) {
  const T omega = 1.0;
  MultiScalarField3D<int> geometry(nx, ny, nz);
  plb_ifstream file(path.c_str());
  if (!file.is_open()) {
    pcout << "cannot open " << path << std::endl;
    return 2;
  }
  file >> geometry;
  MultiBlockLattice3D<T, descriptors::D3Q19Descriptor> lattice(
      nx, ny, nz, new TRTdynamics<T, descriptors::D3Q19Descriptor>(omega));
  lattice.periodicity().toggleAll(true);
  defineDynamics(lattice, geometry, new BounceBack<T, descriptors::D3Q19Descriptor>(), 1);
  initializeAtEquilibrium(lattice, lattice.getBoundingBox(), (T)1, Array<T, 3>((T)0, (T)0, (T)0));
  lattice.initialize();
  const T solid = computeSum(geometry);
  const double fluid = double(nx * ny * nz) - double(solid);
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    global::timer("lbm").restart();
    for (int s = 0; s < steps; ++s)
      lattice.collideAndStream();
    seconds.push_back(global::timer("lbm").stop());
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  pcout << "palabos ranks " << global::mpi().getSize() << " image " << nx << "x" << ny << "x" << nz
        << " fluid " << fluid / double(nx * ny * nz) << " steps " << steps << " repeats " << repeats
        << " median " << median << " s: " << double(nx * ny * nz) * steps / median * 1e-6 << " MLUPS, "
        << fluid * steps / median * 1e-6 << " MFLUPS" << std::endl;
  return 0;
}

int main(int argc, char* argv[]) {
  plbInit(&argc, &argv);
  if (argc < 7) {
    pcout << "usage: palabos_bench GEOMETRY.txt NX NY NZ STEPS REPEATS [double|float]" << std::endl;
    return 2;
  }
  const std::string precision = argc > 7 ? argv[7] : "double";
  const plint nx = std::atol(argv[2]), ny = std::atol(argv[3]), nz = std::atol(argv[4]);
  const int steps = std::atoi(argv[5]), repeats = std::atoi(argv[6]);
  if (precision == "float") return run<float>(argv[1], nx, ny, nz, steps, repeats);
  return run<double>(argv[1], nx, ny, nz, steps, repeats);
}
