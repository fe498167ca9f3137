#include "probe/source.hpp"

#include "common/h5/content_hash.hpp"

namespace aniso::probe {

ProbeSource probe_source(const std::string& path, const h5::Checkpoint& checkpoint, const mpi::Comm& comm) {
  ProbeSource source;
  source.path = path;
  source.hash = h5::content_hash(path, comm);
  source.cell_strain = (checkpoint.cell.lengths - checkpoint.cell.reference_lengths)
                           .cwiseQuotient(checkpoint.cell.reference_lengths);
  // A prepared assembly (every axis stress-servoed: isotropic consolidation) has not been loaded;
  // its reference lengths are those of the sparse start, so -eps_11 would be the compaction strain.
  const auto& mode = checkpoint.cell.mode;
  const bool prepared =
      mode[0] == h5::AxisMode::stress && mode[1] == h5::AxisMode::stress && mode[2] == h5::AxisMode::stress;
  source.strain = prepared ? 0.0 : -source.cell_strain[0];
  return source;
}

} // namespace aniso::probe
