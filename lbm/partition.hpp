#pragma once
// Block decomposition of the image over MPI ranks, laid out by a PETSc DMDA
// (so -da_processors_x/y/z and the rest of the options database apply).
// Each rank owns one box of voxels; owner() answers for any voxel, which the
// halo set-up uses to know whom to ask for a population.

#include "common/mpi.hpp"
#include "lbm/boundary.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace aniso::lbm {

using Index3 = std::array<int, 3>;

struct Partition {
  Index3 global_shape{};                    ///< voxels along x1, x2, x3
  Index3 lo{};                              ///< first voxel of this rank's box
  Index3 count{};                           ///< voxels of this rank's box along each axis
  Index3 procs{1, 1, 1};                    ///< ranks along each axis
  std::array<std::vector<int>, 3> coord_of; ///< per axis: process coordinate that owns each voxel index

  /// Rank owning a voxel (coordinates inside the global box), in the DMDA's order (x1 fastest).
  [[nodiscard]] int owner(const Index3& cell) const {
    return coord_of[0][static_cast<std::size_t>(cell[0])] +
           procs[0] * (coord_of[1][static_cast<std::size_t>(cell[1])] +
                       procs[1] * coord_of[2][static_cast<std::size_t>(cell[2])]);
  }
  [[nodiscard]] bool is_local(const Index3& cell) const {
    for (std::size_t a = 0; a < 3; ++a)
      if (cell[a] < lo[a] || cell[a] >= lo[a] + count[a]) return false;
    return true;
  }
};

/// Decomposes `shape` over the ranks of comm with a DMDA (collective; PETSc must be initialized).
/// InputError if an axis is too short for the number of ranks along it.
Partition make_partition(const Index3& shape, const Faces& faces, const mpi::Comm& comm);

/// The same decomposition computed without PETSc for a given process grid (tests and tools).
Partition make_partition(const Index3& shape, const Index3& procs, int rank);

} // namespace aniso::lbm
