#include "common/h5/checkpoint.hpp"

#include "common/error.hpp"
#include "common/exchange.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/h5/particle_separation.hpp"
#include "common/root_only.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <utility>

namespace aniso::h5 {
namespace {

constexpr const char* checkpoint_schema_name = "aniso-checkpoint";
constexpr double quaternion_norm_tolerance = 1e-6;

using Key = std::array<std::uint64_t, 2>;
// Names a row in messages: "row 7" when reading, "particle id 7" or "contact (3, 9)" when writing.
using RowLabel = std::function<std::string(std::size_t)>;

// Shortest text that reads back to the same double ("1e-09", not std::to_string's "0.000000").
std::string number(double value) {
  return fmt::format("{}", value);
}

// ---- Conversions between the in-memory rows and flat row-major arrays

std::vector<double> flatten(std::span<const Vec3> vectors) {
  std::vector<double> flat(3 * vectors.size());
  for (std::size_t k = 0; k < vectors.size(); ++k)
    for (int axis = 0; axis < 3; ++axis)
      flat[3 * k + static_cast<std::size_t>(axis)] = vectors[k][axis];
  return flat;
}

std::vector<std::int32_t> flatten(std::span<const Vec3i> vectors) {
  std::vector<std::int32_t> flat(3 * vectors.size());
  for (std::size_t k = 0; k < vectors.size(); ++k)
    for (int axis = 0; axis < 3; ++axis)
      flat[3 * k + static_cast<std::size_t>(axis)] = vectors[k][axis];
  return flat;
}

// Quaternions are stored as (w, x, y, z) whatever Eigen's internal order.
std::vector<double> flatten(std::span<const Quat> quaternions) {
  std::vector<double> flat(4 * quaternions.size());
  for (std::size_t k = 0; k < quaternions.size(); ++k) {
    const Quat& q = quaternions[k];
    flat[4 * k] = q.w();
    flat[4 * k + 1] = q.x();
    flat[4 * k + 2] = q.y();
    flat[4 * k + 3] = q.z();
  }
  return flat;
}

template <class T, std::size_t width> std::vector<T> flatten(std::span<const std::array<T, width>> rows) {
  std::vector<T> flat(width * rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
    std::copy(rows[k].begin(), rows[k].end(), flat.begin() + static_cast<std::ptrdiff_t>(width * k));
  return flat;
}

std::vector<Vec3> to_vec3(const std::vector<double>& flat) {
  std::vector<Vec3> vectors(flat.size() / 3);
  for (std::size_t k = 0; k < vectors.size(); ++k)
    vectors[k] = Vec3(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
  return vectors;
}

std::vector<Vec3i> to_vec3i(const std::vector<std::int32_t>& flat) {
  std::vector<Vec3i> vectors(flat.size() / 3);
  for (std::size_t k = 0; k < vectors.size(); ++k)
    vectors[k] = Vec3i(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
  return vectors;
}

std::vector<Quat> to_quat(const std::vector<double>& flat) {
  std::vector<Quat> quaternions(flat.size() / 4);
  for (std::size_t k = 0; k < quaternions.size(); ++k)
    quaternions[k] = Quat(flat[4 * k], flat[4 * k + 1], flat[4 * k + 2], flat[4 * k + 3]);
  return quaternions;
}

template <class T, std::size_t width>
std::vector<std::array<T, width>> to_arrays(const std::vector<T>& flat) {
  std::vector<std::array<T, width>> rows(flat.size() / width);
  for (std::size_t k = 0; k < rows.size(); ++k)
    std::copy_n(flat.begin() + static_cast<std::ptrdiff_t>(width * k), width, rows[k].begin());
  return rows;
}

Vec3 to_vec3_single(const std::vector<double>& flat) {
  return Vec3(flat[0], flat[1], flat[2]);
}

// ---- Validation shared by the writer (InputError) and the reader (FileError).
// Each check returns "<dataset>: <problem>", or nothing when the data are fine.

using Problem = std::optional<std::string>;

Problem check_finite(const std::string& dataset, std::span<const double> values, std::size_t width,
                     const RowLabel& label) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k]))
      return dataset + ": non-finite value " + number(values[k]) + " at " + label(k / width) +
             (width > 1 ? ", column " + std::to_string(k % width) : "");
  return std::nullopt;
}

Problem check_finite(const std::string& dataset, std::span<const Vec3> vectors, const RowLabel& label) {
  const std::vector<double> flat = flatten(vectors);
  return check_finite(dataset, flat, 3, label);
}

Problem check_positive(const std::string& dataset, std::span<const double> values, std::size_t width,
                       const RowLabel& label) {
  if (auto problem = check_finite(dataset, values, width, label)) return problem;
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!(values[k] > 0))
      return dataset + ": value " + number(values[k]) + " at " + label(k / width) + ", expected > 0";
  return std::nullopt;
}

Problem first_of(std::initializer_list<std::function<Problem()>> checks) {
  for (const auto& check : checks)
    if (auto problem = check()) return problem;
  return std::nullopt;
}

