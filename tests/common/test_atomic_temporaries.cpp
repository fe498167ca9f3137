// Temporaries of atomic writes are named after their host and pid, and the next write of the same
// file removes those a dead process of this host left behind (kill -9), and only those.
#include "common/h5/atomic_write.hpp"
#include "common/mpi.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

std::string host_name() {
  std::array<char, 256> name{};
  gethostname(name.data(), name.size() - 1);
  return name.data();
}

// No process has a pid of pid_max or above.
std::string dead_pid() {
  std::ifstream in("/proc/sys/kernel/pid_max");
  long long pid_max = 4194304;
  in >> pid_max;
  return std::to_string(pid_max);
}

void touch(const fs::path& path) {
  std::ofstream(path) << "partial";
}

TEST(AtomicTemporaries, NamedAfterHostAndPid) {
  const std::string folder = aniso::test::make_temp_folder(aniso::mpi::Comm(MPI_COMM_SELF), "aniso-atomic");
  ASSERT_FALSE(folder.empty());
  const aniso::h5::AtomicFile atomic((fs::path(folder) / "x.h5").string());
  const std::string name = fs::path(atomic.temp_path()).filename().string();
  const std::string prefix = ".x.h5.tmp-" + host_name() + "-" + std::to_string(getpid()) + "-";
  EXPECT_EQ(name.rfind(prefix, 0), 0u) << name;
  EXPECT_EQ(name.size(), prefix.size() + 6) << name;
  fs::remove_all(folder);
}

TEST(AtomicTemporaries, StaleOnesOfThisFileAndHostGo) {
  const fs::path folder = aniso::test::make_temp_folder(aniso::mpi::Comm(MPI_COMM_SELF), "aniso-atomic");
  ASSERT_FALSE(folder.empty());
  const std::string host = host_name();
  const fs::path dead = folder / (".x.h5.tmp-" + host + "-" + dead_pid() + "-AbC123");
  const fs::path live = folder / (".x.h5.tmp-" + host + "-" + std::to_string(getpid()) + "-AbC123");
  const fs::path other_host = folder / (".x.h5.tmp-" + host + "x-" + dead_pid() + "-AbC123");
  const fs::path unnamed = folder / ".x.h5.tmp-AbC123"; // the older form: whose, unknown
  const fs::path other_file = folder / (".y.h5.tmp-" + host + "-" + dead_pid() + "-AbC123");
  const fs::path not_one = folder / (".x.h5.tmp-" + host + "-" + dead_pid() + "-AbC1234");
  for (const fs::path& path : {dead, live, other_host, unnamed, other_file, not_one})
    touch(path);
  aniso::h5::write_text_atomically((folder / "x.h5").string(), "complete\n");
  EXPECT_TRUE(fs::exists(folder / "x.h5"));
  EXPECT_FALSE(fs::exists(dead));
  for (const fs::path& path : {live, other_host, unnamed, other_file, not_one})
    EXPECT_TRUE(fs::exists(path)) << path;
  fs::remove_all(folder);
}

} // namespace
