// aniso-voxel end to end on a small random checkpoint of spheres and ovoids: the image and the
// void results are written, read back and consistent with the library; thread count changes no
// result; bad input is refused with the right error naming the problem, and results already
// written are left intact.
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/content_hash.hpp"
#include "common/h5/file.hpp"
#include "common/h5/image.hpp"
#include "common/mpi.hpp"
#include "tests/common/checkpoint_sample.hpp"
#include "voxel/digitize.hpp"
#include "voxel/stage.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using aniso::FileError;
using aniso::InputError;
using aniso::mpi::Comm;
using ::testing::HasSubstr;

class VoxelStage : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = aniso::test::make_temp_folder(self_, "aniso-voxel-stage");
    ASSERT_FALSE(folder_.empty());
    aniso::h5::Checkpoint checkpoint = aniso::test::sample_checkpoint(5, 40, 25, 1);
    // A dense cell (solid fraction about 0.35) instead of the sample's dilute one.
    const aniso::Vec3 lengths(6e-3, 5e-3, 5.5e-3);
    checkpoint.cell.lengths = lengths;
    aniso::RandomStream stream(5, 1);
    aniso::test::place_apart(checkpoint, stream, lengths);
    // Aspect ratios down to 0.3 need a splice angle below 2 atan(0.3) = 0.58 rad.
    checkpoint.parameters.push_back({"ovoid_splice_angle", 0.5, "rad"});
    aniso::h5::write_checkpoint(path("no_d50.h5"), checkpoint, aniso::test::sample_provenance(1), self_);
    checkpoint.parameters.push_back({"d50", 1.5e-3, "m"});
    aniso::h5::write_checkpoint(path("ck.h5"), checkpoint, aniso::test::sample_provenance(1), self_);
    checkpoint.parameters.erase(checkpoint.parameters.end() - 2); // the default splice angle is too large
    fs::create_directory(path("broken"));
    aniso::h5::write_checkpoint(path("broken/ck.h5"), checkpoint, aniso::test::sample_provenance(1), self_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (fs::path(folder_) / name).string();
  }

  int run(const std::string& input, const std::string& output, std::vector<std::string> extra = {}) {
    std::vector<std::string> args{
        "aniso-voxel",        "--input",     input, "--set", "voxel.output_dir='" + output + "'", "--set",
        "voxel.resolution=8", "--log-level", "warn"};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (auto& arg : args)
      argv.push_back(arg.data());
    return aniso::voxel::run_voxel_stage(static_cast<int>(argv.size()), argv.data(), self_);
  }

  const Comm self_{MPI_COMM_SELF};
  std::string folder_;
};

std::string bytes_of(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_F(VoxelStage, WritesTheImageAndTheVoidResults) {
  ASSERT_EQ(run(path("ck.h5"), path("out")), 0);
  const aniso::h5::VoxelImage image = aniso::h5::read_voxel_image(path("out/image_ck.h5"));
  EXPECT_EQ(image.source, path("ck.h5"));
  EXPECT_EQ(image.source_hash, aniso::h5::content_hash(path("ck.h5")));
  const aniso::h5::Checkpoint checkpoint = aniso::h5::read_checkpoint(path("ck.h5"), self_);
  const aniso::h5::VoxelImage expected = aniso::voxel::digitize_checkpoint(checkpoint, "", "", 8);
  EXPECT_EQ(image.shape, expected.shape);
  EXPECT_EQ(image.phase, expected.phase);
  EXPECT_TRUE(fs::exists(path("out/image_ck.xmf")));

  const aniso::h5::File results = aniso::h5::File::open(path("out/voids_ck.h5"));
  const aniso::h5::Group voids = results.open_group("voids");
  EXPECT_EQ(voids.read_string_attribute("source_hash"), image.source_hash);
  for (const char* name : {"free_path_median", "breadth_median"})
    for (const double value : voids.read_dataset<double>(name, {3})) {
      EXPECT_TRUE(std::isfinite(value) && value > 0) << name;
      EXPECT_LT(value, 5e-3) << name; // within the cell
    }
  const double median = voids.read_dataset<double>("void_size_median", {})[0];
  EXPECT_GT(median, 0);
  const auto fraction = voids.open_group("ball").open_dataset("fraction").read<double>();
  EXPECT_EQ(fraction.front(), 1.0);
  EXPECT_EQ(fraction.back(), 0.0);
  // Not necessarily monotone: digital balls of successive radii are nested but do not form a
  // granulometry (the larger is not open with respect to the smaller).
  for (const double f : fraction)
    EXPECT_TRUE(f >= 0 && f <= 1);
  EXPECT_EQ(voids.open_group("euler").read_attribute<std::int64_t>("counted_torus"), 40 - 25);
  const std::string csv = bytes_of(path("out/voids_ck.csv"));
  EXPECT_THAT(csv, HasSubstr("template,axis,size_voxels,size_m,size_d50,kept_voxels,fraction\nball,0,0,"));
  EXPECT_THAT(csv, HasSubstr("\nspar,3,"));
  EXPECT_THAT(csv, HasSubstr("\ndisk,2,"));
}

TEST_F(VoxelStage, ThreadCountChangesNoResult) {
  ASSERT_EQ(run(path("ck.h5"), path("one"), {"--set", "voxel.threads=1"}), 0);
  ASSERT_EQ(run(path("ck.h5"), path("two"), {"--set", "voxel.threads=2"}), 0);
  EXPECT_EQ(bytes_of(path("one/voids_ck.csv")), bytes_of(path("two/voids_ck.csv")));
  EXPECT_EQ(aniso::h5::read_voxel_image(path("one/image_ck.h5")).phase,
            aniso::h5::read_voxel_image(path("two/image_ck.h5")).phase);
}

TEST_F(VoxelStage, BadInputIsRefusedAndEarlierResultsSurvive) {
  ASSERT_EQ(run(path("ck.h5"), path("out")), 0);
  const std::string before = bytes_of(path("out/voids_ck.h5"));
  const std::string image_before = bytes_of(path("out/image_ck.h5"));
  try {
    run(path("no_d50.h5"), path("out"));
    ADD_FAILURE() << "a checkpoint without d50 was accepted";
  } catch (const FileError& error) {
    EXPECT_THAT(error.what(), HasSubstr("d50"));
    EXPECT_THAT(error.what(), HasSubstr("no_d50.h5"));
  }
  EXPECT_EQ(bytes_of(path("out/voids_ck.h5")), before);
  EXPECT_EQ(bytes_of(path("out/image_ck.h5")), image_before);
  EXPECT_THROW(run(path("absent.h5"), path("out")), FileError);
  try {
    run(path("broken/ck.h5"), path("out"));
    ADD_FAILURE() << "the default splice angle was accepted for aspect ratio 0.3";
  } catch (const FileError& error) {
    EXPECT_THAT(error.what(), HasSubstr("splice angle"));
  }
  EXPECT_THROW(run(path("ck.h5"), path("out"), {"--set", "voxel.resolutoin=4"}), InputError);
  EXPECT_THROW(run(path("ck.h5"), path("out"), {"--set", "voxel.resolution=1"}), InputError);
  EXPECT_EQ(bytes_of(path("out/voids_ck.h5")), before);
}

TEST_F(VoxelStage, DryRunWritesNothing) {
  ASSERT_EQ(run(path("ck.h5"), path("dry"), {"--dry-run"}), 0);
  EXPECT_FALSE(fs::exists(path("dry")));
}

} // namespace
