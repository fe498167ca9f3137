#include "dem/interop/assembly_text.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

namespace aniso::dem::interop {
namespace {

// A text file as numbered lines, with the file name for messages.
class TextLines {
public:
  explicit TextLines(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw FileError(fmt::format("{}: cannot open for reading", path));
    for (std::string line; std::getline(in, line);)
      lines_.push_back(line);
  }
  [[nodiscard]] std::size_t size() const { return lines_.size(); }
  [[nodiscard]] const std::string& operator[](std::size_t k) const { return lines_[k]; }
  [[noreturn]] void fail(std::size_t k, const std::string& what) const {
    throw FileError(fmt::format("{}: line {}: {}", path_, k + 1, what));
  }

private:
  std::string path_;
  std::vector<std::string> lines_;
};

std::string without_comment(const std::string& line) {
  return line.substr(0, line.find('#'));
}

bool blank(const std::string& line) {
  return split_words(without_comment(line)).empty();
}

template <typename T>
T number(const TextLines& lines, std::size_t k, const std::string& word, const char* what) {
  T value{};
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size())
    lines.fail(k, fmt::format("'{}' is not a number ({})", word, what));
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) lines.fail(k, fmt::format("{} is {} (not finite)", what, word));
  }
  return value;
}

// Section names of LAMMPS data files that describe molecules, force fields or other atom
// styles: nothing a granular assembly of spheres has.
const std::set<std::string>& unsupported_sections() {
  static const std::set<std::string> names{"Bonds",
                                           "Angles",
                                           "Dihedrals",
                                           "Impropers",
                                           "Ellipsoids",
                                           "Lines",
                                           "Triangles",
                                           "Bodies",
                                           "Pair Coeffs",
                                           "PairIJ Coeffs",
                                           "Bond Coeffs",
                                           "Angle Coeffs",
                                           "Dihedral Coeffs",
                                           "Improper Coeffs",
                                           "BondBond Coeffs",
                                           "BondAngle Coeffs",
                                           "MiddleBondTorsion Coeffs",
                                           "EndBondTorsion Coeffs",
                                           "AngleTorsion Coeffs",
                                           "AngleAngleTorsion Coeffs",
                                           "BondBond13 Coeffs",
                                           "AngleAngle Coeffs"};
  return names;
}

bool is_section(const std::string& line, std::string* name) {
  const std::string text = without_comment(line);
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos || !std::isupper(static_cast<unsigned char>(text[first]))) return false;
  const auto last = text.find_last_not_of(" \t\r");
  *name = text.substr(first, last - first + 1);
  return true;
}

// The header: counts and box, up to the first section line. Returns that line's index.
struct Header {
  std::size_t atoms = 0;
  std::size_t atom_types = 0;
  Vec3 low = Vec3::Zero(), high = Vec3::Zero();
  std::array<bool, 3> has_axis{false, false, false};
};

std::size_t read_header(const TextLines& lines, Header& header) {
  for (std::size_t k = 1; k < lines.size(); ++k) { // line 1 is a title, whatever it says
    std::string section;
    if (is_section(lines[k], &section)) return k;
    const std::vector<std::string> w = split_words(without_comment(lines[k]));
    if (w.empty()) continue;
    const std::string keyword = w.size() >= 2 ? w[w.size() - 2] + " " + w.back() : w.back();
    if (w.size() == 2 && w[1] == "atoms") {
      header.atoms = number<std::size_t>(lines, k, w[0], "atom count");
    } else if (w.size() == 3 && keyword == "atom types") {
      header.atom_types = number<std::size_t>(lines, k, w[0], "atom type count");
    } else if (w.size() == 4 && (keyword == "xlo xhi" || keyword == "ylo yhi" || keyword == "zlo zhi")) {
      const int axis = w[2][0] - 'x';
      header.low[axis] = number<double>(lines, k, w[0], "box lower bound");
      header.high[axis] = number<double>(lines, k, w[1], "box upper bound");
      header.has_axis[static_cast<std::size_t>(axis)] = true;
    } else if (w.size() == 6 && w[3] == "xy" && w[4] == "xz" && w[5] == "yz") {
      for (int t = 0; t < 3; ++t)
        if (number<double>(lines, k, w[static_cast<std::size_t>(t)], "tilt factor") != 0.0)
          lines.fail(k, "a triclinic (tilted) box: aniso's periodic cell is orthogonal");
    } else if (w.size() >= 2 && w[0] != "0" &&
               (w.back() == "bonds" || w.back() == "angles" || w.back() == "dihedrals" ||
                w.back() == "impropers" || w.back() == "ellipsoids" || w.back() == "lines" ||
                w.back() == "triangles" || w.back() == "bodies")) {
      lines.fail(k, fmt::format("{} {}: aniso imports granular assemblies of spheres only", w[0], w.back()));
    }
    // Other header lines (bond types, extra/... per atom) carry nothing for spheres.
  }
  return lines.size();
}

