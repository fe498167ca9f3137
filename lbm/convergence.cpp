#include "lbm/convergence.hpp"

#include <algorithm>

namespace aniso::lbm {

std::string_view stop_criterion_name(StopCriterion criterion) {
  return criterion == StopCriterion::error ? "error" : "change";
}

namespace {

// Two changes this far below the tolerance end the run even without a steady ratio: round-off
// (single precision) stalls the ratio near 1, and the error left is then below the tolerance for
// any decay faster than 1% per check.
constexpr double kStalledFraction = 1e-2;

double geometric_tail(double before_last, double last, double change) {
  if (!(before_last > 0) || !(last > 0)) return std::numeric_limits<double>::infinity();
  const double r1 = last / before_last;
  const double r2 = change / last;
  const double rho = std::max(r1, r2);
  // A change that dips by chance (a component through zero) gives one small ratio; a steady decay
  // gives two alike.
  if (!(rho < 1) || std::min(r1, r2) < 0.5 * rho) return std::numeric_limits<double>::infinity();
  return change * rho / (1 - rho);
}

} // namespace

bool ConvergenceTest::converged_after(double change) {
  if (seen_ >= 2) estimate_ = geometric_tail(before_last_, last_, change);
  const bool stalled = seen_ >= 1 && std::max(last_, change) <= kStalledFraction * tolerance_;
  before_last_ = last_;
  last_ = change;
  ++seen_;
  if (criterion_ == StopCriterion::change) return change <= tolerance_;
  return estimate_ <= tolerance_ || stalled;
}

} // namespace aniso::lbm
