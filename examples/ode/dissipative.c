static const char help[] = "Dissipative three-scale ODE of Lee & Engquist (their eq. exp1), solved with TSVSHMM or any PETSc TS.\n\
\n\
    dxi/dt   = sin(xi+eta+zeta) - (xi+eta+zeta)^2/20     (scale 0, slow)\n\
    deta/dt  = (3 xi^2 - eta^2 + zeta^2)/eps             (scale 1, medium)\n\
    dzeta/dt = (xi - eta - zeta)/eps^2                    (scale 2, fast)\n\
\n\
As eps -> 0, xi follows the averaged equation dXi/dt = sin(2 Xi) - Xi^2/5, Xi(0) = xi(0).\n\
The state is a parallel Vec of size 3; run it on 1 or more MPI ranks.\n\
\n\
Options:\n\
  -eps <1e-2>                    : the scale separation parameter\n\
  -x0 <5,-10,5>                  : initial state xi,eta,zeta\n\
  -split_kind <component>        : component (each split returns its own component) or\n\
                                   additive (each split returns a full-size term)\n\
  -mode <full>                   : full (the 3-component system) or averaged (the 1-component averaged equation)\n\
  -print_interval <0.5>          : print xi at the steps that land on multiples of this time\n\
  -print_every_step              : print xi after every step instead\n\
  -slow_csv <file>               : write t,xi after every step (every sampled time) as CSV\n\
  -slow_csv_stride <1>           : write only every n-th step (and the last) to the CSV file\n\
  -no_timing                     : do not print the wall_time line (for output comparisons)\n\
  -observe_state                 : -ts_vshmm_adapt controls the error of the whole state (in PETSc's\n\
                                   weighted norm) instead of the slow variable xi\n\
\n\
The default time stepper is TSRK with time step 0.1 (the VSHMM sampling interval) and final time 2.\n\
Typical runs:\n\
  DNS:    -ts_type rk -ts_rk_type 4 -ts_dt 1e-6\n\
  VSHMM:  -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10\n\
  Averaged equation: -mode averaged -ts_type rk -ts_rk_type 4 -ts_dt 1e-3\n\
The RHS Jacobian is provided, so implicit types work too (-ts_type beuler, or\n\
-ts_type arkimex -ts_arkimex_fully_implicit); -ts_type mprk needs the component splits.\n\n";

#include <petscvshmm.h>

typedef enum {
  SPLIT_ADDITIVE,
  SPLIT_COMPONENT
} SplitKind;
static const char *const SplitKinds[] = {"additive", "component"};

typedef enum {
  MODE_FULL,
  MODE_AVERAGED
} Mode;
static const char *const Modes[] = {"full", "averaged"};

typedef struct {
  PetscReal  eps;
  SplitKind  split_kind;
  Mode       mode;
  VecScatter gather; /* full state to every rank */
  Vec        Useq;   /* the gathered copy of the state */
  PetscInt64 nrhs;   /* calls of the full right-hand side */
  PetscInt64 nsplit; /* calls of the split right-hand sides */
  PetscReal  print_interval, next_print;
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

/* The term of scale k (with its 1/eps_k factor) at the state x = (xi, eta, zeta) */
static PetscReal ScaleTerm(PetscInt k, const PetscScalar *x, PetscReal eps)
{
  const PetscReal xi = PetscRealPart(x[0]), eta = PetscRealPart(x[1]), zeta = PetscRealPart(x[2]);
  const PetscReal s = xi + eta + zeta;

  switch (k) {
  case 0:
    return PetscSinReal(s) - s * s / 20.0;
  case 1:
    return (3.0 * xi * xi - eta * eta + zeta * zeta) / eps;
  default:
    return (xi - eta - zeta) / (eps * eps);
  }
}

/* The full field f_0 + f_1/eps + f_2/eps^2; each rank writes the entries it owns. */
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
  for (i = lo; i < hi; i++) f[i - lo] = ScaleTerm(i, x, user->eps);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(RestoreState(user, &x));
  PetscFunctionReturn(0);
}

/* The averaged equation dXi/dt = sin(2 Xi) - Xi^2/5 (one component) */
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
    f[0]              = PetscSinReal(2.0 * X) - X * X / 5.0;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(RestoreState(user, &x));
  PetscFunctionReturn(0);
}

