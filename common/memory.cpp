#include "common/memory.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

namespace aniso {

namespace {

constexpr double kGiB = 1073741824.0;

// A soft resource limit in bytes; 0 when unlimited or unknown.
double resource_limit(int resource) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0.0;
  return static_cast<double>(limit.rlim_cur);
}

// cgroup v2 memory.max of this process's group (what SLURM's --mem sets); 0 when "max" or absent.
double cgroup_limit() {
  std::ifstream group_file("/proc/self/cgroup");
  std::string line, path;
  while (std::getline(group_file, line))
    if (line.rfind("0::", 0) == 0) path = line.substr(3);
  std::ifstream limit_file("/sys/fs/cgroup" + path + "/memory.max");
  std::string value;
  if (!(limit_file >> value) || value == "max") return 0.0;
  try {
    return std::stod(value);
  } catch (const std::exception&) {
    return 0.0;
  }
}

} // namespace

std::uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream fields(line.substr(6));
    std::uint64_t kilobytes = 0;
    fields >> kilobytes;
    return kilobytes * 1024;
  }
  return 0;
}

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size) : 0.0;
}

double usable_memory_bytes() {
  double usable = 0.0;
  for (const double limit :
       {physical_memory_bytes(), resource_limit(RLIMIT_AS), resource_limit(RLIMIT_DATA), cgroup_limit()})
    if (limit > 0) usable = usable > 0 ? std::min(usable, limit) : limit;
  return usable;
}

void require_memory(double bytes, const std::string& what, const std::string& remedy) {
  const double usable = usable_memory_bytes();
  require_input(usable == 0 || bytes < usable,
                fmt::format("{}: about {:.3g} GiB needed, more than the {:.3g} GiB this process may use (the "
                            "smallest of the machine's memory, ulimit -v/-d and the job's memory limit); {}",
                            what, bytes / kGiB, usable / kGiB, remedy));
}

} // namespace aniso
