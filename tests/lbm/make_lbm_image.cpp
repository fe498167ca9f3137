// Writes an analytic voxel image for the LBM tests, benchmarks and charts:
//   make_lbm_image sphere_array OUT.h5 --side N --solid-fraction PHI [--voxel-size H]
//   make_lbm_image random OUT.h5 --side N --radius R --solid-fraction PHI [--seed S] [--voxel-size H]
#include "common/h5/image.hpp"
#include "common/h5/provenance.hpp"
#include "lbm/geometry.hpp"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  using namespace aniso;
  mpi::Environment environment(argc, argv);
  CLI::App app{"make_lbm_image: analytic voxel images (simple cubic sphere array, random spheres)"};
  std::string kind, path;
  int side = 32;
  double phi = 0.2, radius = 5, voxel_size = 1e-5;
  unsigned seed = 1;
  app.add_option("kind", kind, "sphere_array or random")
      ->required()
      ->check(CLI::IsMember({"sphere_array", "random"}));
  app.add_option("output", path, "image file (HDF5)")->required();
  app.add_option("--side", side, "cube side [voxels]")->check(CLI::Range(4, 2048));
  app.add_option("--solid-fraction", phi, "solid fraction")->check(CLI::Range(0.001, 0.85));
  app.add_option("--radius", radius, "random: sphere radius [voxels]")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "random: seed");
  app.add_option("--voxel-size", voxel_size, "voxel edge [m]")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  h5::VoxelImage image = kind == "sphere_array" ? lbm::sphere_array_matching(side, phi)
                                                : lbm::random_spheres({side, side, side}, radius, phi, seed);
  image.voxel_size = voxel_size;
  const mpi::Comm comm = mpi::Comm::world();
  const auto provenance = h5::make_provenance("make_lbm_image", "", "make_lbm_image " + kind, comm);
  if (comm.is_root()) h5::write_voxel_image(path, image, provenance);
  return 0;
}