/* The Jacobian of the full field (for implicit or IMEX types such as -ts_type arkimex, beuler) */
static PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec U, Mat A, Mat B, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscInt           lo, hi, i, cols[3] = {0, 1, 2};
  PetscScalar        row[3];

  PetscFunctionBeginUser;
  PetscCall(GatherState(user, U, &x));
  PetscCall(MatGetOwnershipRange(B, &lo, &hi));
  if (user->mode == MODE_FULL) {
    const PetscReal xi = PetscRealPart(x[0]), eta = PetscRealPart(x[1]), zeta = PetscRealPart(x[2]);
    const PetscReal s = xi + eta + zeta, eps = user->eps;

    for (i = lo; i < hi; i++) {
      switch (i) {
      case 0:
        row[0] = row[1] = row[2] = PetscCosReal(s) - s / 10.0;
        break;
      case 1:
        row[0] = 6.0 * xi / eps;
        row[1] = -2.0 * eta / eps;
        row[2] = 2.0 * zeta / eps;
        break;
      default:
        row[0] = 1.0 / (eps * eps);
        row[1] = row[2] = -1.0 / (eps * eps);
      }
      PetscCall(MatSetValues(B, 1, &i, 3, cols, row, INSERT_VALUES));
    }
  } else if (hi > lo) {
    const PetscReal X = PetscRealPart(x[0]);

    row[0] = 2.0 * PetscCosReal(2.0 * X) - 2.0 * X / 5.0;
    PetscCall(MatSetValues(B, 1, &lo, 1, cols, row, INSERT_VALUES));
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
   The split of scale k. U is the full state. For component splits F holds only component k
   (local size 1 on the rank that owns k, 0 elsewhere); for additive splits F is full size and
   gets k's term in row k and zeros in the other rows.
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
  fk = ScaleTerm(k, x, user->eps);
  PetscCall(RestoreState(user, &x));
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  if (user->split_kind == SPLIT_COMPONENT) {
    if (hi > lo) f[0] = fk;
  } else {
    for (i = lo; i < hi; i++) f[i - lo] = (i == k) ? fk : 0.0;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

static PetscErrorCode RHSSlow(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(SplitFunction(0, U, F, (AppCtx *)ctx));
  PetscFunctionReturn(0);
}

static PetscErrorCode RHSMedium(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(SplitFunction(1, U, F, (AppCtx *)ctx));
  PetscFunctionReturn(0);
}

static PetscErrorCode RHSFast(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(SplitFunction(2, U, F, (AppCtx *)ctx));
  PetscFunctionReturn(0);
}

/* Print xi at the sampled times that are multiples of print_interval; write the CSV file. */
/* The observable of -ts_vshmm_adapt: the slow variable xi (TSVSHMMSetObservables()). */
static PetscErrorCode Observables(TS ts, PetscReal t, Vec U, PetscReal q[], void *ctx)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((AppCtx *)ctx, U, &x));
  q[0] = PetscRealPart(x[0]);
  PetscCall(RestoreState((AppCtx *)ctx, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscReal          xi;

  PetscFunctionBeginUser;
  PetscCall(GatherState(user, U, &x));
  xi = PetscRealPart(x[0]);
  PetscCall(RestoreState(user, &x));
  if (user->print_every_step) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT " t %.6f xi %.8e\n", step, (double)t, (double)xi));
  } else if (t >= user->next_print - 1e-6 * user->print_interval) {
    /* the first step at or after the next multiple (less a round-off allowance); printed once */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "t %.4f xi %.8e\n", (double)t, (double)xi));
    while (user->next_print <= t + 1e-6 * user->print_interval) user->next_print += user->print_interval;
  }
  if (user->csv && step % user->csv_stride == 0) {
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user->csv, "%.10g,%.16e\n", (double)t, (double)xi));
    user->csv_last_step = step;
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  TS          ts;
  Vec         U;
  Mat         J;
  AppCtx      user;
  PetscReal   x0[3]  = {5.0, -10.0, 5.0}, tfinal, xi, t0, t1;
  PetscInt    nx0    = 3, n, lo, hi, k, steps;
  PetscInt64  nevals = 0;
  PetscBool   isvshmm, timing = PETSC_TRUE, flg, observe_state = PETSC_FALSE;
  PetscInt    split_kind = SPLIT_COMPONENT, mode = MODE_FULL;
  char        csvname[PETSC_MAX_PATH_LEN] = "";
  const char *splitnames[3]               = {"slow", "medium", "fast"};
  TSType      type;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.eps            = 1e-2;
  user.print_interval = 0.5;
  user.csv_stride     = 1;
  user.csv_last_step  = -1;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Dissipative three-scale example options", NULL);
  PetscCall(PetscOptionsReal("-eps", "scale separation parameter", NULL, user.eps, &user.eps, NULL));
  PetscCall(PetscOptionsRealArray("-x0", "initial state xi,eta,zeta", NULL, x0, &nx0, &flg));
  PetscCheck(!flg || nx0 == 3, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "-x0 needs 3 values xi,eta,zeta, got %" PetscInt_FMT, nx0);
  PetscCall(PetscOptionsEList("-split_kind", "how the three scales are split", NULL, SplitKinds, 2, SplitKinds[split_kind], &split_kind, NULL));
  PetscCall(PetscOptionsEList("-mode", "full system or averaged equation", NULL, Modes, 2, Modes[mode], &mode, NULL));
  PetscCall(PetscOptionsReal("-print_interval", "print xi at multiples of this time", NULL, user.print_interval, &user.print_interval, NULL));
  PetscCall(PetscOptionsBool("-print_every_step", "print xi after every step", NULL, user.print_every_step, &user.print_every_step, NULL));
  PetscCall(PetscOptionsString("-slow_csv", "write t,xi after every step to this CSV file", NULL, csvname, csvname, sizeof(csvname), NULL));
  PetscCall(PetscOptionsInt("-slow_csv_stride", "write every n-th step to the CSV file", NULL, user.csv_stride, &user.csv_stride, NULL));
  flg = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-no_timing", "omit the wall_time line", NULL, flg, &flg, NULL));
  timing = flg ? PETSC_FALSE : PETSC_TRUE;
  PetscCall(PetscOptionsBool("-observe_state", "-ts_vshmm_adapt controls the whole state, not xi", NULL, observe_state, &observe_state, NULL));
  PetscOptionsEnd();
  PetscCheck(user.eps > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-eps must be positive");
  PetscCheck(user.print_interval > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-print_interval must be positive");
  PetscCheck(user.csv_stride > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-slow_csv_stride must be positive");
  user.split_kind = (SplitKind)split_kind;
  user.mode       = (Mode)mode;

  /* The state: (xi, eta, zeta), or Xi alone for the averaged equation, spread over the ranks */
  n = user.mode == MODE_FULL ? 3 : 1;
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
  PetscCall(MatSeqAIJSetPreallocation(J, n, NULL));
  PetscCall(MatMPIAIJSetPreallocation(J, n, NULL, n, NULL));
  PetscCall(MatSetUp(J));

  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetProblemType(ts, TS_NONLINEAR));
  PetscCall(TSSetSolution(ts, U));
  if (user.mode == MODE_FULL) {
    TSRHSFunction splitfns[3] = {RHSSlow, RHSMedium, RHSFast};

    PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
    /* One split per scale, slowest first. The split output vectors are created by PETSc with the IS layout. */
    for (k = 0; k < 3; k++) {
      IS is;

      if (user.split_kind == SPLIT_COMPONENT) {
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
  PetscCall(TSSetMaxSteps(ts, 100000000));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSMonitorSet(ts, Monitor, &user, NULL));
  if (user.mode == MODE_FULL && !observe_state) PetscCall(TSVSHMMSetObservables(ts, 1, Observables, &user)); /* the tolerance of -ts_vshmm_adapt applies to xi */
  PetscCall(TSSetFromOptions(ts));

  user.next_print = 0.0;
  if (csvname[0]) {
    PetscCall(PetscFOpen(PETSC_COMM_WORLD, csvname, "w", &user.csv));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user.csv, "t,xi\n"));
  }

  PetscCall(PetscTime(&t0));
  PetscCall(TSSolve(ts, U));
  PetscCall(PetscTime(&t1));

  PetscCall(TSGetSolveTime(ts, &tfinal));
  PetscCall(TSGetStepNumber(ts, &steps));
  {
    const PetscScalar *x;

    PetscCall(GatherState(&user, U, &x));
    xi = PetscRealPart(x[0]);
    PetscCall(RestoreState(&user, &x));
  }
  if (user.csv) {
    if (user.csv_last_step != steps) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user.csv, "%.10g,%.16e\n", (double)tfinal, (double)xi));
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
    if (nevals + stats.stability_evaluations + stats.adapt_evaluations != user.nsplit) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: statistics count %lld split evaluations, the split functions counted %lld\n", (long long)(nevals + stats.stability_evaluations + stats.adapt_evaluations), (long long)user.nsplit));
    PetscCall(TSVSHMMGetAdapt(ts, &flg));
    if (flg) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adapt: error_estimate %.3e (sum over the run; 1 = the tolerance) estimation_evaluations %lld rejections %lld\n", (double)stats.error_estimate_total, (long long)stats.adapt_evaluations, (long long)stats.adapt_rejections));
  } else {
    nevals = user.nrhs;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ts_type %s steps %" PetscInt_FMT "\n", type, steps));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "final t %.4f xi %.10e\n", (double)tfinal, (double)xi));
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
