// Test helper: writes a synthetic loading series into a folder for the command-line tests:
//   load_000.h5 .. load_005.h5  FCC spheres compressed along x1 (extended along x3) step by step
//   probe_load_00K.h5, voids_load_00K.h5, image_load_00K.h5 + permeability_image_load_00K.h5
//                               (the permeability's source: the image for even K, the checkpoint
//                               for odd K, as aniso-lbm writes it)
//   broken.h5                   a checkpoint whose /contacts/force dataset was removed
// Values of the linked results are smooth functions of the strain with some noise, so that the
// correlations are neither trivial nor undefined.
#include "common/error.hpp"
#include "common/h5/content_hash.hpp"
#include "common/h5/file.hpp"
#include "common/h5/image.hpp"
#include "common/mpi.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

#include "synthetic.hpp"

namespace {

using namespace aniso;

void write_matrix(h5::Group& group, const std::string& name, const Mat3& m, const char* unit) {
  std::vector<double> v(9);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      v[static_cast<std::size_t>(3 * a + b)] = m(a, b);
  group.write_dataset<double>(name, v, {3, 3}, unit, "synthetic");
}

void write_vector(h5::Group& group, const std::string& name, const Vec3& x) {
  group.write_dataset<double>(name, std::vector<double>{x[0], x[1], x[2]}, {3}, "m", "synthetic");
}

void write_linked(const std::string& folder, const std::string& stem, const std::string& checkpoint,
                  double strain, bool image_source, RandomStream& noise) {
  const std::string hash = h5::content_hash(checkpoint);
  {
    h5::File file = h5::File::create(folder + "/probe_" + stem + ".h5");
    h5::Group g = file.create_group("stiffness");
    g.write_attribute("source", checkpoint);
    g.write_attribute("source_hash", hash);
    g.write_attribute_with_units("strain", strain, "1");
    Mat3 C = 1e8 * Mat3::Ones();
    C(0, 0) += 4e8 * (1 + 30 * strain + 0.05 * noise.normal());
    C(1, 1) += 3e8 * (1 + 10 * strain + 0.05 * noise.normal());
    C(2, 2) += 3e8 * (1 - 20 * strain + 0.05 * noise.normal());
    write_matrix(g, "C", C, "Pa");
    g.write_attribute_with_units("K_C", C.sum() / 9.0, "Pa");
  }
  {
    h5::File file = h5::File::create(folder + "/voids_" + stem + ".h5");
    h5::Group g = file.create_group("voids");
    g.write_attribute("source", checkpoint);
    g.write_attribute("source_hash", hash);
    write_vector(g, "free_path_median",
                 1e-4 * Vec3(1 - 5 * strain + 0.01 * noise.normal(), 1.0, 1 + 5 * strain));
    write_vector(g, "breadth_median",
                 3e-5 * Vec3(1 + 3 * strain + 0.01 * noise.normal(), 1.0, 1 - 2 * strain));
  }
  h5::VoxelImage image;
  image.shape = {4, 4, 4};
  image.voxel_size = 1e-4;
  image.phase.assign(64, 0);
  image.phase[0] = 1;
  image.source = checkpoint;
  image.source_hash = hash;
  const std::string image_name = "image_" + stem + ".h5";
  h5::write_voxel_image(folder + "/" + image_name, image, fabric::test::test_provenance());
  h5::File file = h5::File::create(folder + "/permeability_image_" + stem + ".h5");
  h5::Group g = file.create_group("permeability");
  if (image_source) { // the source is the image (relative: found beside the permeability file)
    g.write_attribute("source", image_name);
    g.write_attribute("source_hash", h5::content_hash(folder + "/" + image_name));
  } else { // as aniso-lbm writes it: the image's own source, the checkpoint
    g.write_attribute("source", checkpoint);
    g.write_attribute("source_hash", hash);
  }
  g.write_attribute("method", std::string_view("periodic_body_force"));
  const Mat3 K =
      1e-11 * Vec3(1 + 2 * strain + 0.01 * noise.normal(), 1.0, 1 - 3 * strain).asDiagonal().toDenseMatrix();
  write_matrix(g, "K", K, "m^2");
  write_matrix(g, "K_lattice", K / 1e-8, "1");
}

int write_all(const std::string& folder) {
  const mpi::Comm self(MPI_COMM_SELF);
  std::filesystem::create_directories(folder);
  RandomStream noise(42, 3);
  for (int k = 0; k < 6; ++k) {
    fabric::test::LatticeSpec spec;
    spec.kind = fabric::test::Lattice::fcc;
    spec.cells = 3;
    spec.spacing = 0.985e-3;
    spec.jitter = 0.01;
    spec.seed = 7; // the same arrangement, deformed further at each step
    const double strain = 0.003 * k;
    spec.stretch = Vec3(1 - strain, 1.0, 1 + 0.8 * strain);
    h5::Checkpoint c = fabric::test::lattice_checkpoint(spec);
    c.step = 1000 * (k + 1);
    char stem[32];
    std::snprintf(stem, sizeof stem, "load_%03d", k);
    const std::string path = folder + "/" + stem + ".h5";
    h5::write_checkpoint(path, c, fabric::test::test_provenance(), self);
    write_linked(folder, stem, path, strain, k % 2 == 0, noise);
    if (k == 0) {
      h5::write_checkpoint(folder + "/broken.h5", c, fabric::test::test_provenance(), self);
      h5::File broken = h5::File::open(folder + "/broken.h5", h5::File::Access::read_write);
      if (H5Ldelete(broken.id(), "/contacts/force", H5P_DEFAULT) < 0)
        throw FileError("cannot delete the dataset");
    }
  }
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  const mpi::Environment environment(argc, argv);
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FOLDER\n", argv[0]);
    return 2;
  }
  return write_all(argv[1]);
}
