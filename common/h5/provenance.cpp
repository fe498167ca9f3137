#include "common/h5/provenance.hpp"

#include "common/h5/file.hpp"
#include "common/version.hpp"

#include <ctime>
#include <vector>

namespace aniso::h5 {
namespace {

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  const std::size_t length = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return std::string(text, length);
}

} // namespace

Provenance make_provenance(const std::string& program, const std::string& config,
                           const std::string& command_line, const mpi::Comm& comm) {
  Provenance provenance;
  provenance.program = program;
  provenance.version = version_string;
  provenance.git_hash = git_hash;
  provenance.config = config;
  provenance.command_line = command_line;
  provenance.n_ranks = comm.size();
  // Ranks may straddle a second boundary; every rank must write the same attribute values.
  const std::string date = comm.is_root() ? utc_now_iso8601() : std::string();
  std::vector<char> bytes(date.begin(), date.end());
  comm.broadcast(bytes, 0);
  provenance.date.assign(bytes.begin(), bytes.end());
  return provenance;
}

void write_provenance(Group& parent, const Provenance& provenance) {
  Group group = parent.create_group("provenance");
  group.write_attribute("program", provenance.program);
  group.write_attribute("version", provenance.version);
  group.write_attribute("git_hash", provenance.git_hash);
  group.write_attribute("config", provenance.config);
  group.write_attribute("command_line", provenance.command_line);
  group.write_attribute("n_ranks", static_cast<std::int64_t>(provenance.n_ranks));
  group.write_attribute("date", provenance.date);
}

Provenance read_provenance(const Group& parent) {
  const Group group = parent.open_group("provenance");
  Provenance provenance;
  provenance.program = group.read_string_attribute("program");
  provenance.version = group.read_string_attribute("version");
  provenance.git_hash = group.read_string_attribute("git_hash");
  provenance.config = group.read_string_attribute("config");
  provenance.command_line = group.read_string_attribute("command_line");
  const std::int64_t n_ranks = group.read_attribute<std::int64_t>("n_ranks");
  if (n_ranks < 1 || n_ranks > 1'000'000'000)
    group.fail("n_ranks = " + std::to_string(n_ranks) + ", expected >= 1");
  provenance.n_ranks = static_cast<int>(n_ranks);
  provenance.date = group.read_string_attribute("date");
  return provenance;
}

} // namespace aniso::h5
