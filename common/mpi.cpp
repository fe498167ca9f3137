#include "common/mpi.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace aniso::mpi {
namespace {

void check(int status, const char* what) {
  if (status != MPI_SUCCESS) throw Error(ExitCode::internal_error, std::string("MPI call failed: ") + what);
}

// A process that mpiexec or srun started carries its rank in the environment; one started on its
// own is a singleton.
bool started_by_launcher() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_RANK") != nullptr;
}

// Open MPI 4's isolated singletons all take job family 0, so every one of a user's singletons on a
// host uses the session directory <tmp>/ompi.<host>.<uid>/jf.0: created check-then-mkdir and
// removed by the first to finish. Two stages started at once by make -j or ctest -j race there, and
// the loser aborts in MPI_Init ("A call to mkdir was unable to create the desired directory ...
// File exists"; seen in CI on an LBM direction of the paper e2e test; open-mpi/ompi#8510). A
// singleton gets a session base of its own under $TMPDIR (or /tmp), removed when it ends; the
// user's own orte_tmpdir_base wins. Empty when not made (launched, set by the user, or no
// writable temporary folder: then Open MPI's default, as before).
std::string own_session_base() {
#if defined(OPEN_MPI) && OMPI_MAJOR_VERSION < 5
  if (started_by_launcher() || std::getenv("OMPI_MCA_orte_tmpdir_base") != nullptr) return {};
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/aniso-mpi-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) return {};
  setenv("OMPI_MCA_orte_tmpdir_base", pattern.c_str(), 1);
  return pattern;
#else
  return {};
#endif
}

} // namespace

Environment::Environment(int& argc, char**& argv) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    // A program started without mpiexec is an Open MPI singleton, which by default forks an
    // orted daemon first; where the host name does not resolve (a container or chroot without
    // /etc/hosts) that waits about 5 s for DNS. aniso never spawns processes, so the isolated
    // singleton does. The user's own setting wins; under mpiexec the key has no effect.
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
    // Isolated singletons all take job family 0 and so share one session directory, which the
    // first to finish removes; OMPIO's "sm" shared-file-pointer component creates a file there
    // at every MPI_File_open, and a concurrent singleton's HDF5 write then failed ("unable to
    // open file for mmap", seen once under ctest -j2; Open MPI issue 10971 is the same warning).
    // aniso never uses shared file pointers; without "sm" OMPIO takes "lockedfile", whose lock
    // sits next to the file being written and is removed when it is closed. Under mpiexec the
    // session directory is the job's own, and the choice makes no difference.
    setenv("OMPI_MCA_sharedfp", "^sm", 0);
    session_base_ = own_session_base();
    check(MPI_Init(&argc, &argv), "MPI_Init");
  }
  // Errors come back as codes so that we can throw with a message instead of aborting silently.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

Environment::~Environment() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
  std::error_code ignored; // a leftover in the temporary folder is no reason to fail a finished run
  if (!session_base_.empty()) std::filesystem::remove_all(session_base_, ignored);
}

Comm Comm::world() {
  return Comm(MPI_COMM_WORLD);
}

int Comm::rank() const {
  int value = 0;
  check(MPI_Comm_rank(raw_, &value), "MPI_Comm_rank");
  return value;
}

int Comm::size() const {
  int value = 0;
  check(MPI_Comm_size(raw_, &value), "MPI_Comm_size");
  return value;
}

Comm Comm::split(int colour, int key) const {
  MPI_Comm result = MPI_COMM_NULL;
  check(MPI_Comm_split(raw_, colour, key, &result), "MPI_Comm_split");
  return Comm(result);
}

void Comm::free() {
  if (raw_ != MPI_COMM_NULL && raw_ != MPI_COMM_WORLD && raw_ != MPI_COMM_SELF) MPI_Comm_free(&raw_);
}

void Comm::barrier() const {
  check(MPI_Barrier(raw_), "MPI_Barrier");
}

double Comm::sum_exact(double local) const {
  ExactSum sum;
  sum.add(local);
  return sum_exact(sum).value();
}

std::vector<double> Comm::sum_exact(std::span<const double> local) const {
  std::vector<ExactSum> sums(local.size());
  for (std::size_t i = 0; i < local.size(); ++i)
    sums[i].add(local[i]);
  const std::vector<ExactSum> reduced = sum_exact(std::span<const ExactSum>(sums));
  std::vector<double> result(local.size());
  for (std::size_t i = 0; i < local.size(); ++i)
    result[i] = reduced[i].value();
  return result;
}

ExactSum Comm::sum_exact(const ExactSum& local) const {
  return sum_exact(std::span<const ExactSum>(&local, 1))[0];
}

