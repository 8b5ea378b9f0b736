static const char help[] = "Relaxation chain with 2 to 6 time scales, solved with TSVSHMM or any PETSc TS.\n\
\n\
    dx0/dt = sin(x1) - x0/2                              (scale 0, slow)\n\
    dxk/dt = (x(k-1) - xk)/e_k,   e_k = e^k,   k = 1..K  (scale k)\n\
\n\
Each fast variable relaxes to the one before it, so on the slow manifold x1 = ... = xK = x0 and,\n\
for every number of scales K+1, x0 follows the averaged equation dX/dt = sin(X) - X/2,\n\
X(0) = x0(0) (error O(e)). The stiffness ratio is about 2/e^K: 2e10 for 6 scales and e = 1e-2.\n\
The state is a parallel Vec of size K+1; run it on 1 or more MPI ranks (on one rank the right-hand\n\
sides read the Vec's own array, on several each call gathers the state). There is one RHS split\n\
per scale, named s0 (slowest) to sK (fastest), and the full right-hand side (and its Jacobian), so\n\
that every -ts_type works.\n\
\n\
Options:\n\
  -scales <4>                    : number of scales K+1, 2 to 6\n\
  -e <1e-2>                      : scale separation: e_k = e^k\n\
  -x0 <1,0,...,0>                : initial state x0,...,xK (at most K+1 finite values; missing ones are 0)\n\
  -split_kind <component>        : component (split k returns component k only), additive (split k\n\
                                   returns a full-size vector with its term in row k) or mixed\n\
                                   (additive for even k, component for odd k)\n\
  -mode <full>                   : full (the chain) or averaged (the 1-component averaged equation)\n\
  -print_interval <0.5>          : print x0 at the steps that land on multiples of this time\n\
  -print_every_step              : print x0 after every step instead\n\
  -slow_csv <file>               : write t,x0 after every step (every sampled time) as CSV\n\
  -slow_csv_stride <1>           : write only every n-th step (and the last) to the CSV file\n\
  -no_timing                     : do not print the wall_time line (for output comparisons)\n\
  -observe_state                 : -ts_vshmm_adapt controls the error of the whole state (in PETSc's\n\
                                   weighted norm) instead of the slow variable x0\n\
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
#include "../common/ode_example.h"

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
  PetscInt   nscales;                    /* K+1 */
  PetscReal  e;                          /* e_k = e^k */
  PetscReal  ek[CHAIN_MAX_SCALES];       /* e_k, k >= 1 */
  PetscBool  additive[CHAIN_MAX_SCALES]; /* kind of split k */
  Mode       mode;
  PetscReal  maxabs; /* largest |x_k| at the sampled times */
  OdeExample ex;     /* state access, output, work counts (common/ode_example.h) */
} AppCtx;

/* The term of scale k (with its 1/e_k factor) at the state x; it has only component k, so it is
   also component k of the full field. */
static PetscReal ScaleTerm(PetscInt k, const PetscScalar *x, void *ctx)
{
  const AppCtx *user = (const AppCtx *)ctx;

  if (k == 0) return PetscSinReal(PetscRealPart(x[1])) - 0.5 * PetscRealPart(x[0]);
  return PetscRealPart(x[k - 1] - x[k]) / user->ek[k];
}

/* The averaged equation dX/dt = sin(X) - X/2 (one component) */
static PetscReal Averaged(PetscInt i, const PetscScalar *x, void *ctx)
{
  const PetscReal X = PetscRealPart(x[0]);
  return PetscSinReal(X) - 0.5 * X;
}

/* The full field (or the averaged one); each rank writes the entries it owns. */
static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx *user = (AppCtx *)ctx;

  PetscFunctionBeginUser;
  user->ex.nrhs++;
  PetscCall(OdeExampleEvaluate(&user->ex, U, F, user->mode == MODE_FULL ? ScaleTerm : Averaged, user));
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
  PetscCall(OdeExampleGetState(&user->ex, U, &x));
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
  PetscCall(OdeExampleRestoreState(&user->ex, U, &x));
  PetscCall(OdeExampleAssembleJacobian(A, B));
  PetscFunctionReturn(0);
}

/* The split of scale k (see OdeExampleEvaluateSplit()). */
static PetscErrorCode SplitFunction(PetscInt k, Vec U, Vec F, AppCtx *user)
{
  PetscFunctionBeginUser;
  PetscCall(OdeExampleEvaluateSplit(&user->ex, k, user->additive[k], U, F, ScaleTerm, user));
  PetscFunctionReturn(0);
}

/* One split function per scale (the split's number is in the function, the context is shared) */
ODE_EXAMPLE_SPLIT(RHSSplit0, 0)
ODE_EXAMPLE_SPLIT(RHSSplit1, 1)
ODE_EXAMPLE_SPLIT(RHSSplit2, 2)
ODE_EXAMPLE_SPLIT(RHSSplit3, 3)
ODE_EXAMPLE_SPLIT(RHSSplit4, 4)
ODE_EXAMPLE_SPLIT(RHSSplit5, 5)

