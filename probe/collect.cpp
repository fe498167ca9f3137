#include "probe/collect.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <optional>

namespace aniso::probe {

std::array<ForkFile, n_fork_files> check_forks(const std::vector<ForkFile>& files,
                                               const std::vector<std::string>& paths,
                                               const std::string& expected_hash) {
  check_invariant(files.size() == paths.size(), "one path per fork file");
  std::array<std::optional<std::size_t>, n_fork_files> slot;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const ForkFile& f = files[k];
    const auto index = static_cast<std::size_t>(f.result.index);
    if (slot[index]) {
      throw FileError(fmt::format("fork files '{}' and '{}' both hold fork {}", paths[*slot[index]], paths[k],
                                  f.result.index));
    }
    slot[index] = k;
    if (f.source.hash != expected_hash) {
      throw FileError(fmt::format(
          "fork file '{}' comes from another checkpoint: its source '{}' has content hash {}, expected {}",
          paths[k], f.source.path, f.source.hash, expected_hash));
    }
  }
  std::array<ForkFile, n_fork_files> ordered;
  for (int index = 0; index < n_fork_files; ++index) {
    const auto& found = slot[static_cast<std::size_t>(index)];
    if (!found)
      throw FileError(
          fmt::format("fork {} is missing: {} fork files given, none holds it", index, files.size()));
    ordered[static_cast<std::size_t>(index)] = files[*found];
  }
  const ForkFile& first = ordered[0];
  const std::string& first_path = paths[*slot[0]];
  for (int index = 1; index < n_fork_files; ++index) {
    const ForkFile& f = ordered[static_cast<std::size_t>(index)];
    const std::string& path = paths[*slot[static_cast<std::size_t>(index)]];
    if (!(f.settings == first.settings)) {
      throw FileError(fmt::format(
          "fork file '{}' was run with other probe settings than '{}' (increment {} vs {}, inertial number "
          "{} vs {}, hold steps {} vs {}, window steps {} vs {})",
          path, first_path, f.settings.increment, first.settings.increment, f.settings.inertial_number,
          first.settings.inertial_number, f.settings.hold_steps, first.settings.hold_steps,
          f.settings.window_steps, first.settings.window_steps));
    }
    if (f.result.stress_start != first.result.stress_start ||
        f.result.half_steps != first.result.half_steps) {
      throw FileError(fmt::format(
          "fork file '{}' starts from another restored state or step count than '{}' although both come from "
          "the same checkpoint: they were run by different builds of aniso-probe; rerun the forks with one "
          "build",
          path, first_path));
    }
  }
  return ordered;
}

ProbeResult assemble_result(const std::array<ForkFile, n_fork_files>& forks, const ProbeConfig& config,
                            std::string& warning) {
  ProbeResult result;
  result.source = forks[0].source;
  result.settings = forks[0].settings;
  result.stress_reference = mean_of(forks[reference_fork].result.samples_final);
  for (int k = 0; k < n_fork_files; ++k)
    result.forks[static_cast<std::size_t>(k)] = forks[static_cast<std::size_t>(k)].result;
  result.stiffness = assemble_stiffness(result.forks);
  warning = increment_problems(result.stiffness, config.tolerances);
  result.checks_passed = warning.empty();
  if (!warning.empty() && config.check_increment) {
    throw NumericalError(
        fmt::format("probe of '{}': {} (set probe.check_increment = false to keep such a result)",
                    result.source.path, warning));
  }
  return result;
}

} // namespace aniso::probe
