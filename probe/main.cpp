// aniso-probe: incremental stiffness from six oedometric probes of one checkpoint
// (paper section 5). `run` does all seven forks (reference and six increments, split over the ranks) and
// writes probe_<stem>.h5/.csv; `fork` runs one of them (SLURM job arrays) and `collect` assembles the result
// from the seven fork files.
#include "common/cli.hpp"
#include "common/error.hpp"
#include "common/h5/checkpoint.hpp"
#include "common/h5/content_hash.hpp"
#include "common/output_folder.hpp"
#include "common/stop_request.hpp"
#include "common/timer.hpp"
#include "dem/protocol/run_timing.hpp"
#include "probe/collect.hpp"
#include "probe/config.hpp"
#include "probe/files.hpp"
#include "probe/resume.hpp"
#include "probe/schedule.hpp"
#include "probe/source.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace {

using namespace aniso;

std::string csv_path_of(const std::string& h5_path) {
  return std::filesystem::path(h5_path).replace_extension(".csv").string();
}

void report(const Logger& logger, const std::string& path, const probe::ProbeResult& result) {
  const Mat3& c = result.stiffness.C;
  const double k = result.stiffness.K_C;
  logger->info("wrote {}: K_C = {:.5g} Pa, C11/K_C = {:.4f}, C22/K_C = {:.4f}, C33/K_C = {:.4f}, "
               "max |D|/K_C = {:.4f}",
               path, k, c(0, 0) / k, c(1, 1) / k, c(2, 2) / k, result.stiffness.D.cwiseAbs().maxCoeff() / k);
}

void write_result(const std::string& path, const probe::ProbeResult& result, const h5::Provenance& provenance,
                  const std::string& warning, const Logger& logger, const mpi::Comm& comm) {
  if (!warning.empty()) logger->warn("{}", warning);
  if (comm.is_root()) {
    probe::write_probe_result(path, result, provenance);
    probe::write_probe_csv(csv_path_of(path), result);
  }
  report(logger, path, result);
}

