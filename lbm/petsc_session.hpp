#pragma once
// PETSc for the lifetime of the object, on top of an MPI that is already
// initialized (so PetscFinalize leaves MPI alone). `options` is a string in
// PETSc's command-line syntax ("-log_view -da_processors_x 2") that goes into
// the options database before PETSc starts, so -log_view takes effect.

#include <string>
#include <vector>

namespace aniso::lbm {

class PetscSession {
public:
  explicit PetscSession(const std::string& options = "");
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

private:
  std::vector<std::string> words_; ///< PETSc keeps pointers to its argv for the whole session
  std::vector<char*> argv_;
  bool owner_ = false; ///< false when PETSc was already running
};

} // namespace aniso::lbm
