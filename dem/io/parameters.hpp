#pragma once
// The DEM's parameters, each declared once in one table (parameters.cpp): its configuration key
// with unit, default (the DemConfig member's), allowed range and help; the checkpoint attribute
// that stores it with the engine's member it fills; and how a checkpoint's value meets the
// configured one. The configuration reader, the checkpoint's /parameters written and read, the
// settings the engine starts with, the ranges of a stored value and the one check of a
// configuration against a checkpoint are all driven by that table (docs/decisions.md,
// "One parameter table", shows how a parameter is added).

#include "common/config.hpp"
#include "common/h5/checkpoint.hpp"
#include "dem/config.hpp"
#include "dem/model/cell_control.hpp"
#include "dem/simulation.hpp"

#include <string>
#include <vector>

namespace aniso::dem::io {

/// How a stored value relates to the configured one.
enum class Binding : std::uint8_t {
  config_only, ///< a configuration key that no checkpoint stores
  /// Fixed by the checkpoint (its particles and their material): a run from a checkpoint uses the
  /// stored value, and refuses a configuration that gives another.
  fixed,
  /// Kept by a resumed loading: `load --resume` refuses a configuration with another value.
  resumed,
  stored_only, ///< the engine's own setting, stored for exact restarts; no configuration key
};

/// Reads every [dem] key through `reader` (which records and range-checks them), then checks
/// the keys against each other.
DemConfig read_dem_config(config::Reader& reader);

/// The engine's settings for a fresh start: the table's stored members from the configuration,
/// and the time step from the Rayleigh step of the smallest particle (`smallest_diameter`).
SimulationSettings settings_from_config(const DemConfig& config, double smallest_diameter);

/// The /parameters a checkpoint stores of `settings`: every table entry with an attribute.
std::vector<h5::Parameter> stored_parameters(const SimulationSettings& settings);

/// The settings a checkpoint stores; FileError naming `path`, the attribute and the range for a
/// missing or out-of-range value (a file cannot carry what the configuration would refuse).
SimulationSettings settings_from_checkpoint(const h5::Checkpoint& checkpoint, const std::string& path);

/// Sets each key that the checkpoint fixes (Binding::fixed; and the particle count, diameter
/// bounds and aspect ratio of its rows) to the stored value and records it in the reader's
/// effective configuration, so that provenance says what was used. A key the configuration gives
/// with another value is refused with InputError naming the key, both values and the file.
void adopt_checkpoint_values(DemConfig& config, config::Reader& reader, const h5::Checkpoint& checkpoint,
                             const std::string& path);

/// `load --resume` keeps the loading stored in its checkpoint: InputError listing every
/// Binding::resumed key (and the inertial number, mean stress and time step of the loading)
/// whose configured value differs from the stored one (`stored`, `control`; `critical_time_step`
/// turns a configured time-step fraction into a step).
void require_resume_matches(const DemConfig& config, const SimulationSettings& stored,
                            const model::CellControl& control, double critical_time_step);

/// The allowed range of a configuration key (InternalError for a key not in the table).
config::Range key_range(std::string_view key);

/// The loading's time step: dem.integration.time_step, or its fraction of `critical_time_step`.
double configured_time_step(const DemConfig& config, double critical_time_step);

} // namespace aniso::dem::io
