/*
   ode_example.h - the code shared by the ODE examples examples/ode/dissipative.c, oscillatory.c
   and examples/stress/chain.c (as examples/spectral/spectral_example.h is for the spectral ones):

   - the whole (small) state on every rank for the right-hand sides, monitors and Jacobians:
     on one rank the Vec's own array, on several a copy gathered by a scatter;
   - the options they share (-x0 checked for its count and finiteness, -print_interval,
     -print_every_step, -slow_csv, -slow_csv_stride, -no_timing) and the output of the slow
     variables at the sampled times (printed lines and the CSV file);
   - the timed solve, and the report: TS type, steps, final slow variables, right-hand-side
     evaluations (for TSVSHMM from its statistics, cross-checked against the program's own count
     of split calls) and wall time.

   Include it once per program, after petscvshmm.h; every function is static.
*/
#include <petscvshmm.h>

#define ODE_EXAMPLE_MAX_SLOW 4 /* slow variables printed per line */

typedef struct {
  /* the whole state on every rank */
  VecScatter gather; /* several ranks: the state to every rank; one rank: NULL */
  Vec        Useq;   /* its gathered copy */
  /* work counted by the program's own right-hand sides */
  PetscInt64 nrhs;   /* calls of the full right-hand side */
  PetscInt64 nsplit; /* calls of the split right-hand sides */
  /* the slow variables and their output */
  PetscInt       nslow;
  const char    *slow[ODE_EXAMPLE_MAX_SLOW]; /* their names */
  PetscReal      print_interval, next_print;
  PetscBool      print_every_step, timing;
  char           csvname[PETSC_MAX_PATH_LEN];
  FILE          *csv;
  PetscInt       csv_stride, csv_last_step;
  PetscLogDouble wall;
} OdeExample;

/* Defines the RHS split function `name` of scale k as a call SplitFunction(k, U, F, (AppCtx *)ctx)
   of the program's SplitFunction() and AppCtx. */
#define ODE_EXAMPLE_SPLIT(name, k) \
  static PetscErrorCode name(TS ts, PetscReal t, Vec U, Vec F, void *ctx) \
  { \
    PetscFunctionBeginUser; \
    PetscCall(SplitFunction(k, U, F, (AppCtx *)ctx)); \
    PetscFunctionReturn(0); \
  }

