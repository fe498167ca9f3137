#pragma once
// A thin RAII layer over the HDF5 C API: files (serial or MPI-IO), groups,
// datasets and attributes, typed for the element types aniso stores. Every
// failure becomes aniso::FileError naming the file and the object; HDF5's own
// error printing is switched off (docs/formats/checkpoint.md shows a layout).
//
// Parallel files: every call that creates or changes metadata (groups,
// datasets, attributes) is collective and must be made by all ranks of the
// file's communicator with identical arguments. Dataset writes are collective
// (H5FD_MPIO_COLLECTIVE); a rank with nothing to write still calls them.
// Reads are independent and may be made by any subset of ranks.

#include "common/mpi.hpp"
#include "common/row_slab.hpp"

#include <hdf5.h>

#include <concepts>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace aniso::h5 {

/// The element types aniso stores in datasets and numeric attributes.
template <class T>
concept Element = std::same_as<T, double> || std::same_as<T, std::int64_t> ||
    std::same_as<T, std::uint64_t> || std::same_as<T, std::int32_t> || std::same_as<T, std::uint8_t>;

/// Dataset dimensions, slowest first; empty for a scalar.
using Dims = std::vector<hsize_t>;

/// True while the HDF5 library still holds a file that failed to close (a write that failed, disk
/// full): HDF5 would close it again when MPI finalizes, and crashes there, so the process must
/// then end without MPI_Finalize (cli::run does).
bool library_holds_a_failed_file();

/// "[4, 3]" for messages.
std::string format_dims(const Dims& dims);

/// Owns one HDF5 identifier and releases it with the matching H5?close function.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() noexcept = default;
  Handle(hid_t id, Closer closer) noexcept : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  [[nodiscard]] hid_t get() const noexcept { return id_; }
  [[nodiscard]] bool valid() const noexcept { return id_ >= 0; }
  /// Closes now; returns the close status (negative on failure). Idempotent.
  herr_t close() noexcept {
    herr_t status = 0;
    if (id_ >= 0 && closer_ != nullptr) status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }
  void reset() noexcept { static_cast<void>(close()); }

private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// What every object of one open file shares: its path (for messages) and how it was opened.
struct FileContext {
  std::string path;
  bool parallel = false;         ///< opened with MPI-IO
  int rank = 0;                  ///< this rank in the file's communicator (0 when serial)
  int size = 1;                  ///< ranks in the file's communicator (1 when serial)
  MPI_Comm comm = MPI_COMM_NULL; ///< the caller's communicator; must outlive the file
};

/// A set of global rows that this rank writes, given in the order in which the rank holds
/// its data. Rows need not be sorted; a row may appear only once (InputError otherwise).
/// Build it once and reuse it for every dataset that shares the row numbering.
class RowSelection {
public:
  explicit RowSelection(std::span<const std::uint64_t> rows);
  [[nodiscard]] std::size_t size() const { return n_rows_; }
  /// Largest row + 1, or 0 when empty.
  [[nodiscard]] std::uint64_t end() const { return end_; }

private:
  friend class Dataset;
  std::size_t n_rows_ = 0;
  std::uint64_t end_ = 0;
  std::vector<std::size_t> order_;                ///< caller's index of the k-th smallest row
  bool sorted_ = true;                            ///< order_ is the identity
  std::vector<std::pair<hsize_t, hsize_t>> runs_; ///< (first row, count) of consecutive rows
};

/// Anything that carries attributes: a file's root group, a group or a dataset.
class Object {
public:
  [[nodiscard]] hid_t id() const { return handle_.get(); }
  [[nodiscard]] const std::string& file_path() const { return context_->path; }
  /// Absolute path of the object inside the file, "/" for the root.
  [[nodiscard]] const std::string& name() const { return name_; }
  /// "file.h5: /group/dataset", the prefix of every message about this object.
  [[nodiscard]] std::string where() const;
  [[nodiscard]] bool parallel() const { return context_->parallel; }

  [[nodiscard]] bool has_attribute(const std::string& attribute) const;
  /// Writes (or replaces) a scalar numeric attribute. Collective in a parallel file.
  template <Element T> void write_attribute(const std::string& attribute, T value);
  /// Writes (or replaces) a scalar UTF-8 variable-length string attribute. Collective in a parallel file.
  void write_attribute(const std::string& attribute, std::string_view value);
  /// Writes `attribute` = value and `attribute`_units = units: how a scalar attribute carries its SI unit.
  void write_attribute_with_units(const std::string& attribute, double value, std::string_view units);

  /// Reads a scalar numeric attribute; throws FileError if missing, not scalar or of another type class.
  template <Element T> [[nodiscard]] T read_attribute(const std::string& attribute) const;
  /// Reads a string attribute (fixed or variable length); throws FileError if missing or not a string.
  [[nodiscard]] std::string read_string_attribute(const std::string& attribute) const;
  /// Attribute names in creation order where the file tracks it (files aniso writes do), else by name.
  [[nodiscard]] std::vector<std::string> attribute_names() const;