std::vector<ExactSum> Comm::sum_exact(std::span<const ExactSum> local) const {
  constexpr int n_limbs = ExactSum::n_limbs;
  constexpr std::size_t stride = n_limbs + 1; // one extra slot carries the non-finite flag
  const std::size_t n_values = local.size();
  std::vector<std::int64_t> packed(n_values * stride);
  for (std::size_t i = 0; i < n_values; ++i) {
    const auto limbs = local[i].normalized_limbs();
    std::copy(limbs.begin(), limbs.end(), packed.begin() + static_cast<std::ptrdiff_t>(i * stride));
    packed[i * stride + n_limbs] = local[i].nonfinite() ? 1 : 0;
  }
  // Normalized limbs are below 2^32, so an integer sum over any realistic rank count cannot overflow.
  check(
      MPI_Allreduce(MPI_IN_PLACE, packed.data(), static_cast<int>(packed.size()), MPI_INT64_T, MPI_SUM, raw_),
      "MPI_Allreduce (exact sum)");
  std::vector<ExactSum> result(n_values);
  for (std::size_t i = 0; i < n_values; ++i) {
    ExactSum::Limbs limbs{};
    std::copy_n(packed.begin() + static_cast<std::ptrdiff_t>(i * stride), n_limbs, limbs.begin());
    result[i] = ExactSum::from_limbs(limbs, packed[i * stride + n_limbs] != 0);
  }
  return result;
}

std::int64_t Comm::sum(std::int64_t local) const {
  std::int64_t result = 0;
  check(MPI_Allreduce(&local, &result, 1, MPI_INT64_T, MPI_SUM, raw_), "MPI_Allreduce (sum)");
  return result;
}

std::vector<std::int64_t> Comm::sum(std::span<const std::int64_t> local) const {
  std::vector<std::int64_t> result(local.begin(), local.end());
  check(
      MPI_Allreduce(MPI_IN_PLACE, result.data(), static_cast<int>(result.size()), MPI_INT64_T, MPI_SUM, raw_),
      "MPI_Allreduce (sum)");
  return result;
}

double Comm::max(double local) const {
  double result = 0;
  check(MPI_Allreduce(&local, &result, 1, MPI_DOUBLE, MPI_MAX, raw_), "MPI_Allreduce (max)");
  return result;
}

std::vector<double> Comm::max(std::span<const double> local) const {
  std::vector<double> result(local.begin(), local.end());
  check(
      MPI_Allreduce(MPI_IN_PLACE, result.data(), static_cast<int>(result.size()), MPI_DOUBLE, MPI_MAX, raw_),
      "MPI_Allreduce (max)");
  return result;
}

double Comm::min(double local) const {
  double result = 0;
  check(MPI_Allreduce(&local, &result, 1, MPI_DOUBLE, MPI_MIN, raw_), "MPI_Allreduce (min)");
  return result;
}

std::int64_t Comm::max(std::int64_t local) const {
  std::int64_t result = 0;
  check(MPI_Allreduce(&local, &result, 1, MPI_INT64_T, MPI_MAX, raw_), "MPI_Allreduce (max)");
  return result;
}

bool Comm::any(bool local) const {
  int value = local ? 1 : 0;
  int result = 0;
  check(MPI_Allreduce(&value, &result, 1, MPI_INT, MPI_LOR, raw_), "MPI_Allreduce (any)");
  return result != 0;
}

std::int64_t Comm::exclusive_scan(std::int64_t local) const {
  std::int64_t result = 0;
  check(MPI_Exscan(&local, &result, 1, MPI_INT64_T, MPI_SUM, raw_), "MPI_Exscan");
  return rank() == 0 ? 0 : result; // MPI leaves rank 0's result undefined
}

void Comm::broadcast(std::vector<char>& bytes, int root) const {
  auto n_bytes = static_cast<std::int64_t>(bytes.size());
  check(MPI_Bcast(&n_bytes, 1, MPI_INT64_T, root, raw_), "MPI_Bcast (size)");
  bytes.resize(static_cast<std::size_t>(n_bytes));
  check(MPI_Bcast(bytes.data(), static_cast<int>(n_bytes), MPI_CHAR, root, raw_), "MPI_Bcast");
}

std::vector<std::int64_t> Comm::all_gather(std::int64_t local) const {
  std::vector<std::int64_t> result(static_cast<std::size_t>(size()));
  check(MPI_Allgather(&local, 1, MPI_INT64_T, result.data(), 1, MPI_INT64_T, raw_), "MPI_Allgather");
  return result;
}

std::optional<RankProblem> first_problem(const Comm& comm, const std::optional<std::string>& local) {
  const std::vector<std::int64_t> failed = comm.all_gather(local ? 1 : 0);
  for (int rank = 0; rank < static_cast<int>(failed.size()); ++rank) {
    if (failed[static_cast<std::size_t>(rank)] == 0) continue;
    const std::string text = local.value_or("");
    std::vector<char> bytes(text.begin(), text.end());
    comm.broadcast(bytes, rank);
    return RankProblem{rank, std::string(bytes.begin(), bytes.end())};
  }
  return std::nullopt;
}

} // namespace aniso::mpi
