#pragma once
// Pearson correlation coefficient (paper eq. (c2)).

#include <span>

namespace aniso::fabric {

/// cov(x, y) / (std(x) std(y)) over equally long series (two-pass, as numpy.corrcoef);
/// NaN when fewer than two points or either series is constant.
double pearson(std::span<const double> x, std::span<const double> y);

} // namespace aniso::fabric
