#include "fabric/summary.hpp"

#include <limits>

namespace aniso::fabric {

TensorSummary summarize(const Mat3& tensor) {
  TensorSummary s;
  s.eigenvalues = sorted_eigen(0.5 * (tensor + tensor.transpose())).values;
  // A tensor over an empty set (no strong contacts) is zero: its anisotropy is undefined.
  if (tensor.trace() == 0.0) {
    s.anisotropy = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  } else {
    s.anisotropy = axis_anisotropy(tensor);
  }
  return s;
}

} // namespace aniso::fabric
