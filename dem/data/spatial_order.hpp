#pragma once
// Particle ids in spatial order. The force loop visits pairs in id order, so ids
// that follow the random order of the sparse start put a pair's two particles far
// apart in memory; ids in Morton (Z-curve) order of bins about two diameters wide
// keep neighbours close, which made the force pass 1.15x (spheres) and 1.24x
// (alpha = 0.5 ovoids) faster (docs/performance.md).

#include "common/tensor.hpp"

#include <cstddef>
#include <vector>

namespace aniso::dem::data {

/// The order in which to number `positions` (inside the cell [0, lengths)): by the Morton
/// code of their bin of width at least `bin_width`, ties in the given order.
std::vector<std::size_t> spatial_order(const std::vector<Vec3>& positions, const Vec3& lengths,
                                       double bin_width);

} // namespace aniso::dem::data
