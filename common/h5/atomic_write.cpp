#include "common/h5/atomic_write.hpp"

#include "common/error.hpp"

#include <array>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace aniso::h5 {
namespace {

std::string folder_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

std::string system_error(const std::string& what) {
  return what + ": " + std::strerror(errno);
}

// This host's name as it appears in temporaries' names: letters, digits, '.', '_' and '-' only.
std::string host_tag() {
  std::array<char, 256> name{};
  if (gethostname(name.data(), name.size() - 1) != 0) return "unknown";
  std::string tag(name.data());
  for (char& c : tag)
    if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '.' && c != '_' && c != '-') c = '_';
  return tag.empty() ? "unknown" : tag.substr(0, 64);
}

// The pid in "<pid>-XXXXXX" (the end of a temporary's name after its host), or 0 if it is not one.
pid_t pid_of(const std::string& rest) {
  const std::size_t dash = rest.find('-');
  if (dash == 0 || dash == std::string::npos || dash > 10 || rest.size() != dash + 7) return 0;
  for (std::size_t k = 0; k < rest.size(); ++k) {
    const auto c = static_cast<unsigned char>(rest[k]);
    if (k < dash ? std::isdigit(c) == 0 : (k > dash && std::isalnum(c) == 0)) return 0;
  }
  const long long pid = std::stoll(rest.substr(0, dash));
  return pid <= std::numeric_limits<pid_t>::max() ? static_cast<pid_t>(pid) : 0;
}

// Removes the temporaries of this final file that a process of this host left when it died (kill -9,
// a node's time limit): their pid no longer exists. Those of live processes, of other hosts (whose
// pids mean nothing here) and of the older unnamed form are left alone.
void remove_stale_temporaries(const std::filesystem::path& folder, const std::string& prefix) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const pid_t pid = pid_of(name.substr(prefix.size()));
    if (pid > 0 && kill(pid, 0) != 0 && errno == ESRCH) std::filesystem::remove(entry.path(), error);
  }
}

// Creates ".<name>.tmp-<host>-<pid>-XXXXXX" in the final file's folder (same file system, so rename is
// atomic), first removing stale temporaries of the same name. Returns the path, or throws FileError.
std::string create_temporary(const std::string& final_path) {
  const std::filesystem::path final_name = std::filesystem::path(final_path).filename();
  if (final_name.empty()) throw FileError(final_path + ": not a file name");
  const std::filesystem::path folder(folder_of(final_path));
  const std::string prefix = "." + final_name.string() + ".tmp-" + host_tag() + "-";
  remove_stale_temporaries(folder, prefix);
  std::string pattern = (folder / (prefix + std::to_string(getpid()) + "-XXXXXX")).string();
  const int descriptor = mkstemp(pattern.data());
  if (descriptor < 0)
    throw FileError(final_path + ": " +
                    system_error("cannot create a temporary file in " + folder_of(final_path)));
  // mkstemp makes the file private (0600); give it the permissions a plain create would.
  const mode_t mask = umask(0);
  umask(mask);
  fchmod(descriptor, static_cast<mode_t>(0666 & ~mask));
  close(descriptor);
  return pattern;
}

// fsync a file or folder; returns an error message, empty on success.
std::string sync_path(const std::string& path, bool folder) {
  const int descriptor = open(path.c_str(), folder ? (O_RDONLY | O_DIRECTORY) : O_RDONLY);
  if (descriptor < 0) return system_error("cannot open " + path + " to sync it");
  std::string error;
  // Some file systems refuse fsync on folders (EINVAL); the rename itself is still atomic there.
  if (fsync(descriptor) != 0 && !(folder && errno == EINVAL))
    error = system_error("fsync of " + path + " failed");
  close(descriptor);
  return error;
}

// Throws FileError with the first rank's message if any rank has one; collective when comm is given.
void throw_if_any_failed(const std::optional<mpi::Comm>& comm, const std::string& local_error) {
  if (!comm) {
    if (!local_error.empty()) throw FileError(local_error);
    return;
  }
  const std::vector<std::int64_t> failed = comm->all_gather(local_error.empty() ? 0 : 1);
  for (int rank = 0; rank < static_cast<int>(failed.size()); ++rank) {
    if (failed[static_cast<std::size_t>(rank)] == 0) continue;
    std::vector<char> bytes(local_error.begin(), local_error.end());
    comm->broadcast(bytes, rank);
    throw FileError(std::string(bytes.begin(), bytes.end()));
  }
}

} // namespace

AtomicFile::AtomicFile(std::string final_path)
    : final_path_(std::move(final_path)), temp_path_(create_temporary(final_path_)) {}

AtomicFile::AtomicFile(std::string final_path, const mpi::Comm& comm)
    : final_path_(std::move(final_path)), comm_(comm), is_root_(comm.is_root()) {
  std::string error;
  if (is_root_) {
    try {
      temp_path_ = create_temporary(final_path_);
    } catch (const FileError& failure) {
      error = failure.what();
    }
  }
  throw_if_any_failed(comm_, error);
  std::vector<char> bytes(temp_path_.begin(), temp_path_.end());
  comm.broadcast(bytes, 0);
  temp_path_.assign(bytes.begin(), bytes.end());
}

AtomicFile::~AtomicFile() {
  if (!committed_ && is_root_ && !temp_path_.empty()) std::remove(temp_path_.c_str());
}

void AtomicFile::commit() {
  if (committed_) throw FileError(final_path_ + ": commit() called twice");
  throw_if_any_failed(comm_, sync_path(temp_path_, false));
  std::string error;
  if (is_root_) {
    if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
      error = system_error("cannot rename " + temp_path_ + " to " + final_path_);
    } else {
      committed_ = true;
      error = sync_path(folder_of(final_path_), true);
    }
  }
  throw_if_any_failed(comm_, error);
  committed_ = true;
}

void write_text_atomically(const std::string& path, const std::string& text) {
  AtomicFile atomic(path);
  {
    std::ofstream out(atomic.temp_path(), std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw FileError(path + ": cannot write");
  }
  atomic.commit();
}

} // namespace aniso::h5
