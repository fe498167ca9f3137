#include "dem/io/parameters.hpp"

#include "common/error.hpp"
#include "common/units.hpp"
#include "dem/load_behaviour.hpp"
#include "dem/measures.hpp"
#include "dem/model/integrator.hpp"
#include "dem/model/particle_shape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <type_traits>
#include <variant>

namespace aniso::dem::io {
namespace {

using config::Range;

// The member a key sets, by its path of member pointers: member<&DemConfig::load,
// &LoadConfig::final_strain> is config.load.final_strain.
template <auto... Path> auto& member(DemConfig& config) {
  return (config.*....*Path);
}

// The engine's member an attribute holds, read and written as the attribute's double.
template <auto... Path> double get_setting(const SimulationSettings& settings) {
  const auto& value = (settings.*....*Path);
  if constexpr (std::is_enum_v<std::remove_cvref_t<decltype(value)>>) {
    return static_cast<double>(static_cast<int>(value));
  } else {
    return static_cast<double>(value);
  }
}
template <auto... Path> void set_setting(SimulationSettings& settings, double stored) {
  auto& value = (settings.*....*Path);
  using Value = std::remove_cvref_t<decltype(value)>;
  if constexpr (std::is_enum_v<Value>) {
    value = static_cast<Value>(static_cast<int>(stored));
  } else {
    value = static_cast<Value>(stored);
  }
}

using Real = double& (*)(DemConfig&);
using Integer = std::int64_t& (*)(DemConfig&);
using Boolean = bool& (*)(DemConfig&);
using Text = std::string& (*)(DemConfig&);
using Reals = std::vector<double>& (*)(DemConfig&);
// A choice key's member, an enum, as the index of its word.
struct Choice {
  int (*get)(const DemConfig&);
  void (*set)(DemConfig&, int);
};
template <auto... Path> constexpr Choice choice() {
  return {[](const DemConfig& config) { return static_cast<int>((config.*....*Path)); },
          [](DemConfig& config, int index) {
            auto& value = (config.*....*Path);
            value = static_cast<std::remove_cvref_t<decltype(value)>>(index);
          }};
}
using Seed = std::uint64_t& (*)(DemConfig&);
using ConfigMember = std::variant<std::monostate, Real, Integer, Boolean, Text, Reals, Choice, Seed>;

// A configured value whose key is in another unit than its member: key = member * scale / divisor,
// member = key * divisor / scale (degrees on the key, radians in the member).
struct KeyUnit {
  double scale = 1;
  double divisor = 1;
};

// A stored value in another unit than its key: the skin is configured in D50 and stored in metres.
struct StoredUnit {
  double (*from_config)(double configured, const DemConfig& config);
  double (*to_config)(double stored, const DemConfig& config);
};

struct Parameter {
  std::string_view key = {}; ///< configuration key ("" for Binding::stored_only)
  ConfigMember config = {};
  std::string_view unit = {}; ///< of the key's value
  Range range = {};           ///< of the key's value
  std::string_view help = {};
  std::string_view attribute = {}; ///< checkpoint /parameters attribute ("": not stored)
  double (*get)(const SimulationSettings&) = nullptr;
  void (*set)(SimulationSettings&, double) = nullptr;
  Binding binding = Binding::config_only;
  std::string_view stored_unit = {}; ///< of the attribute, when not the key's
  std::optional<Range> stored_range = {};
  std::optional<KeyUnit> key_unit = {};
  std::optional<StoredUnit> stored_as = {};
  std::size_t min_count = 0;           ///< list keys: fewest elements
  std::vector<std::string> words = {}; ///< choice keys: the words, in enum order
  /// The stored value of a checkpoint written before the attribute existed (none: it must be there).
  std::optional<double> absent = {};
};

constexpr double degrees_per_radian = 180.0;
constexpr double radian_divisor = std::numbers::pi;

// Every DEM parameter, in the order --print-config lists them.
const std::vector<Parameter>& parameters() {
  using D = DemConfig;
  using S = SimulationSettings;
  using Material = model::ContactMaterial;
  using Servo = model::ServoSettings;
  static const std::vector<Parameter> table{
      {.key = "dem.seed",
       .config = &member<&D::seed>,
       .range = Range::non_negative(),
       .help = "seed of every random stream"},
      {.key = "dem.output_dir",
       .config = &member<&D::output_dir>,
       .help = "folder for checkpoints and history"},
      {.key = "dem.particles.count",
       .config = &member<&D::particles, &ParticleConfig::count>,
       .range = Range::closed(2, 1e9),
       .help = "number of particles"},
      // Particle diameters in metres, from a nanometre to a kilometre: far smaller sizes underflow
      // the volumes and inertias (d^5) that the simulation needs.
      {.key = "dem.particles.diameter_min",
       .config = &member<&D::particles, &ParticleConfig::diameter_min>,
       .unit = units::metre,
       .range = Range::closed(1e-9, 1e3),
       .help = "smallest diameter (mid-plane diameter for ovoids)"},
      {.key = "dem.particles.diameter_max",
       .config = &member<&D::particles, &ParticleConfig::diameter_max>,
       .unit = units::metre,
       .range = Range::closed(1e-9, 1e3),
       .help = "largest diameter"},
      {.key = "dem.particles.d50",
       .config = &member<&D::particles, &ParticleConfig::d50>,
       .unit = units::metre,
       .range = Range::closed(1e-9, 1e3),
       .help = "median diameter by volume",
       .attribute = h5::parameter_name::d50,
       .get = &get_setting<&S::d50>,
       .set = &set_setting<&S::d50>,
       .binding = Binding::fixed},
      {.key = "dem.particles.aspect_ratio",
       .config = &member<&D::particles, &ParticleConfig::aspect_ratio>,
       .unit = units::none,
       .range = Range::open_closed(0.2, 1.0),
       .help = "axial height / mid-plane diameter (paper: 1, 0.8, 0.625, 0.5)"},
      {.key = "dem.particles.splice_angle_degrees",
       .config = &member<&D::particles, &ParticleConfig::splice_angle>,
       .unit = units::none,
       .range = Range::open(0.0, 90.0),
       .help = "ovoid splice angle beta between axis and surface normal where cap meets band, in degrees "
               "(Kuhn's OVAL: 45); must be below 2 atan(aspect_ratio)",
       .attribute = h5::parameter_name::splice_angle,
       .get = &get_setting<&S::splice_angle>,
       .set = &set_setting<&S::splice_angle>,
       .binding = Binding::fixed,
       .stored_unit = units::radian,
       .stored_range = Range::open(0.0, std::numbers::pi / 2),
       .key_unit = KeyUnit{degrees_per_radian, radian_divisor}},
      {.key = "dem.particles.density",
       .config = &member<&D::particles, &ParticleConfig::density>,
       .unit = units::density,
       .range = Range::positive(),
       .help = "solid density",
       .attribute = h5::parameter_name::density,
       .get = &get_setting<&S::density>,
       .set = &set_setting<&S::density>,
       .binding = Binding::fixed},
      {.key = "dem.material.shear_modulus",
       .config = &member<&D::material, &MaterialConfig::shear_modulus>,
       .unit = units::pascal,
       .range = Range::positive(),
       .help = "particle shear modulus G",
       .attribute = "shear_modulus",
       .get = &get_setting<&S::material, &Material::shear_modulus>,
       .set = &set_setting<&S::material, &Material::shear_modulus>,
       .binding = Binding::fixed},
      {.key = "dem.material.poisson_ratio",
       .config = &member<&D::material, &MaterialConfig::poisson_ratio>,
       .unit = units::none,
       .range = Range::open(-1.0, 0.5),
       .help = "particle Poisson ratio",
       .attribute = "poisson_ratio",
       .get = &get_setting<&S::material, &Material::poisson_ratio>,
       .set = &set_setting<&S::material, &Material::poisson_ratio>,
       .binding = Binding::fixed},
      {.key = "dem.material.friction",
       .config = &member<&D::material, &MaterialConfig::friction>,
       .unit = units::none,
       .range = Range::non_negative(),
       .help = "inter-particle friction for consolidation and loading",
       .attribute = "friction",
       .get = &get_setting<&S::material, &Material::friction>,
       .set = &set_setting<&S::material, &Material::friction>,
       .binding = Binding::resumed},
      {.key = "dem.material.friction_prepare",
       .config = &member<&D::material, &MaterialConfig::friction_prepare>,
       .unit = units::none,
       .range = Range::non_negative(),
       .help = "inter-particle friction during compaction cycles"},
      {.key = "dem.material.hertz_radius",
       .config = choice<&D::material, &MaterialConfig::hertz_radius>(),
       .help =
           "ovoid Hertz radius: 'halfwidth' R* = a_i a_j / (a_i + a_j) as in Kuhn's code, 'curvature' "
           "(elliptic Hertz from the surface curvatures) or 'mean_semi_axis' (each a_i (2 + alpha) / 3, as "
           "DEMPLA 0.2.5 does)",
       .attribute = "hertz_radius_curvature",
       .get = &get_setting<&S::hertz_radius>,
       .set = &set_setting<&S::hertz_radius>,
       .binding = Binding::fixed,
       .stored_unit = units::none,
       .stored_range = Range::closed(0.0, 2.0),
       .words = {"halfwidth", "curvature", "mean_semi_axis"}},
      {.key = "dem.integration.time_step_fraction",
       .config = &member<&D::integration, &IntegrationConfig::time_step_fraction>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 1.0),
       .help = "time step as a fraction of the Rayleigh critical step of the smallest particle"},
      {.key = "dem.integration.time_step",
       .config = &member<&D::integration, &IntegrationConfig::time_step>,
       .unit = units::second,
       .range = Range::non_negative(),
       .help = "explicit time step (0: from time_step_fraction); refused above the critical step"},
      {.key = "dem.integration.damping",
       .config = &member<&D::integration, &IntegrationConfig::damping>,
       .unit = units::none,
       .range = Range::closed(0.0, 1.0),
       .help = "viscous contact damping ratio during loading",
       .attribute = "damping_ratio",
       .get = &get_setting<&S::material, &Material::damping_ratio>,
       .set = &set_setting<&S::material, &Material::damping_ratio>,
       .binding = Binding::resumed},
      {.key = "dem.integration.global_damping",
       .config = &member<&D::integration, &IntegrationConfig::global_damping>,
       .unit = units::none,
       .range = Range::closed(0.0, 10.0),
       .help = "global damping of the fluctuating motion during loading, as a fraction of critical for the "
               "mean particle on the mean contact stiffness",
       .attribute = "global_damping",
       .get = &get_setting<&S::global_damping>,
       .set = &set_setting<&S::global_damping>,
       .binding = Binding::resumed},
      {.key = "dem.integration.global_damping_spin_factor",
       .config = &member<&D::integration, &IntegrationConfig::global_damping_spin_factor>,
       .unit = units::none,
       .range = Range::closed(0.0, 100.0),
       .help =
           "the global damping rate of the spin as a multiple of that of the translation (1: the same; "
           "about 6 gives the damping torque of DEMPLA's samples, whose grains have five times a sphere's "
           "moment of inertia: a rolling resistance in effect)",
       .attribute = "global_damping_spin_factor",
       .get = &get_setting<&S::global_damping_spin_factor>,
       .set = &set_setting<&S::global_damping_spin_factor>,
       .binding = Binding::resumed,
       .absent = 1.0},
      {.key = "dem.integration.skin",
       .config = &member<&D::integration, &IntegrationConfig::skin>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 1.0),
       .help = "neighbour-list skin in units of D50",
       .attribute = "skin",
       .get = &get_setting<&S::skin>,
       .set = &set_setting<&S::skin>,
       .binding = Binding::fixed,
       .stored_unit = units::metre,
       .stored_range = Range::positive(),
       .stored_as = StoredUnit{[](double skin, const DemConfig& c) { return skin * c.particles.d50; },
                               [](double skin, const DemConfig& c) { return skin / c.particles.d50; }}},
      {.key = "dem.integration.control_interval",
       .config = &member<&D::integration, &IntegrationConfig::control_interval>,
       .range = Range::closed(1, 1e6),
       .help = "steps between stress measurements and servo updates",
       .attribute = "control_interval",
       .get = &get_setting<&S::control_interval>,
       .set = &set_setting<&S::control_interval>,
       .binding = Binding::resumed,
       .stored_unit = units::none},
      {.key = "dem.integration.servo_gain",
       .config = &member<&D::integration, &IntegrationConfig::servo_gain>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 1.0),
       .help = "fraction of the stress error removed per servo update",
       .attribute = "servo_gain",
       .get = &get_setting<&S::servo, &Servo::gain>,
       .set = &set_setting<&S::servo, &Servo::gain>,
       .binding = Binding::resumed},
      {.attribute = "servo_max_rate",
       .get = &get_setting<&S::servo, &Servo::max_rate>,
       .set = &set_setting<&S::servo, &Servo::max_rate>,
       .binding = Binding::stored_only,
       .stored_unit = units::per_second,
       .stored_range = Range::non_negative()}, // 0: no cap
      {.attribute = "servo_integral_intervals",
       .get = &get_setting<&S::servo, &Servo::integral_intervals>,
       .set = &set_setting<&S::servo, &Servo::integral_intervals>,
       .binding = Binding::stored_only,
       .stored_unit = units::none,
       .stored_range = Range::positive()},
      {.key = "dem.integration.explosion_overlap",
       .config = &member<&D::integration, &IntegrationConfig::explosion_overlap>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "stop when an overlap exceeds this fraction of a radius",
       .attribute = "explosion_overlap",
       .get = &get_setting<&S::explosion_overlap>,
       .set = &set_setting<&S::explosion_overlap>,
       .binding = Binding::fixed},
      {.key = "dem.prepare.cell_aspect",
       .config = &member<&D::prepare, &PrepareConfig::cell_aspect>,
       .unit = units::none,
       .range = Range::positive(),
       .help = "cell proportions L1:L2:L3",
       .min_count = 3},
      {.key = "dem.prepare.initial_solid_fraction",
       .config = &member<&D::prepare, &PrepareConfig::initial_solid_fraction>,
       .unit = units::none,
       .range = Range::open(0.0, 0.4),
       .help = "solid fraction of the sparse start, counted with bounding spheres (half-width radius)"},
      {.key = "dem.prepare.cycles",
       .config = &member<&D::prepare, &PrepareConfig::cycles>,
       .range = Range::closed(1, 1000),
       .help = "most compaction cycles (paper: 14); stops at the first that seizes at or below the target"},
      {.key = "dem.prepare.target_void_ratio",
       .config = &member<&D::prepare, &PrepareConfig::target_void_ratio>,
       .unit = units::none,
       .range = Range::positive(),
       .help = "keep the assembly nearest this void ratio"},
      {.key = "dem.prepare.void_ratio_tolerance",
       .config = &member<&D::prepare, &PrepareConfig::void_ratio_tolerance>,
       .unit = units::none,
       .range = Range::positive(),
       .help = "largest |e - target_void_ratio| of the prepared assembly; beyond it prepare fails (exit 5)"},
      {.key = "dem.prepare.confining_pressure",
       .config = &member<&D::prepare, &PrepareConfig::confining_pressure>,
       .unit = units::pascal,
       .range = Range::positive(),
       .help = "isotropic consolidation pressure p0"},
      {.key = "dem.prepare.inertial_number",
       .config = &member<&D::prepare, &PrepareConfig::inertial_number>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "compaction and consolidation rate as I at p0"},
      {.key = "dem.prepare.damping",
       .config = &member<&D::prepare, &PrepareConfig::damping>,
       .unit = units::none,
       .range = Range::closed(0.0, 1.0),
       .help = "contact damping ratio while compacting"},
      {.key = "dem.prepare.global_damping",
       .config = &member<&D::prepare, &PrepareConfig::global_damping>,
       .unit = units::none,
       .range = Range::closed(0.0, 10.0),
       .help = "global damping ratio of the fluctuating motion while compacting"},
      {.key = "dem.prepare.global_damping_spin_factor",
       .config = &member<&D::prepare, &PrepareConfig::global_damping_spin_factor>,
       .unit = units::none,
       .range = Range::closed(0.0, 100.0),
       .help = "the spin's global damping rate while compacting, as a multiple of the translation's (the "
               "loading's dem.integration.global_damping_spin_factor does not act here)"},
      {.key = "dem.prepare.seize_stress",
       .config = &member<&D::prepare, &PrepareConfig::seize_stress>,
       .unit = units::pascal,
       .range = Range::positive(),
       .help = "mean stress at which a compacting assembly counts as seized"},
      {.key = "dem.prepare.seize_force_ratio",
       .config = &member<&D::prepare, &PrepareConfig::seize_force_ratio>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "unbalanced-force ratio below which a held assembly above the seize stress has seized"},
      {.key = "dem.prepare.agitation_speed",
       .config = &member<&D::prepare, &PrepareConfig::agitation_speed>,
       .unit = units::none,
       .range = Range::non_negative(),
       .help = "rms random speed between cycles, in sqrt(p0/rho)"},
      {.key = "dem.prepare.consolidation_tolerance",
       .config = &member<&D::prepare, &PrepareConfig::consolidation_tolerance>,
       .unit = units::none,
       .range = Range::open(0.0, 0.5),
       .help = "|p - p0|/p0 to end consolidation"},
      {.key = "dem.prepare.refinement_cycles",
       .config = &member<&D::prepare, &PrepareConfig::refinement_cycles>,
       .range = Range::closed(0, 100),
       .help = "most re-runs of the cycle that steps across the target (plus the consolidation's compaction) "
               "with a weaker agitation"},
      {.key = "dem.prepare.compaction_stop_void_ratio",
       .config = &member<&D::prepare, &PrepareConfig::compaction_stop_void_ratio>,
       .unit = units::none,
       .range = Range::non_negative(),
       .help =
           "0: the compaction cycles (seize, agitate, repeat); above 0: one compaction at friction_prepare, "
           "stopped when e falls to this value, then consolidated at the loading friction (e.g. a "
           "frictionless-made assembly)"},
      {.key = "dem.load.inertial_number",
       .config = &member<&D::load, &LoadConfig::inertial_number>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "I = strain rate * D50 * sqrt(density / p)"},
      {.key = "dem.load.final_strain",
       .config = &member<&D::load, &LoadConfig::final_strain>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 0.9),
       .help = "final compressive strain -eps11"},
      {.key = "dem.load.mean_stress",
       .config = &member<&D::load, &LoadConfig::mean_stress>,
       .unit = units::pascal,
       .range = Range::positive(),
       .help = "mean stress held during loading"},
      {.key = "dem.load.checkpoint_strains",
       .config = &member<&D::load, &LoadConfig::checkpoint_strains>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 0.9),
       .help = "compressive strains -eps11 at which checkpoints are written"},
      {.key = "dem.load.history_interval",
       .config = &member<&D::load, &LoadConfig::history_interval>,
       .unit = units::none,
       .range = Range::positive(),
       .help = "strain between history rows"},
      {.key = "dem.equilibrium.tolerance",
       .config = &member<&D::equilibrium, &EquilibriumConfig::tolerance>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "unbalanced-force ratio (mean |net force| / mean |contact force|) below which a state counts "
               "as static"},
      {.key = "dem.equilibrium.stress_tolerance",
       .config = &member<&D::equilibrium, &EquilibriumConfig::stress_tolerance>,
       .unit = units::none,
       .range = Range::open(0.0, 0.5),
       .help = "|p - p_target| / p_target required together with the force tolerance"},
      {.key = "dem.equilibrium.damping",
       .config = &member<&D::equilibrium, &EquilibriumConfig::damping>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 10.0),
       .help = "global damping ratio while relaxing to equilibrium"},
      {.key = "dem.equilibrium.verify_steps",
       .config = &member<&D::equilibrium, &EquilibriumConfig::verify_steps>,
       .range = Range::closed(0, 1e9),
       .help = "time steps the tolerances must then keep holding with the damping of the run (an unstable "
               "balance fails this and relaxes on)"},
      {.key = "dem.equilibrium.kinetic_growth",
       .config = &member<&D::equilibrium, &EquilibriumConfig::kinetic_growth>,
       .unit = units::none,
       .range = Range::closed(0.0, 1e12),
       .help = "a verification window also fails when the kinetic/elastic energy ratio grows this many times "
               "above its lowest value in the window past its first tenth: the balance is unstable (0: not "
               "checked)"},
      {.key = "dem.equilibrium.kinetic_floor",
       .config = &member<&D::equilibrium, &EquilibriumConfig::kinetic_floor>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "kinetic/elastic energy ratio below which its growth in a window does not count"},
      {.key = "dem.equilibrium.escape_steps",
       .config = &member<&D::equilibrium, &EquilibriumConfig::escape_steps>,
       .range = Range::closed(0, 1e9),
       .help = "after a window failed on dem.equilibrium.kinetic_growth, time steps of the run's own "
               "dynamics with the servo on (the unstable balance falls to another) before minimising again"},
      {.key = "dem.equilibrium.margin",
       .config = &member<&D::equilibrium, &EquilibriumConfig::margin>,
       .unit = units::none,
       .range = Range::open_closed(0.0, 1.0),
       .help = "a relaxation that is verified afterwards first reaches this fraction of the tolerances (a "
               "state that only just met them left them at the first fluctuation of the window)"},
      {.key = "dem.equilibrium.max_steps",
       .config = &member<&D::equilibrium, &EquilibriumConfig::max_steps>,
       .range = Range::closed(1, 1e10),
       .help = "most time steps of one relaxation; beyond it the run stops (exit 5)"},
      {.key = "dem.equilibrium.method",
       .config = choice<&D::equilibrium, &EquilibriumConfig::method>(),
       .help = "how a relaxation reaches a static state: 'fire' (the FIRE minimiser on the fluctuating "
               "motion) or 'damped' (global viscous damping of ratio dem.equilibrium.damping)",
       .words = {"damped", "fire"}},
      {.key = "dem.equilibrium.fire_time_step_factor",
       .config = &member<&D::equilibrium, &EquilibriumConfig::fire_time_step_factor>,
       .unit = units::none,
       .range = Range::closed(1.0, 4.0),
       .help = "largest time step of the FIRE minimiser, in the run's time steps (kept below the "
               "Rayleigh step)"},
      {.key = "dem.equilibrium.max_windows",
       .config = &member<&D::equilibrium, &EquilibriumConfig::max_windows>,
       .range = Range::non_negative(),
       .help = "verification windows a load checkpoint's or relax's relaxation may leave before it ends "
               "unverified at the balance the last window began from, its held steps recorded (0: no limit, "
               "it runs to max_steps; the consolidation always runs to its verification)"},
      {.key = "dem.equilibrium.at_checkpoints",
       .config = &member<&D::equilibrium, &EquilibriumConfig::at_checkpoints>,
       .help = "relax to equilibrium (cell held, p servoed) before each load checkpoint"},
      {.key = "dem.load.behaviour",
       .config = choice<&D::load, &LoadConfig::behaviour>(),
       .help = "named loading behaviour, read before the keys it sets (a key given explicitly wins): "
               "'inertial' (continuous, contact damping on sticking contacts), 'oval' (DEMPLA/OVAL's body "
               "damping of translation and spin, no contact damping, checkpoints relaxed as copies) or "
               "'quasi_static' (increments of 3e-5, each minimised to 1e-3); docs/methods/dem.md",
       .words = load_behaviour_words()},
      {.key = "dem.equilibrium.fork_checkpoints",
       .config = &member<&D::equilibrium, &EquilibriumConfig::fork_checkpoints>,
       .help = "with at_checkpoints: relax a copy of the state for each checkpoint and go on loading from "
               "the unrelaxed state, so that the loading path is that of a run without relaxations"},
      {.key = "dem.load.increment",
       .config = &member<&D::load, &LoadConfig::increment>,
       .unit = units::none,
       .range = Range::closed(0.0, 0.1),
       .help = "strain per loading increment, each followed by a relaxation to increment_tolerance (Kuhn's "
               "OVAL practice); 0: continuous loading"},
      {.key = "dem.load.quasi_static",
       .config = &member<&D::load, &LoadConfig::quasi_static>,
       .help = "athermal quasi-static loading: each increment one affine step of the cell, then relaxed to "
               "increment_tolerance (needs dem.load.increment > 0); the inertial number then sets no rate"},
      {.key = "dem.load.increment_tolerance",
       .config = &member<&D::load, &LoadConfig::increment_tolerance>,
       .unit = units::none,
       .range = Range::open(0.0, 1.0),
       .help = "unbalanced-force ratio that ends the relaxation after each increment (OVAL: 0.01)"},
  };
  return table;
}

