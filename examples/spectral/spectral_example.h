/*
   spectral_example.h - the program shared by examples/spectral/diffusion.c and advection.c:
   set up a VSHMMSpectral scene from the options (-spectral_*), give the TS the full right-hand
   side and one RHS split per cluster, and run it to the output times. The output is the
   example's, not the library's:

     -output_times t1,t2,...        stop on each t_i (TS_EXACTFINALTIME_MATCHSTEP) and print
                                    output t <t> rhs_evaluations <n> split_evaluations <n> inverse_ffts <n> forward_ffts <n> direct_modes <n> wall_time <s> [file <name>]
                                    counted from the start of the solve (any number of times;
                                    without it: the TS's final time)
     -grid_solution_file PREFIX     write PREFIX_<t>.txt (<t> by C's %g): N lines "x_j u(x_j)", %.17g
     -compare_grid_solution PREFIX  print "compare t <t> relative_l2_error <e> max_error <e> weighted_error <w>" against
                                    PREFIX_<t>.txt; w = RMS over the grid of |u - u_ref| / (atol + rtol |u_ref|)
                                    with the TS's tolerances (-ts_atol, -ts_rtol): 1 = the tolerance met in the
                                    measure TSVSHMM's accuracy control applies to u on the grid
     -compare_tolerance TOL         and stop with an error if a relative L2 error exceeds TOL
     -spectrum_file FILE            a TS monitor writing "t k |c_k|" blocks every -spectrum_interval
     -no_timing                     leave the wall times out
     -observe_state                 with -ts_vshmm_adapt: weigh the Fourier coefficients of the state,
                                    not u on the grid (the default observables)
     -micro_step_from_stability 0   with -ts_vshmm_adapt: let adapt choose the micro step also where
                                    the fast modes only decay (default: the stability limit there)
     -stable_step_recheck 0         an explicit TS stepping by the stable step the example chose
                                    (no -ts_dt): do not estimate it again as the solution grows
                                    (StableStepMonitor(); by default it is, for nonlinear scenes)
   With -log_view the work is in two stages, "Spectral set-up" and "Solve".
   Detected clusters (no -spectral_clusters) are widened where the truncation check asks for it
   (-spectral_truncation_check widen, the default here; WidenPostStep()): the solve stops, the
   example prints "truncation check at t = ...: the clusters are widened ..." and the clusters, and
   runs again from the initial state (the output lines of the stopped run stay; the last run's
   counts and wall time include the stopped runs). TSVSHMM with -ts_vshmm_adapt on one cluster runs
   the explicit sparse method instead (OneClusterFallback()), and says so.
*/
#include <petscvshmm.h>
#include <petscvshmmspectral.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct {
  VSHMMSpectral   sp;
  PetscReal      *times; /* output times */
  PetscInt        ntimes;
  char            grid_prefix[PETSC_MAX_PATH_LEN], compare_prefix[PETSC_MAX_PATH_LEN], spectrum_file[PETSC_MAX_PATH_LEN];
  PetscReal       compare_tol, spectrum_interval, next_spectrum;
  PetscBool       timing;
  FILE           *spectrum_fp;
  PetscInt        N, nmodes;
  const PetscInt *modes;
  PetscReal      *u, *mags; /* N grid values; one magnitude per retained mode */
  PetscMPIInt     rank;
  PetscBool       detected; /* the clusters were detected */
  PetscInt        nclusters;
  /* an explicit TS's step from VSHMMSpectralGetStableTimeStep() (linearised at u0), re-checked by
     StableStepMonitor(): the method, sum |c_k| at the last estimate, the estimates made, the step */
  PetscBool recheck;
  TSRKType  recheck_rk;
  PetscReal recheck_w, recheck_dt, recheck_dt0;
  PetscInt  rechecks;
  PetscBool restart;                                                          /* the truncation check asked for wider clusters: run again (WidenPostStep()) */
  PetscReal atol, rtol;                                                       /* the TS's tolerances, for the compare line's weighted error */
  PetscReal t_start;                                                          /* the TS's initial time */
  PetscBool fallback;                                                         /* OneClusterFallback() replaced TSVSHMM */
  long long stopped_splits, stopped_inverse, stopped_forward, stopped_direct; /* the counts of the runs the truncation check stopped (their rhs_evaluations: the statistics' widening_evaluations) */
} SpectralRun;

/* -output_times: any number of values. PETSc's array reader stops silently at the capacity it is
   given, so the capacity grows until the list fits; then PetscOptionsRealArray() reads it for -help. */
