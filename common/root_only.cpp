#include "common/root_only.hpp"

#include "common/error.hpp"

#include <exception>
#include <string>
#include <vector>

namespace aniso {

void run_on_root(const mpi::Comm& comm, const std::function<void()>& body) {
  std::string failure; // first byte: exit code; the rest: the message
  if (comm.is_root()) {
    try {
      body();
    } catch (const Error& e) {
      failure = std::string(1, static_cast<char>(e.code())) + e.what();
    } catch (const std::exception& e) {
      failure = std::string(1, static_cast<char>(ExitCode::internal_error)) + e.what();
    }
  }
  std::vector<char> bytes(failure.begin(), failure.end());
  comm.broadcast(bytes);
  if (bytes.empty()) return;
  throw Error(static_cast<ExitCode>(bytes[0]), std::string(bytes.begin() + 1, bytes.end()));
}

} // namespace aniso
