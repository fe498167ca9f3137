#include "dem/interop/replicate.hpp"

#include "common/error.hpp"
#include "common/h5/content_hash.hpp"
#include "common/memory.hpp"
#include "dem/interop/import.hpp"
#include "dem/interop/transfer_commands.hpp"
#include "dem/io/checkpoint.hpp"
#include "dem/io/parameters.hpp"
#include "dem/protocol/load.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <optional>
#include <string_view>

namespace aniso::dem::interop {
namespace {

// Root attributes beyond those of h5::write_checkpoint that a tiled checkpoint carries unchanged:
// each describes the state, which the copies repeat (docs/formats/checkpoint.md).
constexpr std::array<std::string_view, 2> carried_int64_attributes{"static_held_steps",
                                                                   protocol::relaxed_copy_attribute};
constexpr std::string_view carried_flag_attribute = "static_verified";
// The provenance of a replication, written anew by each one.
constexpr std::string_view from_attribute = io::replicated_from_attribute;
constexpr std::string_view from_hash_attribute = "replicated_from_hash";
constexpr std::string_view copies_attribute = "replicate_copies";
// What h5::write_checkpoint itself writes at the root.
constexpr std::array<std::string_view, 14> written_attributes{"schema",
                                                              "schema_version",
                                                              "description",
                                                              "time",
                                                              "time_units",
                                                              "step",
                                                              "step_units",
                                                              "time_step",
                                                              "time_step_units",
                                                              "unbalanced_force_ratio",
                                                              "unbalanced_force_ratio_units",
                                                              "kinetic_elastic_ratio",
                                                              "kinetic_elastic_ratio_units",
                                                              "run_id"};

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// A coordinate moved by `shift` old cell lengths (0 <= shift < n) into the tiled cell [0, n L):
// unchanged for shift 0; a sum that rounds onto n L wraps to the cell's start.
double moved_coordinate(double x, std::int64_t shift, double length, double tiled_length) {
  if (shift == 0) return x;
  const double y = x + static_cast<double>(shift) * length;
  return y >= tiled_length ? y - tiled_length : y;
}

struct Tiling {
  Copies n;
  Vec3 length;       // the original cell's
  Vec3 tiled_length; // n .* length
  std::uint64_t count = 0;

  [[nodiscard]] std::int64_t copies() const { return n[0] * n[1] * n[2]; }
  [[nodiscard]] std::uint64_t index(const Copies& c) const {
    return static_cast<std::uint64_t>(c[0] + n[0] * (c[1] + n[1] * c[2]));
  }
  [[nodiscard]] Copies copy(std::int64_t index) const {
    return {index % n[0], (index / n[0]) % n[1], index / (n[0] * n[1])};
  }
  [[nodiscard]] Vec3 moved(const Vec3& x, const Copies& shift) const {
    Vec3 y;
    for (int a = 0; a < 3; ++a)
      y[a] = moved_coordinate(x[a], shift[a], length[a], tiled_length[a]);
    return y;
  }
};

void tile_particles(const h5::ParticleRows& p, const Tiling& tiling, h5::ParticleRows& out) {
  const std::size_t n = p.size();
  out.resize(n * static_cast<std::size_t>(tiling.copies()));
  out.source_id = tiling.copies() == 1 ? p.source_id : std::vector<std::uint64_t>{};
  for (std::int64_t c = 0; c < tiling.copies(); ++c) {
    const Copies shift = tiling.copy(c);
    const std::size_t first = static_cast<std::size_t>(c) * n;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t row = first + k;
      out.id[row] = p.id[k] + first;
      out.diameter[row] = p.diameter[k];
      out.aspect_ratio[row] = p.aspect_ratio[k];
      out.mass[row] = p.mass[k];
      out.inertia[row] = p.inertia[k];
      out.position[row] = tiling.moved(p.position[k], shift);
      out.orientation[row] = p.orientation[k];
      out.velocity[row] = p.velocity[k];
      out.angular_velocity[row] = p.angular_velocity[k];
      out.force[row] = p.force[k];
      out.torque[row] = p.torque[k];
    }
  }
}

// The branch vector from a to b that the contact's image shift gives must lie within the reach of
// a contact (the two bounding radii, the mid-plane radii also of ovoids): otherwise the shift does
// not say which copy of b is a's neighbour.
void check_branch(const h5::Checkpoint& original, std::size_t row, const std::string& path) {
  const auto& p = original.particles;
  const auto [a, b] = original.contacts.particles[row];
  const Vec3i& s = original.contacts.image_shift[row];
  const Vec3 branch = p.position[b] - p.position[a] + s.cast<double>().cwiseProduct(original.cell.lengths);
  const double reach = 0.5 * (p.diameter[a] + p.diameter[b]);
  require_file(branch.norm() <= reach * (1 + 1e-9),
               fmt::format("{}: /contacts/image_shift: contact ({}, {}) at row {}: shift ({}, {}, {}) puts "
                           "particle {} {:.6g} m from particle {}, beyond the reach {:.6g} m of a contact "
                           "(the image shift does not match the positions)",
                           path, a, b, row, s[0], s[1], s[2], b, branch.norm(), a, reach));
}

template <class T> void permute(std::vector<T>& values, const std::vector<std::size_t>& order) {
  std::vector<T> sorted;
  sorted.reserve(order.size());
  for (const std::size_t k : order)
    sorted.push_back(values[k]);
  values = std::move(sorted);
}

void tile_contacts(const h5::Checkpoint& original, const Tiling& tiling, h5::ContactRows& out) {
  const h5::ContactRows& in = original.contacts;
  const auto& positions = original.particles.position;
  const std::size_t m = in.size();
  out.resize(0);
  for (std::int64_t c = 0; c < tiling.copies(); ++c) {
    const Copies copy_a = tiling.copy(c);
    for (std::size_t k = 0; k < m; ++k) {
      const auto [a, b] = in.particles[k];
      Copies copy_b{};
      Vec3i shift;
      Copies point_shift{};
      for (int axis = 0; axis < 3; ++axis) {
        const std::int64_t n = tiling.n[axis];
        const std::int64_t reached = copy_a[axis] + in.image_shift[k][axis];
        shift[axis] = static_cast<int>(floor_div(reached, n));
        copy_b[axis] = reached - n * shift[axis];
        // The stored point is wrapped into the original cell, `wrapped` lengths away from where
        // a's own centre reaches it; a's copy in copy_a reaches it in copy (copy_a - wrapped) mod n.
        const auto wrapped = static_cast<std::int64_t>(
            std::nearbyint((in.point[k][axis] - positions[a][axis]) / tiling.length[axis]));
        const std::int64_t to_copy = copy_a[axis] - wrapped;
        point_shift[axis] = to_copy - n * floor_div(to_copy, n);
      }
      const std::uint64_t id_a = a + tiling.index(copy_a) * tiling.count;
      const std::uint64_t id_b = b + tiling.index(copy_b) * tiling.count;
      const double sign = id_a < id_b ? 1.0 : -1.0; // stored from the lower id's side
      out.particles.push_back({std::min(id_a, id_b), std::max(id_a, id_b)});
      out.image_shift.push_back(id_a < id_b ? shift : Vec3i(-shift));
      out.normal.push_back(sign * in.normal[k]);
      out.point.push_back(tiling.moved(in.point[k], point_shift));
      out.overlap.push_back(in.overlap[k]);
      out.force.push_back(sign * in.force[k]);
      out.tangential_force.push_back(sign * in.tangential_force[k]);
      out.sliding.push_back(in.sliding[k]);
    }
  }
  std::vector<std::size_t> order(out.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return out.particles[x] < out.particles[y]; });
  permute(out.particles, order);
  permute(out.image_shift, order);
  permute(out.normal, order);
  permute(out.point, order);
  permute(out.overlap, order);
  permute(out.force, order);
  permute(out.tangential_force, order);
  permute(out.sliding, order);
}