static PetscErrorCode ReadOutputTimes(PetscOptionItems *PetscOptionsObject, SpectralRun *run)
{
  PetscInt  capacity = 16, n;
  PetscBool set      = PETSC_FALSE, given;

  PetscFunctionBeginUser;
  for (;; capacity *= 2) {
    PetscCall(PetscCalloc1(capacity, &run->times));
    n = capacity;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-output_times", run->times, &n, &set));
    if (!set || n < capacity) break;
    PetscCall(PetscFree(run->times));
  }
  n = capacity;
  PetscCall(PetscOptionsRealArray("-output_times", "times at which to print the work and write the grid solution", NULL, run->times, &n, &set));
  run->ntimes = set ? n : 0;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-output_times", &given)); /* PETSc takes a value-less option for an absent one */
  PetscCheck(given == set && (!set || n > 0), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-output_times needs at least one time");
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadRunOptions(SpectralRun *run)
{
  PetscBool no_timing = PETSC_FALSE;

  PetscFunctionBeginUser;
  run->compare_tol       = 0;
  run->spectrum_interval = 0.01;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Output of the sparse spectral examples", NULL);
  PetscCall(ReadOutputTimes(PetscOptionsObject, run));
  PetscCall(PetscOptionsString("-grid_solution_file", "prefix of the grid solution files PREFIX_<t>.txt", NULL, run->grid_prefix, run->grid_prefix, sizeof(run->grid_prefix), NULL));
  PetscCall(PetscOptionsString("-compare_grid_solution", "prefix of reference grid solutions PREFIX_<t>.txt to compare with", NULL, run->compare_prefix, run->compare_prefix, sizeof(run->compare_prefix), NULL));
  PetscCall(PetscOptionsReal("-compare_tolerance", "stop with an error if the relative L2 error exceeds this (0: no check)", NULL, run->compare_tol, &run->compare_tol, NULL));
  PetscCall(PetscOptionsString("-spectrum_file", "write t k |c_k| blocks to this file", NULL, run->spectrum_file, run->spectrum_file, sizeof(run->spectrum_file), NULL));
  PetscCall(PetscOptionsReal("-spectrum_interval", "time between two spectra in -spectrum_file", NULL, run->spectrum_interval, &run->spectrum_interval, NULL));
  PetscCall(PetscOptionsBool("-no_timing", "omit wall times", NULL, no_timing, &no_timing, NULL));
  PetscOptionsEnd();
  run->timing = no_timing ? PETSC_FALSE : PETSC_TRUE;
  PetscCheck(isfinite(run->compare_tol) && run->compare_tol >= 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-compare_tolerance must be finite and nonnegative (0: no check), got %g", (double)run->compare_tol);
  PetscCheck(isfinite(run->spectrum_interval) && run->spectrum_interval > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-spectrum_interval must be finite and positive, got %g", (double)run->spectrum_interval);
  PetscFunctionReturn(0);
}

/* TS monitor of -spectrum_file: |c_k| of the retained modes every -spectrum_interval. */
static PetscErrorCode SpectrumMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  SpectralRun *run = (SpectralRun *)ctx;
  PetscInt     i;

  PetscFunctionBeginUser;
  (void)ts;
  (void)step;
  if (t < run->next_spectrum - 1e-9 * run->spectrum_interval) PetscFunctionReturn(0);
  while (run->next_spectrum <= t + 1e-9 * run->spectrum_interval) run->next_spectrum += run->spectrum_interval;
  PetscCall(VSHMMSpectralGetModeMagnitudes(run->sp, U, run->mags));
  if (run->rank == 0) {
    for (i = 0; i < run->nmodes; i++) fprintf(run->spectrum_fp, "%.10g %d %.6e\n", (double)t, (int)run->modes[i], (double)run->mags[i]);
    fprintf(run->spectrum_fp, "\n");
  }
  PetscFunctionReturn(0);
}

/* The grid solution at output time t: PREFIX_<t>.txt, N lines "x_j u(x_j)". */
static PetscErrorCode WriteGridSolution(SpectralRun *run, Vec U, PetscReal t, char file[], size_t len)
{
  PetscInt j;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetGridValues(run->sp, U, run->u));
  snprintf(file, len, "%s_%g.txt", run->grid_prefix, (double)t); /* C's %g, not PETSc's */
  if (run->rank == 0) {
    FILE *fp = fopen(file, "w");
    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot open the grid solution file %s", file);
    for (j = 0; j < run->N; j++) fprintf(fp, "%.17g %.17g\n", 2.0 * PETSC_PI * (double)j / (double)run->N, (double)run->u[j]);
    PetscCheck(fclose(fp) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write the grid solution file %s", file);
  }
  PetscFunctionReturn(0);
}

/* The relative L2 and max errors against PREFIX_<t>.txt. */
static PetscErrorCode CompareGridSolution(SpectralRun *run, Vec U, PetscReal t)
{
  char       name[PETSC_MAX_PATH_LEN], line[256];
  double     e2 = 0, r2 = 0, w2 = 0, emax = 0, rel;
  PetscReal *ref;
  PetscInt   j;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetGridValues(run->sp, U, run->u));
  snprintf(name, sizeof(name), "%s_%g.txt", run->compare_prefix, (double)t);
  PetscCall(PetscMalloc1(run->N, &ref));
  PetscCall(VSHMMSpectralReadGridValues(run->sp, name, ref));
  for (j = 0; j < run->N; j++) {
    const double d = run->u[j] - ref[j];
    const double w = d / (run->atol + run->rtol * fabs(ref[j]));
    e2 += d * d;
    r2 += ref[j] * ref[j];
    w2 += w * w;
    if (!(fabs(d) <= emax)) emax = fabs(d); /* keeps a NaN */
  }
  PetscCall(PetscFree(ref));
  rel = sqrt(e2 / (r2 > 0 ? r2 : 1.0));
  snprintf(line, sizeof(line), "compare t %g relative_l2_error %.3e max_error %.3e weighted_error %.3e", (double)t, rel, emax, sqrt(w2 / run->N));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", line));
  PetscCheck(run->compare_tol <= 0 || rel <= run->compare_tol, /* false for NaN */ PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "The relative L2 error %.3e against %s exceeds -compare_tolerance %g", rel, name, (double)run->compare_tol);
  PetscFunctionReturn(0);
}

/* "output t ..." with the work counted by the VSHMMSpectral so far. */
static PetscErrorCode PrintWork(SpectralRun *run, PetscReal t, double wall, const char *file)
{
  VSHMMSpectralStatistics st;
  char                    line[PETSC_MAX_PATH_LEN + 512];
  int                     len;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetStatistics(run->sp, &st));
  /* C's %g (PetscPrintf would print 1 as "1.") */
  len = snprintf(line, sizeof(line), "output t %g rhs_evaluations %lld split_evaluations %lld inverse_ffts %lld forward_ffts %lld direct_modes %lld", (double)t, (long long)(st.field_evaluations + st.widening_evaluations),
                 (long long)st.split_calls + run->stopped_splits, (long long)st.inverse_ffts + run->stopped_inverse, (long long)st.forward_ffts + run->stopped_forward, (long long)st.direct_modes + run->stopped_direct);
  if (run->timing && len > 0 && len < (int)sizeof(line)) len += snprintf(line + len, sizeof(line) - len, " wall_time %.4e", wall);
  if (file && len > 0 && len < (int)sizeof(line)) len += snprintf(line + len, sizeof(line) - len, " file %s", file);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", line));
  PetscFunctionReturn(0);
}

/* "detection ...": the cluster detection's work (set-up, not in the output lines' counts). */
static PetscErrorCode PrintDetectionCost(SpectralRun *run)
{
  VSHMMSpectralStatistics st;
  char                    line[256];
  int                     len;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetStatistics(run->sp, &st));
  if (!st.detection_evaluations) PetscFunctionReturn(0);
  len = snprintf(line, sizeof(line), "detection dns_steps %lld evaluations %lld", (long long)st.detection_steps, (long long)st.detection_evaluations);
  if (run->timing && len > 0 && len < (int)sizeof(line)) snprintf(line + len, sizeof(line) - len, " wall_time %.4e", (double)st.detection_time);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", line));
  PetscFunctionReturn(0);
}

