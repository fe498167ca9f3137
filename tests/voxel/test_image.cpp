// The voxel image file (docs/formats/image.md): a random image survives the round trip bit for
// bit with its geometry and source; the file carries the agreed layout (dims [n3, n2, n1],
// chunked + deflated, attributes) and an XDMF sidecar; bad images are refused before anything is
// written; damaged files give a FileError naming the file and the problem.
#include "common/error.hpp"
#include "common/h5/file.hpp"
#include "common/h5/image.hpp"
#include "common/mpi.hpp"
#include "common/rng.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using aniso::FileError;
using aniso::InputError;
using aniso::h5::File;
using aniso::h5::VoxelImage;
using ::testing::HasSubstr;

VoxelImage random_image() {
  VoxelImage image;
  image.shape = {7, 5, 3};
  image.voxel_size = 2.5e-5;
  image.origin = aniso::Vec3(-1e-4, 0.5e-4, 3e-4);
  image.source = "runs/demo/checkpoint_0003.h5";
  image.source_hash = "0123456789abcdef";
  std::mt19937_64 engine(11);
  image.phase.resize(image.size());
  for (auto& value : image.phase)
    value = static_cast<std::uint8_t>(engine() & 1U);
  return image;
}

class ImageFile : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = aniso::test::make_temp_folder(aniso::mpi::Comm(MPI_COMM_SELF), "aniso-image");
    ASSERT_FALSE(folder_.empty());
  }
  void TearDown() override { fs::remove_all(folder_); }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (fs::path(folder_) / name).string();
  }
  std::string folder_;
};

TEST_F(ImageFile, RoundTripsBitForBit) {
  const VoxelImage image = random_image();
  EXPECT_EQ(image.index(1, 2, 1), 1U + 7U * (2U + 5U * 1U));
  aniso::h5::write_voxel_image(path("img.h5"), image, aniso::test::sample_provenance(1));
  const VoxelImage read = aniso::h5::read_voxel_image(path("img.h5"));
  EXPECT_EQ(read.shape, image.shape);
  EXPECT_EQ(read.voxel_size, image.voxel_size);
  EXPECT_EQ(read.origin, image.origin);
  EXPECT_EQ(read.phase, image.phase);
  EXPECT_EQ(read.source, image.source);
  EXPECT_EQ(read.source_hash, image.source_hash);
}

TEST_F(ImageFile, LayoutMatchesTheContract) {
  const VoxelImage image = random_image();
  aniso::h5::write_voxel_image(path("img.h5"), image, aniso::test::sample_provenance(1));
  const File file = File::open(path("img.h5"));
  const auto phase = file.open_group("image").open_dataset("phase");
  EXPECT_EQ(phase.dims(), (aniso::h5::Dims{3, 5, 7}));
  // Slowest first on disk: element [k][j][i] is voxel (i, j, k).
  const auto values = phase.read<std::uint8_t>();
  EXPECT_EQ(values[image.index(4, 3, 2)], image.phase[4 + 7 * (3 + 5 * 2)]);
  EXPECT_EQ(phase.read_attribute<double>("voxel_size"), 2.5e-5);
  EXPECT_EQ(phase.read_string_attribute("voxel_size_units"), "m");
  EXPECT_EQ(phase.read_attribute<std::int64_t>("periodic"), 1);
  EXPECT_EQ(phase.read_attribute<std::int64_t>("schema_version"), aniso::h5::image_schema_version);
  const aniso::h5::Handle create_list(H5Dget_create_plist(phase.id()), H5Pclose);
  EXPECT_EQ(H5Pget_layout(create_list.get()), H5D_CHUNKED);
  EXPECT_GE(H5Pget_nfilters(create_list.get()), 1);
  EXPECT_TRUE(file.has_child("provenance"));

  ASSERT_EQ(aniso::h5::xdmf_sidecar_path(path("img.h5")), path("img.xmf"));
  std::ifstream sidecar(path("img.xmf"));
  std::stringstream text;
  text << sidecar.rdbuf();
  EXPECT_THAT(text.str(), HasSubstr("img.h5:/image/phase"));
  EXPECT_THAT(text.str(), HasSubstr(R"(Dimensions="4 6 8")"));
  EXPECT_THAT(text.str(), HasSubstr(R"(Dimensions="3 5 7")"));
}

TEST_F(ImageFile, InconsistentImagesAreRefusedBeforeWriting) {
  const std::vector<std::function<void(VoxelImage&)>> damages = {
      [](VoxelImage& image) { image.phase.pop_back(); },
      [](VoxelImage& image) { image.phase[3] = 2; },
      [](VoxelImage& image) { image.voxel_size = 0; },
      [](VoxelImage& image) { image.origin.x() = std::nan(""); },
      [](VoxelImage& image) { image.shape[1] = 0; },
  };
  for (const auto& damage : damages) {
    VoxelImage image = random_image();
    damage(image);
    EXPECT_THROW(aniso::h5::write_voxel_image(path("bad.h5"), image, aniso::test::sample_provenance(1)),
                 InputError);
    EXPECT_FALSE(fs::exists(path("bad.h5")));
  }
}

TEST_F(ImageFile, DamagedFilesNameTheProblem) {
  const auto expect_failure = [&](const std::string& name, const std::function<void(File&)>& damage,
                                  const std::string& problem) {
    aniso::h5::write_voxel_image(path(name), random_image(), aniso::test::sample_provenance(1));
    {
      File file = File::open(path(name), File::Access::read_write);
      damage(file);
      file.close();
    }
    try {
      static_cast<void>(aniso::h5::read_voxel_image(path(name)));
      ADD_FAILURE() << "no error for " << problem;
    } catch (const FileError& error) {
      EXPECT_THAT(error.what(), HasSubstr(name));
      EXPECT_THAT(error.what(), HasSubstr(problem));
    }
  };
  expect_failure(
      "schema.h5", [](File& f) { f.write_attribute("schema", std::string_view("other")); }, "schema 'other'");
  expect_failure(
      "version.h5",
      [](File& f) {
        f.open_group("image").open_dataset("phase").write_attribute("schema_version", std::int64_t{9});
      },
      "schema_version 9");
  expect_failure(
      "size.h5",
      [](File& f) { f.open_group("image").open_dataset("phase").write_attribute("voxel_size", -1.0); },
      "voxel_size -1");
  expect_failure(
      "value.h5",
      [](File& f) {
        auto phase = f.open_group("image").open_dataset("phase");
        std::vector<std::uint8_t> values = phase.read<std::uint8_t>();
        values[5] = 7;
        phase.write<std::uint8_t>(values);
      },
      "value 7 at flat index 5");
  expect_failure(
      "origin.h5", [](File& f) { H5Adelete(f.open_group("image").open_dataset("phase").id(), "origin"); },
      "missing attribute 'origin'");
  EXPECT_THROW(static_cast<void>(aniso::h5::read_voxel_image(path("absent.h5"))), FileError);
}

} // namespace
