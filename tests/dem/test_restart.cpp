// Restart is bit for bit (dem/io/checkpoint.hpp): a run interrupted by a checkpoint,
// written to HDF5, read back and continued, ends in exactly the state of the
// uninterrupted run. Checked at several split points of a biaxial-loading
// segment: mid-way, one step before and after a control update, right after
// a neighbour-list rebuild, and at the very first step.
#include "common/h5/checkpoint.hpp"
#include "common/mpi.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/protocol/load.hpp"
#include "tests/dem/assembly_fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>
#include <vector>

namespace {

using aniso::Vec3;
using namespace aniso;
using namespace aniso::dem;
using namespace aniso::dem::data;
using namespace aniso::dem::io;
using namespace aniso::dem::protocol;

/// Counts bit-level differences between two arrays and reports the first.
template <typename T>
void expect_identical(const char* what, const std::vector<T>& a, const std::vector<T>& b) {
  ASSERT_EQ(a.size(), b.size()) << what;
  std::size_t differences = 0, first = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!(a[k] == b[k])) {
      if (differences++ == 0) first = k;
    }
  }
  if (differences > 0) {
    std::ostringstream detail;
    if constexpr (std::is_same_v<T, Vec3>) {
      detail.precision(17);
      detail << a[first].transpose() << " vs " << b[first].transpose();
    }
    ADD_FAILURE() << what << ": " << differences << " of " << a.size() << " differ, first at " << first
                  << " (" << detail.str() << ")";
  }
}

void expect_same_state(const Simulation& restarted, const Simulation& straight) {
  EXPECT_EQ(restarted.step_count(), straight.step_count());
  EXPECT_EQ(restarted.time(), straight.time());
  const Particles& a = restarted.particles();
  const Particles& b = straight.particles();
  expect_identical("position", a.position, b.position);
  expect_identical("velocity", a.velocity, b.velocity);
  expect_identical("angular velocity", a.angular_velocity, b.angular_velocity);
  expect_identical("force", a.force, b.force);
  expect_identical("torque", a.torque, b.torque);
  const model::CellControl& sa = restarted.control();
  const model::CellControl& sb = straight.control();
  for (int axis = 0; axis < 3; ++axis) {
    SCOPED_TRACE(axis);
    EXPECT_EQ(restarted.cell().lengths()[axis], straight.cell().lengths()[axis]);
    EXPECT_EQ(restarted.cell().reference_lengths()[axis], straight.cell().reference_lengths()[axis]);
    EXPECT_EQ(sa.strain_rate[axis], sb.strain_rate[axis]);
    EXPECT_EQ(sa.target[axis], sb.target[axis]);
    EXPECT_EQ(sa.servo_state[axis], sb.servo_state[axis]);
    EXPECT_EQ(sa.mode[static_cast<std::size_t>(axis)], sb.mode[static_cast<std::size_t>(axis)]);
  }
  EXPECT_EQ(sa.hold_mean_stress, sb.hold_mean_stress);
  EXPECT_EQ(sa.mean_stress_target, sb.mean_stress_target);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(restarted.stress()(r, c), straight.stress()(r, c));
  EXPECT_EQ(restarted.servo_error(), straight.servo_error());
  // Contact history: the touching pairs with their springs and forces.
  const h5::Checkpoint ca = to_checkpoint(restarted), cb = to_checkpoint(straight);
  ASSERT_EQ(ca.contacts.size(), cb.contacts.size());
  EXPECT_TRUE(ca.contacts.particles == cb.contacts.particles);
  expect_identical("contact normal", ca.contacts.normal, cb.contacts.normal);
  expect_identical("contact overlap", ca.contacts.overlap, cb.contacts.overlap);
  expect_identical("contact force", ca.contacts.force, cb.contacts.force);
  expect_identical("tangential spring", ca.contacts.tangential_force, cb.contacts.tangential_force);
  EXPECT_TRUE(ca.contacts.sliding == cb.contacts.sliding);
}

// A base state mid-way through loading: a thin skin and a fast loading rate, so that the
// neighbour list is rebuilt within the short segment under test.
struct RestartCase {
  DemConfig config;
  Simulation base;
};

