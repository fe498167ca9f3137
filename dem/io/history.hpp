#pragma once
// The loading history: one row per history interval of strain, in HDF5
// (history.h5, one 1-D dataset per column with its unit) and CSV. Rewritten
// atomically at every checkpoint, so the file on disk always matches a
// checkpoint that exists. Layout: docs/formats/history.md.

#include "common/h5/provenance.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::dem::io {

struct HistoryColumn {
  std::string name;
  std::string unit;
  std::string description;
};

/// The columns, in order.
const std::vector<HistoryColumn>& history_columns();

class History {
public:
  History();
  /// Appends a row; values in the order of history_columns().
  void append(const std::vector<double>& row);
  [[nodiscard]] std::size_t size() const { return columns_.empty() ? 0 : columns_[0].size(); }
  [[nodiscard]] const std::vector<double>& column(const std::string& name) const;
  /// Drops rows whose step is above `step` (resuming from an earlier checkpoint).
  void truncate_after_step(double step);
  /// The step of the last row (NaN when empty).
  [[nodiscard]] double last_step() const;

  /// The loading run these rows belong to (root attribute run_id; empty in files written
  /// before run ids).
  [[nodiscard]] const std::string& run_id() const { return run_id_; }
  void set_run_id(std::string run_id) { run_id_ = std::move(run_id); }

  /// Writes history.h5 and history.csv into `folder`, each atomically; covers_step is the
  /// simulation step now: every row up to it is in the file (attribute covers_step).
  void write(const std::string& folder, const h5::Provenance& provenance, std::int64_t covers_step) const;
  /// The step up to which the file read was complete (-1 in files written before 2026-12-03).
  [[nodiscard]] std::int64_t covers_step() const { return covers_step_; }
  /// Reads history.h5 from `folder`; FileError naming the file if absent or malformed.
  static History read(const std::string& folder);

private:
  std::vector<std::vector<double>> columns_;
  std::string run_id_;
  std::int64_t covers_step_ = -1;
};

} // namespace aniso::dem::io
