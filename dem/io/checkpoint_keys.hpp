#pragma once
// The DEM keys a checkpoint fixes: its particles (count, sizes, shape, density) and their
// contact material. `load` and `hold` take them from the file, never from the configuration.

#include "common/config.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"

#include <string>

namespace aniso::dem::io {

/// Sets each fixed key of config to the checkpoint's value and records it in the reader's
/// effective configuration (so provenance says what was used). A key the configuration gives
/// (file or --set) with another value is refused with InputError naming the key, both values
/// and the file: the run would otherwise ignore it. docs/user-guide.md lists the keys.
void adopt_checkpoint_values(DemConfig& config, config::Reader& reader, const h5::Checkpoint& checkpoint,
                             const std::string& path);

} // namespace aniso::dem::io