/* x0 at the sampled times: printed at multiples of -print_interval, written to the CSV file; and
   the largest |x_k| so far. */
static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx   *user = (AppCtx *)ctx;
  PetscReal x0, umax, dt;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(U, NORM_INFINITY, &umax));
  if (PetscIsInfOrNanReal(umax) || umax > user->maxabs) user->maxabs = umax; /* keeps an Inf or NaN */
  PetscCall(OdeExampleGetComponent(&user->ex, U, 0, &x0));
  /* round-off allowance for "at a multiple": well below the step, so that a DNS with a tiny step
     does not print the step before the multiple */
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(OdeExampleMonitorSlow(&user->ex, step, t, PetscMin(1e-6 * user->ex.print_interval, 0.25 * PetscAbsReal(dt)), &x0));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  TS                ts;
  Vec               U;
  Mat               J;
  AppCtx            user;
  PetscReal         x0[CHAIN_MAX_SCALES] = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0}, xs;
  PetscInt          n, k;
  PetscInt          split_kind = SPLIT_COMPONENT, mode = MODE_FULL;
  char              splitnames[CHAIN_MAX_SCALES][8], extra[64];
  TSRHSFunction     splitfns[CHAIN_MAX_SCALES] = {RHSSplit0, RHSSplit1, RHSSplit2, RHSSplit3, RHSSplit4, RHSSplit5};
  const char *const slow[]                     = {"x0"};

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.nscales = 4;
  user.e       = 1e-2;
  PetscCall(OdeExampleInitialize(&user.ex, 1, slow, 0.5));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Relaxation chain options", NULL);
  PetscCall(PetscOptionsInt("-scales", "number of scales K+1 (2 to 6)", NULL, user.nscales, &user.nscales, NULL));
  PetscCheck(user.nscales >= 2 && user.nscales <= CHAIN_MAX_SCALES, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-scales must be 2 to %d, got %" PetscInt_FMT, CHAIN_MAX_SCALES, user.nscales);
  PetscCall(PetscOptionsReal("-e", "scale separation: e_k = e^k", NULL, user.e, &user.e, NULL));
  PetscCall(OdeExampleOptionsInitialState(PetscOptionsObject, "x0,...,xK", 1, user.nscales, x0));
  PetscCall(PetscOptionsEList("-split_kind", "how the scales are split", NULL, SplitKinds, 3, SplitKinds[split_kind], &split_kind, NULL));
  PetscCall(PetscOptionsEList("-mode", "full chain or averaged equation", NULL, Modes, 2, Modes[mode], &mode, NULL));
  PetscCall(OdeExampleOptionsOutput(PetscOptionsObject, &user.ex));
  PetscOptionsEnd();
  PetscCheck(user.e > 0 && user.e < 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-e must be in (0, 1), got %g", (double)user.e);
  user.mode  = (Mode)mode;
  user.ek[0] = 1.0;
  for (k = 1; k < user.nscales; k++) user.ek[k] = user.ek[k - 1] * user.e;
  for (k = 0; k < user.nscales; k++) user.additive[k] = (split_kind == SPLIT_ADDITIVE || (split_kind == SPLIT_MIXED && k % 2 == 0)) ? PETSC_TRUE : PETSC_FALSE;

  /* The state x0..xK, or X alone for the averaged equation, spread over the ranks */
  n = user.mode == MODE_FULL ? user.nscales : 1;
  PetscCall(OdeExampleCreateState(&user.ex, n, x0, &U));

  PetscCall(OdeExampleCreateTS(U, 2, 2.0, 0.1, Monitor, &user, &ts, &J));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
  if (user.mode == MODE_FULL) {
    /* One split per scale, slowest first. The split output vectors are created by PETSc with the IS layout. */
    for (k = 0; k < user.nscales; k++) {
      PetscCall(PetscSNPrintf(splitnames[k], sizeof(splitnames[k]), "s%" PetscInt_FMT, k));
      PetscCall(OdeExampleSetSplit(ts, splitnames[k], user.additive[k] ? ODE_SPLIT_ALL : ODE_SPLIT_COMPONENT, k, splitfns[k], &user));
    }
  }
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &user));
  PetscCall(TSSetFromOptions(ts));
  if (user.mode == MODE_FULL) PetscCall(OdeExampleSetObservable(&user.ex, ts)); /* the tolerance of -ts_vshmm_adapt applies to x0 */

  PetscCall(OdeExampleSolve(&user.ex, ts, U));
  PetscCall(OdeExampleGetComponent(&user.ex, U, 0, &xs));
  PetscCall(PetscSNPrintf(extra, sizeof(extra), "max_abs_state %.6e\n", (double)user.maxabs));
  PetscCall(OdeExampleReport(&user.ex, ts, &xs, extra));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(OdeExampleFinalize(&user.ex));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFinalize());
  return 0;
}
