#include "dem/parallel/halo.hpp"

#include "common/error.hpp"
#include "common/exchange.hpp"
#include "dem/parallel/pack.hpp"

#include <algorithm>

namespace aniso::dem::parallel {
namespace {

// What changes from step to step: position, orientation, velocity and angular velocity.
constexpr std::size_t ghost_state_size = 3 + 4 + 3 + 3;

double* put_ghost_state(double* out, const data::Particles& p, std::size_t k) {
  const Vec3& x = p.position[k];
  const Quat& q = p.orientation[k];
  const Vec3& v = p.velocity[k];
  const Vec3& w = p.angular_velocity[k];
  for (const double value :
       {x[0], x[1], x[2], q.w(), q.x(), q.y(), q.z(), v[0], v[1], v[2], w[0], w[1], w[2]})
    *out++ = value;
  return out;
}

void get_ghost_state(const double* in, data::Particles& p, std::size_t k) {
  p.position[k] = Vec3(in[0], in[1], in[2]);
  p.orientation[k] = Quat(in[3], in[4], in[5], in[6]);
  p.velocity[k] = Vec3(in[7], in[8], in[9]);
  p.angular_velocity[k] = Vec3(in[10], in[11], in[12]);
}

// Everything that defines a particle (forces are recomputed after every exchange).
void pack_particle(ByteWriter& out, const data::Particles& p, std::size_t k) {
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

void unpack_particle(ByteReader& in, data::Particles& p) {
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

std::vector<data::HistoryRecord> Halo::migrate(data::Particles& particles, const PeriodicCell& cell,
                                               const Domain& domain, const data::NeighborList& neighbors) {
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
  std::vector<std::vector<data::HistoryRecord>> outgoing_history(static_cast<std::size_t>(comm.size()));
  // Histories of touching pairs that involve a leaving particle go with it.
  const auto& pairs = neighbors.pairs();
  const auto& history = neighbors.history();
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    const model::ContactHistory& h = history[c];
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
    for (const data::HistoryRecord& record : outgoing_history[static_cast<std::size_t>(r)]) {
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
  std::vector<data::HistoryRecord> arrived;
  for (int r = 0; r < comm.size(); ++r) {
    if (r == rank) continue;
    ByteReader in(incoming[static_cast<std::size_t>(r)]);
    const auto n_particles = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n_particles; ++k)
      unpack_particle(in, particles);
    const auto n_records = in.get<std::uint64_t>();
    for (std::uint64_t k = 0; k < n_records; ++k) {
      data::HistoryRecord record;
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

void Halo::exchange_ghosts(data::Particles& particles, const PeriodicCell& cell, const Domain& domain) {
  const mpi::Comm& comm = domain.comm();
  particles.truncate(particles.n_owned);
  const auto n_ranks = static_cast<std::size_t>(comm.size());
  send_lists_.assign(n_ranks, {});
  if (comm.size() == 1) return;
  for (std::uint32_t k = 0; k < particles.n_owned; ++k) {
    for (const int r : domain.ghost_ranks(domain.bin_of(cell, particles.position[k]))) {
      send_lists_[static_cast<std::size_t>(r)].push_back(k);
    }
  }
  std::vector<std::vector<char>> outgoing(n_ranks);
  for (std::size_t r = 0; r < outgoing.size(); ++r) {
    ByteWriter out(outgoing[r]);
    for (const std::uint32_t k : send_lists_[r])
      pack_particle(out, particles, k);
  }
  const auto incoming = exchange_bytes(comm, outgoing);
  std::vector<std::size_t> send_counts(n_ranks), receive_counts(n_ranks);
  for (std::size_t r = 0; r < n_ranks; ++r) {
    const std::size_t before = particles.size();
    ByteReader in(incoming[r]);
    while (!in.done())
      unpack_particle(in, particles);
    receive_counts[r] = (particles.size() - before) * ghost_state_size;
    send_counts[r] = send_lists_[r].size() * ghost_state_size;
  }
  refresh_.resize(comm, send_counts, receive_counts);
}

void Halo::update_ghosts(data::Particles& particles, const Domain& domain) {
  const mpi::Comm& comm = domain.comm();
  if (comm.size() == 1) return;
  for (int r = 0; r < comm.size(); ++r) {
    double* out = refresh_.outgoing(r).data();
    for (const std::uint32_t k : send_lists_[static_cast<std::size_t>(r)])
      out = put_ghost_state(out, particles, k);
  }
  refresh_.exchange(comm);
  // Ghosts sit after the owned particles in the order exchange_ghosts appended them: by source rank.
  std::size_t ghost = particles.n_owned;
  for (int r = 0; r < comm.size(); ++r) {
    const std::span<const double> in = refresh_.incoming(r);
    for (std::size_t at = 0; at < in.size(); at += ghost_state_size)
      get_ghost_state(in.data() + at, particles, ghost++);
  }
  check_invariant(ghost == particles.size(), "every ghost refreshed");
}

std::size_t Halo::n_sent() const {
  std::size_t sent = 0;
  for (const auto& list : send_lists_)
    sent += list.size();
  return sent;
}

int Halo::n_partners() const {
  return static_cast<int>(std::ranges::count_if(send_lists_, [](const auto& list) { return !list.empty(); }));
}

std::size_t Halo::state_bytes() {
  return ghost_state_size * sizeof(double);
}

} // namespace aniso::dem::parallel
