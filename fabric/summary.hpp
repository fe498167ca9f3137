#pragma once
// What the paper plots of each tensor: principal values and the two axis anisotropies.

#include "common/tensor.hpp"

#include <array>

namespace aniso::fabric {

struct TensorSummary {
  Vec3 eigenvalues;                 ///< of the symmetric part, descending
  std::array<double, 2> anisotropy; ///< (A11 - A33)/(tr A / 3), (A22 - A33)/(tr A / 3); NaN when tr A = 0
};

TensorSummary summarize(const Mat3& tensor);

} // namespace aniso::fabric
