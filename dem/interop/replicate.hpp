#pragma once
// `aniso-dem replicate`: a checkpoint tiled periodically into n1 x n2 x n3 copies of its cell, a
// larger assembly in the same state (the same stress, fabric and void ratio) that `load`, `relax`
// and every later stage read as any checkpoint. aniso's cell is rectangular, so its lattice
// vectors are L_x e_x, L_y e_y, L_z e_z and the copies lie along the axes.

#include "common/config.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "dem/config.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace aniso::dem::interop {

/// Copies of the cell along x, y and z, each >= 1.
using Copies = std::array<std::int64_t, 3>;

/// "n1,n2,n3" as copies; InputError naming the text unless it is three whole numbers >= 1.
Copies parse_copies(const std::string& text);

/// The checkpoint tiled into `copies` (every row; pure). Copy c = (i, j, k), 0 <= i < n1, ...,
/// has index i + n1 (j + n2 k); its particles are the original's moved by (i L_x, j L_y, k L_z),
/// every other per-particle value kept, with ids id + index N (N = the original's count), so that
/// rows stay in id order. A contact (a, b) with image shift s joins, in copy c, a's copy to b's
/// copy (c + s) mod n, the one its branch vector reaches; its new image shift is
/// floor((c + s) / n). Where that puts the higher id first, the pair is stored the other way
/// round with its normal, force, tangential force and image shift negated. The cell's lengths
/// and reference lengths are multiplied by the copies; time, step, controller, parameters, random
/// streams, equilibrium ratios and run id are kept (all intensive). /particles/source_id is kept
/// for a single copy and dropped otherwise (the copies would share their source ids).
/// FileError naming `path` for a contact whose image shift puts its partner beyond reach.
h5::Checkpoint replicate_checkpoint(const h5::Checkpoint& original, const Copies& copies,
                                    const std::string& path);

struct ReplicateOptions {
  std::string input;      ///< checkpoint to tile
  std::string output;     ///< tiled checkpoint to write (not the input)
  std::string copies;     ///< "n1,n2,n3"
  bool overwrite = false; ///< replace an existing output
};

/// Reads the input, refuses what it cannot tile (a relaxation stopped on SIGTERM, a piece of a
/// prepare, a root attribute it does not know), records the tiled count in the configuration and
/// writes the tiled checkpoint with root attributes replicated_from and replicate_copies
/// (collective).
int run_replicate(const ReplicateOptions& options, DemConfig& config, config::Reader& reader,
                  const std::string& command_line, const Logger& logger, const mpi::Comm& comm);

} // namespace aniso::dem::interop
