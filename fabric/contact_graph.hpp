#pragma once
// The contact network as a graph on particle ids: coordination with and without rattlers,
// and the triple and quadruple overlaps (cliques of 3 and 4 mutually touching particles
// whose bodies share a point) that enter the void's Euler characteristic on the 3-torus.

#include "common/tensor.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace aniso::fabric {

/// A partner of a particle and the periodic image of the partner relative to it.
struct Neighbour {
  std::uint64_t id;
  Vec3i shift; ///< in cell lengths: partner centre = its stored position + shift * L
};

class ContactGraph {
public:
  /// pairs[c] = (i, j) with i < j < n_particles, shifts[c] the image of j relative to i.
  ContactGraph(std::size_t n_particles, std::span<const std::array<std::uint64_t, 2>> pairs,
               std::span<const Vec3i> shifts);
  [[nodiscard]] std::size_t n_particles() const { return adjacency_.size(); }
  /// Partners of a particle, by increasing id.
  [[nodiscard]] const std::vector<Neighbour>& partners(std::uint64_t id) const { return adjacency_[id]; }

private:
  std::vector<std::vector<Neighbour>> adjacency_;
};

/// Rattlers: particles with fewer than min_contacts contacts, removed repeatedly (removing one
/// lowers its partners' counts) until every remaining particle has at least min_contacts.
std::vector<bool> find_rattlers(const ContactGraph& graph, int min_contacts);

struct Coordination {
  double all = 0;         ///< 2 N_c / N_p
  double no_rattlers = 0; ///< 2 N_c' / N_p' over the non-rattlers and the contacts among them
  std::int64_t n_rattlers = 0;
};
Coordination coordination(const ContactGraph& graph, std::size_t n_contacts, int min_contacts);

/// Decides whether particles (by id) share a point, given their centres in one periodic image.
using SharePoint = std::function<bool(std::span<const std::uint64_t> ids, std::span<const Vec3> centres)>;

struct MultipleOverlaps {
  std::int64_t triples = 0;    ///< N_3
  std::int64_t quadruples = 0; ///< N_4
};

/// Counts the triples and quadruples whose lowest-id edge is one of pairs[begin, end), so that
/// disjoint ranges over ranks add up to the whole count. positions: stored centres; lengths: cell.
MultipleOverlaps count_multiple_overlaps(const ContactGraph& graph,
                                         std::span<const std::array<std::uint64_t, 2>> pairs,
                                         std::size_t begin, std::size_t end, std::span<const Vec3> positions,
                                         const Vec3& lengths, const SharePoint& share_point);

} // namespace aniso::fabric