Problem check_particles(const ParticleRows& particles, const RowLabel& label) {
  const std::vector<double> inertia = flatten(particles.inertia);
  return first_of({
      [&] { return check_positive("/particles/diameter", particles.diameter, 1, label); },
      [&]() -> Problem {
        for (std::size_t k = 0; k < particles.size(); ++k)
          if (!(particles.aspect_ratio[k] > 0 && particles.aspect_ratio[k] <= 1))
            return "/particles/aspect_ratio: value " + number(particles.aspect_ratio[k]) + " at " + label(k) +
                   ", expected in (0, 1]";
        return std::nullopt;
      },
      [&] { return check_positive("/particles/mass", particles.mass, 1, label); },
      [&] { return check_positive("/particles/inertia", inertia, 3, label); },
      [&] { return check_finite("/particles/position", particles.position, label); },
      [&]() -> Problem {
        const std::vector<double> flat = flatten(particles.orientation);
        if (auto problem = check_finite("/particles/orientation", flat, 4, label)) return problem;
        for (std::size_t k = 0; k < particles.size(); ++k) {
          const double norm = particles.orientation[k].norm();
          if (std::abs(norm - 1) > quaternion_norm_tolerance)
            return "/particles/orientation: quaternion norm " + number(norm) + " at " + label(k) +
                   ", expected 1 within 1e-6";
        }
        return std::nullopt;
      },
      [&] { return check_finite("/particles/velocity", particles.velocity, label); },
      [&] { return check_finite("/particles/angular_velocity", particles.angular_velocity, label); },
      [&] { return check_finite("/particles/force", particles.force, label); },
      [&] { return check_finite("/particles/torque", particles.torque, label); },
  });
}

// Stored positions are wrapped into [0, L); a particle outside the cell gives a wrong stress and
// a wrong image, so the reader refuses one beyond a round-off of either end.
Problem check_positions_in_cell(const ParticleRows& particles, const Vec3& lengths, const RowLabel& label) {
  for (std::size_t k = 0; k < particles.size(); ++k)
    for (int axis = 0; axis < 3; ++axis) {
      const double x = particles.position[k][axis], slack = 1e-9 * lengths[axis];
      if (!(x >= -slack && x <= lengths[axis] + slack))
        return "/particles/position: coordinate " + std::to_string(axis) + " = " + number(x) + " m at " +
               label(k) + " lies outside the cell [0, " + number(lengths[axis]) + "] m";
    }
  return std::nullopt;
}

Problem check_contact_values(const ContactRows& contacts, const RowLabel& label) {
  return first_of({
      [&] { return check_finite("/contacts/normal", contacts.normal, label); },
      [&] { return check_finite("/contacts/point", contacts.point, label); },
      [&] { return check_finite("/contacts/overlap", contacts.overlap, 1, label); },
      [&] { return check_finite("/contacts/force", contacts.force, label); },
      [&] { return check_finite("/contacts/tangential_force", contacts.tangential_force, label); },
      [&]() -> Problem {
        for (std::size_t k = 0; k < contacts.size(); ++k)
          if (contacts.sliding[k] > 1)
            return "/contacts/sliding: value " + std::to_string(contacts.sliding[k]) + " at " + label(k) +
                   ", expected 0 or 1";
        return std::nullopt;
      },
  });
}

// Pairs must satisfy id_i < id_j < n_particles.
Problem check_contact_ids(std::span<const Key> pairs, std::uint64_t n_particles, const RowLabel& label) {
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [id_i, id_j] = pairs[k];
    const std::string text = "(" + std::to_string(id_i) + ", " + std::to_string(id_j) + ")";
    if (id_i >= id_j) return "/contacts/particles: " + text + " at " + label(k) + ", expected id_i < id_j";
    if (id_j >= n_particles)
      return "/contacts/particles: " + text + " at " + label(k) + ", id out of range [0, " +
             std::to_string(n_particles) + ")";
  }
  return std::nullopt;
}

Problem check_cell(const CellState& cell) {
  const RowLabel axis = [](std::size_t k) { return "axis " + std::to_string(k); };
  const std::vector<double> lengths(cell.lengths.begin(), cell.lengths.end());
  const std::vector<double> reference(cell.reference_lengths.begin(), cell.reference_lengths.end());
  const std::vector<double> strain_rate(cell.strain_rate.begin(), cell.strain_rate.end());
  const std::vector<double> target(cell.target.begin(), cell.target.end());
  const std::vector<double> servo(cell.servo_state.begin(), cell.servo_state.end());
  return first_of({
      [&] { return check_positive("/cell/lengths", lengths, 1, axis); },
      [&] { return check_positive("/cell/reference_lengths", reference, 1, axis); },
      [&] { return check_finite("/cell/strain_rate", strain_rate, 1, axis); },
      [&]() -> Problem {
        for (std::size_t k = 0; k < 3; ++k)
          if (static_cast<std::uint8_t>(cell.mode[k]) > 1)
            return "/cell/mode: value " + std::to_string(static_cast<int>(cell.mode[k])) + " at axis " +
                   std::to_string(k) + ", expected 0 (strain_rate) or 1 (stress)";
        return std::nullopt;
      },
      [&] { return check_finite("/cell/target", target, 1, axis); },
      [&] { return check_finite("/cell/servo_state", servo, 1, axis); },
      [&] {
        return check_finite("/cell/mean_stress_target", std::span<const double>(&cell.mean_stress_target, 1),
                            1, axis);
      },
  });
}

