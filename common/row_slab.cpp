#include "common/row_slab.hpp"

namespace aniso {

std::uint64_t slab_start(std::uint64_t total, int rank, int ranks) {
  // R r / P without forming R r, which could overflow: R = q P + s gives q r + s r / P (s r < P^2).
  const auto r = static_cast<std::uint64_t>(rank), p = static_cast<std::uint64_t>(ranks);
  return total / p * r + total % p * r / p;
}

RowSlab row_slab(std::uint64_t total, int rank, int ranks) {
  const std::uint64_t first = slab_start(total, rank, ranks);
  return {first, slab_start(total, rank + 1, ranks) - first};
}

int rank_of_row(std::uint64_t total, std::uint64_t row, int ranks) {
  // The last rank whose slab starts at or before the row: empty slabs start where the next one does.
  int low = 0, high = ranks - 1;
  while (low < high) {
    const int middle = low + (high - low + 1) / 2;
    if (slab_start(total, middle, ranks) <= row)
      low = middle;
    else
      high = middle - 1;
  }
  return low;
}

} // namespace aniso
