#include "dem/data/neighbors.hpp"

#include "common/error.hpp"
#include "dem/model/rotation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace aniso::dem::data {
namespace {

// Both positions are inside the cell, so one comparison per axis gives the minimum image.
Vec3 separation(const Vec3& from, const Vec3& to, const Vec3& lengths) {
  return PeriodicCell::minimum_image_of_wrapped(to - from, lengths);
}

bool pair_less(const Particles& particles, const Pair& a, const Pair& b) {
  const auto ai = particles.id[a.i], bi = particles.id[b.i];
  return ai != bi ? ai < bi : particles.id[a.j] < particles.id[b.j];
}

} // namespace

void NeighborList::build(const Particles& particles, const PeriodicCell& cell,
                         const std::vector<HistoryRecord>& carried) {
  const std::size_t n = particles.size();
  const std::size_t n_owned = particles.n_owned;
  const Vec3& lengths = cell.lengths();
  max_radius_ = global_max_radius_ > 0 ? global_max_radius_
                : n                    ? *std::max_element(particles.radius.begin(), particles.radius.end())
                                       : 0.0;
  const double bin_reach = 2 * max_radius_ + skin_;
  for (int a = 0; a < 3; ++a) {
    // The minimum image is unique only if no pair can interact through two images.
    if (lengths[a] < 2 * bin_reach) {
      throw NumericalError(
          fmt::format("periodic cell length {:.4g} m on axis {} is below twice the interaction "
                      "range {:.4g} m: use more particles or a less elongated cell",
                      lengths[a], a + 1, bin_reach));
    }
  }
  int n_bins[3];
  for (int a = 0; a < 3; ++a)
    n_bins[a] = std::max(1, static_cast<int>(lengths[a] / bin_reach));
  const auto bin_of = [&](const Vec3& x) {
    int b[3];
    for (int a = 0; a < 3; ++a) {
      b[a] = static_cast<int>(x[a] / lengths[a] * n_bins[a]);
      b[a] = std::clamp(b[a], 0, n_bins[a] - 1);
    }
    return (b[0] * n_bins[1] + b[1]) * n_bins[2] + b[2];
  };
  // Counting sort of particles into bins.
  const int total_bins = n_bins[0] * n_bins[1] * n_bins[2];
  std::vector<int> bin_start(static_cast<std::size_t>(total_bins) + 1, 0);
  std::vector<int> particle_bin(n);
  for (std::size_t i = 0; i < n; ++i) {
    particle_bin[i] = bin_of(particles.position[i]);
    ++bin_start[static_cast<std::size_t>(particle_bin[i]) + 1];
  }
  for (int b = 0; b < total_bins; ++b)
    bin_start[b + 1] += bin_start[b];
  std::vector<std::uint32_t> binned(n);
  {
    std::vector<int> fill(bin_start.begin(), bin_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      binned[static_cast<std::size_t>(fill[particle_bin[i]]++)] = static_cast<std::uint32_t>(i);
  }
  // Neighbour bin offsets, de-duplicated for axes with fewer than three bins.
  std::vector<Pair> fresh;
  fresh.reserve(pairs_.size() + n);
  std::vector<int> neighbour_bins;
  for (int b0 = 0; b0 < n_bins[0]; ++b0) {
    for (int b1 = 0; b1 < n_bins[1]; ++b1) {
      for (int b2 = 0; b2 < n_bins[2]; ++b2) {
        const int home = (b0 * n_bins[1] + b1) * n_bins[2] + b2;
        neighbour_bins.clear();
        for (int o0 = -1; o0 <= 1; ++o0)
          for (int o1 = -1; o1 <= 1; ++o1)
            for (int o2 = -1; o2 <= 1; ++o2) {
              const int c0 = (b0 + o0 + n_bins[0]) % n_bins[0];
              const int c1 = (b1 + o1 + n_bins[1]) % n_bins[1];
              const int c2 = (b2 + o2 + n_bins[2]) % n_bins[2];
              neighbour_bins.push_back((c0 * n_bins[1] + c1) * n_bins[2] + c2);
            }
        std::sort(neighbour_bins.begin(), neighbour_bins.end());
        neighbour_bins.erase(std::unique(neighbour_bins.begin(), neighbour_bins.end()), neighbour_bins.end());
        for (int p = bin_start[home]; p < bin_start[home + 1]; ++p) {
          const std::uint32_t i = binned[static_cast<std::size_t>(p)];
          for (int other : neighbour_bins) {
            for (int q = bin_start[other]; q < bin_start[other + 1]; ++q) {
              const std::uint32_t j = binned[static_cast<std::size_t>(q)];
              if (particles.id[j] <= particles.id[i]) continue;
              if (i >= n_owned && j >= n_owned) continue; // two ghosts: their owners compute it
              const double reach = particles.radius[i] + particles.radius[j] + skin_;
              if (separation(particles.position[i], particles.position[j], lengths).squaredNorm() <
                  reach * reach) {
                fresh.push_back({i, j});
              }
            }
          }
        }
      }
    }
  }
  std::sort(fresh.begin(), fresh.end(),
            [&](const Pair& a, const Pair& b) { return pair_less(particles, a, b); });
  // Carry history over by ids: from the previous list (both are sorted by ids),
  // then from histories that arrived with migrating particles.
  std::vector<std::array<std::uint64_t, 2>> fresh_ids(fresh.size());
  for (std::size_t k = 0; k < fresh.size(); ++k)
    fresh_ids[k] = {particles.id[fresh[k].i], particles.id[fresh[k].j]};
  std::vector<model::ContactHistory> fresh_history(fresh.size());
  std::vector<Vec3> fresh_separating(fresh.size(), Vec3::Zero());
  std::size_t old_k = 0;
  for (std::size_t k = 0; k < fresh.size() && old_k < pair_ids_.size(); ++k) {
    while (old_k < pair_ids_.size() && pair_ids_[old_k] < fresh_ids[k])
      ++old_k;
    if (old_k < pair_ids_.size() && pair_ids_[old_k] == fresh_ids[k]) {
      fresh_history[k] = history_[old_k];
      fresh_separating[k] = separating_normals_[old_k];
    }
  }
  for (const HistoryRecord& record : carried) {
    const std::array<std::uint64_t, 2> key{record.id_i, record.id_j};
    const auto it = std::lower_bound(fresh_ids.begin(), fresh_ids.end(), key);
    if (it != fresh_ids.end() && *it == key)
      fresh_history[static_cast<std::size_t>(it - fresh_ids.begin())] = record.history;
  }
  pair_ids_ = std::move(fresh_ids);
  pairs_ = std::move(fresh);
  history_ = std::move(fresh_history);
  separating_normals_ = std::move(fresh_separating);
  records_.assign(pairs_.size(), ContactRecord{});
  properties_.resize(pairs_.size());
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::uint32_t i = pairs_[k].i, j = pairs_[k].j;
    properties_[k].effective_radius =
        particles.radius[i] * particles.radius[j] / (particles.radius[i] + particles.radius[j]);
    properties_[k].effective_mass =
        particles.mass[i] * particles.mass[j] / (particles.mass[i] + particles.mass[j]);
  }
  proofs_.assign(pairs_.size(), ApartProof{});
  position_at_build_.assign(particles.position.begin(),
                            particles.position.begin() + static_cast<std::ptrdiff_t>(n_owned));
  axis_at_build_.assign(n_owned, Vec3::Zero());
  for (std::size_t i = 0; i < n_owned; ++i)
    if (particles.aspect_ratio[i] != 1.0) axis_at_build_[i] = model::particle_axis(particles.orientation[i]);
  position_before_ = position_at_build_;
  axis_before_ = axis_at_build_;
  lengths_before_ = lengths;
  travelled_ = 0;
  bounds_ = {0, 0}; // the particles stand where the build saw them
  lengths_at_build_ = lengths;
  ++n_builds_;
}

