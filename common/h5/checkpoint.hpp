#pragma once
// The DEM checkpoint, schema version 1: everything needed to continue a run
// bit for bit (DESIGN.md "Data formats"). On disk the layout is documented in
// docs/formats/checkpoint.md. Particles are stored in id order (row = id) and
// contacts in (id_i, id_j) order, whatever the number of ranks that wrote them,
// so that files written by 1 or N ranks hold the same data.

#include "common/h5/file.hpp"
#include "common/h5/provenance.hpp"
#include "common/mpi.hpp"
#include "common/tensor.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace aniso::h5 {

inline constexpr std::int64_t checkpoint_schema_version = 1;

/// How one axis of the periodic cell is driven.
enum class AxisMode : std::uint8_t { strain_rate = 0, stress = 1 };

/// Cell geometry and the state of its controller.
struct CellState {
  Vec3 lengths = Vec3::Ones();           ///< current lengths [m]
  Vec3 reference_lengths = Vec3::Ones(); ///< lengths at zero strain [m]
  Vec3 strain_rate = Vec3::Zero();       ///< current rate dL/dt / L per axis [1/s]
  std::array<AxisMode, 3> mode{AxisMode::strain_rate, AxisMode::strain_rate, AxisMode::strain_rate};
  Vec3 target = Vec3::Zero(); ///< per axis: strain rate [1/s] (strain_rate mode) or stress [Pa] (stress mode)
  bool hold_mean_stress = false;   ///< stress-mode axes together hold p = mean_stress_target
  double mean_stress_target = 0;   ///< [Pa], compression positive
  Vec3 servo_state = Vec3::Zero(); ///< controller memory (integral terms) per axis
};

/// The /parameters that stages other than the DEM read, by name. The DEM's parameter table
/// (dem/io/parameters.cpp) declares every parameter a checkpoint stores, these among them.
namespace parameter_name {
inline constexpr const char* d50 = "d50";                         ///< median diameter by volume [m]
inline constexpr const char* density = "density";                 ///< solid density [kg/m^3]
inline constexpr const char* splice_angle = "ovoid_splice_angle"; ///< ovoid splice angle beta [rad]
} // namespace parameter_name

/// A named scalar parameter with its unit, stored as an attribute of /parameters.
struct Parameter {
  std::string name;
  double value = 0;
  std::string unit;
};

/// Particles held by this rank (structure of arrays; all vectors have the same length).
struct ParticleRows {
  std::vector<std::uint64_t> id;    ///< 0 .. N-1 over all ranks, each exactly once
  std::vector<double> diameter;     ///< mid-plane diameter [m]
  std::vector<double> aspect_ratio; ///< axial height / mid-plane diameter; 1 = sphere
  std::vector<double> mass;         ///< [kg]
  std::vector<Vec3> inertia;        ///< principal moments in the body frame, axis of revolution = z [kg m^2]
  std::vector<Vec3> position;       ///< [m], inside the cell
  std::vector<Quat> orientation;    ///< body to world rotation, unit quaternion (w, x, y, z on disk)
  std::vector<Vec3> velocity;       ///< [m/s]
  std::vector<Vec3> angular_velocity; ///< world frame [rad/s]
  std::vector<Vec3> force;            ///< total force at the stored step [N]
  std::vector<Vec3> torque;           ///< total torque at the stored step, world frame [N m]
  /// Optional (empty, or one per row): the id each particle had in the file it was imported
  /// from (`aniso-dem import`); /particles/source_id on disk. resize() leaves it alone.
  std::vector<std::uint64_t> source_id;

  [[nodiscard]] std::size_t size() const { return id.size(); }
  void resize(std::size_t n);
};

