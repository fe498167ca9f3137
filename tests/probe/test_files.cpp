// Probe files: fork and result files round-trip exactly; readers name the file and the problem;
// collect refuses forks of another checkpoint, a missing or doubled fork, other settings and
// another restored state.
#include "common/error.hpp"
#include "common/h5/file.hpp"
#include "probe/collect.hpp"
#include "probe/files.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace aniso::probe {
namespace {

using dem::test::TemporaryFolder;

h5::Provenance provenance() {
  return dem::test::test_provenance();
}

// A fork of an isotropic linear material (modulus 200 MPa on the loaded axis, 60 MPa across).
ForkFile sample_fork(int index, const std::string& hash = "0123456789abcdef") {
  const ForkSpec spec = fork_spec(index);
  const double delta = 5e-5;
  ForkFile f;
  f.source = {"runs/demo/load_003.h5", hash, 0.01, Vec3(-0.01, 0.0, 0.0098)};
  f.settings = {delta, 1e-3, 500, 250};
  ForkResult& r = f.result;
  r.index = index;
  r.stress_start = -1e5 * Mat3::Identity();
  r.strain_rate = 10.0;
  r.time_step = 8e-9;
  r.half_steps = 88;
  r.hold_steps = 500;
  r.contacts_start = 1200;
  r.sliding_start = 230;
  r.contacts_final = 1190 + index;
  r.sliding_final = 120 + index;
  for (int k = 0; k < 4; ++k) {
    Mat3 reference = -(9e4 - 100.0 * k) * Mat3::Identity();
    Mat3 half = reference, final = reference;
    if (spec.sign != 0) {
      Vec3 response = Vec3::Constant(60e6 * spec.sign * delta);
      response[spec.axis] = 200e6 * spec.sign * delta;
      half.diagonal() += 0.5 * response;
      final.diagonal() += response;
    }
    r.samples_half.push_back(half);
    r.samples_final.push_back(final);
  }
  if (spec.sign != 0) {
    r.strain_half[spec.axis] = 0.5 * spec.sign * delta;
    r.strain_final[spec.axis] = spec.sign * delta;
  }
  return f;
}

std::vector<ForkFile> all_forks() {
  std::vector<ForkFile> files;
  for (int index = 0; index <= n_forks; ++index)
    files.push_back(sample_fork(index));
  return files;
}

std::vector<std::string> names(std::size_t n) {
  std::vector<std::string> paths;
  for (std::size_t k = 0; k < n; ++k)
    paths.push_back("fork" + std::to_string(k) + ".h5");
  return paths;
}

template <class Error, class Body> std::string message_of(const Body& body) {
  try {
    body();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected an error";
  return {};
}

TEST(ProbeFiles, NamesFollowTheCheckpointStem) {
  EXPECT_EQ(checkpoint_stem("runs/demo/load_003.h5"), "load_003");
  EXPECT_EQ(fork_path("out", "runs/demo/load_003.h5", 4), "out/probe_load_003_fork4.h5");
  EXPECT_EQ(result_path("out", "runs/demo/load_003.h5"), "out/probe_load_003.h5");
}

TEST(ProbeFiles, ForkFileRoundTripsExactly) {
  const TemporaryFolder folder("probe_files");
  const ForkFile written = sample_fork(3);
  write_fork_file(folder.file("f.h5"), written, provenance());
  const ForkFile read = read_fork_file(folder.file("f.h5"));
  EXPECT_EQ(read.source.path, written.source.path);
  EXPECT_EQ(read.source.hash, written.source.hash);
  EXPECT_EQ(read.source.strain, written.source.strain);
  EXPECT_EQ(read.source.cell_strain, written.source.cell_strain);
  EXPECT_TRUE(read.settings == written.settings);
  EXPECT_EQ(read.result.index, 3);
  EXPECT_EQ(read.result.samples_final, written.result.samples_final);
  EXPECT_EQ(read.result.samples_half, written.result.samples_half);
  EXPECT_EQ(read.result.strain_final, written.result.strain_final);
  EXPECT_EQ(read.result.stress_start, written.result.stress_start);
  EXPECT_EQ(read.result.sliding_final, written.result.sliding_final);
  EXPECT_EQ(read.result.half_steps, written.result.half_steps);
}

TEST(ProbeFiles, ResultRoundTripsAndHoldsTheMatrices) {
  const TemporaryFolder folder("probe_files");
  std::string warning;
  const ProbeResult result =
      assemble_result(check_forks(all_forks(), names(7), "0123456789abcdef"), ProbeConfig{}, warning);
  EXPECT_EQ(warning, "");
  EXPECT_TRUE(result.checks_passed);
  // The isotropic material: C = 200 MPa on the diagonal, 60 MPa off it; no D; K_C their mean.
  EXPECT_NEAR(result.stiffness.C(0, 0), 200e6, 1e-3);
  EXPECT_NEAR(result.stiffness.C(2, 1), 60e6, 1e-3);
  EXPECT_NEAR(result.stiffness.D.cwiseAbs().maxCoeff(), 0.0, 1e-3);
  EXPECT_NEAR(result.stiffness.K_C, (3 * 200e6 + 6 * 60e6) / 9, 1e-3);
  write_probe_result(folder.file("r.h5"), result, provenance());
  write_probe_csv(folder.file("r.csv"), result);
  const ProbeResult read = read_probe_result(folder.file("r.h5"));
  EXPECT_EQ(read.stiffness.C, result.stiffness.C);
  EXPECT_EQ(read.stiffness.D, result.stiffness.D);
  EXPECT_EQ(read.stiffness.Q_plus, result.stiffness.Q_plus);
  EXPECT_EQ(read.stiffness.Q_minus, result.stiffness.Q_minus);
  EXPECT_EQ(read.stiffness.K_C, result.stiffness.K_C);
  EXPECT_EQ(read.source.hash, "0123456789abcdef");
  EXPECT_EQ(read.forks[5].samples_final, result.forks[5].samples_final);
  EXPECT_TRUE(std::filesystem::is_regular_file(folder.file("r.csv")));
}

TEST(ProbeFiles, ReaderNamesTheFileAndTheProblem) {
  const TemporaryFolder folder("probe_files");
  const std::string path = folder.file("bad.h5");
  write_fork_file(path, sample_fork(1), provenance());
  EXPECT_NE(message_of<FileError>([&] { static_cast<void>(read_probe_result(path)); }).find("schema"),
            std::string::npos);
  {
    h5::File file = h5::File::open(path, h5::File::Access::read_write);
    file.write_attribute("schema_version", std::int64_t{99});
  }
  const std::string message = message_of<FileError>([&] { static_cast<void>(read_fork_file(path)); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("schema_version 99"), std::string::npos) << message;
  EXPECT_NE(message_of<FileError>([&] {
              static_cast<void>(read_fork_file(folder.file("none.h5")));
            }).find("none.h5"),
            std::string::npos);
}

TEST(ProbeFiles, ReaderRefusesNonFiniteStress) {
  const TemporaryFolder folder("probe_files");
  ForkFile fork = sample_fork(2);
  fork.result.samples_final[1](0, 0) = std::nan("");
  write_fork_file(folder.file("nan.h5"), fork, provenance());
  const std::string message =
      message_of<FileError>([&] { static_cast<void>(read_fork_file(folder.file("nan.h5"))); });
  EXPECT_NE(message.find("samples_final"), std::string::npos) << message;
  EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
}

TEST(Collect, RefusesAForkOfAnotherCheckpoint) {
  auto files = all_forks();
  files[4] = sample_fork(4, "fedcba9876543210");
  const std::string message =
      message_of<FileError>([&] { static_cast<void>(check_forks(files, names(7), "0123456789abcdef")); });
  EXPECT_NE(message.find("fork4.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("another checkpoint"), std::string::npos) << message;
  // And all seven of another checkpoint against this one's hash.
  EXPECT_THROW(static_cast<void>(check_forks(all_forks(), names(7), "fedcba9876543210")), FileError);
}

TEST(Collect, RefusesAMissingOrDoubledFork) {
  auto files = all_forks();
  files.erase(files.begin() + 5);
  std::string message =
      message_of<FileError>([&] { static_cast<void>(check_forks(files, names(6), "0123456789abcdef")); });
  EXPECT_NE(message.find("fork 5 is missing"), std::string::npos) << message;
  files = all_forks();
  files.erase(files.begin()); // the reference
  message =
      message_of<FileError>([&] { static_cast<void>(check_forks(files, names(6), "0123456789abcdef")); });
  EXPECT_NE(message.find("fork 0 is missing"), std::string::npos) << message;
  files = all_forks();
  files[6] = sample_fork(2);
  message =
      message_of<FileError>([&] { static_cast<void>(check_forks(files, names(7), "0123456789abcdef")); });
  EXPECT_NE(message.find("both hold fork 2"), std::string::npos) << message;
}

TEST(Collect, RefusesOtherSettingsOrAnotherRestoredState) {
  auto files = all_forks();
  files[3].settings.increment = 1e-4;
  std::string message =
      message_of<FileError>([&] { static_cast<void>(check_forks(files, names(7), "0123456789abcdef")); });
  EXPECT_NE(message.find("other probe settings"), std::string::npos) << message;
  files = all_forks();
  files[2].result.stress_start(1, 1) += 1e-9;
  message =
      message_of<FileError>([&] { static_cast<void>(check_forks(files, names(7), "0123456789abcdef")); });
  EXPECT_NE(message.find("another restored state"), std::string::npos) << message;
}

TEST(Collect, RefusesAnIncrementThatFailsItsChecksUnlessAskedToKeepIt) {
  auto files = all_forks();
  files[1].result.sliding_final = files[0].result.sliding_final + 300; // 25% of the contacts made to slide
  const auto forks = check_forks(files, names(7), "0123456789abcdef");
  std::string warning;
  ProbeConfig config;
  EXPECT_THROW(static_cast<void>(assemble_result(forks, config, warning)), NumericalError);
  config.check_increment = false;
  const ProbeResult kept = assemble_result(forks, config, warning);
  EXPECT_FALSE(kept.checks_passed);
  EXPECT_NE(warning.find("increment too large"), std::string::npos) << warning;
}

} // namespace
} // namespace aniso::probe
