#include "lbm/petsc_session.hpp"

#include "common/error.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <sstream>

namespace aniso::lbm {

PetscSession::PetscSession(const std::string& options) {
  PetscBool initialized = PETSC_FALSE;
  static_cast<void>(PetscInitialized(&initialized));
  if (initialized == PETSC_TRUE) return;
  // PETSc reads its options from an argv; build one from the option string.
  words_.emplace_back("aniso-lbm");
  std::istringstream stream(options);
  for (std::string word; stream >> word;)
    words_.push_back(word);
  for (std::string& word : words_)
    argv_.push_back(word.data());
  argv_.push_back(nullptr);
  int argc = static_cast<int>(words_.size());
  char** argv_pointer = argv_.data();
  if (PetscInitialize(&argc, &argv_pointer, nullptr, nullptr) != 0)
    throw InputError(fmt::format("PETSc did not start with options '{}' (lbm.petsc_options)", options));
  owner_ = true;
}

PetscSession::~PetscSession() {
  if (owner_) static_cast<void>(PetscFinalize());
}

} // namespace aniso::lbm
