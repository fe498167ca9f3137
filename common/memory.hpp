#pragma once
// Memory figures: the peak resident set of this process (logs, benchmarks), the memory this
// process may use, and the check that refuses a problem too large for it before allocating
// (an allocation failure deep inside a stage said only "std::bad_alloc").

#include <cstdint>
#include <string>

namespace aniso {

/// VmHWM from /proc/self/status in bytes; 0 where unavailable.
std::uint64_t peak_resident_bytes();

/// Physical memory of the machine in bytes (sysconf); 0 where unavailable.
double physical_memory_bytes();

/// The memory this process may use: the smallest of the physical memory, the address-space and
/// data-segment limits (ulimit -v, -d) and the cgroup limit (a SLURM job's --mem); 0 if none is known.
double usable_memory_bytes();

/// InputError (exit 2) "<what>: about X GiB needed, more than the Y GiB this process may use;
/// <remedy>" when `bytes` exceeds usable_memory_bytes().
void require_memory(double bytes, const std::string& what, const std::string& remedy);

} // namespace aniso