Problem check_run_state(const Checkpoint& checkpoint) {
  if (!std::isfinite(checkpoint.time))
    return "/ (attribute time): non-finite value " + number(checkpoint.time);
  if (!std::isfinite(checkpoint.time_step) || checkpoint.time_step < 0)
    return "/ (attribute time_step): value " + number(checkpoint.time_step) + ", expected finite and >= 0";
  if (checkpoint.step < 0)
    return "/ (attribute step): value " + std::to_string(checkpoint.step) + ", expected >= 0";
  for (std::size_t k = 0; k < checkpoint.parameters.size(); ++k) {
    const Parameter& parameter = checkpoint.parameters[k];
    const std::string where = "/parameters (attribute '" + parameter.name + "')";
    if (parameter.name.empty() || parameter.name == "description" || parameter.name.ends_with("_units"))
      return where +
             ": not a valid parameter name (empty, 'description' and names ending in _units are reserved)";
    if (!std::isfinite(parameter.value)) return where + ": non-finite value " + number(parameter.value);
    for (std::size_t other = 0; other < k; ++other)
      if (checkpoint.parameters[other].name == parameter.name) return where + ": given twice";
  }
  return std::nullopt;
}

// ---- Collective error handling: every rank throws the same message, or none does.

template <class ErrorType>
void throw_if_any(const mpi::Comm& comm, const Problem& local, const std::string& prefix) {
  if (const auto problem = mpi::first_problem(comm, local))
    throw ErrorType(prefix + problem->text +
                    (comm.size() > 1 ? " (found on rank " + std::to_string(problem->rank) + ")" : ""));
}

// ---- Writing

// Bytes of everything that is not per-row; all ranks must hold the same.
std::vector<char> shared_state_bytes(const Checkpoint& checkpoint, const Provenance& provenance) {
  std::vector<char> bytes;
  const auto append_raw = [&](const void* data, std::size_t size) {
    const auto* begin = static_cast<const char*>(data);
    bytes.insert(bytes.end(), begin, begin + size);
  };
  const auto append_string = [&](const std::string& text) {
    const std::uint64_t size = text.size();
    append_raw(&size, sizeof size);
    append_raw(text.data(), text.size());
  };
  append_raw(&checkpoint.time, sizeof checkpoint.time);
  append_raw(&checkpoint.step, sizeof checkpoint.step);
  append_raw(&checkpoint.time_step, sizeof checkpoint.time_step);
  append_string(checkpoint.run_id);
  const CellState& cell = checkpoint.cell;
  for (const Vec3* vector :
       {&cell.lengths, &cell.reference_lengths, &cell.strain_rate, &cell.target, &cell.servo_state})
    append_raw(vector->data(), 3 * sizeof(double));
  append_raw(cell.mode.data(), sizeof cell.mode);
  const char hold = cell.hold_mean_stress ? 1 : 0;
  append_raw(&hold, 1);
  append_raw(&cell.mean_stress_target, sizeof(double));
  for (const Parameter& parameter : checkpoint.parameters) {
    append_string(parameter.name);
    append_raw(&parameter.value, sizeof(double));
    append_string(parameter.unit);
  }
  const std::uint64_t n_streams = checkpoint.rng_state.size();
  append_raw(&n_streams, sizeof n_streams);
  for (const auto& state : checkpoint.rng_state)
    append_raw(state.data(), sizeof state);
  for (const std::string* text : {&provenance.program, &provenance.version, &provenance.git_hash,
                                  &provenance.config, &provenance.command_line, &provenance.date})
    append_string(*text);
  append_raw(&provenance.n_ranks, sizeof provenance.n_ranks);
  return bytes;
}

Problem check_sizes(const Checkpoint& local) {
  const ParticleRows& p = local.particles;
  const std::size_t n = p.id.size();
  for (const std::size_t size :
       {p.diameter.size(), p.aspect_ratio.size(), p.mass.size(), p.inertia.size(), p.position.size(),
        p.orientation.size(), p.velocity.size(), p.angular_velocity.size(), p.force.size(), p.torque.size()})
    if (size != n) return "/particles: the particle arrays have different lengths";
  if (!p.source_id.empty() && p.source_id.size() != n)
    return "/particles/source_id: one per particle, or none";
  const ContactRows& c = local.contacts;
  const std::size_t m = c.particles.size();
  for (const std::size_t size : {c.image_shift.size(), c.normal.size(), c.point.size(), c.overlap.size(),
                                 c.force.size(), c.tangential_force.size(), c.sliding.size()})
    if (size != m) return "/contacts: the contact arrays have different lengths";
  return std::nullopt;
}

