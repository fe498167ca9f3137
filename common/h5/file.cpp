#include "common/h5/file.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <optional>

namespace aniso::h5 {
namespace {

// HDF5 prints its error stack to stderr by default; we report through exceptions instead.
void silence_hdf5() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  static_cast<void>(silenced);
}

herr_t first_description(unsigned /*n*/, const H5E_error2_t* entry, void* client) {
  auto* text = static_cast<std::string*>(client);
  if (text->empty() && entry->desc != nullptr) *text = entry->desc;
  return 0;
}

// The innermost message on HDF5's error stack (where the problem was detected), then clears it.
std::string hdf5_detail() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_description, &text);
  H5Eclear2(H5E_DEFAULT);
  // Some HDF5 messages (a failed write's errno report) span lines; keep the error on one.
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

[[noreturn]] void fail_at(const std::string& where, const std::string& problem) {
  const std::string detail = hdf5_detail();
  throw FileError(where + ": " + problem + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

template <Element T> hid_t memory_type() {
  if constexpr (std::same_as<T, double>)
    return H5T_NATIVE_DOUBLE;
  else if constexpr (std::same_as<T, std::int64_t>)
    return H5T_NATIVE_INT64;
  else if constexpr (std::same_as<T, std::uint64_t>)
    return H5T_NATIVE_UINT64;
  else if constexpr (std::same_as<T, std::int32_t>)
    return H5T_NATIVE_INT32;
  else
    return H5T_NATIVE_UINT8;
}

// Files are little-endian whatever the machine, so that they read the same everywhere.
template <Element T> hid_t file_type() {
  if constexpr (std::same_as<T, double>)
    return H5T_IEEE_F64LE;
  else if constexpr (std::same_as<T, std::int64_t>)
    return H5T_STD_I64LE;
  else if constexpr (std::same_as<T, std::uint64_t>)
    return H5T_STD_U64LE;
  else if constexpr (std::same_as<T, std::int32_t>)
    return H5T_STD_I32LE;
  else
    return H5T_STD_U8LE;
}

template <Element T> std::string type_name() {
  if constexpr (std::same_as<T, double>)
    return "64-bit float";
  else if constexpr (std::same_as<T, std::int64_t>)
    return "64-bit signed integer";
  else if constexpr (std::same_as<T, std::uint64_t>)
    return "64-bit unsigned integer";
  else if constexpr (std::same_as<T, std::int32_t>)
    return "32-bit signed integer";
  else
    return "8-bit unsigned integer";
}

std::string stored_type_name(hid_t type) {
  const H5T_class_t type_class = H5Tget_class(type);
  const std::string bits = std::to_string(8 * H5Tget_size(type)) + "-bit ";
  if (type_class == H5T_FLOAT) return bits + "float";
  if (type_class == H5T_INTEGER)
    return bits + (H5Tget_sign(type) == H5T_SGN_NONE ? "unsigned integer" : "signed integer");
  if (type_class == H5T_STRING) return "string";
  return "non-numeric type";
}

// True if `type` holds exactly T's values: same class, size and signedness.
template <Element T> bool stored_type_matches(hid_t type) {
  const H5T_class_t type_class = H5Tget_class(type);
  if (H5Tget_size(type) != sizeof(T)) return false;
  if constexpr (std::same_as<T, double>) {
    return type_class == H5T_FLOAT;
  } else {
    const bool is_signed = std::same_as<T, std::int64_t> || std::same_as<T, std::int32_t>;
    return type_class == H5T_INTEGER && (H5Tget_sign(type) == H5T_SGN_2) == is_signed;
  }
}

Handle property_list(hid_t property_class, const std::string& path) {
  Handle list(H5Pcreate(property_class), H5Pclose);
  if (!list.valid()) fail_at(path, "cannot create an HDF5 property list");
  return list;
}

// Creation properties that make h5dump and attribute_names() list things in the order written.
void track_creation_order(hid_t create_list, const std::string& where) {
  const unsigned flags = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
  if (H5Pset_link_creation_order(create_list, flags) < 0 ||
      H5Pset_attr_creation_order(create_list, flags) < 0)
    fail_at(where, "cannot set creation-order tracking");
}

Handle string_type(const std::string& where) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), H5T_VARIABLE) < 0 ||
      H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0)
    fail_at(where, "cannot build the string type");
  return type;
}

