// Checkpoints on one rank: a random checkpoint survives the round trip bit for
// bit; empty contact and stream lists work; every corruption in the failure
// table gets a FileError naming the file and the dataset; bad input is refused
// before anything is written; and a crash between write and rename leaves the
// previous checkpoint intact.
#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/file.hpp"
#include "common/mpi.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using aniso::FileError;
using aniso::InputError;
using aniso::h5::Checkpoint;
using aniso::h5::File;
using aniso::mpi::Comm;
using aniso::test::rewrite;
using aniso::test::sample_checkpoint;
using aniso::test::sample_provenance;

class CheckpointFile : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = aniso::test::make_temp_folder(Comm(MPI_COMM_SELF), "aniso-checkpoint");
    ASSERT_FALSE(folder_.empty());
  }
  void TearDown() override { fs::remove_all(folder_); }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (fs::path(folder_) / name).string();
  }

  const Comm self_{MPI_COMM_SELF};
  std::string folder_;
};

TEST_F(CheckpointFile, RandomContentRoundTripsBitForBit) {
  const Checkpoint full = sample_checkpoint(7, 40, 90, 3);
  // Rows handed over in reverse order: the writer must place them by id and by (id_i, id_j).
  const Checkpoint shuffled = aniso::test::select_rows(
      full, [](std::size_t) { return true; }, [](std::size_t) { return true; });
  aniso::h5::write_checkpoint(path("ck.h5"), shuffled, sample_provenance(1), self_);
  const Checkpoint read = aniso::h5::read_checkpoint(path("ck.h5"), self_);
  aniso::test::expect_bit_identical(full, read);
  EXPECT_EQ(aniso::h5::parameter(read, "shear_modulus", path("ck.h5")), 29e9);
  EXPECT_THROW(static_cast<void>(aniso::h5::parameter(read, "absent", path("ck.h5"))), FileError);

  const File file = File::open(path("ck.h5"));
  const aniso::h5::Provenance provenance = aniso::h5::read_provenance(file);
  EXPECT_EQ(provenance.config, sample_provenance(1).config);
  EXPECT_EQ(file.open_group("particles").open_dataset("position").read_string_attribute("units"), "m");
  EXPECT_EQ(file.open_group("parameters").read_string_attribute("shear_modulus_units"), "Pa");
}

TEST_F(CheckpointFile, NoContactsAndNoStreams) {
  const Checkpoint full = sample_checkpoint(8, 5, 0, 0);
  aniso::h5::write_checkpoint(path("empty.h5"), full, sample_provenance(1), self_);
  const Checkpoint read = aniso::h5::read_checkpoint(path("empty.h5"), self_);
  aniso::test::expect_bit_identical(full, read);
  EXPECT_EQ(read.contacts.size(), 0u);
  EXPECT_TRUE(read.rng_state.empty());
}

TEST_F(CheckpointFile, ProvenanceFromTheBuild) {
  const aniso::h5::Provenance provenance = aniso::h5::make_provenance("aniso test", "[x]", "a b", self_);
  EXPECT_EQ(provenance.n_ranks, 1);
  EXPECT_FALSE(provenance.version.empty());
  ASSERT_EQ(provenance.date.size(), 20u) << provenance.date; // 2024-01-01T00:00:00Z
  EXPECT_EQ(provenance.date.back(), 'Z');
}

// ---- Failure table: each row corrupts a valid file one way and names what the message must contain.

struct Corruption {
  std::string name;
  std::function<void(const std::string&)> apply;
  std::vector<std::string> message_parts; ///< besides the file name
};

