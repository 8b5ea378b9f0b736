static const char help[] = "Fermi-Pasta-Ulam chain with stiff springs (Hairer, Lubich, Wanner, Geometric Numerical\n\
Integration, sect. I.5): 2m masses joined alternately by stiff linear springs (frequency omega) and\n\
soft cubic springs, fixed ends; solved with TSVSHMM or any PETSc TS.\n\
\n\
    H = 1/2 sum p_i^2 + omega^2/4 sum_j (q_2j - q_2j-1)^2 + sum_i (q_2i+1 - q_2i)^4,  q_0 = q_2m+1 = 0\n\
\n\
The stiff springs oscillate with period 2 pi/omega; their total energy I = sum_j I_j,\n\
I_j = (xdot_j^2 + omega^2 x_j^2)/2 with x_j = (q_2j - q_2j-1)/sqrt(2), is an adiabatic invariant:\n\
it stays within O(1/omega) of its initial value for times far beyond 1/omega, while the energy\n\
moves between the springs on the time scale omega.\n\
The state is (q_1..q_2m, p_1..p_2m). Two RHS splits, both additive (full-size vectors):\n\
  slow: q' = p, p' = the soft springs' forces\n\
  fast: p' = the stiff springs' forces\n\
so that the slow split holds the kinematics of every mass: with large mesoscopic steps the slow\n\
level moves the stiff springs' ends without their restoring force, which can pump energy into\n\
the stiff springs (the case TSVSHMM's stability check must notice).\n\
\n\
Options:\n\
  -m <3>                  : number of stiff springs (2m masses)\n\
  -omega <50>             : frequency of the stiff springs\n\
  -print_interval <1>     : print I and H at the steps that land on multiples of this time\n\
  -slow_csv <file>        : write t,I,H after every step as CSV\n\
  -no_timing              : do not print the wall_time line\n\
  -observe_state          : -ts_vshmm_adapt controls the whole state instead of I and H\n\
  -reference_I <I>        : print |I - reference| at the final time (the converged DNS, RK4 dt = 1e-4\n\
                            and 5e-5, gives I(10) = 0.98194398275 for the defaults)\n\
Initial data (GNI): x_1 = 1/omega, xdot_1 = 1, y_1 = 1, ydot_1 = 1 (y_j = (q_2j + q_2j-1)/sqrt(2)),\n\
all others 0, so I = 1 at t = 0.\n\
The default time stepper is TSRK (RK4) with time step 0.1 and final time 10.\n\
The TSVSHMM observables (TSVSHMMSetObservables()) are I and the total energy H.\n\n";

#include <petscvshmm.h>
#include "../common/ode_example.h"

typedef struct {
  PetscInt   m;     /* stiff springs; 2m masses, state size 4m */
  PetscReal  omega; /* stiff frequency */
  OdeExample ex;
} AppCtx;

/* q_a (a = 1..2m) at the whole state x; q_0 = q_2m+1 = 0 */
static PetscReal Q(const AppCtx *user, const PetscScalar *x, PetscInt a)
{
  return (a < 1 || a > 2 * user->m) ? 0.0 : PetscRealPart(x[a - 1]);
}

/* The soft springs' force on mass a (1..2m): spring i joins q_2i and q_2i+1, V_i = d^4, d = q_2i+1 - q_2i */
static PetscReal SoftForce(const AppCtx *user, const PetscScalar *x, PetscInt a)
{
  if (a % 2) { /* a = 2i+1: spring i pulls with -4 d^3 */
    const PetscReal d = Q(user, x, a) - Q(user, x, a - 1);
    return -4.0 * d * d * d;
  } else { /* a = 2i: spring i pushes with +4 d^3 */
    const PetscReal d = Q(user, x, a + 1) - Q(user, x, a);
    return 4.0 * d * d * d;
  }
}

/* The stiff springs' force on mass a: spring j joins q_2j-1 and q_2j, V_j = omega^2/4 (q_2j - q_2j-1)^2 */
static PetscReal StiffForce(const AppCtx *user, const PetscScalar *x, PetscInt a)
{
  const PetscReal w2 = user->omega * user->omega;
  if (a % 2) return 0.5 * w2 * (Q(user, x, a + 1) - Q(user, x, a));
  return -0.5 * w2 * (Q(user, x, a) - Q(user, x, a - 1));
}

