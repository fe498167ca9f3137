#pragma once
// Content hash of a file: 64-bit FNV-1a over its bytes, as 16 lower-case hex digits.
// Stages that derive results from a checkpoint (probe forks, voxel images) record it, so that
// a collector can refuse to combine results that came from different files. It identifies
// content, not a path: a copy has the same hash, a rewritten checkpoint (new provenance date)
// has another. Not a cryptographic hash; it guards against mix-ups, not tampering.

#include "common/mpi.hpp"

#include <string>
#include <string_view>

namespace aniso::h5 {

/// FNV-1a 64 of the file's bytes, hex; FileError naming the file if it cannot be read.
std::string content_hash(const std::string& path);

/// content_hash(path) computed on rank 0 and broadcast (collective): one rank reads the file.
std::string content_hash(const std::string& path, const mpi::Comm& comm);

/// FNV-1a 64 of a byte string, hex (the same function applied to memory).
std::string content_hash_of_bytes(std::string_view bytes);

} // namespace aniso::h5
