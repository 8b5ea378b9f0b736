/*
  The stability check of TSVSHMM: estimates the eigenvalues of each level's field at the current
  state and compares the level's steps with the stability region of the inner Runge-Kutta method.

  Eigenvalues: a few Arnoldi steps on the Jacobian of G_l = f_0 + ... + f_l, applied by finite
  differences of the split functions (no user Jacobian); the Ritz values approximate the extreme
  eigenvalues, the ones that limit an explicit step.

  Verdict, for every Ritz value lambda except growing modes (Re lambda > 0.1 |lambda|), with a
  step allowed to grow a mode as much as the exact flow does (|R(z)| <= max(1, |exp(z)|), which
  matters for slightly growing oscillations):
  - the micro step dt of the full field must satisfy that for z = x dt lambda, x in [0, 1];
  - a mesoscopic level passes if its largest step does; variable steps may exceed the limit near
    the kernel's peak as long as the level's steps over a whole macro step damp the mode
    (prod |R(h lambda)| <= 1). Otherwise the check fails with an error that names the level,
    the step, the eigenvalue, the spectral radius and the largest stable step.
*/
#include "vshmmimpl.hpp"

#include <petscblaslapack.h>

#include <cmath>
#include <complex>
#include <string>

static constexpr PetscInt  kArnoldiSteps       = 16;
static constexpr PetscReal kDampingTarget      = 0.5; /* what a suggested savings factor achieves over a macro step */
static constexpr PetscReal kGrowingMode        = 0.1; /* Re lambda > this |lambda|: a growing mode, not checked */
static constexpr PetscReal kMaxTransientGrowth = 100; /* largest growth of a mode within a macro step that only warns */

/* Ritz values of the Jacobian of level l's field at (t, X). */
static PetscErrorCode LevelRitzValues(TS ts, PetscInt level, PetscReal t, Vec X, std::vector<std::complex<double>> &ritz, PetscBool *finite)
{
  TS_VSHMM    *vs = (TS_VSHMM *)ts->data;
  PetscInt     N, rstart, rend;
  Vec         *V, G0, Xp, W;
  PetscReal    xnorm;
  PetscScalar *v;

  PetscFunctionBegin;
  ritz.clear();
  *finite = PETSC_TRUE;
  PetscCall(VecGetSize(X, &N));
  const PetscInt m = PetscMin(kArnoldiSteps, N);
  PetscCall(VecDuplicateVecs(X, m + 1, &V));
  PetscCall(VecDuplicate(X, &G0));
  PetscCall(VecDuplicate(X, &Xp));
  PetscCall(VecDuplicate(X, &W));

  /* A deterministic start vector that does not depend on the number of ranks */
  PetscCall(VecGetOwnershipRange(V[0], &rstart, &rend));
  PetscCall(VecGetArray(V[0], &v));
  for (PetscInt i = rstart; i < rend; ++i) v[i - rstart] = 1.0 + 0.5 * std::sin(1.7 * (double)i + 0.3);
  PetscCall(VecRestoreArray(V[0], &v));
  PetscReal beta;
  PetscCall(VecNormalize(V[0], &beta));

  PetscCall(VecNorm(X, NORM_2, &xnorm));
  const PetscReal delta = std::sqrt(PETSC_MACHINE_EPSILON) * (1.0 + xnorm);
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, t, X, G0));

  std::vector<PetscScalar> H((m + 1) * m, 0.0), h(m + 1);
  PetscInt                 k = 0; /* Krylov dimension reached */
  for (PetscInt j = 0; j < m; ++j) {
    /* W = J V_j ~ (G(X + delta V_j) - G(X)) / delta */
    PetscCall(VecWAXPY(Xp, delta, V[j], X));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, t, Xp, W));
    PetscCall(VecAXPY(W, -1.0, G0));
    PetscCall(VecScale(W, 1.0 / delta));
    /* Gram-Schmidt, twice */
    for (int pass = 0; pass < 2; ++pass) {
      PetscCall(VecMDot(W, j + 1, V, h.data()));
      for (PetscInt i = 0; i <= j; ++i) {
        H[i + j * (m + 1)] += h[i];
        h[i] = -h[i];
      }
      PetscCall(VecMAXPY(W, j + 1, h.data(), V));
    }
    PetscReal hnext;
    PetscCall(VecNorm(W, NORM_2, &hnext));
    if (!std::isfinite(hnext)) {
      *finite = PETSC_FALSE;
      break;
    }
    H[j + 1 + j * (m + 1)] = hnext;
    k                      = j + 1;
    PetscReal hnorm        = 0;
    for (PetscInt i = 0; i <= j + 1; ++i) hnorm = PetscMax(hnorm, PetscAbsScalar(H[i + j * (m + 1)]));
    if (hnext <= 1e-12 * hnorm || j + 1 == m) break; /* invariant subspace, or done */
    PetscCall(VecCopy(W, V[j + 1]));
    PetscCall(VecScale(V[j + 1], 1.0 / hnext));
  }
  PetscCall(VecDestroyVecs(m + 1, &V));
  PetscCall(VecDestroy(&G0));
  PetscCall(VecDestroy(&Xp));
  PetscCall(VecDestroy(&W));
  if (!*finite || k == 0) PetscFunctionReturn(0);

  /* Eigenvalues of the k x k Hessenberg matrix */
  std::vector<PetscScalar> A(k * k), work(8 * k + 8);
  std::vector<PetscReal>   wr(k), wi(k);
  for (PetscInt j = 0; j < k; ++j)
    for (PetscInt i = 0; i < k; ++i) A[i + j * k] = H[i + j * (m + 1)];
  PetscBLASInt n, lwork = (PetscBLASInt)work.size(), one = 1, info;
  PetscCall(PetscBLASIntCast(k, &n));
  PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &n, A.data(), &n, wr.data(), wi.data(), nullptr, &one, nullptr, &one, work.data(), &lwork, &info));
  if (info) {
    *finite = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < k; ++i) ritz.emplace_back(wr[i], wi[i]);
  PetscFunctionReturn(0);
}

