#pragma once
// Biaxial plane strain at constant mean stress (paper section 2): axis 1
// shortened at a constant rate, axis 2 held, axis 3 servoed so that p stays at
// its target. Checkpoints at the configured strains, a history row every
// history_interval of strain. A run can resume from any of its checkpoints
// and reproduces the uninterrupted run bit for bit.

#include "common/h5/provenance.hpp"
#include "common/log.hpp"
#include "common/timer.hpp"
#include "dem/config.hpp"
#include "dem/io/relaxation_state.hpp"
#include "dem/simulation.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace aniso::dem::protocol {

struct LoadSummary {
  double final_strain = 0;
  double peak_stress_ratio = 0;
  double peak_strain = 0;
  std::int64_t steps = 0;
  std::int64_t relaxation_steps = 0; ///< of `steps`, spent relaxing (after increments, before checkpoints)
  double relaxation_seconds = 0;     ///< wall time of those
  /// Not of `steps`: spent relaxing the copies written as checkpoints (dem.equilibrium.fork_checkpoints).
  std::int64_t fork_steps = 0;
  double fork_seconds = 0; ///< wall time of those
  double wall_seconds = 0;
  std::vector<TimingRow> timing; ///< where the wall time went (common/timer.hpp)
  std::vector<std::string> checkpoints;
  std::string interrupted_checkpoint; ///< written on SIGTERM, for --resume; empty if the run ended
};

/// Sets up loading on a prepared assembly: strain measured from here, loading friction
/// and damping, the biaxial controller.
void start_loading(Simulation& simulation, const DemConfig& config);

/// Runs from the simulation's current strain to the final strain, writing checkpoints
/// (load_NNN.h5 in output_dir, NNN = index in checkpoint_strains) and the history, each marked
/// with run_id. Resuming, run_id is the input checkpoint's: the history.h5 in output_dir must
/// belong to the same run and reach the checkpoint's step (InputError naming both otherwise).
/// `interrupted`: the input's relaxation stopped on SIGTERM (its /relaxation group), which a
/// resumed run continues first. SIGTERM, at a control update of the loading or of a relaxation,
/// ends the run with load_interrupted.h5 (LoadSummary::interrupted_checkpoint). Every
/// `keep_every_seconds` of wall time (common/keep_clock.hpp) the loading's state between
/// relaxations is kept there too, with the history, without stopping: a run killed outright then
/// resumes from it, not from its last numbered checkpoint.
LoadSummary run_loading(Simulation& simulation, const DemConfig& config, const std::string& output_dir,
                        const h5::Provenance& provenance, const Logger& logger, bool resuming,
                        const std::string& run_id = {},
                        const io::InterruptedRelaxation* interrupted = nullptr,
                        double keep_every_seconds = INFINITY);

/// Path of checkpoint number `index` in `folder`.
std::string load_checkpoint_path(const std::string& folder, std::size_t index);

/// Path of load_resume.h5 in `folder`: with dem.equilibrium.fork_checkpoints the checkpoints are
/// relaxed copies, not states the loading passed through, so each checkpoint also rewrites the
/// loading's own state there, the point `load --resume` continues from after a kill.
std::string load_resume_path(const std::string& folder);

/// The root attribute of a checkpoint that is a relaxed copy (fork_checkpoints): the loading's
/// step it was copied at. `load --resume` refuses such a file and names load_resume.h5.
inline constexpr const char* relaxed_copy_attribute = "relaxed_copy_of_step";

} // namespace aniso::dem::protocol