/* Component i of the slow split, the fast split and the full field */
static PetscReal SlowComponent(PetscInt i, const PetscScalar *x, void *ctx)
{
  const AppCtx  *user = (const AppCtx *)ctx;
  const PetscInt n2   = 2 * user->m;
  return i < n2 ? PetscRealPart(x[n2 + i]) : SoftForce(user, x, i - n2 + 1);
}
static PetscReal FastComponent(PetscInt i, const PetscScalar *x, void *ctx)
{
  const AppCtx  *user = (const AppCtx *)ctx;
  const PetscInt n2   = 2 * user->m;
  return i < n2 ? 0.0 : StiffForce(user, x, i - n2 + 1);
}
static PetscReal FullComponent(PetscInt i, const PetscScalar *x, void *ctx)
{
  return SlowComponent(i, x, ctx) + FastComponent(i, x, ctx);
}

static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx *user = (AppCtx *)ctx;

  PetscFunctionBeginUser;
  user->ex.nrhs++;
  PetscCall(OdeExampleEvaluate(&user->ex, U, F, FullComponent, user));
  PetscFunctionReturn(0);
}
static PetscErrorCode RHSSlow(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx *user = (AppCtx *)ctx;

  PetscFunctionBeginUser;
  user->ex.nsplit++;
  PetscCall(OdeExampleEvaluate(&user->ex, U, F, SlowComponent, user));
  PetscFunctionReturn(0);
}
static PetscErrorCode RHSFast(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  AppCtx *user = (AppCtx *)ctx;

  PetscFunctionBeginUser;
  user->ex.nsplit++;
  PetscCall(OdeExampleEvaluate(&user->ex, U, F, FastComponent, user));
  PetscFunctionReturn(0);
}

/* The Jacobian of the full field (for implicit TS types) */
static PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec U, Mat A, Mat B, void *ctx)
{
  AppCtx            *user = (AppCtx *)ctx;
  const PetscScalar *x;
  const PetscInt     n2 = 2 * user->m;
  const PetscReal    w2 = user->omega * user->omega;
  PetscInt           lo, hi;

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetState(&user->ex, U, &x));
  PetscCall(MatGetOwnershipRange(B, &lo, &hi));
  for (PetscInt i = lo; i < hi; i++) {
    PetscInt    cols[3], nc = 0;
    PetscScalar row[3];
    if (i < n2) {
      cols[nc]  = n2 + i;
      row[nc++] = 1.0;
    } else {
      const PetscInt  a = i - n2 + 1;                    /* mass a, q_a is column a-1 */
      const PetscInt  b = (a % 2) ? a - 1 : a + 1;       /* the soft neighbour (0 or 2m+1: a wall) */
      const PetscInt  s = (a % 2) ? a + 1 : a - 1;       /* the stiff neighbour */
      const PetscReal d = Q(user, x, a) - Q(user, x, b); /* soft force -4 (q_a - q_b)^3 in both cases */
      cols[nc]          = a - 1;
      row[nc++]         = -12.0 * d * d - 0.5 * w2;
      if (b >= 1 && b <= n2) {
        cols[nc]  = b - 1;
        row[nc++] = 12.0 * d * d;
      }
      cols[nc]  = s - 1;
      row[nc++] = 0.5 * w2;
    }
    PetscCall(MatSetValues(B, 1, &i, nc, cols, row, INSERT_VALUES));
  }
  PetscCall(OdeExampleRestoreState(&user->ex, U, &x));
  PetscCall(OdeExampleAssembleJacobian(A, B));
  PetscFunctionReturn(0);
}

