static const char help[] = "Cost per evaluation of TSVSHMM against TSRK, and TSVSHMM's set-up cost.\n\
A linear three-scale problem on a Vec of n unknowns, dx/dt = -x - 100 x - 1e4 x, given as the full\n\
right-hand side and as three additive RHS splits (each one pass over the Vec). It times\n\
  rk:    TSRK 4 with dt = 1e-4 for -cycles steps: wall time per call of the full RHS;\n\
  vshmm: TSVSHMM, micro step 1e-4, savings factors 10,10, for -cycles micro cycles (stability check\n\
         off): wall time per split call and per level-field evaluation, for the cosine and the\n\
         exponential kernel;\n\
  setup: the first macro step of a one-step solve minus a later one, with and without the\n\
         stability check (the set-up cost on its own).\n\
Options: -n <unknowns> -cycles <N> -repeat <r> (best of r).\n\n";

#include <petscvshmm.h>

typedef struct {
  PetscReal  lambda[3];
  PetscInt64 calls;
} Ctx;

static PetscErrorCode FullRHS(TS ts, PetscReal t, Vec X, Vec F, void *ctx)
{
  Ctx *c = (Ctx *)ctx;

  PetscFunctionBeginUser;
  PetscCall(VecAXPBY(F, -(c->lambda[0] + c->lambda[1] + c->lambda[2]), 0.0, X));
  c->calls++;
  PetscFunctionReturn(0);
}

#define OVERHEAD_SPLIT(k) \
  static PetscErrorCode Split##k(TS ts, PetscReal t, Vec X, Vec F, void *ctx) \
  { \
    Ctx *c = (Ctx *)ctx; \
    PetscFunctionBeginUser; \
    PetscCall(VecAXPBY(F, -c->lambda[k], 0.0, X)); \
    c->calls++; \
    PetscFunctionReturn(0); \
  }
OVERHEAD_SPLIT(0)
OVERHEAD_SPLIT(1)
OVERHEAD_SPLIT(2)

/* A TS of the given type on a fresh state of n ones */
static PetscErrorCode MakeTS(PetscInt n, Ctx *c, TSType type, TS *ts, Vec *X)
{
  TSRHSFunction fns[3]   = {Split0, Split1, Split2};
  const char   *names[3] = {"slow", "medium", "fast"};
  PetscInt      k, lo, hi;

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, n, X));
  PetscCall(VecSet(*X, 1.0));
  PetscCall(VecGetOwnershipRange(*X, &lo, &hi));
  PetscCall(TSCreate(PETSC_COMM_WORLD, ts));
  PetscCall(TSSetProblemType(*ts, TS_NONLINEAR));
  PetscCall(TSSetSolution(*ts, *X));
  PetscCall(TSSetRHSFunction(*ts, NULL, FullRHS, c));
  for (k = 0; k < 3; k++) {
    IS is;

    PetscCall(ISCreateStride(PETSC_COMM_WORLD, hi - lo, lo, 1, &is));
    PetscCall(TSRHSSplitSetIS(*ts, names[k], is));
    PetscCall(TSRHSSplitSetRHSFunction(*ts, names[k], NULL, fns[k], c));
    PetscCall(ISDestroy(&is));
  }
  PetscCall(TSSetType(*ts, type));
  PetscCall(TSSetExactFinalTime(*ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetMaxSteps(*ts, PETSC_MAX_INT));
  PetscFunctionReturn(0);
}

