#pragma once
// One DEM run: the periodic cell, the particles, the contact list and the cell
// controller, advanced one velocity-Verlet step at a time. step() is the
// whole algorithm in order; read it first. The protocols (dem/protocol/) drive
// it through a Phase: a control state, the dynamics of the phase, a step budget.

#include "common/cell.hpp"
#include "common/timer.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/equilibrium.hpp"
#include "dem/force_pass.hpp"
#include "dem/measures.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/model/contact_law.hpp"
#include "dem/model/ovoid_contact.hpp"
#include "dem/model/particle_shape.hpp"
#include "dem/parallel/domain.hpp"
#include "dem/parallel/halo.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace aniso::dem {

/// What the engine runs with. The material, shape and neighbour-list members are fixed for an
/// assembly; the protocols change the others between phases (reconfigure()).
struct SimulationSettings {
  model::ContactMaterial material; ///< G and nu fixed; friction and contact damping per phase
  double density = 2650;           ///< [kg/m^3]
  double d50 = 0;       ///< median diameter by volume [m]: the length of the assembly's inertial numbers
  double time_step = 0; ///< [s]; checked against the Rayleigh step
  double skin = 0;      ///< neighbour-list skin [m]
  std::int64_t control_interval = 10; ///< steps between stress measurements and servo updates
  model::ServoSettings servo;
  /// Global damping of the fluctuating motion as a fraction of critical for the mean
  /// particle on the mean contact stiffness: gamma = 2 ratio sqrt(k_n / m) (docs/methods/dem.md).
  double global_damping = 0;
  /// The spin's damping rate as a multiple of gamma. DEMPLA's samples give every grain five times
  /// a solid sphere's moment of inertia and damp spin on it, about 6 times aniso's torque at
  /// factor 1: a rolling resistance in effect (docs/validation.md, "DEM against DEMPLA").
  double global_damping_spin_factor = 1;
  double explosion_overlap = 0.05; ///< stop when an overlap exceeds this fraction of the smaller radius
  double splice_angle = 0.7853981633974483; ///< ovoid splice angle beta [rad], assembly-wide
  model::HertzRadius hertz_radius = model::HertzRadius::halfwidth;
};

/// Where a restarted run continues: its clock, the contacts as stored, the damping rate.
struct RestartState {
  double time = 0;       ///< [s]
  std::int64_t step = 0; ///< steps taken
  std::vector<StoredContact> contacts;
  double global_damping_rate = 0; ///< [1/s], as it was at the stored step
  std::string source;             ///< names the stored state in messages ("checkpoint 'path'")
  /// False: every rank holds every particle and every contact. True: each rank holds its share
  /// of each (a distributed read, h5::RowShare::slab), each particle on exactly one rank.
  bool dealt = false;
};

class Simulation {
public:
  /// A fresh start from every particle (the same set on every rank) at rest in `cell`:
  /// decomposes the cell over `comm`, keeps this rank's particles, builds the contact list and
  /// computes the forces (collective).
  Simulation(data::Particles particles, const PeriodicCell& cell, const model::CellControl& control,
             const SimulationSettings& settings, const mpi::Comm& comm);
  /// A restart that continues exactly where a stored state left off: the particles with their
  /// stored forces, the contacts' records and histories rebuilt by the force pass's own arithmetic
  /// (force_pass.hpp, restore_contact_records), the stress and equilibrium measured from them
  /// (collective). FileError naming `restart.source` when the contacts disagree with the positions.
  /// `particles` are all particles on every rank, or with `restart.dealt` this rank's share.
  Simulation(data::Particles particles, const PeriodicCell& cell, const model::CellControl& control,
             const SimulationSettings& settings, const RestartState& restart, const mpi::Comm& comm);

  /// One velocity-Verlet step: half kick, drift and cell strain, contact list refresh if
  /// needed, forces, half kick, and every control_interval steps a stress measurement and servo update.
  void step();
  /// True when the last step ended with a control update (stress and servo fresh).
  [[nodiscard]] bool at_control_update() const { return step_ % settings_.control_interval == 0; }

  /// Changes the controller (modes, targets) from the next step on; rates are recomputed now
  /// from the present stress (collective).
  void set_control(const model::CellControl& control);
  /// Changes what a protocol may change between phases (friction, contact and global damping,
  /// time step, control interval, servo gain and cap); the material, shape and list settings must
  /// stay. Refuses a time step above the critical one; sets the global damping's rate from the
  /// present contacts (collective).
  void reconfigure(const SimulationSettings& settings);
  /// Measures the equilibrium at every control update from now on (and now, collectively), or not.
  void watch_equilibrium(bool on);
  /// Makes the current lengths the zero-strain reference.
  void reset_reference_lengths() { cell_ = PeriodicCell(cell_.lengths()); }
  /// Puts back a control, settings and equilibrium watching by assignment alone, measuring
  /// nothing and calling no collective: what a phase that an exception leaves does
  /// (protocol/phase.hpp), so that a failure seen on one rank cannot hang the others.
  void put_back(const model::CellControl& control, const SimulationSettings& settings, bool watch) {
    control_ = control;
    settings_ = settings;
    watch_equilibrium_ = watch;
  }
  /// Measures the stress and equilibrium of the present forces now, between control updates
  /// (collective).
  void measure_stress_now();