/* I (stiff energy) and H (total energy) */
static PetscErrorCode Energies(AppCtx *user, Vec U, PetscReal *istiff, PetscReal *htotal)
{
  const PetscScalar *x;
  const PetscInt     n2 = 2 * user->m;
  const PetscReal    w2 = user->omega * user->omega;

  PetscFunctionBeginUser;
  PetscCall(OdeExampleGetState(&user->ex, U, &x));
  *istiff = 0;
  *htotal = 0;
  for (PetscInt j = 1; j <= user->m; j++) {
    const PetscReal xj = (Q(user, x, 2 * j) - Q(user, x, 2 * j - 1)) / PETSC_SQRT2;
    const PetscReal vj = PetscRealPart(x[n2 + 2 * j - 1] - x[n2 + 2 * j - 2]) / PETSC_SQRT2;
    *istiff += 0.5 * (vj * vj + w2 * xj * xj);
  }
  for (PetscInt a = 0; a < n2; a++) *htotal += 0.5 * PetscRealPart(x[n2 + a] * x[n2 + a]);
  for (PetscInt i = 0; i <= user->m; i++) {
    const PetscReal d = Q(user, x, 2 * i + 1) - Q(user, x, 2 * i);
    *htotal += d * d * d * d;
  }
  for (PetscInt j = 1; j <= user->m; j++) {
    const PetscReal d = Q(user, x, 2 * j) - Q(user, x, 2 * j - 1);
    *htotal += 0.25 * w2 * d * d;
  }
  PetscCall(OdeExampleRestoreState(&user->ex, U, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Observables(TS ts, PetscReal t, Vec U, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(Energies((AppCtx *)ctx, U, &q[0], &q[1]));
  PetscFunctionReturn(0);
}

static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  AppCtx   *user = (AppCtx *)ctx;
  PetscReal q[2], dt;

  PetscFunctionBeginUser;
  PetscCall(Energies(user, U, &q[0], &q[1]));
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
  PetscReal        *x0, q[2];
  PetscBool         state = PETSC_FALSE, compare = PETSC_FALSE;
  PetscReal         reference = 0;
  const char *const slow[]    = {"I", "H"};

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TSVSHMMInitializePackage());

  PetscCall(PetscMemzero(&user, sizeof(user)));
  user.m     = 3;
  user.omega = 50;
  PetscCall(OdeExampleInitialize(&user.ex, 2, slow, 1.0));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Stiff-spring Fermi-Pasta-Ulam chain options", NULL);
  PetscCall(PetscOptionsInt("-m", "number of stiff springs", NULL, user.m, &user.m, NULL));
  PetscCall(PetscOptionsReal("-omega", "frequency of the stiff springs", NULL, user.omega, &user.omega, NULL));
  PetscCall(PetscOptionsReal("-reference_I", "print |I - reference| at the final time", NULL, reference, &reference, &compare));
  PetscCall(OdeExampleOptionsOutput(PetscOptionsObject, &user.ex));
  PetscOptionsEnd();
  PetscCheck(user.m >= 1 && user.m <= 1000, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-m must be 1 to 1000, got %" PetscInt_FMT, user.m);
  PetscCall(OdeExampleCheckPositive("-omega", user.omega));

  /* GNI's initial data: x_1 = 1/omega, xdot_1 = 1, y_1 = 1, ydot_1 = 1 */
  PetscCall(PetscCalloc1(4 * user.m, &x0));
  x0[0]              = (1.0 - 1.0 / user.omega) / PETSC_SQRT2; /* q_1 = (y_1 - x_1)/sqrt 2 */
  x0[1]              = (1.0 + 1.0 / user.omega) / PETSC_SQRT2; /* q_2 = (y_1 + x_1)/sqrt 2 */
  x0[2 * user.m]     = 0.0;                                    /* p_1 = (ydot_1 - xdot_1)/sqrt 2 */
  x0[2 * user.m + 1] = PETSC_SQRT2;                            /* p_2 = (ydot_1 + xdot_1)/sqrt 2 */
  PetscCall(OdeExampleCreateState(&user.ex, 4 * user.m, x0, &U));
  PetscCall(PetscFree(x0));

  PetscCall(OdeExampleCreateTS(U, 3, 10.0, 0.1, Monitor, &user, &ts, &J));
  PetscCall(TSRKSetType(ts, TSRK4));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &user));
  PetscCall(OdeExampleSetSplit(ts, "slow", ODE_SPLIT_ALL, 0, RHSSlow, &user));
  PetscCall(OdeExampleSetSplit(ts, "fast", ODE_SPLIT_ALL, 1, RHSFast, &user));
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &user));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-observe_state", &state, NULL));
  if (!state) PetscCall(TSVSHMMSetObservables(ts, 2, Observables, &user));

  PetscCall(OdeExampleSolve(&user.ex, ts, U));
  PetscCall(Energies(&user, U, &q[0], &q[1]));
  PetscCall(OdeExampleReport(&user.ex, ts, q, NULL));
  if (compare) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "I_error %.6e\n", (double)PetscAbsReal(q[0] - reference)));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(OdeExampleFinalize(&user.ex));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFinalize());
  return 0;
}
