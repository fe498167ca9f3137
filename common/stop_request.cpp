#include "common/stop_request.hpp"

#include <csignal>
#include <cstdlib>
#include <string>

namespace aniso {
namespace {

// The one process-wide mutable state: a signal handler can reach nothing else, and may only
// write a volatile sig_atomic_t.
volatile std::sig_atomic_t stop_signal_received = 0;

extern "C" void on_stop_signal(int) {
  stop_signal_received = 1;
}

} // namespace

void install_stop_handler() {
  std::signal(SIGTERM, on_stop_signal);
}

bool stop_requested_here() {
  return stop_signal_received != 0;
}

bool stop_requested(const mpi::Comm& comm) {
  return comm.size() == 1 ? stop_requested_here() : comm.any(stop_requested_here());
}

bool stop_requested(const mpi::Comm& comm, std::int64_t step) {
  const char* stop_at = std::getenv("ANISO_TEST_STOP_AT_STEP");
  const bool test_stop = stop_at != nullptr && *stop_at != '\0' && step >= std::stoll(stop_at);
  const bool here = stop_requested_here() || test_stop;
  return comm.size() == 1 ? here : comm.any(here);
}

} // namespace aniso