/* Runs the TS to each output time (the TS's time step restored before each segment). */
static PetscErrorCode SolveToOutputTimes(SpectralRun *run, TS ts, Vec U)
{
  PetscReal      t0, dt0, tf;
  PetscLogDouble w0, w1;
  PetscInt       i;

  PetscFunctionBeginUser;
  PetscCall(TSGetTime(ts, &t0));
  PetscCall(TSGetTimeStep(ts, &dt0));
  run->t_start = t0;
  if (run->ntimes) { /* the output times set the end; a final time given as well must not fall before them */
    const char *prefix;
    PetscBool   given;

    PetscCall(TSGetOptionsPrefix(ts, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_max_time", &given));
    PetscCall(TSGetMaxTime(ts, &tf));
    PetscCheck(!given || run->times[run->ntimes - 1] <= tf * (1 + 1e-12), PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "-output_times goes to %g, beyond -%sts_max_time %g: drop the later output times or raise the final time", (double)run->times[run->ntimes - 1], prefix ? prefix : "", (double)tf);
  }
  if (!run->ntimes) {
    PetscCall(TSGetMaxTime(ts, &tf));
    PetscCall(PetscFree(run->times));
    PetscCall(PetscMalloc1(1, &run->times));
    run->times[0] = tf;
    run->ntimes   = 1;
  }
  for (i = 0; i < run->ntimes; i++) {
    char a[64], b[64];

    PetscCheck(isfinite(run->times[i]) && run->times[i] > t0 && (i == 0 || run->times[i] > run->times[i - 1]), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-output_times must be increasing and after the initial time %g; item %d is %g", (double)t0, (int)i + 1,
               (double)run->times[i]);
    if (i == 0) continue;
    /* the output lines and the files PREFIX_<t>.txt name a time by C's %g: two times that print
       alike would share a name (the second file overwriting the first) */
    snprintf(a, sizeof(a), "%g", (double)run->times[i - 1]);
    snprintf(b, sizeof(b), "%g", (double)run->times[i]);
    PetscCheck(strcmp(a, b), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-output_times: items %d and %d (%.17g and %.17g) print alike as %s with %%g, which names the output lines and the files PREFIX_<t>.txt: give times that differ within 6 significant digits", (int)i, (int)i + 1,
               (double)run->times[i - 1], (double)run->times[i], b);
  }
  if (run->spectrum_file[0]) {
    if (run->rank == 0) {
      run->spectrum_fp = fopen(run->spectrum_file, "w");
      PetscCheck(run->spectrum_fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot open -spectrum_file %s", run->spectrum_file);
      fprintf(run->spectrum_fp, "# t k |c_k| (Fourier series coefficients; unitary DFT magnitude = sqrt(N) |c_k|, N = %d)\n", (int)run->N);
    }
    {
      PetscBool isvshmm;

      PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
      if (isvshmm && run->spectrum_interval < dt0 * (1 - 1e-12)) /* its states between the sampled times are internal */
        PetscCall(PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "Note: TSVSHMM's solution is defined at the sampled times only, one macro step (DeltaT = %g) apart: -spectrum_interval %g writes a spectrum at the first sampled time of each interval, not more often\n", (double)dt0,
                               (double)run->spectrum_interval));
    }
    run->next_spectrum = t0;
    PetscCall(SpectrumMonitor(ts, 0, t0, U, run));
    PetscCall(TSMonitorSet(ts, SpectrumMonitor, run, NULL));
  }
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(PetscTime(&w0));
  for (i = 0; i < run->ntimes; i++) {
    const PetscReal   ti = run->times[i];
    PetscReal         t, norm;
    TSConvergedReason reason;
    char              file[PETSC_MAX_PATH_LEN] = "";

    PetscCall(TSSetMaxTime(ts, ti));
    /* the stable step (lowered by StableStepMonitor()), and at least 10 steps to this output time
       (SetDefaultSteps()) */
    PetscCall(TSSetTimeStep(ts, run->recheck ? PetscMin(run->recheck_dt, (ti - (i ? run->times[i - 1] : t0)) / 10) : dt0));
    PetscCall(TSSolve(ts, U));
    PetscCall(VSHMMSpectralGetTruncationWidening(run->sp, &run->restart, NULL));
    if (run->restart) break; /* RunSpectralExample() widens the clusters and runs again */
    PetscCall(TSGetSolveTime(ts, &t));
    PetscCall(TSGetConvergedReason(ts, &reason));
    PetscCheck(reason >= 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "The TS diverged (%s) at t = %g before the output time %g", TSConvergedReasons[reason], (double)t, (double)ti);
    PetscCheck(fabs(t - ti) <= 1e-9 * PetscMax(1.0, fabs(ti)), PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "The TS stopped at t = %.12g, not at the output time %g (%s; raise -ts_max_steps?)", (double)t, (double)ti, TSConvergedReasons[reason]);
    PetscCall(PetscTime(&w1));
    PetscCall(VecNorm(U, NORM_2, &norm));
    PetscCheck(isfinite(norm), PETSC_COMM_WORLD, PETSC_ERR_FP, "The solution at t = %g is not finite (Inf or NaN): the time step is probably too large for the fastest retained mode (see VSHMMSpectralGetStableTimeStep(); -ts_dt, -ts_vshmm_micro_dt, -ts_vshmm_savings_factors)", (double)ti);
    if (run->grid_prefix[0]) PetscCall(WriteGridSolution(run, U, ti, file, sizeof(file)));
    PetscCall(PrintWork(run, ti, w1 - w0, file[0] ? file : NULL));
    if (run->compare_prefix[0]) PetscCall(CompareGridSolution(run, U, ti));
  }
  if (run->spectrum_fp) {
    fclose(run->spectrum_fp);
    run->spectrum_fp = NULL;
  }
  PetscFunctionReturn(0);
}

/* The smallest spacing of the output times (the span to the TS's final time without them: with
   them the program's default final time is not the run's; outputs at 2, 5, 10 took a sampling
   interval of 1, the diffusion program's default final time, before 2026-11-28). */
static PetscErrorCode OutputSpacing(SpectralRun *run, TS ts, PetscReal *dt)
{
  PetscReal t0;
  PetscInt  i;

  PetscFunctionBeginUser;
  PetscCall(TSGetTime(ts, &t0));
  if (!run->ntimes) {
    PetscCall(TSGetMaxTime(ts, dt));
    *dt -= t0;
  } else *dt = PETSC_MAX_REAL;
  for (i = 0; i < run->ntimes; i++) *dt = PetscMin(*dt, run->times[i] - (i ? run->times[i - 1] : t0));
  PetscFunctionReturn(0);
}

/* TSVSHMM without -ts_dt: the sampling interval DeltaT is the smallest spacing of the output
   times (the final time without them), not the stable step of an explicit method. */
static PetscErrorCode DefaultSamplingInterval(SpectralRun *run, TS ts)
{
  PetscBool   isvshmm, set;
  PetscReal   dt;
  const char *prefix;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_dt", &set));
  if (!isvshmm || set) PetscFunctionReturn(0);
  PetscCall(OutputSpacing(run, ts, &dt));
  if (dt > 0) PetscCall(TSSetTimeStep(ts, dt));
  PetscFunctionReturn(0);
}

/* -ts_vshmm_adapt's observables: u at the N grid points, so that the tolerance applies to the
   solution's values (weighed by atol + rtol |u(x_j)|, RMS over the grid, i.e. in the L2 norm).
   Without them TSVSHMM would weigh the Fourier coefficients of the state, whose RMS over the
   n retained reals is the L2 norm divided by sqrt(n): the error would look sqrt(n) times smaller. */
static PetscErrorCode GridObservable(TS ts, PetscReal t, Vec X, PetscReal q[], void *ctx)
{
  SpectralRun *run = (SpectralRun *)ctx;

  PetscFunctionBeginUser;
  (void)ts;
  (void)t;
  PetscCall(VSHMMSpectralGetGridValues(run->sp, X, q));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetGridObservables(SpectralRun *run, TS ts)
{
  PetscBool isvshmm, adapt = PETSC_FALSE, state = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  if (isvshmm) {
    PetscInt nclusters;

    PetscCall(VSHMMSpectralGetSizes(run->sp, NULL, NULL, &nclusters));
    run->nclusters = nclusters;
    PetscCheck(nclusters != 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "-ts_type vshmm needs the scene's time scales as clusters, but the scene is in mode dns (every wavenumber, no clusters): use -spectral_mode sparse (with -spectral_clusters, or the detection) or another TS type");
    PetscCheck(nclusters != 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_INCOMP, "-ts_type vshmm needs at least two clusters (time scales), but the scene has one%s: there is nothing to separate. Use -ts_type rk (the explicit sparse method, or -spectral_mode dns), -ts_vshmm_adapt (which then runs the explicit sparse method) or give -spectral_clusters",
               nclusters == 1 && run->detected ? " (the detection kept one band of wavenumbers)" : "");
    PetscCall(TSVSHMMGetAdapt(ts, &adapt));
  }
  if (adapt) { /* the clusters' separations (their slowest modes), unless given on the command line */
    const PetscReal   *S;
    const char *const *scales;
    PetscInt           n, nscales, next = 0;
    const char        *prefix;
    PetscBool          set, ok = PETSC_TRUE;
    PetscReal          Sscale[64];

    PetscCall(TSGetOptionsPrefix(ts, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_vshmm_scale_separations", &set));
    PetscCall(VSHMMSpectralGetScaleSeparations(run->sp, &n, &S));
    /* one separation per pair of scales: where a scale groups clusters (-ts_vshmm_splits K3+K4), the
       separation at each boundary between scales is that of the clusters on either side; scales
       that are not consecutive clusters in order get none (TSVSHMM then uses its own estimate) */
    PetscCall(TSVSHMMGetSplitOrder(ts, &nscales, &scales));
    ok = (n > 0 && n + 1 == run->nclusters && nscales >= 2 && nscales <= 64) ? PETSC_TRUE : PETSC_FALSE;
    for (PetscInt l = 0; ok && l < nscales; ++l) {
      const char *c = scales[l];
      while (ok && *c) {
        char *end;
        long  k;
        if (*c != 'K') {
          ok = PETSC_FALSE;
          break;
        }
        k = strtol(c + 1, &end, 10);
        if (end == c + 1 || k != next) ok = PETSC_FALSE;
        next++;
        c = *end == '+' ? end + 1 : end;
        if (*end && *end != '+') ok = PETSC_FALSE;
      }
      if (ok && l + 1 < nscales) Sscale[l] = S[next - 1];
    }
    if (ok && next != run->nclusters) ok = PETSC_FALSE;
    if (!set && ok) PetscCall(TSVSHMMSetScaleSeparations(ts, nscales - 1, Sscale));
  }
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-observe_state", &state, NULL));
  if (adapt && !state) PetscCall(TSVSHMMSetObservables(ts, run->N, GridObservable, run));
  PetscFunctionReturn(0);
}

/* The micro step against the operator's stable step. TSVSHMM's fastest level integrates the sum of
   all splits, the whole operator on the clusters, with the inner RK type (-ts_vshmm_rk_type), so
   the micro step must be stable for that operator: VSHMMSpectralGetStableTimeStep() of the inner
   RK type (linearised at u0; computed once per set-up, about 40 operator applications, not in the
   evaluations counted by the output lines).
   * -ts_vshmm_micro_dt given: a warning (stderr) if it exceeds that step, naming the option, the
     value, the step and the estimated limit (TSVSHMM's stability check, on by default, then stops
     the first solve, but may name a savings factor instead of the micro step).
   * -ts_vshmm_adapt without -ts_vshmm_micro_dt, where the fastest modes only decay (diffusion
     dominates; they are slaved to the slower ones and their error does not accumulate): the micro
     step is that step (itself 0.9 of the estimated limit; a further 0.9 was measured and is not
     better, docs/spectral.md); adapt then chooses the savings factors. Its own
     choice, tol^(1/p) / rho, is made for oscillating fast scales (8x smaller at tol 1e-3). "Only
     decay": the stable RK3 step times the estimated spectral radius is at least 0.8 of RK3's
     limit on the negative real axis (0.9 times 2.5127, the estimate's margin included): 1 where
     the limiting eigenvalues are real and negative, 0.69 where they are imaginary (advection:
     RK3's limit there is sqrt 3). Otherwise, or with -micro_step_from_stability false, adapt
     chooses. */
static PetscErrorCode StableMicroStep(SpectralRun *run, TS ts)
{
  PetscBool   isvshmm, adapt = PETSC_FALSE, set, use = PETSC_TRUE, rk3;
  const char *prefix;
  TSRKType    rk;
  PetscReal   h, h3, rho;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  if (!isvshmm || run->nclusters < 2) PetscFunctionReturn(0);
  PetscCall(TSVSHMMGetAdapt(ts, &adapt));
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_vshmm_micro_dt", &set));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-micro_step_from_stability", &use, NULL));
  if (!set && (!adapt || !use)) PetscFunctionReturn(0);
  PetscCall(TSVSHMMGetRKType(ts, &rk));
  PetscCall(VSHMMSpectralGetStableTimeStep(run->sp, rk, &h));
  if (set) {
    PetscReal mdt;

    PetscCall(TSVSHMMGetMicroStep(ts, &mdt));
    if (mdt > h)
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "Warning: -%sts_vshmm_micro_dt %g exceeds the stable step %g of the fastest level (the whole operator on the clusters, inner RK %s; VSHMMSpectralGetStableTimeStep(), 0.9 of the estimated stability limit %g): the micro steps are likely unstable; use -%sts_vshmm_micro_dt %g or less\n", prefix ? prefix : "", (double)mdt, (double)h, rk, (double)(h / 0.9), prefix ? prefix : "", (double)h));
    PetscFunctionReturn(0);
  }
  if (h >= PETSC_INFINITY) PetscFunctionReturn(0); /* no eigenvalue limits it (PETSC_INFINITY, a finite number): adapt chooses */
  PetscCall(PetscStrcmp(rk, TSRK3, &rk3));
  if (rk3) h3 = h; /* the same estimate */
  else PetscCall(VSHMMSpectralGetStableTimeStep(run->sp, TSRK3, &h3));
  PetscCall(VSHMMSpectralGetSpectralRadius(run->sp, &rho, NULL));
  {
    PetscReal DeltaT; /* a sampling interval of fewer than 5 stable steps (output times close together) leaves adapt the choice */

    PetscCall(TSGetTimeStep(ts, &DeltaT));
    if (!(h < DeltaT / 5)) PetscFunctionReturn(0);
  }
  if (h3 * rho >= 0.8 * 0.9 * 2.5127) PetscCall(TSVSHMMSetMicroStep(ts, h));
  PetscFunctionReturn(0);
}

/* "ts_type ...": the stepper and its step sizes. */
static PetscErrorCode PrintStepper(TS ts)
{
  PetscReal dt;
  PetscBool isvshmm, isrk;
  TSType    type;
  char      line[512];

  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts, &type));
  PetscCall(TSGetTimeStep(ts, &dt));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &isrk));
  /* C's snprintf for %g (PetscPrintf would print 1 as "1.") */
  if (isvshmm) {
    PetscReal        mdt;
    PetscInt         n, i;
    const PetscReal *alpha;
    TSRKType         rk;
    int              len;

    PetscCall(TSVSHMMGetMicroStep(ts, &mdt));
    PetscCall(TSVSHMMGetSavingsFactors(ts, &n, &alpha));
    PetscCall(TSVSHMMGetRKType(ts, &rk));
    len = snprintf(line, sizeof(line), "ts_type vshmm: sampling interval %g, micro step %g, inner RK %s, savings factors", (double)dt, (double)(mdt > 0 ? mdt : dt / 100), rk);
    for (i = 0; i < n && len > 0 && len < (int)sizeof(line); i++) len += snprintf(line + len, sizeof(line) - len, "%s%g", i ? "," : " ", (double)alpha[i]);
    if (!n && len > 0 && len < (int)sizeof(line)) snprintf(line + len, sizeof(line) - len, " (all 1)");
  } else if (isrk) {
    TSRKType rk;

    PetscCall(TSRKGetType(ts, &rk));
    snprintf(line, sizeof(line), "ts_type rk %s: time step %g", rk, (double)dt);
  } else {
    snprintf(line, sizeof(line), "ts_type %s: time step %g", type, (double)dt);
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", line));
  PetscFunctionReturn(0);
}

