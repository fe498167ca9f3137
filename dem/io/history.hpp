#pragma once
// The loading history: one row per history interval of strain, in HDF5
// (history.h5, one 1-D dataset per column with its unit) and CSV. Rewritten
// atomically at every checkpoint, so the file on disk always matches a
// checkpoint that exists. Layout: docs/formats/history.md.

#include "common/h5/provenance.hpp"
#include "common/timer.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aniso::dem::io {

/// history.h5's schema version; files of other versions are refused with a message naming both.
inline constexpr std::int64_t history_schema_version = 4;

/// One row of the history, filled by name (history_columns() says what each member is).
struct HistoryRow {
  double step = 0, time = 0;
  double strain_11 = 0, strain_22 = 0, strain_33 = 0, volumetric_strain = 0;
  double stress_11 = 0, stress_22 = 0, stress_33 = 0, stress_23 = 0, stress_13 = 0, stress_12 = 0;
  double p = 0, q = 0, stress_ratio = 0, void_ratio = 0;
  double coordination = 0, coordination_no_rattlers = 0, n_contacts = 0;
  double inertial_number = 0, kinetic_elastic_ratio = 0, servo_error = 0;
  double axis_orientation_11 = 0, axis_orientation_22 = 0, axis_orientation_33 = 0;
  double unbalanced_force_ratio = 0;
};

struct HistoryColumn {
  std::string_view name;
  std::string_view unit;
  std::string_view description;
  double HistoryRow::*value; ///< the member that holds the column's value
};

/// The columns, in file order, each declared with the member of HistoryRow it is.
const std::vector<HistoryColumn>& history_columns();

class History {
public:
  History();
  void append(const HistoryRow& row);
  [[nodiscard]] std::size_t size() const { return columns_.empty() ? 0 : columns_[0].size(); }
  [[nodiscard]] const std::vector<double>& column(std::string_view name) const;
  /// Drops rows whose step is above `step` (resuming from an earlier checkpoint).
  void truncate_after_step(double step);

  /// The loading run these rows belong to (root attribute run_id).
  [[nodiscard]] const std::string& run_id() const { return run_id_; }
  void set_run_id(std::string run_id) { run_id_ = std::move(run_id); }
  /// Where the run's wall time went (written as the attributes of /timing: each section's
  /// [min, avg, max] seconds over the ranks, and wall_seconds).
  void set_timing(std::vector<TimingRow> rows, double wall_seconds);

  /// Writes history.h5 and history.csv into `folder`, each atomically; covers_step is the
  /// simulation step now: every row up to it is in the file (attribute covers_step).
  void write(const std::string& folder, const h5::Provenance& provenance, std::int64_t covers_step) const;
  /// The step up to which the file read was complete.
  [[nodiscard]] std::int64_t covers_step() const { return covers_step_; }
  /// Reads history.h5 from `folder`; FileError naming the file if absent, of another schema
  /// version or malformed.
  static History read(const std::string& folder);

private:
  std::vector<std::vector<double>> columns_;
  std::string run_id_;
  std::int64_t covers_step_ = -1;
  std::vector<TimingRow> timing_;
  double wall_seconds_ = 0;
};

} // namespace aniso::dem::io
