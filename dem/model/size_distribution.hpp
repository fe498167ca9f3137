#pragma once
// Particle sizes: a grading given by its smallest, median-by-volume and largest
// diameter (paper: 0.075, 0.17 and 0.28 mm). The cumulative volume fraction is
// taken linear in log D between (D_min, 0), (D50, 1/2) and (D_max, 1): the
// simplest grading that honours all three numbers. Number frequencies follow
// from volume frequencies divided by D^3. See docs/methods/dem.md.

#include "common/rng.hpp"

#include <vector>

namespace aniso::dem::model {

struct Grading {
  double diameter_min;
  double d50;
  double diameter_max;
};

/// Cumulative volume fraction finer than `diameter`.
double volume_fraction_finer(const Grading& grading, double diameter);

/// `count` diameters drawn independently by number from the grading, sorted descending.
std::vector<double> sample_diameters(const Grading& grading, std::size_t count, RandomStream& stream);

/// Median diameter by volume of a sample (the D for which half the solid volume is finer).
double volume_median(std::vector<double> diameters);

} // namespace aniso::dem::model
