#pragma once
// The command line every aniso program shares (CLI11):
//   --config FILE.toml   --set key=value (repeatable)   --print-config
//   --log-level LEVEL    --dry-run   --help   --version
// and the one place where exceptions become exit codes.

#include "common/config.hpp"
#include "common/log.hpp"
#include "common/mpi.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace aniso::cli {

struct CommonOptions {
  std::string config_path;            ///< empty: defaults only
  std::vector<std::string> overrides; ///< key=value, applied after the file, in order
  bool print_config = false;          ///< print the effective configuration and stop
  bool dry_run = false;               ///< validate config and inputs, then stop
  std::string log_level = "info";
  std::string command_line; ///< argv joined, for provenance
};

/// Adds the shared options and --version to `app`.
void add_common_options(CLI::App& app, CommonOptions& options, const std::string& program);

/// Parses argv. Returns an exit code when the program should stop now
/// (--help, --version, or a command-line error, printed on rank 0 only).
std::optional<int> parse(CLI::App& app, int argc, char** argv, const mpi::Comm& comm);

/// The config file (if any) with every --set override applied, and a name for messages.
struct ConfigSource {
  toml::table table;
  std::string name;
};
ConfigSource load_config(const CommonOptions& options);

/// After a stage has read all its keys: rejects unknown keys, and handles
/// --print-config (prints on rank 0). Returns true if the program should stop now.
bool finish_config(const config::Reader& reader, const CommonOptions& options, const mpi::Comm& comm);

/// Runs `body` inside an MPI environment and maps exceptions to exit codes
/// (see ExitCode). The message is printed once, prefixed by the program name.
/// Used by every main(): `return aniso::cli::run(argc, argv, "aniso-x", body);`
int run(int argc, char** argv, const std::string& program,
        const std::function<int(int argc, char** argv, const mpi::Comm& comm)>& body);

/// argv joined with spaces.
std::string join_command_line(int argc, char** argv);

/// InputError naming both when an output path is one of the inputs (the same file under any
/// spelling, links included): writing it would replace the input.
void require_output_is_not_an_input(const std::string& output, const std::vector<std::string>& inputs);

} // namespace aniso::cli
