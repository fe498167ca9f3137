#pragma once
// After a distributed read (h5::RowShare::slab) each rank holds a slab of the stored contacts,
// in file order, not the contacts of the particles the decomposition gave it. This sends each
// contact to the ranks that own either of its particles. No rank learns the whole assembly's
// owners: a particle's owner is known to the rank of its id's slab (common/row_slab.hpp), which
// forwards the contacts of that particle to it.

#include "dem/data/particles.hpp"
#include "dem/force_pass.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aniso::dem::parallel {

/// The stored contacts with at least one particle owned by this rank, in (id_i, id_j) order,
/// from `contacts`, whatever share of the stored contacts each rank passes (collective).
/// `particles` are this rank's after the decomposition (owned first); `n_particles` the
/// assembly's count, whose ids are 0 .. n_particles - 1. The contacts travel in rounds of at
/// most `batch` per rank, which bounds the buffers' memory.
std::vector<StoredContact> route_contacts(std::span<const StoredContact> contacts,
                                          const data::Particles& particles, std::int64_t n_particles,
                                          const mpi::Comm& comm, std::size_t batch = std::size_t{1} << 16);

} // namespace aniso::dem::parallel
