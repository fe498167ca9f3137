// When a long loop that --resume continues writes its state without stopping: a run killed
// without SIGTERM (SIGKILL at the end of an allocation or a login session, a lost node, the OOM
// killer) then loses at most one interval of work, where SIGTERM loses none
// (common/stop_request.hpp). Rank 0's clock decides, so every rank keeps at the same step.
#pragma once

#include "common/mpi.hpp"

#include <chrono>

namespace aniso {

class KeepClock {
public:
  /// Due once `interval_seconds` of wall time have passed since construction or the last time
  /// it was due; 0: at every call (the tests'); infinity: never.
  explicit KeepClock(double interval_seconds);

  /// Collective (none when the interval is infinite): true on every rank when it is due.
  [[nodiscard]] bool due(const mpi::Comm& comm);

  [[nodiscard]] double interval_seconds() const { return interval_; }

private:
  double interval_;
  std::chrono::steady_clock::time_point last_;
};

} // namespace aniso