/* Defaults; `slow` names the nslow slow variables (printed and written in this order). */
static PetscErrorCode OdeExampleInitialize(OdeExample *ex, PetscInt nslow, const char *const slow[], PetscReal print_interval)
{
  PetscFunctionBeginUser;
  PetscCheck(nslow >= 1 && nslow <= ODE_EXAMPLE_MAX_SLOW, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "at most %d slow variables", ODE_EXAMPLE_MAX_SLOW);
  PetscCall(PetscMemzero(ex, sizeof(*ex)));
  ex->nslow = nslow;
  for (PetscInt i = 0; i < nslow; i++) ex->slow[i] = slow[i];
  ex->print_interval = print_interval;
  ex->csv_stride     = 1;
  ex->csv_last_step  = -1;
  ex->timing         = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* A positive and finite real option (Inf and NaN are refused: PETSc's reader accepts them). */
static PetscErrorCode OdeExampleCheckPositive(const char *option, PetscReal value)
{
  PetscFunctionBeginUser;
  PetscCheck(value > 0 && !PetscIsInfOrNanReal(value), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "%s must be positive and finite, got %g", option, (double)value);
  PetscFunctionReturn(0);
}

/* -x0 inside PetscOptionsBegin/End: between nmin and nmax finite values (`names` lists them)
   replace the first entries of x0[nmax]; more than nmax values are an error, not dropped. */
static PetscErrorCode OdeExampleOptionsInitialState(PetscOptionItems *PetscOptionsObject, const char *names, PetscInt nmin, PetscInt nmax, PetscReal x0[])
{
  PetscReal *v;
  PetscInt   n = nmax + 1; /* room for one value too many, to see it */
  PetscBool  set;
  char       text[256];

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(n, &v));
  for (PetscInt i = 0; i < nmax; i++) v[i] = x0[i]; /* shown by -help */
  PetscCall(PetscSNPrintf(text, sizeof(text), "initial state %s", names));
  PetscCall(PetscOptionsRealArray("-x0", text, NULL, v, &n, &set));
  if (set) {
    if (nmin == nmax) PetscCheck(n == nmax, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "-x0 takes %" PetscInt_FMT " values %s, got %s%" PetscInt_FMT, nmax, names, n > nmax ? "more than " : "", n > nmax ? nmax : n);
    else PetscCheck(n >= nmin && n <= nmax, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "-x0 takes %" PetscInt_FMT " to %" PetscInt_FMT " values %s, got %s%" PetscInt_FMT, nmin, nmax, names, n > nmax ? "more than " : "", n > nmax ? nmax : n);
    for (PetscInt i = 0; i < n; i++) {
      PetscCheck(!PetscIsInfOrNanReal(v[i]), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-x0 value %" PetscInt_FMT " is %g: the initial state must be finite", i + 1, (double)v[i]);
      x0[i] = v[i];
    }
  }
  PetscCall(PetscFree(v));
  PetscFunctionReturn(0);
}

/* The output options, inside PetscOptionsBegin/End. */
static PetscErrorCode OdeExampleOptionsOutput(PetscOptionItems *PetscOptionsObject, OdeExample *ex)
{
  char      names[128] = "", text[256];
  PetscBool no_timing  = PETSC_FALSE;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ex->nslow; i++) {
    PetscCall(PetscStrlcat(names, i ? "," : "", sizeof(names)));
    PetscCall(PetscStrlcat(names, ex->slow[i], sizeof(names)));
  }
  PetscCall(PetscSNPrintf(text, sizeof(text), "print %s at multiples of this time", names));
  PetscCall(PetscOptionsReal("-print_interval", text, NULL, ex->print_interval, &ex->print_interval, NULL));
  PetscCall(PetscSNPrintf(text, sizeof(text), "print %s after every step", names));
  PetscCall(PetscOptionsBool("-print_every_step", text, NULL, ex->print_every_step, &ex->print_every_step, NULL));
  PetscCall(PetscSNPrintf(text, sizeof(text), "write t,%s after every step to this CSV file", names));
  PetscCall(PetscOptionsString("-slow_csv", text, NULL, ex->csvname, ex->csvname, sizeof(ex->csvname), NULL));
  PetscCall(PetscOptionsInt("-slow_csv_stride", "write every n-th step to the CSV file", NULL, ex->csv_stride, &ex->csv_stride, NULL));
  PetscCall(PetscOptionsBool("-no_timing", "omit the wall_time line", NULL, no_timing, &no_timing, NULL));
  ex->timing = no_timing ? PETSC_FALSE : PETSC_TRUE;
  PetscCall(OdeExampleCheckPositive("-print_interval", ex->print_interval));
  PetscCheck(ex->csv_stride > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-slow_csv_stride must be positive");
  PetscFunctionReturn(0);
}

/* The state U (size n, spread over the ranks) with the values x0[0..n-1]. */
static PetscErrorCode OdeExampleCreateState(OdeExample *ex, PetscInt n, const PetscReal x0[], Vec *U)
{
  PetscInt    lo, hi;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(VecCreate(PETSC_COMM_WORLD, U));
  PetscCall(VecSetSizes(*U, PETSC_DECIDE, n));
  PetscCall(VecSetFromOptions(*U));
  PetscCall(VecGetOwnershipRange(*U, &lo, &hi));
  for (PetscInt k = lo; k < hi; k++) PetscCall(VecSetValue(*U, k, x0[k], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(*U));
  PetscCall(VecAssemblyEnd(*U));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  if (size > 1) PetscCall(VecScatterCreateToAll(*U, &ex->gather, &ex->Useq));
  PetscFunctionReturn(0);
}

/* A read-only pointer to the whole state U (the same on every rank): on one rank U's own array,
   on several ranks the gathered copy. Restore it with OdeExampleRestoreState(). */
static PetscErrorCode OdeExampleGetState(OdeExample *ex, Vec U, const PetscScalar **x)
{
  PetscFunctionBeginUser;
  if (!ex->gather) {
    PetscCall(VecGetArrayRead(U, x));
    PetscFunctionReturn(0);
  }
  PetscCall(VecScatterBegin(ex->gather, U, ex->Useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(ex->gather, U, ex->Useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(ex->Useq, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode OdeExampleRestoreState(OdeExample *ex, Vec U, const PetscScalar **x)
{
  PetscFunctionBeginUser;
  PetscCall(VecRestoreArrayRead(ex->gather ? ex->Useq : U, x));
  PetscFunctionReturn(0);
}

/* A component of a field at the whole state x: component i of the full field, or the term of
   scale i (which has only component i), with the program's context. */
typedef PetscReal (*OdeExampleComponent)(PetscInt i, const PetscScalar *x, void *ctx);

/* F = the field whose owned rows i are component(i, x) at the whole state x of U. */
static PetscErrorCode OdeExampleEvaluate(OdeExample *ex, Vec U, Vec F, OdeExampleComponent component, void *ctx)
{
  const PetscScalar *x;
  PetscScalar       *f;
  PetscInt           lo, hi;

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetState(ex, U, &x));
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  for (PetscInt i = lo; i < hi; i++) f[i - lo] = component(i, x, ctx);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(OdeExampleRestoreState(ex, U, &x));
  PetscFunctionReturn(0);
}

/* The split of scale k whose term term(k, x) has only component k. A component split's F holds
   only component k (local size 1 on the rank that owns k, 0 elsewhere); an additive split's F
   has the layout of U and gets the term in row k and zeros in the other rows. */
static PetscErrorCode OdeExampleEvaluateSplit(OdeExample *ex, PetscInt k, PetscBool additive, Vec U, Vec F, OdeExampleComponent term, void *ctx)
{
  const PetscScalar *x;
  PetscScalar       *f;
  PetscReal          fk;
  PetscInt           lo, hi;

  PetscFunctionBeginUser;
  ex->nsplit++;
  PetscCall(OdeExampleGetState(ex, U, &x));
  fk = term(k, x, ctx);
  PetscCall(OdeExampleRestoreState(ex, U, &x));
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  if (!additive) {
    if (hi > lo) f[0] = fk;
  } else {
    for (PetscInt i = lo; i < hi; i++) f[i - lo] = (i == k) ? fk : 0.0;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

/* The IS of a split: component k alone, every locally owned component, or none. */
typedef enum {
  ODE_SPLIT_COMPONENT,
  ODE_SPLIT_ALL,
  ODE_SPLIT_NONE
} OdeExampleSplitIS;

/* Declares the RHS split `name` of the TS (whose solution is set) with its IS and function. */
static PetscErrorCode OdeExampleSetSplit(TS ts, const char *name, OdeExampleSplitIS which, PetscInt k, TSRHSFunction f, void *ctx)
{
  Vec      U;
  IS       is;
  PetscInt lo, hi;

  PetscFunctionBeginUser;
  PetscCall(TSGetSolution(ts, &U));
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  if (which == ODE_SPLIT_COMPONENT) PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, (k >= lo && k < hi) ? 1 : 0, &k, PETSC_COPY_VALUES, &is));
  else PetscCall(ISCreateStride(PETSC_COMM_WORLD, which == ODE_SPLIT_ALL ? hi - lo : 0, lo, 1, &is));
  PetscCall(TSRHSSplitSetIS(ts, name, is));
  PetscCall(TSRHSSplitSetRHSFunction(ts, name, NULL, f, ctx));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* A TS of type TSRK for the state U with the Jacobian matrix J (AIJ, n x n with U's rows, nz
   nonzeros per row), the final time, the time step (the sampling interval for TSVSHMM), the final
   time matched exactly, and the monitor; the caller adds the right-hand side, the splits and the
   Jacobian function, then calls TSSetFromOptions(). */
static PetscErrorCode OdeExampleCreateTS(Vec U, PetscInt nz, PetscReal tfinal, PetscReal dt, PetscErrorCode (*monitor)(TS, PetscInt, PetscReal, Vec, void *), void *ctx, TS *ts, Mat *J)
{
  PetscInt n, nlocal;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(U, &n));
  PetscCall(VecGetLocalSize(U, &nlocal));
  PetscCall(MatCreate(PETSC_COMM_WORLD, J));
  PetscCall(MatSetSizes(*J, nlocal, nlocal, n, n));
  PetscCall(MatSetFromOptions(*J));
  PetscCall(MatSeqAIJSetPreallocation(*J, nz, NULL));
  PetscCall(MatMPIAIJSetPreallocation(*J, nz, NULL, nz, NULL));
  PetscCall(MatSetUp(*J));

  PetscCall(TSCreate(PETSC_COMM_WORLD, ts));
  PetscCall(TSSetProblemType(*ts, TS_NONLINEAR));
  PetscCall(TSSetSolution(*ts, U));
  PetscCall(TSSetType(*ts, TSRK));
  PetscCall(TSSetMaxTime(*ts, tfinal));
  PetscCall(TSSetTimeStep(*ts, dt));
  PetscCall(TSSetMaxSteps(*ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(*ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSMonitorSet(*ts, monitor, ctx, NULL));
  PetscFunctionReturn(0);
}

/* Component i of the state U, on every rank. */
static PetscErrorCode OdeExampleGetComponent(OdeExample *ex, Vec U, PetscInt i, PetscReal *v)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetState(ex, U, &x));
  *v = PetscRealPart(x[i]);
  PetscCall(OdeExampleRestoreState(ex, U, &x));
  PetscFunctionReturn(0);
}

/* The observable of -ts_vshmm_adapt of the examples whose slow variable is component 0 (the
   tolerance then applies to it; TSVSHMMSetObservables()); ctx is the OdeExample. */
static PetscErrorCode OdeExampleFirstComponent(TS ts, PetscReal t, Vec U, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetComponent((OdeExample *)ctx, U, 0, &q[0]));
  PetscFunctionReturn(0);
}

/* -observe_state: -ts_vshmm_adapt controls the whole state (PETSc's weighted norm) instead of
   component 0. Registers the observable unless it is given. Call after TSSetFromOptions() (the
   setter acts on a TS of type TSVSHMM only). */
static PetscErrorCode OdeExampleSetObservable(OdeExample *ex, TS ts)
{
  PetscBool state = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-observe_state", &state, NULL));
  if (!state) PetscCall(TSVSHMMSetObservables(ts, 1, OdeExampleFirstComponent, ex));
  PetscFunctionReturn(0);
}

/* Assembles the Jacobian matrices after MatSetValues() on B. */
static PetscErrorCode OdeExampleAssembleJacobian(Mat A, Mat B)
{
  PetscFunctionBeginUser;
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

/* The slow variables in a line: " name %<fmt> ..." (fmt "%.8e" or "%.10e") or CSV ",%.16e...". */
static PetscErrorCode OdeExampleFormatSlow(OdeExample *ex, const PetscReal v[], PetscBool csv, PetscInt digits, char line[], size_t len)
{
  char item[128];

  PetscFunctionBeginUser;
  line[0] = 0;
  for (PetscInt i = 0; i < ex->nslow; i++) {
    if (csv) PetscCall(PetscSNPrintf(item, sizeof(item), ",%.16e", (double)v[i]));
    else PetscCall(PetscSNPrintf(item, sizeof(item), " %s %.*e", ex->slow[i], (int)digits, (double)v[i]));
    PetscCall(PetscStrlcat(line, item, len));
  }
  PetscFunctionReturn(0);
}

/* For a TSMonitor: prints the slow variables v at every step (-print_every_step) or at the first
   step at or after each multiple of -print_interval (less the allowance tol: a multiple the step
   meant to land on may be computed a little below it; printed once), and writes them to the CSV
   file every -slow_csv_stride steps. */
static PetscErrorCode OdeExampleMonitorSlow(OdeExample *ex, PetscInt step, PetscReal t, PetscReal tol, const PetscReal v[])
{
  char line[512];

  PetscFunctionBeginUser;
  if (ex->print_every_step) {
    PetscCall(OdeExampleFormatSlow(ex, v, PETSC_FALSE, 8, line, sizeof(line)));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT " t %.6f%s\n", step, (double)t, line));
  } else if (t >= ex->next_print - tol) {
    PetscCall(OdeExampleFormatSlow(ex, v, PETSC_FALSE, 8, line, sizeof(line)));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "t %.4f%s\n", (double)t, line));
    while (ex->next_print <= t + tol) ex->next_print += ex->print_interval;
  }
  if (ex->csv && step % ex->csv_stride == 0) {
    PetscCall(OdeExampleFormatSlow(ex, v, PETSC_TRUE, 16, line, sizeof(line)));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ex->csv, "%.10g%s\n", (double)t, line));
    ex->csv_last_step = step;
  }
  PetscFunctionReturn(0);
}

/* Opens the CSV file (if asked for) and runs TSSolve(), timed. */
static PetscErrorCode OdeExampleSolve(OdeExample *ex, TS ts, Vec U)
{
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  ex->next_print = 0.0;
  if (ex->csvname[0]) {
    char header[128] = "t";

    for (PetscInt i = 0; i < ex->nslow; i++) {
      PetscCall(PetscStrlcat(header, ",", sizeof(header)));
      PetscCall(PetscStrlcat(header, ex->slow[i], sizeof(header)));
    }
    PetscCall(PetscFOpen(PETSC_COMM_WORLD, ex->csvname, "w", &ex->csv));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ex->csv, "%s\n", header));
  }
  PetscCall(PetscTime(&t0));
  PetscCall(TSSolve(ts, U));
  PetscCall(PetscTime(&t1));
  ex->wall = t1 - t0;
  PetscFunctionReturn(0);
}