hsize_t product(const Dims& dims, std::size_t from) {
  hsize_t result = 1;
  for (std::size_t axis = from; axis < dims.size(); ++axis)
    result *= dims[axis];
  return result;
}

// Arrays are stored in chunks of about this size: small enough to checksum and read in pieces,
// large enough that a 6400-particle checkpoint's arrays are one chunk each.
constexpr hsize_t kChunkBytes = hsize_t{1} << 20;

// Every non-empty array carries HDF5's Fletcher32 checksum (which needs a chunked layout), so
// that a flipped bit fails the read, naming the dataset, instead of giving a wrong value.
// Chunks are whole rows along the first axis; scalars and empty arrays stay contiguous.
Handle checksummed_layout(const Dims& dims, std::size_t element_bytes, const std::string& where) {
  if (dims.empty() || product(dims, 0) == 0) return Handle(H5P_DEFAULT, nullptr);
  Handle list = property_list(H5P_DATASET_CREATE, where);
  Dims chunk = dims;
  const hsize_t row_bytes = product(dims, 1) * element_bytes;
  chunk[0] = std::clamp<hsize_t>(kChunkBytes / std::max<hsize_t>(row_bytes, 1), 1, dims[0]);
  if (H5Pset_chunk(list.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
      H5Pset_fletcher32(list.get()) < 0)
    fail_at(where, "cannot set up a checksummed dataset");
  return list;
}

Handle transfer_list(bool parallel, const std::string& where) {
  if (!parallel) return Handle(H5P_DEFAULT, nullptr);
  Handle list = property_list(H5P_DATASET_XFER, where);
  if (H5Pset_dxpl_mpio(list.get(), H5FD_MPIO_COLLECTIVE) < 0)
    fail_at(where, "cannot request collective MPI-IO");
  return list;
}

// Closing a file closes every object still open in it, so that the file is complete on close().
Handle access_list(const std::string& path) {
  Handle list = property_list(H5P_FILE_ACCESS, path);
  if (H5Pset_fclose_degree(list.get(), H5F_CLOSE_STRONG) < 0) fail_at(path, "cannot set the close degree");
  return list;
}

void check_openable(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw FileError(path + ": file not found");
  if (!std::filesystem::is_regular_file(path, error)) throw FileError(path + ": not a regular file");
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 == 0) throw FileError(path + ": not an HDF5 file");
  if (is_hdf5 < 0) fail_at(path, "cannot be read");
}

unsigned open_flags(File::Access access) {
  return access == File::Access::read_write ? H5F_ACC_RDWR : H5F_ACC_RDONLY;
}

} // namespace

std::string format_dims(const Dims& dims) {
  // fmt rather than string concatenation, which GCC 12 under link-time optimisation flags with a
  // false -Wstringop-overflow (GCC bug 105329's family).
  return fmt::format("[{}]", fmt::join(dims, ", "));
}

// ---- RowSelection

RowSelection::RowSelection(std::span<const std::uint64_t> rows) : n_rows_(rows.size()) {
  order_.resize(n_rows_);
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  sorted_ = std::is_sorted(rows.begin(), rows.end());
  // HDF5 walks a hyperslab selection in file order, so the memory buffer must be in row order too.
  if (!sorted_)
    std::sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return rows[a] < rows[b]; });
  for (std::size_t k = 0; k < n_rows_; ++k) {
    const hsize_t row = rows[order_[k]];
    if (runs_.empty() || runs_.back().first + runs_.back().second < row) {
      runs_.emplace_back(row, 1);
    } else if (runs_.back().first + runs_.back().second == row) {
      ++runs_.back().second;
    } else {
      throw InputError("row selection: row " + std::to_string(row) + " given twice");
    }
  }
  end_ = runs_.empty() ? 0 : runs_.back().first + runs_.back().second;
}

// ---- Object

std::string Object::where() const {
  return context_->path + ": " + name_;
}

std::string Object::child_name(const std::string& child) const {
  return name_ == "/" ? "/" + child : name_ + "/" + child;
}

