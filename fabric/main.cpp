// aniso-fabric: the paper's thirteen fabric measures, stress and correlations from checkpoints (section 3).
//   aniso-fabric --input A.h5 [B.h5 ...]            -> fabric.h5 + fabric.csv (a group / row per checkpoint)
//   aniso-fabric series --input load_*.h5 [--probe ...] [--permeability ...] [--voids ...]
//                                                    -> fabric_series.h5, fabric_series.csv,
//                                                       fabric_series_correlations.csv
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/content_hash.hpp"
#include "common/output_folder.hpp"
#include "common/timer.hpp"
#include "fabric/config.hpp"
#include "fabric/measures.hpp"
#include "fabric/output.hpp"
#include "fabric/series.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace {

using namespace aniso;

void log_measures(const Logger& logger, const fabric::FabricMeasures& m) {
  logger->info(
      "{}: strain_11 {:.5g}, p {:.4g} Pa, q/p {:.4f}, e {:.4f}, Z {:.3f} ({:.3f} without {} rattlers), "
      "chi/N_p {:.4f} (torus {:.4f})",
      m.source, m.strain[0], m.mean_stress, m.deviatoric_stress / m.mean_stress, m.void_ratio, m.coordination,
      m.coordination_no_rattlers, m.n_rattlers, m.chi_paper / static_cast<double>(m.n_particles),
      m.chi_torus / static_cast<double>(m.n_particles));
  if (m.n_contacts == 0) logger->warn("{}: {}", m.source, fabric::no_contacts_warning);
}

int run_fabric(int argc, char** argv, const mpi::Comm& comm) {
  CLI::App app{"aniso-fabric: fabric measures, contact stress and correlations from DEM checkpoints "
               "(Kuhn, Sun & Wang 2015, section 3)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-fabric");
  std::vector<std::string> inputs, probes, permeabilities, voids;
  std::string output;
  app.add_option("--input", inputs, "one or more DEM checkpoints (HDF5)")->required();
  app.add_option("--output", output,
                 "results file (default <fabric.output_dir>/fabric.h5, or fabric_series.h5 for series); "
                 "CSV files are written beside it");
  auto* series = app.add_subcommand("series", "time series over a loading run's checkpoints and the Pearson "
                                              "correlations c1, c2 (Table 2; with --probe, --permeability, "
                                              "--voids also sections 4 and 5)");
  series->add_option("--probe", probes, "collected probe results probe_<stem>.h5 (/stiffness/C)");
  series->add_option("--permeability", permeabilities, "permeability results (/permeability/K)");
  series->add_option("--voids", voids, "void morphology results (/voids free_path_median, breadth_median)");
  series->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"dem", "probe", "voxel", "lbm", "workflow"});
  const fabric::FabricConfig config = fabric::read_fabric_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-fabric", comm, options.log_level);
  const bool is_series = series->parsed();
  if (is_series)
    require_input(inputs.size() >= 3,
                  "series needs at least 3 checkpoints to correlate, got " + std::to_string(inputs.size()));
  fabric::require_distinct_stems(inputs);
  if (output.empty()) output = config.output_dir + (is_series ? "/fabric_series.h5" : "/fabric.h5");
  {
    std::vector<std::string> every_input = inputs;
    for (const auto* list : {&probes, &permeabilities, &voids})
      every_input.insert(every_input.end(), list->begin(), list->end());
    cli::require_output_is_not_an_input(output, every_input);
    cli::require_output_is_not_an_input(std::filesystem::path(output).replace_extension(".csv").string(),
                                        every_input);
  }

  const auto start = std::chrono::steady_clock::now();
  std::vector<fabric::FabricMeasures> measures;
  for (const std::string& path : inputs) {
    const h5::Checkpoint checkpoint = h5::read_checkpoint(path, comm);
    if (options.dry_run) continue;
    measures.push_back(fabric::measure_fabric(checkpoint, path, config, comm));
    measures.back().source_hash = h5::content_hash(path);
    log_measures(logger, measures.back());
  }
  fabric::LinkedResults linked;
  for (const auto& path : probes) {
    linked.probes.push_back(fabric::read_probe_stiffness(path));
    if (!linked.probes.back().checks_passed)
      logger->warn("{}: the probe's own checks failed (checks_passed = 0); its C is correlated all the same",
                   path);
  }
  for (const auto& path : permeabilities)
    linked.permeabilities.push_back(fabric::read_permeability(path));
  for (const auto& path : voids)
    linked.voids.push_back(fabric::read_void_medians(path));
  logger->info("inputs are valid ({} checkpoints)", inputs.size());
  if (options.dry_run) return 0;

  if (!std::filesystem::path(output).parent_path().empty())
    create_output_folder(std::filesystem::path(output).parent_path().string());
  const std::string command = cli::join_command_line(argc, argv);
  if (!is_series) {
    const auto provenance = h5::make_provenance("aniso-fabric", reader.effective_toml(), command, comm);
    const std::string csv = std::filesystem::path(output).replace_extension(".csv").string();
    fabric::write_fabric_results(output, csv, measures, provenance, comm);
    logger->info("wrote {} and {}", output, csv);
  } else {
    std::stable_sort(measures.begin(), measures.end(),
                     [](const auto& a, const auto& b) { return a.step < b.step; });
    std::vector<fabric::Correlation> correlations = fabric::stress_correlations(measures);
    for (fabric::Correlation& c : fabric::linked_correlations(measures, linked))
      correlations.push_back(std::move(c));
    for (const fabric::Correlation& c : correlations)
      logger->info("c1 = {:+.3f}, c2 = {:+.3f} ({} points): {} vs {}", c.c1, c.c2, c.n_points, c.measure,
                   c.against);
    const auto provenance =
        h5::make_provenance("aniso-fabric series", reader.effective_toml(), command, comm);
    fabric::write_series_results(output, measures, correlations, provenance, comm);
    logger->info("wrote {} with its CSV files", output);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  logger->info("done: {} checkpoints in {:.2f} s", measures.size(), seconds);
  logger->info(wall_time_line(seconds, comm.size()));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-fabric", run_fabric);
}
