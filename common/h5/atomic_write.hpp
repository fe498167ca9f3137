#pragma once
// Atomic file replacement (DESIGN.md "Data formats"): a file is written under a
// temporary name in its final folder, flushed to disk, and renamed over the
// final name only when complete. A crash at any point leaves either the old
// file or the new one under the final name, never a partial file. A crash may
// leave a stale temporary (".<name>.tmp-<host>-<pid>-XXXXXX"); it never affects
// the final file, and the next atomic write of the same file removes it once no
// process of that pid lives on this host (those of other hosts stay: their pids
// mean nothing here; delete them by hand once their job has ended).

#include "common/mpi.hpp"

#include <optional>
#include <string>

namespace aniso::h5 {

/// One atomic write. Create it, write the whole file at temp_path() and close every handle to
/// it, then call commit(). If the object is destroyed without commit() the temporary is removed.
class AtomicFile {
public:
  /// Serial: this process alone writes. Creates the temporary file (empty) next to final_path.
  explicit AtomicFile(std::string final_path);
  /// Collective on comm: rank 0 creates the temporary and broadcasts its name; all ranks then
  /// write it together (for example with File::create(temp_path(), comm)). FileError on every
  /// rank if rank 0 cannot create it.
  AtomicFile(std::string final_path, const mpi::Comm& comm);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  [[nodiscard]] const std::string& temp_path() const { return temp_path_; }
  [[nodiscard]] const std::string& final_path() const { return final_path_; }

  /// Makes the written file visible under final_path: each rank fsyncs the temporary, rank 0
  /// renames it over final_path and fsyncs the folder. Collective on the constructor's comm
  /// (if any); FileError on every rank if any step fails on any rank. Call once.
  void commit();

private:
  std::string final_path_;
  std::string temp_path_;
  std::optional<mpi::Comm> comm_;
  bool is_root_ = true; ///< removes the temporary and renames
  bool committed_ = false;
};

/// Writes a whole text file atomically (serial: this process alone). FileError naming the path.
void write_text_atomically(const std::string& path, const std::string& text);

} // namespace aniso::h5
