#include "common/h5/particle_separation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace aniso::h5 {
namespace {

struct DeepestOverlap {
  double fraction = 0; // overlap / smaller inscribed radius
  std::size_t i = 0, j = 0;
  double distance = 0;
};

// Bins of at least the largest inscribed diameter, so that every overlapping pair lies in
// neighbouring bins; fewer than three bins on an axis would visit a pair twice, and there the
// assembly is small enough to test every pair.
class SeparationBins {
public:
  SeparationBins(std::span<const Vec3> positions, const Vec3& lengths, double size) {
    // Larger bins than the range only cost pairs; about one particle per bin bounds the memory
    // when the particles are tiny beside the cell.
    const double most = std::max(3.0, std::ceil(std::cbrt(static_cast<double>(positions.size()))));
    for (int a = 0; a < 3; ++a)
      count_[a] = static_cast<std::int64_t>(std::clamp(std::floor(lengths[a] / size), 1.0, most));
    usable_ = count_[0] >= 3 && count_[1] >= 3 && count_[2] >= 3;
    if (!usable_) return;
    members_.resize(static_cast<std::size_t>(count_[0] * count_[1] * count_[2]));
    for (std::size_t k = 0; k < positions.size(); ++k) {
      std::array<std::int64_t, 3> bin{};
      for (int a = 0; a < 3; ++a)
        bin[a] = std::clamp(static_cast<std::int64_t>(
                                std::floor(positions[k][a] / lengths[a] * static_cast<double>(count_[a]))),
                            std::int64_t{0}, count_[a] - 1);
      members_[index(bin)].push_back(k);
    }
  }
  [[nodiscard]] bool usable() const { return usable_; }

  /// Calls visit(i, j) once for every pair i < j in neighbouring bins.
  template <class Visit> void for_each_near_pair(Visit&& visit) const {
    std::array<std::int64_t, 3> bin{};
    for (bin[0] = 0; bin[0] < count_[0]; ++bin[0])
      for (bin[1] = 0; bin[1] < count_[1]; ++bin[1])
        for (bin[2] = 0; bin[2] < count_[2]; ++bin[2])
          for (const std::size_t i : members_[index(bin)])
            for (int d0 = -1; d0 <= 1; ++d0)
              for (int d1 = -1; d1 <= 1; ++d1)
                for (int d2 = -1; d2 <= 1; ++d2) {
                  const std::array<std::int64_t, 3> other{wrap(bin[0] + d0, 0), wrap(bin[1] + d1, 1),
                                                          wrap(bin[2] + d2, 2)};
                  for (const std::size_t j : members_[index(other)])
                    if (j > i) visit(i, j);
                }
  }

private:
  [[nodiscard]] std::int64_t wrap(std::int64_t b, int axis) const {
    return (b + count_[axis]) % count_[axis];
  }
  [[nodiscard]] std::size_t index(const std::array<std::int64_t, 3>& bin) const {
    return static_cast<std::size_t>((bin[0] * count_[1] + bin[1]) * count_[2] + bin[2]);
  }

  std::array<std::int64_t, 3> count_{};
  bool usable_ = false;
  std::vector<std::vector<std::size_t>> members_;
};

} // namespace

std::optional<std::string> deepest_impossible_overlap(std::span<const Vec3> positions,
                                                      std::span<const double> diameters,
                                                      std::span<const double> aspect_ratios,
                                                      const Vec3& lengths, double limit) {
  const std::size_t n = positions.size();
  std::vector<double> inscribed(n);
  double largest = 0;
  for (std::size_t k = 0; k < n; ++k) {
    inscribed[k] = 0.5 * diameters[k] * std::min(1.0, aspect_ratios[k]);
    largest = std::max(largest, inscribed[k]);
  }
  DeepestOverlap deepest;
  const auto test = [&](std::size_t i, std::size_t j) {
    Vec3 branch = positions[j] - positions[i];
    for (int a = 0; a < 3; ++a)
      branch[a] -= lengths[a] * std::round(branch[a] / lengths[a]); // the nearest image
    const double distance = branch.norm();
    const double fraction = (inscribed[i] + inscribed[j] - distance) / std::min(inscribed[i], inscribed[j]);
    if (fraction > deepest.fraction) deepest = {fraction, i, j, distance};
  };
  const SeparationBins bins(positions, lengths, 2.0 * largest);
  if (bins.usable())
    bins.for_each_near_pair(test);
  else
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        test(i, j);
  // A relative slack of 1e-9 keeps a DEM state right at the limit (same overlap, other rounding).
  if (!(deepest.fraction > limit * (1 + 1e-9))) return std::nullopt;
  if (deepest.distance == 0)
    return fmt::format("particles {} and {} share the position ({:.9g}, {:.9g}, {:.9g}) m", deepest.i,
                       deepest.j, positions[deepest.i].x(), positions[deepest.i].y(),
                       positions[deepest.i].z());
  return fmt::format(
      "particles {} and {} overlap by {:.3g} of the smaller one's radius (centres {:.4g} m apart), "
      "beyond the run's explosion limit {:g} (/parameters/explosion_overlap)",
      deepest.i, deepest.j, deepest.fraction, deepest.distance, limit);
}

} // namespace aniso::h5
