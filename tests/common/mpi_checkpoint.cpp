// Parallel checkpoints (run on 1 and 2 ranks): each rank holds a disjoint,
// interleaved, reverse-ordered share of a deterministic random checkpoint and
// writes it collectively with MPI-IO; every rank then reads the file back and
// finds the full content bit for bit. Because the expected content does not
// depend on the rank count, files written by 1 and by N ranks hold the same
// data; the last test also checks that directly against a one-rank file.
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/file.hpp"
#include "common/mpi.hpp"
#include "common/row_slab.hpp"
#include "tests/common/checkpoint_sample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

namespace {

namespace fs = std::filesystem;
using aniso::h5::Checkpoint;
using aniso::mpi::Comm;
using aniso::test::sample_checkpoint;
using aniso::test::sample_provenance;

class MpiCheckpoint : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = aniso::test::make_temp_folder(comm_, "aniso-mpi-checkpoint");
    ASSERT_FALSE(folder_.empty());
  }
  void TearDown() override {
    comm_.barrier();
    if (comm_.is_root()) fs::remove_all(folder_);
  }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (fs::path(folder_) / name).string();
  }
  [[nodiscard]] std::size_t rank() const { return static_cast<std::size_t>(comm_.rank()); }
  [[nodiscard]] std::size_t n_ranks() const { return static_cast<std::size_t>(comm_.size()); }

  // Writes this rank's share, reads on every rank, compares with the full content.
  void round_trip(const Checkpoint& full, const std::function<bool(std::size_t)>& mine_particle,
                  const std::function<bool(std::size_t)>& mine_contact, const std::string& name) {
    const Checkpoint share = aniso::test::select_rows(full, mine_particle, mine_contact);
    aniso::h5::write_checkpoint(path(name), share, sample_provenance(comm_.size()), comm_);
    const Checkpoint read = aniso::h5::read_checkpoint(path(name), comm_);
    aniso::test::expect_bit_identical(full, read);
  }

  // Writes the whole checkpoint from rank 0 alone, for every rank to read.
  void write_alone(const Checkpoint& full, const std::string& name) {
    Comm alone = comm_.split(comm_.is_root() ? 0 : 1, 0);
    if (comm_.is_root()) aniso::h5::write_checkpoint(path(name), full, sample_provenance(1), alone);
    alone.free();
    comm_.barrier();
  }

  const Comm comm_ = Comm::world();
  std::string folder_;
};

TEST_F(MpiCheckpoint, InterleavedRowsRoundTrip) {
  // Contacts dealt by row, not by particle: contacts sharing id_i sit on different ranks.
  const Checkpoint full = sample_checkpoint(31, 257, 700, 4);
  round_trip(
      full, [&](std::size_t k) { return k % n_ranks() == rank(); },
      [&](std::size_t k) { return (k / 3) % n_ranks() == rank(); }, "interleaved.h5");
}

TEST_F(MpiCheckpoint, ContactsWithTheOwnerOfTheFirstParticle) {
  const Checkpoint full = sample_checkpoint(32, 100, 300, 1);
  round_trip(
      full, [&](std::size_t k) { return k % n_ranks() == rank(); },
      [&](std::size_t k) { return full.contacts.particles[k][0] % n_ranks() == rank(); }, "owner.h5");
}

TEST_F(MpiCheckpoint, RanksWithNothingStillTakePart) {
  const Checkpoint full = sample_checkpoint(33, 50, 80, 2);
  const std::size_t last = n_ranks() - 1;
  round_trip(
      full, [&](std::size_t) { return rank() == last; }, [&](std::size_t) { return rank() == 0; },
      "lopsided.h5");
}

TEST_F(MpiCheckpoint, NoContactsAndNoStreams) {
  const Checkpoint full = sample_checkpoint(34, 9, 0, 0);
  round_trip(
      full, [&](std::size_t k) { return k % n_ranks() == rank(); }, [](std::size_t) { return true; },
      "empty.h5");
}

TEST_F(MpiCheckpoint, InvalidSharesFailOnEveryRank) {
  const Checkpoint full = sample_checkpoint(35, 20, 30, 1);
  // Every rank claims particle 0 too: duplicated as soon as there are two ranks.
  Checkpoint share = aniso::test::select_rows(
      full, [&](std::size_t k) { return k % n_ranks() == rank() || (n_ranks() > 1 && k == 0); },
      [&](std::size_t k) { return k % n_ranks() == rank(); });
  if (n_ranks() > 1) {
    EXPECT_THROW(aniso::h5::write_checkpoint(path("bad.h5"), share, sample_provenance(comm_.size()), comm_),
                 aniso::InputError);
  }
  // A contact that only rank 0 gets wrong: every rank must still throw.
  share = aniso::test::select_rows(
      full, [&](std::size_t k) { return k % n_ranks() == rank(); },
      [&](std::size_t k) { return k % n_ranks() == rank(); });
  if (comm_.is_root()) share.contacts.normal[0].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(aniso::h5::write_checkpoint(path("bad.h5"), share, sample_provenance(comm_.size()), comm_),
               aniso::InputError);
  EXPECT_FALSE(fs::exists(path("bad.h5")));
}

