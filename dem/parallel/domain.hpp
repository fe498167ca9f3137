#pragma once
// Domain decomposition of the periodic cell: a grid of bins in fractional
// coordinates (so it follows the deforming cell), each at least one
// interaction range wide, assigned to ranks by METIS on the graph of
// neighbouring bins with particle counts as weights. A particle belongs to the
// rank of its bin; a rank keeps ghost copies of every particle in the bins
// next to its own. The grid and the partition are redrawn when the cell has
// deformed so far that a bin is narrower than the range, or when the load is
// out of balance.

#include "common/cell.hpp"
#include "common/mpi.hpp"

#include <cstdint>
#include <vector>

namespace aniso::dem::parallel {

class Domain {
public:
  explicit Domain(const mpi::Comm& comm) : comm_(comm) {}

  /// Redraws the bin grid for `cell` with bins at least `reach` wide, and assigns bins to
  /// ranks from the global particle count per bin (collective). `positions` are this rank's owned particles.
  void partition(const PeriodicCell& cell, double reach, const std::vector<Vec3>& positions);
  /// True if the grid no longer fits the cell (a bin narrower than `reach`) or the owned counts
  /// are out of balance by more than `max_imbalance` (max / mean; collective).
  [[nodiscard]] bool needs_partition(const PeriodicCell& cell, double reach, std::size_t n_owned,
                                     double max_imbalance) const;

  [[nodiscard]] int bin_of(const PeriodicCell& cell, const Vec3& position) const;
  [[nodiscard]] int owner_of_bin(int bin) const { return owner_[static_cast<std::size_t>(bin)]; }
  /// Ranks other than the owner that hold bins next to `bin` (they need ghost copies of its particles).
  [[nodiscard]] const std::vector<int>& ghost_ranks(int bin) const {
    return ghost_ranks_[static_cast<std::size_t>(bin)];
  }
  [[nodiscard]] const mpi::Comm& comm() const { return comm_; }
  [[nodiscard]] int n_bins() const { return n_bins_[0] * n_bins_[1] * n_bins_[2]; }
  [[nodiscard]] std::int64_t n_partitions() const { return n_partitions_; }

private:
  std::vector<int> neighbour_bins(int bin) const;
  mpi::Comm comm_;
  int n_bins_[3] = {1, 1, 1};
  std::vector<int> owner_;
  std::vector<std::vector<int>> ghost_ranks_;
  std::int64_t n_partitions_ = 0;
};

} // namespace aniso::dem::parallel
