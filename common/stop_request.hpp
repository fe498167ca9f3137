// A polite stop on SIGTERM, what SLURM sends at a job's time limit (or earlier with
// `#SBATCH --signal=TERM@120`) and on scancel: the handler only sets a flag, and long loops
// poll it at safe points and end with a checkpoint that `--resume` continues from.
#pragma once

#include "common/mpi.hpp"

#include <cstdint>

namespace aniso {

/// Installs the SIGTERM handler (repeat calls do nothing more).
void install_stop_handler();

/// True once SIGTERM has reached this process.
[[nodiscard]] bool stop_requested_here();

/// Collective: true on every rank once any rank has received SIGTERM, so that all ranks stop
/// at the same step.
[[nodiscard]] bool stop_requested(const mpi::Comm& comm);

/// Collective: stop_requested(comm), or true once `step` has reached the environment variable
/// ANISO_TEST_STOP_AT_STEP: how the tests stop a run at a chosen step, inside the phase they
/// mean, as a SIGTERM arriving then would (read here alone; unset, it does nothing).
[[nodiscard]] bool stop_requested(const mpi::Comm& comm, std::int64_t step);

} // namespace aniso
