/*
   spectral_example.h - the program shared by examples/spectral/diffusion.c and advection.c:
   set up a VSHMMSpectral scene from the options, give the TS the full right-hand side and one
   RHS split per cluster, and run it to the output times (output contract of VSHMMSpectralSolve()).
*/
#include <petscvshmm.h>
#include <petscvshmmspectral.h>
#include <stdio.h>

/* Runs the scene `scene` ("diffusion" or "advection") with default final time tfinal. */
static PetscErrorCode RunSpectralExample(const char *scene, PetscReal tfinal)
{
  VSHMMSpectral sp;
  TS            ts;
  Vec           U;
  PetscReal     dt;
  PetscBool     isvshmm, isrk;
  TSType        type;
  char          line[512];

  PetscFunctionBeginUser;
  PetscCall(TSVSHMMInitializePackage());
  PetscCall(VSHMMSpectralCreate(PETSC_COMM_WORLD, &sp));
  PetscCall(VSHMMSpectralSetDefaultScene(sp, scene));
  PetscCall(VSHMMSpectralSetFromOptions(sp));
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(VSHMMSpectralView(sp, NULL));
  PetscCall(VSHMMSpectralCreateVec(sp, &U));
  PetscCall(VSHMMSpectralSetInitialCondition(sp, U));

  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetProblemType(ts, TS_LINEAR));
  PetscCall(TSSetSolution(ts, U));
  PetscCall(VSHMMSpectralSetUpTS(sp, ts));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRKSetType(ts, TSRK3));
  PetscCall(VSHMMSpectralEstimateTimeStep(sp, &dt)); /* stable for RK3; set -ts_dt for accuracy */
  PetscCall(TSSetTimeStep(ts, dt));
  PetscCall(TSSetMaxTime(ts, tfinal));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetFromOptions(ts));

  PetscCall(TSGetType(ts, &type));
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &isrk));
  /* C's snprintf for %g (PetscPrintf would print 1 as "1.") */
  if (isvshmm) {
    PetscReal        mdt;
    PetscInt         n, i;
    const PetscReal *alpha;
    TSRKType         rk;
    int              len;

    PetscCall(TSVSHMMGetMicroStep(ts, &mdt));
    PetscCall(TSVSHMMGetSavingsFactors(ts, &n, &alpha));
    PetscCall(TSVSHMMGetRKType(ts, &rk));
    len = snprintf(line, sizeof(line), "ts_type vshmm: sampling interval %g, micro step %g, inner RK %s, savings factors", (double)dt, (double)(mdt > 0 ? mdt : dt / 100), rk);
    for (i = 0; i < n && len > 0 && len < (int)sizeof(line); i++) len += snprintf(line + len, sizeof(line) - len, "%s%g", i ? "," : " ", (double)alpha[i]);
    if (!n && len > 0 && len < (int)sizeof(line)) snprintf(line + len, sizeof(line) - len, " (all 1)");
  } else if (isrk) {
    TSRKType rk;

    PetscCall(TSRKGetType(ts, &rk));
    snprintf(line, sizeof(line), "ts_type rk %s: time step %g", rk, (double)dt);
  } else {
    snprintf(line, sizeof(line), "ts_type %s: time step %g", type, (double)dt);
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", line));

  PetscCall(VSHMMSpectralSolve(sp, ts, U));

  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
  PetscCall(VSHMMSpectralDestroy(&sp));
  PetscFunctionReturn(0);
}
