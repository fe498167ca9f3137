#pragma once
// The fabric stage's settings ([fabric] in the config file), each with its unit, default and range.

#include "common/config.hpp"

#include <cstdint>
#include <string>

namespace aniso::fabric {

struct FabricConfig {
  std::string output_dir = ".";          ///< folder for fabric.h5 / fabric_series.h5 and their CSV files
  std::int64_t rattler_min_contacts = 2; ///< particles with fewer contacts are rattlers (peeled iteratively)
  double strong_factor = 1.0;            ///< strong contact: normal force > strong_factor * mean normal force
};

/// Reads the [fabric] keys; InputError naming the key on a wrong type or range.
FabricConfig read_fabric_config(config::Reader& reader);

} // namespace aniso::fabric
