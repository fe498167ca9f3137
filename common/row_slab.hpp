#pragma once
// Contiguous shares of a dataset's rows over the ranks: rank r of P holds rows
// [R r / P, R (r + 1) / P). The parallel checkpoint writer gathers each block on its rank
// before writing it, the distributed read hands the rows out this way, and after such a read
// a particle's row (its id) names the rank that knows where the particle went.

#include <cstdint>

namespace aniso {

struct RowSlab {
  std::uint64_t first = 0; ///< first row of the slab
  std::uint64_t count = 0; ///< rows in it (0 where there are more ranks than rows)
  [[nodiscard]] std::uint64_t end() const { return first + count; }
};

/// The first row of rank `rank`'s slab of `total` rows over `ranks` ranks (rank == ranks: total).
[[nodiscard]] std::uint64_t slab_start(std::uint64_t total, int rank, int ranks);
/// Rank `rank`'s slab of `total` rows over `ranks` ranks.
[[nodiscard]] RowSlab row_slab(std::uint64_t total, int rank, int ranks);
/// The rank whose slab holds `row` (row < total).
[[nodiscard]] int rank_of_row(std::uint64_t total, std::uint64_t row, int ranks);

} // namespace aniso
