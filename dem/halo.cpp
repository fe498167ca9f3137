#include "dem/halo.hpp"

#include "common/error.hpp"
#include "common/exchange.hpp"

namespace aniso::dem {
namespace {

void put_vec3(ByteWriter& out, const Vec3& v) {
  out.put(v[0]);
  out.put(v[1]);
  out.put(v[2]);
}

Vec3 get_vec3(ByteReader& in) {
  const double x = in.get<double>(), y = in.get<double>(), z = in.get<double>();
  return {x, y, z};
}

void put_quat(ByteWriter& out, const Quat& q) {
  out.put(q.w());
  out.put(q.x());
  out.put(q.y());
  out.put(q.z());
}

Quat get_quat(ByteReader& in) {
  const double w = in.get<double>(), x = in.get<double>(), y = in.get<double>(), z = in.get<double>();
  return {w, x, y, z};
}

// Everything that defines a particle (forces are recomputed after every exchange).
void pack_particle(ByteWriter& out, const Particles& p, std::size_t k) {
  out.put(p.id[k]);
  out.put(p.radius[k]);
  out.put(p.aspect_ratio[k]);
  out.put(p.mass[k]);
  put_vec3(out, p.inertia[k]);
  put_vec3(out, p.position[k]);
  put_quat(out, p.orientation[k]);
  put_vec3(out, p.velocity[k]);
  put_vec3(out, p.angular_velocity[k]);
  put_vec3(out, p.force[k]);
  put_vec3(out, p.torque[k]);
}

void unpack_particle(ByteReader& in, Particles& p) {
  p.id.push_back(in.get<std::uint64_t>());
  p.radius.push_back(in.get<double>());
  p.aspect_ratio.push_back(in.get<double>());
  p.mass.push_back(in.get<double>());
  p.inertia.push_back(get_vec3(in));
  p.position.push_back(get_vec3(in));
  p.orientation.push_back(get_quat(in));
  p.velocity.push_back(get_vec3(in));
  p.angular_velocity.push_back(get_vec3(in));
  p.force.push_back(get_vec3(in));
  p.torque.push_back(get_vec3(in));
}

} // namespace

std::vector<HistoryRecord> Halo::migrate(Particles& particles, const PeriodicCell& cell, const Domain& domain,
                                         const NeighborList& neighbors) {
  const mpi::Comm& comm = domain.comm();
  const int rank = comm.rank();
  particles.truncate(particles.n_owned);
  send_lists_.clear();
  if (comm.size() == 1) return {};
  const std::size_t n_owned = particles.n_owned;
  std::vector<int> destination(n_owned, rank);
  for (std::size_t k = 0; k < n_owned; ++k) {
    destination[k] = domain.owner_of_bin(domain.bin_of(cell, particles.position[k]));
  }
  std::vector<std::vector<char>> outgoing(static_cast<std::size_t>(comm.size()));
  std::vector<std::vector<HistoryRecord>> outgoing_history(static_cast<std::size_t>(comm.size()));
  // Histories of touching pairs that involve a leaving particle go with it.
  const auto& pairs = neighbors.pairs();
  const auto& history = neighbors.history();
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    const ContactHistory& h = history[c];
    if (h.tangential_force.isZero(0.0) && !h.sliding && h.normal.isZero(0.0)) continue;
    for (const std::uint32_t k : {pairs[c].i, pairs[c].j}) {
      if (k < n_owned && destination[k] != rank) {
        outgoing_history[static_cast<std::size_t>(destination[k])].push_back(
            {particles.id[pairs[c].i], particles.id[pairs[c].j], h});
      }
    }
  }
  std::vector<std::size_t> n_leaving(static_cast<std::size_t>(comm.size()), 0);
  for (std::size_t k = 0; k < n_owned; ++k)
    n_leaving[static_cast<std::size_t>(destination[k])] += destination[k] != rank;
  for (int r = 0; r < comm.size(); ++r) {
    ByteWriter out(outgoing[static_cast<std::size_t>(r)]);
    out.put(static_cast<std::uint64_t>(n_leaving[static_cast<std::size_t>(r)]));
    if (r == rank) continue;
    for (std::size_t k = 0; k < n_owned; ++k) {
      if (destination[k] == r) pack_particle(out, particles, k);
    }
    out.put(static_cast<std::uint64_t>(outgoing_history[static_cast<std::size_t>(r)].size()));
    for (const HistoryRecord& record : outgoing_history[static_cast<std::size_t>(r)]) {
      out.put(record.id_i);
      out.put(record.id_j);
      put_vec3(out, record.history.tangential_force);
      out.put(static_cast<std::uint8_t>(record.history.sliding ? 1 : 0));
      put_vec3(out, record.history.normal);
    }
  }
  // Keep the staying particles in their order, then append the arrivals in rank order.
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n_owned; ++k) {
    if (destination[k] != rank) continue;
    if (kept != k) particles.move(kept, k);
    ++kept;
  }
  particles.n_owned = kept;
  particles.truncate(kept);
  const auto incoming = exchange_bytes(comm, outgoing);
  std::vector<HistoryRecord> arrived;
  for (int r = 0; r < comm.size(); ++r) {
    if (r == rank) continue;
    ByteReader in(incoming[static_cast<std::size_t>(r)]);
    const auto n_particles = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n_particles; ++k)
      unpack_particle(in, particles);
    const auto n_records = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n_records; ++k) {
      HistoryRecord record;
      record.id_i = in.get<std::uint64_t>();
      record.id_j = in.get<std::uint64_t>();
      record.history.tangential_force = get_vec3(in);
      record.history.sliding = in.get<std::uint8_t>() != 0;
      record.history.normal = get_vec3(in);
      arrived.push_back(record);
    }
  }
  particles.n_owned = particles.size();
  return arrived;
}

