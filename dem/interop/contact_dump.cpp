#include "dem/interop/contact_dump.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "dem/interop/assembly_text.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace aniso::dem::interop {
namespace {

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

} // namespace

ContactColumns parse_contact_columns(const std::string& text) {
  std::vector<int> values;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    int value = 0;
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    require_input(error == std::errc() && end == item.data() + item.size(),
                  fmt::format("--contact-columns '{}': '{}' is not an integer", text, item));
    values.push_back(value);
  }
  require_input(
      values.size() == 3 && values[0] > 0 && values[1] > 0 && values[2] != 0 && values[0] != values[1] &&
          std::abs(values[2]) != values[0] && std::abs(values[2]) != values[1],
      fmt::format("--contact-columns '{}': expected I,J,T: the 1-based columns of the two ids and of "
                  "the first tangential force component (negative: the force on the second id), "
                  "all different",
                  text));
  return {values[0], values[1], values[2]};
}

std::vector<DumpedContact> read_contact_dump(const std::string& path, const ContactColumns& columns) {
  std::ifstream in(path);
  if (!in) throw FileError(fmt::format("{}: cannot open for reading", path));
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw FileError(fmt::format("{}: line {}: {}", path, line, what));
  };
  std::string text;
  std::size_t line = 0;
  bool in_entries = false;
  std::vector<DumpedContact> contacts;
  std::set<std::pair<std::uint64_t, std::uint64_t>> pairs;
  const int first_force = std::abs(columns.tangential);
  const auto needed = static_cast<std::size_t>(std::max({columns.id_i, columns.id_j, first_force + 2}));
  while (std::getline(in, text)) {
    ++line;
    if (starts_with(text, "ITEM:")) {
      if (in_entries) break; // the first snapshot only
      in_entries = starts_with(text, "ITEM: ENTRIES");
      continue;
    }
    if (!in_entries) continue;
    const std::vector<std::string> w = split_words(text);
    if (w.empty()) continue;
    if (w.size() < needed)
      fail(line, fmt::format("{} columns, --contact-columns needs {}", w.size(), needed));
    const auto id = [&](int column) {
      std::uint64_t value = 0;
      const std::string& word = w[static_cast<std::size_t>(column - 1)];
      // Dumps print ids as integers, some as reals ("12.0"); both are exact.
      double real = 0;
      const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), real);
      if (error != std::errc() || end != word.data() + word.size() || !(real >= 1) ||
          real != std::floor(real))
        fail(line, fmt::format("column {}: '{}' is not a particle id", column, word));
      value = static_cast<std::uint64_t>(real);
      return value;
    };
    DumpedContact contact;
    contact.id_i = id(columns.id_i);
    contact.id_j = id(columns.id_j);
    for (int a = 0; a < 3; ++a) {
      const std::string& word = w[static_cast<std::size_t>(first_force - 1 + a)];
      double value = 0;
      const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
      if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value))
        fail(line, fmt::format("column {}: '{}' is not a finite force", first_force + a, word));
      contact.tangential_force[a] = columns.tangential > 0 ? value : -value;
    }
    if (contact.id_i == contact.id_j)
      fail(line, fmt::format("a contact of particle {} with itself", contact.id_i));
    if (!pairs.emplace(std::min(contact.id_i, contact.id_j), std::max(contact.id_i, contact.id_j)).second)
      fail(line, fmt::format("contact ({}, {}) again", contact.id_i, contact.id_j));
    contacts.push_back(contact);
  }
  if (!in_entries && contacts.empty())
    throw FileError(path + ": no 'ITEM: ENTRIES' block: not a LAMMPS `dump local` file");
  return contacts;
}

void write_contact_dump(const std::string& path, const h5::Checkpoint& checkpoint) {
  const std::vector<std::uint64_t> ids = lammps_ids(checkpoint);
  const auto& c = checkpoint.contacts;
  const Vec3& lengths = checkpoint.cell.lengths;
  std::string text =
      fmt::format("ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ENTRIES\n{}\nITEM: BOX BOUNDS pp pp pp\n",
                  checkpoint.step, c.size());
  for (int a = 0; a < 3; ++a)
    text += fmt::format("0 {:.17g}\n", lengths[a]);
  text += "ITEM: ENTRIES id1 id2 fnx fny fnz ftx fty ftz\n";
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Vec3& n = c.normal[k];
    const Vec3 normal_part = c.force[k].dot(n) * n;
    const Vec3& t = c.tangential_force[k];
    text += fmt::format("{} {} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", ids[c.particles[k][0]],
                        ids[c.particles[k][1]], normal_part.x(), normal_part.y(), normal_part.z(), t.x(),
                        t.y(), t.z());
  }
  h5::write_text_atomically(path, text);
}

} // namespace aniso::dem::interop