void Object::fail(const std::string& problem) const {
  fail_at(where(), problem);
}

void Dataset::fail_read() const {
  const std::string detail = hdf5_detail();
  if (detail.find("Fletcher32") != std::string::npos)
    throw FileError(where() +
                    ": the data fails its Fletcher32 checksum: the file is damaged (HDF5: " + detail + ")");
  throw FileError(where() + ": read failed" + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

bool Object::has_attribute(const std::string& attribute) const {
  const htri_t exists = H5Aexists(id(), attribute.c_str());
  if (exists < 0) fail("cannot query attribute '" + attribute + "'");
  return exists > 0;
}

namespace {

Handle create_attribute(const Object& object, const std::string& attribute, hid_t type) {
  if (object.has_attribute(attribute) && H5Adelete(object.id(), attribute.c_str()) < 0)
    object.fail("cannot replace attribute '" + attribute + "'");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle handle(H5Acreate2(object.id(), attribute.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                H5Aclose);
  if (!space.valid() || !handle.valid()) object.fail("cannot create attribute '" + attribute + "'");
  return handle;
}

Handle open_attribute(const Object& object, const std::string& attribute) {
  if (!object.has_attribute(attribute)) object.fail("missing attribute '" + attribute + "'");
  Handle handle(H5Aopen(object.id(), attribute.c_str(), H5P_DEFAULT), H5Aclose);
  if (!handle.valid()) object.fail("cannot open attribute '" + attribute + "'");
  Handle space(H5Aget_space(handle.get()), H5Sclose);
  if (!space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1)
    object.fail("attribute '" + attribute + "' is not a scalar");
  return handle;
}

} // namespace

template <Element T> void Object::write_attribute(const std::string& attribute, T value) {
  const Handle handle = create_attribute(*this, attribute, file_type<T>());
  if (H5Awrite(handle.get(), memory_type<T>(), &value) < 0)
    fail("cannot write attribute '" + attribute + "'");
}

void Object::write_attribute(const std::string& attribute, std::string_view value) {
  const Handle type = string_type(where());
  const Handle handle = create_attribute(*this, attribute, type.get());
  const std::string text(value);
  const char* pointer = text.c_str();
  if (H5Awrite(handle.get(), type.get(), static_cast<const void*>(&pointer)) < 0)
    fail("cannot write attribute '" + attribute + "'");
}

void Object::write_attribute_with_units(const std::string& attribute, double value, std::string_view units) {
  write_attribute(attribute, value);
  write_attribute(attribute + "_units", units);
}

template <Element T> T Object::read_attribute(const std::string& attribute) const {
  const Handle handle = open_attribute(*this, attribute);
  const Handle type(H5Aget_type(handle.get()), H5Tclose);
  if (!type.valid() || !stored_type_matches<T>(type.get()))
    fail("attribute '" + attribute + "' is " + (type.valid() ? stored_type_name(type.get()) : "unreadable") +
         ", expected " + type_name<T>());
  T value{};
  if (H5Aread(handle.get(), memory_type<T>(), &value) < 0) fail("cannot read attribute '" + attribute + "'");
  return value;
}

std::string Object::read_string_attribute(const std::string& attribute) const {
  const Handle handle = open_attribute(*this, attribute);
  const Handle type(H5Aget_type(handle.get()), H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_STRING)
    fail("attribute '" + attribute + "' is " + (type.valid() ? stored_type_name(type.get()) : "unreadable") +
         ", expected a string");
  const htri_t variable = H5Tis_variable_str(type.get());
  if (variable > 0) {
    const Handle memory = string_type(where());
    char* pointer = nullptr;
    if (H5Aread(handle.get(), memory.get(), static_cast<void*>(&pointer)) < 0)
      fail("cannot read attribute '" + attribute + "'");
    std::string text = pointer != nullptr ? pointer : "";
    H5free_memory(pointer);
    return text;
  }
  const std::size_t size = H5Tget_size(type.get());
  const Handle memory(H5Tcopy(H5T_C_S1), H5Tclose);
  std::string text(size, '\0');
  if (!memory.valid() || H5Tset_size(memory.get(), size) < 0 ||
      H5Aread(handle.get(), memory.get(), static_cast<void*>(text.data())) < 0)
    fail("cannot read attribute '" + attribute + "'");
  const bool space_padded = H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD;
  while (!text.empty() && (text.back() == '\0' || (space_padded && text.back() == ' ')))
    text.pop_back();
  if (const auto nul = text.find('\0'); nul != std::string::npos) text.resize(nul);
  return text;
}

std::vector<std::string> Object::attribute_names() const {
  H5O_info_t info{};
  if (H5Oget_info2(id(), &info, H5O_INFO_NUM_ATTRS) < 0) fail("cannot list attributes");
  std::vector<std::string> names;
  for (const H5_index_t index : {H5_INDEX_CRT_ORDER, H5_INDEX_NAME}) {
    names.clear();
    for (hsize_t k = 0; k < info.num_attrs; ++k) {
      const ssize_t length = H5Aget_name_by_idx(id(), ".", index, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
      if (length < 0) break;
      std::string name(static_cast<std::size_t>(length) + 1, '\0');
      H5Aget_name_by_idx(id(), ".", index, H5_ITER_INC, k, name.data(), name.size(), H5P_DEFAULT);
      name.resize(static_cast<std::size_t>(length));
      names.push_back(std::move(name));
    }
    if (names.size() == info.num_attrs) {
      H5Eclear2(H5E_DEFAULT);
      return names;
    }
  }
  fail("cannot list attributes");
}

// ---- Dataset

Dims Dataset::dims() const {
  const Handle space(H5Dget_space(id()), H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (rank < 0) fail("cannot read the dataset's shape");
  Dims result(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), result.data(), nullptr) < 0)
    fail("cannot read the dataset's shape");
  return result;
}

template <Element T> void Dataset::check_stored_type() const {
  const Handle type(H5Dget_type(id()), H5Tclose);
  if (!type.valid()) fail("cannot read the dataset's type");
  if (!stored_type_matches<T>(type.get()))
    fail("stored type is " + stored_type_name(type.get()) + ", expected " + type_name<T>());
}

namespace {

// Throws InputError on every rank of a parallel file if any rank has a problem (collective there).
void agree_or_throw(const FileContext& context, const std::string& where, const std::string& local_problem) {
  int failed = local_problem.empty() ? 0 : 1;
  if (context.parallel && context.size > 1 &&
      MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, context.comm) != MPI_SUCCESS)
    throw FileError(where + ": MPI_Allreduce failed");
  if (failed != 0)
    throw InputError(where + ": " + (local_problem.empty() ? "invalid rows on another rank" : local_problem));
}

template <Element T> MPI_Datatype mpi_type() {
  if constexpr (std::same_as<T, double>)
    return MPI_DOUBLE;
  else if constexpr (std::same_as<T, std::int64_t>)
    return MPI_INT64_T;
  else if constexpr (std::same_as<T, std::uint64_t>)
    return MPI_UINT64_T;
  else if constexpr (std::same_as<T, std::int32_t>)
    return MPI_INT32_T;
  else
    return MPI_UINT8_T;
}

} // namespace

template <Element T> void Dataset::write(std::span<const T> data) {
  const hsize_t n_values = product(dims(), 0);
  const bool writer = context_->rank == 0;
  agree_or_throw(*context_, where(),
                 writer && data.size() != n_values
                     ? std::to_string(data.size()) + " values given, dataset holds " +
                           std::to_string(n_values)
                     : std::string());
  if (n_values == 0) return; // every rank knows the shape, so every rank skips together
  const Handle transfer = transfer_list(parallel(), where());
  if (writer) {
    if (H5Dwrite(id(), memory_type<T>(), H5S_ALL, H5S_ALL, transfer.get(), data.data()) < 0)
      fail("write failed");
    return;
  }
  // Other ranks take part in the collective write with an empty selection.
  Handle file_space(H5Dget_space(id()), H5Sclose);
  const hsize_t one = 1;
  Handle memory_space(H5Screate_simple(1, &one, nullptr), H5Sclose);
  const T dummy{};
  if (!file_space.valid() || !memory_space.valid() || H5Sselect_none(file_space.get()) < 0 ||
      H5Sselect_none(memory_space.get()) < 0 ||
      H5Dwrite(id(), memory_type<T>(), memory_space.get(), file_space.get(), transfer.get(), &dummy) < 0)
    fail("write failed");
}

template <Element T> void Dataset::write_rows(const RowSelection& rows, std::span<const T> data) {
  const Dims shape = dims();
  const hsize_t row_width = shape.empty() ? 0 : product(shape, 1);
  std::string problem;
  if (shape.empty())
    problem = "write_rows on a scalar dataset";
  else if (data.size() != rows.size() * row_width)
    problem = std::to_string(data.size()) + " values given for " + std::to_string(rows.size()) + " rows of " +
              std::to_string(row_width);
  else if (rows.end() > shape[0])
    problem = "row " + std::to_string(rows.end() - 1) + " beyond the " + std::to_string(shape[0]) +
              " rows of the dataset";
  agree_or_throw(*context_, where(), problem);
  if (shape[0] == 0 || row_width == 0) return; // empty dataset: all ranks skip together
  if (!parallel() || context_->size == 1) {
    write_local_rows(rows, data, shape);
    return;
  }

  // HDF5 1.10 builds a union of hyperslabs in time quadratic in their number, and rows from a
  // spatial decomposition are scattered. So each row first goes to the rank owning its block of
  // the dataset; each rank then writes one contiguous block (for a complete set of rows).
  const int n_ranks = context_->size;
  const hsize_t n_total = shape[0];
  const auto block_start = [&](int rank) { return slab_start(n_total, rank, n_ranks); };
  std::vector<int> send_counts(static_cast<std::size_t>(n_ranks), 0);
  std::vector<std::uint64_t> send_rows;
  send_rows.reserve(rows.size());
  std::vector<T> send_values;
  send_values.reserve(data.size());
  int destination = 0;
  std::size_t sorted = 0;
  for (const auto& [first, n_rows] : rows.runs_) {
    for (hsize_t row = first; row < first + n_rows; ++row, ++sorted) {
      while (row >= block_start(destination + 1))
        ++destination;
      ++send_counts[static_cast<std::size_t>(destination)];
      send_rows.push_back(row);
      const auto source = data.begin() + static_cast<std::ptrdiff_t>(rows.order_[sorted] * row_width);
      send_values.insert(send_values.end(), source, source + static_cast<std::ptrdiff_t>(row_width));
    }
  }
  std::vector<int> receive_counts(send_counts.size(), 0);
  if (MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, context_->comm) !=
      MPI_SUCCESS)
    fail("MPI_Alltoall of row counts failed");
  std::vector<int> send_offsets(send_counts.size(), 0);
  std::vector<int> receive_offsets(send_counts.size(), 0);
  std::exclusive_scan(send_counts.begin(), send_counts.end(), send_offsets.begin(), 0);
  std::exclusive_scan(receive_counts.begin(), receive_counts.end(), receive_offsets.begin(), 0);
  const auto n_received = static_cast<std::size_t>(receive_offsets.back() + receive_counts.back());
  std::vector<std::uint64_t> received_rows(n_received);
  std::vector<T> received_values(n_received * row_width);
  MPI_Datatype row_type = MPI_DATATYPE_NULL;
  if (MPI_Type_contiguous(static_cast<int>(row_width), mpi_type<T>(), &row_type) != MPI_SUCCESS ||
      MPI_Type_commit(&row_type) != MPI_SUCCESS)
    fail("cannot build the MPI row type");
  const bool exchanged = MPI_Alltoallv(send_rows.data(), send_counts.data(), send_offsets.data(),
                                       MPI_UINT64_T, received_rows.data(), receive_counts.data(),
                                       receive_offsets.data(), MPI_UINT64_T, context_->comm) == MPI_SUCCESS &&
                         MPI_Alltoallv(send_values.data(), send_counts.data(), send_offsets.data(), row_type,
                                       received_values.data(), receive_counts.data(), receive_offsets.data(),
                                       row_type, context_->comm) == MPI_SUCCESS;
  MPI_Type_free(&row_type);
  if (!exchanged) fail("MPI_Alltoallv of rows failed");

  std::optional<RowSelection> block;
  problem.clear();
  try {
    block.emplace(received_rows);
  } catch (const InputError& error) {
    problem = std::string(error.what()) + " (by two ranks)";
  }
  agree_or_throw(*context_, where(), problem);
  write_local_rows(*block, std::span<const T>(received_values), shape);
}

template <Element T>
void Dataset::write_local_rows(const RowSelection& rows, std::span<const T> data, const Dims& shape) {
  const hsize_t row_width = product(shape, 1);
  Handle file_space(H5Dget_space(id()), H5Sclose);
  if (!file_space.valid() || H5Sselect_none(file_space.get()) < 0) fail("cannot select rows");
  Dims start(shape.size(), 0);
  Dims count = shape;
  for (const auto& [first, n_rows] : rows.runs_) {
    start[0] = first;
    count[0] = n_rows;
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_OR, start.data(), nullptr, count.data(), nullptr) <
        0)
      fail("cannot select rows");
  }
  const hsize_t n_values = std::max<hsize_t>(data.size(), 1);
  Handle memory_space(H5Screate_simple(1, &n_values, nullptr), H5Sclose);
  if (!memory_space.valid() || (data.empty() && H5Sselect_none(memory_space.get()) < 0))
    fail("cannot build the memory selection");

  // HDF5 walks a hyperslab union in file order, so the buffer must be in row order too.
  std::vector<T> reordered;
  const T* buffer = data.data();
  if (!rows.sorted_) {
    reordered.resize(data.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(rows.order_[k] * row_width), row_width,
                  reordered.begin() + static_cast<std::ptrdiff_t>(k * row_width));
    buffer = reordered.data();
  }
  const T dummy{};
  if (buffer == nullptr) buffer = &dummy;
  const Handle transfer = transfer_list(parallel(), where());
  if (H5Dwrite(id(), memory_type<T>(), memory_space.get(), file_space.get(), transfer.get(), buffer) < 0)
    fail("write failed");
}