  /// Throws FileError "<file>: <object>: <problem>", with HDF5's innermost error message appended if any.
  [[noreturn]] void fail(const std::string& problem) const;

protected:
  Object(std::shared_ptr<const FileContext> context, Handle handle, std::string name)
      : context_(std::move(context)), handle_(std::move(handle)), name_(std::move(name)) {}
  [[nodiscard]] std::string child_name(const std::string& child) const;

  std::shared_ptr<const FileContext> context_;
  Handle handle_;
  std::string name_;
};

/// A dataset of one of the Element types.
class Dataset : public Object {
public:
  [[nodiscard]] Dims dims() const;

  /// Writes the whole dataset from `data` (row-major, size = product of dims). Collective in a
  /// parallel file: rank 0's data is stored, the other ranks' `data` is ignored (may be empty).
  /// InputError on every rank if rank 0's data has the wrong size.
  template <Element T> void write(std::span<const T> data);
  /// Writes this rank's rows: data holds rows.size() rows of (product of dims[1..]) values each, in
  /// the order of the rows given to RowSelection. Collective in a parallel file; a rank with no rows
  /// still calls it. Different ranks must select disjoint rows (InputError on every rank if not).
  /// In a parallel file the rows first travel to the rank that owns their block of the dataset
  /// (rank r owns rows [R r / P, R (r + 1) / P)), so that each rank writes one contiguous block.
  template <Element T> void write_rows(const RowSelection& rows, std::span<const T> data);
  /// Reads the whole dataset (row-major). Throws FileError if the stored type class or size
  /// differs from T's (no silent conversions).
  template <Element T> [[nodiscard]] std::vector<T> read() const;
  /// As read(), after checking that the shape is `expected` (message: found vs expected dims).
  template <Element T> [[nodiscard]] std::vector<T> read(const Dims& expected) const;
  /// As read(expected), rows `rows` of the first dimension only (one hyperslab): a rank's share
  /// of a dataset that every rank would otherwise read whole.
  template <Element T>
  [[nodiscard]] std::vector<T> read_rows(const Dims& expected, const RowSlab& rows) const;

private:
  friend class Group;
  using Object::Object;
  template <Element T> void check_stored_type() const;
  /// FileError when the dataset claims more elements than the file stores bytes for (a damaged
  /// header, e.g. 1e12 rows in a 200 kB file), before anything that size is allocated.
  void check_stored_size() const;
  /// Throws the FileError of a failed read; a failed checksum is named as damage to the file.
  [[noreturn]] void fail_read() const;
  /// Writes rows already on this rank through one hyperslab union; collective in a parallel file.
  template <Element T>
  void write_local_rows(const RowSelection& rows, std::span<const T> data, const Dims& shape);
};

/// A group; the root group of a file is a File.
class Group : public Object {
public:
  /// Creates a child group that tracks the creation order of its links and attributes. Collective in a
  /// parallel file.
  Group create_group(const std::string& child);
  /// Opens a child group; FileError "missing group" if absent.
  [[nodiscard]] Group open_group(const std::string& child) const;
  /// True if a link of this name exists in this group.
  [[nodiscard]] bool has_child(const std::string& child) const;

  /// Creates a contiguous dataset of T with the given dims and its `units` and `description`
  /// string attributes. Collective in a parallel file.
  template <Element T>
  Dataset create_dataset(const std::string& child, const Dims& dims, std::string_view units,
                         std::string_view description);
  /// Opens a child dataset; FileError "missing dataset" if absent.
  [[nodiscard]] Dataset open_dataset(const std::string& child) const;

  /// create_dataset + Dataset::write: collective in a parallel file, rank 0's data is stored.
  template <Element T>
  void write_dataset(const std::string& child, std::span<const T> data, const Dims& dims,
                     std::string_view units, std::string_view description);
  /// open_dataset + Dataset::read(expected): FileError naming the dataset on a missing dataset or wrong
  /// shape.
  template <Element T>
  [[nodiscard]] std::vector<T> read_dataset(const std::string& child, const Dims& expected) const;
  /// open_dataset + Dataset::read_rows.
  template <Element T>
  [[nodiscard]] std::vector<T> read_dataset_rows(const std::string& child, const Dims& expected,
                                                 const RowSlab& rows) const;

protected:
  friend class File;
  using Object::Object;
};

/// An open HDF5 file; as a Group it is the root group "/". Closing it closes every object in it.
class File : public Group {
public:
  enum class Access { read_only, read_write };

  /// Creates (truncating) a file for this process alone.
  static File create(const std::string& path);
  /// Creates (truncating) a file with MPI-IO on `comm`. Collective on comm; comm must outlive the File.
  static File create(const std::string& path, const mpi::Comm& comm);
  /// Opens an existing file for this process alone. FileError distinguishes a missing file,
  /// a file that is not HDF5, and one that HDF5 cannot open (truncated or damaged).
  static File open(const std::string& path, Access access = Access::read_only);
  /// Opens an existing file with MPI-IO on `comm`. Collective on comm; comm must outlive the File.
  static File open(const std::string& path, const mpi::Comm& comm, Access access = Access::read_only);

  /// Flushes buffers to the file system (collective in a parallel file).
  void flush();
  /// Closes the file (collective in a parallel file); FileError if closing fails. Idempotent.
  void close();

private:
  using Group::Group;
};

} // namespace aniso::h5