/* The steps the options leave open, from the operator's stable step (VSHMMSpectralGetStableTimeStep()):
   without -ts_dt, an explicit TS steps by the stable step of its method (TSRK's type; TSRK1FE for
   euler; TSRK3 for any other type), at least 10 steps to each output time; with -ts_dt an explicit
   TS (TSRK, TSEULER) is warned where it exceeds that step; TSVSHMM without -ts_vshmm_micro_dt and -ts_vshmm_adapt takes
   the stable step of its inner method as the micro step (the fastest level evaluates the whole
   field), and without -ts_dt 100 micro steps as the sampling interval. */
static PetscErrorCode SetDefaultSteps(SpectralRun *run, TS ts)
{
  PetscBool   dt_given, isvshmm, isrk, iseuler;
  PetscReal   h, DeltaT;
  TSRKType    rk = TSRK3;
  const char *prefix;

  PetscFunctionBeginUser;
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_dt", &dt_given));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &isrk));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSEULER, &iseuler));
  if (isvshmm) {
    PetscBool adapt, micro_given;

    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_vshmm_micro_dt", &micro_given));
    PetscCall(TSVSHMMGetAdapt(ts, &adapt));
    if (micro_given || adapt) PetscFunctionReturn(0);
    PetscCall(TSVSHMMGetRKType(ts, &rk));
    PetscCall(VSHMMSpectralGetStableTimeStep(run->sp, rk, &h));
    PetscCall(TSGetTimeStep(ts, &DeltaT)); /* given, or the output times' spacing (DefaultSamplingInterval()) */
    PetscCall(TSVSHMMSetMicroStep(ts, PetscMin(h, DeltaT / 100)));
    PetscFunctionReturn(0);
  }
  if (isrk) PetscCall(TSRKGetType(ts, &rk));
  if (iseuler) rk = TSRK1FE;
  PetscCall(VSHMMSpectralGetStableTimeStep(run->sp, rk, &h));
  if (dt_given) { /* the user's step against the stable one */
    PetscReal dt;

    PetscCall(TSGetTimeStep(ts, &dt));
    if ((isrk || iseuler) && h < PETSC_INFINITY && dt > h)
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "Warning: -%sts_dt %g exceeds the stable step %g of TSRK %s for the scene's operator (VSHMMSpectralGetStableTimeStep(), 0.9 of the estimated stability limit %g): the steps are likely unstable, and a growth the scene's terms allow may not be caught; use -%sts_dt %g or less\n", prefix ? prefix : "", (double)dt, (double)h, rk, (double)(h / 0.9), prefix ? prefix : "", (double)h));
    PetscFunctionReturn(0);
  }
  if (h >= PETSC_INFINITY) PetscFunctionReturn(0); /* no eigenvalue limits it (PETSC_INFINITY, a finite number): keep the TS's step */
  run->recheck    = PETSC_TRUE;
  run->recheck_rk = rk;
  run->recheck_dt = run->recheck_dt0 = h;
  PetscCall(OutputSpacing(run, ts, &DeltaT)); /* at least 10 steps between two outputs (per output interval, SolveToOutputTimes()): the stable step of a few slow modes (a sparse run on narrow clusters) need not resolve their rates */
  if (DeltaT > 0) h = PetscMin(h, DeltaT / 10);
  PetscCall(TSSetTimeStep(ts, h));
  PetscFunctionReturn(0);
}