void Dataset::check_stored_size() const {
  const Handle type(H5Dget_type(id()), H5Tclose);
  const Handle creation(H5Dget_create_plist(id()), H5Pclose);
  if (!type.valid() || !creation.valid()) fail("cannot read the dataset's type or layout");
  // Only a compressing filter may store fewer bytes than the data hold (Fletcher32 adds four).
  const int n_filters = H5Pget_nfilters(creation.get());
  for (int k = 0; k < n_filters; ++k) {
    unsigned flags = 0;
    std::size_t n_values = 0;
    unsigned config = 0;
    if (H5Pget_filter2(creation.get(), static_cast<unsigned>(k), &flags, &n_values, nullptr, 0, nullptr,
                       &config) != H5Z_FILTER_FLETCHER32)
      return;
  }
  const double claimed =
      static_cast<double>(product(dims(), 0)) * static_cast<double>(H5Tget_size(type.get()));
  const auto stored = static_cast<double>(H5Dget_storage_size(id()));
  if (claimed > stored)
    fail(fmt::format(
        "shape {} claims {:.4g} bytes but the file stores {:.4g} bytes of it: the file is damaged",
        format_dims(dims()), claimed, stored));
}

template <Element T> std::vector<T> Dataset::read() const {
  check_stored_type<T>();
  check_stored_size();
  std::vector<T> values(product(dims(), 0));
  if (!values.empty() && H5Dread(id(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    fail_read();
  return values;
}

template <Element T> std::vector<T> Dataset::read(const Dims& expected) const {
  const Dims found = dims();
  if (found != expected) fail("shape " + format_dims(found) + " found, expected " + format_dims(expected));
  return read<T>();
}

template <Element T> std::vector<T> Dataset::read_rows(const Dims& expected, const RowSlab& rows) const {
  const Dims found = dims();
  if (found != expected) fail("shape " + format_dims(found) + " found, expected " + format_dims(expected));
  if (found.empty() || rows.end() > found[0])
    fail(fmt::format("rows {}..{} asked of shape {}", rows.first, rows.end(), format_dims(found)));
  if (rows.first == 0 && rows.count == found[0]) return read<T>(); // HDF5's whole-dataset path
  check_stored_type<T>();
  check_stored_size();
  std::vector<T> values(rows.count * product(found, 1));
  if (values.empty()) return values;
  Handle file_space(H5Dget_space(id()), H5Sclose);
  Dims start(found.size(), 0);
  Dims count = found;
  start[0] = rows.first;
  count[0] = rows.count;
  const hsize_t n_values = values.size();
  Handle memory_space(H5Screate_simple(1, &n_values, nullptr), H5Sclose);
  if (!file_space.valid() || !memory_space.valid() ||
      H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) < 0)
    fail("cannot select rows");
  if (H5Dread(id(), memory_type<T>(), memory_space.get(), file_space.get(), H5P_DEFAULT, values.data()) < 0)
    fail_read();
  return values;
}

// ---- Group

Group Group::create_group(const std::string& child) {
  const std::string name = child_name(child);
  Handle create_list = property_list(H5P_GROUP_CREATE, context_->path + ": " + name);
  track_creation_order(create_list.get(), context_->path + ": " + name);
  Handle handle(H5Gcreate2(id(), child.c_str(), H5P_DEFAULT, create_list.get(), H5P_DEFAULT), H5Gclose);
  if (!handle.valid()) fail_at(context_->path + ": " + name, "cannot create group");
  return Group(context_, std::move(handle), name);
}

bool Group::has_child(const std::string& child) const {
  const htri_t exists = H5Lexists(id(), child.c_str(), H5P_DEFAULT);
  if (exists < 0) fail("cannot look up '" + child + "'");
  return exists > 0;
}

Group Group::open_group(const std::string& child) const {
  const std::string name = child_name(child);
  if (!has_child(child)) throw FileError(context_->path + ": " + name + ": missing group");
  Handle handle(H5Gopen2(id(), child.c_str(), H5P_DEFAULT), H5Gclose);
  if (!handle.valid()) fail_at(context_->path + ": " + name, "cannot open group");
  return Group(context_, std::move(handle), name);
}

template <Element T>
Dataset Group::create_dataset(const std::string& child, const Dims& dims, std::string_view units,
                              std::string_view description) {
  const std::string name = child_name(child);
  Handle space(dims.empty() ? H5Screate(H5S_SCALAR)
                            : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
               H5Sclose);
  if (!space.valid()) fail_at(context_->path + ": " + name, "cannot create dataspace " + format_dims(dims));
  const Handle create_list = checksummed_layout(dims, sizeof(T), context_->path + ": " + name);
  Handle handle(H5Dcreate2(id(), child.c_str(), file_type<T>(), space.get(), H5P_DEFAULT, create_list.get(),
                           H5P_DEFAULT),
                H5Dclose);
  if (!handle.valid()) fail_at(context_->path + ": " + name, "cannot create dataset");
  Dataset dataset(context_, std::move(handle), name);
  dataset.write_attribute("units", units);
  dataset.write_attribute("description", description);
  return dataset;
}

Dataset Group::open_dataset(const std::string& child) const {
  const std::string name = child_name(child);
  if (!has_child(child)) throw FileError(context_->path + ": " + name + ": missing dataset");
  Handle handle(H5Dopen2(id(), child.c_str(), H5P_DEFAULT), H5Dclose);
  if (!handle.valid()) fail_at(context_->path + ": " + name, "cannot open dataset");
  return Dataset(context_, std::move(handle), name);
}

template <Element T>
void Group::write_dataset(const std::string& child, std::span<const T> data, const Dims& dims,
                          std::string_view units, std::string_view description) {
  create_dataset<T>(child, dims, units, description).write(data);
}

template <Element T>
std::vector<T> Group::read_dataset(const std::string& child, const Dims& expected) const {
  return open_dataset(child).read<T>(expected);
}

template <Element T>
std::vector<T> Group::read_dataset_rows(const std::string& child, const Dims& expected,
                                        const RowSlab& rows) const {
  return open_dataset(child).read_rows<T>(expected, rows);
}

// ---- File

bool library_holds_a_failed_file() {
  // Every File closes its identifier when it goes out of scope, so one still counted after the
  // stage's body has returned is a file whose close failed.
  return H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE) > 0;
}

File File::create(const std::string& path) {
  silence_hdf5();
  Handle create_list = property_list(H5P_FILE_CREATE, path);
  track_creation_order(create_list.get(), path);
  const Handle access = access_list(path);
  Handle handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, create_list.get(), access.get()), H5Fclose);
  if (!handle.valid()) fail_at(path, "cannot create file");
  return File(std::make_shared<const FileContext>(FileContext{path, false, 0}), std::move(handle), "/");
}

