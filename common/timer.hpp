#pragma once
// Wall time per named section of a run, and the table a run prints at its end (LAMMPS' and
// ExaMiniMD's closing summary): each section's seconds as min / avg / max over the ranks, its
// share of the run's wall time and how often it ran. Timers wrap the calls of an orchestrating
// function (a time step, a protocol), never the inside of a kernel.

#include "common/mpi.hpp"

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace aniso {

/// Accumulated seconds and call counts of a fixed list of sections, indexed by position.
class SectionTimes {
public:
  using Clock = std::chrono::steady_clock;

  explicit SectionTimes(std::vector<std::string> names);
  /// Adds the time since `start` to section `k`, counted as `calls` calls, and returns now (the
  /// start of what follows).
  Clock::time_point add_since(std::size_t k, Clock::time_point start, std::int64_t calls = 1) {
    const Clock::time_point now = Clock::now();
    seconds_[k] += std::chrono::duration<double>(now - start).count();
    calls_[k] += calls;
    return now;
  }
  void add(std::size_t k, double seconds, std::int64_t calls = 1) {
    seconds_[k] += seconds;
    calls_[k] += calls;
  }
  /// Adds every section of `other` (same names) to this one.
  void merge(const SectionTimes& other);
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] double seconds(std::size_t k) const { return seconds_[k]; }
  [[nodiscard]] std::int64_t calls(std::size_t k) const { return calls_[k]; }

private:
  std::vector<std::string> names_;
  std::vector<double> seconds_;
  std::vector<std::int64_t> calls_;
};

/// Adds the lifetime of the object to one section (exception-safe).
class ScopedSection {
public:
  ScopedSection(SectionTimes& times, std::size_t section)
      : times_(times), section_(section), start_(SectionTimes::Clock::now()) {}
  ~ScopedSection() { times_.add_since(section_, start_); }
  ScopedSection(const ScopedSection&) = delete;
  ScopedSection& operator=(const ScopedSection&) = delete;

private:
  SectionTimes& times_;
  std::size_t section_;
  SectionTimes::Clock::time_point start_;
};

struct TimingRow {
  std::string name;
  double min = 0, avg = 0, max = 0; ///< seconds over the ranks
  double share = 0;                 ///< avg over the run's wall time
  std::int64_t calls = 0;           ///< on rank 0
};

/// The rows of `times` over all ranks, plus a last row "other" for the wall time no section
/// holds (collective). `wall_seconds` is this rank's wall time of the whole run.
std::vector<TimingRow> timing_rows(const SectionTimes& times, double wall_seconds, const mpi::Comm& comm);

/// "timing: W s wall on N rank(s)": the line every program logs at the end of a run, alone or as
/// the head of its timing table; a campaign's stage times are read from it (paper_export.py).
std::string wall_time_line(double wall_seconds, int n_ranks);

/// Seconds since `start` on the clock of SectionTimes.
double seconds_since(SectionTimes::Clock::time_point start);

/// The table as aligned text lines, headed by the run's wall time.
std::vector<std::string> format_timing_table(const std::vector<TimingRow>& rows, double wall_seconds,
                                             int n_ranks);

} // namespace aniso
