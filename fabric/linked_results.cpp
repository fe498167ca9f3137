#include "fabric/linked_results.hpp"

#include "common/error.hpp"
#include "common/h5/file.hpp"

#include <cmath>
#include <filesystem>
#include <vector>

namespace aniso::fabric {
namespace {

std::vector<double> read_finite(const h5::Group& group, const std::string& name, const h5::Dims& dims) {
  std::vector<double> values = group.read_dataset<double>(name, dims);
  for (double v : values)
    if (!std::isfinite(v)) group.open_dataset(name).fail("holds a non-finite value");
  return values;
}

Mat3 read_matrix(const h5::Group& group, const std::string& name) {
  const std::vector<double> v = read_finite(group, name, {3, 3});
  Mat3 m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      m(a, b) = v[static_cast<std::size_t>(3 * a + b)];
  return m;
}

Vec3 read_vector(const h5::Group& group, const std::string& name) {
  const std::vector<double> v = read_finite(group, name, {3});
  return {v[0], v[1], v[2]};
}

std::string read_hash(const h5::Object& object) {
  std::string hash = object.read_string_attribute("source_hash");
  if (hash.empty())
    object.fail("attribute source_hash is empty: the result cannot be linked to a checkpoint");
  return hash;
}

// The permeability's source: the voxel image, or (as aniso-lbm writes it) the checkpoint that
// image came from. A relative path is tried as given, then beside the permeability file.
std::string resolve(const std::string& permeability_path, const std::string& source) {
  if (std::filesystem::exists(source)) return source;
  const auto beside = std::filesystem::path(permeability_path).parent_path() / source;
  return std::filesystem::exists(beside) ? beside.string() : std::string();
}

} // namespace

ProbeStiffness read_probe_stiffness(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("stiffness");
  ProbeStiffness p;
  p.path = path;
  p.checkpoint_hash = read_hash(group);
  p.C = read_matrix(group, "C");
  p.K_C = group.read_attribute<double>("K_C");
  if (!(std::isfinite(p.K_C) && p.K_C > 0)) group.fail("attribute K_C must be positive and finite");
  if (group.has_attribute("checks_passed"))
    p.checks_passed = group.read_attribute<std::int64_t>("checks_passed") != 0;
  return p;
}

Permeability read_permeability(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("permeability");
  Permeability k;
  k.path = path;
  k.K = read_matrix(group, "K");
  k.checkpoint_hash = read_hash(group);
  // When the source is a voxel image, the checkpoint is the one the image names.
  const std::string source = resolve(path, group.read_string_attribute("source"));
  if (!source.empty()) {
    const h5::File origin = h5::File::open(source);
    if (origin.has_child("image"))
      k.checkpoint_hash = read_hash(origin.open_group("image").open_dataset("phase"));
  }
  return k;
}

VoidMedians read_void_medians(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("voids");
  VoidMedians v;
  v.path = path;
  v.checkpoint_hash = read_hash(group);
  v.free_path = read_vector(group, "free_path_median");
  v.breadth = read_vector(group, "breadth_median");
  for (int a = 0; a < 3; ++a)
    if (!(v.free_path[a] > 0 && v.breadth[a] > 0))
      group.fail("median free paths and breadths must be positive");
  return v;
}

} // namespace aniso::fabric