// Where each of this rank's contacts goes in the global (id_i, id_j) order. Collective.
// Contacts sharing id_i may be spread over ranks; those few are exchanged so that every rank can
// place its own. Throws InputError on every rank if a pair is held twice.
std::vector<std::uint64_t> contact_rows(const std::vector<Key>& pairs,
                                        const std::vector<std::int64_t>& global_count,
                                        const std::vector<std::int64_t>& local_count, const mpi::Comm& comm) {
  const std::size_t n_local = pairs.size();
  std::vector<std::size_t> order(n_local);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pairs[a] < pairs[b]; });

  Problem duplicate;
  for (std::size_t k = 1; k < n_local && !duplicate; ++k)
    if (pairs[order[k]] == pairs[order[k - 1]])
      duplicate = "/contacts/particles: contact (" + std::to_string(pairs[order[k]][0]) + ", " +
                  std::to_string(pairs[order[k]][1]) + ") given twice";
  throw_if_any<InputError>(comm, duplicate, "write_checkpoint: ");

  std::vector<std::uint64_t> offset(global_count.size() + 1, 0);
  for (std::size_t id = 0; id < global_count.size(); ++id)
    offset[id + 1] = offset[id] + static_cast<std::uint64_t>(global_count[id]);

  // Pairs whose id_i also appears on another rank.
  const auto split = [&](const Key& pair) { return local_count[pair[0]] != global_count[pair[0]]; };
  std::vector<Key> shared;
  for (const std::size_t k : order)
    if (split(pairs[k])) shared.push_back(pairs[k]);
  std::vector<Key> all_shared;
  if (comm.any(!shared.empty())) {
    for (int rank = 0; rank < comm.size(); ++rank) {
      std::vector<char> bytes;
      if (rank == comm.rank()) {
        bytes.resize(shared.size() * sizeof(Key));
        if (!shared.empty()) std::memcpy(bytes.data(), shared.data(), bytes.size());
      }
      comm.broadcast(bytes, rank);
      const std::size_t n_received = bytes.size() / sizeof(Key);
      const std::size_t old_size = all_shared.size();
      all_shared.resize(old_size + n_received);
      if (n_received > 0) std::memcpy(all_shared.data() + old_size, bytes.data(), bytes.size());
    }
    std::sort(all_shared.begin(), all_shared.end());
    const auto repeated = std::adjacent_find(all_shared.begin(), all_shared.end());
    if (repeated != all_shared.end())
      throw InputError("write_checkpoint: /contacts/particles: contact (" + std::to_string((*repeated)[0]) +
                       ", " + std::to_string((*repeated)[1]) + ") held by more than one rank");
  }

  std::vector<std::uint64_t> rows(n_local);
  std::uint64_t previous_id = 0;
  std::uint64_t rank_in_group = 0;
  for (std::size_t sorted = 0; sorted < n_local; ++sorted) {
    const Key& pair = pairs[order[sorted]];
    rank_in_group = (sorted > 0 && pair[0] == previous_id) ? rank_in_group + 1 : 0;
    previous_id = pair[0];
    if (split(pair)) {
      const auto group_begin = std::lower_bound(all_shared.begin(), all_shared.end(), Key{pair[0], 0});
      const auto here = std::lower_bound(all_shared.begin(), all_shared.end(), pair);
      rows[order[sorted]] = offset[pair[0]] + static_cast<std::uint64_t>(here - group_begin);
    } else {
      rows[order[sorted]] = offset[pair[0]] + rank_in_group;
    }
  }
  return rows;
}

std::vector<double> as_vector(const Vec3& vector) {
  return {vector.x(), vector.y(), vector.z()};
}