void Halo::exchange_ghosts(Particles& particles, const PeriodicCell& cell, const Domain& domain) {
  const mpi::Comm& comm = domain.comm();
  particles.truncate(particles.n_owned);
  send_lists_.assign(static_cast<std::size_t>(comm.size()), {});
  if (comm.size() == 1) return;
  for (std::uint32_t k = 0; k < particles.n_owned; ++k) {
    for (const int r : domain.ghost_ranks(domain.bin_of(cell, particles.position[k]))) {
      send_lists_[static_cast<std::size_t>(r)].push_back(k);
    }
  }
  std::vector<std::vector<char>> outgoing(static_cast<std::size_t>(comm.size()));
  for (std::size_t r = 0; r < outgoing.size(); ++r) {
    ByteWriter out(outgoing[r]);
    for (const std::uint32_t k : send_lists_[r])
      pack_particle(out, particles, k);
  }
  const auto incoming = exchange_bytes(comm, outgoing);
  for (const auto& buffer : incoming) {
    ByteReader in(buffer);
    while (!in.done())
      unpack_particle(in, particles);
  }
}

void Halo::update_ghosts(Particles& particles, const Domain& domain) {
  const mpi::Comm& comm = domain.comm();
  if (comm.size() == 1) return;
  std::vector<std::vector<char>> outgoing(static_cast<std::size_t>(comm.size()));
  for (std::size_t r = 0; r < outgoing.size(); ++r) {
    ByteWriter out(outgoing[r]);
    for (const std::uint32_t k : send_lists_[r]) {
      put_vec3(out, particles.position[k]);
      put_quat(out, particles.orientation[k]);
      put_vec3(out, particles.velocity[k]);
      put_vec3(out, particles.angular_velocity[k]);
    }
  }
  const auto incoming = exchange_bytes(comm, outgoing);
  // Ghosts sit after the owned particles in the order exchange_ghosts appended them: by source rank.
  std::size_t ghost = particles.n_owned;
  for (const auto& buffer : incoming) {
    ByteReader in(buffer);
    while (!in.done()) {
      particles.position[ghost] = get_vec3(in);
      particles.orientation[ghost] = get_quat(in);
      particles.velocity[ghost] = get_vec3(in);
      particles.angular_velocity[ghost] = get_vec3(in);
      ++ghost;
    }
  }
  check_invariant(ghost == particles.size(), "every ghost refreshed");
}

} // namespace aniso::dem
