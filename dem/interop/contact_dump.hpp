#pragma once
// Contact forces in LAMMPS' `dump local` text format: how a static state's tangential forces
// (the Mindlin history, which positions alone do not give) travel between aniso and other codes.

#include "common/h5/checkpoint.hpp"
#include "common/tensor.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::dem::interop {

/// One dumped contact: the two particles' ids in the source file and the tangential force on
/// the first of them from the second [N].
struct DumpedContact {
  std::uint64_t id_i = 0;
  std::uint64_t id_j = 0;
  Vec3 tangential_force = Vec3::Zero();
};

/// Which columns (1-based) of the dump's entries hold what. A negative `tangential` column says
/// the dumped force acts on the particle of the second id column (the sign is turned).
/// aniso's own export: 1, 2, 6 (id1 id2 fnx fny fnz ftx fty ftz). LIGGGHTS'
/// `compute pair/gran/local id force_tangential`: 1, 2, 4 (id1 id2 periodic-flag ftx fty ftz).
struct ContactColumns {
  int id_i = 1;
  int id_j = 2;
  int tangential = 6; ///< the first of three (x, y, z)
};

/// Parses "I,J,T" (the options' spelling); InputError naming the text if it is not three
/// distinct non-zero integers with I, J > 0.
ContactColumns parse_contact_columns(const std::string& text);

/// Reads the entries of a `dump local` file (the ITEM: ENTRIES block of its first snapshot).
/// FileError naming the file and line on a short row, a non-number or a pair given twice.
std::vector<DumpedContact> read_contact_dump(const std::string& path, const ContactColumns& columns);

/// Writes every contact of a whole checkpoint as a `dump local` snapshot with entries
/// `id1 id2 fnx fny fnz ftx fty ftz`: the normal and tangential parts of the force on id1
/// from id2 [N], ids as write_lammps_data gives them.
void write_contact_dump(const std::string& path, const h5::Checkpoint& checkpoint);

} // namespace aniso::dem::interop
