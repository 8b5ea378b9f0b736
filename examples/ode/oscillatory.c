static const char help[] = "Resonant oscillators of Lee & Engquist (section \"Oscillatory case\"), solved with TSVSHMM or any PETSc TS.\n\
\n\
    dx1/dt = -y1/eps^2 + y2^2/eps - 3 x1 x2^2\n\
    dx2/dt = -(1/eps^2 + 1/eps) y2 - x2\n\
    dy1/dt = x1/eps^2 + y1/2\n\
    dy2/dt = (1/eps^2 + 1/eps) x2 - y2 + 2 x1^2 y2\n\
\n\
The state is the parallel Vec (x1, x2, y1, y2) of size 4; run it on 1 or more MPI ranks.\n\
Every component has a term of every scale, so the three splits are additive (each split's IS\n\
holds all locally owned components and its function returns its term for each of them):\n\
    fast   (scale 2): (-y1, -y2, x1, x2)/eps^2\n\
    medium (scale 1): (y2^2, -y2, 0, x2)/eps\n\
    slow   (scale 0): (-3 x1 x2^2, -x2, y1/2, -y2 + 2 x1^2 y2)\n\
The slow variables are I1 = x1^2 + y1^2 and I2 = x2^2 + y2^2.\n\
For TSMPRK, which partitions the components, use -split_kind component: no component is free\n\
of the fastest scale, so the splits slow and medium are empty and fast holds every component.\n\
\n\
Options:\n\
  -eps <1e-3>                    : the scale separation parameter\n\
  -x0 <1,0.5,0,0.5>              : initial state x1,x2,y1,y2 (the paper gives none)\n\
  -split_kind <additive>         : additive (one term of the field per scale; for TSVSHMM) or\n\
                                   component (TSMPRK's partition: every component is fast)\n\
  -print_interval <0.8>          : print I1, I2 at the steps nearest to the multiples of this time\n\
  -print_every_step              : print I1, I2 after every step instead\n\
  -slow_csv <file>               : write t,I1,I2 after every step (every sampled time) as CSV\n\
  -slow_csv_stride <1>           : write only every n-th step (and the last) to the CSV file\n\
  -no_timing                     : do not print the wall_time line (for output comparisons)\n\
\n\
The default time stepper is TSRK 4 with time step 0.8 (the paper's VSHMM sampling interval)\n\
and final time 8. Typical runs:\n\
  DNS (within 1e-4 of the converged I1, I2 at t = 0.8):  -ts_type rk -ts_rk_type 4 -ts_dt 2.5e-8 -ts_max_time 0.8\n\
  VSHMM (the paper's):  -ts_type vshmm -ts_dt 0.8 -ts_vshmm_micro_dt 1e-7 -ts_vshmm_savings_factors 68200,330\n\
  TSMPRK (single rate here):  -ts_type mprk -split_kind component -ts_dt 1e-8\n\n";

#include <petscvshmm.h>

typedef enum {
  SPLIT_ADDITIVE,
  SPLIT_COMPONENT
} SplitKind;
static const char *const SplitKinds[] = {"additive", "component"};

