#pragma once
// One DEM run: the periodic cell, the particles, the contact list and the cell
// controller, advanced one velocity-Verlet step at a time. step() is the
// whole algorithm in order; read it first.

#include "common/cell.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"
#include "dem/data/neighbors.hpp"
#include "dem/data/particles.hpp"
#include "dem/equilibrium.hpp"
#include "dem/force_pass.hpp"
#include "dem/measures.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/model/contact_law.hpp"
#include "dem/model/particle_shape.hpp"
#include "dem/parallel/domain.hpp"
#include "dem/parallel/halo.hpp"

#include <cstdint>
#include <string>

namespace aniso::dem {

struct SimulationSettings {
  model::ContactMaterial material;
  double density = 2650;              ///< [kg/m^3]
  double time_step = 0;               ///< [s]; checked against the Rayleigh step
  double skin = 0;                    ///< neighbour-list skin [m]
  std::int64_t control_interval = 10; ///< steps between stress measurements and servo updates
  model::ServoSettings servo;
  /// Global damping of the fluctuating motion as a fraction of critical for the mean
  /// particle on the mean contact stiffness: gamma = 2 ratio sqrt(k_n / m) (docs/methods/dem.md).
  double global_damping = 0;
  double explosion_overlap = 0.05; ///< stop when an overlap exceeds this fraction of the smaller radius
  double splice_angle = 0.7853981633974483; ///< ovoid splice angle beta [rad], assembly-wide
  model::HertzRadius hertz_radius = model::HertzRadius::halfwidth;
};

class Simulation {
public:
  /// Takes every particle (the same set on every rank, with forces as stored, or zero) and the
  /// cell state; decomposes the cell over `comm`, keeps this rank's particles and builds the
  /// contact list (collective). If `forces_valid` is false the initial forces are computed here;
  /// if true (a restart) the caller then calls restore_contacts() and restore_stress().
  Simulation(data::Particles particles, const h5::CellState& control, const SimulationSettings& settings,
             double time, std::int64_t step, bool forces_valid, const mpi::Comm& comm);

  /// One velocity-Verlet step: half kick, drift and cell strain, contact list refresh if
  /// needed, forces, half kick, and every control_interval steps a stress measurement and servo update.
  void step();

  [[nodiscard]] StateMeasures measure() const;
  /// Restores contact history and per-pair records of the pairs this rank holds (after a restart).
  void restore_contacts(const h5::ContactRows& contacts, const std::string& path);
  /// Overlap of particles i and j (local indices) at the present positions, by the force pass's
  /// narrow phase (< 0: apart); guess is the normal an ovoid pair's iteration starts from.
  [[nodiscard]] double geometric_overlap(std::uint32_t i, std::uint32_t j, const Vec3& guess) const;
  /// Recomputes the stress from restored contact records (after a restart; collective).
  void restore_stress();
  [[nodiscard]] const mpi::Comm& comm() const { return domain_.comm(); }
  [[nodiscard]] const parallel::Domain& domain() const { return domain_; }
  /// Number of particles on all ranks.
  [[nodiscard]] std::int64_t n_particles() const { return n_particles_; }
  [[nodiscard]] const Mat3& stress() const { return stress_; } ///< at the last control update
  [[nodiscard]] double servo_error() const;

  [[nodiscard]] const data::Particles& particles() const { return particles_; }
  [[nodiscard]] data::Particles& particles() { return particles_; }
  [[nodiscard]] const PeriodicCell& cell() const { return cell_; }
  [[nodiscard]] const data::NeighborList& neighbors() const { return neighbors_; }
  [[nodiscard]] data::NeighborList& neighbors() { return neighbors_; }
  [[nodiscard]] const h5::CellState& control() const { return control_; }
  /// Changes the controller (mode, targets) from the next step on; rates are recomputed now.
  void set_control(const h5::CellState& control);
  [[nodiscard]] const SimulationSettings& settings() const { return settings_; }
  /// Changes the friction coefficient (preparation uses a lower one).
  void set_friction(double friction) { settings_.material.friction = friction; }
  /// Changes the contact damping ratio.
  void set_damping(double ratio) { settings_.material.damping_ratio = ratio; }
  /// Rayleigh critical time step of the smallest particle on any rank (collective).
  [[nodiscard]] double critical_time_step() const;
  /// Changes the time step from the next step on; refused above the critical step (collective).
  void set_time_step(double time_step);
  /// Changes the global damping ratio and sets its rate from the present contacts (collective).
  void set_global_damping(double ratio);
  /// Rate gamma of the global damping [1/s], set at every control update.
  [[nodiscard]] double global_damping_rate() const { return damping_rate_; }
  /// Restores the damping rate of a checkpoint (exact restarts).
  void restore_global_damping_rate(double rate) { damping_rate_ = rate; }
  /// Equilibrium measures at the last control update that measured them: every update while
  /// watched or while the global damping is on (its rate needs them), else only at
  /// construction, restore_stress() and watch_equilibrium(true). They cost about 9% of a
  /// loading step when measured at every update, so loading does without them.
  [[nodiscard]] const Equilibrium& equilibrium() const { return equilibrium_; }
  /// Measures the equilibrium at every control update from now on (and now, collectively), or not.
  void watch_equilibrium(bool on);
  [[nodiscard]] bool watching_equilibrium() const { return watch_equilibrium_; }
  /// Makes the current lengths the zero-strain reference.
  void reset_reference_lengths() { cell_ = PeriodicCell(cell_.lengths()); }
  /// Caps the servo's strain rate [1/s].
  void set_servo_max_rate(double rate) { settings_.servo.max_rate = rate; }
  /// Changes the steps between stress measurements and servo updates, and the servo gain.
  void set_control_interval(std::int64_t steps, double servo_gain) {
    settings_.control_interval = steps;
    settings_.servo.gain = servo_gain;
  }
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] std::int64_t step_count() const { return step_; }
  [[nodiscard]] double solid_volume() const { return solid_volume_; }
  /// Captures the cell state (lengths, rates, controller) for a checkpoint.
  [[nodiscard]] h5::CellState cell_state() const;

  /// The shapes of this assembly's particles.
  [[nodiscard]] const model::ShapeTable& shapes() const { return shapes_; }
  [[nodiscard]] ContactInput contact_input() const { return {&shapes_, settings_.hertz_radius}; }

private:
  /// The force pass; with `measure`, it also fills contact_sums_ for the control update that follows.
  void compute_forces(bool measure = false);
  [[nodiscard]] double restored_hertz_radius(std::uint32_t i, std::uint32_t j,
                                             const data::ContactRecord& record) const;
  void update_control();
  void update_equilibrium();
  void update_damping_rate();
  void rebuild_decomposition();

  data::Particles particles_;
  model::ShapeTable shapes_;
  std::vector<model::ConvexBody> bodies_; ///< scratch of the force pass: world-frame bodies
  PeriodicCell cell_;
  h5::CellState control_;
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
};

} // namespace aniso::dem
