#pragma once
// Peak resident set size of this process, for the memory figures in the log and benchmarks.

#include <cstdint>

namespace aniso::voxel {

/// VmHWM from /proc/self/status in bytes; 0 where unavailable.
std::uint64_t peak_resident_bytes();

} // namespace aniso::voxel
