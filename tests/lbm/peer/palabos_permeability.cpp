// The permeability of a periodic voxel image along one axis by Palabos (Debian libplb-dev, Palabos
// 1.5), as an independent check of aniso-lbm's periodic body-force method on the same image
// (docs/methods/lbm.md, eq. (kij)): D3Q19 BGK with Guo's forcing, halfway bounce-back on the solid
// voxels, every face periodic, a body force g along the axis; run until the mean velocity changes
// by less than TOL of itself per 100 steps; then K = nu <u> / g in voxels^2, <u> the superficial
// velocity (the mean over every node, the solid ones at zero). Built by build.sh beside it.
//
// usage: palabos_permeability GEOMETRY.txt NX NY NZ AXIS TAU FORCE MAX_STEPS TOL
//   GEOMETRY.txt: NX*NY*NZ integers 0 (fluid) / 1 (solid), x slowest (image_to_palabos.py);
//   AXIS 0, 1 or 2. Prints one line: axis, steps, <u>, K_lattice, converged.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "palabos3D.h"
#include "palabos3D.hh"

using namespace plb;
using T = double;
#define DESCRIPTOR descriptors::ForcedD3Q19Descriptor

int main(int argc, char* argv[]) {
  plbInit(&argc, &argv);
  if (argc != 10) {
    pcout << "usage: palabos_permeability GEOMETRY.txt NX NY NZ AXIS TAU FORCE MAX_STEPS TOL" << std::endl;
    return 2;
  }
  const plint nx = std::atol(argv[2]), ny = std::atol(argv[3]), nz = std::atol(argv[4]);
  const int axis = std::atoi(argv[5]);
  const T tau = std::atof(argv[6]), force = std::atof(argv[7]), tolerance = std::atof(argv[9]);
  const long max_steps = std::atol(argv[8]);
  if (axis < 0 || axis > 2 || tau <= 0.5 || force <= 0) {
    pcout << "palabos_permeability: AXIS must be 0-2, TAU > 1/2, FORCE > 0" << std::endl;
    return 2;
  }
  MultiScalarField3D<int> geometry(nx, ny, nz);
  plb_ifstream file(argv[1]);
  if (!file.is_open()) {
    pcout << "palabos_permeability: cannot open " << argv[1] << std::endl;
    return 2;
  }
  file >> geometry;
  MultiBlockLattice3D<T, DESCRIPTOR> lattice(nx, ny, nz,
                                             new GuoExternalForceBGKdynamics<T, DESCRIPTOR>(1 / tau));
  lattice.periodicity().toggleAll(true);
  defineDynamics(lattice, geometry, new BounceBack<T, DESCRIPTOR>(), 1);
  Array<T, 3> g((T)0, (T)0, (T)0);
  g[axis] = force;
  setExternalVector(lattice, lattice.getBoundingBox(), DESCRIPTOR<T>::ExternalField::forceBeginsAt, g);
  initializeAtEquilibrium(lattice, lattice.getBoundingBox(), (T)1, Array<T, 3>((T)0, (T)0, (T)0));
  lattice.initialize();
  const T nu = (tau - 0.5) / 3;
  T previous = 0, mean = 0;
  long step = 0;
  bool converged = false;
  while (step < max_steps && !converged) {
    for (int s = 0; s < 100; ++s)
      lattice.collideAndStream();
    step += 100;
    mean = computeAverage(*computeVelocityComponent(lattice, lattice.getBoundingBox(), axis));
    converged = step > 100 && std::fabs(mean - previous) <= tolerance * std::fabs(mean);
    previous = mean;
    if (step % 1000 == 0) pcout << "step " << step << " <u> " << mean << std::endl;
  }
  char line[256];
  std::snprintf(line, sizeof line, "axis %d steps %ld mean_velocity %.10g K_lattice %.10g converged %d", axis,
                step, double(mean), double(nu * mean / force), int(converged));
  pcout << line << std::endl;
  return converged ? 0 : 3;
}
