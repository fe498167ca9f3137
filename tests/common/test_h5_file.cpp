// The HDF5 layer: typed round trips, row-selection writes, attributes, the
// messages a bad file gets, and atomic replacement. Serial (one process).
#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/mpi.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using aniso::FileError;
using aniso::InputError;
using aniso::h5::AtomicFile;
using aniso::h5::Dims;
using aniso::h5::File;
using aniso::h5::Group;
using aniso::h5::RowSelection;

class H5File : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = aniso::test::make_temp_folder(aniso::mpi::Comm(MPI_COMM_SELF), "aniso-h5-file");
    ASSERT_FALSE(folder_.empty());
  }
  void TearDown() override { fs::remove_all(folder_); }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (fs::path(folder_) / name).string();
  }

  std::string folder_;
};

// Expects `action` to throw FileError whose message contains every one of `parts`.
template <class Action> void expect_file_error(Action action, const std::vector<std::string>& parts) {
  try {
    action();
    ADD_FAILURE() << "no FileError thrown";
  } catch (const FileError& error) {
    for (const std::string& part : parts)
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos)
          << "message '" << error.what() << "' lacks '" << part << "'";
  }
}

TEST_F(H5File, EveryElementTypeRoundTripsWithUnitsAndDescription) {
  const std::vector<double> doubles{1.5, -0.0, std::numeric_limits<double>::denorm_min(), 1e300, -2, 3};
  const std::vector<std::int64_t> int64s{std::numeric_limits<std::int64_t>::min(), -1, 0, 1, 2,
                                         std::numeric_limits<std::int64_t>::max()};
  const std::vector<std::uint64_t> uint64s{0, 1, 2, 3, 4, std::numeric_limits<std::uint64_t>::max()};
  const std::vector<std::int32_t> int32s{-7, 0, 7, std::numeric_limits<std::int32_t>::min(), 5, 6};
  const std::vector<std::uint8_t> uint8s{0, 1, 2, 3, 254, 255};
  {
    File file = File::create(path("types.h5"));
    Group group = file.create_group("data");
    group.write_dataset<double>("doubles", doubles, Dims{2, 3}, "m", "a 2 x 3 matrix");
    group.write_dataset<std::int64_t>("int64s", int64s, Dims{6}, "1", "signed");
    group.write_dataset<std::uint64_t>("uint64s", uint64s, Dims{3, 2}, "1", "unsigned");
    group.write_dataset<std::int32_t>("int32s", int32s, Dims{6}, "1", "small signed");
    group.write_dataset<std::uint8_t>("uint8s", uint8s, Dims{6, 1}, "1", "bytes");
    const double scalar = 42;
    group.write_dataset<double>("scalar", std::span<const double>(&scalar, 1), Dims{}, "Pa", "a scalar");
    file.close();
  }
  const File file = File::open(path("types.h5"));
  const Group group = file.open_group("data");
  EXPECT_TRUE(aniso::test::same_bits(group.read_dataset<double>("doubles", Dims{2, 3}), doubles));
  EXPECT_EQ(group.read_dataset<std::int64_t>("int64s", Dims{6}), int64s);
  EXPECT_EQ(group.read_dataset<std::uint64_t>("uint64s", Dims{3, 2}), uint64s);
  EXPECT_EQ(group.read_dataset<std::int32_t>("int32s", Dims{6}), int32s);
  EXPECT_EQ(group.read_dataset<std::uint8_t>("uint8s", Dims{6, 1}), uint8s);
  EXPECT_EQ(group.read_dataset<double>("scalar", Dims{}), std::vector<double>{42});
  const auto dataset = group.open_dataset("doubles");
  EXPECT_EQ(dataset.read_string_attribute("units"), "m");
  EXPECT_EQ(dataset.read_string_attribute("description"), "a 2 x 3 matrix");
  EXPECT_EQ(dataset.name(), "/data/doubles");
}

TEST_F(H5File, AttributesRoundTripInCreationOrder) {
  {
    File file = File::create(path("attributes.h5"));
    Group group = file.create_group("g");
    group.write_attribute("zeta", std::int64_t{-3});
    group.write_attribute("alpha", std::string_view("text with spaces and UTF-8: µm"));
    group.write_attribute_with_units("young", 29e9, "Pa");
    group.write_attribute("empty", std::string_view(""));
    group.write_attribute("alpha", std::string_view("replaced")); // replaces, keeps one attribute
  }
  const File file = File::open(path("attributes.h5"));
  const Group group = file.open_group("g");
  EXPECT_EQ(group.read_attribute<std::int64_t>("zeta"), -3);
  EXPECT_EQ(group.read_string_attribute("alpha"), "replaced");
  EXPECT_EQ(group.read_attribute<double>("young"), 29e9);
  EXPECT_EQ(group.read_string_attribute("young_units"), "Pa");
  EXPECT_EQ(group.read_string_attribute("empty"), "");
  EXPECT_EQ(group.attribute_names(),
            (std::vector<std::string>{"zeta", "young", "young_units", "empty", "alpha"}));
  expect_file_error([&] { static_cast<void>(group.read_attribute<std::int64_t>("young")); },
                    {"attributes.h5", "/g", "young", "64-bit float", "expected 64-bit signed integer"});
  expect_file_error([&] { static_cast<void>(group.read_string_attribute("missing")); },
                    {"attributes.h5", "/g", "missing attribute 'missing'"});
}

