#include "lbm/config.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

namespace aniso::lbm {

LbmConfig read_lbm_config(config::Reader& reader) {
  using config::Range;
  LbmConfig c;
  PermeabilitySettings& p = c.permeability;
  FlowSettings& f = p.flow;
  p.method =
      reader.choice("lbm.method", "periodic_body_force", {"periodic_body_force", "paper_walls"},
                    "periodic_body_force: fully periodic, three force directions, whole tensor; "
                    "paper_walls: the paper's no-slip then free-slip side walls and eq. (kijsolver)") ==
              "paper_walls"
          ? Method::paper_walls
          : Method::periodic_body_force;
  f.precision = reader.choice("lbm.precision", "double", {"double", "float"},
                              "floating-point type of the populations and the collision") == "float"
                    ? Precision::float32
                    : Precision::float64;
  const std::string level = reader.choice(
      "lbm.instruction_set", "auto", {"auto", "baseline", "x86-64-v3", "x86-64-v4"},
      "x86-64 level of the step: auto picks the best this CPU runs; every level gives the same bits");
  f.instruction_set = level == "baseline"    ? InstructionSet::baseline
                      : level == "x86-64-v3" ? InstructionSet::x86_64_v3
                      : level == "x86-64-v4" ? InstructionSet::x86_64_v4
                                             : InstructionSet::automatic;
  f.tau =
      reader.real("lbm.tau", 0.0, "1", Range::closed(0.0, 10.0),
                  "TRT relaxation time of the symmetric moments, in (1/2, 10]; viscosity nu = (tau - 1/2)/3; "
                  "0: chosen from the image for the fewest steps (docs/methods/lbm.md)");
  require_input(
      f.tau == 0.0 || f.tau > 0.5,
      fmt::format("lbm.tau = {} must be above 1/2 (the viscosity (tau - 1/2)/3 must be positive), or 0 "
                  "for the automatic choice",
                  f.tau));
  f.magic = reader.real("lbm.magic", 3.0 / 16.0, "1", Range::positive(),
                        "TRT magic parameter Lambda; 3/16 puts halfway bounce-back walls exactly midway");
  p.body_force = reader.real("lbm.body_force", 0.0, "lattice", Range::closed(0.0, 1e-1),
                             "driving force density in lattice units (velocity and Mach number scale with "
                             "it); 0: chosen from the image for lbm.target_reynolds (docs/methods/lbm.md)");
  p.target_reynolds =
      reader.real("lbm.target_reynolds", 0.05, "1", Range::open_closed(0.0, 1.0),
                  "permeability Reynolds number |<j>| sqrt(K) / nu the automatic force aims at "
                  "(inertia biases K by about -2e-3 Re^2)");
  f.criterion = reader.choice("lbm.convergence.criterion", "error", {"error", "change"},
                              "error: stop when the relative error of the mean velocity that its decay "
                              "leaves is below the tolerance; change: when it changes by less than the "
                              "tolerance per check interval (docs/methods/lbm.md)") == "change"
                    ? StopCriterion::change
                    : StopCriterion::error;
  f.tolerance = reader.real("lbm.convergence.tolerance", f.criterion == StopCriterion::error ? 1e-4 : 1e-5,
                            "1", Range::open(0.0, 1.0),
                            "the error criterion's bound on the estimated relative error of the mean "
                            "velocity (default 1e-4), or the change criterion's on its relative change per "
                            "check interval (default 1e-5)");
  f.check_interval =
      reader.integer("lbm.convergence.check_interval", 100, Range::closed(2, 1e6),
                     "steps between convergence and divergence checks (each check averages the "
                     "flow over two consecutive steps)");
  f.max_steps = reader.integer("lbm.max_steps", 200000, Range::closed(1, 1e9),
                               "step limit of each flow run (ConvergenceError when reached)");
  f.max_mach = reader.real("lbm.divergence.max_mach", 0.1, "1", Range::open_closed(0.0, 1.0),
                           "stop when max|u|/c_s exceeds this (compressibility error, onset of instability)");
  f.mass_drift = reader.real("lbm.divergence.mass_drift", 1e-6, "1", Range::positive(),
                             "stop when the mean density deviation drifts by more than this");
  c.write_velocity = reader.boolean("lbm.write_velocity", false,
                                    "also write the velocity field of every run (HDF5 + XDMF for ParaView)");
  f.keep_velocity = c.write_velocity;
  // The convergence test compares the mean velocity at two checks, so fewer steps never converge
  // (and the first check came after max_steps, reported as a run longer than asked).
  require_input(f.max_steps >= 2 * f.check_interval,
                fmt::format("lbm.max_steps = {} is below two convergence checks (2 x "
                            "lbm.convergence.check_interval = {}): the test compares the mean velocity "
                            "of two checks, so the flow could never converge",
                            f.max_steps, 2 * f.check_interval));
  c.output_dir = reader.text("lbm.output_dir", ".", "folder for permeability_<image stem>.h5");
  c.petsc_options =
      reader.text("lbm.petsc_options", "", "PETSc options database entries, e.g. \"-log_view\"");
  return c;
}

} // namespace aniso::lbm