File File::create(const std::string& path, const mpi::Comm& comm) {
  silence_hdf5();
  Handle create_list = property_list(H5P_FILE_CREATE, path);
  track_creation_order(create_list.get(), path);
  const Handle access = access_list(path);
  if (H5Pset_fapl_mpio(access.get(), comm.raw(), MPI_INFO_NULL) < 0) fail_at(path, "cannot select MPI-IO");
  Handle handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, create_list.get(), access.get()), H5Fclose);
  if (!handle.valid()) fail_at(path, "cannot create file with MPI-IO");
  return File(
      std::make_shared<const FileContext>(FileContext{path, true, comm.rank(), comm.size(), comm.raw()}),
      std::move(handle), "/");
}

File File::open(const std::string& path, Access access) {
  silence_hdf5();
  check_openable(path);
  const Handle access_properties = access_list(path);
  Handle handle(H5Fopen(path.c_str(), open_flags(access), access_properties.get()), H5Fclose);
  if (!handle.valid()) fail_at(path, "HDF5 cannot open the file (truncated or damaged?)");
  return File(std::make_shared<const FileContext>(FileContext{path, false, 0}), std::move(handle), "/");
}

File File::open(const std::string& path, const mpi::Comm& comm, Access access) {
  silence_hdf5();
  check_openable(path);
  const Handle access_properties = access_list(path);
  if (H5Pset_fapl_mpio(access_properties.get(), comm.raw(), MPI_INFO_NULL) < 0)
    fail_at(path, "cannot select MPI-IO");
  Handle handle(H5Fopen(path.c_str(), open_flags(access), access_properties.get()), H5Fclose);
  if (!handle.valid()) fail_at(path, "HDF5 cannot open the file with MPI-IO (truncated or damaged?)");
  return File(
      std::make_shared<const FileContext>(FileContext{path, true, comm.rank(), comm.size(), comm.raw()}),
      std::move(handle), "/");
}

