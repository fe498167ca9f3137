#pragma once
// Test helpers for checkpoint tests: a deterministic random checkpoint with
// awkward values (negative zero, subnormals, extremes), a way to deal its rows
// out to ranks, and a bit-for-bit comparison of two checkpoints.
#include "common/h5/checkpoint.hpp"
#include "common/h5/file.hpp"
#include "common/mpi.hpp"
#include "common/rng.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace aniso::test {

inline Vec3 random_vec3(RandomStream& stream, double low, double high) {
  return Vec3(stream.uniform(low, high), stream.uniform(low, high), stream.uniform(low, high));
}

/// Places the particles at random in [0, region) of each axis, one after another, each where its
/// inscribed sphere overlaps no earlier one's by 0.9 of the smaller radius across the periodic
/// cell: the reader refuses a whole radius (common/h5/particle_separation.hpp).
inline void place_apart(h5::Checkpoint& checkpoint, RandomStream& stream, const Vec3& region) {
  h5::ParticleRows& p = checkpoint.particles;
  const Vec3& lengths = checkpoint.cell.lengths;
  const auto inscribed = [&](std::size_t k) { return 0.5 * p.diameter[k] * p.aspect_ratio[k]; };
  for (std::size_t k = 0; k < p.size(); ++k) {
    for (bool apart = false; !apart;) {
      p.position[k] = random_vec3(stream, 0, 1).cwiseProduct(region);
      apart = true;
      for (std::size_t j = 0; j < k && apart; ++j) {
        Vec3 branch = p.position[k] - p.position[j];
        for (int a = 0; a < 3; ++a)
          branch[a] -= lengths[a] * std::round(branch[a] / lengths[a]);
        apart = inscribed(k) + inscribed(j) - branch.norm() < 0.9 * std::min(inscribed(k), inscribed(j));
      }
    }
  }
}

