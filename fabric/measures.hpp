#pragma once
// All fabric measures of one checkpoint (paper section 3, Table 1): stress from contacts,
// p, q, e, coordination, J^p, I^s, S^s, F^c, G^c, H^c and their strong variants, chi^v
// (paper and 3-torus forms) and W_3^{2,0}.

#include "common/h5/checkpoint.hpp"
#include "common/mpi.hpp"
#include "common/tensor.hpp"
#include "fabric/config.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aniso::fabric {

/// Stored (attribute "warning") and logged with the results of a checkpoint without contacts, a
/// valid state (a loose gas) on which every contact measure is 0/0.
inline constexpr std::string_view no_contacts_warning =
    "no contacts: the stress ratios, the contact tensors' anisotropies and the correlations that use "
    "them are undefined (NaN)";

/// One tensor result with what a reader needs to know about it.
struct NamedTensor {
  std::string name;        ///< dataset / column stem, e.g. "H_strong"
  std::string unit;        ///< "1" or "Pa" or "m"
  std::string description; ///< with the paper's equation label
  Mat3 value;
};

/// One scalar result (integers are flagged so that files store them as integers).
struct NamedScalar {
  std::string name;
  std::string unit;
  std::string description;
  double value;
  bool integer = false;
};

struct FabricMeasures {
  std::string source;      ///< checkpoint path
  std::string source_hash; ///< content hash of the checkpoint (set by the caller: common/h5/content_hash.hpp)
  double time = 0;         ///< simulated time [s]
  std::int64_t step = 0;
  Vec3 strain = Vec3::Zero(); ///< engineering strain L / L0 - 1 per axis
  std::int64_t n_particles = 0;
  std::int64_t n_contacts = 0;
  std::int64_t n_strong = 0;
  std::int64_t n_rattlers = 0;
  std::int64_t n_triples = 0;    ///< N_3
  std::int64_t n_quadruples = 0; ///< N_4
  double mean_normal_force = 0;  ///< [N]
  double mean_stress = 0;        ///< p from the contact stress, compression positive [Pa]
  double deviatoric_stress = 0;  ///< q = sqrt(3 J2) [Pa]
  double void_ratio = 0;
  double coordination = 0;
  double coordination_no_rattlers = 0;
  double chi_paper = 0;               ///< 1 + N_p - N_c, eq. (Chis1)
  double chi_torus = 0;               ///< N_p - N_c + N_3 - N_4, the void on the periodic cell
  Mat3 stress_contact = Mat3::Zero(); ///< (1/V) sum l (x) f, tension positive [Pa]
  Mat3 stress_kinetic = Mat3::Zero(); ///< -(1/V) sum m v (x) v [Pa]; contact + kinetic = the DEM's stress
  Mat3 J = Mat3::Zero();              ///< eq. (Jbar)
  Mat3 I = Mat3::Zero();              ///< eq. (Ipar)
  Mat3 S = Mat3::Zero();              ///< eq. (Sbar)
  Mat3 F = Mat3::Zero(), F_strong = Mat3::Zero(); ///< eqs. (Fc), (Fcstrong)
  Mat3 G = Mat3::Zero(), G_strong = Mat3::Zero(); ///< eq. (Lc)
  Mat3 H = Mat3::Zero(), H_strong = Mat3::Zero(); ///< eq. (Hbarc)
  Mat3 W320 = Mat3::Zero();                       ///< eq. (W320), about the cell centre [m^2]
  Mat3 W320_boundary = Mat3::Zero();              ///< eq. (W202) on the cell's boundary box [m^2]
  Mat3 W320_normalized = Mat3::Zero();            ///< eq. (MinkNormal)

  /// Every scalar in output order (time, strain, counts, p, q, e, Z, chi).
  [[nodiscard]] std::vector<NamedScalar> scalars() const;
  /// Every tensor in output order (stress first, then Table 1's order).
  [[nodiscard]] std::vector<NamedTensor> tensors() const;
};

/// Computes every measure of a checkpoint that every rank holds in full (as read_checkpoint gives
/// it). Collective: particles and contacts are dealt to ranks in blocks and summed exactly, so the
/// result is bit-identical for any rank count. FileError naming `path` on inconsistent contents.
FabricMeasures measure_fabric(const h5::Checkpoint& checkpoint, const std::string& path,
                              const FabricConfig& config, const mpi::Comm& comm);

} // namespace aniso::fabric
