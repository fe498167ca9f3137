#pragma once
// Identifying the checkpoint a probe runs on: its path, content hash and loading strain.

#include "common/h5/checkpoint.hpp"
#include "common/mpi.hpp"
#include "probe/files.hpp"

#include <string>

namespace aniso::probe {

/// Hash computed on rank 0 and broadcast (collective).
ProbeSource probe_source(const std::string& path, const h5::Checkpoint& checkpoint, const mpi::Comm& comm);

} // namespace aniso::probe
