#include "common/error.hpp"

#include <fmt/format.h>

namespace aniso {

void check_invariant(bool condition, const char* what, std::source_location where) {
  if (!condition) {
    throw Error(ExitCode::internal_error, fmt::format("internal error: invariant '{}' violated at {}:{}",
                                                      what, where.file_name(), where.line()));
  }
}

const char* exit_code_name(ExitCode code) noexcept {
  switch (code) {
  case ExitCode::success: return "success";
  case ExitCode::internal_error: return "internal error";
  case ExitCode::bad_input: return "bad input";
  case ExitCode::file_error: return "file error";
  case ExitCode::numerical_failure: return "numerical failure";
  case ExitCode::convergence_failure: return "convergence failure";
  case ExitCode::interrupted: return "interrupted";
  }
  return "unknown";
}

} // namespace aniso