/* sum over the retained k of |c_k| (k > 0 twice): a bound on max|u| over the grid. */
static PetscErrorCode WienerNorm(SpectralRun *run, Vec U, PetscReal *w)
{
  PetscInt i;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetModeMagnitudes(run->sp, U, run->mags));
  *w = 0;
  for (i = 0; i < run->nmodes; i++) *w += (run->modes[i] ? 2.0 : 1.0) * run->mags[i];
  PetscFunctionReturn(0);
}

/* The stable step of an explicit TS set by SetDefaultSteps() is the operator's linearised at u0.
   A nonlinear term's Jacobian grows with the solution (burgers: by max|c u| kmax + max|(c u)_x|;
   a reaction: by |r| (|c1| + 2 |c2| M + 3 |c3| M^2), M = max|u|), and every such bound grows with
   W = sum |c_k| >= max|u| (max|(c u)_x| <= kmax max|c u|). So every 8 steps W is compared with its
   value at the last estimate; when it has grown by more than 10% the stable step is estimated
   again at the current state (VSHMMSpectralGetStableTimeStepAt(): 40 evaluations, none for a
   linear scene) and the step is lowered to it if smaller, with a message. The step is never
   raised again. */
static PetscErrorCode StableStepMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  SpectralRun *run = (SpectralRun *)ctx;
  PetscReal    w, h, dt;

  PetscFunctionBeginUser;
  if (step % 8) PetscFunctionReturn(0);
  PetscCall(WienerNorm(run, U, &w));
  if (!(w > 1.1 * run->recheck_w)) PetscFunctionReturn(0);
  PetscCall(VSHMMSpectralGetStableTimeStepAt(run->sp, U, run->recheck_rk, &h));
  run->rechecks++;
  if (h < run->recheck_dt) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stable step at t = %g: %g (TSRK %s, the Jacobian at the current state; sum |c_k| %g, %g at the last estimate): the time step is lowered from %g\n", (double)t, (double)h, run->recheck_rk, (double)w,
                          (double)run->recheck_w, (double)run->recheck_dt));
    run->recheck_dt = h;
  }
  PetscCall(TSGetTimeStep(ts, &dt)); /* possibly already shortened to end at the final time */
  if (dt > run->recheck_dt) PetscCall(TSSetTimeStep(ts, run->recheck_dt));
  run->recheck_w = w;
  PetscFunctionReturn(0);
}

