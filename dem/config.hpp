#pragma once
// Typed configuration of aniso-dem, read from the [dem] table. Every key has a
// unit, a default from the paper (section "DEM Simulations") and an allowed
// range; docs/methods/dem.md lists them.

#include "common/config.hpp"
#include "dem/model/ovoid_contact.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::dem {

struct ParticleConfig {
  std::int64_t count = 1000;
  double diameter_min = 0.075e-3;           ///< [m]
  double diameter_max = 0.28e-3;            ///< [m]
  double d50 = 0.17e-3;                     ///< median diameter by volume [m]
  double aspect_ratio = 1.0;                ///< 1 = sphere, < 1 oblate ovoid
  double splice_angle = 0.7853981633974483; ///< ovoid splice angle beta [rad] (Kuhn's OVAL: 45 degrees)
  double density = 2650.0;                  ///< [kg/m^3]
};

struct MaterialConfig {
  double shear_modulus = 29e9;   ///< G [Pa]
  double poisson_ratio = 0.15;   ///< nu
  double friction = 0.5;         ///< mu during consolidation and loading
  double friction_prepare = 0.3; ///< mu during compaction cycles
  model::HertzRadius hertz_radius = model::HertzRadius::halfwidth;
};

struct IntegrationConfig {
  double time_step_fraction =
      0.5; ///< of the Rayleigh critical step of the smallest particle (docs/methods/dem.md, "Time step")
  double time_step = 0.0;      ///< explicit step [s]; 0 = from the fraction; refused above critical
  double damping = 0.05;       ///< viscous contact damping ratio during loading (see docs/methods/dem.md)
  double global_damping = 0.0; ///< global damping of the fluctuating motion during loading, of critical
  /// The global damping rate of the spin as a multiple of that of the translation (1: the same rate).
  double global_damping_spin_factor = 1.0;
  double skin = 0.1; ///< neighbour-list skin in units of D50
  std::int64_t control_interval =
      4; ///< steps between stress measurements and servo updates (2 t_R at the default step)
  double servo_gain = 0.2;         ///< fraction of the stress error removed per servo update
  double explosion_overlap = 0.05; ///< stop when an overlap exceeds this fraction of the smaller radius
};

struct PrepareConfig {
  std::vector<double> cell_aspect{1.5, 1.0, 1.0}; ///< L1:L2:L3 of the cell
  double initial_solid_fraction = 0.25;           ///< sparse random arrangement
  std::int64_t cycles = 14;                       ///< compaction cycles
  double target_void_ratio = 0.556;               ///< keep the cycle nearest this
  double void_ratio_tolerance = 0.003;            ///< a prepared e further than this from the target fails
  double confining_pressure = 100e3;              ///< p0 [Pa]
  double inertial_number = 1e-2;                  ///< compaction and consolidation rate, I at p0
  double damping = 0.3;                           ///< contact damping ratio while compacting
  double global_damping = 0.0;                    ///< global damping ratio while compacting
  double global_damping_spin_factor = 1.0; ///< its rate for the spin, as a multiple of the translation's
  double seize_stress = 1e3;               ///< p at which a compacting assembly counts as seized [Pa]
  double seize_force_ratio = 1e-2;         ///< unbalanced-force ratio a held, seized assembly is below
  double agitation_speed = 0.1;            ///< rms random speed between cycles, in units of sqrt(p0/rho)
  double consolidation_tolerance = 0.005;  ///< |p - p0| / p0 at the end of consolidation
  std::int64_t refinement_cycles = 6;      ///< most re-runs of a cycle with a weaker agitation
  /// > 0: one compaction, ended when e falls to this (or at seizure, if earlier), then consolidated
  /// with the loading's friction: an assembly made at friction_prepare up to a chosen density
  double compaction_stop_void_ratio = 0.0;
};

