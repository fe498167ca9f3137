#include "dem/protocol/run_timing.hpp"

#include <fmt/format.h>

#include <array>

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

std::vector<std::string> halo_lines(const Simulation& simulation) {
  const mpi::Comm& comm = simulation.comm();
  if (comm.size() == 1) return {};
  const data::Particles& particles = simulation.particles();
  const parallel::Halo& halo = simulation.ghost_halo();
  const std::array<double, 4> local{
      static_cast<double>(particles.size() - particles.n_owned), static_cast<double>(particles.n_owned),
      static_cast<double>(halo.n_sent()), static_cast<double>(halo.n_partners())};
  std::array<double, 4> negated{};
  for (std::size_t k = 0; k < local.size(); ++k)
    negated[k] = -local[k];
  const std::vector<double> high = comm.max(std::span<const double>(local));
  const std::vector<double> low = comm.max(std::span<const double>(negated));
  const std::vector<double> sum = comm.sum_exact(std::span<const double>(local));
  const double ranks = comm.size();
  const double bytes = static_cast<double>(parallel::Halo::state_bytes());
  return {fmt::format("halo: {:.0f} ghosts per rank (min {:.0f}, max {:.0f}), {:.1f}% of the owned; a "
                      "refresh sends {:.1f} kB per rank per step (max {:.1f} kB) to at most {:.0f} rank(s)",
                      sum[0] / ranks, -low[0], high[0], 100 * sum[0] / sum[1], sum[2] / ranks * bytes / 1e3,
                      high[2] * bytes / 1e3, high[3])};
}

} // namespace aniso::dem::protocol