// Next non-blank line from k, or lines.size().
std::size_t skip_blank(const TextLines& lines, std::size_t k) {
  while (k < lines.size() && blank(lines[k]))
    ++k;
  return k;
}

// InputError naming the first particle that is not a sphere, and why the format needs spheres.
void require_spheres(const h5::Checkpoint& checkpoint, const std::string& why) {
  const auto& p = checkpoint.particles;
  for (std::size_t k = 0; k < p.size(); ++k)
    require_input(p.aspect_ratio[k] == 1.0, fmt::format("export: particle {} has aspect ratio {:g}: {}",
                                                        p.id[k], p.aspect_ratio[k], why));
}

} // namespace

ImportedAssembly read_lammps_data(const std::string& path) {
  const TextLines lines(path);
  if (lines.size() == 0) throw FileError(path + ": empty file: not a LAMMPS data file");
  Header header;
  std::size_t k = read_header(lines, header);
  if (header.atoms == 0) throw FileError(path + ": no 'N atoms' line in the header (or N = 0)");
  for (std::size_t axis = 0; axis < 3; ++axis)
    if (!header.has_axis[axis])
      throw FileError(fmt::format("{}: no '{}lo {}hi' line in the header: the box is needed", path,
                                  "xyz"[axis], "xyz"[axis]));
  const Vec3 lengths = header.high - header.low;
  if (!(lengths.minCoeff() > 0)) throw FileError(path + ": the box has a length <= 0");

  ImportedAssembly result;
  result.source = path;
  result.format = "lammps";
  result.lengths = lengths;
  std::map<std::uint64_t, std::size_t> row_of_id;
  std::vector<std::array<double, 6>> velocities;
  std::vector<std::uint64_t> velocity_ids;
  std::vector<std::size_t> velocity_lines;
  bool has_atoms = false;
  while (k < lines.size()) {
    std::string section;
    if (!is_section(lines[k], &section)) lines.fail(k, "expected a section name (Atoms, Velocities, ...)");
    const std::size_t title = k;
    if (unsupported_sections().count(section))
      lines.fail(k, fmt::format("section '{}': aniso imports granular assemblies of spheres only", section));
    // The atom style hint after the section name ("Atoms # sphere").
    const auto hash = lines[k].find('#');
    const std::string style = hash == std::string::npos ? ""
                              : split_words(lines[k].substr(hash + 1)).empty()
                                  ? ""
                                  : split_words(lines[k].substr(hash + 1))[0];
    std::size_t rows = 0;
    if (section == "Atoms" || section == "Velocities") {
      rows = header.atoms;
    } else if (section == "Masses") {
      rows = header.atom_types;
    } else {
      lines.fail(k, fmt::format("unknown section '{}' (aniso reads Atoms, Velocities and Masses)", section));
    }
    if (section == "Atoms" && !style.empty() && style != "sphere" && style != "granular")
      lines.fail(title, fmt::format("atom style '{}': aniso imports `atom_style sphere` or `granular` "
                                    "(id type diameter density x y z)",
                                    style));
    k = skip_blank(lines, k + 1);
    for (std::size_t r = 0; r < rows; ++r, k = skip_blank(lines, k + 1)) {
      if (k >= lines.size())
        throw FileError(fmt::format("{}: section '{}' (line {}) ends after {} of its {} rows", path, section,
                                    title + 1, r, rows));
      const std::vector<std::string> w = split_words(without_comment(lines[k]));
      if (section == "Masses") continue;
      if (section == "Atoms") {
        has_atoms = true;
        if (w.size() != 7 && w.size() != 10)
          lines.fail(k, fmt::format("{} columns; `atom_style sphere` has 7 (id type diameter density x y z) "
                                    "or 10 (with image flags)",
                                    w.size()));
        const auto id = number<std::uint64_t>(lines, k, w[0], "atom id");
        if (!row_of_id.emplace(id, result.id.size()).second)
          lines.fail(k, fmt::format("atom id {} again", id));
        const double diameter = number<double>(lines, k, w[2], "diameter");
        const double density = number<double>(lines, k, w[3], "density");
        if (!(diameter > 0))
          lines.fail(k, fmt::format("diameter {}: point particles cannot be imported", w[2]));
        if (!(density > 0)) lines.fail(k, fmt::format("density {}, expected > 0", w[3]));
        result.id.push_back(id);
        result.diameter.push_back(diameter);
        result.density.push_back(density);
        Vec3 x;
        for (int a = 0; a < 3; ++a)
          x[a] = number<double>(lines, k, w[static_cast<std::size_t>(4 + a)], "position") - header.low[a];
        result.position.push_back(x);
      } else {
        if (w.size() != 7)
          lines.fail(
              k, fmt::format("{} columns; Velocities of `atom_style sphere` have 7 (id vx vy vz wx wy wz)",
                             w.size()));
        velocity_ids.push_back(number<std::uint64_t>(lines, k, w[0], "atom id"));
        velocity_lines.push_back(k);
        std::array<double, 6> v{};
        for (std::size_t c = 0; c < 6; ++c)
          v[c] = number<double>(lines, k, w[1 + c], "velocity");
        velocities.push_back(v);
      }
    }
  }
  if (!has_atoms) throw FileError(path + ": no Atoms section");
  result.velocity.assign(result.size(), Vec3::Zero());
  result.angular_velocity.assign(result.size(), Vec3::Zero());
  std::vector<char> seen(result.size(), 0);
  for (std::size_t r = 0; r < velocities.size(); ++r) {
    const auto found = row_of_id.find(velocity_ids[r]);
    if (found == row_of_id.end())
      lines.fail(velocity_lines[r],
                 fmt::format("velocity of atom id {}, which is not in Atoms", velocity_ids[r]));
    if (seen[found->second]++)
      lines.fail(velocity_lines[r], fmt::format("atom id {} again", velocity_ids[r]));
    const auto& v = velocities[r];
    result.velocity[found->second] = Vec3(v[0], v[1], v[2]);
    result.angular_velocity[found->second] = Vec3(v[3], v[4], v[5]);
  }
  return result;
}