/* After the solve, with the final slow variables v: closes the CSV file (with the final state if
   the last step was not written) and prints the report; `extra` (or NULL) is a line of the
   program's own, printed after the final values. */
static PetscErrorCode OdeExampleReport(OdeExample *ex, TS ts, const PetscReal v[], const char *extra)
{
  PetscReal  tfinal;
  PetscInt   steps;
  PetscInt64 nevals = 0;
  PetscBool  isvshmm;
  TSType     type;
  char       line[512];

  PetscFunctionBeginUser;
  PetscCall(TSGetSolveTime(ts, &tfinal));
  PetscCall(TSGetStepNumber(ts, &steps));
  if (ex->csv) {
    if (ex->csv_last_step != steps) {
      PetscCall(OdeExampleFormatSlow(ex, v, PETSC_TRUE, 16, line, sizeof(line)));
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, ex->csv, "%.10g%s\n", (double)tfinal, line));
    }
    PetscCall(PetscFClose(PETSC_COMM_WORLD, ex->csv));
    ex->csv = NULL;
  }
  PetscCall(TSGetType(ts, &type));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  if (isvshmm) {
    TSVSHMMStatistics stats;
    PetscBool         adapt;

    PetscCall(TSVSHMMGetStatistics(ts, &stats));
    for (PetscInt k = 0; k < stats.nsplits; k++) nevals += stats.rhs_evaluations[k];
    /* Cross-check the library's statistics against this program's own count of split calls,
       which also sees the calls of the stability and separation checks and of the accuracy
       control (their own counters in the statistics). */
    if (nevals + stats.stability_evaluations + stats.adapt_evaluations != ex->nsplit)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: statistics count %lld split evaluations (%lld for checks, %lld for accuracy control), the split functions counted %lld\n", (long long)nevals, (long long)stats.stability_evaluations,
                            (long long)stats.adapt_evaluations, (long long)ex->nsplit));
    PetscCall(TSVSHMMGetAdapt(ts, &adapt));
    if (adapt) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adapt: error_estimate %.3e (sum over the run; 1 = the tolerance) estimation_evaluations %lld rejections %lld\n", (double)stats.error_estimate_total, (long long)stats.adapt_evaluations, (long long)stats.adapt_rejections));
      if (stats.global_estimate >= 0) /* -ts_vshmm_adapt_global_estimate */
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adapt: global_estimate %.3e (the carried comparison at the last sampled time; largest %.3e)\n", (double)stats.global_estimate, (double)stats.global_estimate_max));
    }
  } else {
    /* full-field evaluations, plus the split calls of types that use the splits (e.g. mprk) */
    nevals = ex->nrhs + ex->nsplit;
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ts_type %s steps %" PetscInt_FMT "\n", type, steps));
  PetscCall(OdeExampleFormatSlow(ex, v, PETSC_FALSE, 10, line, sizeof(line)));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "final t %.4f%s\n", (double)tfinal, line));
  if (extra) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s", extra));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "rhs_evaluations %lld\n", (long long)nevals));
  if (ex->timing) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "wall_time %.6e\n", (double)ex->wall));
  PetscFunctionReturn(0);
}

static PetscErrorCode OdeExampleFinalize(OdeExample *ex)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(&ex->gather));
  PetscCall(VecDestroy(&ex->Useq));
  PetscFunctionReturn(0);
}