// A real, integer or choice member as a double (a choice as its word's index). The accessors
// serve the reader too, which writes through them, so they see a copy here.
double member_value(const Parameter& parameter, DemConfig readable) {
  return std::visit(
      [&](auto access) -> double {
        using Access = decltype(access);
        if constexpr (std::is_same_v<Access, Real> || std::is_same_v<Access, Integer>) {
          return static_cast<double>(access(readable));
        } else if constexpr (std::is_same_v<Access, Choice>) {
          return static_cast<double>(access.get(readable));
        } else {
          check_invariant(false, "a stored parameter is a real, an integer or a choice");
          return 0.0;
        }
      },
      parameter.config);
}

void set_member_value(const Parameter& parameter, DemConfig& config, double value) {
  std::visit(
      [&](auto access) {
        using Access = decltype(access);
        if constexpr (std::is_same_v<Access, Real>) {
          access(config) = value;
        } else if constexpr (std::is_same_v<Access, Integer>) {
          access(config) = static_cast<std::int64_t>(value);
        } else if constexpr (std::is_same_v<Access, Choice>) {
          access.set(config, static_cast<int>(value));
        }
      },
      parameter.config);
}

// The unit conversions between the member, its key and its attribute.
double stored_from_member(const Parameter& parameter, double member, const DemConfig& config) {
  return parameter.stored_as ? parameter.stored_as->from_config(member, config) : member;
}
double member_from_stored(const Parameter& parameter, double stored, const DemConfig& config) {
  return parameter.stored_as ? parameter.stored_as->to_config(stored, config) : stored;
}
double key_from_member(const Parameter& parameter, double member) {
  return parameter.key_unit ? member * parameter.key_unit->scale / parameter.key_unit->divisor : member;
}
double member_from_key(const Parameter& parameter, double key) {
  return parameter.key_unit ? key * parameter.key_unit->divisor / parameter.key_unit->scale : key;
}

