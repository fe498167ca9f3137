#pragma once
// Assembling a probe result from six fork results, with the checks that make a
// mix-up impossible: every fork 0..6 present exactly once, all from the same
// checkpoint (content hash), all with the same settings, and all starting from
// the same restored state with the same step count (bit for bit).

#include "probe/config.hpp"
#include "probe/files.hpp"

#include <string>
#include <vector>

namespace aniso::probe {

/// Orders and checks fork files (paths[k] is where files[k] came from, for messages) against the
/// checkpoint hash `expected_hash`. FileError naming the file and the problem otherwise.
std::array<ForkFile, n_fork_files> check_forks(const std::vector<ForkFile>& files,
                                               const std::vector<std::string>& paths,
                                               const std::string& expected_hash);

/// The result of six checked forks: the matrices, and the increment checks. If the increment is
/// found too large or too small, NumericalError when config.check_increment, else the result is
/// returned with checks_passed = false and `warning` set to the message.
ProbeResult assemble_result(const std::array<ForkFile, n_fork_files>& forks, const ProbeConfig& config,
                            std::string& warning);

} // namespace aniso::probe
