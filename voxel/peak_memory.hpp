#pragma once
// Memory figures: peak resident set size of this process (log, benchmarks) and the machine's
// physical memory (refusing images that cannot fit).

#include <cstdint>

namespace aniso::voxel {

/// VmHWM from /proc/self/status in bytes; 0 where unavailable.
std::uint64_t peak_resident_bytes();

/// Physical memory of the machine in bytes (sysconf); 0 where unavailable.
double physical_memory_bytes();

} // namespace aniso::voxel
