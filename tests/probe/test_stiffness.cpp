// The assembly of Q+, Q-, C, D and K_C (eqs. (Oplus), (Ominus), (decomp)) from a reference and
// six forks, checked on synthetic forks of a material that answers exactly
// d sigma = C d eps + D |d eps| on top of a relaxing reference, and the increment checks on
// forks made non-linear or noisy on purpose.
#include "common/error.hpp"
#include "probe/stiffness.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace aniso::probe {
namespace {

Mat3 sample_C() {
  Mat3 c;
  c << 300e6, 80e6, 70e6, 75e6, 250e6, 60e6, 72e6, 66e6, 200e6;
  return c;
}

Mat3 sample_D() {
  Mat3 d;
  d << -40e6, 5e6, -6e6, 3e6, -25e6, 4e6, -2e6, 7e6, -30e6;
  return d;
}

constexpr std::size_t n_samples = 8;

// The reference relaxes (p falls along the window) and carries a shear stress; forks add to it.
std::vector<Mat3> reference_samples(double offset) {
  std::vector<Mat3> samples;
  for (std::size_t k = 0; k < n_samples; ++k) {
    Mat3 s = -(100e3 - offset - 500.0 * static_cast<double>(k)) * Mat3::Identity();
    s(0, 1) = s(1, 0) = 1e3;
    samples.push_back(s);
  }
  return samples;
}

ForkResult reference() {
  ForkResult f;
  f.index = reference_fork;
  f.samples_half = reference_samples(0.0);
  f.samples_final = reference_samples(2000.0);
  return f;
}

// A fork of the bilinear material: the halves scaled by (1 - bend) and (1 + bend), the readings of the
// final window alternating by +-wobble on the loaded axis.
ForkResult synthetic_fork(int index, double delta, double bend = 0.0, double wobble = 0.0) {
  const ForkSpec spec = fork_spec(index);
  Vec3 d_eps = Vec3::Zero();
  d_eps[spec.axis] = spec.sign * delta;
  const Vec3 d_sigma = sample_C() * d_eps + sample_D() * d_eps.cwiseAbs();
  ForkResult f = reference();
  f.index = index;
  for (std::size_t k = 0; k < n_samples; ++k) {
    f.samples_half[k].diagonal() += 0.5 * (1 - bend) * d_sigma;
    f.samples_final[k].diagonal() += d_sigma;
    f.samples_final[k](spec.axis, spec.axis) += (k % 2 == 0 ? wobble : -wobble);
  }
  f.strain_half = 0.5 * d_eps;
  f.strain_final = d_eps;
  return f;
}

std::array<ForkResult, n_fork_files> synthetic_forks(double delta, double bend = 0.0, double wobble = 0.0) {
  std::array<ForkResult, n_fork_files> forks;
  forks[0] = reference();
  for (int k = 1; k <= n_forks; ++k)
    forks[static_cast<std::size_t>(k)] = synthetic_fork(k, delta, bend, wobble);
  return forks;
}

TEST(ForkSpec, NumbersForksByAxisThenSign) {
  const int axes[] = {0, 0, 0, 1, 1, 2, 2};
  const int signs[] = {0, 1, -1, 1, -1, 1, -1};
  for (int index = 0; index <= n_forks; ++index) {
    EXPECT_EQ(fork_spec(index).axis, axes[index]);
    EXPECT_EQ(fork_spec(index).sign, signs[index]);
  }
  EXPECT_THROW(static_cast<void>(fork_spec(-1)), InputError);
  EXPECT_THROW(static_cast<void>(fork_spec(7)), InputError);
}

TEST(Stiffness, RecoversCAndDOfABilinearMaterial) {
  const Stiffness s = assemble_stiffness(synthetic_forks(5e-5));
  EXPECT_LT((s.C - sample_C()).cwiseAbs().maxCoeff(), 1e-6 * 300e6);
  EXPECT_LT((s.D - sample_D()).cwiseAbs().maxCoeff(), 1e-6 * 300e6);
  EXPECT_NEAR(s.K_C, sample_C().sum() / 9.0, 1e-6 * 300e6);
  EXPECT_LT((s.Q_plus - (sample_C() + sample_D())).cwiseAbs().maxCoeff(), 1e-6 * 300e6);
  EXPECT_LT((s.Q_minus - (sample_C() - sample_D())).cwiseAbs().maxCoeff(), 1e-6 * 300e6);
  for (int i = 0; i < 3; ++i) {
    // O_i and K_i^j as the paper defines them, and Q built back from them.
    EXPECT_NEAR(s.O_plus[i], sample_C()(i, i) + sample_D()(i, i), 1e-6 * 300e6);
    EXPECT_NEAR(s.O_minus[i], sample_C()(i, i) - sample_D()(i, i), 1e-6 * 300e6);
    EXPECT_DOUBLE_EQ(s.K_plus(i, i), 1.0);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(s.K_plus(j, i) * s.O_plus[i], s.Q_plus(j, i), 1e-9 * 300e6);
      EXPECT_NEAR(s.K_minus(j, i) * s.O_minus[i], s.Q_minus(j, i), 1e-9 * 300e6);
    }
  }
  EXPECT_LT(s.linearity_plus.maxCoeff(), 1e-9);
  EXPECT_EQ(increment_problems(s, IncrementTolerances{}), "");
}

