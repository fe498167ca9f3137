#include "dem/model/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace aniso::dem::model {

double volume_fraction_finer(const Grading& g, double diameter) {
  if (diameter <= g.diameter_min) return 0.0;
  if (diameter >= g.diameter_max) return 1.0;
  if (diameter <= g.d50) return 0.5 * std::log(diameter / g.diameter_min) / std::log(g.d50 / g.diameter_min);
  return 0.5 + 0.5 * std::log(diameter / g.d50) / std::log(g.diameter_max / g.d50);
}

std::vector<double> sample_diameters(const Grading& g, std::size_t count, RandomStream& stream) {
  // Draw by volume (inverse of the piecewise log-linear cumulative), then keep a draw
  // with probability (D_min / D)^3, which turns volume frequencies into number frequencies.
  const auto by_volume = [&](double fraction) {
    if (fraction < 0.5) return g.diameter_min * std::pow(g.d50 / g.diameter_min, 2 * fraction);
    return g.d50 * std::pow(g.diameter_max / g.d50, 2 * fraction - 1);
  };
  std::vector<double> diameters;
  diameters.reserve(count);
  while (diameters.size() < count) {
    const double diameter = by_volume(stream.uniform01());
    const double keep = std::pow(g.diameter_min / diameter, 3);
    if (stream.uniform01() < keep) diameters.push_back(diameter);
  }
  std::sort(diameters.begin(), diameters.end(), std::greater<>());
  return diameters;
}

double volume_median(std::vector<double> diameters) {
  std::sort(diameters.begin(), diameters.end());
  double total = 0;
  for (double d : diameters)
    total += d * d * d;
  double finer = 0;
  for (double d : diameters) {
    finer += d * d * d;
    if (finer >= 0.5 * total) return d;
  }
  return diameters.empty() ? 0.0 : diameters.back();
}

} // namespace aniso::dem::model
