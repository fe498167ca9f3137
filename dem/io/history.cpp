#include "dem/io/history.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/h5/file.hpp"
#include "common/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

namespace aniso::dem::io {

const std::vector<HistoryColumn>& history_columns() {
  static const std::vector<HistoryColumn> columns{
      {"step", units::none, "time steps since the start of preparation"},
      {"time", units::second, "simulated time"},
      {"strain_11", units::none,
       "engineering strain of axis 1 since the start of loading, extension positive"},
      {"strain_22", units::none, "engineering strain of axis 2"},
      {"strain_33", units::none, "engineering strain of axis 3"},
      {"volumetric_strain", units::none, "(V - V0)/V0, dilation positive"},
      {"stress_11", units::pascal, "average stress, tension positive"},
      {"stress_22", units::pascal, "average stress, tension positive"},
      {"stress_33", units::pascal, "average stress, tension positive"},
      {"stress_23", units::pascal, "average stress"},
      {"stress_13", units::pascal, "average stress"},
      {"stress_12", units::pascal, "average stress"},
      {"p", units::pascal, "mean stress, compression positive"},
      {"q", units::pascal, "sqrt(3 J2)"},
      {"stress_ratio", units::none,
       "(sigma_11 - sigma_33)/p with compression positive stresses (paper Fig. 3a)"},
      {"void_ratio", units::none, "(V - V_solid)/V_solid"},
      {"coordination", units::none, "2 N_c / N"},
      {"coordination_no_rattlers", units::none,
       "2 N_c / N without rattlers (fewer than 2 contacts, removed iteratively)"},
      {"n_contacts", units::none, "touching pairs"},
      {"inertial_number", units::none, "|strain rate 11| D50 sqrt(density / p)"},
      {"kinetic_elastic_ratio", units::none, "kinetic energy / elastic contact energy"},
      {"servo_error", units::none, "(p - p_target)/p_target"},
      {"axis_orientation_11", units::none,
       "mean e1^2 of the particle axes e (ovoids; 1/3 for spheres, whose axis is undefined)"},
      {"axis_orientation_22", units::none, "mean e2^2 of the particle axes"},
      {"axis_orientation_33", units::none, "mean e3^2 of the particle axes"},
      {"unbalanced_force_ratio", units::none,
       "mean |net contact force| over particles with contacts / mean |contact force|"},
  };
  return columns;
}

History::History() : columns_(history_columns().size()) {}

void History::append(const std::vector<double>& row) {
  check_invariant(row.size() == columns_.size(), "history row has one value per column");
  for (std::size_t c = 0; c < row.size(); ++c)
    columns_[c].push_back(row[c]);
}

const std::vector<double>& History::column(const std::string& name) const {
  const auto& names = history_columns();
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c].name == name) return columns_[c];
  }
  throw Error(ExitCode::internal_error, "no history column " + name);
}

void History::truncate_after_step(double step) {
  const auto& steps = columns_[0];
  const auto keep = static_cast<std::size_t>(
      std::find_if(steps.begin(), steps.end(), [&](double s) { return s > step; }) - steps.begin());
  for (auto& column : columns_)
    column.resize(keep);
}

double History::last_step() const {
  return columns_[0].empty() ? std::numeric_limits<double>::quiet_NaN() : columns_[0].back();
}

void History::write(const std::string& folder, const h5::Provenance& provenance,
                    std::int64_t covers_step) const {
  const auto& names = history_columns();
  {
    h5::AtomicFile atomic(folder + "/history.h5");
    {
      h5::File file = h5::File::create(atomic.temp_path());
      file.write_attribute("schema", std::string_view("aniso-history"));
      file.write_attribute("schema_version", std::int64_t{3});
      if (!run_id_.empty()) file.write_attribute("run_id", run_id_);
      file.write_attribute("covers_step", covers_step);
      h5::Group group = file.create_group("history");
      for (std::size_t c = 0; c < names.size(); ++c) {
        group.write_dataset<double>(names[c].name, columns_[c], {columns_[c].size()}, names[c].unit,
                                    names[c].description);
      }
      h5::write_provenance(file, provenance);
      file.close();
    }
    atomic.commit();
  }
  const std::string csv = folder + "/history.csv";
  const std::string temp = folder + "/.history.csv.tmp";
  {
    std::ofstream out(temp);
    for (std::size_t c = 0; c < names.size(); ++c)
      out << (c ? "," : "") << names[c].name;
    out << '\n';
    for (std::size_t r = 0; r < size(); ++r) {
      for (std::size_t c = 0; c < names.size(); ++c)
        out << (c ? "," : "") << fmt::format("{:.17g}", columns_[c][r]);
      out << '\n';
    }
    if (!out) throw FileError(fmt::format("cannot write '{}'", temp));
  }
  std::filesystem::rename(temp, csv);
}

History History::read(const std::string& folder) {
  const std::string path = folder + "/history.h5";
  require_file(std::filesystem::exists(path), fmt::format("history file '{}' does not exist", path));
  h5::File file = h5::File::open(path);
  const h5::Group group = file.open_group("history");
  History history;
  if (file.has_attribute("run_id")) history.run_id_ = file.read_string_attribute("run_id");
  if (file.has_attribute("covers_step"))
    history.covers_step_ = file.read_attribute<std::int64_t>("covers_step");
  const auto& names = history_columns();
  const auto n_rows = group.open_dataset("step").read<double>().size();
  for (std::size_t c = 0; c < names.size(); ++c)
    history.columns_[c] = group.read_dataset<double>(names[c].name, {n_rows});
  return history;
}

} // namespace aniso::dem::io
