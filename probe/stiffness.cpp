#include "probe/stiffness.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aniso::probe {
namespace {

struct ForkModuli {
  Vec3 column = Vec3::Zero(); ///< d sigma_jj / d eps_ii for j = 1..3 (secant over the whole increment)
  double linearity = 0;
  double noise = 0;
  double sliding = 0;
  double resolution = 0;
};

// d sigma(t) of a fork against the reference at the same steps.
std::vector<Mat3> differences(const std::vector<Mat3>& fork, const std::vector<Mat3>& reference, int index) {
  require_input(
      fork.size() == reference.size(),
      fmt::format("fork {} has {} stress samples, the reference {}: they were not run with the same "
                  "steps",
                  index, fork.size(), reference.size()));
  std::vector<Mat3> d(fork.size());
  for (std::size_t k = 0; k < fork.size(); ++k)
    d[k] = fork[k] - reference[k];
  return d;
}

ForkModuli fork_moduli(const ForkResult& fork, const ForkResult& reference) {
  const ForkSpec spec = fork_spec(fork.index);
  const int a = spec.axis;
  const double strain = fork.strain_final[a];
  const double strain_half = fork.strain_half[a];
  require_input(spec.sign * strain > 0 && spec.sign * strain_half > 0 &&
                    spec.sign * (strain - strain_half) > 0,
                fmt::format("fork {}: the loaded axis x{} strained by {:.4g} (half {:.4g}); expected sign {}",
                            fork.index, a + 1, strain, strain_half, spec.sign > 0 ? "+" : "-"));
  const std::vector<Mat3> d_half = differences(fork.samples_half, reference.samples_half, fork.index);
  const std::vector<Mat3> d_final = differences(fork.samples_final, reference.samples_final, fork.index);
  const Mat3 mean_half = mean_of(d_half), mean_final = mean_of(d_final);
  ForkModuli m;
  m.column = mean_final.diagonal() / strain;
  // Secant moduli of the two halves: equal for an incrementally linear response.
  const double first = mean_half(a, a) / strain_half;
  const double second = (mean_final(a, a) - mean_half(a, a)) / (strain - strain_half);
  m.linearity = std::abs(second - first) / std::abs(m.column[a]);
  double square_sum = 0;
  for (const Mat3& d : d_final)
    square_sum += (d(a, a) - mean_final(a, a)) * (d(a, a) - mean_final(a, a));
  m.noise = std::sqrt(square_sum / static_cast<double>(d_final.size())) / std::abs(mean_final(a, a));
  // Contacts made to slide by the increment: the fork's count against the reference's at the same step.
  m.sliding = static_cast<double>(fork.sliding_final - reference.sliding_final) /
              static_cast<double>(std::max<std::int64_t>(reference.contacts_final, 1));
  m.resolution = std::abs(mean_final(a, a)) / mean_of(reference.samples_final).cwiseAbs().maxCoeff();
  return m;
}

} // namespace

Stiffness assemble_stiffness(const std::array<ForkResult, n_fork_files>& forks) {
  for (int k = 0; k < n_fork_files; ++k) {
    const int index = forks[static_cast<std::size_t>(k)].index;
    require_input(index == k, fmt::format("fork results out of order: position {} holds fork {}", k, index));
  }
  const ForkResult& reference = forks[reference_fork];
  Stiffness s;
  for (int k = 1; k <= n_forks; ++k) {
    const ForkResult& fork = forks[static_cast<std::size_t>(k)];
    const ForkSpec spec = fork_spec(fork.index);
    const int i = spec.axis;
    const ForkModuli m = fork_moduli(fork, reference);
    const bool plus = spec.sign > 0;
    (plus ? s.Q_plus : s.Q_minus).col(i) = m.column;               // eqs. (Oplus), (Ominus)
    (plus ? s.O_plus : s.O_minus)[i] = m.column[i];                // O_i = d sigma_ii / d eps_ii
    (plus ? s.K_plus : s.K_minus).col(i) = m.column / m.column[i]; // K_i^j = d sigma_jj / d sigma_ii
    (plus ? s.linearity_plus : s.linearity_minus)[i] = m.linearity;
    (plus ? s.noise_plus : s.noise_minus)[i] = m.noise;
    (plus ? s.sliding_plus : s.sliding_minus)[i] = m.sliding;
    (plus ? s.resolution_plus : s.resolution_minus)[i] = m.resolution;
  }
  s.C = 0.5 * (s.Q_plus + s.Q_minus); // eq. (decomp)
  s.D = 0.5 * (s.Q_plus - s.Q_minus);
  s.K_C = s.C.sum() / 9.0;
  return s;
}

std::string increment_problems(const Stiffness& stiffness, const IncrementTolerances& tolerances) {
  const auto largest = [](const Vec3& plus, const Vec3& minus) {
    return std::max(plus.maxCoeff(), minus.maxCoeff());
  };
  const double linearity = largest(stiffness.linearity_plus, stiffness.linearity_minus);
  const double sliding = largest(stiffness.sliding_plus, stiffness.sliding_minus);
  const double resolution =
      std::min(stiffness.resolution_plus.minCoeff(), stiffness.resolution_minus.minCoeff());
  const double noise = largest(stiffness.noise_plus, stiffness.noise_minus);
  std::string problems;
  if (!(linearity <= tolerances.linearity && sliding <= tolerances.sliding)) {
    problems += fmt::format("increment too large: it made {:.3g} of the contacts slide (tolerance {:.3g}) "
                            "and the two half increments "
                            "differ in modulus by {:.3g} of O_i (tolerance {:.3g}): the response is no "
                            "longer incrementally linear; "
                            "lower probe.increment. ",
                            sliding, tolerances.sliding, linearity, tolerances.linearity);
  }
  if (!(resolution >= tolerances.resolution)) {
    problems += fmt::format("increment too small: the stress response is {:.3g} of the stress (floor "
                            "{:.3g}): round-off decides its "
                            "digits; raise probe.increment. ",
                            resolution, tolerances.resolution);
  }
  if (!(noise <= tolerances.noise)) {
    problems += fmt::format(
        "reading unsettled: the stress response fluctuates by {:.3g} of itself over the reading window "
        "(tolerance {:.3g}); raise probe.window_steps or probe.hold_steps. ",
        noise, tolerances.noise);
  }
  if (!problems.empty()) problems.pop_back();
  return problems;
}

} // namespace aniso::probe