ImportedAssembly read_yade_text(const std::string& path, const Vec3& lengths) {
  require_input(lengths.minCoeff() > 0 && std::isfinite(lengths.sum()),
                fmt::format("import of '{}': the cell lengths must be > 0 (YADE's text export does not "
                            "carry the periodic cell: give it with --cell LX,LY,LZ)",
                            path));
  const TextLines lines(path);
  ImportedAssembly result;
  result.source = path;
  result.format = "yade";
  result.lengths = lengths;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const std::vector<std::string> w = split_words(without_comment(lines[k]));
    if (w.empty()) continue;
    if (w.size() != 4)
      lines.fail(k, fmt::format("{} columns; YADE's sphere export has 4 (x y z r)", w.size()));
    Vec3 x;
    for (std::size_t a = 0; a < 3; ++a)
      x[static_cast<int>(a)] = number<double>(lines, k, w[a], "position");
    const double radius = number<double>(lines, k, w[3], "radius");
    if (!(radius > 0)) lines.fail(k, fmt::format("radius {}, expected > 0", w[3]));
    result.id.push_back(result.id.size() + 1);
    result.diameter.push_back(2 * radius);
    result.position.push_back(x);
  }
  if (result.size() == 0) throw FileError(path + ": no spheres (expected 'x y z r' lines)");
  result.velocity.assign(result.size(), Vec3::Zero());
  result.angular_velocity.assign(result.size(), Vec3::Zero());
  return result;
}

