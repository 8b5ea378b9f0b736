static char help[] = "Checks that TSVSHMM can be registered again after PetscFinalize() and a second PetscInitialize().\n";

#include <petscvshmm.h>

/* One PETSc session: register, create a TSVSHMM, check its type, finalize. */
static PetscErrorCode Session(int *argc, char ***argv, int round)
{
  TS        ts;
  PetscBool same;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(argc, argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());
  PetscCall(TSVSHMMInitializePackage()); /* idempotent */
  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetType(ts, TSVSHMM));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &same));
  PetscCheck(same, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "round %d: the TS is not of type vshmm", round);
  {
    TSType type;
    PetscCall(TSGetType(ts, &type));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "round %d: TS type %s\n", round, type));
  }
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscFinalize());
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  /* MPI outlives both PETSc sessions: PETSc neither initializes nor finalizes it. */
  if (MPI_Init(&argc, &argv)) return 1;
  if (Session(&argc, &argv, 1)) return 1;
  if (Session(&argc, &argv, 2)) return 1;
  return MPI_Finalize() ? 1 : 0;
}
