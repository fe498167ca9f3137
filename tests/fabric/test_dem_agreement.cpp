// The contact stress, coordination and void ratio of a checkpoint written by the DEM equal
// what the DEM itself measures at that state (dem/measures.hpp), for a small assembly built
// with the DEM's public API (tests/dem/assembly_fixture.hpp) and loaded for a few steps.
#include "dem/io/checkpoint.hpp"
#include "dem/io/history.hpp"
#include "dem/measures.hpp"
#include "dem/protocol/load.hpp"
#include "fabric/measures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "../dem/assembly_fixture.hpp"

namespace aniso::fabric {
namespace {

TEST(FabricDem, ContactStressAndCoordinationEqualTheDemsOwn) {
  const mpi::Comm self(MPI_COMM_SELF);
  dem::DemConfig config = dem::test::small_config(150, 11);
  dem::Simulation simulation = dem::test::prepared_assembly(config);
  dem::protocol::start_loading(simulation, config);
  for (int k = 0; k < 500; ++k)
    simulation.step();

  const dem::test::TemporaryFolder folder("fabric_dem_agreement");
  const std::string path = folder.file("state.h5");
  h5::write_checkpoint(path, dem::io::to_checkpoint(simulation, {{{1, 2, 3, 4}}, {}}),
                       dem::test::test_provenance(), self);
  const h5::Checkpoint checkpoint = h5::read_checkpoint(path, self);
  const FabricMeasures m = measure_fabric(checkpoint, path, FabricConfig{}, self);

  const dem::StateMeasures dem_state =
      dem::measure_state(simulation.particles(), simulation.cell(), simulation.neighbors(),
                         simulation.solid_volume(), simulation.n_particles(), self);
  ASSERT_GT(m.n_contacts, 100);
  EXPECT_EQ(m.n_contacts, dem_state.n_contacts);
  // The DEM's stress includes the kinetic term; the branch vectors differ only by round-off
  // (centre difference + image shift here, distance * normal there).
  const Mat3 total = m.stress_contact + m.stress_kinetic;
  EXPECT_LT((total - dem_state.stress).cwiseAbs().maxCoeff(), 1e-12 * dem_state.stress.cwiseAbs().maxCoeff())
      << total << "\nDEM\n"
      << dem_state.stress;
  EXPECT_LT(m.stress_kinetic.norm(), 1e-3 * m.stress_contact.norm());
  EXPECT_NEAR(m.mean_stress, mean_stress_compression_positive(m.stress_contact), 0.0);
  EXPECT_EQ(m.coordination, dem_state.coordination);
  EXPECT_EQ(m.coordination_no_rattlers, dem_state.coordination_no_rattlers);
  EXPECT_EQ(m.n_rattlers, dem_state.n_rattlers);
  EXPECT_NEAR(m.void_ratio, dem_state.void_ratio, 1e-12 * dem_state.void_ratio);
}

TEST(FabricDem, ContactStressOfLoadCheckpointsEqualsTheRecordedHistory) {
  // A short loading run through the DEM's own driver: its history.h5 row at each checkpoint's
  // step holds the stress the DEM measured there (contact + kinetic).
  const mpi::Comm self(MPI_COMM_SELF);
  dem::DemConfig config = dem::test::small_config(150, 12);
  config.load.final_strain = 4e-4;
  config.load.history_interval = 1e-4;
  config.load.checkpoint_strains = {2e-4, 4e-4};
  // This 150-sphere assembly creeps near a force ratio of 1e-4; the test is about the stress
  // sums, so a looser static state keeps it short.
  config.equilibrium.tolerance = 1e-3;
  config.equilibrium.verify_steps = 2000;
  dem::Simulation simulation = dem::test::prepared_assembly(config);
  dem::protocol::start_loading(simulation, config);
  const dem::test::TemporaryFolder folder("fabric_dem_history");
  const std::string out = folder.file("");
  dem::protocol::run_loading(simulation, config, out, dem::test::test_provenance(), make_silent_logger(),
                             false);
  const dem::io::History history = dem::io::History::read(out);
  const std::vector<std::string> columns{"stress_11", "stress_22", "stress_33",
                                         "stress_23", "stress_13", "stress_12"};
  const std::array<std::array<int, 2>, 6> entry{{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  for (std::size_t index = 0; index < config.load.checkpoint_strains.size(); ++index) {
    const std::string path = dem::protocol::load_checkpoint_path(out, index);
    const FabricMeasures m = measure_fabric(h5::read_checkpoint(path, self), path, FabricConfig{}, self);
    const std::vector<double>& steps = history.column("step");
    const auto row = std::find(steps.begin(), steps.end(), static_cast<double>(m.step));
    ASSERT_NE(row, steps.end()) << "no history row at step " << m.step << " of " << path;
    const auto r = static_cast<std::size_t>(row - steps.begin());
    const Mat3 total = m.stress_contact + m.stress_kinetic;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double recorded = history.column(columns[c])[r];
      EXPECT_NEAR(total(entry[c][0], entry[c][1]), recorded, 1e-12 * std::abs(history.column("p")[r]))
          << columns[c] << " of " << path;
    }
    EXPECT_NEAR(m.void_ratio, history.column("void_ratio")[r], 1e-12);
    EXPECT_EQ(m.coordination, history.column("coordination")[r]);
  }
}

} // namespace
} // namespace aniso::fabric