RestartCase make_case(double aspect_ratio, std::int64_t count) {
  DemConfig config = test::small_config(count, 11);
  config.particles.aspect_ratio = aspect_ratio;
  if (aspect_ratio < 1.0) config.prepare.initial_solid_fraction = 0.35; // bounding spheres
  config.integration.skin = 0.01;
  config.load.inertial_number = 2e-2;
  Simulation simulation = test::loose_assembly(config);
  test::compact_until(simulation, -test::compaction_rate(config, 2e-2), 3e4, 400000);
  start_loading(simulation, config);
  for (int k = 0; k < 300; ++k)
    simulation.step();
  return {config, std::move(simulation)};
}

void expect_bit_for_bit_restarts(const RestartCase& test_case) {
  const Simulation* base_ = &test_case.base;
  const StateMeasures start = base_->measure();
  ASSERT_GT(start.n_contacts, 50) << "the base assembly has too few contacts for a meaningful restart";
  const std::int64_t interval = base_->settings().control_interval;
  ASSERT_EQ(base_->step_count() % interval, 0) << "segment should start on a control update";

  constexpr std::int64_t n_steps = 400;
  Simulation straight = *base_;
  std::vector<std::int64_t> builds{straight.neighbors().n_builds()};
  for (std::int64_t k = 1; k <= n_steps; ++k) {
    straight.step();
    builds.push_back(straight.neighbors().n_builds());
  }
  // Split points: the first step, mid-way (a control update), one step before
  // and one after a control update, and right after each of the first two rebuilds.
  std::set<std::int64_t> splits{1, n_steps / 2, 10 * 13 - 1, 10 * 13 + 1};
  int rebuild_splits = 0;
  for (std::int64_t k = 1; k + interval <= n_steps && rebuild_splits < 2; ++k) {
    if (builds[static_cast<std::size_t>(k)] > builds[static_cast<std::size_t>(k - 1)]) {
      splits.insert(k);
      ++rebuild_splits;
    }
  }
  std::printf(
      "[ measured ] %d contacts, %lld rebuilds in %lld steps, splits:", static_cast<int>(start.n_contacts),
      static_cast<long long>(builds.back() - builds.front()), static_cast<long long>(n_steps));
  for (auto s : splits)
    std::printf(" %lld", static_cast<long long>(s));
  std::printf("\n");
  ASSERT_GE(rebuild_splits, 1) << "no neighbour-list rebuild within the segment: thin the skin";

  test::TemporaryFolder folder("aniso_test_restart");
  const mpi::Comm self(MPI_COMM_SELF);
  for (const std::int64_t split : splits) {
    SCOPED_TRACE("split after " + std::to_string(split) + " steps");
    Simulation first = *base_;
    for (std::int64_t k = 0; k < split; ++k)
      first.step();
    const std::string path = folder.file("split_" + std::to_string(split) + ".h5");
    h5::write_checkpoint(path, to_checkpoint(first), test::test_provenance(), self);
    const h5::Checkpoint checkpoint = h5::read_checkpoint(path, self);
    EXPECT_EQ(checkpoint.step, first.step_count());
    Simulation second = from_checkpoint(checkpoint, path, mpi::Comm(MPI_COMM_SELF));
    EXPECT_EQ(second.step_count(), first.step_count());
    for (std::int64_t k = split; k < n_steps; ++k)
      second.step();
    expect_same_state(second, straight);
  }
}

TEST(Restart, ContinuesBitForBitAtEverySplitPoint) {
  expect_bit_for_bit_restarts(make_case(1.0, 150));
}

// The global damping's rate is set at control updates and stored in the checkpoint, so a
// restart between two updates must take it from there to continue bit for bit.
TEST(Restart, GlobalDampingContinuesBitForBitAtEverySplitPoint) {
  RestartCase test_case = make_case(1.0, 150);
  SimulationSettings damped = test_case.base.settings();
  damped.global_damping = 0.3;
  test_case.base.reconfigure(damped);
  ASSERT_GT(test_case.base.global_damping_rate(), 0.0);
  expect_bit_for_bit_restarts(test_case);
}

// Ovoids carry their last contact normal in the contact history (the narrow phase starts
// from it), so a restart must restore it to continue bit for bit.
TEST(Restart, OvoidsContinueBitForBitAtEverySplitPoint) {
  expect_bit_for_bit_restarts(make_case(0.625, 300));
}

} // namespace
