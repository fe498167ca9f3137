#include "common/keep_clock.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aniso {

KeepClock::KeepClock(double interval_seconds)
    : interval_(interval_seconds), last_(std::chrono::steady_clock::now()) {
  require_input(interval_seconds >= 0 && !std::isnan(interval_seconds),
                fmt::format("keep interval {} s: expected 0 or more", interval_seconds));
}

bool KeepClock::due(const mpi::Comm& comm) {
  if (std::isinf(interval_)) return false;
  const auto now = std::chrono::steady_clock::now();
  const bool here = comm.is_root() && std::chrono::duration<double>(now - last_).count() >= interval_;
  const bool due = comm.size() == 1 ? here : comm.any(here);
  if (due) last_ = now;
  return due;
}

} // namespace aniso
