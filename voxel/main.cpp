// aniso-voxel: digitize a checkpoint and measure the void space by ball, spar and disk openings (section 3).
#include "common/cli.hpp"
#include "common/stage_stub.hpp"

int main(int argc, char** argv) {
  return aniso::cli::run(
      argc, argv, "aniso-voxel", [](int argc_, char** argv_, const aniso::mpi::Comm& comm) {
        return aniso::cli::run_pending_stage(
            argc_, argv_, comm,
            {"aniso-voxel",
             "digitize a checkpoint and measure the void space by ball, spar and disk openings (section 3)",
             "voxel", aniso::cli::InputKind::checkpoint, 7});
      });
}
