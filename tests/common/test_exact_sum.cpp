// ExactSum: the sum of doubles must not depend on the order of the terms.
#include "common/exact_sum.hpp"
#include "common/rng.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace {

double exact_sum(const std::vector<double>& terms) {
  aniso::ExactSum sum;
  for (double term : terms)
    sum.add(term);
  return sum.value();
}

std::vector<double> wide_range_terms(std::uint64_t seed, int n) {
  aniso::RandomStream stream(seed, 0);
  std::vector<double> terms;
  for (int i = 0; i < n; ++i) {
    const double magnitude = std::ldexp(stream.uniform(0.5, 1.0), static_cast<int>(stream.below(120)) - 60);
    terms.push_back(stream.uniform01() < 0.5 ? -magnitude : magnitude);
  }
  return terms;
}

TEST(ExactSum, SimpleValuesAreExact) {
  EXPECT_EQ(exact_sum({}), 0.0);
  EXPECT_EQ(exact_sum({1.0, 2.0, 3.5}), 6.5);
  EXPECT_EQ(exact_sum({-1.0, 0.25}), -0.75);
  EXPECT_EQ(exact_sum({0.1}), 0.1);
}

TEST(ExactSum, CancellationThatNaiveSummationLoses) {
  // 1e100 + 1 - 1e100 is 1 exactly; naive left-to-right summation gives 0.
  EXPECT_EQ(exact_sum({1e100, 1.0, -1e100}), 1.0);
  EXPECT_EQ(exact_sum({1.0, 1e-300, -1.0}), 1e-300);
}

TEST(ExactSum, ExtremesOfTheDoubleRange) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double huge = std::numeric_limits<double>::max();
  EXPECT_EQ(exact_sum({tiny}), tiny);
  EXPECT_EQ(exact_sum({tiny, tiny}), 2 * tiny);
  EXPECT_EQ(exact_sum({huge, -huge, tiny}), tiny);
  EXPECT_EQ(exact_sum({huge * 0.5, huge * 0.5}), huge);
  EXPECT_TRUE(std::isinf(exact_sum({huge, huge})));
  EXPECT_TRUE(std::isnan(exact_sum({1.0, std::nan("")})));
}

TEST(ExactSum, OrderIndependentBitForBit) {
  std::vector<double> terms = wide_range_terms(42, 5000);
  const double reference = exact_sum(terms);
  aniso::RandomStream shuffler(7, 0);
  for (int trial = 0; trial < 20; ++trial) {
    for (std::size_t i = terms.size() - 1; i > 0; --i)
      std::swap(terms[i], terms[shuffler.below(i + 1)]);
    EXPECT_EQ(exact_sum(terms), reference) << "trial " << trial;
  }
}

TEST(ExactSum, CorrectlyRoundedAgainstLongDoubleOnModestRanges) {
  // With terms within 2^±10 of each other and few enough of them, an 80-bit long
  // double sum in sorted order is exact, so it is the reference.
  aniso::RandomStream stream(3, 1);
  std::vector<double> terms;
  for (int i = 0; i < 200; ++i)
    terms.push_back(std::ldexp(stream.uniform(-1.0, 1.0), static_cast<int>(stream.below(8))));
  long double reference = 0;
  for (double term : terms)
    reference += term;
  EXPECT_EQ(exact_sum(terms), static_cast<double>(reference));
}

TEST(ExactSum, MergingPartialSumsEqualsOneSum) {
  const std::vector<double> terms = wide_range_terms(11, 3000);
  for (std::size_t split : {std::size_t{1}, std::size_t{1000}, std::size_t{2999}}) {
    aniso::ExactSum left, right;
    for (std::size_t i = 0; i < split; ++i)
      left.add(terms[i]);
    for (std::size_t i = split; i < terms.size(); ++i)
      right.add(terms[i]);
    right.add(left);
    EXPECT_EQ(right.value(), exact_sum(terms));
  }
}

} // namespace
