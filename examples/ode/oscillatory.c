static const char help[] = "Resonant oscillators of Lee & Engquist (section \"Oscillatory case\"), solved with TSVSHMM or any PETSc TS.\n\
\n\
    dx1/dt = -y1/eps^2 + y2^2/eps - 3 x1 x2^2\n\
    dx2/dt = -(1/eps^2 + 1/eps) y2 - x2\n\
    dy1/dt = x1/eps^2 + y1/2\n\
    dy2/dt = (1/eps^2 + 1/eps) x2 - y2 + 2 x1^2 y2\n\
\n\
The state is the parallel Vec (x1, x2, y1, y2) of size 4; run it on 1 or more MPI ranks (on one\n\
rank the right-hand sides read the Vec's own array, on several each call gathers the state).\n\
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
  -eps <1e-3>                    : the scale separation parameter (positive, finite)\n\
  -x0 <1,0.5,0,0.5>              : initial state x1,x2,y1,y2 (exactly 4 finite values; the paper gives none)\n\
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
#include "../common/ode_example.h"

typedef enum {
  SPLIT_ADDITIVE,
  SPLIT_COMPONENT
} SplitKind;
static const char *const SplitKinds[] = {"additive", "component"};

typedef struct {
  PetscReal  eps;
  SplitKind  split_kind;
  OdeExample ex; /* state access, output, work counts (common/ode_example.h) */
} AppCtx;

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

/* Component i of the full field f_0 + f_1/eps + f_2/eps^2 at x. */
static PetscReal FullField(PetscInt i, const PetscScalar *x, void *ctx)
{
  const PetscReal eps = ((AppCtx *)ctx)->eps;
  return ScaleTerm(0, i, x, eps) + ScaleTerm(1, i, x, eps) + ScaleTerm(2, i, x, eps);
}

/* Component i of the term of one scale at x. */
typedef struct {
  AppCtx  *user;
  PetscInt k; /* the scale */
} TermCtx;

static PetscReal TermOfScale(PetscInt i, const PetscScalar *x, void *ctx)
{
  const TermCtx *c = (const TermCtx *)ctx;
  return ScaleTerm(c->k, i, x, c->user->eps);
}

/* The full field; each rank writes the entries it owns. */
static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx *user = (AppCtx *)ctx;

  PetscFunctionBeginUser;
  user->ex.nrhs++;
  PetscCall(OdeExampleEvaluate(&user->ex, U, F, FullField, user));
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
  PetscCall(OdeExampleGetState(&user->ex, U, &x));
  x1 = PetscRealPart(x[0]);
  x2 = PetscRealPart(x[1]);
  y2 = PetscRealPart(x[3]);
  PetscCall(OdeExampleRestoreState(&user->ex, U, &x));
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
  PetscCall(OdeExampleAssembleJacobian(A, B));
  PetscFunctionReturn(0);
}

/* The split of scale k; U is the full state.
   additive:  F has the layout of U (the split's IS is every locally owned component) and gets
              the term of scale k in every owned row;
   component: the split's IS is every component for k = 2 (fast) and none for k = 0, 1, and F
              gets the full field in its rows (TSMPRK's form: the field of the split's components). */
static PetscErrorCode SplitFunction(PetscInt k, Vec U, Vec F, AppCtx *user)
{
  TermCtx term = {user, k};

  PetscFunctionBeginUser;
  user->ex.nsplit++;
  if (user->split_kind == SPLIT_ADDITIVE) PetscCall(OdeExampleEvaluate(&user->ex, U, F, TermOfScale, &term));
  else PetscCall(OdeExampleEvaluate(&user->ex, U, F, FullField, user));
  PetscFunctionReturn(0);
}

/* One split function per scale */
ODE_EXAMPLE_SPLIT(RHSSlow, 0)
ODE_EXAMPLE_SPLIT(RHSMedium, 1)
ODE_EXAMPLE_SPLIT(RHSFast, 2)

/* The slow variables I1 = x1^2 + y1^2, I2 = x2^2 + y2^2 of the state U (on every rank). */
static PetscErrorCode SlowVariables(AppCtx *user, Vec U, PetscReal *I1, PetscReal *I2)
{
  const PetscScalar *x;
  PetscReal          x1, x2, y1, y2;

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetState(&user->ex, U, &x));
  x1 = PetscRealPart(x[0]);
  x2 = PetscRealPart(x[1]);
  y1 = PetscRealPart(x[2]);
  y2 = PetscRealPart(x[3]);
  PetscCall(OdeExampleRestoreState(&user->ex, U, &x));
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

