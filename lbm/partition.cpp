#include "lbm/partition.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <petscdmda.h>

namespace aniso::lbm {
namespace {

void check_petsc(PetscErrorCode code, const char* what) {
  if (code != 0) throw Error(ExitCode::internal_error, fmt::format("PETSc call {} failed", what));
}

/// Builds the partition from the voxel counts each process coordinate owns along each axis.
Partition from_ownership(const Index3& shape, const std::array<std::vector<int>, 3>& counts, int rank) {
  Partition partition;
  partition.global_shape = shape;
  Index3 coords{};
  int rest = rank;
  for (std::size_t a = 0; a < 3; ++a) {
    partition.procs[a] = static_cast<int>(counts[a].size());
    coords[a] = rest % partition.procs[a];
    rest /= partition.procs[a];
    partition.coord_of[a].reserve(static_cast<std::size_t>(shape[a]));
    int start = 0;
    for (int p = 0; p < partition.procs[a]; ++p) {
      if (p == coords[a]) {
        partition.lo[a] = start;
        partition.count[a] = counts[a][static_cast<std::size_t>(p)];
      }
      for (int k = 0; k < counts[a][static_cast<std::size_t>(p)]; ++k)
        partition.coord_of[a].push_back(p);
      start += counts[a][static_cast<std::size_t>(p)];
    }
    check_invariant(start == shape[a], "ownership counts cover the axis");
  }
  return partition;
}

} // namespace

Partition make_partition(const Index3& shape, const Faces& faces, const mpi::Comm& comm) {
  const auto boundary = [&](std::size_t a) {
    return faces[a] == FaceKind::periodic ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_NONE;
  };
  // One degree of freedom per voxel: the DMDA only lays out the boxes; the
  // populations live in our own fluid-only arrays (lbm/topology.hpp).
  DM da = nullptr;
  check_petsc(DMDACreate3d(comm.raw(), boundary(0), boundary(1), boundary(2), DMDA_STENCIL_BOX, shape[0],
                           shape[1], shape[2], PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, 1, 1, nullptr,
                           nullptr, nullptr, &da),
              "DMDACreate3d");
  struct Destroy {
    DM* da;
    ~Destroy() { static_cast<void>(DMDestroy(da)); }
  } destroy{&da};
  check_petsc(DMSetFromOptions(da), "DMSetFromOptions");
  if (DMSetUp(da) != 0)
    throw InputError(fmt::format("cannot decompose a {}x{}x{} image over {} MPI ranks (PETSc DMDA refused: "
                                 "each rank needs at least one voxel layer per axis); use fewer ranks",
                                 shape[0], shape[1], shape[2], comm.size()));
  PetscInt m = 0, n = 0, p = 0;
  check_petsc(DMDAGetInfo(da, nullptr, nullptr, nullptr, nullptr, &m, &n, &p, nullptr, nullptr, nullptr,
                          nullptr, nullptr, nullptr),
              "DMDAGetInfo");
  const PetscInt* lx = nullptr;
  const PetscInt* ly = nullptr;
  const PetscInt* lz = nullptr;
  check_petsc(DMDAGetOwnershipRanges(da, &lx, &ly, &lz), "DMDAGetOwnershipRanges");
  std::array<std::vector<int>, 3> counts{std::vector<int>(lx, lx + m), std::vector<int>(ly, ly + n),
                                         std::vector<int>(lz, lz + p)};
  Partition partition = from_ownership(shape, counts, comm.rank());
  PetscInt xs = 0, ys = 0, zs = 0, xm = 0, ym = 0, zm = 0;
  check_petsc(DMDAGetCorners(da, &xs, &ys, &zs, &xm, &ym, &zm), "DMDAGetCorners");
  check_invariant(partition.lo == Index3{static_cast<int>(xs), static_cast<int>(ys), static_cast<int>(zs)} &&
                      partition.count ==
                          Index3{static_cast<int>(xm), static_cast<int>(ym), static_cast<int>(zm)},
                  "DMDA corners match the rank order");
  return partition;
}

Partition make_partition(const Index3& shape, const Index3& procs, int rank) {
  std::array<std::vector<int>, 3> counts;
  for (std::size_t a = 0; a < 3; ++a) {
    require_input(
        procs[a] >= 1 && procs[a] <= shape[a],
        fmt::format("cannot split {} voxels over {} ranks along axis {}", shape[a], procs[a], a + 1));
    for (int k = 0; k < procs[a]; ++k)
      counts[a].push_back(shape[a] / procs[a] + (k < shape[a] % procs[a] ? 1 : 0));
  }
  return from_ownership(shape, counts, rank);
}

} // namespace aniso::lbm