std::string shown(const Parameter& parameter, double value_in_key_unit) {
  if (!parameter.words.empty()) return parameter.words.at(static_cast<std::size_t>(value_in_key_unit));
  const bool unitless = parameter.unit.empty() || parameter.unit == units::none;
  return fmt::format("{:g}{}", value_in_key_unit,
                     unitless ? std::string() : fmt::format(" {}", parameter.unit));
}

std::string toml_value(const Parameter& parameter, double value_in_key_unit) {
  if (!parameter.words.empty())
    return fmt::format("\"{}\"", parameter.words.at(static_cast<std::size_t>(value_in_key_unit)));
  if (std::holds_alternative<Integer>(parameter.config))
    return fmt::format("{}", static_cast<std::int64_t>(value_in_key_unit));
  return fmt::format("{}", value_in_key_unit);
}

void read_parameter(const Parameter& parameter, config::Reader& reader, DemConfig& config) {
  std::visit(
      [&](auto access) {
        using Access = decltype(access);
        if constexpr (std::is_same_v<Access, Real>) {
          double& value = access(config);
          if (parameter.key_unit) {
            const KeyUnit& unit = *parameter.key_unit;
            value = reader.real(parameter.key, value * unit.scale / unit.divisor, parameter.unit,
                                parameter.range, parameter.help) *
                    unit.divisor / unit.scale;
          } else {
            value = reader.real(parameter.key, value, parameter.unit, parameter.range, parameter.help);
          }
        } else if constexpr (std::is_same_v<Access, Integer>) {
          std::int64_t& value = access(config);
          value = reader.integer(parameter.key, value, parameter.range, parameter.help);
        } else if constexpr (std::is_same_v<Access, Seed>) {
          std::uint64_t& value = access(config);
          value = static_cast<std::uint64_t>(reader.integer(parameter.key, static_cast<std::int64_t>(value),
                                                            parameter.range, parameter.help));
        } else if constexpr (std::is_same_v<Access, Boolean>) {
          bool& value = access(config);
          value = reader.boolean(parameter.key, value, parameter.help);
        } else if constexpr (std::is_same_v<Access, Text>) {
          std::string& value = access(config);
          value = reader.text(parameter.key, value, parameter.help);
        } else if constexpr (std::is_same_v<Access, Reals>) {
          std::vector<double>& value = access(config);
          value = reader.reals(parameter.key, value, parameter.unit, parameter.range, parameter.min_count,
                               parameter.help);
        } else if constexpr (std::is_same_v<Access, Choice>) {
          const std::string word =
              reader.choice(parameter.key, parameter.words.at(static_cast<std::size_t>(access.get(config))),
                            parameter.words, parameter.help);
          access.set(config,
                     static_cast<int>(std::find(parameter.words.begin(), parameter.words.end(), word) -
                                      parameter.words.begin()));
        }
      },
      parameter.config);
}