std::vector<Corruption> corruptions() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {
      {"truncated", [](const std::string& p) { fs::resize_file(p, fs::file_size(p) / 2); }, {"truncated"}},
      {"wrong_schema_version",
       [](const std::string& p) {
         File::open(p, File::Access::read_write).write_attribute("schema_version", std::int64_t{2});
       },
       {"schema_version 2 found, expected 1"}},
      {"wrong_schema",
       [](const std::string& p) {
         File::open(p, File::Access::read_write).write_attribute("schema", std::string_view("aniso-image"));
       },
       {"schema 'aniso-image' found, expected 'aniso-checkpoint'"}},
      {"missing_dataset",
       [](const std::string& p) {
         const File file = File::open(p, File::Access::read_write);
         ASSERT_GE(H5Ldelete(file.open_group("particles").id(), "velocity", H5P_DEFAULT), 0);
       },
       {"/particles/velocity", "missing dataset"}},
      {"missing_attribute",
       [](const std::string& p) {
         const File file = File::open(p, File::Access::read_write);
         ASSERT_GE(H5Adelete(file.id(), "time_step"), 0);
       },
       {"missing attribute 'time_step'"}},
      {"nan_position",
       [=](const std::string& p) {
         rewrite<double>(p, "particles", "position", [=](auto& v) { v[3 * 4 + 1] = nan; });
       },
       {"/particles/position", "non-finite", "row 4", "column 1"}},
      {"position_outside_the_cell", // a wrong stress and a wrong image, in every stage
       [](const std::string& p) {
         const File file = File::open(p, File::Access::read_write);
         const std::vector<double> lengths = file.open_group("cell").read_dataset<double>("lengths", {3});
         rewrite<double>(p, "particles", "position", [&](auto& v) { v[3 * 5 + 2] = 1.5 * lengths[2]; });
       },
       {"/particles/position", "coordinate 2", "row 5", "lies outside the cell"}},
      {"bad_ids",
       [](const std::string& p) {
         rewrite<std::uint64_t>(p, "particles", "id", [](auto& v) { std::swap(v[2], v[3]); });
       },
       {"/particles/id", "row 2 holds id 3"}},
      {"contacts_unsorted",
       [](const std::string& p) {
         rewrite<std::uint64_t>(p, "contacts", "particles", [](auto& v) {
           std::swap(v[0], v[2]);
           std::swap(v[1], v[3]);
         });
       },
       {"/contacts/particles", "not in strictly increasing"}},
      {"contact_id_out_of_range",
       [](const std::string& p) {
         rewrite<std::uint64_t>(p, "contacts", "particles", [](auto& v) { v.back() = 999; });
       },
       {"/contacts/particles", "out of range"}},
      {"contact_ids_reversed",
       [](const std::string& p) {
         rewrite<std::uint64_t>(p, "contacts", "particles",
                                [](auto& v) { std::swap(v[v.size() - 2], v.back()); });
       },
       {"/contacts/particles", "expected id_i < id_j"}},
      {"quaternion_not_unit",
       [](const std::string& p) {
         rewrite<double>(p, "particles", "orientation", [](auto& v) {
           for (std::size_t k = 4 * 6; k < 4 * 7; ++k)
             v[k] *= 1.00001;
         });
       },
       {"/particles/orientation", "quaternion norm", "row 6"}},
      {"negative_diameter",
       [](const std::string& p) {
         rewrite<double>(p, "particles", "diameter", [](auto& v) { v[9] = -1e-3; });
       },
       {"/particles/diameter", "row 9", "expected > 0"}},
      {"aspect_ratio_above_one",
       [](const std::string& p) {
         rewrite<double>(p, "particles", "aspect_ratio", [](auto& v) { v[1] = 1.5; });
       },
       {"/particles/aspect_ratio", "row 1", "(0, 1]"}},
      {"zero_cell_length",
       [](const std::string& p) { rewrite<double>(p, "cell", "lengths", [](auto& v) { v[2] = 0; }); },
       {"/cell/lengths", "axis 2", "expected > 0"}},
      {"wrong_shape",
       [](const std::string& p) {
         const File file = File::open(p, File::Access::read_write);
         auto group = file.open_group("contacts");
         ASSERT_GE(H5Ldelete(group.id(), "normal", H5P_DEFAULT), 0);
         group.write_dataset<double>("normal", std::vector<double>(5, 0.0), aniso::h5::Dims{5}, "1", "bad");
       },
       {"/contacts/normal", "shape [5] found, expected [30, 3]"}},
      {"wrong_type",
       [](const std::string& p) {
         const File file = File::open(p, File::Access::read_write);
         auto group = file.open_group("particles");
         ASSERT_GE(H5Ldelete(group.id(), "mass", H5P_DEFAULT), 0);
         group.write_dataset<std::int64_t>("mass", std::vector<std::int64_t>(20, 1), aniso::h5::Dims{20},
                                           "kg", "x");
       },
       {"/particles/mass", "expected 64-bit float"}},
  };
}

class CheckpointCorruption : public ::testing::TestWithParam<Corruption> {};

