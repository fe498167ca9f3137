#include "dem/io/history.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace aniso::dem::io {

const std::vector<HistoryColumn>& history_columns() {
  using R = HistoryRow;
  static const std::vector<HistoryColumn> columns{
      {"step", units::none, "time steps since the start of preparation", &R::step},
      {"time", units::second, "simulated time", &R::time},
      {"strain_11", units::none,
       "engineering strain of axis 1 since the start of loading, extension positive", &R::strain_11},
      {"strain_22", units::none, "engineering strain of axis 2", &R::strain_22},
      {"strain_33", units::none, "engineering strain of axis 3", &R::strain_33},
      {"volumetric_strain", units::none, "(V - V0)/V0, dilation positive", &R::volumetric_strain},
      {"stress_11", units::pascal, "average stress, tension positive", &R::stress_11},
      {"stress_22", units::pascal, "average stress, tension positive", &R::stress_22},
      {"stress_33", units::pascal, "average stress, tension positive", &R::stress_33},
      {"stress_23", units::pascal, "average stress", &R::stress_23},
      {"stress_13", units::pascal, "average stress", &R::stress_13},
      {"stress_12", units::pascal, "average stress", &R::stress_12},
      {"p", units::pascal, "mean stress, compression positive", &R::p},
      {"q", units::pascal, "sqrt(3 J2)", &R::q},
      {"stress_ratio", units::none,
       "(sigma_11 - sigma_33)/p with compression positive stresses (paper Fig. 3a)", &R::stress_ratio},
      {"void_ratio", units::none, "(V - V_solid)/V_solid", &R::void_ratio},
      {"coordination", units::none, "2 N_c / N", &R::coordination},
      {"coordination_no_rattlers", units::none,
       "2 N_c / N without rattlers (fewer than 2 contacts, removed iteratively)",
       &R::coordination_no_rattlers},
      {"n_contacts", units::none, "touching pairs", &R::n_contacts},
      {"inertial_number", units::none, "|strain rate 11| D50 sqrt(density / p)", &R::inertial_number},
      {"kinetic_elastic_ratio", units::none, "kinetic energy / elastic contact energy",
       &R::kinetic_elastic_ratio},
      {"servo_error", units::none, "(p - p_target)/p_target", &R::servo_error},
      {"axis_orientation_11", units::none,
       "mean e1^2 of the particle axes e (ovoids; 1/3 for spheres, whose axis is undefined)",
       &R::axis_orientation_11},
      {"axis_orientation_22", units::none, "mean e2^2 of the particle axes", &R::axis_orientation_22},
      {"axis_orientation_33", units::none, "mean e3^2 of the particle axes", &R::axis_orientation_33},
      {"unbalanced_force_ratio", units::none,
       "mean |net contact force| over particles with contacts / mean |contact force|",
       &R::unbalanced_force_ratio},
  };
  return columns;
}

History::History() : columns_(history_columns().size()) {}

void History::append(const HistoryRow& row) {
  const auto& columns = history_columns();
  for (std::size_t c = 0; c < columns.size(); ++c)
    columns_[c].push_back(row.*columns[c].value);
}

const std::vector<double>& History::column(std::string_view name) const {
  const auto& names = history_columns();
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c].name == name) return columns_[c];
  }
  throw Error(ExitCode::internal_error, fmt::format("no history column {}", name));
}

void History::truncate_after_step(double step) {
  const auto& steps = columns_[0];
  const auto keep = static_cast<std::size_t>(
      std::find_if(steps.begin(), steps.end(), [&](double s) { return s > step; }) - steps.begin());
  for (auto& column : columns_)
    column.resize(keep);
}

void History::set_timing(std::vector<TimingRow> rows, double wall_seconds) {
  timing_ = std::move(rows);
  wall_seconds_ = wall_seconds;
}

void History::write(const std::string& folder, const h5::Provenance& provenance,
                    std::int64_t covers_step) const {
  const auto& columns = history_columns();
  {
    h5::AtomicFile atomic(folder + "/history.h5");
    {
      h5::File file = h5::File::create(atomic.temp_path());
      file.write_attribute("schema", std::string_view("aniso-history"));
      file.write_attribute("schema_version", history_schema_version);
      file.write_attribute("run_id", run_id_);
      file.write_attribute("covers_step", covers_step);
      h5::Group group = file.create_group("history");
      for (std::size_t c = 0; c < columns.size(); ++c) {
        group.write_dataset<double>(std::string(columns[c].name), columns_[c], {columns_[c].size()},
                                    columns[c].unit, columns[c].description);
      }
      if (!timing_.empty()) {
        h5::Group timing = file.create_group("timing");
        timing.write_attribute_with_units("wall_seconds", wall_seconds_, units::second);
        for (const TimingRow& row : timing_) {
          std::string name = row.name;
          std::replace(name.begin(), name.end(), ' ', '_');
          timing.write_attribute(name + "_min_seconds", row.min);
          timing.write_attribute(name + "_avg_seconds", row.avg);
          timing.write_attribute(name + "_max_seconds", row.max);
          timing.write_attribute(name + "_share", row.share);
        }
      }
      h5::write_provenance(file, provenance);
      file.close();
    }
    atomic.commit();
  }
  std::string csv;
  for (std::size_t c = 0; c < columns.size(); ++c)
    csv += fmt::format("{}{}", c ? "," : "", columns[c].name);
  csv += '\n';
  for (std::size_t r = 0; r < size(); ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      csv += fmt::format("{}{:.17g}", c ? "," : "", columns_[c][r]);
    csv += '\n';
  }
  h5::write_text_atomically(folder + "/history.csv", csv);
}

History History::read(const std::string& folder) {
  const std::string path = folder + "/history.h5";
  require_file(std::filesystem::exists(path), fmt::format("history file '{}' does not exist", path));
  h5::File file = h5::File::open(path);
  const std::int64_t version = file.read_attribute<std::int64_t>("schema_version");
  if (version != history_schema_version)
    file.fail(fmt::format("schema_version {}, expected {}: the history was written by another version of "
                          "aniso-dem; continue the run with that version, or start the loading anew",
                          version, history_schema_version));
  const h5::Group group = file.open_group("history");
  History history;
  history.run_id_ = file.read_string_attribute("run_id");
  history.covers_step_ = file.read_attribute<std::int64_t>("covers_step");
  const auto& columns = history_columns();
  const auto n_rows = group.open_dataset("step").read<double>().size();
  for (std::size_t c = 0; c < columns.size(); ++c)
    history.columns_[c] = group.read_dataset<double>(std::string(columns[c].name), {n_rows});
  return history;
}

} // namespace aniso::dem::io