TEST_F(MpiCheckpoint, SameDataAsAOneRankFile) {
  const Checkpoint full = sample_checkpoint(36, 120, 333, 3);
  const Checkpoint share = aniso::test::select_rows(
      full, [&](std::size_t k) { return k % n_ranks() == rank(); },
      [&](std::size_t k) { return k % n_ranks() == rank(); });
  aniso::h5::write_checkpoint(path("all_ranks.h5"), share, sample_provenance(1), comm_);
  write_alone(full, "one_rank.h5");
  const Checkpoint from_all = aniso::h5::read_checkpoint(path("all_ranks.h5"), comm_);
  const Checkpoint from_one = aniso::h5::read_checkpoint(path("one_rank.h5"), comm_);
  aniso::test::expect_bit_identical(from_one, from_all);
  // Same stored type, shape and size for the row datasets.
  const aniso::h5::File a = aniso::h5::File::open(path("all_ranks.h5"));
  const aniso::h5::File b = aniso::h5::File::open(path("one_rank.h5"));
  for (const char* group : {"particles", "contacts"}) {
    for (const char* dataset : {"id", "diameter", "position", "orientation", "particles", "normal", "overlap",
                                "sliding", "image_shift"}) {
      if (!a.open_group(group).has_child(dataset)) continue;
      const auto x = a.open_group(group).open_dataset(dataset);
      const auto y = b.open_group(group).open_dataset(dataset);
      EXPECT_EQ(x.dims(), y.dims()) << x.name();
      const aniso::h5::Handle x_type(H5Dget_type(x.id()), H5Tclose);
      const aniso::h5::Handle y_type(H5Dget_type(y.id()), H5Tclose);
      EXPECT_EQ(H5Tequal(x_type.get(), y_type.get()), 1) << x.name();
      EXPECT_EQ(H5Dget_storage_size(x.id()), H5Dget_storage_size(y.id())) << x.name();
    }
  }
}

// The DEM's start: each rank reads its contiguous slab of the rows, and the totals of all.
TEST_F(MpiCheckpoint, SlabReadGivesEachRankItsRowsAndTheTotals) {
  for (const auto& [n_particles, n_contacts] : {std::pair<std::size_t, std::size_t>{121, 345}, {1, 0}}) {
    const Checkpoint full = sample_checkpoint(37, n_particles, n_contacts, 2);
    const std::string name = "slab" + std::to_string(n_particles) + ".h5";
    write_alone(full, name);
    const Checkpoint read = aniso::h5::read_checkpoint(path(name), comm_, aniso::h5::RowShare::slab);
    const aniso::RowSlab particles = aniso::row_slab(n_particles, comm_.rank(), comm_.size());
    const aniso::RowSlab contacts = aniso::row_slab(n_contacts, comm_.rank(), comm_.size());
    const Checkpoint expected = aniso::test::select_rows(
        full, [&](std::size_t k) { return k >= particles.first && k < particles.end(); },
        [&](std::size_t k) { return k >= contacts.first && k < contacts.end(); }, true);
    aniso::test::expect_bit_identical(expected, read);
    EXPECT_EQ(read.share, comm_.size() > 1 ? aniso::h5::RowShare::slab : aniso::h5::RowShare::all);
    EXPECT_EQ(comm_.sum(static_cast<std::int64_t>(read.particles.size())),
              static_cast<std::int64_t>(n_particles));
    const aniso::h5::RowTotals& totals = read.totals;
    EXPECT_EQ(totals.particles, n_particles);
    EXPECT_EQ(totals.contacts, n_contacts);
    const auto& d = full.particles.diameter;
    const auto& a = full.particles.aspect_ratio;
    EXPECT_EQ(totals.diameter_min, *std::min_element(d.begin(), d.end()));
    EXPECT_EQ(totals.diameter_max, *std::max_element(d.begin(), d.end()));
    EXPECT_EQ(totals.aspect_ratio_min, *std::min_element(a.begin(), a.end()));
    EXPECT_EQ(totals.aspect_ratio_max, *std::max_element(a.begin(), a.end()));
  }
}

// Two contact rows swapped where rank 0's slab ends and rank 1's begins: each slab is in order
// by itself, the file is not. Every rank throws the message one rank gives for the whole file.
TEST_F(MpiCheckpoint, SlabReadRefusesContactsOutOfOrderAcrossSlabs) {
  const std::size_t n_contacts = 40;
  write_alone(sample_checkpoint(38, 30, n_contacts, 1), "swapped.h5");
  const std::size_t boundary = aniso::row_slab(n_contacts, 1, std::max(comm_.size(), 2)).first;
  if (comm_.is_root())
    aniso::test::rewrite<std::uint64_t>(path("swapped.h5"), "contacts", "particles", [&](auto& v) {
      std::swap(v[2 * (boundary - 1)], v[2 * boundary]);
      std::swap(v[2 * (boundary - 1) + 1], v[2 * boundary + 1]);
    });
  comm_.barrier();
  const std::string expected = "/contacts/particles: rows " + std::to_string(boundary - 1) + " and " +
                               std::to_string(boundary) +
                               " are not in strictly increasing (id_i, id_j) order";
  for (const auto share : {aniso::h5::RowShare::all, aniso::h5::RowShare::slab}) {
    try {
      static_cast<void>(aniso::h5::read_checkpoint(path("swapped.h5"), comm_, share));
      ADD_FAILURE() << "read a file with contacts out of order";
    } catch (const aniso::FileError& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
    }
  }
}

} // namespace
