#pragma once
// Serial output from rank 0 with a collective outcome: if rank 0 fails, every rank throws the
// same error, so that all ranks exit with the same code and no rank waits forever.

#include "common/mpi.hpp"

#include <functional>

namespace aniso {

/// Runs body on rank 0 only; collective. Rethrows rank 0's aniso::Error (or an internal error
/// for any other exception) on every rank.
void run_on_root(const mpi::Comm& comm, const std::function<void()>& body);

} // namespace aniso