ListMotion NeighborList::motion(const Particles& particles, const PeriodicCell& cell) const {
  if (position_at_build_.size() != particles.n_owned) {
    const double infinite = std::numeric_limits<double>::infinity();
    return {infinite, infinite, infinite};
  }
  const Vec3& lengths = cell.lengths();
  const Vec3 scale = lengths.cwiseQuotient(lengths_at_build_);
  const Vec3 step_scale = lengths.cwiseQuotient(lengths_before_);
  double shift_squared = 0, turn_squared = 0, step_shift_squared = 0, step_turn_squared = 0;
  for (std::size_t i = 0; i < particles.n_owned; ++i) {
    const Vec3& x = particles.position[i];
    shift_squared = std::max(shift_squared,
                             separation(position_at_build_[i].cwiseProduct(scale), x, lengths).squaredNorm());
    step_shift_squared =
        std::max(step_shift_squared,
                 separation(position_before_[i].cwiseProduct(step_scale), x, lengths).squaredNorm());
    if (particles.aspect_ratio[i] != 1.0) {
      // A body of revolution turned from axis u0 to u is the old body turned by the smallest
      // rotation between them: no point within radius a of the centre moves more than a |u - u0|.
      const Vec3 axis = model::particle_axis(particles.orientation[i]);
      const double radius_squared = particles.radius[i] * particles.radius[i];
      turn_squared = std::max(turn_squared, radius_squared * (axis - axis_at_build_[i]).squaredNorm());
      step_turn_squared =
          std::max(step_turn_squared, radius_squared * (axis - axis_before_[i]).squaredNorm());
    }
  }
  // A pair's separation changes by at most twice the largest non-affine shift plus the cell
  // strain times its length (at most the interaction range); its gap along a fixed direction
  // by that plus the surface motion of both bodies' turns.
  const double range = 4 * max_radius_ + skin_;
  const double strain = (scale - Vec3::Ones()).cwiseAbs().maxCoeff();
  const double step_strain = (step_scale - Vec3::Ones()).cwiseAbs().maxCoeff();
  ListMotion result;
  result.separation = 2 * std::sqrt(shift_squared) + strain * range;
  result.gap = result.separation + 2 * std::sqrt(turn_squared);
  result.step_gap =
      2 * std::sqrt(step_shift_squared) + step_strain * range + 2 * std::sqrt(step_turn_squared);
  return result;
}

