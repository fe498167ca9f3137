#include "probe/resume.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <vector>

namespace aniso::probe {
namespace {

// The fork in the file at `path`, if it is one of this checkpoint and these settings.
std::optional<ForkResult> reusable_fork(const std::string& path, int index, const ProbeSource& source,
                                        const ForkSettings& settings, const Logger& logger) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  try {
    ForkFile file = read_fork_file(path);
    if (file.result.index != index || file.source.hash != source.hash || !(file.settings == settings))
      return std::nullopt;
    return std::move(file.result);
  } catch (const FileError& error) {
    logger->warn("{}: cannot be used ({}); fork {} is run anew", path, error.what(), index);
    return std::nullopt;
  }
}

std::string index_list(const ForkResults& results, bool done) {
  std::string list;
  for (int index = 0; index < n_fork_files; ++index)
    if (results[static_cast<std::size_t>(index)].has_value() == done)
      list += (list.empty() ? "" : ", ") + std::to_string(index);
  return list.empty() ? "none" : list;
}

} // namespace

ForkResults finished_forks(const std::string& folder, const std::string& input, const ProbeSource& source,
                           const ForkSettings& settings, const mpi::Comm& comm, const Logger& logger) {
  ForkResults finished;
  for (int index = 0; index < n_fork_files; ++index) {
    std::vector<char> bytes;
    if (comm.is_root())
      if (auto fork = reusable_fork(fork_path(folder, input, index), index, source, settings, logger))
        bytes = pack_fork(*fork);
    comm.broadcast(bytes, 0);
    if (!bytes.empty()) finished[static_cast<std::size_t>(index)] = unpack_fork(bytes);
  }
  if (index_list(finished, true) != "none")
    logger->info("forks already done by an earlier run: {} (fork files in '{}'); running the others",
                 index_list(finished, true), folder);
  return finished;
}

void keep_forks(const std::string& folder, const std::string& input, const ProbeSource& source,
                const ForkSettings& settings, const ForkResults& results, const ForkResults& finished,
                const h5::Provenance& provenance, const mpi::Comm& comm) {
  if (!comm.is_root()) return;
  for (int index = 0; index < n_fork_files; ++index) {
    const auto k = static_cast<std::size_t>(index);
    if (results[k] && !finished[k])
      write_fork_file(fork_path(folder, input, index), {source, settings, *results[k]}, provenance);
  }
}

void remove_finished(const std::string& folder, const std::string& input, const ForkResults& finished,
                     const mpi::Comm& comm) {
  if (!comm.is_root()) return;
  for (int index = 0; index < n_fork_files; ++index)
    if (finished[static_cast<std::size_t>(index)]) std::filesystem::remove(fork_path(folder, input, index));
}

std::string stop_message(const std::string& folder, const std::string& input, const ForkResults& results,
                         const std::string& command) {
  const std::string files =
      (std::filesystem::path(folder) / fmt::format("probe_{}_fork<N>.h5", checkpoint_stem(input))).string();
  return fmt::format("stopped on SIGTERM: forks done: {} (kept as {}); forks left: {}; continue with the "
                     "same command, which runs only the forks left: {}",
                     index_list(results, true), files, index_list(results, false), command);
}

} // namespace aniso::probe
