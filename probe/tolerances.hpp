#pragma once
// Limits of the probe's increment checks (docs/methods/probe.md, "Stability and the choice
// of defaults"); the defaults come from the stability sweep.

namespace aniso::probe {

/// Limits of the increment checks (docs/methods/probe.md, "Stability").
struct IncrementTolerances {
  double linearity = 1.0;   ///< too large: the two half moduli differ by more (fraction of O_i)
  double sliding = 0.15;    ///< too large: the increment made more than this fraction of contacts slide
  double resolution = 1e-9; ///< too small: the response is a smaller fraction of the stress (round-off)
  double noise = 0.25;      ///< reading unsettled: rms of d sigma_ii(t) in the window / |d sigma_ii|
};

} // namespace aniso::probe
