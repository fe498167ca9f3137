// Failure paths of the DEM stage: an unstable time step is refused before a
// run starts, an exploding run stops with a NumericalError about the overlap
// (and a checkpoint written earlier survives it), and an inconsistent grading
// in the config is rejected naming its keys; a checkpoint with settings the config would refuse
// is refused naming the file and the attribute.
#include "common/config.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/mpi.hpp"
#include "dem/config.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/parameters.hpp"
#include "dem/model/contact_law.hpp"
#include "dem/model/integrator.hpp"
#include "dem/protocol/rates.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

namespace {

using namespace aniso;
using namespace aniso::dem;
using namespace aniso::dem::data;
using namespace aniso::dem::io;
using namespace aniso::dem::model;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// (a) A step 1 % above the Rayleigh step is refused; the message gives both numbers.
TEST(Failures, TimeStepAboveCriticalIsRefused) {
  const ContactMaterial material;
  const double critical = rayleigh_time_step(0.5 * 0.075e-3, 2650.0, material);
  const double requested = 1.01 * critical;
  try {
    require_stable_time_step(requested, critical);
    ADD_FAILURE() << "no NumericalError for a step 1.01 x critical";
  } catch (const NumericalError& error) {
    const std::string message = error.what();
    EXPECT_TRUE(contains(message, fmt::format("{:.4g}", requested))) << message;
    EXPECT_TRUE(contains(message, fmt::format("{:.4g}", critical))) << message;
    EXPECT_EQ(error.code(), ExitCode::numerical_failure);
  }
  EXPECT_NO_THROW(require_stable_time_step(critical, critical));
  EXPECT_NO_THROW(require_stable_time_step(0.99 * critical, critical));
  EXPECT_THROW(require_stable_time_step(0.0, critical), NumericalError);
  EXPECT_THROW(require_stable_time_step(-critical, critical), NumericalError);
}

TEST(Failures, ConfiguredTimeStepAboveCriticalIsRefused) {
  DemConfig config;
  const double smallest = config.particles.diameter_min;
  ContactMaterial material;
  material.shear_modulus = config.material.shear_modulus;
  material.poisson_ratio = config.material.poisson_ratio;
  const double critical = rayleigh_time_step(0.5 * smallest, config.particles.density, material);
  config.integration.time_step = 1.01 * critical;
  EXPECT_THROW(settings_from_config(config, smallest), NumericalError);
  config.integration.time_step = 0.99 * critical;
  EXPECT_EQ(settings_from_config(config, smallest).time_step, 0.99 * critical);
  // The fraction is of the smallest particle's step.
  config.integration.time_step = 0;
  config.integration.time_step_fraction = 0.2;
  EXPECT_EQ(settings_from_config(config, smallest).time_step, 0.2 * critical);
}

// (b) Two spheres driven into each other at 500 m/s overlap by far more than
// 5 % of a radius within a few steps: the run stops with a NumericalError that
// names the overlap and the pair.
TEST(Failures, HeadOnImpactStopsWithOverlapError) {
  DemConfig config;
  Particles particles;
  const double radius = 0.1e-3;
  const Vec3 lengths = Vec3::Constant(1.0e-3);
  particles.add(0, radius, 1.0, config.particles.splice_angle, config.particles.density,
                Vec3(0.5e-3 - radius - 0.5e-6, 0.5e-3, 0.5e-3));
  particles.add(1, radius, 1.0, config.particles.splice_angle, config.particles.density,
                Vec3(0.5e-3 + radius + 0.5e-6, 0.5e-3, 0.5e-3));
  particles.velocity[0] = Vec3(500.0, 0, 0);
  particles.velocity[1] = Vec3(-500.0, 0, 0);
  const PeriodicCell state(lengths);
  SimulationSettings settings = settings_from_config(config, config.particles.diameter_min);
  Simulation simulation(std::move(particles), state, model::CellControl{}, settings,
                        mpi::Comm(MPI_COMM_SELF));
  try {
    for (int k = 0; k < 1000; ++k)
      simulation.step();
    ADD_FAILURE() << "no NumericalError after 1000 steps";
  } catch (const NumericalError& error) {
    const std::string message = error.what();
    EXPECT_TRUE(contains(message, "overlap")) << message;
    EXPECT_TRUE(contains(message, "particles 0 and 1")) << message;
    std::printf("[ measured ] stopped at step %lld: %s\n", static_cast<long long>(simulation.step_count()),
                message.c_str());
    EXPECT_LT(simulation.step_count(), 20);
  }
}

// (b) An assembly strained at an absurd rate explodes; the checkpoint written
// before the explosion is still intact and readable afterwards.
TEST(Failures, ExplosionLeavesEarlierCheckpointIntact) {
  const DemConfig config = test::small_config(150, 5);
  Simulation simulation = test::loose_assembly(config);
  for (int k = 0; k < 50; ++k)
    simulation.step();
  test::TemporaryFolder folder("aniso_test_failures");
  const std::string path = folder.file("before_explosion.h5");
  const mpi::Comm self(MPI_COMM_SELF);
  h5::write_checkpoint(path, to_checkpoint(simulation), test::test_provenance(), self);
  const std::int64_t written_step = simulation.step_count();
  const std::vector<Vec3> written_positions = simulation.particles().position;
  const auto size_before = std::filesystem::file_size(path);

  // Shortening every axis by 0.2 % per step closes gaps far faster than the
  // particles can respond: some overlap passes 5 % of a radius.
  simulation.set_control(test::isotropic_rate(simulation, -2e-3 / simulation.settings().time_step));
  std::string message;
  try {
    for (int k = 0; k < 2000; ++k)
      simulation.step();
  } catch (const NumericalError& error) {
    message = error.what();
  }
  std::printf("[ measured ] exploded at step %lld: %s\n", static_cast<long long>(simulation.step_count()),
              message.c_str());
  EXPECT_TRUE(contains(message, "overlap")) << "message: '" << message << "'";

  EXPECT_EQ(std::filesystem::file_size(path), size_before);
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, self);
  EXPECT_EQ(checkpoint.step, written_step);
  ASSERT_EQ(checkpoint.particles.size(), written_positions.size());
  for (std::size_t k = 0; k < written_positions.size(); ++k) {
    ASSERT_EQ(checkpoint.particles.position[k], written_positions[k]) << "particle " << k;
  }
  // ...and it restarts.
  const Simulation restarted = from_checkpoint(checkpoint, path, mpi::Comm(MPI_COMM_SELF));
  EXPECT_EQ(restarted.step_count(), written_step);
}

