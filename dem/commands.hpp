#pragma once
// The aniso-dem subcommands that run a protocol: each reads its input, runs the protocol
// (dem/protocol/), writes its files (dem/io/) and ends with the run's timing table. main.cpp
// parses the command line and calls one of them; import and export are in dem/interop/.

#include "common/config.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "dem/config.hpp"

#include <cstdint>
#include <string>

namespace aniso::dem {

/// What every subcommand gets: the configuration as read (and adopted from an input checkpoint),
/// its reader (for provenance), the command line, the logger and the communicator.
struct CommandContext {
  const DemConfig& config;
  const config::Reader& reader;
  std::string command_line;
  Logger logger;
  mpi::Comm comm;
};

struct PrepareOptions {
  bool resume = false; ///< continue from the pieces kept in dem.output_dir
  /// How often the compaction or consolidation in progress is kept [min of wall time]; 0: at
  /// every control update.
  double keep_every_minutes = 20;
};

/// prepare: a dense isotropic assembly, written to <output_dir>/prepared.h5. Its finished pieces
/// (dem/io/prepare_pieces.hpp) are kept in <output_dir> until then, and the piece in progress
/// every options.keep_every_minutes; on SIGTERM it stops with exit 143, keeping the piece in
/// progress, and `resume` continues from them to the bits of an uninterrupted run (after a kill,
/// from what was kept last).
int run_prepare(const CommandContext& context, const PrepareOptions& options);

struct LoadOptions {
  bool resume = false;    ///< continue the loading run whose checkpoint `input` is
  bool overwrite = false; ///< replace a loading run already in the output folder
  /// How often the loading's state is kept as load_interrupted.h5 [min of wall time]; 0: at
  /// every control update.
  double keep_every_minutes = 20;
};
/// load: biaxial plane strain at constant mean stress from `checkpoint` (read from `input`).
int run_load(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
             const LoadOptions& options);

struct HoldOptions {
  std::int64_t steps = 0;
  std::string csv;      ///< "": no CSV
  double max_drift = 0; ///< exit 5 if |p - p_start| / p_start exceeds it (0: report only)
};
/// hold: the checkpoint at a fixed cell; reports the drift of p.
int run_hold(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
             const HoldOptions& options);

struct RelaxOptions {
  bool resume = false; ///< `input` is the _interrupted file of a stopped or killed run
  /// How often the relaxation's state is kept as that file [min of wall time]; 0: at every
  /// control update.
  double keep_every_minutes = 20;
};

/// relax: the checkpoint relaxed at its own loading control to the verified equilibrium of
/// dem.equilibrium, written to `output` (never the input). On SIGTERM it writes its state to
/// `output` with _interrupted before the extension and exits 143, and it keeps its state there
/// every options.keep_every_minutes (removed when it ends); options.resume continues from such a
/// file (`input`) to the bits of an uninterrupted run.
int run_relax(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
              const std::string& output, const RelaxOptions& options);

/// consolidate: an assembly from another code (aniso-dem import) consolidated isotropically to
/// dem.prepare.confining_pressure with the loading's contacts and relaxed to the verified
/// equilibrium, written to `output` as a prepared assembly that `load` starts from. SIGTERM and
/// options as for run_relax.
int run_consolidate(const CommandContext& context, const h5::Checkpoint& checkpoint, const std::string& input,
                    const std::string& output, const RelaxOptions& options);

} // namespace aniso::dem
