#pragma once
// `aniso-fabric series`: the measures of a loading run's checkpoints as time series, and the
// paper's Pearson correlations c1, c2 (eq. (c2), Table 2; sections 4 and 5).

#include "fabric/linked_results.hpp"
#include "fabric/measures.hpp"

#include <span>
#include <string>
#include <vector>

namespace aniso::fabric {

struct Correlation {
  std::string measure;    ///< e.g. "H_strong" or "C"
  std::string against;    ///< e.g. "stress" or "H"
  std::string definition; ///< what c1 correlates (c2: the same with 22 for 11)
  double c1 = 0;          ///< over the 11 - 33 differences
  double c2 = 0;          ///< over the 22 - 33 differences
  std::int64_t n_points = 0;
};

/// Every fabric tensor against the deviatoric contact stress, compression positive:
/// c1 = corr(A11 - A33, s11 - s33), c2 = corr(A22 - A33, s22 - s33) with s = -stress (eq. (c2)).
std::vector<Correlation> stress_correlations(std::span<const FabricMeasures> series);

struct LinkedResults {
  std::vector<ProbeStiffness> probes;
  std::vector<Permeability> permeabilities;
  std::vector<VoidMedians> voids;
};

/// With probes: corr(C11 - C33, A11 - A33) and the 22 one for the six contact tensors A (section 4).
/// With permeabilities and voids at the same checkpoints: corr of the normalized anisotropies
/// (X11 - X33)/(tr X / 3) of K with those of L^v and of R^v (section 5). Every linked file must
/// belong to one of the series' checkpoints (FileError naming it otherwise).
std::vector<Correlation> linked_correlations(std::span<const FabricMeasures> series,
                                             const LinkedResults& linked);

/// Writes <h5_path> with /checkpoints (as fabric.h5), /series (one dataset per column, in the
/// given order) and /correlations/<measure>_vs_<against> (attributes c1, c2, n_points), plus the
/// CSV files <stem>.csv (time series) and <stem>_correlations.csv, atomically from rank 0.
void write_series_results(const std::string& h5_path, std::span<const FabricMeasures> series,
                          std::span<const Correlation> correlations, const h5::Provenance& provenance,
                          const mpi::Comm& comm);

} // namespace aniso::fabric
