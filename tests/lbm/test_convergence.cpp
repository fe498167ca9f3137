// The stop test of a flow from rest (lbm/convergence.hpp): the error it estimates from a decaying
// series of changes, where it must not stop, and the change criterion it replaces.
#include "lbm/convergence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace aniso::lbm {
namespace {

/// Index of the change after which the test stops, or -1 if it never does.
int stop_index(ConvergenceTest& test, const std::vector<double>& changes) {
  for (std::size_t k = 0; k < changes.size(); ++k)
    if (test.converged_after(changes[k])) return static_cast<int>(k);
  return -1;
}

std::vector<double> geometric(double first, double ratio, int n) {
  std::vector<double> c;
  for (int k = 0; k < n; ++k)
    c.push_back(first * std::pow(ratio, k));
  return c;
}

TEST(Convergence, ErrorOfAGeometricDecayIsItsTail) {
  // c_k = 0.2 rho^k: what is left after change k is sum_{j>k} c_j = c_k rho / (1 - rho) exactly.
  for (double rho : {0.3, 0.5, 0.9, 0.99}) {
    ConvergenceTest test(StopCriterion::error, 1e-4);
    const std::vector<double> c = geometric(0.2, rho, 5000);
    const int k = stop_index(test, c);
    ASSERT_GE(k, 2) << "rho " << rho;
    const double tail = c[static_cast<std::size_t>(k)] * rho / (1 - rho);
    EXPECT_NEAR(test.estimated_error(), tail, 1e-12 * tail) << "rho " << rho;
    EXPECT_LE(tail, 1e-4) << "rho " << rho;
    // ... and not one check later than needed: the tail one change earlier was above 1e-4.
    EXPECT_GT(tail / rho, 1e-4) << "rho " << rho;
  }
}

TEST(Convergence, TheChangeCriterionLeavesAnErrorThatGrowsWithTheDecayTime) {
  // What the error criterion fixes: at tolerance 1e-5 on the change, rho = 0.99 stops with 1e-3
  // of <j> still to come.
  ConvergenceTest test(StopCriterion::change, 1e-5);
  const std::vector<double> c = geometric(0.2, 0.99, 5000);
  const int k = stop_index(test, c);
  ASSERT_GE(k, 0);
  EXPECT_LE(c[static_cast<std::size_t>(k)], 1e-5);
  EXPECT_GT(c[static_cast<std::size_t>(k)] / 0.99, 1e-5);
  EXPECT_NEAR(test.estimated_error(), c[static_cast<std::size_t>(k)] * 99, 1e-9);
  EXPECT_GT(test.estimated_error(), 9e-4);
}

TEST(Convergence, ADipOfOneChangeDoesNotStopTheRun) {
  // A component through zero can make one change small by chance: one small ratio beside a
  // steady one is not a steady decay.
  std::vector<double> c = geometric(0.2, 0.8, 10);
  c.push_back(1e-9);
  c.push_back(c[9] * 0.8);
  ConvergenceTest test(StopCriterion::error, 1e-4);
  EXPECT_EQ(stop_index(test, c), -1);
}

TEST(Convergence, GrowingOrSteadyChangesNeverConverge) {
  ConvergenceTest growing(StopCriterion::error, 1e-4);
  EXPECT_EQ(stop_index(growing, geometric(1e-5, 1.01, 100)), -1);
  EXPECT_TRUE(std::isinf(growing.estimated_error()));
  ConvergenceTest steady(StopCriterion::error, 1e-4);
  EXPECT_EQ(stop_index(steady, std::vector<double>(100, 1e-5)), -1);
}

TEST(Convergence, ChangesStalledFarBelowTheToleranceEndTheRun) {
  // Single-precision round-off: the changes stop decaying at a level far below the tolerance.
  ConvergenceTest test(StopCriterion::error, 1e-4);
  EXPECT_EQ(stop_index(test, {1e-2, 3e-7, 5e-7, 4e-7}), 2);
  ConvergenceTest zero(StopCriterion::error, 1e-4);
  EXPECT_EQ(stop_index(zero, {1e-2, 0.0, 0.0}), 2);
}

TEST(Convergence, NeedsThreeChangesForAnEstimate) {
  ConvergenceTest test(StopCriterion::error, 1e-3);
  EXPECT_FALSE(test.converged_after(1e-3));
  EXPECT_FALSE(test.converged_after(5e-4));
  EXPECT_TRUE(std::isinf(test.estimated_error()));
  EXPECT_TRUE(test.converged_after(2.5e-4));
  EXPECT_DOUBLE_EQ(test.estimated_error(), 2.5e-4);
}

} // namespace
} // namespace aniso::lbm