// The checks of keys against each other, after every key is read.
void check_consistency(const DemConfig& c) {
  const auto& p = c.particles;
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
  require_input(c.prepare.cell_aspect.size() == 3,
                fmt::format("config key 'dem.prepare.cell_aspect': {} values given, expected exactly 3",
                            c.prepare.cell_aspect.size()));
  require_input(c.prepare.seize_stress < c.prepare.confining_pressure,
                "config: dem.prepare.seize_stress must be below dem.prepare.confining_pressure");
  require_input(
      !c.load.quasi_static || c.load.increment > 0,
      "config: dem.load.quasi_static needs dem.load.increment > 0 (the strain of each affine step)");
  require_input(!c.equilibrium.fork_checkpoints || c.equilibrium.at_checkpoints,
                "config: dem.equilibrium.fork_checkpoints needs dem.equilibrium.at_checkpoints = true (it "
                "says how the checkpoints are relaxed, not whether)");
  // load_NNN.h5 is numbered in list order and the loading passes each strain once.
  const auto& l = c.load;
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
}

bool differs(double configured, double stored) {
  return std::abs(configured - stored) > 1e-9 * std::max(std::abs(configured), std::abs(stored));
}

} // namespace

DemConfig read_dem_config(config::Reader& reader) {
  DemConfig config;
  // The behaviour first: it sets the defaults of the keys it names, which are read after it.
  const auto is_behaviour = [](const Parameter& parameter) { return parameter.key == "dem.load.behaviour"; };
  const auto& table = parameters();
  const auto behaviour = std::find_if(table.begin(), table.end(), is_behaviour);
  read_parameter(*behaviour, reader, config);
  apply_load_behaviour(config.load.behaviour, config);
  for (const Parameter& parameter : table)
    if (!parameter.key.empty() && !is_behaviour(parameter)) read_parameter(parameter, reader, config);
  check_consistency(config);
  return config;
}

