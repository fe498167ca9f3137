#include "common/stop_request.hpp"

#include <csignal>

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

} // namespace aniso
