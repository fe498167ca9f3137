#pragma once
// The periodic orthorhombic cell: lengths that change under homogeneous
// deformation, the strain they imply, minimum-image vectors and wrapping.
// Positions are stored in Cartesian coordinates inside [0, L_i) per axis.

#include "common/tensor.hpp"

namespace aniso {

class PeriodicCell {
public:
  /// A cell with the given current lengths; the reference (zero-strain) lengths default to them.
  explicit PeriodicCell(const Vec3& lengths);
  PeriodicCell(const Vec3& lengths, const Vec3& reference_lengths);

  [[nodiscard]] const Vec3& lengths() const { return lengths_; }
  [[nodiscard]] const Vec3& reference_lengths() const { return reference_lengths_; }
  [[nodiscard]] double volume() const { return lengths_.prod(); }

  /// Engineering strain per axis, (L - L0)/L0, extension positive.
  [[nodiscard]] Vec3 engineering_strain() const;
  /// Logarithmic (true) strain per axis, ln(L/L0), extension positive.
  [[nodiscard]] Vec3 logarithmic_strain() const;

  /// Shortest periodic image of a separation vector (exact for orthorhombic cells).
  [[nodiscard]] Vec3 minimum_image(const Vec3& separation) const;
  /// Integer image shift n such that separation + n .* L is the minimum image.
  [[nodiscard]] Vec3i image_shift(const Vec3& separation) const;
  /// Position mapped back into [0, L_i) on every axis.
  [[nodiscard]] Vec3 wrap(const Vec3& position) const;
  /// Fractional coordinates s = x ./ L, and back.
  [[nodiscard]] Vec3 to_fractional(const Vec3& position) const { return position.cwiseQuotient(lengths_); }
  [[nodiscard]] Vec3 from_fractional(const Vec3& fractional) const {
    return fractional.cwiseProduct(lengths_);
  }

  /// Minimum image of the separation of two positions that are both inside the cell
  /// (|d_a| < L_a): one comparison per axis and no rounding, for inner loops.
  [[nodiscard]] static Vec3 minimum_image_of_wrapped(Vec3 d, const Vec3& lengths) {
    for (int a = 0; a < 3; ++a) {
      if (d[a] > 0.5 * lengths[a]) {
        d[a] -= lengths[a];
      } else if (d[a] < -0.5 * lengths[a]) {
        d[a] += lengths[a];
      }
    }
    return d;
  }
  /// Position mapped back into [0, L_i) when it has left the cell by less than one length
  /// (a time step); falls back to wrap() otherwise.
  [[nodiscard]] Vec3 wrap_nearby(Vec3 position) const {
    for (int a = 0; a < 3; ++a) {
      if (position[a] >= lengths_[a]) {
        position[a] -= lengths_[a];
      } else if (position[a] < 0.0) {
        position[a] += lengths_[a];
      }
      if (!(position[a] >= 0.0 && position[a] < lengths_[a])) return wrap(position);
    }
    return position;
  }

  /// Sets new lengths (all positive); affine remapping of particles is the caller's job.
  void set_lengths(const Vec3& lengths);

private:
  Vec3 lengths_;
  Vec3 reference_lengths_;
};

} // namespace aniso