ImportedAssembly read_dempla_dfile(const std::string& path) {
  const TextLines lines(path);
  constexpr int sphere_code = 4, ovoid_code = 5;
  const auto words_of = [&](std::size_t k, std::size_t expected, const char* what) {
    if (k >= lines.size()) lines.fail(k, fmt::format("the file ends before the {} line", what));
    const std::vector<std::string> w = split_words(lines[k]);
    if (w.size() != expected)
      lines.fail(k, fmt::format("{} words on the {} line, expected {}", w.size(), what, expected));
    return w;
  };
  const int shape = number<int>(lines, 0, words_of(0, 1, "shape code")[0], "shape code");
  if (shape != sphere_code && shape != ovoid_code)
    lines.fail(0, fmt::format("shape code {}: aniso imports DEMPLA's spheres (code 4) and ovoids (5); the 2D "
                              "and clustered shapes are not read",
                              shape));
  const bool ovoids = shape == ovoid_code;
  const std::vector<std::string> head = words_of(1, 4, "count and cell");
  const auto count = number<std::int64_t>(lines, 1, head[0], "particle count");
  if (count <= 0) lines.fail(1, fmt::format("particle count {}, expected > 0", count));
  ImportedAssembly result;
  result.source = path;
  result.format = "dempla";
  for (int a = 0; a < 3; ++a) {
    result.lengths[a] = number<double>(lines, 1, head[static_cast<std::size_t>(a) + 1], "cell length");
    if (!(result.lengths[a] > 0)) lines.fail(1, fmt::format("cell length {}, expected > 0", head[1 + a]));
  }
  for (const std::string& offset : words_of(2, 3, "cell offsets"))
    if (number<double>(lines, 2, offset, "cell offset") != 0.0)
      lines.fail(2, fmt::format("cell offset {}: aniso's periodic cell is rectangular (all three offsets "
                                "must be 0)",
                                offset));
  std::size_t k = 3;
  if (ovoids) {
    const double degrees = number<double>(lines, k, words_of(k, 1, "splice angle")[0], "splice angle");
    if (!(degrees > 0 && degrees < 90))
      lines.fail(k, fmt::format("splice angle {:g} degrees, expected between 0 and 90", degrees));
    result.splice_angle = degrees * std::numbers::pi / 180;
    ++k;
  }
  // A particle's values in order, whatever the line breaks (Fortran's list-directed read).
  const std::size_t per_particle = ovoids ? 7 : 4;
  std::vector<double> values;
  std::size_t row_line = k;
  for (; k < lines.size() && static_cast<std::int64_t>(result.size()) < count; ++k) {
    const std::vector<std::string> words = split_words(lines[k]);
    if (values.empty()) row_line = k;
    for (const std::string& word : words)
      values.push_back(number<double>(lines, k, word, ovoids ? "ovoid value" : "sphere value"));
    if (values.size() < per_particle) continue;
    if (values.size() > per_particle)
      lines.fail(k, fmt::format("{} values for one particle, expected {} ({})", values.size(), per_particle,
                                ovoids ? "half-width aspect x1 x2 x3 gamma1 gamma2" : "radius x1 x2 x3"));
    const double radius = values[0];
    if (!(radius > 0)) lines.fail(row_line, fmt::format("radius {:g}, expected > 0", radius));
    const std::size_t at = ovoids ? 2 : 1;
    result.id.push_back(result.id.size() + 1);
    result.diameter.push_back(2 * radius);
    result.position.emplace_back(values[at], values[at + 1], values[at + 2]);
    if (ovoids) {
      const double aspect = values[1];
      if (!(aspect > 0 && aspect <= 1))
        lines.fail(row_line,
                   fmt::format("aspect ratio {:g}: aniso's ovoids are oblate (0 < alpha <= 1)", aspect));
      if (result.size() == 1) result.aspect_ratio = aspect;
      if (aspect != result.aspect_ratio)
        lines.fail(row_line,
                   fmt::format("aspect ratio {:.17g} where the first particle has {:.17g}: aniso holds "
                               "one aspect ratio per assembly",
                               aspect, result.aspect_ratio));
      const double polar = values[5] * std::numbers::pi / 180, azimuth = values[6] * std::numbers::pi / 180;
      result.axis.emplace_back(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                               std::cos(polar));
    }
    values.clear();
  }
  if (!values.empty()) lines.fail(row_line, "the file ends inside a particle's row");
  if (static_cast<std::int64_t>(result.size()) < count)
    throw FileError(fmt::format("{}: {} particles, the header says {}", path, result.size(), count));
  for (; k < lines.size(); ++k)
    if (!blank(lines[k])) lines.fail(k, fmt::format("more rows than the {} particles of the header", count));
  result.velocity.assign(result.size(), Vec3::Zero());
  result.angular_velocity.assign(result.size(), Vec3::Zero());
  return result;
}

