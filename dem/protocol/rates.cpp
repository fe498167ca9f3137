#include "dem/protocol/rates.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

namespace aniso::dem::protocol {

void require_reachable_strain(double strain, double rate, double time_step, const std::string& what) {
  const double steps = strain / (rate * time_step);
  require_input(
      steps <= max_run_steps,
      fmt::format("{}: a strain of {:.3g} at {:.3g} /s with a time step of {:.3g} s takes {:.3g} steps "
                  "(more than {:.0e}): the rate (set by the inertial number and the mean stress) or the "
                  "time step (set by the shear modulus, the density and the smallest particle) is too small",
                  what, strain, rate, time_step, steps, max_run_steps));
}

} // namespace aniso::dem::protocol
