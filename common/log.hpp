#pragma once
// Logging: rank 0 speaks on stdout at the chosen level; other ranks report
// only errors (on stderr). Loggers are values passed to whoever needs one,
// never looked up from a registry. Progress prints a line with an ETA at most
// once per wall-clock interval.

#include "common/mpi.hpp"

#include <spdlog/logger.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace aniso {

using Logger = std::shared_ptr<spdlog::logger>;

/// A logger named after the program; level is one of trace, debug, info, warn, error, off.
Logger make_logger(const std::string& program, const mpi::Comm& comm, const std::string& level);

/// A logger that writes nothing (for tests and library calls that want silence).
Logger make_silent_logger();

/// Throttled progress reporting with an estimate of the time remaining. The estimate takes the
/// pace of the more recent half of the run so far: a stage that slows down near its end (a
/// compaction waiting to seize) does not keep promising the early pace.
class Progress {
public:
  using Clock = std::function<double()>; ///< seconds, monotonic

  /// Reports "label: done/total" at most every `interval_seconds` of wall-clock time. `from` is
  /// where this run starts (a resumed load's strain): the remaining time is estimated from the
  /// pace since then, not from the whole way as if this run had done it all.
  Progress(Logger logger, std::string label, double total, double interval_seconds, Clock clock = {},
           double from = 0.0);

  /// Records progress `done` (same unit as total) and prints if the interval has passed. Returns true if
  /// printed. `detail`, called only when printing, adds what the stage is doing to the line.
  bool update(double done, const std::function<std::string()>& detail = {});
  /// The line that update() would print for `done` now (for tests).
  [[nodiscard]] std::string line(double done) const;

private:
  Logger logger_;
  std::string label_;
  double total_;
  double from_;
  double interval_;
  Clock clock_;
  double start_;
  double last_print_;
  std::vector<std::pair<double, double>> printed_; ///< (time, done) at the start and at each print
};

/// "1 h 02 min", "3 min 05 s", "12 s": short human durations for progress lines.
std::string format_duration(double seconds);

} // namespace aniso
