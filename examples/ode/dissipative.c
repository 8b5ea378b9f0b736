static const char help[] = "Dissipative three-scale ODE of Lee & Engquist (their eq. exp1), solved with TSVSHMM or any PETSc TS.\n\
\n\
    dxi/dt   = sin(xi+eta+zeta) - (xi+eta+zeta)^2/20     (scale 0, slow)\n\
    deta/dt  = (3 xi^2 - eta^2 + zeta^2)/eps             (scale 1, medium)\n\
    dzeta/dt = (xi - eta - zeta)/eps^2                    (scale 2, fast)\n\
\n\
As eps -> 0, xi follows the averaged equation dXi/dt = sin(2 Xi) - Xi^2/5, Xi(0) = xi(0).\n\
The state is a parallel Vec of size 3; run it on 1 or more MPI ranks (on one rank the right-hand\n\
sides read the Vec's own array, on several each call gathers the three components).\n\
\n\
Options:\n\
  -eps <1e-2>                    : the scale separation parameter (positive, finite)\n\
  -x0 <5,-10,5>                  : initial state xi,eta,zeta (exactly 3 finite values)\n\
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
#include "../common/ode_example.h"

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
  OdeExample ex; /* state access, output, work counts (common/ode_example.h) */
} AppCtx;

/* The term of scale k (with its 1/eps_k factor) at the state x = (xi, eta, zeta); it has only
   component k, so it is also component k of the full field f_0 + f_1/eps + f_2/eps^2. */
static PetscReal ScaleTerm(PetscInt k, const PetscScalar *x, void *ctx)
{
  const PetscReal eps = ((AppCtx *)ctx)->eps;
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

/* The averaged equation dXi/dt = sin(2 Xi) - Xi^2/5 (one component) */
static PetscReal Averaged(PetscInt i, const PetscScalar *x, void *ctx)
{
  const PetscReal X = PetscRealPart(x[0]);
  return PetscSinReal(2.0 * X) - X * X / 5.0;
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

/* The Jacobian of the full field (for implicit or IMEX types such as -ts_type arkimex, beuler) */
static PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec U, Mat A, Mat B, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  PetscInt           lo, hi, i, cols[3] = {0, 1, 2};
  PetscScalar        row[3];

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetState(&user->ex, U, &x));
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
  PetscCall(OdeExampleRestoreState(&user->ex, U, &x));
  PetscCall(OdeExampleAssembleJacobian(A, B));
  PetscFunctionReturn(0);
}

/* The split of scale k (see OdeExampleEvaluateSplit()). */
static PetscErrorCode SplitFunction(PetscInt k, Vec U, Vec F, AppCtx *user)
{
  PetscFunctionBeginUser;
  PetscCall(OdeExampleEvaluateSplit(&user->ex, k, user->split_kind == SPLIT_ADDITIVE ? PETSC_TRUE : PETSC_FALSE, U, F, ScaleTerm, user));
  PetscFunctionReturn(0);
}

/* One split function per scale */
ODE_EXAMPLE_SPLIT(RHSSlow, 0)
ODE_EXAMPLE_SPLIT(RHSMedium, 1)
ODE_EXAMPLE_SPLIT(RHSFast, 2)

/* xi at the sampled times: printed at multiples of -print_interval, written to the CSV file. */
static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx   *user = (AppCtx *)ctx;
  PetscReal xi;

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetComponent(&user->ex, U, 0, &xi));
  PetscCall(OdeExampleMonitorSlow(&user->ex, step, t, 1e-6 * user->ex.print_interval, &xi));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  TS                ts;
  Vec               U;
  Mat               J;
  AppCtx            user;
  PetscReal         x0[3] = {5.0, -10.0, 5.0}, xi;
  PetscInt          n, k;
  PetscInt          split_kind = SPLIT_COMPONENT, mode = MODE_FULL;
  const char       *splitnames[3] = {"slow", "medium", "fast"};
  const char *const slow[]        = {"xi"};

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.eps = 1e-2;
  PetscCall(OdeExampleInitialize(&user.ex, 1, slow, 0.5));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Dissipative three-scale example options", NULL);
  PetscCall(PetscOptionsReal("-eps", "scale separation parameter", NULL, user.eps, &user.eps, NULL));
  PetscCall(OdeExampleOptionsInitialState(PetscOptionsObject, "xi,eta,zeta", 3, 3, x0));
  PetscCall(PetscOptionsEList("-split_kind", "how the three scales are split", NULL, SplitKinds, 2, SplitKinds[split_kind], &split_kind, NULL));
  PetscCall(PetscOptionsEList("-mode", "full system or averaged equation", NULL, Modes, 2, Modes[mode], &mode, NULL));
  PetscCall(OdeExampleOptionsOutput(PetscOptionsObject, &user.ex));
  PetscOptionsEnd();
  PetscCall(OdeExampleCheckPositive("-eps", user.eps));
  user.split_kind = (SplitKind)split_kind;
  user.mode       = (Mode)mode;

  /* The state: (xi, eta, zeta), or Xi alone for the averaged equation, spread over the ranks */
  n = user.mode == MODE_FULL ? 3 : 1;
  PetscCall(OdeExampleCreateState(&user.ex, n, x0, &U));

  PetscCall(OdeExampleCreateTS(U, n, 2.0, 0.1, Monitor, &user, &ts, &J));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
  if (user.mode == MODE_FULL) {
    TSRHSFunction splitfns[3] = {RHSSlow, RHSMedium, RHSFast};

    /* One split per scale, slowest first. The split output vectors are created by PETSc with the IS layout. */
    for (k = 0; k < 3; k++) PetscCall(OdeExampleSetSplit(ts, splitnames[k], user.split_kind == SPLIT_COMPONENT ? ODE_SPLIT_COMPONENT : ODE_SPLIT_ALL, k, splitfns[k], &user));
  }
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &user));
  PetscCall(TSSetFromOptions(ts));
  if (user.mode == MODE_FULL) PetscCall(OdeExampleSetObservable(&user.ex, ts)); /* the tolerance of -ts_vshmm_adapt applies to xi */

  PetscCall(OdeExampleSolve(&user.ex, ts, U));
  PetscCall(OdeExampleGetComponent(&user.ex, U, 0, &xi));
  PetscCall(OdeExampleReport(&user.ex, ts, &xi, NULL));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(OdeExampleFinalize(&user.ex));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFinalize());
  return 0;
}