SimulationSettings settings_from_config(const DemConfig& config, double smallest_diameter) {
  SimulationSettings settings;
  for (const Parameter& parameter : parameters())
    if (parameter.set != nullptr && !parameter.key.empty())
      parameter.set(settings, stored_from_member(parameter, member_value(parameter, config), config));
  const double critical = model::rayleigh_time_step(
      model::volume_equivalent_radius(0.5 * smallest_diameter, config.particles.aspect_ratio,
                                      settings.splice_angle),
      settings.density, settings.material);
  settings.time_step = config.integration.time_step > 0 ? config.integration.time_step
                                                        : config.integration.time_step_fraction * critical;
  model::require_stable_time_step(settings.time_step, critical);
  return settings;
}

std::vector<h5::Parameter> stored_parameters(const SimulationSettings& settings) {
  std::vector<h5::Parameter> stored;
  for (const Parameter& parameter : parameters()) {
    if (parameter.attribute.empty()) continue;
    const std::string_view unit = parameter.stored_unit.empty() ? parameter.unit : parameter.stored_unit;
    stored.push_back({std::string(parameter.attribute), parameter.get(settings), std::string(unit)});
  }
  return stored;
}

SimulationSettings settings_from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path) {
  SimulationSettings settings;
  for (const Parameter& parameter : parameters()) {
    if (parameter.attribute.empty()) continue;
    const std::string attribute(parameter.attribute);
    const double value = parameter.absent && !h5::has_parameter(checkpoint, attribute)
                             ? *parameter.absent
                             : h5::parameter(checkpoint, attribute, path);
    const Range range = parameter.stored_range.value_or(parameter.range);
    if (!range.contains(value)) {
      throw FileError(fmt::format("{}: /parameters (attribute '{}'): value {:g} is out of range, expected {}",
                                  path, parameter.attribute, value, range.describe()));
    }
    parameter.set(settings, value);
  }
  if (!(checkpoint.time_step > 0.0))
    throw FileError(
        fmt::format("{}: / (attribute time_step): value {:g}, expected > 0", path, checkpoint.time_step));
  settings.time_step = checkpoint.time_step;
  return settings;
}