ListMotion NeighborList::measure_motion(const Particles& particles, const PeriodicCell& cell) {
  const ListMotion result = motion(particles, cell);
  if (position_before_.size() == particles.n_owned) {
    std::copy(particles.position.begin(),
              particles.position.begin() + static_cast<std::ptrdiff_t>(particles.n_owned),
              position_before_.begin());
    for (std::size_t i = 0; i < particles.n_owned; ++i)
      if (particles.aspect_ratio[i] != 1.0) axis_before_[i] = model::particle_axis(particles.orientation[i]);
    lengths_before_ = cell.lengths();
  }
  return result;
}

std::int64_t NeighborList::find(const Particles& particles, std::uint32_t i, std::uint32_t j) const {
  const Pair key{i, j};
  const auto it = std::lower_bound(pairs_.begin(), pairs_.end(), key,
                                   [&](const Pair& a, const Pair& b) { return pair_less(particles, a, b); });
  if (it == pairs_.end() || it->i != i || it->j != j) return -1;
  return it - pairs_.begin();
}

std::vector<Pair> brute_force_pairs(const Particles& particles, const PeriodicCell& cell, double range) {
  std::vector<Pair> result;
  for (std::uint32_t i = 0; i < particles.size(); ++i) {
    for (std::uint32_t j = 0; j < particles.size(); ++j) {
      if (particles.id[j] <= particles.id[i]) continue;
      const double reach = particles.radius[i] + particles.radius[j] + range;
      if (separation(particles.position[i], particles.position[j], cell.lengths()).squaredNorm() <
          reach * reach) {
        result.push_back({i, j});
      }
    }
  }
  std::sort(result.begin(), result.end(),
            [&](const Pair& a, const Pair& b) { return pair_less(particles, a, b); });
  return result;
}

} // namespace aniso::dem::data
