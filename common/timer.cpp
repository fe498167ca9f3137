#include "common/timer.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <span>

namespace aniso {

SectionTimes::SectionTimes(std::vector<std::string> names)
    : names_(std::move(names)), seconds_(names_.size(), 0.0), calls_(names_.size(), 0) {}

void SectionTimes::merge(const SectionTimes& other) {
  check_invariant(other.names_ == names_, "merged section timers have the same sections");
  for (std::size_t k = 0; k < names_.size(); ++k)
    add(k, other.seconds_[k], other.calls_[k]);
}

std::vector<TimingRow> timing_rows(const SectionTimes& times, double wall_seconds, const mpi::Comm& comm) {
  std::vector<double> local;
  double held = 0;
  for (std::size_t k = 0; k < times.names().size(); ++k) {
    local.push_back(times.seconds(k));
    held += times.seconds(k);
  }
  local.push_back(std::max(0.0, wall_seconds - held)); // other
  std::vector<double> negated(local.size());
  std::transform(local.begin(), local.end(), negated.begin(), [](double seconds) { return -seconds; });
  std::vector<double> low = comm.max(std::span<const double>(negated));
  for (double& seconds : low)
    seconds = -seconds;
  const std::vector<double> high = comm.max(std::span<const double>(local));
  const std::vector<double> sum = comm.sum_exact(std::span<const double>(local));
  const double wall = comm.max(wall_seconds);
  std::vector<TimingRow> rows;
  for (std::size_t k = 0; k < local.size(); ++k) {
    TimingRow row;
    row.name = k < times.names().size() ? times.names()[k] : "other";
    row.min = low[k];
    row.max = high[k];
    row.avg = sum[k] / comm.size();
    row.share = wall > 0 ? row.avg / wall : 0.0;
    row.calls = k < times.names().size() ? times.calls(k) : 0;
    rows.push_back(row);
  }
  return rows;
}

std::string wall_time_line(double wall_seconds, int n_ranks) {
  return fmt::format("timing: {:.3f} s wall on {} rank(s)", wall_seconds, n_ranks);
}

double seconds_since(SectionTimes::Clock::time_point start) {
  return std::chrono::duration<double>(SectionTimes::Clock::now() - start).count();
}

std::vector<std::string> format_timing_table(const std::vector<TimingRow>& rows, double wall_seconds,
                                             int n_ranks) {
  std::size_t width = 7;
  for (const TimingRow& row : rows)
    width = std::max(width, row.name.size());
  std::vector<std::string> lines;
  lines.push_back(wall_time_line(wall_seconds, n_ranks));
  lines.push_back(fmt::format("  {:<{}} {:>10} {:>10} {:>10} {:>7} {:>12}", "section", width, "min [s]",
                              "avg [s]", "max [s]", "%total", "calls"));
  for (const TimingRow& row : rows)
    lines.push_back(fmt::format("  {:<{}} {:>10.3f} {:>10.3f} {:>10.3f} {:>6.1f}% {:>12}", row.name, width,
                                row.min, row.avg, row.max, 100.0 * row.share, row.calls));
  return lines;
}

} // namespace aniso
