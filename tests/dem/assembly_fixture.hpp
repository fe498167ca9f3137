#pragma once
// Shared set-up for the DEM tests: a small polydisperse assembly built
// quickly (sparse random arrangement, fast isotropic compaction, optional
// stress-servo consolidation), temporary file names and a fixed provenance.
// Everything here is deterministic: the same seed gives the same assembly.

#include "common/h5/provenance.hpp"
#include "common/log.hpp"
#include "common/rng.hpp"
#include "common/tensor.hpp"
#include "dem/config.hpp"
#include "dem/io/parameters.hpp"
#include "dem/protocol/prepare.hpp"
#include "dem/protocol/rates.hpp"
#include "dem/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace aniso::dem::test {

/// The paper's material and grading with a small count in a cubic cell. 150
/// particles at a solid fraction of 0.6 give a cell of about 0.67 mm, above
/// twice the neighbour-list interaction range (about 0.59 mm).
inline DemConfig small_config(std::int64_t count = 150, std::uint64_t seed = 7) {
  DemConfig config;
  config.seed = seed;
  config.particles.count = count;
  config.prepare.cell_aspect = {1.0, 1.0, 1.0};
  config.prepare.initial_solid_fraction = 0.3;
  return config;
}

/// Sparse random arrangement without overlaps (preparation friction and damping).
inline Simulation loose_assembly(const DemConfig& config) {
  RandomStream sizes(config.seed, 0), placement(config.seed, 1);
  return protocol::sparse_assembly(config, sizes, placement, mpi::Comm(MPI_COMM_SELF));
}

/// Isotropic compaction rate [1/s] for an inertial number at the confining pressure.
inline double compaction_rate(const DemConfig& config, double inertial_number) {
  return strain_rate_for_inertial_number(inertial_number, config.particles.d50, config.particles.density,
                                         config.prepare.confining_pressure);
}

inline model::CellControl isotropic_rate(const Simulation& simulation, double rate) {
  return model::strain_controlled(simulation.control(), Vec3::Constant(rate));
}

/// Compacts isotropically at `rate` (negative) until p reaches `pressure` at a
/// control update, then stops the cell. Fails the test after `max_steps`.
inline void compact_until(Simulation& simulation, double rate, double pressure, std::int64_t max_steps) {
  simulation.set_control(isotropic_rate(simulation, rate));
  const std::int64_t start = simulation.step_count();
  while (mean_stress_compression_positive(simulation.stress()) < pressure) {
    ASSERT_LT(simulation.step_count() - start, max_steps)
        << "compaction did not reach p = " << pressure << " Pa";
    simulation.step();
  }
  simulation.set_control(isotropic_rate(simulation, 0.0));
}

/// The library's own preparation protocol (dem::prepare_assembly) with a single
/// compaction cycle: compaction until the assembly seizes, then stress-servo
/// consolidation to the confining pressure until |p - p0|/p0 is below
/// dem.prepare.consolidation_tolerance and the assembly is at rest.
inline Simulation prepared_assembly(const DemConfig& config) {
  DemConfig one_cycle = config;
  one_cycle.prepare.cycles = 1;
  one_cycle.prepare.void_ratio_tolerance = 1.0; // one fast cycle: any density will do
  protocol::PreparedAssembly prepared =
      protocol::prepare_assembly(one_cycle, make_silent_logger(), mpi::Comm(MPI_COMM_SELF));
  return std::move(*prepared.simulation);
}

/// A fixed provenance for checkpoints written by tests.
inline h5::Provenance test_provenance() {
  h5::Provenance provenance;
  provenance.program = "aniso dem test";
  provenance.version = "0.0.0";
  provenance.git_hash = "test";
  provenance.config = "[dem]\n";
  provenance.command_line = "test";
  provenance.n_ranks = 1;
  provenance.date = "2024-01-01T00:00:00Z";
  return provenance;
}

/// A fresh, process-unique folder under the system temporary directory, removed on destruction.
class TemporaryFolder {
public:
  explicit TemporaryFolder(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
  std::filesystem::path path_;
};

} // namespace aniso::dem::test
