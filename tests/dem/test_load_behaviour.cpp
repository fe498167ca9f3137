// dem.load.behaviour: each named behaviour gives its keys the stated values, a key given explicitly
// wins wherever it stands in the file, and the lines the docs and messages print are what it sets.

#include "common/config.hpp"
#include "dem/config.hpp"
#include "dem/io/parameters.hpp"
#include "dem/load_behaviour.hpp"

#include <gtest/gtest.h>

#include <string>

namespace aniso::dem {
namespace {

DemConfig read(const std::string& toml_text) {
  config::Reader reader(toml::parse(toml_text), "test");
  return io::read_dem_config(reader);
}

TEST(LoadBehaviour, InertialIsTheEngineDefaults) {
  const DemConfig defaults;
  const DemConfig inertial = read("[dem.load]\nbehaviour = \"inertial\"\n");
  EXPECT_EQ(read("").load.behaviour, LoadBehaviour::inertial);
  EXPECT_EQ(inertial.integration.damping, defaults.integration.damping);
  EXPECT_EQ(inertial.integration.global_damping, 0.0);
  EXPECT_EQ(inertial.integration.global_damping_spin_factor, 1.0);
  EXPECT_EQ(inertial.load.increment, 0.0);
  EXPECT_FALSE(inertial.load.quasi_static);
  EXPECT_FALSE(inertial.equilibrium.fork_checkpoints);
}

TEST(LoadBehaviour, OvalIsDemplasDampingWithForkedCheckpoints) {
  const DemConfig oval = read("[dem.load]\nbehaviour = \"oval\"\n");
  EXPECT_EQ(oval.integration.damping, 0.0);
  EXPECT_DOUBLE_EQ(oval.integration.global_damping, 0.071);
  EXPECT_DOUBLE_EQ(oval.integration.global_damping_spin_factor, 6.0);
  EXPECT_EQ(oval.load.increment, 0.0); // continuous: the damping's strength depends on the rate
  EXPECT_FALSE(oval.load.quasi_static);
  EXPECT_TRUE(oval.equilibrium.at_checkpoints);
  EXPECT_TRUE(oval.equilibrium.fork_checkpoints);
  // The rate is the user's: the default inertial number is DEMPLA's order (8e-4 to 1.2e-3).
  EXPECT_EQ(oval.load.inertial_number, DemConfig{}.load.inertial_number);
}

TEST(LoadBehaviour, QuasiStaticIsTheConvergedIncrement) {
  const DemConfig qs = read("[dem.load]\nbehaviour = \"quasi_static\"\n");
  EXPECT_TRUE(qs.load.quasi_static);
  EXPECT_DOUBLE_EQ(qs.load.increment, 3e-5);
  EXPECT_DOUBLE_EQ(qs.load.increment_tolerance, 1e-3);
  EXPECT_FALSE(qs.equilibrium.fork_checkpoints);
}

TEST(LoadBehaviour, AGivenKeyWinsWhereverItStands) {
  // The key before the behaviour in the file and after it: both win.
  const DemConfig before =
      read("[dem.integration]\nglobal_damping = 0.02\n[dem.load]\nbehaviour = \"oval\"\n");
  const DemConfig after = read("[dem.load]\nbehaviour = \"oval\"\nincrement = 1e-4\n");
  EXPECT_DOUBLE_EQ(before.integration.global_damping, 0.02);
  EXPECT_DOUBLE_EQ(before.integration.global_damping_spin_factor, 6.0); // the rest still the behaviour's
  EXPECT_DOUBLE_EQ(after.load.increment, 1e-4);
  EXPECT_DOUBLE_EQ(after.integration.global_damping, 0.071);
}

TEST(LoadBehaviour, ItsPrintedSettingsAreWhatItSets) {
  for (const LoadBehaviour behaviour :
       {LoadBehaviour::inertial, LoadBehaviour::oval, LoadBehaviour::quasi_static}) {
    SCOPED_TRACE(static_cast<int>(behaviour));
    // The printed lines, given as keys to the inertial behaviour, make the same configuration.
    toml::table table;
    for (const std::string& line : load_behaviour_settings(behaviour))
      config::apply_override(table,
                             line.substr(0, line.find(" = ")) + "=" + line.substr(line.find(" = ") + 3));
    config::Reader reader(std::move(table), "printed");
    DemConfig printed = io::read_dem_config(reader);
    DemConfig named;
    apply_load_behaviour(behaviour, named);
    printed.load.behaviour = named.load.behaviour;
    EXPECT_EQ(printed.integration.damping, named.integration.damping);
    EXPECT_EQ(printed.integration.global_damping, named.integration.global_damping);
    EXPECT_EQ(printed.integration.global_damping_spin_factor, named.integration.global_damping_spin_factor);
    EXPECT_EQ(printed.load.increment, named.load.increment);
    EXPECT_EQ(printed.load.increment_tolerance, named.load.increment_tolerance);
    EXPECT_EQ(printed.load.quasi_static, named.load.quasi_static);
    EXPECT_EQ(printed.equilibrium.fork_checkpoints, named.equilibrium.fork_checkpoints);
  }
}

} // namespace
} // namespace aniso::dem