// The root attributes of `path` that the tiled file carries, after refusing what cannot be tiled:
// a relaxation stopped on SIGTERM (its /relaxation group continues one run, with --resume), a
// piece of a prepare (its /prepare group holds the cell's volume), or an attribute whose meaning
// for the copies is not known here.
struct CarriedAttributes {
  std::vector<std::pair<std::string, std::int64_t>> int64;
  std::optional<std::uint8_t> flag;
};

CarriedAttributes tileable_root(const std::string& path) {
  const h5::File file = h5::File::open(path);
  require_input(!file.has_child("relaxation"),
                fmt::format("replicate: '{}' holds a relaxation stopped on SIGTERM (/relaxation): continue "
                            "it with --resume and replicate the file that run writes",
                            path));
  require_input(!file.has_child("prepare"),
                fmt::format("replicate: '{}' is a piece of an unfinished prepare (/prepare): replicate the "
                            "prepared.h5 that prepare writes",
                            path));
  CarriedAttributes carried;
  for (const std::string& name : file.attribute_names()) {
    const auto among = [&](const auto& names) { return std::ranges::find(names, name) != names.end(); };
    if (among(written_attributes) || name == from_attribute || name == from_hash_attribute ||
        name == copies_attribute)
      continue;
    if (among(carried_int64_attributes)) {
      carried.int64.emplace_back(name, file.read_attribute<std::int64_t>(name));
    } else if (name == carried_flag_attribute) {
      carried.flag = file.read_attribute<std::uint8_t>(name);
    } else {
      throw InputError(
          fmt::format("replicate: '{}' has the root attribute '{}', which replicate does not know "
                      "how to carry into copies (docs/formats/checkpoint.md lists those it does)",
                      path, name));
    }
  }
  return carried;
}

} // namespace

