#pragma once
// The named loading behaviours of dem.load.behaviour (docs/methods/dem.md, "Loading
// behaviours"): each sets the defaults of the keys that decide how a sheared assembly dissipates
// and how its checkpoints are made static; a key given explicitly still wins.

#include "dem/config.hpp"

#include <string>
#include <vector>

namespace aniso::dem {

/// The words of dem.load.behaviour, in the order of LoadBehaviour.
std::vector<std::string> load_behaviour_words();

/// The keys a behaviour sets, with their values, as "key = value" lines for messages and docs.
std::vector<std::string> load_behaviour_settings(LoadBehaviour behaviour);

/// Sets the members behind the behaviour's keys in `config` (before the keys themselves are read).
void apply_load_behaviour(LoadBehaviour behaviour, DemConfig& config);

} // namespace aniso::dem
