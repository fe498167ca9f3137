// Deterministic reductions: the global sum of a fixed set of terms is the same
// bits whatever the number of ranks (this test runs on 1, 2 and 3) and however
// the terms are dealt out. Naive MPI_SUM of doubles fails this test.
#include "common/exact_sum.hpp"
#include "common/mpi.hpp"
#include "common/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

using aniso::ExactSum;
using aniso::mpi::Comm;

std::vector<double> global_terms() {
  aniso::RandomStream stream(2024, 5);
  std::vector<double> terms(1000);
  for (auto& term : terms)
    term = std::ldexp(stream.uniform(-1.0, 1.0), static_cast<int>(stream.below(80)) - 40);
  return terms;
}

double serial_reference(const std::vector<double>& terms) {
  ExactSum sum;
  for (double term : terms)
    sum.add(term);
  return sum.value();
}

TEST(MpiReductions, ExactSumIsIndependentOfRankCountAndDeal) {
  const Comm comm = Comm::world();
  const std::vector<double> terms = global_terms();
  const auto n = terms.size();
  const auto n_ranks = static_cast<std::size_t>(comm.size());
  const auto rank = static_cast<std::size_t>(comm.rank());
  ExactSum round_robin, block, reversed_block;
  for (std::size_t i = rank; i < n; i += n_ranks)
    round_robin.add(terms[i]);
  for (std::size_t i = rank * n / n_ranks; i < (rank + 1) * n / n_ranks; ++i)
    block.add(terms[i]);
  for (std::size_t i = (rank + 1) * n / n_ranks; i-- > rank * n / n_ranks;)
    reversed_block.add(terms[i]);
  const double reference = serial_reference(terms);
  EXPECT_EQ(comm.sum_exact(round_robin).value(), reference);
  EXPECT_EQ(comm.sum_exact(block).value(), reference);
  EXPECT_EQ(comm.sum_exact(reversed_block).value(), reference);
  if (comm.is_root()) std::printf("exact global sum on %zu ranks: %a\n", n_ranks, reference);
}

TEST(MpiReductions, ElementWiseSumOfDoubles) {
  const Comm comm = Comm::world();
  // 1e16 and 1.0 from alternating ranks: naive summation order changes the result.
  std::vector<double> local{comm.rank() % 2 == 1 ? -1e16 : 1e16, 1.0, 0.1 * (comm.rank() + 1)};
  const std::vector<double> result = comm.sum_exact(local);
  ExactSum first, second, third;
  for (int r = 0; r < comm.size(); ++r) {
    first.add(r % 2 == 1 ? -1e16 : 1e16);
    second.add(1.0);
    third.add(0.1 * (r + 1));
  }
  EXPECT_EQ(result[0], first.value());
  EXPECT_EQ(result[1], second.value());
  EXPECT_EQ(result[2], third.value());
  EXPECT_EQ(comm.max(result[2]), comm.min(result[2])) << "ranks disagree on the reduced value";
  EXPECT_TRUE(std::isnan(comm.sum_exact(comm.rank() == 0 ? std::nan("") : 1.0)));
}

TEST(MpiReductions, IntegerHelpers) {
  const Comm comm = Comm::world();
  const std::int64_t n = comm.size();
  EXPECT_EQ(comm.sum(std::int64_t{comm.rank() + 1}), n * (n + 1) / 2);
  EXPECT_EQ(comm.exclusive_scan(std::int64_t{2}), 2 * comm.rank());
  EXPECT_EQ(comm.max(std::int64_t{comm.rank()}), n - 1);
  EXPECT_TRUE(comm.any(comm.rank() == n - 1));
  EXPECT_FALSE(comm.any(false));
  const auto gathered = comm.all_gather(std::int64_t{10 * comm.rank()});
  ASSERT_EQ(static_cast<std::int64_t>(gathered.size()), n);
  for (int r = 0; r < comm.size(); ++r)
    EXPECT_EQ(gathered[static_cast<std::size_t>(r)], 10 * r);
  std::vector<char> bytes;
  if (comm.is_root()) bytes = {'a', 'n', 'i'};
  comm.broadcast(bytes);
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "ani");
}

} // namespace