TEST(Stiffness, MeasuresLinearityFromTheTwoHalves) {
  // Halves scaled by 0.9 and 1.1 of the secant: they differ by 0.2 of it.
  const Stiffness s = assemble_stiffness(synthetic_forks(5e-5, 0.1));
  EXPECT_NEAR(s.linearity_plus.maxCoeff(), 0.2, 1e-9);
  EXPECT_NEAR(s.linearity_minus.minCoeff(), 0.2, 1e-9);
  IncrementTolerances tolerances;
  tolerances.linearity = 0.1;
  const std::string problems = increment_problems(s, tolerances);
  EXPECT_NE(problems.find("increment too large"), std::string::npos) << problems;
  EXPECT_EQ(problems.find("too small"), std::string::npos) << problems;
  tolerances.linearity = 0.25;
  EXPECT_EQ(increment_problems(s, tolerances), "");
}

TEST(Stiffness, FlagsAnIncrementThatMakesContactsSlide) {
  auto forks = synthetic_forks(5e-5);
  for (auto& fork : forks)
    fork.contacts_final = 1000;
  forks[0].sliding_final = 150;
  for (int k = 1; k <= n_forks; ++k)
    forks[static_cast<std::size_t>(k)].sliding_final = 160;
  forks[4].sliding_final = 350; // the compression fork on x2 made 20% of the contacts slide
  const Stiffness s = assemble_stiffness(forks);
  EXPECT_NEAR(s.sliding_minus[1], 0.2, 1e-12);
  EXPECT_NEAR(s.sliding_plus[0], 0.01, 1e-12);
  const std::string problems = increment_problems(s, IncrementTolerances{});
  EXPECT_NE(problems.find("increment too large"), std::string::npos) << problems;
  EXPECT_NE(problems.find("0.2 of the contacts slide"), std::string::npos) << problems;
}

TEST(Stiffness, FlagsAnIncrementLostInRoundOff) {
  // delta = 1e-13 moves sigma_22 by about 1e-5 Pa, 1e-10 of the 1e5 Pa stress.
  const Stiffness s = assemble_stiffness(synthetic_forks(1e-13));
  EXPECT_LT(s.resolution_plus.minCoeff(), 1e-9);
  const std::string problems = increment_problems(s, IncrementTolerances{});
  EXPECT_NE(problems.find("increment too small"), std::string::npos) << problems;
  EXPECT_EQ(increment_problems(assemble_stiffness(synthetic_forks(1e-9)), IncrementTolerances{}), "");
}

TEST(Stiffness, FlagsAnUnsettledReading) {
  // A 5e-7 increment in compression moves sigma_33 by -(200e6 - (-30e6)) 5e-7 = -115 Pa; a wobble of
  // +-34.5 Pa about it is a relative rms of 0.3.
  const Stiffness s = assemble_stiffness(synthetic_forks(5e-7, 0.0, 34.5));
  EXPECT_NEAR(s.noise_minus[2], 0.3, 1e-9);
  const std::string problems = increment_problems(s, IncrementTolerances{});
  EXPECT_NE(problems.find("reading unsettled"), std::string::npos) << problems;
}

TEST(Stiffness, RefusesForksOutOfOrderOrStrainedTheWrongWay) {
  auto forks = synthetic_forks(5e-5);
  std::swap(forks[1], forks[2]);
  EXPECT_THROW(static_cast<void>(assemble_stiffness(forks)), InputError);
  forks = synthetic_forks(5e-5);
  forks[3].strain_final[1] = -forks[3].strain_final[1];
  EXPECT_THROW(static_cast<void>(assemble_stiffness(forks)), InputError);
  forks = synthetic_forks(5e-5);
  forks[4].samples_final.pop_back(); // readings that do not line up with the reference's
  EXPECT_THROW(static_cast<void>(assemble_stiffness(forks)), InputError);
}

} // namespace
} // namespace aniso::probe
