#include "dem/parallel/contact_routing.hpp"

#include "common/error.hpp"
#include "common/exchange.hpp"
#include "common/row_slab.hpp"
#include "dem/parallel/pack.hpp"

#include <algorithm>

namespace aniso::dem::parallel {

namespace {

void put_contact(ByteWriter& out, const StoredContact& contact) {
  out.put(contact.ids);
  put_vec3(out, contact.normal);
  put_vec3(out, contact.point);
  out.put(contact.overlap);
  put_vec3(out, contact.force);
  put_vec3(out, contact.tangential_force);
  out.put(static_cast<std::uint8_t>(contact.sliding ? 1 : 0));
}

StoredContact get_contact(ByteReader& in) {
  StoredContact contact;
  contact.ids = in.get<std::array<std::uint64_t, 2>>();
  contact.normal = get_vec3(in);
  contact.point = get_vec3(in);
  contact.overlap = in.get<double>();
  contact.force = get_vec3(in);
  contact.tangential_force = get_vec3(in);
  contact.sliding = in.get<std::uint8_t>() != 0;
  return contact;
}

} // namespace

std::vector<StoredContact> route_contacts(std::span<const StoredContact> contacts,
                                          const data::Particles& particles, std::int64_t n_particles,
                                          const mpi::Comm& comm, std::size_t batch) {
  const int n_ranks = comm.size();
  const auto total = static_cast<std::uint64_t>(n_particles);
  const RowSlab slab = row_slab(total, comm.rank(), n_ranks);
  const auto slab_rank = [&](std::uint64_t id) { return rank_of_row(total, id, n_ranks); };
  const auto outgoing = [&] { return std::vector<std::vector<char>>(static_cast<std::size_t>(n_ranks)); };

  // 1. Each owned id to the rank of its slab, which then knows every owner of its slab.
  auto ids_out = outgoing();
  for (std::size_t k = 0; k < particles.n_owned; ++k) {
    ByteWriter out(ids_out[static_cast<std::size_t>(slab_rank(particles.id[k]))]);
    out.put(particles.id[k]);
  }
  std::vector<int> owner(slab.count, -1);
  const auto ids_in = exchange_bytes(comm, ids_out);
  for (int rank = 0; rank < n_ranks; ++rank) {
    ByteReader in(ids_in[static_cast<std::size_t>(rank)]);
    while (!in.done())
      owner[in.get<std::uint64_t>() - slab.first] = rank;
  }
  check_invariant(std::find(owner.begin(), owner.end(), -1) == owner.end(),
                  "route_contacts: every particle is owned by one rank");

  // 2. Each contact to the slab ranks of its two ids (once where they are the same rank), and 3.
  // from there on to the owners of the ids in the slab (once per owner). In rounds of at most
  // `batch` contacts per rank: the buffers hold a contact in up to five copies (packed, sent,
  // received, unpacked, forwarded), which for all contacts at once outgrew the neighbour list
  // beside them (measured on 960,000 spheres, 2 ranks).
  const auto my_rounds = static_cast<std::int64_t>((contacts.size() + batch - 1) / batch);
  const std::int64_t rounds = comm.max(my_rounds);
  std::vector<StoredContact> routed;
  for (std::int64_t round = 0; round < rounds; ++round) {
    const std::size_t begin = std::min(contacts.size(), static_cast<std::size_t>(round) * batch);
    const std::size_t end = std::min(contacts.size(), begin + batch);
    auto to_slabs = outgoing();
    for (const StoredContact& contact : contacts.subspan(begin, end - begin)) {
      const int first = slab_rank(contact.ids[0]), second = slab_rank(contact.ids[1]);
      ByteWriter to_first(to_slabs[static_cast<std::size_t>(first)]);
      put_contact(to_first, contact);
      if (second == first) continue;
      ByteWriter to_second(to_slabs[static_cast<std::size_t>(second)]);
      put_contact(to_second, contact);
    }
    const auto at_slabs = exchange_bytes(comm, to_slabs);
    to_slabs.clear();
    auto to_owners = outgoing();
    for (const auto& buffer : at_slabs) {
      ByteReader in(buffer);
      while (!in.done()) {
        const StoredContact contact = get_contact(in);
        int sent_to = -1;
        for (const std::uint64_t id : contact.ids) {
          if (id < slab.first || id >= slab.end()) continue;
          const int rank = owner[id - slab.first];
          if (rank == sent_to) continue;
          ByteWriter out(to_owners[static_cast<std::size_t>(rank)]);
          put_contact(out, contact);
          sent_to = rank;
        }
      }
    }
    for (const auto& buffer : exchange_bytes(comm, to_owners)) {
      ByteReader in(buffer);
      while (!in.done())
        routed.push_back(get_contact(in));
    }
  }

  // A contact whose ids lie in two slabs reaches a common owner twice: keep one.
  const auto by_ids = [](const StoredContact& a, const StoredContact& b) { return a.ids < b.ids; };
  std::sort(routed.begin(), routed.end(), by_ids);
  routed.erase(std::unique(routed.begin(), routed.end(),
                           [](const StoredContact& a, const StoredContact& b) { return a.ids == b.ids; }),
               routed.end());
  return routed;
}

} // namespace aniso::dem::parallel
