#include "probe/config.hpp"

#include "common/error.hpp"
#include "common/units.hpp"

#include <fmt/format.h>

namespace aniso::probe {

using config::Range;

ProbeConfig read_probe_config(config::Reader& reader) {
  ProbeConfig c;
  c.output_dir = reader.text("probe.output_dir", c.output_dir, "folder for probe results and fork files");
  c.increment = reader.real("probe.increment", c.increment, units::none, Range::closed(1e-16, 1e-2),
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
  auto& t = c.tolerances;
  t.linearity = reader.real(
      "probe.linearity_tolerance", t.linearity, units::none, Range::positive(),
      "too large an increment: the moduli of the two half increments differ by more (fraction of O_i)");
  t.sliding = reader.real("probe.sliding_tolerance", t.sliding, units::none, Range::positive(),
                          "too large an increment: it made more than this fraction of the contacts slide");
  t.resolution =
      reader.real("probe.resolution_floor", t.resolution, units::none, Range::closed(0.0, 1.0),
                  "too small an increment: its stress response is a smaller fraction of the stress");
  t.noise = reader.real("probe.noise_tolerance", t.noise, units::none, Range::positive(),
                        "reading unsettled: rms of d sigma_ii over the window, relative to d sigma_ii");
  c.check_increment = reader.boolean("probe.check_increment", c.check_increment,
                                     "refuse results whose increment is detected as too large or too small");
  return c;
}

} // namespace aniso::probe