typedef struct {
  PetscReal   eps;
  SplitKind   split_kind;
  VecScatter  gather; /* full state to every rank */
  Vec         Useq;   /* the gathered copy of the state */
  PetscInt64  nrhs;   /* calls of the full right-hand side */
  PetscInt64  nsplit; /* calls of the split right-hand sides */
  PetscReal   print_interval, next_print;
  PetscBool   print_every_step;
  FILE       *csv;
  PetscInt    csv_stride, csv_last_step;
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

/* Component i (0..3 = x1, x2, y1, y2) of the term of scale k (with its 1/eps_k factor) at x. */
static PetscReal ScaleTerm(PetscInt k, PetscInt i, const PetscScalar *x, PetscReal eps)
{
  const PetscReal x1 = PetscRealPart(x[0]), x2 = PetscRealPart(x[1]), y1 = PetscRealPart(x[2]), y2 = PetscRealPart(x[3]);

  switch (k) {
  case 0: /* slow: f_0 */
    switch (i) {
    case 0:
      return -3.0 * x1 * x2 * x2;
    case 1:
      return -x2;
    case 2:
      return 0.5 * y1;
    default:
      return -y2 + 2.0 * x1 * x1 * y2;
    }
  case 1: /* medium: f_1/eps */
    switch (i) {
    case 0:
      return y2 * y2 / eps;
    case 1:
      return -y2 / eps;
    case 2:
      return 0.0;
    default:
      return x2 / eps;
    }
  default: /* fast: f_2/eps^2 */
    switch (i) {
    case 0:
      return -y1 / (eps * eps);
    case 1:
      return -y2 / (eps * eps);
    case 2:
      return x1 / (eps * eps);
    default:
      return x2 / (eps * eps);
    }
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
  for (i = lo; i < hi; i++) f[i - lo] = ScaleTerm(0, i, x, user->eps) + ScaleTerm(1, i, x, user->eps) + ScaleTerm(2, i, x, user->eps);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(RestoreState(user, &x));
  PetscFunctionReturn(0);
}

/* The Jacobian of the full field (for implicit or IMEX types, e.g. -ts_type arkimex -ts_arkimex_fully_implicit) */
static PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec U, Mat A, Mat B, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscInt           lo, hi, i, cols[4] = {0, 1, 2, 3};
  PetscScalar        row[4];
  PetscReal          x1, x2, y2, e2, w2;

  PetscFunctionBeginUser;
  PetscCall(GatherState(user, U, &x));
  x1 = PetscRealPart(x[0]);
  x2 = PetscRealPart(x[1]);
  y2 = PetscRealPart(x[3]);
  PetscCall(RestoreState(user, &x));
  e2 = 1.0 / (user->eps * user->eps);
  w2 = e2 + 1.0 / user->eps;
  PetscCall(MatGetOwnershipRange(B, &lo, &hi));
  for (i = lo; i < hi; i++) {
    switch (i) { /* d/d(x1, x2, y1, y2) */
    case 0:
      row[0] = -3.0 * x2 * x2;
      row[1] = -6.0 * x1 * x2;
      row[2] = -e2;
      row[3] = 2.0 * y2 / user->eps;
      break;
    case 1:
      row[0] = 0.0;
      row[1] = -1.0;
      row[2] = 0.0;
      row[3] = -w2;
      break;
    case 2:
      row[0] = e2;
      row[1] = 0.0;
      row[2] = 0.5;
      row[3] = 0.0;
      break;
    default:
      row[0] = 4.0 * x1 * y2;
      row[1] = w2;
      row[2] = 0.0;
      row[3] = -1.0 + 2.0 * x1 * x1;
    }
    PetscCall(MatSetValues(B, 1, &i, 4, cols, row, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

/* The split of scale k; U is the full state.
   additive:  F has the layout of U (the split's IS is every locally owned component) and gets
              the term of scale k in every owned row;
   component: the split's IS is every component for k = 2 (fast) and none for k = 0, 1, and F
              gets the full field in its rows (TSMPRK's form: the field of the split's components). */
static PetscErrorCode SplitFunction(PetscInt k, Vec U, Vec F, AppCtx *user)
{
  const PetscScalar *x;
  PetscScalar       *f;
  PetscInt           lo, hi, i;

  PetscFunctionBeginUser;
  user->nsplit++;
  PetscCall(GatherState(user, U, &x));
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  if (user->split_kind == SPLIT_ADDITIVE) {
    for (i = lo; i < hi; i++) f[i - lo] = ScaleTerm(k, i, x, user->eps);
  } else {
    for (i = lo; i < hi; i++) f[i - lo] = ScaleTerm(0, i, x, user->eps) + ScaleTerm(1, i, x, user->eps) + ScaleTerm(2, i, x, user->eps);
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(RestoreState(user, &x));
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

/* The slow variables I1 = x1^2 + y1^2, I2 = x2^2 + y2^2 of the state U (on every rank). */
static PetscErrorCode SlowVariables(AppCtx *user, Vec U, PetscReal *I1, PetscReal *I2)
{
  const PetscScalar *x;
  PetscReal          x1, x2, y1, y2;

  PetscFunctionBeginUser;
  PetscCall(GatherState(user, U, &x));
  x1 = PetscRealPart(x[0]);
  x2 = PetscRealPart(x[1]);
  y1 = PetscRealPart(x[2]);
  y2 = PetscRealPart(x[3]);
  PetscCall(RestoreState(user, &x));
  *I1 = x1 * x1 + y1 * y1;
  *I2 = x2 * x2 + y2 * y2;
  PetscFunctionReturn(0);
}

/* The observables of -ts_vshmm_adapt: the slow variables I1, I2 (TSVSHMMSetObservables()). */
static PetscErrorCode Observables(TS ts, PetscReal t, Vec U, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(SlowVariables((AppCtx *)ctx, U, &q[0], &q[1]));
  PetscFunctionReturn(0);
}

/* Print I1, I2 at the sampled times that are multiples of print_interval; write the CSV file. */
static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx   *user = (AppCtx *)ctx;
  PetscReal I1, I2, dt, tol;

  PetscFunctionBeginUser;
  PetscCall(SlowVariables(user, U, &I1, &I2));
  /* The step nearest to the next multiple of print_interval: the first one past it less half a
     step. (The computed time of the step meant to land on a multiple can be a little below it;
     a fixed allowance would pick an earlier step of a DNS with a step of 1e-8, and I1 oscillates
     with amplitude ~2 eps at frequency 1/eps^2: one step of 1e-8 early changes it by ~1e-5.) */
  PetscCall(TSGetTimeStep(ts, &dt));
  tol = 0.5 * PetscAbsReal(dt);
  if (user->print_every_step) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT " t %.6f I1 %.8e I2 %.8e\n", step, (double)t, (double)I1, (double)I2));
  } else if (t >= user->next_print - tol) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "t %.4f I1 %.8e I2 %.8e\n", (double)t, (double)I1, (double)I2));
    while (user->next_print <= t + tol) user->next_print += user->print_interval;
  }
  if (user->csv && step % user->csv_stride == 0) {
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user->csv, "%.10g,%.16e,%.16e\n", (double)t, (double)I1, (double)I2));
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
  PetscReal   x0[4] = {1.0, 0.5, 0.0, 0.5}, tfinal, tmax, I1, I2, t0, t1;
  PetscInt    nx0 = 4, lo, hi, k, steps;
  PetscInt64  nevals = 0;
  PetscBool   isvshmm, ismprk, timing = PETSC_TRUE, flg;
  PetscInt    split_kind = SPLIT_ADDITIVE;
  char        csvname[PETSC_MAX_PATH_LEN] = "";
  const char *splitnames[3] = {"slow", "medium", "fast"};
  TSType      type;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.eps            = 1e-3;
  user.print_interval = 0.8;
  user.csv_stride     = 1;
  user.csv_last_step  = -1;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Resonant-oscillator three-scale example options", NULL);
  PetscCall(PetscOptionsReal("-eps", "scale separation parameter", NULL, user.eps, &user.eps, NULL));
  PetscCall(PetscOptionsRealArray("-x0", "initial state x1,x2,y1,y2", NULL, x0, &nx0, &flg));
  PetscCheck(!flg || nx0 == 4, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "-x0 needs 4 values x1,x2,y1,y2, got %" PetscInt_FMT, nx0);
  PetscCall(PetscOptionsEList("-split_kind", "additive (TSVSHMM) or component (TSMPRK) splits", NULL, SplitKinds, 2, SplitKinds[split_kind], &split_kind, NULL));
  PetscCall(PetscOptionsReal("-print_interval", "print I1, I2 at multiples of this time", NULL, user.print_interval, &user.print_interval, NULL));
  PetscCall(PetscOptionsBool("-print_every_step", "print I1, I2 after every step", NULL, user.print_every_step, &user.print_every_step, NULL));
  PetscCall(PetscOptionsString("-slow_csv", "write t,I1,I2 after every step to this CSV file", NULL, csvname, csvname, sizeof(csvname), NULL));
  PetscCall(PetscOptionsInt("-slow_csv_stride", "write every n-th step to the CSV file", NULL, user.csv_stride, &user.csv_stride, NULL));
  flg = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-no_timing", "omit the wall_time line", NULL, flg, &flg, NULL));
  timing = flg ? PETSC_FALSE : PETSC_TRUE;
  PetscOptionsEnd();
  PetscCheck(user.eps > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-eps must be positive");
  PetscCheck(user.print_interval > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-print_interval must be positive");
  PetscCheck(user.csv_stride > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-slow_csv_stride must be positive");
  user.split_kind = (SplitKind)split_kind;

  /* The state (x1, x2, y1, y2), spread over the ranks */
  PetscCall(VecCreate(PETSC_COMM_WORLD, &U));
  PetscCall(VecSetSizes(U, PETSC_DECIDE, 4));
  PetscCall(VecSetFromOptions(U));
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  for (k = lo; k < hi; k++) PetscCall(VecSetValue(U, k, x0[k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(U));
  PetscCall(VecAssemblyEnd(U));
  PetscCall(VecScatterCreateToAll(U, &user.gather, &user.Useq));

  PetscCall(MatCreate(PETSC_COMM_WORLD, &J));
  PetscCall(MatSetSizes(J, hi - lo, hi - lo, 4, 4));
  PetscCall(MatSetFromOptions(J));
  PetscCall(MatSeqAIJSetPreallocation(J, 4, NULL));
  PetscCall(MatMPIAIJSetPreallocation(J, 4, NULL, 4, NULL));
  PetscCall(MatSetUp(J));

  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetProblemType(ts, TS_NONLINEAR));
  PetscCall(TSSetSolution(ts, U));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
  {
    TSRHSFunction splitfns[3] = {RHSSlow, RHSMedium, RHSFast};

    /* One split per scale, slowest first. Additive: the IS is every locally owned component.
       Component: slow and medium own no component, fast owns every one. */
    for (k = 0; k < 3; k++) {
      IS       is;
      PetscInt nloc = (user.split_kind == SPLIT_ADDITIVE || k == 2) ? hi - lo : 0;

      PetscCall(ISCreateStride(PETSC_COMM_WORLD, nloc, lo, 1, &is));
      PetscCall(TSRHSSplitSetIS(ts, splitnames[k], is));
      PetscCall(TSRHSSplitSetRHSFunction(ts, splitnames[k], NULL, splitfns[k], &user));
      PetscCall(ISDestroy(&is));
    }
  }
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &user));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRKSetType(ts, TSRK4));
  PetscCall(TSSetMaxTime(ts, 8.0));
  PetscCall(TSSetTimeStep(ts, 0.8));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSMonitorSet(ts, Monitor, &user, NULL));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSVSHMMSetObservables(ts, 2, Observables, &user)); /* the tolerance of -ts_vshmm_adapt applies to I1, I2 */
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSMPRK, &ismprk));
  PetscCheck(!isvshmm || user.split_kind == SPLIT_ADDITIVE, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "TSVSHMM needs -split_kind additive: every component has a term of every scale");
  PetscCheck(!ismprk || user.split_kind == SPLIT_COMPONENT, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "TSMPRK partitions the components: use -split_kind component (additive splits overlap)");

  user.next_print = 0.0;
  if (csvname[0]) {
    PetscCall(PetscFOpen(PETSC_COMM_WORLD, csvname, "w", &user.csv));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user.csv, "t,I1,I2\n"));
  }

  PetscCall(PetscTime(&t0));
  PetscCall(TSSolve(ts, U));
  PetscCall(PetscTime(&t1));

  PetscCall(TSGetSolveTime(ts, &tfinal));
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(TSGetMaxTime(ts, &tmax));
  /* e.g. TSMPRK in PETSc 3.18 may take one more full step when round-off leaves the time just
     below the final time: the final line below is then not at the final time */
  if (tfinal > tmax * (1.0 + 1e-12)) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: the solve stepped past the final time %g to t = %.10g\n", (double)tmax, (double)tfinal));
  PetscCall(SlowVariables(&user, U, &I1, &I2));
  if (user.csv) {
    if (user.csv_last_step != steps) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, user.csv, "%.10g,%.16e,%.16e\n", (double)tfinal, (double)I1, (double)I2));
    PetscCall(PetscFClose(PETSC_COMM_WORLD, user.csv));
  }

  PetscCall(TSGetType(ts, &type));
  if (isvshmm) {
    TSVSHMMStatistics stats;

    PetscCall(TSVSHMMGetStatistics(ts, &stats));
    for (k = 0; k < stats.nsplits; k++) nevals += stats.rhs_evaluations[k];
    /* Cross-check the library's statistics (the evaluations of the steps) against this program's
       own count of split calls, which may be larger: set-up work such as the library's stability
       check also calls the splits (-ts_view shows how often). */
    if (nevals > user.nsplit) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: statistics count %lld split evaluations, the split functions counted only %lld\n", (long long)nevals, (long long)user.nsplit));
    PetscCall(TSVSHMMGetAdapt(ts, &flg));
    if (flg) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adapt: error_estimate %.3e (sum over the run; 1 = the tolerance) estimation_evaluations %lld rejections %lld\n", (double)stats.error_estimate_total, (long long)stats.adapt_evaluations, (long long)stats.adapt_rejections));
  } else {
    /* full-field evaluations, plus the split calls of types that use the splits (e.g. mprk) */
    nevals = user.nrhs + user.nsplit;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ts_type %s steps %" PetscInt_FMT "\n", type, steps));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "final t %.4f I1 %.10e I2 %.10e\n", (double)tfinal, (double)I1, (double)I2));
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
