#pragma once
// States no DEM run can reach: two particles at one position, or a pair overlapping deeper than
// the run's explosion limit (dem.integration.explosion_overlap, a fraction of the smaller
// half-height, where the DEM stops with exit 4). Every stage refuses such a checkpoint when it
// reads it (h5::read_checkpoint), so that fabric and voids are never measured on one.
//
// The test is on inscribed spheres (radius: the half-height alpha D / 2, the whole radius for a
// sphere): their overlap is a lower bound of the bodies' own, so a state the DEM wrote always
// passes, and for spheres the bound is the DEM's overlap itself.

#include "common/tensor.hpp"

#include <optional>
#include <span>
#include <string>

namespace aniso::h5 {

/// The pair whose inscribed spheres overlap deepest, as a fraction of the smaller one's radius,
/// across the periodic cell of `lengths`, described as "particles i and j ...", if that fraction
/// exceeds `limit`; else nothing. `positions`, `diameters` and `aspect_ratios` are the whole assembly's rows.
[[nodiscard]] std::optional<std::string> deepest_impossible_overlap(std::span<const Vec3> positions,
                                                                    std::span<const double> diameters,
                                                                    std::span<const double> aspect_ratios,
                                                                    const Vec3& lengths, double limit);

} // namespace aniso::h5
