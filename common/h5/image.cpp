#include "common/h5/image.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/memory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <span>

namespace aniso::h5 {
namespace {

constexpr const char* image_schema_name = "aniso-voxel-image";
constexpr const char* phase_path = "/image/phase";
// 64^3 bytes = 256 KiB chunks: large enough for fast deflate, small enough for partial reads.
constexpr hsize_t chunk_edge = 64;
// Level 1: solid/void images compress ~10x already at level 1; higher levels cost time for little.
constexpr unsigned deflate_level = 1;

Dims disk_dims(const VoxelImage& image) {
  return {image.shape[2], image.shape[1], image.shape[0]};
}

void check_image(const VoxelImage& image, const std::string& path) {
  const std::string where = path + ": voxel image: ";
  for (std::size_t axis = 0; axis < 3; ++axis)
    require_input(image.shape[axis] > 0,
                  where + "shape has a zero extent along x" + std::to_string(axis + 1));
  require_input(
      image.phase.size() == image.size(),
      where + fmt::format("phase has {} values, expected n1*n2*n3 = {}", image.phase.size(), image.size()));
  require_input(std::isfinite(image.voxel_size) && image.voxel_size > 0,
                where + fmt::format("voxel_size {} is not a finite positive length", image.voxel_size));
  require_input(image.origin.allFinite(), where + "origin is not finite");
  const auto bad = std::find_if(image.phase.begin(), image.phase.end(), [](std::uint8_t v) { return v > 1; });
  require_input(bad == image.phase.end(),
                where + fmt::format("phase value {} at index {}, expected 0 (void) or 1 (solid)",
                                    bad == image.phase.end() ? 0 : *bad, bad - image.phase.begin()));
}

// Creates /image/phase in cubic chunks, deflated and checksummed (file.hpp's create_dataset chunks by rows).
Dataset create_phase_dataset(Group& group, const Dims& dims) {
  const std::string where = group.file_path() + ": " + phase_path;
  const Handle space(H5Screate_simple(3, dims.data(), nullptr), H5Sclose);
  const Handle create_list(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  std::array<hsize_t, 3> chunk{};
  for (std::size_t axis = 0; axis < 3; ++axis)
    chunk[axis] = std::min(dims[axis], chunk_edge);
  if (!space.valid() || !create_list.valid() || H5Pset_chunk(create_list.get(), 3, chunk.data()) < 0 ||
      H5Pset_deflate(create_list.get(), deflate_level) < 0 || H5Pset_fletcher32(create_list.get()) < 0)
    throw FileError(where + ": cannot set up a chunked, deflated dataset");
  const Handle dataset(
      H5Dcreate2(group.id(), "phase", H5T_STD_U8LE, space.get(), H5P_DEFAULT, create_list.get(), H5P_DEFAULT),
      H5Dclose);
  if (!dataset.valid()) throw FileError(where + ": cannot create dataset");
  return group.open_dataset("phase");
}

void write_origin(const Dataset& dataset, const Vec3& origin) {
  const hsize_t three = 3;
  const Handle space(H5Screate_simple(1, &three, nullptr), H5Sclose);
  const Handle attribute(
      H5Acreate2(dataset.id(), "origin", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const std::array<double, 3> values{origin.x(), origin.y(), origin.z()};
  if (!attribute.valid() || H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) < 0)
    dataset.fail("cannot write attribute 'origin'");
}

Vec3 read_origin(const Dataset& dataset) {
  if (!dataset.has_attribute("origin")) dataset.fail("missing attribute 'origin'");
  const Handle attribute(H5Aopen(dataset.id(), "origin", H5P_DEFAULT), H5Aclose);
  const Handle space(H5Aget_space(attribute.get()), H5Sclose);
  const Handle type(H5Aget_type(attribute.get()), H5Tclose);
  if (!attribute.valid() || !space.valid() || !type.valid()) dataset.fail("cannot open attribute 'origin'");
  hsize_t count = 0;
  if (H5Sget_simple_extent_ndims(space.get()) != 1 ||
      H5Sget_simple_extent_dims(space.get(), &count, nullptr) != 1 || count != 3 ||
      H5Tget_class(type.get()) != H5T_FLOAT)
    dataset.fail("attribute 'origin' must be 3 floating-point values");
  std::array<double, 3> values{};
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) < 0)
    dataset.fail("cannot read attribute 'origin'");
  const Vec3 origin(values[0], values[1], values[2]);
  if (!origin.allFinite()) dataset.fail("attribute 'origin' is not finite");
  return origin;
}

void write_hdf5(const std::string& temp_path, const VoxelImage& image, const Provenance& provenance) {
  File file = File::create(temp_path);
  file.write_attribute("schema", std::string_view(image_schema_name));
  file.write_attribute("schema_version", image_schema_version);
  file.write_attribute("description",
                       std::string_view("aniso periodic voxel image (1 solid, 0 void); layout: "
                                        "docs/formats/image.md"));
  write_provenance(file, provenance);
  Group group = file.create_group("image");
  Dataset phase = create_phase_dataset(group, disk_dims(image));
  phase.write_attribute("units", std::string_view("1"));
  phase.write_attribute(
      "description",
      std::string_view("1 solid, 0 void; dims [n3, n2, n1], x1 fastest; voxel (i, j, k) covers "
                       "origin + voxel_size * ([i, i+1] x [j, j+1] x [k, k+1])"));
  phase.write_attribute_with_units("voxel_size", image.voxel_size, "m");
  write_origin(phase, image.origin);
  phase.write_attribute("origin_units", std::string_view("m"));
  phase.write_attribute("periodic", std::int64_t{1});
  phase.write_attribute("schema_version", image_schema_version);
  phase.write_attribute("source", std::string_view(image.source));
  phase.write_attribute("source_hash", std::string_view(image.source_hash));
  phase.write<std::uint8_t>(image.phase);
  file.close();
}

// ParaView reads the image through this XDMF 3 description: a cell-centred uint8 field on a
// 3DCoRectMesh. XDMF lists dimensions slowest first (z y x), so origin and spacing are reversed.
std::string xdmf_text(const std::string& h5_name, const VoxelImage& image) {
  const auto [n1, n2, n3] = image.shape;
  const double h = image.voxel_size;
  return fmt::format(
      R"(<?xml version="1.0" ?>
<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>
<Xdmf Version="3.0">
  <Domain>
    <Grid Name="image" GridType="Uniform">
      <Topology TopologyType="3DCoRectMesh" Dimensions="{3} {2} {1}"/>
      <Geometry GeometryType="ORIGIN_DXDYDZ">
        <DataItem Name="Origin" Dimensions="3" NumberType="Float" Precision="8" Format="XML">{6:.17g} {5:.17g} {4:.17g}</DataItem>
        <DataItem Name="Spacing" Dimensions="3" NumberType="Float" Precision="8" Format="XML">{7:.17g} {7:.17g} {7:.17g}</DataItem>
      </Geometry>
      <Attribute Name="phase" AttributeType="Scalar" Center="Cell">
        <DataItem Dimensions="{10} {9} {8}" NumberType="UChar" Precision="1" Format="HDF">{0}:/image/phase</DataItem>
      </Attribute>
    </Grid>
  </Domain>
</Xdmf>
)",
      h5_name, n1 + 1, n2 + 1, n3 + 1, image.origin.x(), image.origin.y(), image.origin.z(), h, n1, n2, n3);
}

std::int64_t read_int_attribute(const Dataset& dataset, const std::string& name) {
  if (!dataset.has_attribute(name)) dataset.fail("missing attribute '" + name + "'");
  return dataset.read_attribute<std::int64_t>(name);
}

} // namespace

