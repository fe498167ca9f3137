#include "common/cli.hpp"

#include "common/error.hpp"
#include "common/h5/file.hpp"
#include "common/memory.hpp"
#include "common/version.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <new>
#include <string_view>

namespace aniso::cli {
namespace {

std::string rank_tag(const mpi::Comm& comm) {
  return comm.size() > 1 ? fmt::format(" (rank {})", comm.rank()) : std::string();
}

// --print-config shows the configuration without doing anything, so it needs no input file and
// no subcommand: a campaign validates every stage's section with it before the DEM starts.
void drop_requirements(CLI::App& app) {
  for (CLI::Option* option : app.get_options())
    option->required(false);
  app.require_subcommand(0);
  for (CLI::App* subcommand : app.get_subcommands({}))
    drop_requirements(*subcommand);
}

} // namespace

void add_common_options(CLI::App& app, CommonOptions& options, const std::string& program) {
  app.name(program); // error lines and the usage line name the program, not the path it ran from
  // Not CLI::ExistingFile: a missing config file is a file error (exit 3, docs/user-guide.md), not
  // a command-line one (2); config::load_file says which.
  app.add_option("--config", options.config_path, "TOML configuration file (defaults apply to missing keys)")
      ->type_name("FILE");
  app.add_option("--set", options.overrides, "override one config key, e.g. --set dem.seed=7 (repeatable)")
      ->type_name("KEY=VALUE");
  app.add_flag("--print-config", options.print_config,
               "print the effective configuration (every key, default, unit and range) and exit");
  app.add_flag("--dry-run", options.dry_run, "validate the configuration and input files, then exit");
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  app.set_version_flag("--version", fmt::format("{} {} (git {})", program, version_string, git_hash));
}

std::optional<int> parse(CLI::App& app, int argc, char** argv, const mpi::Comm& comm) {
  try {
    for (int i = 1; i < argc; ++i)
      if (std::string_view(argv[i]) == "--print-config") drop_requirements(app);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // CLI11 prints help and version on stdout; a command-line error gets the programs' own
    // "program: error (bad input): ..." line, like every other error. Only rank 0 speaks.
    if (error.get_exit_code() == 0) {
      if (comm.is_root()) static_cast<void>(app.exit(error));
      return 0;
    }
    if (comm.is_root())
      std::cerr << app.get_name() << ": error (" << exit_code_name(ExitCode::bad_input)
                << "): " << error.what() << "\nRun with --help for more information." << std::endl;
    return static_cast<int>(ExitCode::bad_input);
  }
  return std::nullopt;
}

ConfigSource load_config(const CommonOptions& options) {
  ConfigSource source;
  if (!options.config_path.empty()) {
    source.table = config::load_file(options.config_path);
    source.name = "'" + options.config_path + "'";
  } else {
    source.name = "defaults";
  }
  for (const auto& assignment : options.overrides)
    config::apply_override(source.table, assignment);
  if (!options.overrides.empty()) source.name += " with --set overrides";
  return source;
}

bool finish_config(const config::Reader& reader, const CommonOptions& options, const mpi::Comm& comm) {
  reader.reject_unknown();
  if (options.print_config) {
    if (comm.is_root()) std::cout << reader.effective_toml() << std::flush;
    return true;
  }
  return false;
}

std::string join_command_line(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) line += ' '; // appended piecewise: GCC 12's link-time optimisation flags
    line += argv[i];        // "a" + std::string(b) with a false -Wstringop-overflow
  }
  return line;
}

int run(int argc, char** argv, const std::string& program,
        const std::function<int(int argc, char** argv, const mpi::Comm& comm)>& body) {
  mpi::Environment environment(argc, argv);
  const mpi::Comm comm = mpi::Comm::world();
  int code = 0;
  try {
    code = body(argc, argv, comm);
  } catch (const Error& error) {
    code = static_cast<int>(error.code());
    std::cerr << program << rank_tag(comm) << ": error (" << exit_code_name(error.code())
              << "): " << error.what() << std::endl;
  } catch (const std::bad_alloc&) {
    // What was asked for is checked against the memory before the large arrays (common/memory.hpp);
    // an allocation failing anyway is still the size of the problem, not a bug.
    code = static_cast<int>(ExitCode::bad_input);
    std::cerr << program << rank_tag(comm) << ": error (" << exit_code_name(ExitCode::bad_input)
              << "): out of memory: an allocation failed (peak use so far " << peak_resident_bytes() / 1048576
              << " MiB, this process may use "
              << static_cast<std::uint64_t>(usable_memory_bytes() / 1048576.0)
              << " MiB): make the problem smaller or give the job more memory" << std::endl;
  } catch (const std::exception& error) {
    code = static_cast<int>(ExitCode::internal_error);
    std::cerr << program << rank_tag(comm) << ": internal error: " << error.what() << std::endl;
  }
  // An error seen by some ranks only must not leave the others waiting in a collective. A stop
  // on SIGTERM is agreed by all ranks (stop_requested), so they finish MPI normally.
  if (code != 0 && code != static_cast<int>(ExitCode::interrupted) && comm.size() > 1)
    MPI_Abort(MPI_COMM_WORLD, code);
  // A file whose close failed (disk full) would crash HDF5's own shutdown inside MPI_Finalize;
  // the error is reported and every temporary removed by now, so end here with its code.
  if (code != 0 && h5::library_holds_a_failed_file()) {
    std::cout.flush();
    std::cerr.flush();
    std::_Exit(code);
  }
  return code;
}

void require_output_is_not_an_input(const std::string& output, const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  for (const std::string& input : inputs) {
    std::error_code error;
    const bool same = fs::exists(output, error)
                          ? fs::equivalent(output, input, error)
                          : fs::weakly_canonical(output, error) == fs::weakly_canonical(input, error);
    require_input(!same, "output '" + output + "' is the input '" + input +
                             "': writing it would replace the input; "
                             "choose another --output");
  }
}

} // namespace aniso::cli
