// aniso-lbm: D3Q19 lattice Boltzmann permeability tensor of a voxel image (section 6).
#include "common/cli.hpp"
#include "common/stage_stub.hpp"

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-lbm", [](int argc_, char** argv_, const aniso::mpi::Comm& comm) {
    return aniso::cli::run_pending_stage(
        argc_, argv_, comm,
        {"aniso-lbm", "D3Q19 lattice Boltzmann permeability tensor of a voxel image (section 6)", "lbm",
         aniso::cli::InputKind::hdf5_file, 8});
  });
}
