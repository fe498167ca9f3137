#include "fabric/series.hpp"

#include "common/error.hpp"
#include "common/h5/atomic_write.hpp"
#include "common/root_only.hpp"
#include "fabric/output.hpp"
#include "fabric/pearson.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <optional>

namespace aniso::fabric {
namespace {

using Difference = std::function<double(std::size_t point, int axis)>; // axis 0: 11 - 33, 1: 22 - 33

Correlation correlate(std::string measure, std::string against, std::string definition, std::size_t n,
                      const Difference& x, const Difference& y) {
  Correlation c{std::move(measure),          std::move(against), std::move(definition), 0, 0,
                static_cast<std::int64_t>(n)};
  for (int axis = 0; axis < 2; ++axis) {
    std::vector<double> xs(n), ys(n);
    for (std::size_t k = 0; k < n; ++k) {
      xs[k] = x(k, axis);
      ys[k] = y(k, axis);
    }
    (axis == 0 ? c.c1 : c.c2) = pearson(xs, ys);
  }
  return c;
}

double difference(const Mat3& a, int axis) {
  return a(axis, axis) - a(2, 2);
}
double normalized(const Vec3& diagonal, int axis) {
  return (diagonal[axis] - diagonal[2]) / (diagonal.sum() / 3.0);
}

const std::vector<std::string> contact_tensors{"F", "F_strong", "G", "G_strong", "H", "H_strong"};

Mat3 tensor_named(const FabricMeasures& m, const std::string& name) {
  for (const NamedTensor& t : m.tensors())
    if (t.name == name) return t.value;
  throw Error(ExitCode::internal_error, "no fabric tensor " + name);
}

template <class Linked>
std::size_t checkpoint_of(const Linked& linked, std::span<const FabricMeasures> series,
                          const std::string& kind) {
  for (std::size_t k = 0; k < series.size(); ++k)
    if (series[k].source_hash == linked.checkpoint_hash) return k;
  throw FileError(linked.path + ": this " + kind + " result comes from a checkpoint (hash " +
                  linked.checkpoint_hash + ") that is not among the series' inputs");
}

} // namespace

std::vector<Correlation> stress_correlations(std::span<const FabricMeasures> series) {
  std::vector<Correlation> out;
  const Difference stress = [&](std::size_t k, int axis) {
    return -difference(series[k].stress_contact, axis);
  };
  for (const NamedTensor& t : FabricMeasures{}.tensors()) {
    if (t.name.starts_with("stress") || t.name == "W320_boundary") continue; // not fabric
    const std::string name = t.name;
    out.push_back(correlate(
        name, "stress", "corr(" + name + "_11 - " + name + "_33, s_11 - s_33), s = -stress", series.size(),
        [&, name](std::size_t k, int axis) { return difference(tensor_named(series[k], name), axis); },
        stress));
  }
  return out;
}

std::vector<Correlation> linked_correlations(std::span<const FabricMeasures> series,
                                             const LinkedResults& linked) {
  std::vector<Correlation> out;
  if (!linked.probes.empty()) {
    std::vector<std::size_t> at;
    for (const ProbeStiffness& p : linked.probes)
      at.push_back(checkpoint_of(p, series, "probe"));
    for (const std::string& name : contact_tensors) {
      out.push_back(correlate(
          "C", name, "corr(C_11 - C_33, " + name + "_11 - " + name + "_33)", at.size(),
          [&](std::size_t k, int axis) { return difference(linked.probes[k].C, axis); },
          [&, name](std::size_t k, int axis) {
            return difference(tensor_named(series[at[k]], name), axis);
          }));
    }
  }
  // Permeability and void medians meet at the checkpoints both were computed for.
  std::vector<std::pair<std::size_t, std::size_t>> pairs; // (permeability, voids)
  for (const VoidMedians& v : linked.voids)
    static_cast<void>(checkpoint_of(v, series, "voids"));
  for (std::size_t a = 0; a < linked.permeabilities.size(); ++a) {
    const std::size_t at = checkpoint_of(linked.permeabilities[a], series, "permeability");
    for (std::size_t b = 0; b < linked.voids.size(); ++b)
      if (linked.voids[b].checkpoint_hash == series[at].source_hash) pairs.emplace_back(a, b);
  }
  if (!pairs.empty()) {
    const Difference k_aniso = [&](std::size_t k, int axis) {
      return normalized(linked.permeabilities[pairs[k].first].K.diagonal(), axis);
    };
    out.push_back(correlate(
        "K", "L", "corr((K_11 - K_33)/(tr K/3), (L_11 - L_33)/(tr L/3))", pairs.size(), k_aniso,
        [&](std::size_t k, int axis) { return normalized(linked.voids[pairs[k].second].free_path, axis); }));
    out.push_back(correlate(
        "K", "R", "corr((K_11 - K_33)/(tr K/3), (R_11 - R_33)/(tr R/3))", pairs.size(), k_aniso,
        [&](std::size_t k, int axis) { return normalized(linked.voids[pairs[k].second].breadth, axis); }));
  }
  return out;
}

void write_series_results(const std::string& h5_path, std::span<const FabricMeasures> series,
                          std::span<const Correlation> correlations, const h5::Provenance& provenance,
                          const mpi::Comm& comm) {
  const std::filesystem::path base = std::filesystem::path(h5_path).replace_extension();
  run_on_root(comm, [&] {
    const std::vector<std::string> names = column_names(), units = column_units();
    std::vector<std::vector<double>> rows;
    for (const FabricMeasures& m : series)
      rows.push_back(column_values(m));
    h5::AtomicFile atomic(h5_path);
    {
      h5::File file = create_results_file(
          atomic.temp_path(), "fabric time series and correlations of a loading run (docs/formats/fabric.md)",
          provenance);
      h5::Group checkpoints = file.create_group("checkpoints");
      for (const FabricMeasures& m : series)
        write_checkpoint_group(checkpoints, m);
      h5::Group table = file.create_group("series");
      table.write_attribute("description",
                            std::string_view("one value per checkpoint, in the order of `source`"));
      for (std::size_t c = 0; c < names.size(); ++c) {
        std::vector<double> column;
        for (const auto& row : rows)
          column.push_back(row[c]);
        table.write_dataset<double>(names[c], column, {column.size()}, units[c], "column of the series CSV");
      }
      h5::Group group = file.create_group("correlations");
      for (const Correlation& c : correlations) {
        h5::Group child = group.create_group(c.measure + "_vs_" + c.against);
        child.write_attribute("definition", c.definition);
        child.write_attribute<double>("c1", c.c1);
        child.write_attribute<double>("c2", c.c2);
        child.write_attribute<std::int64_t>("n_points", c.n_points);
      }
      file.close();
    }
    atomic.commit();
    std::vector<std::pair<std::string, std::vector<double>>> csv_rows;
    for (std::size_t k = 0; k < series.size(); ++k)
      csv_rows.emplace_back(series[k].source, rows[k]);
    write_csv(base.string() + ".csv", names, csv_rows);
    h5::AtomicFile table(base.string() + "_correlations.csv");
    {
      std::ofstream out(table.temp_path());
      out << "measure,against,c1,c2,n_points,definition\n"
          << std::setprecision(std::numeric_limits<double>::max_digits10);
      for (const Correlation& c : correlations)
        out << c.measure << ',' << c.against << ',' << c.c1 << ',' << c.c2 << ',' << c.n_points << ",\""
            << c.definition << "\"\n";
      out.flush();
      require_file(static_cast<bool>(out), table.final_path() + ": writing the CSV failed");
    }
    table.commit();
  });
}

} // namespace aniso::fabric