void adopt_checkpoint_values(DemConfig& config, config::Reader& reader, const h5::Checkpoint& checkpoint,
                             const std::string& path) {
  const SimulationSettings stored = settings_from_checkpoint(checkpoint, path);
  std::string mismatches;
  // The stored value replaces the configured one; a configured one that differs is listed.
  const auto adopt = [&](std::string_view key, bool same, const std::string& mismatch, std::string value_toml,
                         std::string_view note) {
    if (reader.given(key) && !same) mismatches += fmt::format("\n  {} = {}", key, mismatch);
    reader.replace(key, std::move(value_toml), note);
  };
  constexpr std::string_view from_file = "from the input checkpoint";
  // What the particle rows fix: their count and extreme sizes, and one aspect ratio for all
  // (the whole file's, whichever rows this rank read).
  const h5::RowTotals& rows = checkpoint.totals;
  auto& pc = config.particles;
  const auto n_rows = static_cast<std::int64_t>(rows.particles);
  adopt("dem.particles.count", pc.count == n_rows,
        fmt::format("{}, the checkpoint has {} particles", pc.count, n_rows), std::to_string(n_rows),
        from_file);
  pc.count = n_rows;
  // A size bound is kept when every stored diameter lies within it.
  const double smallest = rows.diameter_min, largest = rows.diameter_max;
  adopt("dem.particles.diameter_min", smallest >= pc.diameter_min * (1 - 1e-9),
        fmt::format("{:g} m, the checkpoint's diameters reach {:g} m", pc.diameter_min, smallest),
        fmt::format("{}", smallest), "from the input checkpoint (its extreme diameter)");
  pc.diameter_min = smallest;
  adopt("dem.particles.diameter_max", largest <= pc.diameter_max * (1 + 1e-9),
        fmt::format("{:g} m, the checkpoint's diameters reach {:g} m", pc.diameter_max, largest),
        fmt::format("{}", largest), "from the input checkpoint (its extreme diameter)");
  pc.diameter_max = largest;
  // One aspect ratio for every particle is what prepare makes; a mixed file has no single value.
  const double flattest = rows.aspect_ratio_min, roundest = rows.aspect_ratio_max;
  if (flattest == roundest) {
    adopt("dem.particles.aspect_ratio", !(std::abs(pc.aspect_ratio - flattest) > 1e-9 * flattest),
          fmt::format("{:g}, the checkpoint has {:g}", pc.aspect_ratio, flattest),
          fmt::format("{}", flattest), from_file);
    pc.aspect_ratio = flattest;
  }
  // What the stored settings fix, in table order (d50 before the skin it scales), compared in
  // the key's unit to 1e-9.
  for (const Parameter& parameter : parameters()) {
    if (parameter.binding != Binding::fixed) continue;
    const double stored_key =
        key_from_member(parameter, member_from_stored(parameter, parameter.get(stored), config));
    const double configured_key = key_from_member(parameter, member_value(parameter, config));
    adopt(parameter.key, !(std::abs(configured_key - stored_key) > 1e-9 * std::abs(stored_key)),
          fmt::format("{}, the checkpoint has {}", shown(parameter, configured_key),
                      shown(parameter, stored_key)),
          toml_value(parameter, stored_key), from_file);
    set_member_value(parameter, config, member_from_key(parameter, stored_key));
  }
  require_input(
      mismatches.empty(),
      fmt::format("the configuration gives keys that the input checkpoint '{}' fixes (its particles "
                  "and their material), with other values:{}\nA run from a checkpoint uses the "
                  "file's values: remove these keys, or prepare a new assembly with them",
                  path, mismatches));
}