double median_by_volume(std::vector<double> diameters) {
  std::sort(diameters.begin(), diameters.end());
  double total = 0;
  for (const double d : diameters)
    total += d * d * d;
  double below = 0;
  for (const double d : diameters) {
    below += d * d * d;
    if (below >= 0.5 * total) return d;
  }
  return diameters.back();
}

ImportedAssembly scaled_to_d50(ImportedAssembly assembly, double d50) {
  require_input(d50 > 0 && std::isfinite(d50), fmt::format("import: --d50 {:g}, expected > 0 [m]", d50));
  const double factor = d50 / median_by_volume(assembly.diameter);
  assembly.lengths *= factor;
  for (std::size_t k = 0; k < assembly.size(); ++k) {
    assembly.diameter[k] *= factor;
    assembly.position[k] *= factor;
    assembly.velocity[k] *= factor;
  }
  return assembly;
}

std::vector<std::string> split_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> result;
  for (std::string word; in >> word;)
    result.push_back(word);
  return result;
}

std::vector<std::uint64_t> lammps_ids(const h5::Checkpoint& checkpoint) {
  const auto& p = checkpoint.particles;
  if (!p.source_id.empty()) return p.source_id;
  std::vector<std::uint64_t> ids(p.size());
  for (std::size_t k = 0; k < ids.size(); ++k)
    ids[k] = p.id[k] + 1;
  return ids;
}

void write_lammps_data(const std::string& path, const h5::Checkpoint& checkpoint) {
  const auto& p = checkpoint.particles;
  require_spheres(checkpoint, "a LAMMPS data file of `atom_style sphere` holds spheres only");
  const std::vector<std::uint64_t> ids = lammps_ids(checkpoint);
  const Vec3& lengths = checkpoint.cell.lengths;
  std::string text = fmt::format("LAMMPS data file (atom_style sphere) exported by aniso-dem, step {}\n\n{} "
                                 "atoms\n1 atom types\n\n",
                                 checkpoint.step, p.size());
  for (int a = 0; a < 3; ++a)
    text += fmt::format("0 {:.17g} {}lo {}hi\n", lengths[a], "xyz"[a], "xyz"[a]);
  text += "\nAtoms # sphere\n\n";
  // The assembly's density as stored (exact), not mass / volume (rounded).
  const bool stored_density = h5::has_parameter(checkpoint, h5::parameter_name::density);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double volume = std::numbers::pi / 6 * p.diameter[k] * p.diameter[k] * p.diameter[k];
    const double density =
        stored_density ? h5::parameter(checkpoint, h5::parameter_name::density, "") : p.mass[k] / volume;
    text += fmt::format("{} 1 {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", ids[k], p.diameter[k], density,
                        p.position[k].x(), p.position[k].y(), p.position[k].z());
  }
  text += "\nVelocities\n\n";
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3& v = p.velocity[k];
    const Vec3& w = p.angular_velocity[k];
    text += fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", ids[k], v.x(), v.y(), v.z(),
                        w.x(), w.y(), w.z());
  }
  h5::write_text_atomically(path, text);
}

