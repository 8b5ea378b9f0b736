/*
  Argument checks of the public functions that stay in every build. PETSc's own
  (PetscValidHeaderSpecific(), PetscValidPointer(), ...) compile to nothing in an optimised PETSc,
  such as Debian's, where a NULL argument (TSVSHMMSetSavingsFactors(ts, 2, NULL),
  TSVSHMMGetStatistics(ts, NULL)) then crashed with a segmentation fault instead of an error
  (private; not installed; included by both libraries).
*/
#pragma once

#include <petsc/private/petscimpl.h>

#define VSHMMValidHeaderSpecific(h, ck, arg) \
  do { \
    PetscCheck((h), PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "Null Object: Parameter # %d", (int)(arg)); \
    PetscCheck(((PetscObject)(h))->classid == (ck), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Wrong type of object: Parameter # %d", (int)(arg)); \
  } while (0)
#define VSHMMValidPointer(p, arg) PetscCheck((p), PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "Null Pointer: Parameter # %d", (int)(arg))