/* Installs StableStepMonitor() when the step came from the stability estimate
   (-stable_step_recheck false: not). */
static PetscErrorCode SetStableStepRecheck(SpectralRun *run, TS ts, Vec U)
{
  PetscBool use = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-stable_step_recheck", &use, NULL));
  if (!run->recheck || !use) {
    run->recheck = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  PetscCall(WienerNorm(run, U, &run->recheck_w));
  PetscCall(TSMonitorSet(ts, StableStepMonitor, run, NULL));
  PetscFunctionReturn(0);
}

/* A sparse run that cost more than a direct simulation would: the DNS of the scene, TSRK 3 at the
   stable step of the operator on every wavenumber (VSHMMSpectralGetDNSStableTimeStep(); at most a
   tenth of each output interval, as SolveToOutputTimes() takes it), its evaluations counted to each
   output time, against this run's with its stopped runs and its detection (each on the same
   N-point transforms). Said on the standard output where the DNS is cheaper by more than a tenth, for TSVSHMM (and the
   explicit sparse method that replaces it on one cluster), not for a TS type and step the user chose. */
static PetscErrorCode CompareWithDNS(SpectralRun *run, TS ts)
{
  VSHMMSpectralStatistics st;
  PetscInt                nclusters, i;
  PetscReal               h, t;
  long long               dns = 0, work, all;
  PetscBool               isvshmm;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetSizes(run->sp, NULL, NULL, &nclusters));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  if (!nclusters || !(isvshmm || run->fallback)) PetscFunctionReturn(0); /* a DNS itself, or the user's method */
  PetscCall(VSHMMSpectralGetDNSStableTimeStep(run->sp, TSRK3, &h));
  if (!(h > 0) || h >= PETSC_INFINITY) PetscFunctionReturn(0);
  for (i = 0, t = run->t_start; i < run->ntimes; t = run->times[i], i++) dns += 3 * (long long)ceil((run->times[i] - t) / PetscMin(h, (run->times[i] - t) / 10) - 1e-9);
  PetscCall(VSHMMSpectralGetStatistics(run->sp, &st));
  work = (long long)(st.field_evaluations + st.widening_evaluations);
  all  = work + (long long)st.detection_evaluations;
  if (all <= dns + dns / 10) PetscFunctionReturn(0); /* about the same (a run on every wavenumber is the DNS itself, with its detection's few evaluations): no note */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "note: this sparse run took %lld evaluations (%lld with the cluster detection's); a direct simulation of the scene (-spectral_mode dns, TSRK 3 at its stable step %g) would take about %lld, each on the same %d-point transforms: at this tolerance the DNS is the cheaper tool\n", work, all, (double)h, dns,
                        (int)run->N));
  PetscFunctionReturn(0);
}

