#pragma once
// The [lbm] configuration section (documented in docs/methods/lbm.md).

#include "common/config.hpp"
#include "lbm/permeability.hpp"

#include <string>

namespace aniso::lbm {

struct LbmConfig {
  PermeabilitySettings permeability;
  bool write_velocity = false; ///< velocity fields of every run, with an XDMF sidecar
  std::string output_dir = ".";
  std::string petsc_options; ///< PETSc options database entries, e.g. "-log_view"
};

/// Reads and range-checks every lbm.* key (InputError naming the key on a bad value).
LbmConfig read_lbm_config(config::Reader& reader);

} // namespace aniso::lbm
