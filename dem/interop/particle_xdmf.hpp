#pragma once
// Particles and force chains of a DEM checkpoint for ParaView: an XDMF 3 file and a small HDF5
// file beside it with the derived arrays (docs/formats/particle-xdmf.md). The checkpoint itself
// is not touched.

#include "common/h5/checkpoint.hpp"

#include <string>

namespace aniso::dem::interop {

struct ParticleXdmfSummary {
  std::string xdmf_path; ///< the .xmf written
  std::string data_path; ///< the HDF5 file it points to
  std::size_t particles = 0;
  std::size_t contacts = 0;
  std::size_t strong_contacts = 0; ///< normal force above the mean normal force (paper, section 3)
  double mean_normal_force = 0;    ///< over all contacts [N]; 0 without contacts
};

/// Writes `xdmf_path` (".xmf") and its data file (same stem, ".vis.h5") atomically from a whole
/// checkpoint (every row, as h5::read_checkpoint returns it; call on one rank). Two grids: the
/// particles (Polyvertex: position, diameter, aspect ratio, velocity, angular velocity, force,
/// the axis of revolution as a unit vector) and the contacts (Polyline of two points, centre of
/// i to the centre of j's periodic image: normal force magnitude, tangential force magnitude,
/// the strong-contact flag). `checkpoint_path` is recorded as the source. InputError if the
/// output path does not end in ".xmf".
ParticleXdmfSummary write_particle_xdmf(const h5::Checkpoint& checkpoint, const std::string& checkpoint_path,
                                        const std::string& xdmf_path);

} // namespace aniso::dem::interop
