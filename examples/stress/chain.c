static const char help[] = "Relaxation chain with 2 to 6 time scales, solved with TSVSHMM or any PETSc TS.\n\
\n\
    dx0/dt = sin(x1) - x0/2                              (scale 0, slow)\n\
    dxk/dt = (x(k-1) - xk)/e_k,   e_k = e^k,   k = 1..K  (scale k)\n\
\n\
Each fast variable relaxes to the one before it, so on the slow manifold x1 = ... = xK = x0 and,\n\
for every number of scales K+1, x0 follows the averaged equation dX/dt = sin(X) - X/2,\n\
X(0) = x0(0) (error O(e)). The stiffness ratio is about 2/e^K: 2e10 for 6 scales and e = 1e-2.\n\
The state is a parallel Vec of size K+1; run it on 1 or more MPI ranks. There is one RHS split\n\
per scale, named s0 (slowest) to sK (fastest), and the full right-hand side (and its Jacobian), so\n\
that every -ts_type works.\n\
\n\
Options:\n\
  -scales <4>                    : number of scales K+1, 2 to 6\n\
  -e <1e-2>                      : scale separation: e_k = e^k\n\
  -x0 <1,0,...,0>                : initial state x0,...,xK (missing values are 0)\n\
  -split_kind <component>        : component (split k returns component k only), additive (split k\n\
                                   returns a full-size vector with its term in row k) or mixed\n\
                                   (additive for even k, component for odd k)\n\
  -mode <full>                   : full (the chain) or averaged (the 1-component averaged equation)\n\
  -print_interval <0.5>          : print x0 at the steps that land on multiples of this time\n\
  -print_every_step              : print x0 after every step instead\n\
  -slow_csv <file>               : write t,x0 after every step (every sampled time) as CSV\n\
  -slow_csv_stride <1>           : write only every n-th step (and the last) to the CSV file\n\
  -no_timing                     : do not print the wall_time line (for output comparisons)\n\
\n\
Besides x0 at the printed times it prints the largest |xk| over all components and all steps\n\
(sampled times), which shows that the whole state stays bounded.\n\
The default time stepper is TSRK with time step 0.1 (the VSHMM sampling interval) and final time 2.\n\
Typical runs (K+1 = 4 scales, e = 1e-2, e_3 = 1e-6):\n\
  DNS:    -ts_type rk -ts_rk_type 4 -ts_dt 1e-6\n\
  VSHMM:  -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-6 -ts_vshmm_savings_factors 5e3,1e4,100\n\
          (dt = e^K, mean h_j = e^(j-1), mean h_1 = e/2: the rules of docs/stress.md)\n\
  Implicit reference: -ts_type arkimex -ts_arkimex_fully_implicit -ts_adapt_type basic -ts_dt 1e-9 -ts_rtol 1e-10 -ts_atol 1e-12\n\
  Averaged equation: -mode averaged -ts_type rk -ts_rk_type 4 -ts_dt 1e-3\n\n";

#include <petscvshmm.h>

#define CHAIN_MAX_SCALES 6

typedef enum {
  SPLIT_COMPONENT,
  SPLIT_ADDITIVE,
  SPLIT_MIXED
} SplitKind;
static const char *const SplitKinds[] = {"component", "additive", "mixed"};

typedef enum {
  MODE_FULL,
  MODE_AVERAGED
} Mode;
static const char *const Modes[] = {"full", "averaged"};

typedef struct {
  PetscInt   nscales;                 /* K+1 */
  PetscReal  e;                       /* e_k = e^k */
  PetscReal  ek[CHAIN_MAX_SCALES];    /* e_k, k >= 1 */
  PetscBool  additive[CHAIN_MAX_SCALES]; /* kind of split k */
  Mode       mode;
  VecScatter gather; /* full state to every rank */
  Vec        Useq;   /* the gathered copy of the state */
  PetscInt64 nrhs;   /* calls of the full right-hand side */
  PetscInt64 nsplit; /* calls of the split right-hand sides */
  PetscReal  print_interval, next_print, maxabs;
  PetscBool  print_every_step;
  FILE      *csv;
  PetscInt   csv_stride, csv_last_step;
} AppCtx;

