/*
   bench_sundials - the ODE benchmark problems (bench_problems.h: the fields of
   examples/ode/oscillatory.c, examples/ode/dissipative.c, examples/stress/chain.c) solved with
   SUNDIALS: CVODE (Adams with fixed-point iteration, BDF with Newton and the analytic dense
   Jacobian), ARKODE ERKStep (adaptive, default 4th-order table, or fixed step) and ARKODE MRIStep
   (explicit slow method with fixed slow step H, explicit inner ARKStep, adaptive or fixed step).
   Only the benchmark uses SUNDIALS; the library never links it.

   Usage: bench_sundials -problem oscillators|dissipative|chain [-eps e] [-scales K+1]
            -method cvode-adams|cvode-bdf|erk|erk-fixed|mri [-rtol r] [-atol a] [-h step]
            [-H slow_step] [-mri_slow_terms m] [-max_steps n] [-max_calls n] [-no_timing] -times t1,t2,...
   -max_steps, -max_calls: budget; a run that exceeds it prints "budget exceeded" and exits with 1.
   -mri_slow_terms m: terms 0..m-1 are the slow field of MRIStep, the others the fast one.
   -h: the fixed step of erk-fixed, or of MRIStep's inner method (0: adaptive inner with rtol, atol).
   Prints "sample t q..." at each time (the slow observables: I1, I2 / xi / x0), then the work:
   calls (of any right-hand side function), term_evaluations (terms f_k evaluated, summed over
   calls), jacobian_evaluations, steps, wall_time. Exit status 1 if the solver fails.
*/
#include "bench_problems.h"
#include <stdio.h>
#include <time.h>
#include <cvode/cvode.h>
#include <arkode/arkode_erkstep.h>
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_mristep.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

typedef struct {
  BenchProblem p;
  int          k0, k1;                  /* the terms this function evaluates */
  long        *allcalls, *terms, *jacs; /* counters shared by the functions of one run */
  long         maxcalls;                /* budget of calls (0: none): beyond it the functions fail */
} FnCtx;

