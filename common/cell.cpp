#include "common/cell.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace aniso {
namespace {

void require_positive_lengths(const Vec3& lengths, const char* what) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!(lengths[axis] > 0.0) || !std::isfinite(lengths[axis])) {
      throw InputError(fmt::format("periodic cell: {} length on axis {} is {}, expected a finite value > 0",
                                   what, axis + 1, lengths[axis]));
    }
  }
}

} // namespace

PeriodicCell::PeriodicCell(const Vec3& lengths) : PeriodicCell(lengths, lengths) {}

PeriodicCell::PeriodicCell(const Vec3& lengths, const Vec3& reference_lengths)
    : lengths_(lengths), reference_lengths_(reference_lengths) {
  require_positive_lengths(lengths_, "current");
  require_positive_lengths(reference_lengths_, "reference");
}

Vec3 PeriodicCell::engineering_strain() const {
  return (lengths_ - reference_lengths_).cwiseQuotient(reference_lengths_);
}

Vec3 PeriodicCell::logarithmic_strain() const {
  Vec3 strain;
  for (int axis = 0; axis < 3; ++axis)
    strain[axis] = std::log(lengths_[axis] / reference_lengths_[axis]);
  return strain;
}

Vec3i PeriodicCell::image_shift(const Vec3& separation) const {
  Vec3i shift;
  for (int axis = 0; axis < 3; ++axis) {
    shift[axis] = -static_cast<int>(std::nearbyint(separation[axis] / lengths_[axis]));
  }
  return shift;
}

Vec3 PeriodicCell::minimum_image(const Vec3& separation) const {
  Vec3 result;
  for (int axis = 0; axis < 3; ++axis) {
    result[axis] = separation[axis] - lengths_[axis] * std::nearbyint(separation[axis] / lengths_[axis]);
  }
  return result;
}

Vec3 PeriodicCell::wrap(const Vec3& position) const {
  Vec3 result;
  for (int axis = 0; axis < 3; ++axis) {
    double x = position[axis] - lengths_[axis] * std::floor(position[axis] / lengths_[axis]);
    if (x >= lengths_[axis]) x = 0.0; // floor rounding can land exactly on L
    result[axis] = x;
  }
  return result;
}

void PeriodicCell::set_lengths(const Vec3& lengths) {
  require_positive_lengths(lengths, "current");
  lengths_ = lengths;
}

} // namespace aniso