// (c) diameter_min at or above d50 is rejected, naming the keys.
TEST(Failures, DiameterMinNotBelowD50IsRejected) {
  for (const char* value : {"0.2e-3", "0.17e-3"}) {
    SCOPED_TRACE(value);
    toml::table table =
        toml::parse(fmt::format("[dem.particles]\ndiameter_min = {}\nd50 = 0.17e-3\n", value));
    config::Reader reader(std::move(table), "test");
    try {
      (void)read_dem_config(reader);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_TRUE(contains(message, "diameter_min")) << message;
      EXPECT_TRUE(contains(message, "d50")) << message;
      EXPECT_EQ(error.code(), ExitCode::bad_input);
    }
  }
  // The defaults pass.
  config::Reader reader(toml::table{}, "defaults");
  EXPECT_NO_THROW((void)read_dem_config(reader));
}

// (d) A checkpoint is refused for what the configuration would refuse, and for particle rows no
// simulation can start from (a control interval of 0 gave SIGFPE, zero particles
// SIGSEGV, a Poisson ratio of 0.7 ran as given). A particle outside the cell is refused by
// h5::read_checkpoint, for every stage (tests/common/test_checkpoint.cpp).
TEST(Failures, CheckpointOutsideTheConfigRangesIsRefused) {
  const DemConfig config = test::small_config(150, 5);
  const Simulation simulation = test::loose_assembly(config);
  const h5::Checkpoint good = to_checkpoint(simulation);
  const mpi::Comm self(MPI_COMM_SELF);
  EXPECT_NO_THROW((void)from_checkpoint(good, "good.h5", self));
  const auto set_parameter = [](h5::Checkpoint& c, const std::string& name, double value) {
    for (auto& parameter : c.parameters)
      if (parameter.name == name) parameter.value = value;
  };
  struct Case {
    const char* what;
    std::function<void(h5::Checkpoint&)> spoil;
    const char* expected;
  };
  const std::vector<Case> cases{
      {"control interval 0", [&](h5::Checkpoint& c) { set_parameter(c, "control_interval", 0); },
       "/parameters (attribute 'control_interval'): value 0 is out of range, expected [1, 1000000]"},
      {"Poisson ratio 0.7", [&](h5::Checkpoint& c) { set_parameter(c, "poisson_ratio", 0.7); },
       "'poisson_ratio'): value 0.7 is out of range, expected (-1, 0.5)"},
      {"negative friction", [&](h5::Checkpoint& c) { set_parameter(c, "friction", -0.1); }, "'friction'"},
      {"negative density", [&](h5::Checkpoint& c) { set_parameter(c, "density", -2650); }, "'density'"},
      {"zero time step", [](h5::Checkpoint& c) { c.time_step = 0; }, "time_step): value 0, expected > 0"},
      {"no particles", [](h5::Checkpoint& c) { c.particles.resize(0); }, "/particles: no particles"},
      {"zero mass", [](h5::Checkpoint& c) { c.particles.mass[7] = 0; }, "/particles/mass: row 7"},
      {"aspect ratio 0.1", [](h5::Checkpoint& c) { c.particles.aspect_ratio[2] = 0.1; },
       "/particles/aspect_ratio: row 2"},
  };
  for (const Case& item : cases) {
    SCOPED_TRACE(item.what);
    h5::Checkpoint bad = good;
    item.spoil(bad);
    try {
      (void)from_checkpoint(bad, "bad.h5", self);
      ADD_FAILURE() << "no FileError";
    } catch (const FileError& error) {
      EXPECT_TRUE(contains(error.what(), "bad.h5")) << error.what();
      EXPECT_TRUE(contains(error.what(), item.expected)) << error.what();
      EXPECT_EQ(error.code(), ExitCode::file_error);
    }
  }
}

} // namespace