config::Range key_range(std::string_view key) {
  for (const Parameter& parameter : parameters())
    if (parameter.key == key) return parameter.range;
  check_invariant(false, "key_range: the key is in the parameter table");
  return {};
}

double configured_time_step(const DemConfig& config, double critical_time_step) {
  return config.integration.time_step > 0 ? config.integration.time_step
                                          : config.integration.time_step_fraction * critical_time_step;
}

void require_resume_matches(const DemConfig& config, const SimulationSettings& stored,
                            const model::CellControl& control, double critical_time_step) {
  std::string mismatches;
  const auto& pc = config.particles;
  const double rate = strain_rate_for_inertial_number(config.load.inertial_number, pc.d50, pc.density,
                                                      config.load.mean_stress);
  const double stored_rate = -control.target[0];
  if (differs(rate, stored_rate))
    mismatches +=
        fmt::format("\n  dem.load.inertial_number = {:.6g}, the checkpoint's loading has {:.6g} (strain "
                    "rate {:.6g} /s)",
                    config.load.inertial_number,
                    inertial_number(stored_rate, pc.d50, pc.density, config.load.mean_stress), stored_rate);
  if (differs(config.load.mean_stress, control.mean_stress_target))
    mismatches += fmt::format("\n  dem.load.mean_stress = {:.6g}, the checkpoint's loading has {:.6g} Pa",
                              config.load.mean_stress, control.mean_stress_target);
  for (const Parameter& parameter : parameters()) {
    if (parameter.binding != Binding::resumed) continue;
    const double configured = stored_from_member(parameter, member_value(parameter, config), config);
    const double kept = parameter.get(stored);
    if (differs(configured, kept))
      mismatches += fmt::format("\n  {} = {:.6g}, the checkpoint's loading has {:.6g}", parameter.key,
                                configured, kept);
  }
  const double time_step = configured_time_step(config, critical_time_step);
  if (differs(time_step, stored.time_step)) {
    const bool explicit_step = config.integration.time_step > 0;
    // Full precision, so that the stored step can be given back with --set to resume.
    mismatches += fmt::format(
        "\n  {} = {:.6g}, the checkpoint's loading has a time step of {:.17g} s ({:.6g} of critical)",
        explicit_step ? "dem.integration.time_step" : "dem.integration.time_step_fraction",
        explicit_step ? config.integration.time_step : config.integration.time_step_fraction,
        stored.time_step, stored.time_step / critical_time_step);
  }
  require_input(mismatches.empty(),
                fmt::format("load --resume: the configuration differs from the loading it would continue "
                            "(a resumed run keeps the stored settings, so these would be ignored):{}\n"
                            "Resume with the original settings, or start a new loading from the checkpoint "
                            "without --resume.",
                            mismatches));
}

} // namespace aniso::dem::io