/* -spectral_truncation_check widen (the examples' default where the clusters are detected): ends
   the solve where the truncation check asks for wider clusters; RunSpectralExample() widens them
   (VSHMMSpectralWidenClusters()) and runs the scene again from its initial state. */
static PetscErrorCode WidenPostStep(TS ts)
{
  SpectralRun *run;
  PetscBool    pending;

  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &run));
  PetscCall(VSHMMSpectralGetTruncationWidening(run->sp, &pending, NULL));
  if (pending) PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
  PetscFunctionReturn(0);
}

/* TSVSHMM with -ts_vshmm_adapt on one cluster (a detection that found one band), or on the one
   cluster of every wavenumber that the truncation check asked for: nothing to separate, so the
   explicit sparse method (TSRK 3 at the operator's stable step), and the example says so; without
   -ts_vshmm_adapt on detected clusters (parameters the user chose for several scales)
   SetGridObservables() stops with the advice. */
static PetscErrorCode OneClusterFallback(SpectralRun *run, TS ts)
{
  PetscBool               isvshmm, adapt = PETSC_FALSE;
  PetscInt                nclusters;
  VSHMMSpectralStatistics st;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVSHMM, &isvshmm));
  if (!isvshmm) PetscFunctionReturn(0);
  PetscCall(TSVSHMMGetAdapt(ts, &adapt));
  PetscCall(VSHMMSpectralGetSizes(run->sp, NULL, NULL, &nclusters));
  PetscCall(VSHMMSpectralGetStatistics(run->sp, &st));
  if (!(adapt || st.widenings) || nclusters != 1) PetscFunctionReturn(0); /* one cluster from a widening: with savings set too */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "one cluster%s: no time scales to separate, so no savings: the explicit sparse method (TSRK 3 at the operator's stable step) instead of TSVSHMM\n",
                        st.widenings    ? " (the truncation check widened the clusters into one)"
                        : run->detected ? " (the detection kept one band of wavenumbers)"
                                        : ""));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRKSetType(ts, TSRK3));
  run->fallback = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The state and the TS on the object's layout, from the initial data, with the example's
   defaults and the options. */