/// Full checkpoint content: particle rows in id order, contacts sorted by (id_i, id_j), all valid
/// (placed apart in the first 0.01 m of each axis).
inline h5::Checkpoint sample_checkpoint(std::uint64_t seed, std::size_t n_particles, std::size_t n_contacts,
                                        std::size_t n_streams) {
  RandomStream stream(seed, 0);
  h5::Checkpoint checkpoint;
  checkpoint.time = stream.uniform(0, 10);
  checkpoint.step = static_cast<std::int64_t>(stream.below(1'000'000'000));
  checkpoint.time_step = stream.uniform(1e-9, 1e-6);
  h5::CellState& cell = checkpoint.cell;
  cell.lengths = random_vec3(stream, 0.01, 0.02);
  cell.reference_lengths = random_vec3(stream, 0.01, 0.02);
  cell.strain_rate = random_vec3(stream, -1, 1);
  cell.mode = {h5::AxisMode::strain_rate, h5::AxisMode::stress, h5::AxisMode::stress};
  cell.target = random_vec3(stream, -1e5, 1e5);
  cell.hold_mean_stress = true;
  cell.mean_stress_target = 1e5;
  cell.servo_state = random_vec3(stream, -1, 1);

  h5::ParticleRows& p = checkpoint.particles;
  p.resize(n_particles);
  for (std::size_t k = 0; k < n_particles; ++k) {
    p.id[k] = k;
    p.diameter[k] = stream.uniform(1e-3, 2e-3);
    p.aspect_ratio[k] = k % 5 == 0 ? 1.0 : stream.uniform(0.3, 1.0);
    p.mass[k] = stream.uniform(1e-6, 1e-5);
    p.inertia[k] = random_vec3(stream, 1e-13, 1e-12);
    p.orientation[k] = Quat(stream.normal(), stream.normal(), stream.normal(), stream.normal()).normalized();
    p.velocity[k] = random_vec3(stream, -1, 1);
    p.angular_velocity[k] = random_vec3(stream, -100, 100);
    p.force[k] = random_vec3(stream, -1, 1);
    p.torque[k] = random_vec3(stream, -1e-3, 1e-3);
  }
  place_apart(checkpoint, stream, Vec3::Constant(0.01));
  // Values whose bits a careless conversion would change.
  if (n_particles > 2) {
    p.velocity[1] = Vec3(-0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max());
    p.force[2] = Vec3(std::numeric_limits<double>::min() / 3, -std::numeric_limits<double>::lowest(), 1e-300);
  }

  std::set<std::array<std::uint64_t, 2>> pairs;
  while (pairs.size() < n_contacts) {
    const std::uint64_t a = stream.below(n_particles);
    const std::uint64_t b = stream.below(n_particles);
    if (a != b) pairs.insert({std::min(a, b), std::max(a, b)});
  }
  h5::ContactRows& c = checkpoint.contacts;
  c.resize(n_contacts);
  std::size_t k = 0;
  for (const auto& pair : pairs) {
    c.particles[k] = pair;
    c.image_shift[k] = Vec3i(static_cast<int>(stream.below(3)) - 1, static_cast<int>(stream.below(3)) - 1, 0);
    c.normal[k] = random_vec3(stream, -1, 1).normalized();
    c.point[k] = random_vec3(stream, 0, 0.01);
    c.overlap[k] = stream.uniform(1e-9, 1e-6);
    c.force[k] = random_vec3(stream, -1, 1);
    c.tangential_force[k] = random_vec3(stream, -1e-7, 1e-7);
    c.sliding[k] = static_cast<std::uint8_t>(stream.below(2));
    ++k;
  }

  checkpoint.parameters = {{"shear_modulus", 29e9, "Pa"},
                           {"poisson_ratio", 0.15, "1"},
                           {"friction_coefficient", 0.5, "1"},
                           {"density", 2650, "kg/m^3"},
                           {"damping", stream.uniform(0, 1), "1"}};
  checkpoint.rng_state.resize(n_streams);
  for (std::size_t s = 0; s < n_streams; ++s)
    checkpoint.rng_state[s] = RandomStream(seed, s + 1).state();
  return checkpoint;
}

/// Changes one dataset of a written file in place (a damaged or edited file, for failure tests).
template <class T>
void rewrite(const std::string& file_path, const std::string& group, const std::string& dataset,
             const std::function<void(std::vector<T>&)>& change) {
  h5::File file = h5::File::open(file_path, h5::File::Access::read_write);
  auto handle = file.open_group(group).open_dataset(dataset);
  std::vector<T> values = handle.template read<T>();
  change(values);
  handle.write(std::span<const T>(values));
}

inline h5::Provenance sample_provenance(int n_ranks) {
  h5::Provenance provenance;
  provenance.program = "aniso test";
  provenance.version = "0.0.0";
  provenance.git_hash = "0123456789ab";
  provenance.config = "[dem]\nseed = 1\n";
  provenance.command_line = "test --flag";
  provenance.n_ranks = n_ranks;
  provenance.date = "2024-01-01T00:00:00Z";
  return provenance;
}

/// The rows of `full` for which keep_particle(row) / keep_contact(row) hold, in reverse order
/// (so that writers cannot rely on sorted input), or in file order with `in_order`.
inline h5::Checkpoint select_rows(const h5::Checkpoint& full,
                                  const std::function<bool(std::size_t)>& keep_particle,
                                  const std::function<bool(std::size_t)>& keep_contact,
                                  bool in_order = false) {
  const auto row = [&](std::size_t n, std::size_t k) { return in_order ? n - 1 - k : k; };
  h5::Checkpoint part = full;
  part.particles = {};
  part.contacts = {};
  const h5::ParticleRows& p = full.particles;
  for (std::size_t r = p.size(); r-- > 0;) {
    const std::size_t k = row(p.size(), r);
    if (!keep_particle(k)) continue;
    h5::ParticleRows& q = part.particles;
    q.id.push_back(p.id[k]);
    q.diameter.push_back(p.diameter[k]);
    q.aspect_ratio.push_back(p.aspect_ratio[k]);
    q.mass.push_back(p.mass[k]);
    q.inertia.push_back(p.inertia[k]);
    q.position.push_back(p.position[k]);
    q.orientation.push_back(p.orientation[k]);
    q.velocity.push_back(p.velocity[k]);
    q.angular_velocity.push_back(p.angular_velocity[k]);
    q.force.push_back(p.force[k]);
    q.torque.push_back(p.torque[k]);
  }
  const h5::ContactRows& c = full.contacts;
  for (std::size_t r = c.size(); r-- > 0;) {
    const std::size_t k = row(c.size(), r);
    if (!keep_contact(k)) continue;
    h5::ContactRows& d = part.contacts;
    d.particles.push_back(c.particles[k]);
    d.image_shift.push_back(c.image_shift[k]);
    d.normal.push_back(c.normal[k]);
    d.point.push_back(c.point[k]);
    d.overlap.push_back(c.overlap[k]);
    d.force.push_back(c.force[k]);
    d.tangential_force.push_back(c.tangential_force[k]);
    d.sliding.push_back(c.sliding[k]);
  }
  return part;
}

template <class T> bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

inline bool same_bits(const Vec3& a, const Vec3& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Vec3)) == 0;
}