std::string xdmf_sidecar_path(const std::string& path) {
  std::filesystem::path result(path);
  if (result.extension() == ".h5") return result.replace_extension(".xmf").string();
  return path + ".xmf";
}

void write_voxel_image(const std::string& path, const VoxelImage& image, const Provenance& provenance) {
  check_image(image, path);
  {
    AtomicFile atomic(path);
    write_hdf5(atomic.temp_path(), image, provenance);
    atomic.commit();
  }
  write_text_atomically(xdmf_sidecar_path(path),
                        xdmf_text(std::filesystem::path(path).filename().string(), image));
}

VoxelImage read_voxel_image(const std::string& path) {
  const File file = File::open(path);
  if (!file.has_attribute("schema"))
    file.fail(std::string("missing attribute 'schema' (expected '") + image_schema_name +
              "'): not a voxel image");
  const std::string schema = file.read_string_attribute("schema");
  if (schema != image_schema_name)
    file.fail("schema '" + schema + "' found, expected '" + image_schema_name + "'");
  const Group group = file.open_group("image");
  const Dataset phase = group.open_dataset("phase");
  const std::int64_t version = read_int_attribute(phase, "schema_version");
  if (version != image_schema_version)
    phase.fail(fmt::format("schema_version {} found, expected {}", version, image_schema_version));
  if (read_int_attribute(phase, "periodic") != 1) phase.fail("attribute 'periodic' must be 1");

  VoxelImage image;
  const Dims dims = phase.dims();
  if (dims.size() != 3 || std::find(dims.begin(), dims.end(), hsize_t{0}) != dims.end())
    phase.fail("shape " + format_dims(dims) + " found, expected three positive extents [n3, n2, n1]");
  image.shape = {dims[2], dims[1], dims[0]};
  if (!phase.has_attribute("voxel_size")) phase.fail("missing attribute 'voxel_size'");
  image.voxel_size = phase.read_attribute<double>("voxel_size");
  if (!(std::isfinite(image.voxel_size) && image.voxel_size > 0))
    phase.fail(fmt::format("voxel_size {} is not a finite positive length", image.voxel_size));
  image.origin = read_origin(phase);
  image.source = phase.read_string_attribute("source");
  image.source_hash = phase.read_string_attribute("source_hash");
  require_memory(static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]),
                 fmt::format("{}: the {} x {} x {} voxel image", path, dims[2], dims[1], dims[0]),
                 "use a coarser image (voxel.resolution)");
  image.phase = phase.read<std::uint8_t>();
  const auto bad = std::find_if(image.phase.begin(), image.phase.end(), [](std::uint8_t v) { return v > 1; });
  if (bad != image.phase.end())
    phase.fail(fmt::format("value {} at flat index {}, expected 0 (void) or 1 (solid)", *bad,
                           bad - image.phase.begin()));
  return image;
}

} // namespace aniso::h5
