static char help[] = "Takes 10^5 TSVSHMM macro steps and checks that the memory in use does not grow.\n";

/* Three scales: x' = 1 - x (slow, additive), y' = (x - y)/1e-2, z' = (y - z)/1e-3 (component splits). */
#include <petscvshmm.h>

static PetscErrorCode Slow(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  const PetscScalar *u;
  PetscScalar       *f;
  PetscInt           n, i;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(F, &n));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  for (i = 0; i < n; i++) f[i] = 0;
  if (n == 3) f[0] = 1 - u[0];
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

static PetscErrorCode Medium(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  const PetscScalar *u;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  f[0] = (u[0] - u[1]) / 1e-2;
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

static PetscErrorCode Fast(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  const PetscScalar *u;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  f[0] = (u[1] - u[2]) / 1e-3;
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscLogDouble rss_early; /* after the first 10^4 macro steps */
} Memory;

static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  Memory *m = (Memory *)ctx;

  PetscFunctionBeginUser;
  if (step == 10000) PetscCall(PetscMemoryGetCurrentUsage(&m->rss_early));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  TS                ts;
  Vec               x;
  IS                all, is1, is2;
  PetscInt          steps   = 100000;
  const PetscReal   alpha[] = {5, 2};
  Memory            m       = {0};
  PetscLogDouble    rss_end;
  TSVSHMMStatistics stats;
  PetscScalar       x0[3]  = {1, 0, 0};
  PetscInt          idx[3] = {0, 1, 2};
  PetscReal         xend;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-steps", &steps, NULL));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3, &x));
  PetscCall(VecSetValues(x, 3, idx, x0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(x));
  PetscCall(VecAssemblyEnd(x));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 3, 0, 1, &all));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 1, 1, 1, &is1));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 1, 2, 1, &is2));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSVSHMM));
  PetscCall(TSRHSSplitSetIS(ts, "slow", all));
  PetscCall(TSRHSSplitSetIS(ts, "medium", is1));
  PetscCall(TSRHSSplitSetIS(ts, "fast", is2));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "slow", NULL, Slow, NULL));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "medium", NULL, Medium, NULL));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "fast", NULL, Fast, NULL));
  PetscCall(TSSetSolution(ts, x));
  PetscCall(TSSetTimeStep(ts, 1e-2));
  PetscCall(TSSetMaxSteps(ts, steps));
  PetscCall(TSSetMaxTime(ts, 1e9));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_STEPOVER));
  PetscCall(TSVSHMMSetMicroStep(ts, 1e-4));
  PetscCall(TSVSHMMSetSavingsFactors(ts, 2, alpha));
  PetscCall(TSVSHMMSetStabilityCheck(ts, PETSC_TRUE, 1000));
  PetscCall(TSMonitorSet(ts, Monitor, &m, NULL));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, x));
  PetscCall(PetscMemoryGetCurrentUsage(&rss_end));
  PetscCall(TSVSHMMGetStatistics(ts, &stats));
  PetscCall(VecShift(x, -1.0));
  PetscCall(VecNorm(x, NORM_INFINITY, &xend));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%lld macro steps, %lld micro cycles, %lld stability checks; |x - 1|_inf = %g\n", (long long)stats.macro_steps, (long long)stats.micro_cycles, (long long)stats.stability_checks, (double)xend));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "resident memory after 10^4 macro steps %.0f kB, at the end %.0f kB\n", m.rss_early / 1024, rss_end / 1024));
  PetscCheck(stats.macro_steps == steps, PETSC_COMM_SELF, PETSC_ERR_PLIB, "took %lld macro steps, not %lld", (long long)stats.macro_steps, (long long)steps);
  PetscCheck(xend < 1e-6, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the state did not relax to (1, 1, 1): |x - 1| = %g", (double)xend);
  PetscCheck(steps < 20000 || rss_end - m.rss_early < 1024 * 1024, PETSC_COMM_SELF, PETSC_ERR_MEM, "resident memory grew by %.0f kB over 9 x 10^4 macro steps", (rss_end - m.rss_early) / 1024);
  PetscCall(ISDestroy(&all));
  PetscCall(ISDestroy(&is1));
  PetscCall(ISDestroy(&is2));
  PetscCall(VecDestroy(&x));
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscFinalize());
  return 0;
}
