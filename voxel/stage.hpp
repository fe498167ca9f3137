#pragma once
// The aniso-voxel program: command line, configuration, digitization, analysis, outputs.

#include "common/mpi.hpp"

namespace aniso::voxel {

/// Runs aniso-voxel on argv (as main() would, minus the exception-to-exit-code mapping of
/// cli::run). Returns the exit code for --help/--version/--print-config/--dry-run and success;
/// throws aniso::Error subclasses on bad input or files.
int run_voxel_stage(int argc, char** argv, const mpi::Comm& comm);

} // namespace aniso::voxel