/* Gather the full state into user->Useq and return a read-only pointer to it (same on every rank). */
static PetscErrorCode GatherState(AppCtx *user, Vec U, const PetscScalar **x)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(user->gather, U, user->Useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(user->gather, U, user->Useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(user->Useq, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreState(AppCtx *user, const PetscScalar **x)
{
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(user->Useq, x));
  PetscFunctionReturn(0);
}

/* The term of scale k (with its 1/e_k factor) at the state x; it has only component k. */
static PetscReal ScaleTerm(const AppCtx *user, PetscInt k, const PetscScalar *x)
{
  if (k == 0) return PetscSinReal(PetscRealPart(x[1])) - 0.5 * PetscRealPart(x[0]);
  return PetscRealPart(x[k - 1] - x[k]) / user->ek[k];
}

/* The full field; each rank writes the entries it owns. */
static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscScalar       *f;
  PetscInt           lo, hi, i;

  PetscFunctionBeginUser;
  user->nrhs++;
  PetscCall(GatherState(user, U, &x));
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  for (i = lo; i < hi; i++) f[i - lo] = ScaleTerm(user, i, x);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(RestoreState(user, &x));
  PetscFunctionReturn(0);
}

/* The averaged equation dX/dt = sin(X) - X/2 (one component) */
static PetscErrorCode RHSFunctionAveraged(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscScalar       *f;
  PetscInt           n;

  PetscFunctionBeginUser;
  user->nrhs++;
  PetscCall(GatherState(user, U, &x));
  PetscCall(VecGetLocalSize(F, &n));
  PetscCall(VecGetArray(F, &f));
  if (n) {
    const PetscReal X = PetscRealPart(x[0]);
    f[0]              = PetscSinReal(X) - 0.5 * X;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(RestoreState(user, &x));
  PetscFunctionReturn(0);
}

/* The Jacobian of the field (for implicit types: -ts_type beuler, arkimex, rosw, bdf, ...) */
static PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec U, Mat A, Mat B, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscInt           lo, hi, i, cols[2];
  PetscScalar        row[2];

  PetscFunctionBeginUser;
  PetscCall(GatherState(user, U, &x));
  PetscCall(MatGetOwnershipRange(B, &lo, &hi));
  for (i = lo; i < hi; i++) {
    if (user->mode == MODE_AVERAGED) {
      cols[0] = 0;
      row[0]  = PetscCosReal(PetscRealPart(x[0])) - 0.5;
      PetscCall(MatSetValues(B, 1, &i, 1, cols, row, INSERT_VALUES));
    } else if (i == 0) { /* d/d(x0, x1) of sin(x1) - x0/2 */
      cols[0] = 0;
      cols[1] = 1;
      row[0]  = -0.5;
      row[1]  = PetscCosReal(PetscRealPart(x[1]));
      PetscCall(MatSetValues(B, 1, &i, 2, cols, row, INSERT_VALUES));
    } else { /* d/d(x(i-1), xi) of (x(i-1) - xi)/e_i */
      cols[0] = i - 1;
      cols[1] = i;
      row[0]  = 1.0 / user->ek[i];
      row[1]  = -1.0 / user->ek[i];
      PetscCall(MatSetValues(B, 1, &i, 2, cols, row, INSERT_VALUES));
    }
  }
  PetscCall(RestoreState(user, &x));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

/*
   The split of scale k. U is the full state. For a component split F holds only component k
   (local size 1 on the rank that owns k, 0 elsewhere); for an additive split F has the layout of
   U and gets k's term in row k and zeros in the other rows.
*/
static PetscErrorCode SplitFunction(PetscInt k, Vec U, Vec F, AppCtx *user)
{
  const PetscScalar *x;
  PetscScalar       *f;
  PetscReal          fk;
  PetscInt           lo, hi, i;

  PetscFunctionBeginUser;
  user->nsplit++;
  PetscCall(GatherState(user, U, &x));
  fk = ScaleTerm(user, k, x);
  PetscCall(RestoreState(user, &x));
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  if (!user->additive[k]) {
    if (hi > lo) f[0] = fk;
  } else {
    for (i = lo; i < hi; i++) f[i - lo] = (i == k) ? fk : 0.0;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

/* One split function per scale (the split's number is in the function, the context is shared) */
#define CHAIN_SPLIT(k) \
  static PetscErrorCode RHSSplit##k(TS ts, PetscReal t, Vec U, Vec F, void *ctx) \
  { \
    PetscFunctionBeginUser; \
    PetscCall(SplitFunction(k, U, F, (AppCtx *)ctx)); \
    PetscFunctionReturn(0); \
  }
CHAIN_SPLIT(0)
CHAIN_SPLIT(1)
CHAIN_SPLIT(2)
CHAIN_SPLIT(3)
CHAIN_SPLIT(4)
CHAIN_SPLIT(5)

/* Print x0 at the sampled times that are multiples of print_interval; track max |x|; write the CSV file. */
static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx   *user = (AppCtx *)ctx;
  PetscReal x0, umax, dt, tol;

  PetscFunctionBeginUser;
  /* round-off allowance for "at a multiple": well below the step, so that a DNS with a tiny step
     does not print the step before the multiple */
  PetscCall(TSGetTimeStep(ts, &dt));
  tol = PetscMin(1e-6 * user->print_interval, 0.25 * PetscAbsReal(dt));
  PetscCall(VecNorm(U, NORM_INFINITY, &umax));
  if (PetscIsInfOrNanReal(umax) || umax > user->maxabs) user->maxabs = umax; /* keeps an Inf or NaN */
  {
    const PetscScalar *x;

    PetscCall(GatherState(user, U, &x));
    x0 = PetscRealPart(x[0]);
    PetscCall(RestoreState(user, &x));
  }
  if (user->print_every_step) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT " t %.6f x0 %.8e\n", step, (double)t, (double)x0));
  } else if (t >= user->next_print - tol) {
    /* the first step at or after the next multiple (less a round-off allowance); printed once */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "t %.4f x0 %.8e\n", (double)t, (double)x0));
    while (user->next_print <= t + tol) user->next_print += user->print_interval;
  }
  if (user->csv && step % user->csv_stride == 0) {
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user->csv, "%.10g,%.16e\n", (double)t, (double)x0));
    user->csv_last_step = step;
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  TS            ts;
  Vec           U;
  Mat           J;
  AppCtx        user;
  PetscReal     x0[CHAIN_MAX_SCALES] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0}, tfinal, xs, t0, t1;
  PetscInt      nx0 = CHAIN_MAX_SCALES, n, lo, hi, k, steps;
  PetscInt64    nevals = 0;
  PetscBool     isvshmm, timing = PETSC_TRUE, flg;
  PetscInt      split_kind = SPLIT_COMPONENT, mode = MODE_FULL;
  char          csvname[PETSC_MAX_PATH_LEN] = "";
  char          splitnames[CHAIN_MAX_SCALES][8];
  TSRHSFunction splitfns[CHAIN_MAX_SCALES] = {RHSSplit0, RHSSplit1, RHSSplit2, RHSSplit3, RHSSplit4, RHSSplit5};
  TSType        type;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.nscales        = 4;
  user.e              = 1e-2;
  user.print_interval = 0.5;
  user.csv_stride     = 1;
  user.csv_last_step  = -1;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Relaxation chain options", NULL);
  PetscCall(PetscOptionsInt("-scales", "number of scales K+1 (2 to 6)", NULL, user.nscales, &user.nscales, NULL));
  PetscCall(PetscOptionsReal("-e", "scale separation: e_k = e^k", NULL, user.e, &user.e, NULL));
  PetscCall(PetscOptionsRealArray("-x0", "initial state x0,...,xK", NULL, x0, &nx0, &flg));
  if (!flg) nx0 = 0;
  PetscCall(PetscOptionsEList("-split_kind", "how the scales are split", NULL, SplitKinds, 3, SplitKinds[split_kind], &split_kind, NULL));
  PetscCall(PetscOptionsEList("-mode", "full chain or averaged equation", NULL, Modes, 2, Modes[mode], &mode, NULL));
  PetscCall(PetscOptionsReal("-print_interval", "print x0 at multiples of this time", NULL, user.print_interval, &user.print_interval, NULL));
  PetscCall(PetscOptionsBool("-print_every_step", "print x0 after every step", NULL, user.print_every_step, &user.print_every_step, NULL));
  PetscCall(PetscOptionsString("-slow_csv", "write t,x0 after every step to this CSV file", NULL, csvname, csvname, sizeof(csvname), NULL));
  PetscCall(PetscOptionsInt("-slow_csv_stride", "write every n-th step to the CSV file", NULL, user.csv_stride, &user.csv_stride, NULL));
  flg = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-no_timing", "omit the wall_time line", NULL, flg, &flg, NULL));
  timing = flg ? PETSC_FALSE : PETSC_TRUE;
  PetscOptionsEnd();
  PetscCheck(user.nscales >= 2 && user.nscales <= CHAIN_MAX_SCALES, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-scales must be 2 to %d, got %" PetscInt_FMT, CHAIN_MAX_SCALES, user.nscales);
  PetscCheck(user.e > 0 && user.e < 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-e must be in (0, 1), got %g", (double)user.e);
  PetscCheck(nx0 <= user.nscales, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "-x0 has %" PetscInt_FMT " values but the chain has %" PetscInt_FMT " components", nx0, user.nscales);
  PetscCheck(user.print_interval > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-print_interval must be positive");
  PetscCheck(user.csv_stride > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-slow_csv_stride must be positive");
  user.mode = (Mode)mode;
  user.ek[0] = 1.0;
  for (k = 1; k < user.nscales; k++) user.ek[k] = user.ek[k - 1] * user.e;
  for (k = 0; k < user.nscales; k++) user.additive[k] = (split_kind == SPLIT_ADDITIVE || (split_kind == SPLIT_MIXED && k % 2 == 0)) ? PETSC_TRUE : PETSC_FALSE;

  /* The state x0..xK, or X alone for the averaged equation, spread over the ranks */
  n = user.mode == MODE_FULL ? user.nscales : 1;
  PetscCall(VecCreate(PETSC_COMM_WORLD, &U));
  PetscCall(VecSetSizes(U, PETSC_DECIDE, n));
  PetscCall(VecSetFromOptions(U));
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  for (k = lo; k < hi; k++) PetscCall(VecSetValue(U, k, x0[k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(U));
  PetscCall(VecAssemblyEnd(U));
  PetscCall(VecScatterCreateToAll(U, &user.gather, &user.Useq));

  PetscCall(MatCreate(PETSC_COMM_WORLD, &J));
  PetscCall(MatSetSizes(J, hi - lo, hi - lo, n, n));
  PetscCall(MatSetFromOptions(J));
  PetscCall(MatSeqAIJSetPreallocation(J, 2, NULL));
  PetscCall(MatMPIAIJSetPreallocation(J, 2, NULL, 1, NULL));
  PetscCall(MatSetUp(J));

  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetProblemType(ts, TS_NONLINEAR));
  PetscCall(TSSetSolution(ts, U));
  if (user.mode == MODE_FULL) {
    PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
    /* One split per scale, slowest first. The split output vectors are created by PETSc with the IS layout. */
    for (k = 0; k < user.nscales; k++) {
      IS is;

      PetscCall(PetscSNPrintf(splitnames[k], sizeof(splitnames[k]), "s%" PetscInt_FMT, k));
      if (!user.additive[k]) {
        PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, (k >= lo && k < hi) ? 1 : 0, &k, PETSC_COPY_VALUES, &is));
      } else {
        PetscCall(ISCreateStride(PETSC_COMM_WORLD, hi - lo, lo, 1, &is));
      }
      PetscCall(TSRHSSplitSetIS(ts, splitnames[k], is));
      PetscCall(TSRHSSplitSetRHSFunction(ts, splitnames[k], NULL, splitfns[k], &user));
      PetscCall(ISDestroy(&is));
    }
  } else {
    PetscCall(TSSetRHSFunction(ts, NULL, RHSFunctionAveraged, &user));
  }
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &user));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSSetMaxTime(ts, 2.0));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSMonitorSet(ts, Monitor, &user, NULL));
  PetscCall(TSSetFromOptions(ts));

  user.next_print = 0.0;
  if (csvname[0]) {
    PetscCall(PetscFOpen(PETSC_COMM_WORLD, csvname, "w", &user.csv));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user.csv, "t,x0\n"));
  }

  PetscCall(PetscTime(&t0));
  PetscCall(TSSolve(ts, U));
  PetscCall(PetscTime(&t1));

  PetscCall(TSGetSolveTime(ts, &tfinal));
  PetscCall(TSGetStepNumber(ts, &steps));
  {
    const PetscScalar *x;

    PetscCall(GatherState(&user, U, &x));
    xs = PetscRealPart(x[0]);
    PetscCall(RestoreState(&user, &x));
  }
  if (user.csv) {
    if (user.csv_last_step != steps) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user.csv, "%.10g,%.16e\n", (double)tfinal, (double)xs));
    PetscCall(PetscFClose(PETSC_COMM_WORLD, user.csv));
  }

  PetscCall(TSGetType(ts, &type));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  if (isvshmm) {
    TSVSHMMStatistics stats;

    PetscCall(TSVSHMMGetStatistics(ts, &stats));
    for (k = 0; k < stats.nsplits; k++) nevals += stats.rhs_evaluations[k];
    /* cross-check the library's statistics against this program's own count of split calls
       (which also sees the calls of the library's stability check) */
    if (nevals + stats.stability_evaluations != user.nsplit) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: statistics count %lld split evaluations, the split functions counted %lld\n", (long long)nevals, (long long)user.nsplit));
  } else {
    /* full-field evaluations, plus the split calls of types that use the splits (e.g. mprk) */
    nevals = user.nrhs + user.nsplit;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ts_type %s steps %" PetscInt_FMT "\n", type, steps));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "final t %.4f x0 %.10e\n", (double)tfinal, (double)xs));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "max_abs_state %.6e\n", (double)user.maxabs));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "rhs_evaluations %lld\n", (long long)nevals));
  if (timing) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "wall_time %.6e\n", (double)(t1 - t0)));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecScatterDestroy(&user.gather));
  PetscCall(VecDestroy(&user.Useq));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFinalize());
  return 0;
}
