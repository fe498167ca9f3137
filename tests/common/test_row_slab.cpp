// Slabs of rows over ranks: they tile [0, R) in rank order, differ in size by at most one, and
// rank_of_row finds the slab of every row, empty slabs (more ranks than rows) included.
#include "common/row_slab.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

namespace {

TEST(RowSlab, SlabsTileTheRowsAndEveryRowFindsItsRank) {
  for (const std::uint64_t total : {0, 1, 2, 5, 7, 64, 1000, 6401}) {
    for (const int ranks : {1, 2, 3, 4, 7, 16, 1024}) {
      std::uint64_t next = 0;
      for (int rank = 0; rank < ranks; ++rank) {
        const aniso::RowSlab slab = aniso::row_slab(total, rank, ranks);
        ASSERT_EQ(slab.first, next) << total << " rows, rank " << rank << " of " << ranks;
        EXPECT_LE(slab.count, total / static_cast<std::uint64_t>(ranks) + 1);
        EXPECT_GE(slab.count, total / static_cast<std::uint64_t>(ranks));
        for (std::uint64_t row = slab.first; row < slab.end(); ++row)
          ASSERT_EQ(aniso::rank_of_row(total, row, ranks), rank) << "row " << row << " of " << total;
        next = slab.end();
      }
      EXPECT_EQ(next, total);
    }
  }
}

TEST(RowSlab, NoOverflowForHugeRowCounts) {
  // R r overflows 64 bits here; the slabs must still tile the rows.
  const std::uint64_t total = std::numeric_limits<std::uint64_t>::max() - 3;
  const int ranks = 1000;
  EXPECT_EQ(aniso::slab_start(total, ranks, ranks), total);
  for (int rank = 0; rank < ranks; ++rank) {
    const aniso::RowSlab slab = aniso::row_slab(total, rank, ranks);
    EXPECT_EQ(slab.end(), aniso::slab_start(total, rank + 1, ranks));
    EXPECT_EQ(aniso::rank_of_row(total, slab.first, ranks), rank);
    EXPECT_EQ(aniso::rank_of_row(total, slab.end() - 1, ranks), rank);
  }
}

} // namespace