static int Field(realtype t, N_Vector y, N_Vector ydot, void *ctx)
{
  FnCtx *c = (FnCtx *)ctx;

  (void)t;
  if (c->maxcalls && *c->allcalls >= c->maxcalls) return -1; /* out of budget: stop the solver */
  BenchTerms(&c->p, c->k0, c->k1, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  (*c->allcalls)++;
  *c->terms += c->k1 - c->k0 + 1;
  return 0;
}

static int Jacobian(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *ctx, N_Vector t1, N_Vector t2, N_Vector t3)
{
  FnCtx        *c = (FnCtx *)ctx;
  double        Jd[BENCH_MAX_N * BENCH_MAX_N];
  const int     n = c->p.n;
  int           i, j, k;
  const double *x = N_VGetArrayPointer(y);

  (void)t;
  (void)fy;
  (void)t1;
  (void)t2;
  (void)t3;
  memset(Jd, 0, sizeof(Jd));
  for (k = c->k0; k <= c->k1; k++) BenchTermJacobianAdd(&c->p, k, x, Jd);
  for (i = 0; i < n; i++)
    for (j = 0; j < n; j++) SM_ELEMENT_D(J, i, j) = Jd[i * n + j];
  (*c->jacs)++;
  return 0;
}

static double Now(void)
{
  struct timespec ts;

  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void Usage(void)
{
  fprintf(stderr, "usage: bench_sundials -problem oscillators|dissipative|chain [-eps e] [-scales n] -method cvode-adams|cvode-bdf|erk|erk-fixed|mri [-rtol r] [-atol a] [-h dt] [-H slow_dt] [-mri_slow_terms m] [-max_steps n] [-max_calls n] "
                  "[-no_timing] -times t1,t2,...\n");
  exit(2);
}

int main(int argc, char **argv)
{
  const char         *problem = "oscillators", *method = "cvode-adams";
  double              eps = -1, rtol = 1e-6, atol = 1e-6, h = 0, H = 0, times[64], t, t0, t1;
  int                 ntimes = 0, nscales = 4, slowterms = -1, timing = 1, i, flag = 0;
  long                maxsteps = 100000000, maxcalls = 0, allcalls = 0, terms = 0, jacs = 0, steps = 0, extra;
  FnCtx               full, slow, fast;
  SUNContext          sunctx;
  N_Vector            y;
  void               *mem = NULL, *inner = NULL;
  MRIStepInnerStepper stepper = NULL;
  SUNMatrix           A       = NULL;
  SUNLinearSolver     LS      = NULL;
  SUNNonlinearSolver  NLS     = NULL;

  for (i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-no_timing")) {
      timing = 0;
      continue;
    }
    if (i + 1 >= argc) Usage();
    if (!strcmp(argv[i], "-problem")) problem = argv[++i];
    else if (!strcmp(argv[i], "-method")) method = argv[++i];
    else if (!strcmp(argv[i], "-eps") || !strcmp(argv[i], "-e")) eps = atof(argv[++i]);
    else if (!strcmp(argv[i], "-scales")) nscales = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-rtol")) rtol = atof(argv[++i]);
    else if (!strcmp(argv[i], "-atol")) atol = atof(argv[++i]);
    else if (!strcmp(argv[i], "-h")) h = atof(argv[++i]);
    else if (!strcmp(argv[i], "-H")) H = atof(argv[++i]);
    else if (!strcmp(argv[i], "-mri_slow_terms")) slowterms = atoi(argv[++i]);
    else if (!strcmp(argv[i], "-max_steps")) maxsteps = strtol(argv[++i], NULL, 10);
    else if (!strcmp(argv[i], "-max_calls")) maxcalls = strtol(argv[++i], NULL, 10);
    else if (!strcmp(argv[i], "-times")) ntimes = BenchParseList(argv[++i], times, 64);
    else Usage();
  }
  if (eps <= 0) eps = !strcmp(problem, "oscillators") ? 1e-3 : 1e-2;
  if (ntimes < 1 || BenchProblemSetUp(&full.p, problem, eps, nscales)) Usage();
  full.k0       = 0;
  full.k1       = full.p.nterms - 1;
  full.allcalls = &allcalls;
  full.terms    = &terms;
  full.jacs     = &jacs;
  full.maxcalls = maxcalls;
  slow = fast = full;
  if (slowterms < 1) slowterms = full.p.nterms - 1;
  if (slowterms >= full.p.nterms) Usage();
  slow.k1 = slowterms - 1;
  fast.k0 = slowterms;

  if (SUNContext_Create(NULL, &sunctx)) return 1;
  y = N_VNew_Serial(full.p.n, sunctx);
  for (i = 0; i < full.p.n; i++) NV_Ith_S(y, i) = full.p.x0[i];

  if (!strcmp(method, "cvode-adams") || !strcmp(method, "cvode-bdf")) {
    int bdf = !strcmp(method, "cvode-bdf");
    mem     = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, sunctx);
    flag |= CVodeInit(mem, Field, 0.0, y);
    flag |= CVodeSetUserData(mem, &full);
    flag |= CVodeSStolerances(mem, rtol, atol);
    flag |= CVodeSetMaxNumSteps(mem, maxsteps);
    if (bdf) {
      A  = SUNDenseMatrix(full.p.n, full.p.n, sunctx);
      LS = SUNLinSol_Dense(y, A, sunctx);
      flag |= CVodeSetLinearSolver(mem, LS, A);
      flag |= CVodeSetJacFn(mem, Jacobian);
    } else {
      NLS = SUNNonlinSol_FixedPoint(y, 0, sunctx);
      flag |= CVodeSetNonlinearSolver(mem, NLS);
    }
  } else if (!strcmp(method, "erk") || !strcmp(method, "erk-fixed")) {
    mem = ERKStepCreate(Field, 0.0, y, sunctx);
    flag |= ERKStepSetUserData(mem, &full);
    flag |= ERKStepSetMaxNumSteps(mem, maxsteps);
    if (!strcmp(method, "erk-fixed")) {
      if (h <= 0) Usage();
      flag |= ERKStepSetFixedStep(mem, h);
    } else flag |= ERKStepSStolerances(mem, rtol, atol);
  } else if (!strcmp(method, "mri")) {
    if (H <= 0) Usage();
    inner = ARKStepCreate(Field, NULL, 0.0, y, sunctx);
    flag |= ARKStepSetUserData(inner, &fast);
    flag |= ARKStepSetMaxNumSteps(inner, maxsteps);
    if (h > 0) flag |= ARKStepSetFixedStep(inner, h);
    else flag |= ARKStepSStolerances(inner, rtol, atol);
    flag |= ARKStepCreateMRIStepInnerStepper(inner, &stepper);
    mem = MRIStepCreate(Field, NULL, 0.0, y, stepper, sunctx);
    flag |= MRIStepSetUserData(mem, &slow);
    flag |= MRIStepSetFixedStep(mem, H);
    flag |= MRIStepSetMaxNumSteps(mem, maxsteps);
  } else Usage();
  if (!mem || flag) {
    fprintf(stderr, "bench_sundials: set-up failed\n");
    return 1;
  }

  printf("method %s problem %s eps %g rtol %g atol %g h %g H %g\n", method, problem, eps, rtol, atol, h, H);
  t0 = Now();
  for (i = 0; i < ntimes; i++) {
    double q[2];
    int    nq, j;

    if (!strncmp(method, "cvode", 5)) flag = CVode(mem, times[i], y, &t, CV_NORMAL);
    else if (!strcmp(method, "mri")) flag = MRIStepEvolve(mem, times[i], y, &t, ARK_NORMAL);
    else flag = ERKStepEvolve(mem, times[i], y, &t, ARK_NORMAL);
    if (flag < 0) {
      /* -1 is CV_TOO_MUCH_WORK and ARK_TOO_MUCH_WORK: the step budget (-max_steps) */
      if (flag == -1 || (maxcalls && allcalls >= maxcalls)) printf("budget exceeded at t %g (flag %d)\n", t, flag);
      else printf("failed at t %g flag %d\n", t, flag);
      break;
    }
    nq = BenchObservables(&full.p, N_VGetArrayPointer(y), q);
    printf("sample %.10g", times[i]);
    for (j = 0; j < nq; j++) printf(" %.12e", q[j]);
    printf("\n");
  }
  t1 = Now();
  if (!strncmp(method, "cvode", 5)) CVodeGetNumSteps(mem, &steps);
  else if (!strcmp(method, "mri")) {
    long fs, fsi;
    MRIStepGetNumSteps(mem, &steps);
    MRIStepGetNumRhsEvals(mem, &fs, &fsi);
    ARKStepGetNumSteps(inner, &extra);
    printf("mri_slow_calls %ld inner_steps %ld\n", fs, extra);
  } else ERKStepGetNumSteps(mem, &steps);
  printf("calls %ld\nterm_evaluations %ld\njacobian_evaluations %ld\nsteps %ld\n", allcalls, terms, jacs, steps);
  if (timing) printf("wall_time %.6e\n", t1 - t0);

  if (!strncmp(method, "cvode", 5)) CVodeFree(&mem);
  else if (!strcmp(method, "mri")) {
    MRIStepFree(&mem);
    MRIStepInnerStepper_Free(&stepper);
    ARKStepFree(&inner);
  } else ERKStepFree(&mem);
  if (LS) SUNLinSolFree(LS);
  if (A) SUNMatDestroy(A);
  if (NLS) SUNNonlinSolFree(NLS);
  N_VDestroy(y);
  SUNContext_Free(&sunctx);
  return flag < 0 ? 1 : 0;
}
