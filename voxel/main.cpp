// aniso-voxel: digitize a checkpoint and measure the void space by ball, spar and disk openings
// (Kuhn, Sun & Wang 2015, section 3). Writes <output_dir>/image_<stem>.h5 (+ .xmf) and
// <output_dir>/voids_<stem>.h5 / .csv; docs/methods/voxel.md.
#include "common/cli.hpp"
#include "voxel/stage.hpp"

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-voxel", aniso::voxel::run_voxel_stage);
}
