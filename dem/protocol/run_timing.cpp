#include "dem/protocol/run_timing.hpp"

namespace aniso::dem::protocol {

std::vector<TimingRow> run_timing(const SectionTimes& engine, const SectionTimes& protocol,
                                  double wall_seconds, const mpi::Comm& comm) {
  std::vector<std::string> names = engine.names();
  names.insert(names.end(), protocol.names().begin(), protocol.names().end());
  SectionTimes joined(names);
  for (std::size_t k = 0; k < engine.names().size(); ++k)
    joined.add(k, engine.seconds(k), engine.calls(k));
  for (std::size_t k = 0; k < protocol.names().size(); ++k)
    joined.add(engine.names().size() + k, protocol.seconds(k), protocol.calls(k));
  return timing_rows(joined, wall_seconds, comm);
}

void log_timing(const Logger& logger, const std::vector<TimingRow>& rows, double wall_seconds, int n_ranks,
                const std::vector<std::string>& phases) {
  for (const std::string& line : format_timing_table(rows, wall_seconds, n_ranks))
    logger->info("{}", line);
  for (const std::string& line : phases)
    logger->info("  {}", line);
}

} // namespace aniso::dem::protocol