TEST_P(CheckpointCorruption, GivesFileErrorNamingFileAndDataset) {
  const Comm self(MPI_COMM_SELF);
  const std::string folder = aniso::test::make_temp_folder(self, "aniso-checkpoint-bad");
  const std::string file_path = (fs::path(folder) / (GetParam().name + ".h5")).string();
  aniso::h5::write_checkpoint(file_path, sample_checkpoint(11, 20, 30, 2), sample_provenance(1), self);
  GetParam().apply(file_path);
  try {
    static_cast<void>(aniso::h5::read_checkpoint(file_path, self));
    ADD_FAILURE() << "no FileError";
  } catch (const FileError& error) {
    const std::string message = error.what();
    std::cout << "  message: " << message << "\n";
    EXPECT_NE(message.find(file_path), std::string::npos) << message;
    for (const std::string& part : GetParam().message_parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << message << "' lacks '" << part << "'";
  }
  fs::remove_all(folder);
}

INSTANTIATE_TEST_SUITE_P(Table, CheckpointCorruption, ::testing::ValuesIn(corruptions()),
                         [](const auto& test_info) { return test_info.param.name; });

// ---- Bad input is refused before a file is touched.

TEST_F(CheckpointFile, WriterRefusesInvalidRows) {
  const Checkpoint good = sample_checkpoint(12, 10, 12, 1);
  const auto expect_input_error = [&](Checkpoint bad, const std::string& part) {
    try {
      aniso::h5::write_checkpoint(path("bad.h5"), bad, sample_provenance(1), self_);
      ADD_FAILURE() << "no InputError for " << part;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    }
    EXPECT_FALSE(fs::exists(path("bad.h5")));
  };
  Checkpoint bad = good;
  bad.particles.position[3].y() = std::numeric_limits<double>::infinity();
  expect_input_error(bad, "/particles/position: non-finite value inf at particle id 3");
  bad = good;
  bad.particles.id[4] = 5;
  expect_input_error(bad, "id 4 held 0 times");
  bad = good;
  bad.particles.id[4] = 10;
  expect_input_error(bad, "id 10 out of range");
  bad = good;
  bad.contacts.particles[0] = {3, 3};
  expect_input_error(bad, "expected id_i < id_j");
  bad = good;
  bad.contacts.particles[1] = bad.contacts.particles[0];
  expect_input_error(bad, "given twice");
  bad = good;
  bad.particles.mass.pop_back();
  expect_input_error(bad, "different lengths");
  bad = good;
  bad.parameters.push_back({"density_units", 1, "1"});
  expect_input_error(bad, "not a valid parameter name");
}

// ---- A crash between write and rename.

// Death tests re-execute this binary ("threadsafe" style), which reruns the test body up to
// EXPECT_EXIT; the folder is passed to the child through the environment so that both use it.
TEST(CheckpointCrash, CrashBeforeRenameLeavesThePreviousCheckpoint) {
  const Comm self(MPI_COMM_SELF);
  const char* inherited = std::getenv("ANISO_TEST_CRASH_FOLDER");
  const bool in_child = inherited != nullptr;
  const std::string folder = in_child ? inherited : aniso::test::make_temp_folder(self, "aniso-crash");
  ASSERT_FALSE(folder.empty());
  setenv("ANISO_TEST_CRASH_FOLDER", folder.c_str(), 1);
  const std::string final_path = (fs::path(folder) / "run.h5").string();
  const Checkpoint old_content = sample_checkpoint(21, 30, 40, 2);
  const Checkpoint new_content = sample_checkpoint(22, 31, 41, 2);
  if (!in_child) aniso::h5::write_checkpoint(final_path, old_content, sample_provenance(1), self);

  // The child writes part of a new checkpoint under the temporary name, then dies before commit().
  EXPECT_EXIT(
      {
        aniso::h5::AtomicFile atomic(final_path);
        File file = File::create(atomic.temp_path());
        file.write_attribute("schema", std::string_view("aniso-checkpoint"));
        file.create_group("particles")
            .write_dataset<double>("diameter", new_content.particles.diameter, aniso::h5::Dims{31}, "m",
                                   "diameter");
        file.flush();
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(0), "");
  unsetenv("ANISO_TEST_CRASH_FOLDER");

  std::vector<std::string> stale;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().rfind(".run.h5.tmp-", 0) == 0)
      stale.push_back(entry.path().string());
  EXPECT_EQ(stale.size(), 1u) << "the crashed writer should have left its temporary behind";
  aniso::test::expect_bit_identical(old_content, aniso::h5::read_checkpoint(final_path, self));

  // The stale temporary does not disturb the next checkpoint, which removes it: the process that
  // wrote it (host and pid in its name) no longer exists (common/h5/atomic_write.hpp).
  aniso::h5::write_checkpoint(final_path, new_content, sample_provenance(1), self);
  aniso::test::expect_bit_identical(new_content, aniso::h5::read_checkpoint(final_path, self));
  if (!stale.empty()) {
    EXPECT_FALSE(fs::exists(stale.front())) << stale.front();
  }
  fs::remove_all(folder);
}

} // namespace
