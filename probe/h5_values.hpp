#pragma once
// Small HDF5 helpers of the probe files: 3x3 matrices (row-major on disk, row i =
// stress component) and 3-vectors written with units and a description, and read
// back with shape and finiteness checks that name the file and the dataset.

#include "common/h5/file.hpp"
#include "common/tensor.hpp"

#include <string>
#include <string_view>

namespace aniso::probe {

void write_matrix(h5::Group& group, const std::string& name, const Mat3& value, std::string_view units,
                  std::string_view description);
void write_vector(h5::Group& group, const std::string& name, const Vec3& value, std::string_view units,
                  std::string_view description);
/// FileError naming the file and dataset if missing, not 3x3, or not finite.
Mat3 read_matrix(const h5::Group& group, const std::string& name);
Vec3 read_vector(const h5::Group& group, const std::string& name);
/// A finite double attribute; FileError naming the file and attribute otherwise.
double read_finite(const h5::Object& object, const std::string& name);

} // namespace aniso::probe