static std::string LevelSplits(const TS_VSHMM *vs, PetscInt level)
{
  std::string s;
  for (PetscInt k = 0; k < vs->level_end[level]; ++k) s += (k ? ", " : "") + vs->splits[k].name;
  return s;
}

/* Estimates, for every level, the spectral radius of its field's Jacobian at the current state,
   the decaying or oscillating modes that limit an explicit step and the largest stable step of
   the inner Runge-Kutta method for them (infinite where none limits). */
PetscErrorCode TSVSHMMLevelSpectra_Private(TS ts)
{
  TS_VSHMM                         *vs      = (TS_VSHMM *)ts->data;
  const PetscInt                    nscales = (PetscInt)vs->level_end.size();
  const vshmm::StabilityFunction    R(*vs->tableau);
  std::vector<std::complex<double>> ritz;

  PetscFunctionBegin;
  const TS_VSHMM::Counter saved       = vs->counting;
  const PetscInt          saved_split = vs->nonfinite_split;
  const PetscReal         saved_time  = vs->nonfinite_time;
  vs->counting                        = TS_VSHMM::COUNT_STABILITY;
  vs->level_radius.assign(nscales, 0.0);
  vs->level_max_step.assign(nscales, PETSC_INFINITY);
  vs->level_worst.assign(nscales, 0.0);
  vs->level_limiting.assign(nscales, {});
  for (PetscInt level = 0; level < nscales; ++level) {
    PetscBool finite;
    PetscCall(LevelRitzValues(ts, level, ts->ptime, ts->vec_sol, ritz, &finite));
    if (!finite) {
      PetscCall(PetscInfo(ts, "Spectra at t = %g: the field of level %" PetscInt_FMT " is not finite near the state; skipped\n", (double)ts->ptime, level));
      continue;
    }
    for (const std::complex<double> &lambda : ritz) {
      vs->level_radius[level] = std::max(vs->level_radius[level], std::abs(lambda));
      /* A mode that grows at a rate comparable to its frequency is the problem's own growth, not a
         matter of step stability; slightly growing oscillations are judged against their own growth. */
      if (std::abs(lambda) == 0 || lambda.real() > kGrowingMode * std::abs(lambda)) continue;
      const double h = R.largestStableStep(lambda);
      if (h < vs->level_max_step[level]) {
        vs->level_max_step[level] = h;
        vs->level_worst[level]    = lambda;
      }
      vs->level_limiting[level].push_back(lambda);
    }
  }
  vs->spectra_time    = ts->ptime;
  vs->counting        = saved;
  vs->nonfinite_split = saved_split;
  vs->nonfinite_time  = saved_time;
  PetscFunctionReturn(0);
}

