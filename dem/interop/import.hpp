#pragma once
// `aniso-dem import`: an assembly (spheres, or DEMPLA's ovoids) from another code's files as a valid aniso
// checkpoint, ready for `hold`, `relax`, `load` and every later stage.

#include "common/config.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"
#include "dem/config.hpp"
#include "dem/interop/assembly_text.hpp"
#include "dem/interop/contact_dump.hpp"

#include <optional>
#include <vector>

namespace aniso::dem::interop {

struct ImportSummary {
  std::size_t contacts = 0;       ///< touching pairs in aniso's contact law
  std::size_t dumped_matched = 0; ///< dumped contacts that gave a contact its tangential force
  std::size_t dumped_apart = 0;   ///< dumped contacts whose particles aniso finds apart
  std::size_t without_dumped = 0; ///< aniso contacts the dump does not list (tangential force 0)
  std::size_t sliding = 0;        ///< dumped tangential forces capped at the Coulomb limit
  double d50 = 0;                 ///< median diameter by volume [m]
  double density = 0;             ///< [kg/m^3]
  double mean_stress = 0;         ///< p of the contact forces, compression positive [Pa]
};

/// The checkpoint of an imported assembly (every row; identical on every rank: pass it to
/// h5::write_checkpoint from rank 0 with empty rows elsewhere, see rows_for_rank). Particles get
/// ids 0..N-1 in spatial order of the source ids' order, keep the source ids in
/// /particles/source_id, and are wrapped into the cell; the cell is fixed (no strain rate).
/// Normal forces follow from the overlaps by aniso's contact law; tangential forces from the
/// dump when one is given (projected on the tangent plane, capped at the Coulomb limit), else 0.
/// The config's particle keys are set from the file (count, sizes, d50, density: InputError if
/// the config gives another density, or the file's densities differ); its material, time step
/// and skin are used as configured.
h5::Checkpoint import_assembly(const ImportedAssembly& assembly, const std::vector<DumpedContact>* dumped,
                               DemConfig& config, config::Reader& reader, ImportSummary& summary);

/// The rows this rank passes to h5::write_checkpoint for a checkpoint every rank holds whole:
/// all of them on rank 0, none elsewhere.
h5::Checkpoint rows_for_rank(const h5::Checkpoint& whole, const mpi::Comm& comm);

} // namespace aniso::dem::interop