int run_probe(int argc, char** argv, const mpi::Comm& comm) {
  CLI::App app{"aniso-probe: incremental stiffness Q+, Q-, C, D from six oedometric forks of a checkpoint "
               "and a reference fork "
               "(Kuhn, Sun & Wang 2015, section 5)"};
  cli::CommonOptions options;
  cli::add_common_options(app, options, "aniso-probe");
  app.require_subcommand(1);
  auto* run = app.add_subcommand("run", "all seven forks (reference and six increments, split over the "
                                        "ranks); writes <output_dir>/probe_<stem>.h5 "
                                        "and .csv");
  auto* fork =
      app.add_subcommand("fork", "one fork (for job arrays); writes <output_dir>/probe_<stem>_fork<N>.h5");
  auto* collect =
      app.add_subcommand("collect", "assembles probe_<stem>.h5 and .csv from the seven fork files of "
                                    "a checkpoint, refusing forks of another checkpoint");
  std::string input;
  int fork_index = 0;
  std::vector<std::string> fork_files;
  run->add_option("--input", input, "checkpoint written by aniso-dem (HDF5)")->required();
  fork->add_option("--input", input, "checkpoint written by aniso-dem (HDF5)")->required();
  fork->add_option(
          "--fork", fork_index,
          "fork number 0..6: 0 is the reference (no increment), 2a-1 is +increment on x_a, 2a is -increment")
      ->required()
      ->check(CLI::Range(probe::reference_fork, probe::n_forks));
  collect->add_option("--input", input, "the checkpoint the forks came from (its content hash is checked)")
      ->required();
  collect->add_option("--forks", fork_files,
                      "the seven fork files (default: <output_dir>/probe_<stem>_fork0..6.h5)");
  for (auto* sub : {run, fork, collect})
    sub->fallthrough();
  if (auto code = cli::parse(app, argc, argv, comm)) return *code;

  const auto source = cli::load_config(options);
  config::Reader reader(source.table, source.name);
  reader.tolerate_sections({"dem", "fabric", "voxel", "lbm", "workflow"});
  const probe::ProbeConfig config = probe::read_probe_config(reader);
  if (cli::finish_config(reader, options, comm)) return 0;
  const Logger logger = make_logger("aniso-probe", comm, options.log_level);
  const std::string command = cli::join_command_line(argc, argv);
  const std::string result_file = probe::result_path(config.output_dir, input);

  if (collect->parsed()) {
    if (fork_files.empty()) {
      for (int index = probe::reference_fork; index <= probe::n_forks; ++index) {
        fork_files.push_back(probe::fork_path(config.output_dir, input, index));
        require_file(std::filesystem::is_regular_file(fork_files.back()),
                     fmt::format("fork {} is missing: '{}' does not exist", index, fork_files.back()));
      }
    }
    std::vector<probe::ForkFile> files;
    for (const auto& path : fork_files) {
      require_file(std::filesystem::is_regular_file(path),
                   fmt::format("fork file '{}' does not exist", path));
      files.push_back(probe::read_fork_file(path));
    }
    const auto forks = probe::check_forks(files, fork_files, h5::content_hash(input, comm));
    logger->info("seven forks of '{}' agree (content hash {})", input, forks[0].source.hash);
    if (options.dry_run) return 0;
    std::string warning;
    const probe::ProbeResult result = probe::assemble_result(forks, config, warning);
    const auto provenance =
        h5::make_provenance("aniso-probe collect", reader.effective_toml(), command, comm);
    write_result(result_file, result, provenance, warning, logger, comm);
    return 0;
  }

  // SLURM's SIGTERM before a time limit: the forks poll it (probe/fork.hpp).
  install_stop_handler();
  const auto start = SectionTimes::Clock::now();
  const h5::Checkpoint checkpoint = h5::read_checkpoint(input, comm);
  const probe::ProbeSource probe_source = probe::probe_source(input, checkpoint, comm);
  logger->info("input '{}': {} particles, {} contacts, loading strain {:.5g}, content hash {}", input,
               checkpoint.particles.size(), checkpoint.contacts.size(), probe_source.strain,
               probe_source.hash);
  if (options.dry_run) return 0;
  if (comm.is_root()) create_output_folder(config.output_dir);

  probe::ForkTimes times;
  SectionTimes output({"output"});
  if (fork->parsed()) {
    const auto provenance = h5::make_provenance("aniso-probe fork", reader.effective_toml(), command, comm);
    std::optional<probe::ForkResult> done;
    try {
      done = probe::run_fork(checkpoint, input, fork_index, config, comm, logger, &times);
    } catch (const Interrupted& stop) {
      logger->warn("{}: nothing written; the same command runs fork {} anew: {}", stop.what(), fork_index,
                   command);
      return static_cast<int>(ExitCode::interrupted);
    }
    const probe::ForkFile file{probe_source, probe::fork_settings(config), *done};
    const std::string path = probe::fork_path(config.output_dir, input, fork_index);
    {
      const ScopedSection writing(output, 0);
      if (comm.is_root()) probe::write_fork_file(path, file, provenance);
    }
    logger->info("wrote {}", path);
  } else {
    const auto provenance = h5::make_provenance("aniso-probe run", reader.effective_toml(), command, comm);
    const probe::ForkSettings settings = probe::fork_settings(config);
    const auto finished =
        probe::finished_forks(config.output_dir, input, probe_source, settings, comm, logger);
    const auto results = probe::run_forks(checkpoint, input, config, comm, logger, &times, finished);
    if (std::any_of(results.begin(), results.end(), [](const auto& done) { return !done; })) {
      probe::keep_forks(config.output_dir, input, probe_source, settings, results, finished, provenance,
                        comm);
      logger->warn("{}", probe::stop_message(config.output_dir, input, results, command));
      return static_cast<int>(ExitCode::interrupted);
    }
    std::array<probe::ForkFile, probe::n_fork_files> forks;
    for (int k = 0; k < probe::n_fork_files; ++k)
      forks[static_cast<std::size_t>(k)] = {probe_source, settings, *results[static_cast<std::size_t>(k)]};
    std::string warning;
    const probe::ProbeResult result = probe::assemble_result(forks, config, warning);
    const ScopedSection writing(output, 0);
    write_result(result_file, result, provenance, warning, logger, comm);
    probe::remove_finished(config.output_dir, input, finished, comm);
  }
  // The table: the engine's sections over this rank's forks, then restarting and writing.
  SectionTimes probe_times({"restart", "output"});
  probe_times.add(0, times.restart.seconds(0), times.restart.calls(0));
  probe_times.add(1, output.seconds(0), output.calls(0));
  const double wall = std::chrono::duration<double>(SectionTimes::Clock::now() - start).count();
  dem::protocol::log_timing(logger, dem::protocol::run_timing(times.engine, probe_times, wall, comm), wall,
                            comm.size());
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return aniso::cli::run(argc, argv, "aniso-probe", run_probe);
}