void write_content(File& file, const Checkpoint& local, const Provenance& provenance, bool with_source_ids,
                   std::uint64_t n_particles, std::uint64_t n_contacts, const RowSelection& particle_rows,
                   const RowSelection& contact_rows) {
  file.write_attribute("schema", std::string_view(checkpoint_schema_name));
  file.write_attribute("schema_version", checkpoint_schema_version);
  file.write_attribute("description", std::string_view("aniso DEM checkpoint: the complete state needed to "
                                                       "continue the run bit for bit. Layout and units: "
                                                       "docs/formats/checkpoint.md"));
  file.write_attribute_with_units("time", local.time, "s");
  file.write_attribute("step", local.step);
  file.write_attribute("step_units", std::string_view("1"));
  file.write_attribute_with_units("time_step", local.time_step, "s");
  if (std::isfinite(local.unbalanced_force_ratio))
    file.write_attribute_with_units("unbalanced_force_ratio", local.unbalanced_force_ratio, "1");
  if (std::isfinite(local.kinetic_elastic_ratio))
    file.write_attribute_with_units("kinetic_elastic_ratio", local.kinetic_elastic_ratio, "1");
  if (!local.run_id.empty()) file.write_attribute("run_id", local.run_id);

  {
    const CellState& cell = local.cell;
    Group group = file.create_group("cell");
    group.write_attribute("description",
                          std::string_view("periodic cell geometry and the state of its controller; "
                                           "index 0, 1, 2 = axis x, y, z"));
    const Dims three{3};
    group.write_dataset<double>("lengths", as_vector(cell.lengths), three, "m", "current cell lengths");
    group.write_dataset<double>("reference_lengths", as_vector(cell.reference_lengths), three, "m",
                                "cell lengths at zero strain");
    group.write_dataset<double>("strain_rate", as_vector(cell.strain_rate), three, "1/s",
                                "current rate (dL/dt)/L per axis");
    const std::vector<std::uint8_t> mode{static_cast<std::uint8_t>(cell.mode[0]),
                                         static_cast<std::uint8_t>(cell.mode[1]),
                                         static_cast<std::uint8_t>(cell.mode[2])};
    group.write_dataset<std::uint8_t>("mode", mode, three, "1",
                                      "how each axis is driven: 0 = strain rate, 1 = stress (servo)");
    group.write_dataset<double>("target", as_vector(cell.target), three, "1/s or Pa",
                                "per axis: strain rate [1/s] if mode = 0, stress [Pa] if mode = 1");
    group.write_dataset<double>("servo_state", as_vector(cell.servo_state), three, "controller-defined",
                                "stress controller memory (integral terms) per axis");
    const std::uint8_t hold = cell.hold_mean_stress ? 1 : 0;
    group.write_dataset<std::uint8_t>(
        "hold_mean_stress", std::span<const std::uint8_t>(&hold, 1), Dims{}, "1",
        "1: the stress-mode axes together hold mean stress = mean_stress_target");
    group.write_dataset<double>("mean_stress_target", std::span<const double>(&cell.mean_stress_target, 1),
                                Dims{}, "Pa", "target mean stress p, compression positive");
  }

  {
    const ParticleRows& p = local.particles;
    Group group = file.create_group("particles");
    group.write_attribute("description", std::string_view("every particle, row = particle id"));
    const auto rows = [&]<Element T>(const std::string& name, const std::vector<T>& data, hsize_t width,
                                     std::string_view units, std::string_view description) {
      const Dims dims = width == 1 ? Dims{n_particles} : Dims{n_particles, width};
      group.create_dataset<T>(name, dims, units, description)
          .write_rows(particle_rows, std::span<const T>(data));
    };
    rows("id", p.id, 1, "1", "particle id, equal to the row number");
    rows("diameter", p.diameter, 1, "m", "mid-plane diameter");
    rows("aspect_ratio", p.aspect_ratio, 1, "1", "axial height / mid-plane diameter; 1 = sphere");
    rows("mass", p.mass, 1, "kg", "mass");
    rows("inertia", flatten(p.inertia), 3, "kg m^2",
         "principal moments of inertia in the body frame, "
         "axis of revolution = body z");
    rows("position", flatten(p.position), 3, "m", "centre position, inside the cell");
    rows("orientation", flatten(p.orientation), 4, "1",
         "body-to-world rotation as a unit quaternion (w, x, y, z)");
    rows("velocity", flatten(p.velocity), 3, "m/s", "translational velocity");
    rows("angular_velocity", flatten(p.angular_velocity), 3, "rad/s", "angular velocity, world frame");
    rows("force", flatten(p.force), 3, "N", "total force at the stored step");
    rows("torque", flatten(p.torque), 3, "N m", "total torque at the stored step, world frame");
    if (with_source_ids)
      rows("source_id", p.source_id, 1, "1", "the particle's id in the file it was imported from");
  }

  {
    const ContactRows& c = local.contacts;
    Group group = file.create_group("contacts");
    group.write_attribute("description", std::string_view("every contact with its history, in increasing "
                                                          "(id_i, id_j) order, id_i < id_j"));
    const auto rows = [&]<Element T>(const std::string& name, const std::vector<T>& data, hsize_t width,
                                     std::string_view units, std::string_view description) {
      const Dims dims = width == 1 ? Dims{n_contacts} : Dims{n_contacts, width};
      group.create_dataset<T>(name, dims, units, description)
          .write_rows(contact_rows, std::span<const T>(data));
    };
    rows("particles", flatten<std::uint64_t, 2>(c.particles), 2, "1",
         "particle ids (id_i, id_j), id_i < id_j");
    rows("image_shift", flatten(c.image_shift), 3, "1",
         "periodic image of particle j relative to i, in whole cell lengths per axis");
    rows("normal", flatten(c.normal), 3, "1", "unit contact normal pointing from i to j");
    rows("point", flatten(c.point), 3, "m", "contact point, wrapped into the cell");
    rows("overlap", c.overlap, 1, "m", "normal overlap");
    rows("force", flatten(c.force), 3, "N", "contact force on particle i from particle j");
    rows("tangential_force", flatten(c.tangential_force), 3, "N",
         "elastic tangential (Mindlin) force on i, the contact history");
    rows("sliding", c.sliding, 1, "1", "1 if at the Coulomb limit at the stored step, else 0");
  }

  {
    Group group = file.create_group("parameters");
    group.write_attribute("description",
                          std::string_view("material and run parameters: attribute <name> holds "
                                           "the value, <name>_units its unit"));
    for (const Parameter& parameter : local.parameters)
      group.write_attribute_with_units(parameter.name, parameter.value, parameter.unit);
  }

  {
    Group group = file.create_group("rng");
    group.write_attribute("description", std::string_view("random streams"));
    const std::vector<std::uint64_t> state = flatten<std::uint64_t, 4>(local.rng_state);
    group.write_dataset<std::uint64_t>("state", state, Dims{local.rng_state.size(), 4}, "1",
                                       "xoshiro256** state (4 x 64 bit) of each random stream, row = stream");
  }

  write_provenance(file, provenance);
}

// ---- Reading

std::string contacts_out_of_order(std::uint64_t row) {
  return "/contacts/particles: rows " + std::to_string(row) + " and " + std::to_string(row + 1) +
         " are not in strictly increasing (id_i, id_j) order";
}

// Which rows of /particles and /contacts this rank reads (everything with RowShare::all).
struct ReadShare {
  RowShare share = RowShare::all;
  int rank = 0, ranks = 1;
  [[nodiscard]] RowSlab of(std::uint64_t total) const {
    return share == RowShare::all ? RowSlab{0, total} : row_slab(total, rank, ranks);
  }
};

