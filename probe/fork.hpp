#pragma once
// One oedometric fork (paper eq. (Darve)): from the stored state, d eps_ii =
// +-delta on one axis while the other two normal strains are held and no shear
// is applied. Forks 1..6: fork 2a-1 is +delta (extension) on axis a, fork 2a is
// -delta (compression) on axis a (a = 1, 2, 3). Fork 0 is the reference: the
// same protocol with no increment.
//
// Protocol (docs/methods/probe.md): restore the checkpoint and stop the loading
// (all strains held); apply half the increment at the probe rate, hold for
// hold_steps and record the stress at every control update of the last
// window_steps; apply the second half, hold and record again. Every fork takes
// the same steps, so its samples line up with the reference fork's: the response
// to the increment is the difference, which removes whatever the stopped
// assembly does on its own (relaxation, creep) to first order.

#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "common/tensor.hpp"
#include "common/timer.hpp"
#include "dem/simulation.hpp"
#include "probe/config.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::probe {

inline constexpr int n_forks = 6;        ///< forks with an increment, 1..6
inline constexpr int reference_fork = 0; ///< the fork without one
inline constexpr int n_fork_files = n_forks + 1;

struct ForkSpec {
  int index = 0; ///< 0..6
  int axis = 0;  ///< 0, 1, 2 (x1, x2, x3); 0 for the reference
  int sign = 0;  ///< +1 extension, -1 compression, 0 reference
};

/// The fork with this number; InputError unless 0 <= index <= 6.
ForkSpec fork_spec(int index);

struct ForkResult {
  int index = 0;
  Mat3 stress_start = Mat3::Zero(); ///< restored stress of the checkpoint, tension positive [Pa]
  std::vector<Mat3> samples_half;   ///< stress at each control update of the window after the first half
  std::vector<Mat3> samples_final;  ///< ... after the second half [Pa]
  Vec3 strain_half = Vec3::Zero();  ///< ln(L / L_start) per axis after the first half
  Vec3 strain_final = Vec3::Zero(); ///< ... after the whole increment
  double strain_rate = 0;           ///< |rate| of the loaded axis [1/s] (the rate forks 1..6 use)
  double time_step = 0;             ///< [s]
  std::int64_t half_steps = 0;      ///< steps of each half increment
  std::int64_t hold_steps = 0;      ///< steps of each hold
  std::int64_t contacts_start = 0;
  std::int64_t sliding_start = 0; ///< contacts at the Coulomb limit at the start
  std::int64_t contacts_final = 0;
  std::int64_t sliding_final = 0;
};

/// Where this rank's forks spent their wall time: the engine's sections of their steps, and the
/// restarts from the checkpoint (for the timing table).
struct ForkTimes {
  SectionTimes engine{dem::Simulation::section_names()};
  SectionTimes restart{{"restart"}};
};

/// Mean of stress samples; InputError if there are none.
Mat3 mean_of(const std::vector<Mat3>& samples);

/// Runs fork `index` from `checkpoint` (read from `path`) on `comm` (collective; every rank
/// passes the whole checkpoint). The same inputs give the same bits on any number of ranks.
/// With `times`, adds the fork's wall time to it. Once any rank of `comm` has received SIGTERM
/// (polled every 100 steps), throws Interrupted on all of them: the fork is dropped.
ForkResult run_fork(const h5::Checkpoint& checkpoint, const std::string& path, int index,
                    const ProbeConfig& config, const mpi::Comm& comm, const Logger& logger,
                    ForkTimes* times = nullptr);

} // namespace aniso::probe
