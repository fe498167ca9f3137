#include "fabric/contact_graph.hpp"

#include "common/error.hpp"

#include <algorithm>

namespace aniso::fabric {
namespace {

const Neighbour* find_partner(const std::vector<Neighbour>& list, std::uint64_t id) {
  const auto it = std::lower_bound(list.begin(), list.end(), id,
                                   [](const Neighbour& n, std::uint64_t v) { return n.id < v; });
  return (it != list.end() && it->id == id) ? &*it : nullptr;
}

Vec3 image(std::span<const Vec3> positions, const Vec3& lengths, std::uint64_t id, const Vec3i& shift) {
  return positions[id] + shift.cast<double>().cwiseProduct(lengths);
}

} // namespace

ContactGraph::ContactGraph(std::size_t n_particles, std::span<const std::array<std::uint64_t, 2>> pairs,
                           std::span<const Vec3i> shifts)
    : adjacency_(n_particles) {
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    const auto [i, j] = pairs[c];
    check_invariant(i < j && j < n_particles, "contact pair ids ordered and in range");
    adjacency_[i].push_back({j, shifts[c]});
    adjacency_[j].push_back({i, -shifts[c]});
  }
  for (auto& list : adjacency_)
    std::sort(list.begin(), list.end(), [](const Neighbour& a, const Neighbour& b) { return a.id < b.id; });
}

std::vector<bool> find_rattlers(const ContactGraph& graph, int min_contacts) {
  const std::size_t n = graph.n_particles();
  std::vector<int> degree(n);
  std::vector<bool> rattler(n, false);
  std::vector<std::uint64_t> work;
  for (std::uint64_t k = 0; k < n; ++k) {
    degree[k] = static_cast<int>(graph.partners(k).size());
    if (degree[k] < min_contacts) {
      rattler[k] = true;
      work.push_back(k);
    }
  }
  while (!work.empty()) {
    const std::uint64_t k = work.back();
    work.pop_back();
    for (const Neighbour& other : graph.partners(k)) {
      if (!rattler[other.id] && --degree[other.id] < min_contacts) {
        rattler[other.id] = true;
        work.push_back(other.id);
      }
    }
  }
  return rattler;
}

Coordination coordination(const ContactGraph& graph, std::size_t n_contacts, int min_contacts) {
  const std::size_t n = graph.n_particles();
  const std::vector<bool> rattler = find_rattlers(graph, min_contacts);
  std::int64_t kept = 0, kept_contacts = 0;
  for (std::uint64_t k = 0; k < n; ++k) {
    if (rattler[k]) continue;
    ++kept;
    for (const Neighbour& other : graph.partners(k))
      kept_contacts += (!rattler[other.id] && other.id > k) ? 1 : 0;
  }
  Coordination c;
  c.all = n ? 2.0 * static_cast<double>(n_contacts) / static_cast<double>(n) : 0.0;
  c.no_rattlers = kept ? 2.0 * static_cast<double>(kept_contacts) / static_cast<double>(kept) : 0.0;
  c.n_rattlers = static_cast<std::int64_t>(n) - kept;
  return c;
}

MultipleOverlaps count_multiple_overlaps(const ContactGraph& graph,
                                         std::span<const std::array<std::uint64_t, 2>> pairs,
                                         std::size_t begin, std::size_t end, std::span<const Vec3> positions,
                                         const Vec3& lengths, const SharePoint& share_point) {
  MultipleOverlaps counts;
  for (std::size_t c = begin; c < end; ++c) {
    const auto [i, j] = pairs[c];
    const auto& of_i = graph.partners(i);
    const Neighbour* ij = find_partner(of_i, j);
    // Third members k > j touching both i and j in one consistent periodic image.
    for (const Neighbour& ik : of_i) {
      if (ik.id <= j) continue;
      const Neighbour* jk = find_partner(graph.partners(j), ik.id);
      if (jk == nullptr || ij->shift + jk->shift != ik.shift) continue;
      const std::array<std::uint64_t, 3> ids{i, j, ik.id};
      const std::array<Vec3, 3> centres{positions[i], image(positions, lengths, j, ij->shift),
                                        image(positions, lengths, ik.id, ik.shift)};
      if (!share_point(ids, centres)) continue;
      ++counts.triples;
      // Fourth members m > k touching i, j and k; a quadruple overlap implies its triples.
      for (const Neighbour& im : of_i) {
        if (im.id <= ik.id) continue;
        const Neighbour* jm = find_partner(graph.partners(j), im.id);
        const Neighbour* km = find_partner(graph.partners(ik.id), im.id);
        if (jm == nullptr || km == nullptr) continue;
        if (ij->shift + jm->shift != im.shift || ik.shift + km->shift != im.shift) continue;
        const std::array<std::uint64_t, 4> ids4{i, j, ik.id, im.id};
        const std::array<Vec3, 4> centres4{centres[0], centres[1], centres[2],
                                           image(positions, lengths, im.id, im.shift)};
        if (share_point(ids4, centres4)) ++counts.quadruples;
      }
    }
  }
  return counts;
}

} // namespace aniso::fabric
