#include "fabric/output.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/root_only.hpp"
#include "fabric/summary.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace aniso::fabric {
namespace {

const char* const components[3][3] = {{"11", "12", "13"}, {"21", "22", "23"}, {"31", "32", "33"}};

std::vector<double> row_major(const Mat3& m) {
  std::vector<double> out(9);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out[static_cast<std::size_t>(3 * a + b)] = m(a, b);
  return out;
}

} // namespace

std::string checkpoint_stem(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

void require_distinct_stems(const std::vector<std::string>& paths) {
  std::map<std::string, std::string> first_with_stem;
  for (const std::string& path : paths) {
    const auto [earlier, fresh] = first_with_stem.emplace(checkpoint_stem(path), path);
    if (fresh) continue;
    require_input(earlier->second != path,
                  fmt::format("checkpoint '{}' is given more than once: give each checkpoint once", path));
    require_input(false, fmt::format("checkpoints '{}' and '{}' share the name '{}' (results are stored by "
                                     "file name): rename one",
                                     earlier->second, path, earlier->first));
  }
}

std::vector<std::string> column_names() {
  std::vector<std::string> names;
  const FabricMeasures empty;
  for (const NamedScalar& s : empty.scalars())
    names.push_back(s.name);
  for (const NamedTensor& t : empty.tensors()) {
    for (const auto& row : components)
      for (const char* ab : row)
        names.push_back(t.name + "_" + ab);
    for (int k = 1; k <= 3; ++k)
      names.push_back(t.name + "_eigenvalue_" + std::to_string(k));
    names.push_back(t.name + "_anisotropy_13");
    names.push_back(t.name + "_anisotropy_23");
  }
  return names;
}

std::vector<std::string> column_units() {
  std::vector<std::string> units;
  const FabricMeasures empty;
  for (const NamedScalar& s : empty.scalars())
    units.push_back(s.unit);
  for (const NamedTensor& t : empty.tensors()) {
    units.insert(units.end(), 12, t.unit); // nine components, three eigenvalues
    units.insert(units.end(), 2, "1");     // two anisotropies
  }
  return units;
}

std::vector<double> column_values(const FabricMeasures& measures) {
  std::vector<double> values;
  for (const NamedScalar& s : measures.scalars())
    values.push_back(s.value);
  for (const NamedTensor& t : measures.tensors()) {
    for (double v : row_major(t.value))
      values.push_back(v);
    const TensorSummary summary = summarize(t.value);
    for (int k = 0; k < 3; ++k)
      values.push_back(summary.eigenvalues[k]);
    values.push_back(summary.anisotropy[0]);
    values.push_back(summary.anisotropy[1]);
  }
  return values;
}

void write_checkpoint_group(h5::Group& checkpoints, const FabricMeasures& m) {
  h5::Group group = checkpoints.create_group(checkpoint_stem(m.source));
  group.write_attribute("source", m.source);
  group.write_attribute("source_hash", m.source_hash);
  if (m.n_contacts == 0) group.write_attribute("warning", no_contacts_warning);
  for (const NamedScalar& s : m.scalars()) {
    if (s.integer) {
      group.write_attribute<std::int64_t>(s.name, static_cast<std::int64_t>(s.value));
    } else {
      group.write_attribute_with_units(s.name, s.value, s.unit);
    }
  }
  for (const NamedTensor& t : m.tensors()) {
    const std::vector<double> value = row_major(t.value);
    group.write_dataset<double>(t.name, value, {3, 3}, t.unit, t.description);
    const TensorSummary summary = summarize(t.value);
    const std::vector<double> eigen{summary.eigenvalues[0], summary.eigenvalues[1], summary.eigenvalues[2]};
    group.write_dataset<double>(t.name + "_eigenvalues", eigen, {3}, t.unit,
                                "principal values of the symmetric part, descending");
    const std::vector<double> anisotropy{summary.anisotropy[0], summary.anisotropy[1]};
    group.write_dataset<double>(t.name + "_anisotropy", anisotropy, {2}, "1",
                                "(A11 - A33)/(tr A/3), (A22 - A33)/(tr A/3); NaN when tr A = 0");
  }
}

void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::pair<std::string, std::vector<double>>>& rows) {
  h5::AtomicFile atomic(path);
  {
    std::ofstream out(atomic.temp_path());
    out << "source";
    for (const std::string& name : header)
      out << ',' << name;
    out << '\n' << std::setprecision(std::numeric_limits<double>::max_digits10);
    for (const auto& [source, values] : rows) {
      out << '"' << source << '"';
      for (double v : values)
        out << ',' << v;
      out << '\n';
    }
    out.flush();
    require_file(static_cast<bool>(out), path + ": writing the CSV failed");
  }
  atomic.commit();
}

h5::File create_results_file(const std::string& path, const std::string& description,
                             const h5::Provenance& provenance) {
  h5::File file = h5::File::create(path);
  file.write_attribute("schema", std::string_view("aniso-fabric"));
  file.write_attribute<std::int64_t>("schema_version", fabric_schema_version);
  file.write_attribute("description", description);
  h5::write_provenance(file, provenance);
  return file;
}

void write_fabric_results(const std::string& h5_path, const std::string& csv_path,
                          std::span<const FabricMeasures> measures, const h5::Provenance& provenance,
                          const mpi::Comm& comm) {
  std::vector<std::string> sources;
  for (const FabricMeasures& m : measures)
    sources.push_back(m.source);
  require_distinct_stems(sources);
  run_on_root(comm, [&] {
    h5::AtomicFile atomic(h5_path);
    {
      h5::File file = create_results_file(
          atomic.temp_path(), "fabric measures per checkpoint (docs/formats/fabric.md)", provenance);
      h5::Group checkpoints = file.create_group("checkpoints");
      for (const FabricMeasures& m : measures)
        write_checkpoint_group(checkpoints, m);
      file.close();
    }
    atomic.commit();
    std::vector<std::pair<std::string, std::vector<double>>> rows;
    for (const FabricMeasures& m : measures)
      rows.emplace_back(m.source, column_values(m));
    write_csv(csv_path, column_names(), rows);
  });
}

} // namespace aniso::fabric
