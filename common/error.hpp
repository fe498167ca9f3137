#pragma once
// Error types shared by every stage, and the process exit code each maps to.
// The codes are part of the user interface (scripts and SLURM test them);
// they are documented in docs/user-guide.md#exit-codes.

#include <source_location>
#include <stdexcept>
#include <string>

namespace aniso {

/// Process exit codes. 0 is success; 1 is reserved for unexpected internal errors.
enum class ExitCode : int {
  success = 0,
  internal_error = 1,      ///< a bug: an exception nobody anticipated
  bad_input = 2,           ///< command line, config key, value or range rejected
  file_error = 3,          ///< a file is missing, unreadable, malformed or fails validation
  numerical_failure = 4,   ///< NaN, explosion, a step above the stability limit
  convergence_failure = 5, ///< an iteration did not reach its criterion within its limit
  interrupted = 143,       ///< stopped on SIGTERM after writing a resumable checkpoint (128 + 15)
};

/// Base of all aniso errors: carries the exit code the process should end with.
class Error : public std::runtime_error {
public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  [[nodiscard]] ExitCode code() const noexcept { return code_; }

private:
  ExitCode code_;
};

/// The user asked for something invalid: an unknown key, a wrong type, a value out of range.
class InputError : public Error {
public:
  explicit InputError(const std::string& message) : Error(ExitCode::bad_input, message) {}
};

/// A file could not be opened, read or written, or its contents fail validation.
class FileError : public Error {
public:
  explicit FileError(const std::string& message) : Error(ExitCode::file_error, message) {}
};

/// The numerics broke down (NaN, overlap explosion, unstable step).
class NumericalError : public Error {
public:
  explicit NumericalError(const std::string& message) : Error(ExitCode::numerical_failure, message) {}
};

/// An iterative method stopped at its limit without meeting its criterion.
class ConvergenceError : public Error {
public:
  explicit ConvergenceError(const std::string& message) : Error(ExitCode::convergence_failure, message) {}
};

/// SIGTERM reached a loop that polls stop_requested() (common/stop_request.hpp): the piece of work in
/// progress is dropped, on every rank at once. A caller that can keep the pieces already finished
/// catches it; otherwise the program ends with exit 143 and the message.
class Interrupted : public Error {
public:
  explicit Interrupted(const std::string& message) : Error(ExitCode::interrupted, message) {}
};

/// Throws InputError(message) unless condition holds. For user-facing checks that stay on in Release.
inline void require_input(bool condition, const std::string& message) {
  if (!condition) throw InputError(message);
}

/// Throws FileError(message) unless condition holds.
inline void require_file(bool condition, const std::string& message) {
  if (!condition) throw FileError(message);
}

/// Internal invariant check that stays on in Release; the message names the source line.
void check_invariant(bool condition, const char* what,
                     std::source_location where = std::source_location::current());

/// Short name of an exit code for messages ("bad input", "file error", ...).
const char* exit_code_name(ExitCode code) noexcept;

} // namespace aniso