static PetscErrorCode CreateRun(SpectralRun *run, PetscReal tfinal, TS *ts, Vec *U)
{
  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralGetSizes(run->sp, &run->N, NULL, NULL));
  PetscCall(VSHMMSpectralGetModes(run->sp, &run->nmodes, &run->modes));
  PetscCall(PetscMalloc2(run->N, &run->u, run->nmodes, &run->mags));
  PetscCall(VSHMMSpectralCreateVec(run->sp, U));
  PetscCall(VSHMMSpectralSetInitialCondition(run->sp, *U));

  PetscCall(TSCreate(PETSC_COMM_WORLD, ts));
  PetscCall(TSSetSolution(*ts, *U));
  PetscCall(VSHMMSpectralSetUpTS(run->sp, *ts));
  PetscCall(TSSetApplicationContext(*ts, run));
  PetscCall(TSSetPostStep(*ts, WidenPostStep));
  PetscCall(TSSetType(*ts, TSRK));
  PetscCall(TSRKSetType(*ts, TSRK3));
  PetscCall(TSSetTimeStep(*ts, tfinal / 100)); /* replaced below unless -ts_dt is given */
  PetscCall(TSSetMaxTime(*ts, tfinal));
  PetscCall(TSSetMaxSteps(*ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(*ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetFromOptions(*ts));
  PetscCall(TSGetTolerances(*ts, &run->atol, NULL, &run->rtol, NULL));
  PetscCall(OneClusterFallback(run, *ts));
  PetscCall(DefaultSamplingInterval(run, *ts)); /* TSVSHMM without -ts_dt: the output times' spacing */
  PetscCall(SetDefaultSteps(run, *ts));
  PetscCall(SetGridObservables(run, *ts));
  PetscCall(StableMicroStep(run, *ts));
  PetscCall(SetStableStepRecheck(run, *ts, *U));
  PetscFunctionReturn(0);
}

static PetscErrorCode DestroyRun(SpectralRun *run, TS *ts, Vec *U)
{
  PetscFunctionBeginUser;
  PetscCall(TSDestroy(ts));
  PetscCall(VecDestroy(U));
  PetscCall(PetscFree2(run->u, run->mags));
  PetscFunctionReturn(0);
}

/* Runs the scene `scene` ("diffusion" or "advection") with default final time tfinal. */
static PetscErrorCode RunSpectralExample(const char *scene, PetscReal tfinal)
{
  SpectralRun   run;
  TS            ts;
  Vec           U;
  PetscLogStage setup_stage, solve_stage;
  PetscBool     clusters;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&run, sizeof(run)));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &run.rank));
  PetscCall(TSVSHMMInitializePackage());
  PetscCall(ReadRunOptions(&run));
  /* -log_view stages: the set-up (fields, FFTW plans, detection, stable-step estimates) and the
     solve (TSVSHMM's set-up, e.g. its stability check, happens in the first TSSolve) */
  PetscCall(PetscLogStageRegister("Spectral set-up", &setup_stage));
  PetscCall(PetscLogStageRegister("Solve", &solve_stage));
  PetscCall(PetscLogStagePush(setup_stage));
  PetscCall(VSHMMSpectralCreate(PETSC_COMM_WORLD, &run.sp));
  PetscCall(VSHMMSpectralSetDefaultScene(run.sp, scene));
  /* detected clusters are widened where the truncation check asks for it, and the run restarts
     (WidenPostStep()); explicit ones are the user's (-spectral_truncation_check overrides both) */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-spectral_clusters", &clusters));
  if (!clusters) PetscCall(VSHMMSpectralSetTruncationCheck(run.sp, VSHMMSPECTRAL_TRUNCATION_WIDEN));
  { /* the detection's tolerance is the time stepping's (-spectral_cluster_tolerance overrides), and
       so is its threshold: the modes it leaves out cost the sparse method (and VSHMM on its
       clusters) an error of about 10 times the threshold (measured: 1e-4 gives 1e-3 to 5e-3 on
       the diffusion scenes), so below tolerance 3e-3 the threshold is tol / 30
       (-spectral_cluster_lambda overrides) */
    PetscReal rtol;
    PetscBool set, lambda;
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-ts_rtol", &rtol, &set));
    PetscCheck(!set || (isfinite(rtol) && rtol >= 0), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-ts_rtol must be finite and nonnegative (the time stepping's tolerance, and the cluster detection's), got %g", (double)rtol);
    if (set) PetscCall(VSHMMSpectralSetClusterTolerance(run.sp, rtol));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-spectral_cluster_lambda", &lambda));
    if (set && !lambda && rtol > 0 && rtol / 30 < 1e-4) PetscCall(VSHMMSpectralSetClusterThreshold(run.sp, rtol / 30));
  }
  PetscCall(VSHMMSpectralSetFromOptions(run.sp));
  PetscCall(VSHMMSpectralSetUp(run.sp));
  PetscCall(VSHMMSpectralView(run.sp, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(PrintDetectionCost(&run));
  {
    VSHMMSpectralStatistics st;

    PetscCall(VSHMMSpectralGetStatistics(run.sp, &st));
    run.detected = st.detection_evaluations > 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(CreateRun(&run, tfinal, &ts, &U));
  PetscCall(PrintStepper(ts));
  PetscCall(PetscLogStagePop());

  PetscCall(PetscLogStagePush(solve_stage));
  for (;;) {
    PetscBool               widened;
    PetscReal               tw;
    VSHMMSpectralStatistics st;

    PetscCall(SolveToOutputTimes(&run, ts, U));
    if (!run.restart) {
      PetscCall(CompareWithDNS(&run, ts));
      break;
    }
    PetscCall(VSHMMSpectralGetTruncationWidening(run.sp, &run.restart, &tw));
    PetscCall(VSHMMSpectralGetStatistics(run.sp, &st)); /* the stopped run's counts, before the widening clears them */
    run.stopped_splits += (long long)st.split_calls;
    run.stopped_inverse += (long long)st.inverse_ffts;
    run.stopped_forward += (long long)st.forward_ffts;
    run.stopped_direct += (long long)st.direct_modes;
    PetscCall(DestroyRun(&run, &ts, &U));
    PetscCall(VSHMMSpectralWidenClusters(run.sp, &widened));
    PetscCall(VSHMMSpectralGetStatistics(run.sp, &st));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "truncation check at t = %g: the clusters are widened (widening %d) and the run starts again from its initial state (rhs_evaluations of the stopped runs %lld, counted in the output lines)\n", (double)tw,
                          (int)st.widenings, (long long)st.widening_evaluations));
    PetscCall(VSHMMSpectralView(run.sp, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(CreateRun(&run, tfinal, &ts, &U));
    PetscCall(PrintStepper(ts));
  }
  if (run.recheck && run.recheck_dt < run.recheck_dt0)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stable step rechecks %d (about 41 evaluations each, not in rhs_evaluations): the time step was lowered from %g to %g\n", (int)run.rechecks, (double)run.recheck_dt0, (double)run.recheck_dt));
  PetscCall(PetscLogStagePop());

  PetscCall(DestroyRun(&run, &ts, &U));
  PetscCall(PetscFree(run.times));
  PetscCall(VSHMMSpectralDestroy(&run.sp));
  PetscFunctionReturn(0);
}