Checkpoint read_file(const std::string& path, const ReadShare& share) {
  const File file = File::open(path);
  if (!file.has_attribute("schema"))
    file.fail("missing attribute 'schema' (expected '" + std::string(checkpoint_schema_name) +
              "'; not an aniso checkpoint?)");
  const std::string schema = file.read_string_attribute("schema");
  if (schema != checkpoint_schema_name)
    file.fail("schema '" + schema + "' found, expected '" + checkpoint_schema_name + "'");
  const std::int64_t version = file.read_attribute<std::int64_t>("schema_version");
  if (version != checkpoint_schema_version)
    file.fail("schema_version " + std::to_string(version) + " found, expected " +
              std::to_string(checkpoint_schema_version));

  Checkpoint checkpoint;
  checkpoint.share = share.share;
  std::uint64_t n_particles = 0;
  RowSlab particle_rows, contact_rows;
  struct WholeAssembly {
    std::vector<Vec3> position;
    std::vector<double> diameter, aspect_ratio;
  } whole; // a slab read's copy of what the overlap check needs of every particle
  checkpoint.time = file.read_attribute<double>("time");
  checkpoint.step = file.read_attribute<std::int64_t>("step");
  checkpoint.time_step = file.read_attribute<double>("time_step");
  if (file.has_attribute("unbalanced_force_ratio"))
    checkpoint.unbalanced_force_ratio = file.read_attribute<double>("unbalanced_force_ratio");
  if (file.has_attribute("kinetic_elastic_ratio"))
    checkpoint.kinetic_elastic_ratio = file.read_attribute<double>("kinetic_elastic_ratio");
  if (file.has_attribute("run_id")) checkpoint.run_id = file.read_string_attribute("run_id");

  {
    const Group group = file.open_group("cell");
    CellState& cell = checkpoint.cell;
    const Dims three{3};
    cell.lengths = to_vec3_single(group.read_dataset<double>("lengths", three));
    cell.reference_lengths = to_vec3_single(group.read_dataset<double>("reference_lengths", three));
    cell.strain_rate = to_vec3_single(group.read_dataset<double>("strain_rate", three));
    const std::vector<std::uint8_t> mode = group.read_dataset<std::uint8_t>("mode", three);
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (mode[axis] > 1)
        group.open_dataset("mode").fail("value " + std::to_string(mode[axis]) + " at axis " +
                                        std::to_string(axis) + ", expected 0 (strain_rate) or 1 (stress)");
      cell.mode[axis] = static_cast<AxisMode>(mode[axis]);
    }
    cell.target = to_vec3_single(group.read_dataset<double>("target", three));
    cell.servo_state = to_vec3_single(group.read_dataset<double>("servo_state", three));
    const std::uint8_t hold = group.read_dataset<std::uint8_t>("hold_mean_stress", Dims{})[0];
    if (hold > 1)
      group.open_dataset("hold_mean_stress").fail("value " + std::to_string(hold) + ", expected 0 or 1");
    cell.hold_mean_stress = hold == 1;
    cell.mean_stress_target = group.read_dataset<double>("mean_stress_target", Dims{})[0];
  }

  {
    const Group group = file.open_group("particles");
    const Dims id_dims = group.open_dataset("id").dims();
    if (id_dims.size() != 1)
      group.open_dataset("id").fail("shape " + format_dims(id_dims) +
                                    " found, expected [N] (one id per particle)");
    const hsize_t n = id_dims[0];
    n_particles = n;
    particle_rows = share.of(n);
    const RowSlab& slab = particle_rows;
    ParticleRows& p = checkpoint.particles;
    p.id = group.read_dataset_rows<std::uint64_t>("id", Dims{n}, slab);
    for (std::size_t k = 0; k < p.id.size(); ++k)
      if (const std::uint64_t row = slab.first + k; p.id[k] != row)
        group.open_dataset("id").fail("row " + std::to_string(row) + " holds id " + std::to_string(p.id[k]) +
                                      ", expected " + std::to_string(row) + " (ids must be 0..N-1 in order)");
    p.diameter = group.read_dataset_rows<double>("diameter", Dims{n}, slab);
    p.aspect_ratio = group.read_dataset_rows<double>("aspect_ratio", Dims{n}, slab);
    p.mass = group.read_dataset_rows<double>("mass", Dims{n}, slab);
    p.inertia = to_vec3(group.read_dataset_rows<double>("inertia", Dims{n, 3}, slab));
    p.position = to_vec3(group.read_dataset_rows<double>("position", Dims{n, 3}, slab));
    p.orientation = to_quat(group.read_dataset_rows<double>("orientation", Dims{n, 4}, slab));
    p.velocity = to_vec3(group.read_dataset_rows<double>("velocity", Dims{n, 3}, slab));
    p.angular_velocity = to_vec3(group.read_dataset_rows<double>("angular_velocity", Dims{n, 3}, slab));
    p.force = to_vec3(group.read_dataset_rows<double>("force", Dims{n, 3}, slab));
    p.torque = to_vec3(group.read_dataset_rows<double>("torque", Dims{n, 3}, slab));
    if (group.has_child("source_id"))
      p.source_id = group.read_dataset_rows<std::uint64_t>("source_id", Dims{n}, slab);
    if (share.share == RowShare::slab) { // the whole assembly's, for the overlap check alone
      whole.position = to_vec3(group.read_dataset<double>("position", Dims{n, 3}));
      whole.diameter = group.read_dataset<double>("diameter", Dims{n});
      whole.aspect_ratio = group.read_dataset<double>("aspect_ratio", Dims{n});
    }
  }

  {
    const Group group = file.open_group("contacts");
    const Dims pair_dims = group.open_dataset("particles").dims();
    if (pair_dims.size() != 2 || pair_dims[1] != 2)
      group.open_dataset("particles").fail("shape " + format_dims(pair_dims) + " found, expected [M, 2]");
    const hsize_t m = pair_dims[0];
    contact_rows = share.of(m);
    const RowSlab& slab = contact_rows;
    ContactRows& c = checkpoint.contacts;
    c.particles =
        to_arrays<std::uint64_t, 2>(group.read_dataset_rows<std::uint64_t>("particles", Dims{m, 2}, slab));
    c.image_shift = to_vec3i(group.read_dataset_rows<std::int32_t>("image_shift", Dims{m, 3}, slab));
    c.normal = to_vec3(group.read_dataset_rows<double>("normal", Dims{m, 3}, slab));
    c.point = to_vec3(group.read_dataset_rows<double>("point", Dims{m, 3}, slab));
    c.overlap = group.read_dataset_rows<double>("overlap", Dims{m}, slab);
    c.force = to_vec3(group.read_dataset_rows<double>("force", Dims{m, 3}, slab));
    c.tangential_force = to_vec3(group.read_dataset_rows<double>("tangential_force", Dims{m, 3}, slab));
    c.sliding = group.read_dataset_rows<std::uint8_t>("sliding", Dims{m}, slab);
  }

  {
    const Group group = file.open_group("parameters");
    for (const std::string& name : group.attribute_names()) {
      if (name == "description" || name.ends_with("_units")) continue;
      checkpoint.parameters.push_back(
          Parameter{name, group.read_attribute<double>(name), group.read_string_attribute(name + "_units")});
    }
  }

  {
    const Group group = file.open_group("rng");
    const Dims state_dims = group.open_dataset("state").dims();
    if (state_dims.size() != 2 || state_dims[1] != 4)
      group.open_dataset("state").fail("shape " + format_dims(state_dims) + " found, expected [S, 4]");
    checkpoint.rng_state =
        to_arrays<std::uint64_t, 4>(group.read_dataset<std::uint64_t>("state", state_dims));
  }

  static_cast<void>(read_provenance(file));

  // Values: the same rules the writer applies, with rows named by their row number.
  const RowLabel row = [&](std::size_t k) { return "row " + std::to_string(particle_rows.first + k); };
  const RowLabel contact_row = [&](std::size_t k) { return "row " + std::to_string(contact_rows.first + k); };
  const auto pairs = std::span<const Key>(checkpoint.contacts.particles);
  Problem problem = first_of({
      [&]() -> Problem {
        if (n_particles == 0) return "/particles: no particles";
        return std::nullopt;
      },
      [&] { return check_run_state(checkpoint); },
      [&] { return check_cell(checkpoint.cell); },
      [&] { return check_particles(checkpoint.particles, row); },
      [&] { return check_positions_in_cell(checkpoint.particles, checkpoint.cell.lengths, row); },
      [&] { return check_contact_ids(pairs, n_particles, contact_row); },
      [&]() -> Problem {
        for (std::size_t k = 1; k < pairs.size(); ++k)
          if (!(pairs[k - 1] < pairs[k])) return contacts_out_of_order(contact_rows.first + k - 1);
        return std::nullopt;
      },
      [&] { return check_contact_values(checkpoint.contacts, contact_row); },
      [&]() -> Problem {
        // Older files without the limit: only what no limit allows (one body inside another).
        const double limit = has_parameter(checkpoint, "explosion_overlap")
                                 ? parameter(checkpoint, "explosion_overlap", path)
                                 : 1.0;
        const ParticleRows& p = checkpoint.particles;
        const bool all = share.share == RowShare::all;
        if (auto pair = deepest_impossible_overlap(
                all ? p.position : whole.position, all ? p.diameter : whole.diameter,
                all ? p.aspect_ratio : whole.aspect_ratio, checkpoint.cell.lengths, limit))
          return "/particles/position: " + *pair + ": no DEM run reaches this state";
        return std::nullopt;
      },
  });
  if (problem) throw FileError(path + ": " + *problem);
  return checkpoint;
}

} // namespace