/// dem.load.behaviour: a named set of defaults for how the sheared assembly dissipates and how its
/// checkpoints are made static (dem/load_behaviour.hpp; docs/methods/dem.md, "Loading behaviours").
enum class LoadBehaviour : std::uint8_t {
  inertial = 0, ///< continuous loading, contact damping on sticking contacts only: the engine's defaults
  oval = 1,     ///< DEMPLA/OVAL's damped loading (body damping of translation and spin), forked checkpoints
  quasi_static = 2, ///< affine increments, each minimised to a static state
};

struct LoadConfig {
  LoadBehaviour behaviour = LoadBehaviour::inertial; ///< sets the defaults of the keys it names
  double inertial_number = 1e-3;                     ///< sets the strain rate: I = rate D50 sqrt(rho / p)
  double final_strain = 0.2;                         ///< compressive eps11 magnitude at the end
  double mean_stress = 100e3;                        ///< p held constant [Pa]
  std::vector<double> checkpoint_strains;            ///< compressive strains at which to write checkpoints
  double history_interval = 1e-4;                    ///< strain between history rows
  double increment = 0;              ///< strain per increment, each followed by a relaxation (0: none)
  double increment_tolerance = 1e-2; ///< unbalanced-force ratio that ends an increment's relaxation
  /// Athermal quasi-static loading: each increment is one affine step of the cell, then minimised
  /// to increment_tolerance; the path depends on the increment size alone, not on a rate.
  bool quasi_static = false;
};

/// How a relaxation reaches a static state (docs/decisions.md, entry 11).
enum class Relaxer : std::uint8_t {
  damped = 0, ///< global viscous damping of the fluctuating motion, ratio `damping`
  fire = 1,   ///< the FIRE minimiser on the fluctuating motion (dem/protocol/fire.hpp)
};

/// Static equilibrium: of the prepared assembly, of every load checkpoint, of `hold`.
struct EquilibriumConfig {
  double tolerance = 1e-4;           ///< unbalanced-force ratio at which a state counts as static
  double stress_tolerance = 1e-3;    ///< |p - p_target| / p_target at the same time
  Relaxer method = Relaxer::fire;    ///< how the relaxations reach it
  double damping = 0.1;              ///< global damping ratio while relaxing (Relaxer::damped)
  double fire_time_step_factor = 1;  ///< largest FIRE time step, in the run's steps
  std::int64_t verify_steps = 20000; ///< the tolerances must then hold this long without extra damping
  /// A window also fails when the kinetic/elastic ratio grows this many times above its lowest
  /// value in the window (no lower than kinetic_floor): an unstable balance (0: not checked, the
  /// default; docs/methods/dem.md, "Static equilibrium").
  double kinetic_growth = 0;
  double kinetic_floor = 1e-8; ///< kinetic/elastic ratio below which its growth does not count
  /// After a window failed on the kinetic growth, time steps of the run's own dynamics with the
  /// servo on, so that the unstable balance falls to another before minimising again.
  std::int64_t escape_steps = 20000;
  /// After this many verification windows left, the relaxation ends unverified at the state the
  /// last window began from (balanced, held for fewer steps; 0: never, it runs to max_steps).
  std::int64_t max_windows = 0;
  double margin = 0.01;            ///< a verified relaxation first reaches this fraction of the tolerances
  std::int64_t max_steps = 500000; ///< a relaxation that needs more stops with exit 5
  bool at_checkpoints = true;      ///< relax before writing each load checkpoint
  /// Relax a copy of the loading state for each checkpoint and go on loading from the state
  /// itself: the path is that of a loading without relaxations, every checkpoint static.
  bool fork_checkpoints = false;
};

struct DemConfig {
  std::uint64_t seed = 1;
  std::string output_dir = ".";
  ParticleConfig particles;
  MaterialConfig material;
  IntegrationConfig integration;
  PrepareConfig prepare;
  LoadConfig load;
  EquilibriumConfig equilibrium;
};

} // namespace aniso::dem
