static const char help[] = "The ODE benchmark problems (bench_problems.h) with an IMEX split for PETSc's TSARKIMEX:\n\
the terms f_0 .. f_(m-1) are explicit (RHS function), the faster terms f_m .. f_K implicit (IFunction\n\
with the analytic Jacobian). The fields are those of examples/ode/oscillatory.c, dissipative.c and\n\
examples/stress/chain.c.\n\
Options:\n\
  -problem <oscillators,dissipative,chain>  -eps <e> (chain: e_k = e^k)  -scales <K+1> (chain)\n\
  -implicit_from <m>   : first implicit term (default 1: every fast scale implicit)\n\
  -times <t1,t2,...>   : sample times (the solve stops on each)\n\
  -no_timing           : omit the wall_time line\n\
and every TS option (-ts_arkimex_type, -ts_adapt_type, -ts_rtol, -ts_atol, -ts_dt, ...).\n\
Prints sample t q..., calls, term_evaluations, jacobian_evaluations, steps, wall_time.\n\n";

#include <petscts.h>
#include "bench_problems.h"

typedef struct {
  BenchProblem p;
  PetscInt     m; /* first implicit term */
  PetscInt64   calls, terms, jacs;
} Ctx;

static PetscErrorCode RHSExplicit(TS ts, PetscReal t, Vec X, Vec F, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *x;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(F, &f));
  BenchTerms(&c->p, 0, (int)c->m - 1, x, f);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(X, &x));
  c->calls++;
  c->terms += c->m;
  PetscFunctionReturn(0);
}

/* F = Xdot - (f_m + ... + f_K)(X) */
static PetscErrorCode IFunction(TS ts, PetscReal t, Vec X, Vec Xdot, Vec F, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *x, *xd;
  PetscScalar       *f;
  PetscInt           i;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArrayRead(Xdot, &xd));
  PetscCall(VecGetArray(F, &f));
  BenchTerms(&c->p, (int)c->m, c->p.nterms - 1, x, f);
  for (i = 0; i < c->p.n; i++) f[i] = xd[i] - f[i];
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Xdot, &xd));
  PetscCall(VecRestoreArrayRead(X, &x));
  c->calls++;
  c->terms += c->p.nterms - c->m;
  PetscFunctionReturn(0);
}

static PetscErrorCode IJacobian(TS ts, PetscReal t, Vec X, Vec Xdot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *x;
  double             J[BENCH_MAX_N * BENCH_MAX_N];
  PetscInt           i, j, k, n = c->p.n;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(PetscMemzero(J, sizeof(J)));
  for (k = c->m; k < c->p.nterms; k++) BenchTermJacobianAdd(&c->p, (int)k, x, J);
  PetscCall(VecRestoreArrayRead(X, &x));
  for (i = 0; i < n; i++)
    for (j = 0; j < n; j++) PetscCall(MatSetValue(B, i, j, (i == j ? shift : 0.0) - J[i * n + j], INSERT_VALUES));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  c->jacs++;
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Ctx          c;
  TS           ts;
  Vec          X;
  Mat          J;
  char         problem[64] = "oscillators";
  PetscReal    eps         = -1, times[64], t0, t1;
  PetscInt     ntimes = 64, nscales = 4, i, j, steps;
  PetscBool    flg, notiming        = PETSC_FALSE;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  c.m = 1;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "IMEX benchmark driver options", NULL);
  PetscCall(PetscOptionsString("-problem", "oscillators, dissipative or chain", NULL, problem, problem, sizeof(problem), NULL));
  PetscCall(PetscOptionsReal("-eps", "scale separation", NULL, eps, &eps, NULL));
  PetscCall(PetscOptionsInt("-scales", "number of scales of the chain", NULL, nscales, &nscales, NULL));
  PetscCall(PetscOptionsInt("-implicit_from", "first implicit term", NULL, c.m, &c.m, NULL));
  PetscCall(PetscOptionsBool("-no_timing", "omit the wall_time line", NULL, notiming, &notiming, NULL));
  PetscCall(PetscOptionsRealArray("-times", "sample times", NULL, times, &ntimes, &flg));
  PetscOptionsEnd();
  PetscCheck(flg && ntimes > 0, PETSC_COMM_WORLD, PETSC_ERR_USER, "-times t1,t2,... is required");
  if (eps <= 0) eps = !strcmp(problem, "oscillators") ? 1e-3 : 1e-2;
  PetscCheck(!BenchProblemSetUp(&c.p, problem, eps, (int)nscales), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-problem must be oscillators, dissipative or chain (chain: -scales 2..6), got %s", problem);
  PetscCheck(c.m >= 1 && c.m < c.p.nterms, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-implicit_from must be 1..%d", c.p.nterms - 1);
  c.calls = c.terms = c.jacs = 0;

  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c.p.n, &X));
  PetscCall(VecGetArray(X, &x));
  for (i = 0; i < c.p.n; i++) x[i] = c.p.x0[i];
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, c.p.n, c.p.n, NULL, &J));

  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetProblemType(ts, TS_NONLINEAR));
  PetscCall(TSSetType(ts, TSARKIMEX));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSExplicit, &c));
  PetscCall(TSSetIFunction(ts, NULL, IFunction, &c));
  PetscCall(TSSetIJacobian(ts, J, J, IJacobian, &c));
  PetscCall(TSSetTimeStep(ts, 1e-3));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "method arkimex problem %s eps %g implicit_from %" PetscInt_FMT "\n", problem, (double)eps, c.m));

  PetscCall(PetscTime(&t0));
  for (i = 0; i < ntimes; i++) {
    double             q[2];
    int                nq;
    const PetscScalar *xr;
    TSConvergedReason  reason;

    PetscCall(TSSetMaxTime(ts, times[i]));
    PetscCall(TSSolve(ts, X));
    PetscCall(TSGetConvergedReason(ts, &reason));
    if (reason < 0 || reason == TS_CONVERGED_ITS) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s at sample %g: %s\n", reason == TS_CONVERGED_ITS ? "budget exceeded (-ts_max_steps)" : "failed", (double)times[i], TSConvergedReasons[reason]));
      break;
    }
    PetscCall(VecGetArrayRead(X, &xr));
    nq = BenchObservables(&c.p, xr, q);
    PetscCall(VecRestoreArrayRead(X, &xr));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "sample %.10g", (double)times[i]));
    for (j = 0; j < nq; j++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, " %.12e", q[j]));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "\n"));
  }
  PetscCall(PetscTime(&t1));
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "calls %lld\nterm_evaluations %lld\njacobian_evaluations %lld\nsteps %" PetscInt_FMT "\n", (long long)c.calls, (long long)c.terms, (long long)c.jacs, steps));
  if (!notiming) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "wall_time %.6e\n", (double)(t1 - t0)));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&X));
  PetscCall(PetscFinalize());
  return 0;
}