void ParticleRows::resize(std::size_t n) {
  id.resize(n);
  diameter.resize(n);
  aspect_ratio.resize(n);
  mass.resize(n);
  inertia.resize(n, Vec3::Zero());
  position.resize(n, Vec3::Zero());
  orientation.resize(n, Quat::Identity());
  velocity.resize(n, Vec3::Zero());
  angular_velocity.resize(n, Vec3::Zero());
  force.resize(n, Vec3::Zero());
  torque.resize(n, Vec3::Zero());
}

void ContactRows::resize(std::size_t n) {
  particles.resize(n);
  image_shift.resize(n, Vec3i::Zero());
  normal.resize(n, Vec3::Zero());
  point.resize(n, Vec3::Zero());
  overlap.resize(n);
  force.resize(n, Vec3::Zero());
  tangential_force.resize(n, Vec3::Zero());
  sliding.resize(n);
}

void write_checkpoint(const std::string& path, const Checkpoint& local, const Provenance& provenance,
                      const mpi::Comm& comm, const std::function<void(File&)>& add) {
  const std::string prefix = "write_checkpoint " + path + ": ";
  const ParticleRows& particles = local.particles;
  const ContactRows& contacts = local.contacts;

  // 1. This rank's rows, checked by the same rules the reader applies.
  const auto n_particles = static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(particles.size())));
  const auto n_contacts = static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(contacts.size())));
  Problem problem = check_sizes(local);
  if (!problem) {
    const RowLabel particle = [&](std::size_t k) { return "particle id " + std::to_string(particles.id[k]); };
    const RowLabel contact = [&](std::size_t k) {
      return "contact (" + std::to_string(contacts.particles[k][0]) + ", " +
             std::to_string(contacts.particles[k][1]) + ")";
    };
    problem = first_of({
        [&]() -> Problem {
          for (const std::uint64_t id : particles.id)
            if (id >= n_particles)
              return "/particles/id: id " + std::to_string(id) + " out of range [0, " +
                     std::to_string(n_particles) + ") (ids over all ranks must be 0..N-1)";
          return std::nullopt;
        },
        [&] { return check_particles(particles, particle); },
        [&] { return check_contact_ids(contacts.particles, n_particles, contact); },
        [&] { return check_contact_values(contacts, contact); },
    });
  }
  throw_if_any<InputError>(comm, problem, prefix);
  const bool with_source_ids = comm.any(!particles.source_id.empty());
  throw_if_any<InputError>(comm,
                           with_source_ids && particles.source_id.size() != particles.size()
                               ? Problem("/particles/source_id: given on some ranks only")
                               : std::nullopt,
                           prefix);

  // 2. What is not per-row must be the same on every rank (rank 0's copy is what gets written).
  const std::vector<char> shared = shared_state_bytes(local, provenance);
  std::vector<char> root_shared = shared;
  comm.broadcast(root_shared, 0);
  problem = first_of({[&] { return check_run_state(local); }, [&] { return check_cell(local.cell); }});
  if (!problem && shared != root_shared)
    problem = "time, cell, parameters, rng state or provenance differ from rank 0's";
  throw_if_any<InputError>(comm, problem, prefix);

  // 3. Every id exactly once over all ranks; contacts per id_i for the global contact order.
  std::vector<std::int64_t> counts(2 * n_particles, 0);
  for (const std::uint64_t id : particles.id)
    ++counts[id];
  for (const Key& pair : contacts.particles)
    ++counts[n_particles + pair[0]];
  const std::vector<std::int64_t> global = comm.sum(counts);
  for (std::uint64_t id = 0; id < n_particles; ++id)
    if (global[id] != 1)
      throw InputError(prefix + "/particles/id: id " + std::to_string(id) + " held " +
                       std::to_string(global[id]) + " times over all ranks, expected exactly once");
  const std::vector<std::int64_t> global_contacts(global.begin() + static_cast<std::ptrdiff_t>(n_particles),
                                                  global.end());
  const std::vector<std::int64_t> local_contacts(counts.begin() + static_cast<std::ptrdiff_t>(n_particles),
                                                 counts.end());
  const RowSelection particle_rows(particles.id);
  const std::vector<std::uint64_t> rows =
      contact_rows(contacts.particles, global_contacts, local_contacts, comm);
  const RowSelection contact_row_selection(rows);

  // 4. Write under a temporary name, then rename.
  AtomicFile atomic(path, comm);
  File file = File::create(atomic.temp_path(), comm);
  write_content(file, local, provenance, with_source_ids, n_particles, n_contacts, particle_rows,
                contact_row_selection);
  file.close();
  if (add) {
    run_on_root(comm, [&] {
      File serial = File::open(atomic.temp_path(), File::Access::read_write);
      add(serial);
      serial.close();
    });
  }
  atomic.commit();
}

