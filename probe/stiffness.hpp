#pragma once
// The eighteen moduli of the six oedometric forks and the matrices built from
// them (paper section 5): O_i and K_i^j of eqs. (Oplus) and (Ominus), Q+ and Q-,
// C = (Q+ + Q-)/2 and D = (Q+ - Q-)/2 of eq. (decomp), and K_C, the mean of the
// nine entries of C. Row i = stress component sigma_ii, column j = strain
// component eps_jj, tension and extension positive: column j of Q+ is
// d sigma / d eps_jj of the extension fork on x_j, of Q- that of the compression fork.
// d sigma is the fork's stress minus the reference fork's at the same steps,
// averaged over the reading window. Pure arithmetic on fork results; no MPI, no files.

#include "common/tensor.hpp"
#include "probe/fork.hpp"

#include <array>

namespace aniso::probe {

struct Stiffness {
  Vec3 O_plus = Vec3::Zero();          ///< O_i^+ = d sigma_ii / d eps_ii, extension forks [Pa]
  Vec3 O_minus = Vec3::Zero();         ///< O_i^-, compression forks [Pa]
  Mat3 K_plus = Mat3::Zero();          ///< (j, i) = K_i^{j+} = d sigma_jj / d sigma_ii; diagonal 1
  Mat3 K_minus = Mat3::Zero();         ///< (j, i) = K_i^{j-}
  Mat3 Q_plus = Mat3::Zero();          ///< (j, i) = K_i^{j+} O_i^+ [Pa]
  Mat3 Q_minus = Mat3::Zero();         ///< (j, i) = K_i^{j-} O_i^- [Pa]
  Mat3 C = Mat3::Zero();               ///< incrementally linear stiffness [Pa]
  Mat3 D = Mat3::Zero();               ///< incrementally non-linear stiffness [Pa]
  double K_C = 0;                      ///< mean of the nine entries of C [Pa]
  Vec3 linearity_plus = Vec3::Zero();  ///< |M_second - M_first| / |O_i^+| of the two half increments
  Vec3 linearity_minus = Vec3::Zero(); ///< the same for the compression forks
  Vec3 noise_plus = Vec3::Zero();      ///< rms of d sigma_ii(t) about its mean in the window / |d sigma_ii|
  Vec3 noise_minus = Vec3::Zero();     ///< the same for the compression forks
  /// (contacts sliding at the end of the fork - those of the reference) / contacts of the reference
  Vec3 sliding_plus = Vec3::Zero();
  Vec3 sliding_minus = Vec3::Zero();
  /// |d sigma_ii| / largest |sigma_kl| of the reference: the digits of the response left after subtraction
  Vec3 resolution_plus = Vec3::Zero();
  Vec3 resolution_minus = Vec3::Zero();
};

/// Assembles the matrices from the seven forks, forks[k] being fork k (0 = reference). InputError if
/// a fork has the wrong number, a loaded axis that did not strain, or samples that do not line up.
Stiffness assemble_stiffness(const std::array<ForkResult, n_fork_files>& forks);

/// What the increment checks found: empty if the increment sits where the moduli do not depend
/// on it, else a message saying which check failed, by how much, and what to change.
std::string increment_problems(const Stiffness& stiffness, const IncrementTolerances& tolerances);

} // namespace aniso::probe
