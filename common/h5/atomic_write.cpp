#include "common/h5/atomic_write.hpp"

#include "common/error.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
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

// Creates ".<name>.tmp-XXXXXX" in the final file's folder (same file system, so rename is atomic).
// Returns the path, or throws FileError.
std::string create_temporary(const std::string& final_path) {
  const std::filesystem::path final_name = std::filesystem::path(final_path).filename();
  if (final_name.empty()) throw FileError(final_path + ": not a file name");
  std::string pattern =
      (std::filesystem::path(folder_of(final_path)) / ("." + final_name.string() + ".tmp-XXXXXX")).string();
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