  [[nodiscard]] StateMeasures measure() const;
  [[nodiscard]] const mpi::Comm& comm() const { return domain_.comm(); }
  [[nodiscard]] const parallel::Domain& domain() const { return domain_; }
  [[nodiscard]] const parallel::Halo& ghost_halo() const { return halo_; }
  /// Number of particles on all ranks.
  [[nodiscard]] std::int64_t n_particles() const { return n_particles_; }
  [[nodiscard]] const Mat3& stress() const { return stress_; } ///< at the last control update
  [[nodiscard]] double servo_error() const;
  [[nodiscard]] const data::Particles& particles() const { return particles_; }
  [[nodiscard]] data::Particles& particles() { return particles_; }
  [[nodiscard]] const PeriodicCell& cell() const { return cell_; }
  [[nodiscard]] const data::NeighborList& neighbors() const { return neighbors_; }
  [[nodiscard]] const model::CellControl& control() const { return control_; }
  [[nodiscard]] const SimulationSettings& settings() const { return settings_; }
  /// Rayleigh critical time step of the smallest particle on any rank (collective).
  [[nodiscard]] double critical_time_step() const;
  /// Rate gamma of the global damping [1/s], set at every control update.
  [[nodiscard]] double global_damping_rate() const { return damping_rate_; }
  /// Equilibrium measures at the last control update that measured them: every update while
  /// watched or while the global damping is on (its rate needs them), else only at
  /// construction, measure_stress_now() and watch_equilibrium(true). They cost about 9% of a
  /// loading step when measured at every update, so loading does without them.
  [[nodiscard]] const Equilibrium& equilibrium() const { return equilibrium_; }
  [[nodiscard]] bool watching_equilibrium() const { return watch_equilibrium_; }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::int64_t step_count() const { return step_; }
  [[nodiscard]] double solid_volume() const { return solid_volume_; }
  /// The shapes of this assembly's particles.
  [[nodiscard]] const model::ShapeTable& shapes() const { return shapes_; }
  /// Overlap of particles i and j (local indices) at the present positions, by the force pass's
  /// narrow phase (< 0: apart); guess is the normal an ovoid pair's iteration starts from.
  [[nodiscard]] double geometric_overlap(std::uint32_t i, std::uint32_t j, const Vec3& guess) const;

  /// The sections of a step's wall time (times()), and their names in the timing table.
  enum Section : std::size_t { integration, list_update, halo, force_pass, control_update, n_sections };
  static std::vector<std::string> section_names() {
    return {"integration", "list update", "halo", "force pass", "control update"};
  }
  /// Wall time of this rank's steps by section, since construction; a copy of a simulation
  /// (prepare's compaction cycles) adds to the same record.
  [[nodiscard]] const SectionTimes& times() const { return *times_; }

private:
  Simulation(data::Particles particles, const PeriodicCell& cell, const model::CellControl& control,
             const SimulationSettings& settings, double time, std::int64_t step, bool dealt,
             const mpi::Comm& comm);
  /// The force pass; with `measure`, it also fills contact_sums_ for the control update that follows.
  void compute_forces(bool measure = false);
  [[nodiscard]] ContactInput contact_input() const { return {&shapes_, settings_.hertz_radius}; }
  void update_control();
  void update_equilibrium();
  /// Whether a control update measures the equilibrium (it is watched, or the global damping needs
  /// the contact stiffness).
  [[nodiscard]] bool measures_equilibrium() const {
    return watch_equilibrium_ || settings_.global_damping > 0;
  }
  void update_damping_rate();
  void rebuild_decomposition();

  data::Particles particles_;
  model::ShapeTable shapes_;
  std::vector<model::ConvexBody> bodies_; ///< scratch of the force pass: world-frame bodies
  PeriodicCell cell_;
  model::CellControl control_;
  SimulationSettings settings_;
  data::NeighborList neighbors_;
  parallel::Domain domain_;
  parallel::Halo halo_;
  double reach_ = 0; ///< largest interaction range, 2 R_max + skin
  std::int64_t n_particles_ = 0;
  Mat3 stress_ = Mat3::Zero();
  double time_ = 0;
  std::int64_t step_ = 0;
  double solid_volume_ = 0;
  double mean_mass_ = 0;    ///< over all particles [kg]
  double damping_rate_ = 0; ///< gamma of the global damping [1/s]
  Equilibrium equilibrium_;
  bool watch_equilibrium_ = false;
  data::ContactSums contact_sums_;      ///< this rank's contact sums of the last measuring force pass
  std::int64_t contact_sums_step_ = -1; ///< the step whose forces they sum (-1: none)
  std::shared_ptr<SectionTimes> times_ = std::make_shared<SectionTimes>(section_names());
};

} // namespace aniso::dem
