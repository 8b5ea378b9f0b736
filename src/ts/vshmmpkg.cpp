/*
  Registration of the TSVSHMM package: the type, its log events, and the dynamic-library hook.
*/
#include "vshmmimpl.hpp"

static PetscBool TSVSHMMPackageInitialized = PETSC_FALSE;

/*@C
   TSVSHMMFinalizePackage - Resets the TSVSHMM package state; called from `PetscFinalize()`

   Level: developer

.seealso: `TSVSHMMInitializePackage()`, `PetscFinalize()`
@*/
PetscErrorCode TSVSHMMFinalizePackage(void)
{
  PetscFunctionBegin;
  TSVSHMMPackageInitialized = PETSC_FALSE;
  PetscCall(TSVSHMMResetLevelEvents_Private());
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMInitializePackage - Registers the `TSVSHMM` time stepper type ("vshmm") with PETSc

   Not Collective

   Notes:
   Call it after `PetscInitialize()` and before `TSSetType()` or `TSSetFromOptions()` select
   "vshmm". It is idempotent, and `PetscFinalize()` resets it, so a later `PetscInitialize()`
   may register the type again. A program that does not call it gets the type by loading the
   library at run time: -dll_append <prefix>/lib/libpetscvshmm.so.

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMFinalizePackage()`, `TSRegister()`
@*/
PetscErrorCode TSVSHMMInitializePackage(void)
{
  PetscFunctionBegin;
  if (TSVSHMMPackageInitialized) PetscFunctionReturn(0);
  TSVSHMMPackageInitialized = PETSC_TRUE;
  PetscCall(TSInitializePackage());
  PetscCall(TSRegister(TSVSHMM, TSCreate_VSHMM));
  PetscCall(PetscRegisterFinalize(TSVSHMMFinalizePackage));
  PetscFunctionReturn(0);
}

/*
  PetscDLLibraryRegister_petscvshmm - called by PETSc when the library is loaded with
  -dll_append (the name follows from the file name libpetscvshmm.so)
*/
PETSC_EXTERN PetscErrorCode PetscDLLibraryRegister_petscvshmm(void)
{
  PetscFunctionBegin;
  PetscCall(TSVSHMMInitializePackage());
  PetscFunctionReturn(0);
}