TEST_F(H5File, RowSelectionWritesRowsGivenInAnyOrder) {
  // Rows 5, 0, 3, 4, 1 written in that order (row 2 left to the second call).
  const std::vector<std::uint64_t> rows{5, 0, 3, 4, 1};
  std::vector<double> values;
  for (const std::uint64_t row : rows)
    for (int column = 0; column < 3; ++column)
      values.push_back(10.0 * static_cast<double>(row) + column);
  {
    File file = File::create(path("rows.h5"));
    auto dataset = file.create_dataset<double>("table", Dims{6, 3}, "m", "rows");
    dataset.write_rows(RowSelection(rows), std::span<const double>(values));
    const std::vector<std::uint64_t> last{2};
    const std::vector<double> row_two{20, 21, 22};
    dataset.write_rows(RowSelection(last), std::span<const double>(row_two));
  }
  const std::vector<double> table = File::open(path("rows.h5")).read_dataset<double>("table", Dims{6, 3});
  for (std::size_t row = 0; row < 6; ++row)
    for (std::size_t column = 0; column < 3; ++column)
      EXPECT_EQ(table[3 * row + column], 10.0 * static_cast<double>(row) + static_cast<double>(column));
}

TEST_F(H5File, EmptyDatasetsWork) {
  {
    File file = File::create(path("empty.h5"));
    auto dataset = file.create_dataset<std::int32_t>("none", Dims{0, 3}, "1", "no rows");
    dataset.write_rows(RowSelection({}), std::span<const std::int32_t>());
    file.write_dataset<double>("also_none", std::span<const double>(), Dims{0}, "m", "no rows");
  }
  const File file = File::open(path("empty.h5"));
  EXPECT_TRUE(file.read_dataset<std::int32_t>("none", Dims{0, 3}).empty());
  EXPECT_TRUE(file.read_dataset<double>("also_none", Dims{0}).empty());
}

TEST_F(H5File, DuplicateRowsAreRejected) {
  const std::vector<std::uint64_t> rows{1, 2, 1};
  EXPECT_THROW(RowSelection{rows}, InputError);
}

TEST_F(H5File, ProblemsNameTheFileAndTheObject) {
  expect_file_error([&] { static_cast<void>(File::open(path("absent.h5"))); },
                    {"absent.h5", "file not found"});
  std::ofstream(path("text.h5")) << "not HDF5 at all\n";
  expect_file_error([&] { static_cast<void>(File::open(path("text.h5"))); }, {"text.h5", "not an HDF5 file"});
  {
    File file = File::create(path("shapes.h5"));
    file.create_group("g").write_dataset<double>("x", std::vector<double>(6, 1.0), Dims{2, 3}, "m", "x");
  }
  const File file = File::open(path("shapes.h5"));
  const Group group = file.open_group("g");
  expect_file_error(
      [&] {
        static_cast<void>(group.read_dataset<double>("x", Dims{3, 3}));
      },
      {"shapes.h5", "/g/x", "shape [2, 3] found, expected [3, 3]"});
  expect_file_error([&] { static_cast<void>(group.read_dataset<double>("y", Dims{3})); },
                    {"shapes.h5", "/g/y", "missing dataset"});
  expect_file_error(
      [&] {
        static_cast<void>(group.read_dataset<std::uint64_t>("x", Dims{2, 3}));
      },
      {"shapes.h5", "/g/x", "stored type is 64-bit float"});
  expect_file_error([&] { static_cast<void>(file.open_group("h")); }, {"shapes.h5", "/h", "missing group"});
}

TEST_F(H5File, AtomicFileAppearsOnlyOnCommit) {
  const std::string final_path = path("atomic.h5");
  {
    File file = File::create(final_path);
    file.write_attribute("generation", std::int64_t{1});
  }
  std::string temp;
  {
    AtomicFile atomic(final_path);
    temp = atomic.temp_path();
    EXPECT_EQ(fs::path(temp).parent_path(), fs::path(final_path).parent_path());
    EXPECT_EQ(fs::path(temp).filename().string().rfind(".atomic.h5.tmp-", 0), 0u) << temp;
    File file = File::create(temp);
    file.write_attribute("generation", std::int64_t{2});
    file.close();
    // Not committed: the old file is still there and the temporary goes away.
  }
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_EQ(File::open(final_path).read_attribute<std::int64_t>("generation"), 1);
  {
    AtomicFile atomic(final_path);
    File file = File::create(atomic.temp_path());
    file.write_attribute("generation", std::int64_t{3});
    file.close();
    atomic.commit();
    EXPECT_FALSE(fs::exists(atomic.temp_path()));
  }
  EXPECT_EQ(File::open(final_path).read_attribute<std::int64_t>("generation"), 3);
  EXPECT_EQ(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()), 1);
}

TEST_F(H5File, AtomicFileInAMissingFolderFails) {
  expect_file_error([&] { AtomicFile atomic(path("no/such/folder/x.h5")); }, {"x.h5", "temporary"});
}

} // namespace