namespace {

// DEMPLA's ovoid axis angles (its D-file, kshape 5): axis = (sin g1 cos g2, sin g1 sin g2, cos g1), in
// degrees. The axis is the body z of aniso's ovoid turned into the world frame; its sign does not
// matter (the shape is symmetric about its mid-plane).
std::pair<double, double> dempla_axis_angles(const Quat& orientation) {
  const Vec3 axis = (orientation * Vec3::UnitZ()).normalized();
  constexpr double degrees = 180.0 / std::numbers::pi;
  return {std::acos(std::clamp(axis.z(), -1.0, 1.0)) * degrees, std::atan2(axis.y(), axis.x()) * degrees};
}

} // namespace

void write_dempla_dfile(const std::string& path, const h5::Checkpoint& checkpoint) {
  const auto& p = checkpoint.particles;
  require_input(p.size() > 0, "export: the checkpoint holds no particles");
  // DEMPLA gives one aspect ratio to the whole assembly (its ovoid D-file writer says so), as aniso does.
  const double aspect = p.aspect_ratio.front();
  for (std::size_t k = 0; k < p.size(); ++k)
    require_input(
        p.aspect_ratio[k] == aspect,
        fmt::format("export: particle {} has aspect ratio {:g} and particle {} {:g}: a DEMPLA D-file "
                    "holds one aspect ratio",
                    p.id[k], p.aspect_ratio[k], p.id.front(), aspect));
  const bool spheres = aspect == 1.0;
  const Vec3& lengths = checkpoint.cell.lengths;
  // The column widths of DEMPLA's own writers (octave/Write_Dfile_Spheres.m, Write_Dfile_Ovoids.m),
  // which its reader expects: shape code 4 (spheres) or 5 (ovoids), count and cell, offsets, and for
  // ovoids the splice angle in degrees.
  std::string text =
      fmt::format("{}\n{:6d}{:25.17e}{:25.17e}{:25.17e}\n      {:25.17e}{:25.17e}{:25.17e}\n",
                  spheres ? 4 : 5, p.size(), lengths.x(), lengths.y(), lengths.z(), 0.0, 0.0, 0.0);
  if (!spheres)
    text += fmt::format("{:25.17e}\n", h5::parameter(checkpoint, h5::parameter_name::splice_angle, "") *
                                           180.0 / std::numbers::pi);
  for (std::size_t k = 0; k < p.size(); ++k) {
    Vec3 x = p.position[k];
    for (int a = 0; a < 3; ++a)
      x[a] -= lengths[a] * std::floor(x[a] / lengths[a]);
    // The radius is the mid-plane half-width for both shapes (DEMPLA's "rad").
    text += fmt::format("{:25.17e}", p.diameter[k] / 2);
    if (!spheres) text += fmt::format("{:25.17e}", aspect);
    text += fmt::format("{:25.17e}{:25.17e}{:25.17e}", x.x(), x.y(), x.z());
    if (!spheres) {
      const auto [polar, azimuth] = dempla_axis_angles(p.orientation[k]);
      text += fmt::format("{:25.17e}{:25.17e}", polar, azimuth);
    }
    text += "\n";
  }
  h5::write_text_atomically(path, text);
}

} // namespace aniso::dem::interop