Copies parse_copies(const std::string& text) {
  Copies copies{};
  std::string_view rest = text;
  std::size_t given = 0;
  bool valid = true;
  while (valid) {
    const std::size_t comma = rest.find(',');
    const std::string_view word = rest.substr(0, comma);
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    valid =
        given < 3 && !word.empty() && error == std::errc() && end == word.data() + word.size() && value >= 1;
    if (valid) copies[given++] = value;
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  require_input(valid && given == 3,
                fmt::format("replicate: --copies '{}': expected three whole numbers n1,n2,n3, each >= 1 (the "
                            "copies of the cell along x, y and z, e.g. 2,2,2)",
                            text));
  return copies;
}

h5::Checkpoint replicate_checkpoint(const h5::Checkpoint& original, const Copies& copies,
                                    const std::string& path) {
  for (std::size_t row = 0; row < original.contacts.size(); ++row)
    check_branch(original, row, path);
  Tiling tiling{copies, original.cell.lengths, original.cell.lengths, original.particles.size()};
  h5::Checkpoint tiled = original;
  for (int a = 0; a < 3; ++a) {
    if (copies[a] == 1) continue; // the same bits
    tiling.tiled_length[a] = static_cast<double>(copies[a]) * original.cell.lengths[a];
    tiled.cell.lengths[a] = tiling.tiled_length[a];
    tiled.cell.reference_lengths[a] = static_cast<double>(copies[a]) * original.cell.reference_lengths[a];
  }
  tile_particles(original.particles, tiling, tiled.particles);
  tile_contacts(original, tiling, tiled.contacts);
  return tiled;
}

int run_replicate(const ReplicateOptions& options, DemConfig& config, config::Reader& reader,
                  const std::string& command_line, const Logger& logger, const mpi::Comm& comm) {
  namespace fs = std::filesystem;
  const Copies copies = parse_copies(options.copies);
  require_input(!fs::exists(options.input) || !fs::exists(options.output) ||
                    !fs::equivalent(options.input, options.output),
                fmt::format("replicate: --output '{}' is the input: write the copies to a new file, so that "
                            "the input is kept",
                            options.output));
  require_input(options.overwrite || !fs::exists(options.output),
                fmt::format("replicate: --output '{}' exists: give a new file, or --overwrite to replace it",
                            options.output));
  const h5::Checkpoint original = h5::read_checkpoint(options.input, comm);
  const CarriedAttributes carried = tileable_root(options.input);
  io::adopt_checkpoint_values(config, reader, original, options.input);
  const std::int64_t n_copies = copies[0] * copies[1] * copies[2];
  const double count = static_cast<double>(original.particles.size()) * static_cast<double>(n_copies);
  require_input(
      count <= static_cast<double>(std::numeric_limits<std::uint32_t>::max()),
      fmt::format("replicate: --copies {} of {} particles make {:.4g}, more than the {} a simulation "
                  "indexes",
                  options.copies, original.particles.size(), count,
                  std::numeric_limits<std::uint32_t>::max()));
  // Every rank holds the input and the tiled rows (27 doubles a particle, 17 words a contact), and
  // the contacts once more while they are sorted.
  const double contacts = static_cast<double>(original.contacts.size()) * static_cast<double>(n_copies);
  const double bytes = count * 27 * 8 + 3 * contacts * 17 * 8;
  require_memory(bytes, fmt::format("replicate: {} copies of '{}'", n_copies, options.input),
                 "replicate fewer copies, or on a machine with more memory");
  const h5::Checkpoint tiled = replicate_checkpoint(original, copies, options.input);
  config.particles.count = static_cast<std::int64_t>(tiled.particles.size());
  reader.replace("dem.particles.count", std::to_string(config.particles.count),
                 fmt::format("the input checkpoint's count times the copies {}", options.copies));
  const std::string source_hash = h5::content_hash(options.input, comm);
  create_parent_folder(options.output);
  const auto provenance =
      h5::make_provenance("aniso-dem replicate", reader.effective_toml(), command_line, comm);
  const std::string copies_text = fmt::format("{},{},{}", copies[0], copies[1], copies[2]);
  h5::write_checkpoint(options.output, rows_for_rank(tiled, comm), provenance, comm, [&](h5::File& file) {
    for (const auto& [name, value] : carried.int64)
      file.write_attribute<std::int64_t>(name, value);
    if (carried.flag) file.write_attribute<std::uint8_t>(std::string(carried_flag_attribute), *carried.flag);
    file.write_attribute(std::string(from_attribute), std::string_view(options.input));
    file.write_attribute(std::string(from_hash_attribute), std::string_view(source_hash));
    file.write_attribute(std::string(copies_attribute), std::string_view(copies_text));
  });
  const Vec3& before = original.cell.lengths;
  const Vec3& after = tiled.cell.lengths;
  logger->info(
      "replicate of '{}' {} x {} x {}: {} -> {} particles (ids + copy index x {}), {} -> {} contacts, "
      "cell {:.6g} x {:.6g} x {:.6g} -> {:.6g} x {:.6g} x {:.6g} m; wrote {}",
      options.input, copies[0], copies[1], copies[2], original.particles.size(), tiled.particles.size(),
      original.particles.size(), original.contacts.size(), tiled.contacts.size(), before.x(), before.y(),
      before.z(), after.x(), after.y(), after.z(), options.output);
  if (!original.particles.source_id.empty() && n_copies > 1)
    logger->warn("replicate: /particles/source_id (the ids of the file '{}' was imported from) is dropped: "
                 "the copies would share them, and export would write them as duplicate ids",
                 options.input);
  return 0;
}

} // namespace aniso::dem::interop
