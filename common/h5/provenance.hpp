#pragma once
// Provenance: who wrote a file, with what, from what. Every file aniso writes has a /provenance group.

#include "common/mpi.hpp"

#include <string>

namespace aniso::h5 {

class Group;

struct Provenance {
  std::string program;      ///< e.g. "aniso-dem load"
  std::string version;      ///< aniso version
  std::string git_hash;     ///< commit the binary was built from
  std::string config;       ///< effective configuration as TOML
  std::string command_line; ///< argv joined with spaces
  int n_ranks = 1;          ///< MPI ranks that wrote the file
  std::string date;         ///< UTC, ISO 8601
};

/// Provenance for this process: version and git hash from the build, date now (rank 0's clock,
/// so that all ranks agree), rank count from comm. Collective on comm.
Provenance make_provenance(const std::string& program, const std::string& config,
                           const std::string& command_line, const mpi::Comm& comm);

/// Writes `parent`/provenance with one string attribute per field (n_ranks as int64).
/// Collective in a parallel file, with identical provenance on every rank.
void write_provenance(Group& parent, const Provenance& provenance);

/// Reads `parent`/provenance; FileError naming the file and the missing group or attribute.
Provenance read_provenance(const Group& parent);

} // namespace aniso::h5
