static char help[] = "Creates a TS of type TSVSHMM: a test of linking with petsc-vshmm.\n";

#include <petscvshmm.h>

int main(int argc, char **argv)
{
  TS        ts;
  TSType    type;
  PetscBool same;
  PetscReal dt;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());
  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetType(ts, TSVSHMM));
  PetscCall(TSVSHMMSetMicroStep(ts, 1e-3));
  PetscCall(TSVSHMMGetMicroStep(ts, &dt));
  PetscCall(TSGetType(ts, &type));
  PetscCall(PetscStrcmp(type, TSVSHMM, &same));
  PetscCheck(same, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "TS type is %s, not %s", type, TSVSHMM);
  PetscCheck(dt == (PetscReal)1e-3, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "micro step %g, not 1e-3", (double)dt);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "vshmm_hello: TS type %s\n", type));
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscFinalize());
  return 0;
}
