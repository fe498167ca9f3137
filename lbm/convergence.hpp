#pragma once
// When a steady flow from rest has converged, from the relative changes of the mean momentum
// <j> between consecutive checks (docs/methods/lbm.md, "Convergence and divergence").
//
// A Stokes flow from rest approaches its steady state as a sum of decaying modes; once the
// slowest dominates, the changes between checks form a geometric series c_k = c_0 rho^k and
// what remains of the flow to come is c_k rho / (1 - rho). The error criterion stops when that
// estimate is below the tolerance, so the tolerance is the error of K itself whatever the
// image's decay time; the change criterion (the earlier default) stops when c_k alone is below
// it, which leaves an error of tolerance x rho / (1 - rho): 10x the tolerance at rho = 0.91,
// 1x at 0.5.

#include <limits>
#include <string_view>

namespace aniso::lbm {

enum class StopCriterion { error, change };

[[nodiscard]] std::string_view stop_criterion_name(StopCriterion criterion);

class ConvergenceTest {
public:
  ConvergenceTest(StopCriterion criterion, double tolerance) : criterion_(criterion), tolerance_(tolerance) {}

  /// Takes the relative change of <j> since the previous check; true once converged.
  bool converged_after(double change);

  /// Estimated relative error of <j> left after the latest check: c rho / (1 - rho) with rho the
  /// larger of the last two ratios of changes; infinite until three changes show a steady decay
  /// (both ratios below 1 and within a factor 2 of each other).
  [[nodiscard]] double estimated_error() const { return estimate_; }

  /// What the tolerance is compared with: the estimate (error criterion) or the change.
  [[nodiscard]] double measure() const { return criterion_ == StopCriterion::error ? estimate_ : last_; }

private:
  StopCriterion criterion_;
  double tolerance_;
  int seen_ = 0;
  double before_last_ = 0;
  double last_ = 0;
  double estimate_ = std::numeric_limits<double>::infinity();
};

} // namespace aniso::lbm