Checkpoint read_checkpoint(const std::string& path, const mpi::Comm& comm, RowShare share) {
  // Every rank reads its rows; a failure anywhere fails everywhere with the same message. One
  // rank's slab is the whole file, read whole (one selection less, no second copy of positions).
  if (comm.size() == 1) share = RowShare::all;
  Checkpoint checkpoint;
  Problem problem;
  try {
    checkpoint = read_file(path, ReadShare{share, comm.rank(), comm.size()});
  } catch (const FileError& error) {
    problem = error.what();
  }
  throw_if_any<FileError>(comm, problem, "");
  const ParticleRows& p = checkpoint.particles;
  const auto pairs = std::span<const Key>(checkpoint.contacts.particles);
  RowTotals& totals = checkpoint.totals;
  const auto [smallest, largest] = std::minmax_element(p.diameter.begin(), p.diameter.end());
  const auto [flattest, roundest] = std::minmax_element(p.aspect_ratio.begin(), p.aspect_ratio.end());
  constexpr double none = std::numeric_limits<double>::infinity();
  totals = {p.size(),
            pairs.size(),
            p.size() > 0 ? *smallest : none,
            p.size() > 0 ? *largest : -none,
            p.size() > 0 ? *flattest : none,
            p.size() > 0 ? *roundest : -none};
  if (share == RowShare::all || comm.size() == 1) return checkpoint;

  totals.particles = static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(totals.particles)));
  totals.contacts = static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(totals.contacts)));
  totals.diameter_min = comm.min(totals.diameter_min);
  totals.diameter_max = comm.max(totals.diameter_max);
  totals.aspect_ratio_min = comm.min(totals.aspect_ratio_min);
  totals.aspect_ratio_max = comm.max(totals.aspect_ratio_max);
  // The contacts' order across the slabs: each slab's first pair after the last pair before it.
  std::vector<char> ends;
  ByteWriter out(ends);
  if (!pairs.empty()) {
    out.put(pairs.front());
    out.put(pairs.back());
  }
  const RowSlab mine = row_slab(totals.contacts, comm.rank(), comm.size());
  std::optional<Key> before;
  const auto gathered = all_gather_bytes(comm, ends);
  for (int rank = 0; rank < comm.rank(); ++rank) {
    const auto& theirs = gathered[static_cast<std::size_t>(rank)];
    if (theirs.empty()) continue;
    ByteReader in(theirs);
    static_cast<void>(in.get<Key>());
    before = in.get<Key>();
  }
  if (before && !pairs.empty() && !(*before < pairs.front())) problem = contacts_out_of_order(mine.first - 1);
  throw_if_any<FileError>(comm, problem ? std::optional(path + ": " + *problem) : std::nullopt, "");
  return checkpoint;
}

bool has_parameter(const Checkpoint& checkpoint, const std::string& name) {
  for (const Parameter& candidate : checkpoint.parameters)
    if (candidate.name == name) return true;
  return false;
}

double parameter(const Checkpoint& checkpoint, const std::string& name, const std::string& path) {
  for (const Parameter& candidate : checkpoint.parameters)
    if (candidate.name == name) return candidate.value;
  throw FileError(path + ": /parameters: missing parameter '" + name + "'");
}

} // namespace aniso::h5