/// Every field of two checkpoints, compared bit for bit.
inline void expect_bit_identical(const h5::Checkpoint& expected, const h5::Checkpoint& actual) {
  EXPECT_TRUE(
      same_bits(std::vector{expected.time, expected.time_step}, std::vector{actual.time, actual.time_step}));
  EXPECT_EQ(expected.step, actual.step);
  const h5::CellState& a = expected.cell;
  const h5::CellState& b = actual.cell;
  EXPECT_TRUE(same_bits(a.lengths, b.lengths));
  EXPECT_TRUE(same_bits(a.reference_lengths, b.reference_lengths));
  EXPECT_TRUE(same_bits(a.strain_rate, b.strain_rate));
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_TRUE(same_bits(a.target, b.target));
  EXPECT_EQ(a.hold_mean_stress, b.hold_mean_stress);
  EXPECT_TRUE(same_bits(std::vector{a.mean_stress_target}, std::vector{b.mean_stress_target}));
  EXPECT_TRUE(same_bits(a.servo_state, b.servo_state));

  const h5::ParticleRows& p = expected.particles;
  const h5::ParticleRows& q = actual.particles;
  EXPECT_EQ(p.id, q.id);
  EXPECT_TRUE(same_bits(p.diameter, q.diameter));
  EXPECT_TRUE(same_bits(p.aspect_ratio, q.aspect_ratio));
  EXPECT_TRUE(same_bits(p.mass, q.mass));
  EXPECT_TRUE(same_bits(p.inertia, q.inertia));
  EXPECT_TRUE(same_bits(p.position, q.position));
  EXPECT_TRUE(same_bits(p.orientation, q.orientation));
  EXPECT_TRUE(same_bits(p.velocity, q.velocity));
  EXPECT_TRUE(same_bits(p.angular_velocity, q.angular_velocity));
  EXPECT_TRUE(same_bits(p.force, q.force));
  EXPECT_TRUE(same_bits(p.torque, q.torque));

  const h5::ContactRows& c = expected.contacts;
  const h5::ContactRows& d = actual.contacts;
  EXPECT_EQ(c.particles, d.particles);
  EXPECT_EQ(c.image_shift, d.image_shift);
  EXPECT_TRUE(same_bits(c.normal, d.normal));
  EXPECT_TRUE(same_bits(c.point, d.point));
  EXPECT_TRUE(same_bits(c.overlap, d.overlap));
  EXPECT_TRUE(same_bits(c.force, d.force));
  EXPECT_TRUE(same_bits(c.tangential_force, d.tangential_force));
  EXPECT_EQ(c.sliding, d.sliding);

  ASSERT_EQ(expected.parameters.size(), actual.parameters.size());
  for (std::size_t k = 0; k < expected.parameters.size(); ++k) {
    EXPECT_EQ(expected.parameters[k].name, actual.parameters[k].name);
    EXPECT_TRUE(
        same_bits(std::vector{expected.parameters[k].value}, std::vector{actual.parameters[k].value}));
    EXPECT_EQ(expected.parameters[k].unit, actual.parameters[k].unit);
  }
  EXPECT_EQ(expected.rng_state, actual.rng_state);
}

/// A fresh folder under the system temp folder, the same on every rank of comm (collective).
inline std::string make_temp_folder(const mpi::Comm& comm, const std::string& stem) {
  std::string path;
  if (comm.is_root()) {
    std::string pattern = (std::filesystem::temp_directory_path() / (stem + "-XXXXXX")).string();
    if (mkdtemp(pattern.data()) != nullptr) path = pattern;
  }
  std::vector<char> bytes(path.begin(), path.end());
  comm.broadcast(bytes, 0);
  return std::string(bytes.begin(), bytes.end());
}

} // namespace aniso::test
