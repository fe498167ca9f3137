#include "probe/config.hpp"

#include "common/error.hpp"
#include "common/units.hpp"

#include <fmt/format.h>

namespace aniso::probe {

using config::Range;

ProbeConfig read_probe_config(config::Reader& reader) {
  ProbeConfig c;
  c.output_dir = reader.text("probe.output_dir", c.output_dir, "folder for probe results and fork files");
  c.increment = reader.real("probe.increment", c.increment, units::none, Range::closed(1e-9, 1e-2),
                            "|d eps_ii| of each oedometric fork (paper: 5e-5)");
  c.inertial_number =
      reader.real("probe.inertial_number", c.inertial_number, units::none, Range::closed(1e-7, 1e-1),
                  "rate of the increment as an inertial number at the checkpoint's mean stress");
  c.hold_steps = reader.integer("probe.hold_steps", c.hold_steps, Range::closed(10, 1e9),
                                "steps held after each half increment before the stress is read");
  c.window_steps = reader.integer("probe.window_steps", c.window_steps, Range::closed(10, 1e9),
                                  "the stress is averaged over the last window_steps of each hold");
  require_input(c.window_steps <= c.hold_steps,
                fmt::format("config: probe.window_steps ({}) must not exceed probe.hold_steps ({})",
                            c.window_steps, c.hold_steps));
  c.linearity_tolerance =
      reader.real("probe.linearity_tolerance", c.linearity_tolerance, units::none, Range::positive(),
                  "largest relative difference of the moduli of the two half increments (too large an "
                  "increment otherwise)");
  c.noise_tolerance =
      reader.real("probe.noise_tolerance", c.noise_tolerance, units::none, Range::positive(),
                  "largest rms fluctuation of d sigma_ii over the window, relative to d sigma_ii (too small "
                  "an increment otherwise)");
  c.check_increment = reader.boolean("probe.check_increment", c.check_increment,
                                     "refuse results whose increment is detected as too large or too small");
  return c;
}

} // namespace aniso::probe
