#pragma once
// MPI vocabulary for aniso: an RAII environment, a communicator value that is
// passed explicitly (no global "world" lookups inside the library), and
// reductions. Sums of doubles go through ExactSum so that the result is
// bit-identical for any number of ranks and any order of contributions.

#include "common/exact_sum.hpp"

#include <mpi.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace aniso::mpi {

/// Initializes MPI on construction and finalizes it on destruction. One per process, in main().
class Environment {
public:
  Environment(int& argc, char**& argv);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

private:
  std::string session_base_; ///< a singleton's own Open MPI session base, removed at the end (mpi.cpp)
};

/// A communicator handle with value semantics (it does not own the MPI_Comm unless it came from split()).
class Comm {
public:
  /// The world communicator. Valid only while an Environment exists.
  static Comm world();
  /// Wraps an existing communicator without taking ownership.
  explicit Comm(MPI_Comm raw) : raw_(raw) {}

  [[nodiscard]] int rank() const;
  [[nodiscard]] int size() const;
  [[nodiscard]] bool is_root() const { return rank() == 0; }
  [[nodiscard]] MPI_Comm raw() const { return raw_; }

  /// Splits into sub-communicators by colour (collective). The caller frees the result with free().
  [[nodiscard]] Comm split(int colour, int key) const;
  /// Frees a communicator obtained from split().
  void free();

  void barrier() const;

  /// Bit-identical global sum, independent of rank count and order (collective).
  [[nodiscard]] double sum_exact(double local) const;
  /// Exact global sum of per-rank accumulators (collective). Accumulate each rank's
  /// terms in an ExactSum, then reduce: the result does not depend on how terms were dealt.
  [[nodiscard]] ExactSum sum_exact(const ExactSum& local) const;
  [[nodiscard]] std::vector<ExactSum> sum_exact(std::span<const ExactSum> local) const;
  /// Element-wise bit-identical global sum of equally long arrays (collective).
  [[nodiscard]] std::vector<double> sum_exact(std::span<const double> local) const;
  /// Integer sums, max and min are exact anyway (collective).
  [[nodiscard]] std::int64_t sum(std::int64_t local) const;
  [[nodiscard]] std::vector<std::int64_t> sum(std::span<const std::int64_t> local) const;
  [[nodiscard]] double max(double local) const;
  /// Element-wise maximum of equally long arrays (collective).
  [[nodiscard]] std::vector<double> max(std::span<const double> local) const;
  [[nodiscard]] double min(double local) const;
  [[nodiscard]] std::int64_t max(std::int64_t local) const;
  /// True on every rank if it is true on any rank (collective).
  [[nodiscard]] bool any(bool local) const;
  /// Exclusive prefix sum over ranks: the count held by lower ranks (collective).
  [[nodiscard]] std::int64_t exclusive_scan(std::int64_t local) const;
  /// Broadcasts bytes from root to all ranks (collective); resizes on receivers.
  void broadcast(std::vector<char>& bytes, int root = 0) const;
  /// Gathers each rank's int64 to every rank (collective).
  [[nodiscard]] std::vector<std::int64_t> all_gather(std::int64_t local) const;

private:
  MPI_Comm raw_;
};

/// A problem found by the lowest rank that found one, with that rank, on every rank; nothing when
/// no rank found any (collective). A check that only some ranks can fail (each checks its own
/// rows) must end on every rank with the same message, or the others wait in the next collective.
struct RankProblem {
  int rank = 0;
  std::string text;
};
[[nodiscard]] std::optional<RankProblem> first_problem(const Comm& comm,
                                                       const std::optional<std::string>& local);

} // namespace aniso::mpi
