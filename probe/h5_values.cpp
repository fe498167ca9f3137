#include "probe/h5_values.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace aniso::probe {
namespace {

void require_finite(const h5::Object& object, const std::string& name, const std::vector<double>& values) {
  for (const double v : values) {
    if (!std::isfinite(v)) object.fail("'" + name + "' holds a non-finite value");
  }
}

} // namespace

void write_matrix(h5::Group& group, const std::string& name, const Mat3& value, std::string_view units,
                  std::string_view description) {
  std::array<double, 9> rows{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      rows[static_cast<std::size_t>(3 * i + j)] = value(i, j);
  group.write_dataset<double>(name, rows, {3, 3}, units, description);
}

void write_vector(h5::Group& group, const std::string& name, const Vec3& value, std::string_view units,
                  std::string_view description) {
  const std::array<double, 3> data{value[0], value[1], value[2]};
  group.write_dataset<double>(name, data, {3}, units, description);
}

Mat3 read_matrix(const h5::Group& group, const std::string& name) {
  const std::vector<double> rows = group.read_dataset<double>(name, {3, 3});
  require_finite(group, name, rows);
  Mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m(i, j) = rows[static_cast<std::size_t>(3 * i + j)];
  return m;
}

Vec3 read_vector(const h5::Group& group, const std::string& name) {
  const std::vector<double> data = group.read_dataset<double>(name, {3});
  require_finite(group, name, data);
  return {data[0], data[1], data[2]};
}

double read_finite(const h5::Object& object, const std::string& name) {
  const double value = object.read_attribute<double>(name);
  if (!std::isfinite(value)) object.fail("attribute '" + name + "' is not finite");
  return value;
}

} // namespace aniso::probe
