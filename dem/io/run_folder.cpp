#include "dem/io/run_folder.hpp"

#include "common/error.hpp"
#include "common/root_only.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace aniso::dem::io {
namespace fs = std::filesystem;

RunFolderLock::RunFolderLock(const std::string& folder, const mpi::Comm& comm)
    : path_(folder + "/.aniso-dem.lock") {
  run_on_root(comm, [&] {
    // A holder removes the file as it releases it (below), so a lock taken on a file that is no
    // longer the one under the name is taken again on the new one.
    for (;;) {
      descriptor_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
      require_file(descriptor_ >= 0,
                   fmt::format("cannot open the lock file '{}': {}", path_, std::strerror(errno)));
      if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        std::string holder;
        std::ifstream(path_) >> holder;
        ::close(descriptor_);
        descriptor_ = -1;
        require_input(
            error != EWOULDBLOCK,
            fmt::format("another aniso-dem (pid {}) is writing into '{}' (it holds '{}'): wait for it "
                        "to end, or choose another dem.output_dir",
                        holder.empty() ? "?" : holder, folder, path_));
        throw FileError(fmt::format("cannot lock '{}': {}", path_, std::strerror(error)));
      }
      struct stat held {
      }, named{};
      if (::fstat(descriptor_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 &&
          held.st_dev == named.st_dev && held.st_ino == named.st_ino)
        break;
      ::close(descriptor_);
    }
    // The holder's pid, for the message above; the lock itself is the flock, not the content.
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(descriptor_, 0) == 0) static_cast<void>(::pwrite(descriptor_, pid.data(), pid.size(), 0));
  });
}

RunFolderLock::~RunFolderLock() {
  if (descriptor_ < 0) return;
  // Removed while still held, so that no lock file outlives the run, whichever way it ends
  // (an exception unwinds through here; a killed process leaves the file, whose flock the
  // kernel has dropped, to the next run).
  ::unlink(path_.c_str());
  ::close(descriptor_); // closing releases the flock
}

std::vector<std::string> loading_run_files(const std::string& folder) {
  static const std::regex pattern(R"(history\.(h5|csv)|load_(\d{3,}|interrupted|resume)\.h5)");
  return files_matching(folder, pattern);
}

std::vector<std::string> files_matching(const std::string& folder, const std::regex& pattern) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, pattern)) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

void clear_for_fresh_loading(const std::string& folder, bool overwrite, const std::string& input,
                             const mpi::Comm& comm) {
  run_on_root(comm, [&] {
    const std::vector<std::string> names = loading_run_files(folder);
    if (names.empty()) return;
    if (!overwrite) {
      std::string listed;
      for (std::size_t k = 0; k < names.size() && k < 4; ++k)
        listed += (k ? ", " : "") + names[k];
      if (names.size() > 4) listed += fmt::format(" and {} more", names.size() - 4);
      throw InputError(
          fmt::format("load: '{}' already holds a loading run ({}); a new loading there would "
                      "replace it. Continue it with --input <its load_NNN.h5, or load_resume.h5 where the "
                      "checkpoints are relaxed copies> --resume, choose "
                      "another dem.output_dir, or pass --overwrite to replace it",
                      folder, listed));
    }
    for (const std::string& name : names) {
      std::error_code same;
      require_input(
          !fs::equivalent(fs::path(folder) / name, input, same),
          fmt::format("load --overwrite: the input '{}' is a file of the run it would remove; copy it "
                      "elsewhere first, or load into another dem.output_dir",
                      input));
    }
    for (const std::string& name : names) {
      std::error_code error;
      fs::remove(fs::path(folder) / name, error);
      require_file(!error,
                   fmt::format("load --overwrite: cannot remove '{}/{}': {}", folder, name, error.message()));
    }
  });
}

std::string new_run_id(const mpi::Comm& comm) {
  std::string id;
  if (comm.is_root()) {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char date[32];
    std::strftime(date, sizeof date, "%Y%m%dT%H%M%SZ", &utc);
    std::random_device entropy;
    const std::uint64_t bits = (static_cast<std::uint64_t>(entropy()) << 32U) ^ entropy();
    id = fmt::format("{}-{:012x}", date, bits & 0xffffffffffffULL);
  }
  std::vector<char> bytes(id.begin(), id.end());
  comm.broadcast(bytes);
  return {bytes.begin(), bytes.end()};
}

} // namespace aniso::dem::io
