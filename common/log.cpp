#include "common/log.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/sinks/stdout_sinks.h>

#include <cmath>

namespace aniso {

Logger make_logger(const std::string& program, const mpi::Comm& comm, const std::string& level_name) {
  const auto level = spdlog::level::from_str(level_name);
  if (level == spdlog::level::off && level_name != "off") {
    throw InputError(
        fmt::format("log level '{}' is not one of trace, debug, info, warn, error, off", level_name));
  }
  Logger logger;
  if (comm.is_root()) {
    logger = std::make_shared<spdlog::logger>(program, std::make_shared<spdlog::sinks::stdout_sink_mt>());
    logger->set_level(level);
  } else {
    logger = std::make_shared<spdlog::logger>(program, std::make_shared<spdlog::sinks::stderr_sink_mt>());
    logger->set_level(std::max(level, spdlog::level::err));
  }
  logger->set_pattern(comm.is_root() ? "[%T] %^%l%$ %v" : fmt::format("[%T] rank {} %^%l%$ %v", comm.rank()));
  return logger;
}

Logger make_silent_logger() {
  auto logger = std::make_shared<spdlog::logger>("silent", std::make_shared<spdlog::sinks::null_sink_mt>());
  logger->set_level(spdlog::level::off);
  return logger;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const auto total = static_cast<long long>(std::llround(seconds));
  if (total >= 3600) return fmt::format("{} h {:02} min", total / 3600, (total % 3600) / 60);
  if (total >= 60) return fmt::format("{} min {:02} s", total / 60, total % 60);
  return fmt::format("{} s", total);
}

Progress::Progress(Logger logger, std::string label, double total, double interval_seconds, Clock clock,
                   double from)
    : logger_(std::move(logger)), label_(std::move(label)), total_(total), from_(from),
      interval_(interval_seconds), clock_(clock ? std::move(clock) : Clock([] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
      })),
      start_(clock_()), last_print_(start_), printed_{{start_, from}} {}

std::string Progress::line(double done) const {
  const double now = clock_();
  const double elapsed = now - start_;
  const double fraction = total_ > 0 ? done / total_ : 0.0;
  // The pace since the last print at least half the elapsed time ago (the start if none).
  auto since = printed_.front();
  for (const auto& sample : printed_) {
    if (sample.first > now - 0.5 * elapsed) break;
    since = sample;
  }
  const double advanced = done - since.second;
  const double remaining = advanced > 0 ? (now - since.first) * (total_ - done) / advanced : NAN;
  return fmt::format("{}: {:.1f}% ({:.4g} of {:.4g}), elapsed {}, ETA {}", label_, 100.0 * fraction, done,
                     total_, format_duration(elapsed), format_duration(remaining));
}

bool Progress::update(double done, const std::function<std::string()>& detail) {
  const double now = clock_();
  if (now - last_print_ < interval_) return false;
  last_print_ = now;
  if (detail)
    logger_->info("{}, {}", line(done), detail());
  else
    logger_->info("{}", line(done));
  printed_.emplace_back(now, done);
  return true;
}

} // namespace aniso
