#pragma once
// PETSc for a whole test program (PETSc cannot restart once finalized).
#include "lbm/petsc_session.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace aniso::lbm::testing {

class PetscEnvironment : public ::testing::Environment {
public:
  void SetUp() override { session_ = std::make_unique<PetscSession>(); }
  void TearDown() override { session_.reset(); }

private:
  std::unique_ptr<PetscSession> session_;
};

inline const ::testing::Environment* const petsc_environment =
    ::testing::AddGlobalTestEnvironment(new PetscEnvironment);

} // namespace aniso::lbm::testing
