#include "dem/parallel/domain.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aniso::dem::parallel {

int Domain::bin_of(const PeriodicCell& cell, const Vec3& position) const {
  int b[3];
  for (int a = 0; a < 3; ++a) {
    b[a] = static_cast<int>(position[a] / cell.lengths()[a] * n_bins_[a]);
    b[a] = std::clamp(b[a], 0, n_bins_[a] - 1);
  }
  return (b[0] * n_bins_[1] + b[1]) * n_bins_[2] + b[2];
}

std::vector<int> Domain::neighbour_bins(int bin) const {
  const int b2 = bin % n_bins_[2], b1 = (bin / n_bins_[2]) % n_bins_[1], b0 = bin / (n_bins_[1] * n_bins_[2]);
  std::vector<int> result;
  for (int o0 = -1; o0 <= 1; ++o0)
    for (int o1 = -1; o1 <= 1; ++o1)
      for (int o2 = -1; o2 <= 1; ++o2) {
        const int c0 = (b0 + o0 + n_bins_[0]) % n_bins_[0];
        const int c1 = (b1 + o1 + n_bins_[1]) % n_bins_[1];
        const int c2 = (b2 + o2 + n_bins_[2]) % n_bins_[2];
        const int other = (c0 * n_bins_[1] + c1) * n_bins_[2] + c2;
        if (other != bin) result.push_back(other);
      }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

void Domain::partition(const PeriodicCell& cell, double reach, const std::vector<Vec3>& positions) {
  for (int a = 0; a < 3; ++a)
    n_bins_[a] = std::max(1, static_cast<int>(cell.lengths()[a] / reach));
  const int total = n_bins();
  const int n_ranks = comm_.size();
  owner_.assign(static_cast<std::size_t>(total), 0);
  if (n_ranks > 1) {
    if (total < n_ranks) {
      throw InputError(
          fmt::format("the cell holds only {} bins of one interaction range ({} x {} x {}) for {} MPI "
                      "ranks: use fewer ranks or more particles",
                      total, n_bins_[0], n_bins_[1], n_bins_[2], n_ranks));
    }
    std::vector<std::int64_t> counts(static_cast<std::size_t>(total), 0);
    for (const Vec3& x : positions)
      ++counts[static_cast<std::size_t>(bin_of(cell, x))];
    counts = comm_.sum(std::span<const std::int64_t>(counts));
    // Rank 0 partitions and broadcasts, so every rank holds the same map whatever METIS does internally.
    std::vector<char> bytes;
    if (comm_.is_root()) {
      std::vector<idx_t> offsets{0}, adjacency, weights;
      for (int b = 0; b < total; ++b) {
        for (int other : neighbour_bins(b))
          adjacency.push_back(other);
        offsets.push_back(static_cast<idx_t>(adjacency.size()));
        weights.push_back(static_cast<idx_t>(counts[static_cast<std::size_t>(b)] + 1));
      }
      idx_t n_vertices = total, n_constraints = 1, n_parts = n_ranks, cut = 0;
      idx_t options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_SEED] = 1;
      std::vector<idx_t> part(static_cast<std::size_t>(total), 0);
      const int status =
          METIS_PartGraphKway(&n_vertices, &n_constraints, offsets.data(), adjacency.data(), weights.data(),
                              nullptr, nullptr, &n_parts, nullptr, nullptr, options, &cut, part.data());
      if (status != METIS_OK) throw Error(ExitCode::internal_error, "METIS_PartGraphKway failed");
      bytes.resize(part.size() * sizeof(int));
      for (std::size_t b = 0; b < part.size(); ++b) {
        const int rank = static_cast<int>(part[b]);
        std::memcpy(bytes.data() + b * sizeof(int), &rank, sizeof(int));
      }
    }
    comm_.broadcast(bytes);
    for (std::size_t b = 0; b < owner_.size(); ++b)
      std::memcpy(&owner_[b], bytes.data() + b * sizeof(int), sizeof(int));
  }
  ghost_ranks_.assign(static_cast<std::size_t>(total), {});
  for (int b = 0; b < total; ++b) {
    auto& ranks = ghost_ranks_[static_cast<std::size_t>(b)];
    for (int other : neighbour_bins(b)) {
      const int rank = owner_of_bin(other);
      if (rank != owner_of_bin(b)) ranks.push_back(rank);
    }
    std::sort(ranks.begin(), ranks.end());
    ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
  }
  ++n_partitions_;
}

bool Domain::needs_partition(const PeriodicCell& cell, double reach, std::size_t n_owned,
                             double max_imbalance) const {
  bool stale = owner_.empty();
  for (int a = 0; a < 3 && !stale; ++a)
    stale = cell.lengths()[a] / n_bins_[a] < reach;
  if (comm_.size() == 1) return stale;
  const auto local = static_cast<std::int64_t>(n_owned);
  const double mean = static_cast<double>(comm_.sum(local)) / comm_.size();
  const double largest = static_cast<double>(comm_.max(local));
  return stale || largest > max_imbalance * mean;
}

} // namespace aniso::dem::parallel
