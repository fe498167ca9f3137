#pragma once
// Provenance: who wrote a file, with what, from what. Every file aniso writes has a /provenance group.

#include "common/mpi.hpp"

#include <string>

namespace aniso::h5 {

struct Provenance {
  std::string program;      ///< e.g. "aniso-dem load"
  std::string version;      ///< aniso version
  std::string git_hash;     ///< commit the binary was built from
  std::string config;       ///< effective configuration as TOML
  std::string command_line; ///< argv joined with spaces
  int n_ranks = 1;          ///< MPI ranks that wrote the file
  std::string date;         ///< UTC, ISO 8601
};

/// Provenance for this process: version and git hash from the build, date now, rank count from comm.
Provenance make_provenance(const std::string& program, const std::string& config, const std::string& command_line,
                           const mpi::Comm& comm);

} // namespace aniso::h5