void File::flush() {
  if (handle_.valid() && H5Fflush(id(), H5F_SCOPE_GLOBAL) < 0) fail("flush failed");
}

void File::close() {
  if (handle_.valid() && handle_.close() < 0) fail_at(context_->path, "close failed");
}

// ---- The element types aniso stores

#define ANISO_H5_INSTANTIATE(T)                                                                              \
  template void Object::write_attribute<T>(const std::string&, T);                                           \
  template T Object::read_attribute<T>(const std::string&) const;                                            \
  template void Dataset::write<T>(std::span<const T>);                                                       \
  template void Dataset::write_rows<T>(const RowSelection&, std::span<const T>);                             \
  template void Dataset::write_local_rows<T>(const RowSelection&, std::span<const T>, const Dims&);          \
  template std::vector<T> Dataset::read<T>() const;                                                          \
  template std::vector<T> Dataset::read<T>(const Dims&) const;                                               \
  template std::vector<T> Dataset::read_rows<T>(const Dims&, const RowSlab&) const;                          \
  template std::vector<T> Group::read_dataset_rows<T>(const std::string&, const Dims&, const RowSlab&)       \
      const;                                                                                                 \
  template Dataset Group::create_dataset<T>(const std::string&, const Dims&, std::string_view,               \
                                            std::string_view);                                               \
  template void Group::write_dataset<T>(const std::string&, std::span<const T>, const Dims&,                 \
                                        std::string_view, std::string_view);                                 \
  template std::vector<T> Group::read_dataset<T>(const std::string&, const Dims&) const;

ANISO_H5_INSTANTIATE(double)
ANISO_H5_INSTANTIATE(std::int64_t)
ANISO_H5_INSTANTIATE(std::uint64_t)
ANISO_H5_INSTANTIATE(std::int32_t)
ANISO_H5_INSTANTIATE(std::uint8_t)
#undef ANISO_H5_INSTANTIATE

} // namespace aniso::h5