/* Time per RHS call of TSRK 4 */
static PetscErrorCode TimeRK(PetscInt n, PetscInt cycles, Ctx *c, PetscReal *percall, PetscInt64 *calls)
{
  TS             ts;
  Vec            X;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(MakeTS(n, c, TSRK, &ts, &X));
  PetscCall(TSRKSetType(ts, TSRK4));
  PetscCall(TSSetTimeStep(ts, 1e-4));
  PetscCall(TSSetMaxTime(ts, 1e-4 * cycles));
  PetscCall(TSSetUp(ts));
  c->calls = 0;
  PetscCall(PetscTime(&t0));
  PetscCall(TSSolve(ts, X));
  PetscCall(PetscTime(&t1));
  *calls   = c->calls;
  *percall = (t1 - t0) / (PetscReal)c->calls;
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

/* Time per split call and per level evaluation of TSVSHMM, micro step 1e-4, savings 10,10, one
   macro step of `cycles` micro cycles (about), stability check off */
static PetscErrorCode TimeVSHMM(PetscInt n, PetscInt cycles, TSVSHMMKernelType kernel, Ctx *c, PetscReal *persplit, PetscReal *perlevel, PetscInt64 *splitcalls)
{
  TS                ts;
  Vec               X;
  PetscLogDouble    t0, t1;
  const PetscReal   alpha[2] = {10.0, 10.0};
  TSVSHMMStatistics st;
  PetscInt64        levels = 0;
  PetscInt          l;

  PetscFunctionBeginUser;
  PetscCall(MakeTS(n, c, TSVSHMM, &ts, &X));
  PetscCall(TSVSHMMSetMicroStep(ts, 1e-4));
  PetscCall(TSVSHMMSetSavingsFactors(ts, 2, alpha));
  PetscCall(TSVSHMMSetKernel(ts, kernel));
  PetscCall(TSVSHMMSetStabilityCheck(ts, PETSC_FALSE, 0));
  PetscCall(TSVSHMMSetSeparationCheck(ts, TSVSHMM_SEPARATION_OFF));
  /* one micro cycle spends dt + h_2 + h_1, about 1e-4 (1 + 10 + 10) = 2.1e-3: one macro step of `cycles` cycles */
  PetscCall(TSSetTimeStep(ts, 2.1e-3 * cycles));
  PetscCall(TSSetMaxTime(ts, 2.1e-3 * cycles));
  PetscCall(TSSetUp(ts));
  c->calls = 0;
  PetscCall(PetscTime(&t0));
  PetscCall(TSSolve(ts, X));
  PetscCall(PetscTime(&t1));
  PetscCall(TSVSHMMGetStatistics(ts, &st));
  for (l = 0; l < st.nscales; l++) levels += st.level_evaluations[l];
  *splitcalls = c->calls;
  *persplit   = (t1 - t0) / (PetscReal)c->calls;
  *perlevel   = (t1 - t0) / (PetscReal)levels;
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

/* Set-up cost: wall time of TSSetUp() plus the first macro step, minus one later macro step */
static PetscErrorCode TimeSetUp(PetscInt n, PetscBool check, Ctx *c, PetscReal *setup, PetscInt64 *evals)
{
  TS                ts;
  Vec               X;
  PetscLogDouble    t0, t1, t2;
  const PetscReal   alpha[2] = {10.0, 10.0};
  TSVSHMMStatistics st;

  PetscFunctionBeginUser;
  PetscCall(MakeTS(n, c, TSVSHMM, &ts, &X));
  PetscCall(TSVSHMMSetMicroStep(ts, 1e-4));
  PetscCall(TSVSHMMSetSavingsFactors(ts, 2, alpha));
  PetscCall(TSVSHMMSetStabilityCheck(ts, check, 0));
  PetscCall(TSVSHMMSetSeparationCheck(ts, TSVSHMM_SEPARATION_OFF));
  PetscCall(TSSetTimeStep(ts, 2.1e-3 * 10));
  PetscCall(TSSetMaxTime(ts, 2.1e-3 * 20));
  PetscCall(PetscTime(&t0));
  PetscCall(TSSetUp(ts));
  PetscCall(TSStep(ts));
  PetscCall(PetscTime(&t1));
  PetscCall(TSStep(ts));
  PetscCall(PetscTime(&t2));
  PetscCall(TSVSHMMGetStatistics(ts, &st));
  *setup = (t1 - t0) - (t2 - t1);
  *evals = st.stability_evaluations;
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Ctx        c = {{1.0, 100.0, 1e4}, 0};
  PetscInt   n = 4, cycles = 2000, repeat = 3, r;
  PetscReal  rk = PETSC_MAX_REAL, cs = PETSC_MAX_REAL, cl = PETSC_MAX_REAL, es = PETSC_MAX_REAL, el = PETSC_MAX_REAL, son = PETSC_MAX_REAL, soff = PETSC_MAX_REAL, a, b;
  PetscInt64 nrk = 0, ncos = 0, nexp = 0, stabevals = 0, dummy;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Overhead benchmark options", NULL);
  PetscCall(PetscOptionsInt("-n", "unknowns", NULL, n, &n, NULL));
  PetscCall(PetscOptionsInt("-cycles", "RK steps and VSHMM micro cycles", NULL, cycles, &cycles, NULL));
  PetscCall(PetscOptionsInt("-repeat", "repetitions (best of)", NULL, repeat, &repeat, NULL));
  PetscOptionsEnd();
  PetscCheck(n > 0 && cycles > 0 && repeat > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-n, -cycles and -repeat must be positive");
  /* back to back, best of repeat: rk, vshmm cosine, vshmm exponential, set-up with and without the check */
  for (r = 0; r < repeat; r++) {
    PetscCall(TimeRK(n, cycles, &c, &a, &nrk));
    rk = PetscMin(rk, a);
    PetscCall(TimeVSHMM(n, cycles, TSVSHMM_KERNEL_COSINE, &c, &a, &b, &ncos));
    cs = PetscMin(cs, a);
    cl = PetscMin(cl, b);
    PetscCall(TimeVSHMM(n, cycles, TSVSHMM_KERNEL_EXPONENTIAL, &c, &a, &b, &nexp));
    es = PetscMin(es, a);
    el = PetscMin(el, b);
    PetscCall(TimeSetUp(n, PETSC_TRUE, &c, &a, &stabevals));
    son = PetscMin(son, a);
    PetscCall(TimeSetUp(n, PETSC_FALSE, &c, &a, &dummy));
    soff = PetscMin(soff, a);
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "n %" PetscInt_FMT "\n", n));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "rk4_per_rhs_call %.4e calls %lld\n", (double)rk, (long long)nrk));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "vshmm_cosine_per_split_call %.4e per_level_evaluation %.4e calls %lld\n", (double)cs, (double)cl, (long long)ncos));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "vshmm_exponential_per_split_call %.4e per_level_evaluation %.4e calls %lld\n", (double)es, (double)el, (long long)nexp));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "setup_with_stability_check %.4e stability_evaluations %lld\n", (double)son, (long long)stabevals));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "setup_without_stability_check %.4e\n", (double)soff));
  PetscCall(PetscFinalize());
  return 0;
}
