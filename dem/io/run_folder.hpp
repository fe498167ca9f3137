#pragma once
// The output folder of a DEM run: one writer at a time, and no loading run's files replaced or
// mixed with another's unless the user asks (docs/user-guide.md, "Output folders").

#include "common/mpi.hpp"

#include <regex>
#include <string>
#include <vector>

namespace aniso::dem::io {

/// An exclusive advisory lock (flock) on <folder>/.aniso-dem.lock, held by rank 0 for the
/// object's lifetime and removed with it, on every way out of the run that unwinds (errors
/// included). The kernel drops the flock when the process ends in any way (kill -9 included),
/// so a lock file left by a killed run never blocks a resume. Collective; InputError on every rank, naming
/// the folder and the holder's pid, when another process holds it.
class RunFolderLock {
public:
  RunFolderLock(const std::string& folder, const mpi::Comm& comm);
  ~RunFolderLock();
  RunFolderLock(const RunFolderLock&) = delete;
  RunFolderLock& operator=(const RunFolderLock&) = delete;

private:
  std::string path_;
  int descriptor_ = -1;
};

/// The files of a loading run in folder: history.h5, history.csv, load_NNN.h5, load_interrupted.h5.
std::vector<std::string> loading_run_files(const std::string& folder);

/// The names of the files in `folder` (not below it) that match `pattern` whole, sorted; none if
/// the folder does not exist.
std::vector<std::string> files_matching(const std::string& folder, const std::regex& pattern);

/// Before a fresh loading into folder: InputError on every rank naming the files of an earlier
/// loading run there, or with overwrite, removes them (so that no file of the old run remains
/// beside the new one) unless one of them is the loading's input. Collective.
void clear_for_fresh_loading(const std::string& folder, bool overwrite, const std::string& input,
                             const mpi::Comm& comm);

/// A new loading run's id: UTC date and time and 48 random bits, made on rank 0 and shared.
std::string new_run_id(const mpi::Comm& comm);

} // namespace aniso::dem::io
