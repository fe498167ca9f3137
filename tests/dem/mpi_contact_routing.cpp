// route_contacts (run on 1, 2 and 3 ranks): particles owned in a scattered pattern, contacts
// handed out in file slabs; every rank must end with exactly the contacts that touch a particle
// it owns, each once, in (id_i, id_j) order, with every field as stored.
#include "common/mpi.hpp"
#include "common/row_slab.hpp"
#include "dem/parallel/contact_routing.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace {

using aniso::Vec3;
using aniso::dem::StoredContact;

constexpr std::uint64_t n_particles = 97;

int owner_of(std::uint64_t id, int ranks) {
  return static_cast<int>((id * 7 + id / 5) % static_cast<std::uint64_t>(ranks));
}

// Every pair (i, j) with j - i in {1, 2, 13} (a few hundred contacts, ids spread over all slabs).
std::vector<StoredContact> all_contacts() {
  std::vector<StoredContact> contacts;
  for (std::uint64_t i = 0; i < n_particles; ++i)
    for (const std::uint64_t gap : {1, 2, 13}) {
      if (i + gap >= n_particles) continue;
      StoredContact c;
      c.ids = {i, i + gap};
      const auto x = static_cast<double>(i), y = static_cast<double>(gap);
      c.normal = Vec3(x, y, 1.0).normalized();
      c.point = Vec3(0.1 * x, 0.2 * y, 0.3);
      c.overlap = 1e-6 * (x + y);
      c.force = Vec3(x, -y, x * y);
      c.tangential_force = Vec3(-x, y, 0.5);
      c.sliding = (i + gap) % 3 == 0;
      contacts.push_back(c);
    }
  return contacts;
}

TEST(ContactRouting, EachRankGetsTheContactsOfItsParticles) {
  const aniso::mpi::Comm comm = aniso::mpi::Comm::world();
  const int rank = comm.rank(), ranks = comm.size();
  aniso::dem::data::Particles particles;
  for (std::uint64_t id = 0; id < n_particles; ++id) {
    if (owner_of(id, ranks) != rank) continue;
    particles.resize(particles.size() + 1);
    particles.id.back() = id;
  }
  const std::size_t n_owned = particles.size();
  // A ghost (another rank's particle) must not draw contacts here.
  const std::uint64_t ghost = owner_of(0, ranks) == rank ? 1 : 0;
  if (ranks > 1 && owner_of(ghost, ranks) != rank) {
    particles.resize(particles.size() + 1);
    particles.id.back() = ghost;
  }
  particles.n_owned = n_owned;
  const std::vector<StoredContact> all = all_contacts();
  const aniso::RowSlab slab = aniso::row_slab(all.size(), rank, ranks);
  const std::vector<StoredContact> mine(all.begin() + static_cast<std::ptrdiff_t>(slab.first),
                                        all.begin() + static_cast<std::ptrdiff_t>(slab.end()));

  // In rounds of 7 contacts per rank (ranks run out of contacts at different rounds), and at once.
  for (const std::size_t batch : {std::size_t{7}, std::size_t{1} << 16}) {
    const std::vector<StoredContact> routed = aniso::dem::parallel::route_contacts(
        mine, particles, static_cast<std::int64_t>(n_particles), comm, batch);

    std::vector<StoredContact> expected;
    for (const StoredContact& c : all)
      if (owner_of(c.ids[0], ranks) == rank || owner_of(c.ids[1], ranks) == rank) expected.push_back(c);
    ASSERT_EQ(routed.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      const StoredContact &a = expected[k], &b = routed[k];
      EXPECT_EQ(a.ids, b.ids);
      EXPECT_EQ(a.normal, b.normal);
      EXPECT_EQ(a.point, b.point);
      EXPECT_EQ(a.overlap, b.overlap);
      EXPECT_EQ(a.force, b.force);
      EXPECT_EQ(a.tangential_force, b.tangential_force);
      EXPECT_EQ(a.sliding, b.sliding);
    }
    // Over all ranks a contact arrives once per rank owning one of its particles.
    std::int64_t owners = 0;
    for (const StoredContact& c : all)
      owners += owner_of(c.ids[0], ranks) == owner_of(c.ids[1], ranks) ? 1 : 2;
    EXPECT_EQ(comm.sum(static_cast<std::int64_t>(routed.size())), owners);
  }
}

} // namespace
