#pragma once
/// PETSc's error codes as exceptions, for the files built with PETSc (NODUS_HAVE_PETSC). nodus installs
/// PetscReturnErrorHandler (mpi_session.cpp), so a failing PETSc call returns its code instead of aborting.

#include <stdexcept>

#include <fmt/format.h>
#include <petscsys.h>

namespace nodus::parallel {

/// Throws std::runtime_error naming `what` if `code` is not 0.
inline void check_petsc(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc: {} failed (error code {})", what, code));
}

}  // namespace nodus::parallel