/// Contacts held by this rank, id_i < id_j; history included.
struct ContactRows {
  std::vector<std::array<std::uint64_t, 2>> particles; ///< (id_i, id_j), id_i < id_j
  std::vector<Vec3i> image_shift;                      ///< periodic image of j relative to i, in cell lengths
  std::vector<Vec3> normal;                            ///< unit normal pointing from i to j
  std::vector<Vec3> point;                             ///< contact point [m], wrapped into the cell
  std::vector<double> overlap;                         ///< normal overlap [m], > 0
  std::vector<Vec3> force;                             ///< force on i from j [N]
  std::vector<Vec3> tangential_force; ///< elastic tangential force on i (Mindlin history) [N]
  std::vector<std::uint8_t> sliding;  ///< 1 if at the Coulomb limit at the stored step

  [[nodiscard]] std::size_t size() const { return particles.size(); }
  void resize(std::size_t n);
};

/// Which rows read_checkpoint gives each rank.
enum class RowShare {
  all,  ///< every row on every rank: the stages that measure the whole assembly
  slab, ///< rank r of P rows [R r / P, R (r + 1) / P) of /particles and of /contacts: the DEM,
        ///< which sends each particle to the rank of its bin, so no rank holds the whole file
};

/// The whole file's rows in numbers, whichever share of them this rank holds.
struct RowTotals {
  std::uint64_t particles = 0;
  std::uint64_t contacts = 0;
  double diameter_min = 0, diameter_max = 0;
  double aspect_ratio_min = 0, aspect_ratio_max = 0;
};

/// The complete state of a DEM run at one step.
struct Checkpoint {
  double time = 0;       ///< simulated time [s]
  std::int64_t step = 0; ///< time steps taken
  double time_step = 0;  ///< [s]
  CellState cell;
  ParticleRows particles;                              ///< this rank's rows (after a read: as `share` says)
  ContactRows contacts;                                ///< this rank's rows (after a read: as `share` says)
  RowShare share = RowShare::all;                      ///< which rows a read gave this rank
  RowTotals totals;                                    ///< the whole file's, set by read_checkpoint
  std::vector<Parameter> parameters;                   ///< material and run parameters
  std::vector<std::array<std::uint64_t, 4>> rng_state; ///< every random stream's state
  /// How near static equilibrium the stored state is (root attributes; NaN: not recorded, as in
  /// files written before they were): mean |net force| / mean |contact force|, and the kinetic
  /// energy of the fluctuating motion over the elastic energy of the contacts.
  double unbalanced_force_ratio = std::numeric_limits<double>::quiet_NaN();
  double kinetic_elastic_ratio = std::numeric_limits<double>::quiet_NaN();
  /// The loading run that wrote this checkpoint (root attribute run_id; empty for a prepared
  /// assembly and for files written before run ids): --resume checks it against history.h5.
  std::string run_id;
};

/// Writes a checkpoint atomically (temporary name, flush, rename), collectively on `comm`.
/// Each rank passes the rows it holds; together the particle ids must be 0..N-1 exactly once.
/// `add` (if any) then writes more groups into the complete file, on rank 0, before it appears
/// under `path`: the file never exists without them (an interrupted run's state, say).
void write_checkpoint(const std::string& path, const Checkpoint& local, const Provenance& provenance,
                      const mpi::Comm& comm, const std::function<void(File&)>& add = {});

/// Reads and validates a checkpoint; every rank receives all rows, or with RowShare::slab its
/// slab of them (every rank still reads the positions and sizes of all, for the one check that
/// spans the whole assembly: no pair overlaps beyond the explosion limit); on one rank a slab is
/// the whole file, and the share is RowShare::all. Throws FileError
/// naming the file and the dataset on any problem (version, missing dataset, shape, non-finite
/// value), on every rank (collective).
Checkpoint read_checkpoint(const std::string& path, const mpi::Comm& comm, RowShare share = RowShare::all);

/// True if the checkpoint holds a parameter of this name.
bool has_parameter(const Checkpoint& checkpoint, const std::string& name);

/// Value of a named parameter; throws FileError naming the file if absent.
double parameter(const Checkpoint& checkpoint, const std::string& name, const std::string& path);

} // namespace aniso::h5