PetscErrorCode TSVSHMMCheckStability_Private(TS ts)
{
  TS_VSHMM                                  *vs      = (TS_VSHMM *)ts->data;
  MPI_Comm                                   comm    = PetscObjectComm((PetscObject)ts);
  const PetscInt                             nscales = (PetscInt)vs->level_end.size(), top = nscales - 1;
  const PetscReal                            t = ts->ptime, DeltaT = ts->time_step;
  const char                                *rk = vs->tableau->name.c_str();
  vshmm::StabilityFunction                   R(*vs->tableau);
  std::unique_ptr<vshmm::MesoscopicSchedule> schedule;

  PetscFunctionBegin;
  PetscCall(TSVSHMMLevelSpectra_Private(ts));
  vs->stability_checks++;
  if (vs->adapt) PetscFunctionReturn(0); /* the adaptive choice keeps every step stable itself */
  const PetscReal dt = vs->micro_dt > 0 ? vs->micro_dt : DeltaT / kDefaultMicroStepsPerMacroStep;
  PetscCall(TSVSHMMCreateSchedule_Private(ts, dt, schedule));
  for (PetscInt level = 0; level <= top; ++level) {
    const std::vector<std::complex<double>> &limiting = vs->level_limiting[level];
    const double                             radius = vs->level_radius[level], hmax = vs->level_max_step[level];
    const std::complex<double>               worst = vs->level_worst[level];
    if (limiting.empty()) continue;
    if (level == top) {
      PetscCheck(dt <= hmax * (1 + 1e-10), comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM stability check at t = %g: level %" PetscInt_FMT " (all splits: %s) is unstable with the micro step dt = %g: the estimated eigenvalue %g%+gi (spectral radius %g) needs dt <= %g for TSRK %s. Use a smaller -ts_vshmm_micro_dt, or -ts_vshmm_check_stability false to skip the check", (double)t, level,
                 LevelSplits(vs, level).c_str(), (double)dt, worst.real(), worst.imag(), radius, hmax, rk);
      PetscCall(PetscInfo(ts, "Stability check at t = %g: level %" PetscInt_FMT " (micro step %g): spectral radius %g, largest stable step %g\n", (double)t, level, (double)dt, radius, hmax));
      continue;
    }
    const PetscInt j     = level + 1;
    const double   hpeak = vshmm::levelAmplification(R, *schedule, DeltaT, (int)level, worst).largestStep;
    if (hpeak <= hmax) {
      PetscCall(PetscInfo(ts, "Stability check at t = %g: level %" PetscInt_FMT " (largest step h_%" PetscInt_FMT " = %g): spectral radius %g, largest stable step %g\n", (double)t, level, j, hpeak, radius, hmax));
      continue;
    }
    /* Beyond the limit near the kernel's peak: does the macro step damp every limiting mode, and
       does no mode grow too much on the way (the running product over the level's steps)? */
    double               logA = -PETSC_MAX_REAL, growth = 0;
    std::complex<double> grows = worst, peaks = worst;
    for (const std::complex<double> &lambda : limiting) {
      if (R.largestStableStep(lambda) >= hpeak) continue; /* every step of the level is stable for it */
      const vshmm::LevelAmplification a = vshmm::levelAmplification(R, *schedule, DeltaT, (int)level, lambda);
      if (a.logAmplification > logA) {
        logA  = a.logAmplification;
        grows = lambda;
      }
      if (a.largestGrowth > growth) {
        growth = a.largestGrowth;
        peaks  = lambda;
      }
    }
    if (logA <= 1e-8 && growth <= std::log(kMaxTransientGrowth)) { /* damped (or neutral) over a macro step, amplified a little near the kernel's peak */
      const double    peak_growth = std::abs(R(hpeak * worst));
      const PetscReal alpha_safe  = vs->savings_used[j - 1] * hmax / hpeak;
      vs->stability_warnings++;
      PetscCall(PetscInfo(ts, "Stability check at t = %g: level %" PetscInt_FMT ": the largest step h_%" PetscInt_FMT " = %g exceeds the stable step %g for the eigenvalue %g%+gi (growth %g per step there); within a macro step the mode grows by up to %g, over a macro step it changes by %g\n", (double)t, level, j, hpeak, hmax,
                          worst.real(), worst.imag(), peak_growth, std::exp(growth), std::exp(logA)));
      if (hpeak / hmax > 1.1 * vs->warned_ratio[level]) { /* first time, or clearly worse than last warned */
        vs->warned_ratio[level] = hpeak / hmax;
        PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: stability check at t = %g: level %" PetscInt_FMT " (splits %s): its largest step h_%" PetscInt_FMT " = %g exceeds the stable step %g of TSRK %s for the estimated eigenvalue %g%+gi (spectral radius %g), which grows by %g per step near the kernel's peak (by up to %g within a macro step); over a macro step the mode changes by a factor %g. Such transient growth can bias the slow variables. A savings factor alpha_%" PetscInt_FMT " <= %g (now %g) keeps every step stable. (Shown again only if it gets worse; -info shows every check.)\n", (double)t, level,
                                      LevelSplits(vs, level).c_str(), j, hpeak, hmax, rk, worst.real(), worst.imag(), radius, peak_growth, std::exp(growth), std::exp(logA), j, (double)alpha_safe, (double)vs->savings_used[j - 1]));
      }
      continue;
    }
    if (logA <= 1e-8) grows = peaks; /* damped in the end, but too much growth on the way */
    PetscReal alpha_max = 0;         /* the largest alpha_j that damps it, found by the core without touching the TS */
    try {
      alpha_max = vshmm::largestStableSavingsFactor(R, *vs->kernel, dt, std::vector<double>(vs->savings_used.begin(), vs->savings_used.end()), std::vector<int>(vs->subintervals_used.begin(), vs->subintervals_used.end()), DeltaT, (int)j, grows, kDampingTarget, kMaxTransientGrowth);
    } catch (const std::exception &e) {
      SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM: %s", e.what());
    }
    SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM stability check at t = %g: level %" PetscInt_FMT " (splits %s) is unstable with its mesoscopic step h_%" PetscInt_FMT ": its largest step %g times the estimated eigenvalue %g%+gi (spectral radius %g) lies outside the stability region of TSRK %s, whose largest stable step for it is %g; within a macro step the level's steps amplify that mode by up to %g (at most %g is tolerated) and over the macro step by %g. Use a savings factor alpha_%" PetscInt_FMT " <= %g (now %g) in -ts_vshmm_savings_factors, -ts_vshmm_adapt, or -ts_vshmm_check_stability false to skip the check", (double)t, level,
            LevelSplits(vs, level).c_str(), j, hpeak, grows.real(), grows.imag(), radius, rk, R.largestStableStep(grows), std::exp(growth), (double)kMaxTransientGrowth, std::exp(logA), j, (double)alpha_max, (double)vs->savings_used[j - 1]);
  }
  PetscFunctionReturn(0);
}
