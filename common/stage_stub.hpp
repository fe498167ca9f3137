#pragma once
// The front door of a stage whose computation has not landed yet. It parses
// the shared options and --input, validates the configuration and the input
// file, and refuses to compute anything: it never prints a made-up result.
// Each stage's main() replaces this call when its issue lands.

#include "common/mpi.hpp"

#include <string>

namespace aniso::cli {

enum class InputKind { checkpoint, hdf5_file };

struct PendingStage {
  std::string program;     ///< e.g. "aniso-fabric"
  std::string description; ///< one line for --help
  std::string section;     ///< its config table, e.g. "fabric"
  InputKind input_kind = InputKind::checkpoint;
  int issue = 0; ///< the issue that builds it
};

/// Returns the exit code: 0 after --help, --version, --print-config or a successful --dry-run.
int run_pending_stage(int argc, char** argv, const mpi::Comm& comm, const PendingStage& stage);

} // namespace aniso::cli