/* I1, I2 at the sampled times: printed at the steps nearest to the multiples of -print_interval,
   written to the CSV file. */
static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx   *user = (AppCtx *)ctx;
  PetscReal q[2], dt;

  PetscFunctionBeginUser;
  PetscCall(SlowVariables(user, U, &q[0], &q[1]));
  /* The step nearest to the next multiple of print_interval: the first one past it less half a
     step. (The computed time of the step meant to land on a multiple can be a little below it;
     a fixed allowance would pick an earlier step of a DNS with a step of 1e-8, and I1 oscillates
     with amplitude ~2 eps at frequency 1/eps^2: one step of 1e-8 early changes it by ~1e-5.) */
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(OdeExampleMonitorSlow(&user->ex, step, t, 0.5 * PetscAbsReal(dt), q));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  TS                ts;
  Vec               U;
  Mat               J;
  AppCtx            user;
  PetscReal         x0[4] = {1.0, 0.5, 0.0, 0.5}, tfinal, tmax, q[2];
  PetscInt          k;
  PetscBool         isvshmm, ismprk;
  PetscInt          split_kind    = SPLIT_ADDITIVE;
  const char       *splitnames[3] = {"slow", "medium", "fast"};
  const char *const slow[]        = {"I1", "I2"};

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.eps = 1e-3;
  PetscCall(OdeExampleInitialize(&user.ex, 2, slow, 0.8));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Resonant-oscillator three-scale example options", NULL);
  PetscCall(PetscOptionsReal("-eps", "scale separation parameter", NULL, user.eps, &user.eps, NULL));
  PetscCall(OdeExampleOptionsInitialState(PetscOptionsObject, "x1,x2,y1,y2", 4, 4, x0));
  PetscCall(PetscOptionsEList("-split_kind", "additive (TSVSHMM) or component (TSMPRK) splits", NULL, SplitKinds, 2, SplitKinds[split_kind], &split_kind, NULL));
  PetscCall(OdeExampleOptionsOutput(PetscOptionsObject, &user.ex));
  PetscOptionsEnd();
  PetscCall(OdeExampleCheckPositive("-eps", user.eps));
  user.split_kind = (SplitKind)split_kind;

  /* The state (x1, x2, y1, y2), spread over the ranks */
  PetscCall(OdeExampleCreateState(&user.ex, 4, x0, &U));

  PetscCall(OdeExampleCreateTS(U, 4, 8.0, 0.8, Monitor, &user, &ts, &J));
  PetscCall(TSRKSetType(ts, TSRK4));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
  {
    TSRHSFunction splitfns[3] = {RHSSlow, RHSMedium, RHSFast};

    /* One split per scale, slowest first. Additive: the IS is every locally owned component.
       Component: slow and medium own no component, fast owns every one. */
    for (k = 0; k < 3; k++) PetscCall(OdeExampleSetSplit(ts, splitnames[k], (user.split_kind == SPLIT_ADDITIVE || k == 2) ? ODE_SPLIT_ALL : ODE_SPLIT_NONE, k, splitfns[k], &user));
  }
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &user));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSVSHMMSetObservables(ts, 2, Observables, &user)); /* the tolerance of -ts_vshmm_adapt applies to I1, I2 */
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSMPRK, &ismprk));
  PetscCheck(!isvshmm || user.split_kind == SPLIT_ADDITIVE, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "TSVSHMM needs -split_kind additive: every component has a term of every scale");
  PetscCheck(!ismprk || user.split_kind == SPLIT_COMPONENT, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "TSMPRK partitions the components: use -split_kind component (additive splits overlap)");

  PetscCall(OdeExampleSolve(&user.ex, ts, U));
  PetscCall(TSGetSolveTime(ts, &tfinal));
  PetscCall(TSGetMaxTime(ts, &tmax));
  /* e.g. TSMPRK in PETSc 3.18 may take one more full step when round-off leaves the time just
     below the final time: the final line below is then not at the final time */
  if (tfinal > tmax * (1.0 + 1e-12)) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: the solve stepped past the final time %g to t = %.10g\n", (double)tmax, (double)tfinal));
  PetscCall(SlowVariables(&user, U, &q[0], &q[1]));
  PetscCall(OdeExampleReport(&user.ex, ts, q, NULL));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(OdeExampleFinalize(&user.ex));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFinalize());
  return 0;
}
