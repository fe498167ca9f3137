#pragma once
// A whole run (no --direction) stopped by SIGTERM keeps the directions it finished as direction
// files (permeability_<stem>_direction<D>.h5, the files `--direction D` writes) and the same command
// then runs only the others. Once the tensor is written the direction files it used are removed:
// their runs are in the result, and a later run (another build, perhaps) starts afresh.
// `collect` checks direction files against each other with the same rule (differing_settings).

#include "common/h5/image.hpp"
#include "common/h5/provenance.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "lbm/io.hpp"
#include "lbm/permeability.hpp"

#include <string>

namespace aniso::lbm {

/// The settings, image and porosity of `file` that differ from those of `reference`, named and
/// joined by ", " ("" when they agree): runs that differ in them do not make one tensor.
std::string differing_settings(const DirectionFile& file, const DirectionFile& reference);

/// The directions whose files in `output_dir` hold runs of this image file (content hash
/// `image_hash`) with these settings. Others are run anew and replaced; an unreadable one is named
/// in a warning. Collective: rank 0 reads, every rank receives.
DirectionRuns finished_directions(const std::string& output_dir, const std::string& input,
                                  const h5::VoxelImage& image, const std::string& image_hash,
                                  const PermeabilitySettings& settings, const mpi::Comm& comm,
                                  const Logger& logger);

/// Writes, on rank 0, a direction file for each direction done in `runs` and not in `finished`.
void keep_directions(const std::string& output_dir, const std::string& input, const h5::VoxelImage& image,
                     const std::string& image_hash, const PermeabilitySettings& settings,
                     const DirectionRuns& runs, const DirectionRuns& finished,
                     const h5::Provenance& provenance, const mpi::Comm& comm);

/// Rank 0: removes the direction files of the directions in `finished` (the result now holds them).
void remove_finished(const std::string& output_dir, const std::string& input, const DirectionRuns& finished,
                     const mpi::Comm& comm);

/// What a stopped run did and left, and the command that continues (`kept`: whether the done
/// directions were kept as files).
std::string stop_message(const std::string& output_dir, const std::string& input, const DirectionRuns& runs,
                         bool kept, const std::string& command);

} // namespace aniso::lbm
