#include "dem/io/parameters.hpp"

#include "common/error.hpp"
#include "common/units.hpp"
#include "dem/io/parameter_ranges.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace aniso::dem::io {

using config::Range;

DemConfig read_dem_config(config::Reader& reader) {
  DemConfig c;
  c.seed = static_cast<std::uint64_t>(
      reader.integer("dem.seed", 1, Range::non_negative(), "seed of every random stream"));
  c.output_dir = reader.text("dem.output_dir", ".", "folder for checkpoints and history");

  auto& p = c.particles;
  p.count = reader.integer("dem.particles.count", p.count, Range::closed(2, 1e9), "number of particles");
  p.diameter_min = reader.real("dem.particles.diameter_min", p.diameter_min, units::metre, ranges::diameter(),
                               "smallest diameter (mid-plane diameter for ovoids)");
  p.diameter_max = reader.real("dem.particles.diameter_max", p.diameter_max, units::metre, ranges::diameter(),
                               "largest diameter");
  p.d50 =
      reader.real("dem.particles.d50", p.d50, units::metre, ranges::diameter(), "median diameter by volume");
  p.aspect_ratio =
      reader.real("dem.particles.aspect_ratio", p.aspect_ratio, units::none, ranges::aspect_ratio(),
                  "axial height / mid-plane diameter (paper: 1, 0.8, 0.625, 0.5)");
  p.splice_angle =
      reader.real("dem.particles.splice_angle_degrees", p.splice_angle * 180.0 / std::numbers::pi,
                  units::none, ranges::splice_angle_degrees(),
                  "ovoid splice angle beta between axis and surface normal where cap meets band, "
                  "in degrees (Kuhn's OVAL: 45); must be below 2 atan(aspect_ratio)") *
      std::numbers::pi / 180.0;
  p.density =
      reader.real("dem.particles.density", p.density, units::density, ranges::density(), "solid density");
  if (p.aspect_ratio < 1.0) {
    const double limit = 2.0 * std::atan(p.aspect_ratio);
    require_input(p.splice_angle < limit,
                  fmt::format("config key 'dem.particles.splice_angle_degrees': {:.6g} is not below "
                              "2 atan(aspect_ratio) = {:.6g} degrees for aspect ratio {}",
                              p.splice_angle * 180.0 / std::numbers::pi, limit * 180.0 / std::numbers::pi,
                              p.aspect_ratio));
  }
  require_input(
      p.diameter_min < p.d50 && p.d50 < p.diameter_max,
      fmt::format("config: need dem.particles.diameter_min < d50 < diameter_max, got {} < {} < {} m",
                  p.diameter_min, p.d50, p.diameter_max));

  auto& m = c.material;
  m.shear_modulus = reader.real("dem.material.shear_modulus", m.shear_modulus, units::pascal,
                                ranges::shear_modulus(), "particle shear modulus G");
  m.poisson_ratio = reader.real("dem.material.poisson_ratio", m.poisson_ratio, units::none,
                                ranges::poisson_ratio(), "particle Poisson ratio");
  m.friction = reader.real("dem.material.friction", m.friction, units::none, ranges::friction(),
                           "inter-particle friction for consolidation and loading");
  m.friction_prepare = reader.real("dem.material.friction_prepare", m.friction_prepare, units::none,
                                   ranges::friction(), "inter-particle friction during compaction cycles");
  m.hertz_radius =
      reader.choice("dem.material.hertz_radius", "halfwidth", {"halfwidth", "curvature"},
                    "ovoid Hertz radius: 'halfwidth' R* = a_i a_j / (a_i + a_j) as in Kuhn's "
                    "code, or 'curvature' (elliptic Hertz from the surface curvatures)") == "curvature"
          ? model::HertzRadius::curvature
          : model::HertzRadius::halfwidth;

  auto& i = c.integration;
  i.time_step_fraction = reader.real(
      "dem.integration.time_step_fraction", i.time_step_fraction, units::none, Range::open_closed(0.0, 1.0),
      "time step as a fraction of the Rayleigh critical step of the smallest particle");
  i.time_step =
      reader.real("dem.integration.time_step", i.time_step, units::second, Range::non_negative(),
                  "explicit time step (0: from time_step_fraction); refused above the critical step");
  i.damping = reader.real("dem.integration.damping", i.damping, units::none, ranges::contact_damping(),
                          "viscous contact damping ratio during loading");
  i.global_damping =
      reader.real("dem.integration.global_damping", i.global_damping, units::none, ranges::global_damping(),
                  "global damping of the fluctuating motion during loading, as a fraction of "
                  "critical for the mean particle on the mean contact stiffness");
  i.skin = reader.real("dem.integration.skin", i.skin, units::none, Range::open_closed(0.0, 1.0),
                       "neighbour-list skin in units of D50");
  i.control_interval =
      reader.integer("dem.integration.control_interval", i.control_interval, ranges::control_interval(),
                     "steps between stress measurements and servo updates");
  i.servo_gain = reader.real("dem.integration.servo_gain", i.servo_gain, units::none, ranges::servo_gain(),
                             "fraction of the stress error removed per servo update");
  i.explosion_overlap =
      reader.real("dem.integration.explosion_overlap", i.explosion_overlap, units::none,
                  ranges::explosion_overlap(), "stop when an overlap exceeds this fraction of a radius");

  auto& pr = c.prepare;
  pr.cell_aspect = reader.reals("dem.prepare.cell_aspect", pr.cell_aspect, units::none, Range::positive(), 3,
                                "cell proportions L1:L2:L3");
  require_input(pr.cell_aspect.size() == 3,
                fmt::format("config key 'dem.prepare.cell_aspect': {} values given, expected exactly 3",
                            pr.cell_aspect.size()));
  pr.initial_solid_fraction = reader.real(
      "dem.prepare.initial_solid_fraction", pr.initial_solid_fraction, units::none, Range::open(0.0, 0.4),
      "solid fraction of the sparse start, counted with bounding spheres (half-width radius)");
  pr.cycles = reader.integer(
      "dem.prepare.cycles", pr.cycles, Range::closed(1, 1000),
      "most compaction cycles (paper: 14); stops at the first that seizes at or below the target");
  pr.target_void_ratio = reader.real("dem.prepare.target_void_ratio", pr.target_void_ratio, units::none,
                                     Range::positive(), "keep the assembly nearest this void ratio");
  pr.void_ratio_tolerance = reader.real(
      "dem.prepare.void_ratio_tolerance", pr.void_ratio_tolerance, units::none, Range::positive(),
      "largest |e - target_void_ratio| of the prepared assembly; beyond it prepare fails (exit 5)");
  pr.confining_pressure = reader.real("dem.prepare.confining_pressure", pr.confining_pressure, units::pascal,
                                      Range::positive(), "isotropic consolidation pressure p0");
  pr.inertial_number = reader.real("dem.prepare.inertial_number", pr.inertial_number, units::none,
                                   Range::open(0.0, 1.0), "compaction and consolidation rate as I at p0");
  pr.damping = reader.real("dem.prepare.damping", pr.damping, units::none, ranges::contact_damping(),
                           "contact damping ratio while compacting");
  pr.global_damping =
      reader.real("dem.prepare.global_damping", pr.global_damping, units::none, ranges::global_damping(),
                  "global damping ratio of the fluctuating motion while compacting");
  pr.seize_stress = reader.real("dem.prepare.seize_stress", pr.seize_stress, units::pascal, Range::positive(),
                                "mean stress at which a compacting assembly counts as seized");
  require_input(pr.seize_stress < pr.confining_pressure,
                "config: dem.prepare.seize_stress must be below dem.prepare.confining_pressure");
  pr.seize_force_ratio =
      reader.real("dem.prepare.seize_force_ratio", pr.seize_force_ratio, units::none, Range::open(0.0, 1.0),
                  "unbalanced-force ratio below which a held assembly above the seize stress has seized");
  pr.agitation_speed = reader.real("dem.prepare.agitation_speed", pr.agitation_speed, units::none,
                                   Range::non_negative(), "rms random speed between cycles, in sqrt(p0/rho)");
  pr.consolidation_tolerance =
      reader.real("dem.prepare.consolidation_tolerance", pr.consolidation_tolerance, units::none,
                  Range::open(0.0, 0.5), "|p - p0|/p0 to end consolidation");
  pr.refinement_cycles = reader.integer(
      "dem.prepare.refinement_cycles", pr.refinement_cycles, Range::closed(0, 100),
      "most re-runs of the cycle that steps across the target (plus the consolidation's compaction) with a "
      "weaker agitation");

  auto& l = c.load;
  l.inertial_number = reader.real("dem.load.inertial_number", l.inertial_number, units::none,
                                  Range::open(0.0, 1.0), "I = strain rate * D50 * sqrt(density / p)");
  l.final_strain = reader.real("dem.load.final_strain", l.final_strain, units::none,
                               Range::open_closed(0.0, 0.9), "final compressive strain -eps11");
  l.mean_stress = reader.real("dem.load.mean_stress", l.mean_stress, units::pascal, Range::positive(),
                              "mean stress held during loading");
  l.checkpoint_strains =
      reader.reals("dem.load.checkpoint_strains", {}, units::none, Range::open_closed(0.0, 0.9), 0,
                   "compressive strains -eps11 at which checkpoints are written");
  // load_NNN.h5 is numbered in list order and the loading passes each strain once.
  for (std::size_t k = 0; k < l.checkpoint_strains.size(); ++k) {
    const double strain = l.checkpoint_strains[k];
    if (k > 0 && strain <= l.checkpoint_strains[k - 1]) {
      throw InputError(
          fmt::format("config key 'dem.load.checkpoint_strains': element {} = {:g} is not above the "
                      "one before it ({:g}): list the strains once each, in increasing order",
                      k, strain, l.checkpoint_strains[k - 1]));
    }
    if (strain > l.final_strain) {
      throw InputError(fmt::format("config key 'dem.load.checkpoint_strains': element {} = {:g} lies beyond "
                                   "dem.load.final_strain = {:g}, so the loading would never write it",
                                   k, strain, l.final_strain));
    }
  }
  l.history_interval = reader.real("dem.load.history_interval", l.history_interval, units::none,
                                   Range::positive(), "strain between history rows");

  auto& e = c.equilibrium;
  e.tolerance = reader.real("dem.equilibrium.tolerance", e.tolerance, units::none, Range::open(0.0, 1.0),
                            "unbalanced-force ratio (mean |net force| / mean |contact force|) below which "
                            "a state counts as static");
  e.stress_tolerance =
      reader.real("dem.equilibrium.stress_tolerance", e.stress_tolerance, units::none, Range::open(0.0, 0.5),
                  "|p - p_target| / p_target required together with the force tolerance");
  e.damping = reader.real("dem.equilibrium.damping", e.damping, units::none, Range::open_closed(0.0, 10.0),
                          "global damping ratio while relaxing to equilibrium");
  e.verify_steps = reader.integer("dem.equilibrium.verify_steps", e.verify_steps, Range::closed(0, 1e9),
                                  "time steps the tolerances must then keep holding with the damping of the "
                                  "run (an unstable balance fails this and relaxes on)");
  e.max_steps = reader.integer("dem.equilibrium.max_steps", e.max_steps, Range::closed(1, 1e10),
                               "most time steps of one relaxation; beyond it the run stops (exit 5)");
  e.at_checkpoints =
      reader.boolean("dem.equilibrium.at_checkpoints", e.at_checkpoints,
                     "relax to equilibrium (cell held, p servoed) before each load checkpoint");
  l.increment = reader.real("dem.load.increment", l.increment, units::none, Range::closed(0.0, 0.1),
                            "strain per loading increment, each followed by a relaxation to "
                            "increment_tolerance (Kuhn's OVAL practice); 0: continuous loading");
  l.increment_tolerance =
      reader.real("dem.load.increment_tolerance", l.increment_tolerance, units::none, Range::open(0.0, 1.0),
                  "unbalanced-force ratio that ends the relaxation after each increment (OVAL: 0.01)");
  return c;
}

} // namespace aniso::dem::io
