#pragma once
// The DEM's parameters: the [dem] configuration keys and the settings a checkpoint stores.

#include "common/config.hpp"
#include "dem/config.hpp"

namespace aniso::dem::io {

/// Reads every [dem] key through `reader` (which records and range-checks them).
DemConfig read_dem_config(config::Reader& reader);

} // namespace aniso::dem::io
