/*
  The stability check of TSVSHMM: estimates the eigenvalues of each level's field at the current
  state and compares the level's steps with the stability region of the inner Runge-Kutta method.

  Eigenvalues: a few Arnoldi steps on the Jacobian of G_l = f_0 + ... + f_l, applied by finite
  differences of the split functions (no user Jacobian); the Ritz values approximate the extreme
  eigenvalues, the ones that limit an explicit step. For the separation check and
  -ts_vshmm_adapt, with component splits, also the block of each faster level's Jacobian on its
  own components: its slowest rate shows a scale that is a band of rates (vshmmadapt.cpp).

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
#include "coupling.hpp"

#include <petscblaslapack.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <string>

static constexpr PetscReal kOwnOscillation      = 2; /* a faster level's limiting oscillation at most this times the slower level's radius is the slower levels' own (SustainedMode()) */
static constexpr PetscInt  kArnoldiSteps        = 16;
static constexpr PetscInt  kRadiusIterations    = 2;    /* power steps of TSVSHMMLevelRadius_Private() per call */
static constexpr PetscReal kAmplitudeSpanChange = 0.05; /* an additive level's own amplitude rate counts where it changes the amplitude by this much over the run */
static constexpr PetscReal kDampingTarget       = 0.5;  /* what a suggested savings factor achieves over a macro step */
static constexpr PetscReal kGrowingMode         = 0.1;  /* Re lambda > this |lambda|: a growing mode, not checked */
static constexpr PetscReal kMaxTransientGrowth  = 100;  /* largest growth of a mode within a macro step that only warns */
static constexpr PetscReal kMaxCouplingGrowth   = 1.05; /* largest growth of a mode over a macro step from the coupling of the levels */
static constexpr PetscReal kFastEnergyGrowth    = 4;    /* growth of the fastest scale's oscillation energy that is warned about */
static constexpr PetscReal kCouplingTarget      = 1.01; /* what suggested savings factors achieve */
static constexpr PetscReal kNegligibleDrive     = 1e-3; /* of the fastest level's part of the state: a drive of the slower levels whose response is not estimated */
static constexpr PetscReal kUnstableShare       = 1e-6; /* the fastest level's part of the state below which it is at an equilibrium (CheckUnstableEquilibrium()) */
static constexpr PetscReal kUnstableSeparation  = 10;   /* an own mode growing this many times faster than the slower level's radius: an unstable equilibrium */
static constexpr PetscReal kFastQuantityRate    = 10;   /* a sampled quantity moving this many times faster than the slower level's radius along a level's own splits moves on that level's scale */
static constexpr PetscReal kSustainedDecay      = 3;    /* an oscillation whose amplitude decays by less than e^this over a macro step is sustained (more: a transient, a layer) */
static constexpr PetscReal kDifferenceStep      = 1e-6; /* relative perturbation of the state for an observable's derivative (central differences) */
static constexpr PetscReal kBeatSeparation      = 10;   /* a difference of two fast frequencies this many times slower than they are: a beat (vshmm::beatFrequencies()) */
static constexpr PetscInt  kMaxBeats            = 3;    /* the slowest beats probed at most (LevelBeats()) */
static constexpr PetscReal kAffineField         = 1e-8; /* a second difference below this of the field: the field is affine (LevelBeats()) */
static constexpr PetscReal kInvariantKrylov     = 1e-6; /* an Arnoldi residual below this of H's column: the Krylov space is invariant (to the forward differences' noise) */

/* A deterministic start vector for the Arnoldi and power iterations, the same on any number of
   ranks: 1 + sin(1.7 i + 0.3) / 2 at global index i. */
static PetscErrorCode DeterministicStart(Vec v)
{
  PetscInt     rstart, rend;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(v, &rstart, &rend));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = rstart; i < rend; ++i) a[i - rstart] = 1.0 + 0.5 * std::sin(1.7 * (double)i + 0.3);
  PetscCall(VecRestoreArray(v, &a));
  PetscFunctionReturn(0);
}

/* Arnoldi on the Jacobian of level l's field at (t, X), applied by finite differences of the level's
   field: an orthonormal basis V[0..k-1] of a Krylov space (V has m + 1 vectors, m = min(16, N),
   destroyed by the caller with VecDestroyVecs(m + 1, &V)) and the k x k Hessenberg matrix
   V^T J V (column-major, leading dimension m + 1, in H). k = 0 where the field is not finite near X. */
static PetscErrorCode LevelArnoldi(TS ts, PetscInt level, PetscReal t, Vec X, Vec **Vout, PetscInt *mout, std::vector<PetscScalar> &H, PetscInt *kout, PetscReal *delta_out, Vec mask = nullptr, Vec start = nullptr, PetscBool central = PETSC_FALSE, PetscBool own = PETSC_FALSE)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscInt  N;
  Vec      *V, G0, Xp, W;
  PetscReal xnorm;

  PetscFunctionBegin;
  PetscCall(VecGetSize(X, &N));
  const PetscInt m = PetscMin(kArnoldiSteps, N);
  PetscCall(VecDuplicateVecs(X, m + 1, &V));
  PetscCall(VecDuplicate(X, &G0));
  PetscCall(VecDuplicate(X, &Xp));
  PetscCall(VecDuplicate(X, &W));
  /* the field: the level's, or with `own` its own splits' only (those new to it) */
  const auto Field = [&](Vec Y, Vec G) -> PetscErrorCode {
    PetscFunctionBegin;
    if (own && level > 0) PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, level, t, Y, G));
    else PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, t, Y, G));
    PetscFunctionReturn(0);
  };

  /* The start vector given, or a deterministic one that does not depend on the number of ranks */
  if (start) PetscCall(VecCopy(start, V[0]));
  else PetscCall(DeterministicStart(V[0]));
  if (mask) PetscCall(VecPointwiseMult(V[0], V[0], mask));
  PetscReal beta;
  PetscCall(VecNormalize(V[0], &beta));

  PetscCall(VecNorm(X, NORM_2, &xnorm));
  /* forward differences at sqrt(eps) (1 + ||X||), central ones at cbrt(eps) (1 + ||X||): their
     truncation error is second order, and the rounding of X + delta V, which a field that varies
     fast about a point far from 0 turns into an error of (eps ||X|| / delta) |J|, is 400 times
     smaller (a stiff bond r' = p, p' = -w^2 (r - 1) at r = 1.0009, w = 1108, read an amplitude rate
     of 7.7e-4 at sqrt(eps), 7e-7 of w and above the central noise: "not separated") */
  const PetscReal delta = (central ? std::cbrt(PETSC_MACHINE_EPSILON) : std::sqrt(PETSC_MACHINE_EPSILON)) * (1.0 + xnorm);
  if (!central) PetscCall(Field(X, G0));

  H.assign((m + 1) * m, 0.0);
  std::vector<PetscScalar> h(m + 1);
  PetscInt                 k = 0; /* Krylov dimension reached */
  for (PetscInt j = 0; j < m; ++j) {
    /* W = J V_j ~ (G(X + delta V_j) - G(X)) / delta, or with central differences
       (G(X + delta V_j) - G(X - delta V_j)) / (2 delta) */
    PetscCall(VecWAXPY(Xp, delta, V[j], X));
    PetscCall(Field(Xp, W));
    if (central) {
      PetscCall(VecWAXPY(Xp, -delta, V[j], X));
      PetscCall(Field(Xp, G0));
      PetscCall(VecAXPY(W, -1.0, G0));
      PetscCall(VecScale(W, 0.5 / delta));
    } else {
      PetscCall(VecAXPY(W, -1.0, G0));
      PetscCall(VecScale(W, 1.0 / delta));
    }
    if (mask) PetscCall(VecPointwiseMult(W, W, mask)); /* the block of the masked components */
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
      k = 0;
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
  PetscCall(VecDestroy(&G0));
  PetscCall(VecDestroy(&Xp));
  PetscCall(VecDestroy(&W));
  *Vout = V;
  *mout = m;
  *kout = k;
  if (delta_out) *delta_out = delta;
  PetscFunctionReturn(0);
}

/* While alive, the split evaluations count as the stability check's, and a fault met on the way
   (a non-finite field near the state) is not reported as the solve's: the counter and the fault
   record are restored when it goes out of scope, on every return path. */
struct StabilityCounting {
  TS_VSHMM         *vs;
  TS_VSHMM::Counter counter;
  PetscInt          split;
  PetscReal         time;
  explicit StabilityCounting(TS_VSHMM *v) : vs(v), counter(v->counting), split(v->nonfinite_split), time(v->nonfinite_time) { vs->counting = TS_VSHMM::COUNT_STABILITY; }
  ~StabilityCounting()
  {
    vs->counting        = counter;
    vs->nonfinite_split = split;
    vs->nonfinite_time  = time;
  }
};

/* Eigenvalues of the k x k matrix A (column-major, leading dimension lda); finite = false if LAPACK fails. */
static PetscErrorCode Eigenvalues(PetscInt k, PetscInt lda, const PetscScalar *A, std::vector<std::complex<double>> &lambda, PetscBool *finite)
{
  std::vector<PetscScalar> B(k * k), work(8 * k + 8);
  std::vector<PetscReal>   wr(k), wi(k);

  PetscFunctionBegin;
  lambda.clear();
  for (PetscInt j = 0; j < k; ++j)
    for (PetscInt i = 0; i < k; ++i) B[i + j * k] = A[i + j * lda];
  PetscBLASInt n, lwork = (PetscBLASInt)work.size(), one = 1, info;
  PetscCall(PetscBLASIntCast(k, &n));
  PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &n, B.data(), &n, wr.data(), wi.data(), nullptr, &one, nullptr, &one, work.data(), &lwork, &info));
  *finite = info ? PETSC_FALSE : PETSC_TRUE;
  if (!info)
    for (PetscInt i = 0; i < k; ++i) lambda.emplace_back(wr[i], wi[i]);
  PetscFunctionReturn(0);
}

/* Ritz values of the Jacobian of level l's field at (t, X) (with a mask: of its block on the
   masked components). */
static PetscErrorCode LevelRitzValues(TS ts, PetscInt level, PetscReal t, Vec X, std::vector<std::complex<double>> &ritz, PetscBool *finite, Vec mask = nullptr, PetscBool central = PETSC_FALSE, PetscBool own = PETSC_FALSE, PetscReal *hmax = nullptr)
{
  Vec                     *V;
  PetscInt                 m, k;
  std::vector<PetscScalar> H;

  PetscFunctionBegin;
  ritz.clear();
  PetscCall(LevelArnoldi(ts, level, t, X, &V, &m, H, &k, NULL, mask, nullptr, central, own));
  PetscCall(VecDestroyVecs(m + 1, &V));
  *finite = k > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (hmax) { /* the largest entry of the Hessenberg matrix (vshmm::amplitudeRateNoise()) */
    *hmax = 0;
    for (PetscInt j = 0; j < k; ++j)
      for (PetscInt i = 0; i < k; ++i) *hmax = PetscMax(*hmax, PetscAbsScalar(H[i + j * (m + 1)]));
  }
  if (!k) PetscFunctionReturn(0);

  PetscCall(Eigenvalues(k, m + 1, H.data(), ritz, finite));
  PetscFunctionReturn(0);
}

/* Ritz values of the block of level l's Jacobian on the masked components at the present state
   (own: of its own splits' field only), and the fraction of |lambda| below which their real parts
   are noise. An oscillation whose amplitude rate forward differences cannot tell from their
   truncation error (a damping at 1e-7 of a rotation's frequency against van der Pol's 1.8e-8 of
   noise where its Jacobian is a rotation) has the Ritz values made again by central differences,
   whose noise is the rounding's (5e-10 on a linear rotation). */
static PetscErrorCode OwnBlockRitzValues(TS ts, PetscInt level, Vec mask, PetscBool own, std::vector<std::complex<double>> &ritz, PetscBool *finite, double *noise)
{
  PetscReal hmax, xnorm;
  double    largest = 0;

  PetscFunctionBegin;
  PetscCall(LevelRitzValues(ts, level, ts->ptime, ts->vec_sol, ritz, finite, mask, PETSC_FALSE, own, &hmax));
  PetscCall(VecNorm(ts->vec_sol, NORM_2, &xnorm));
  for (const std::complex<double> &lambda : ritz) largest = std::max(largest, std::abs(lambda));
  const vshmm::AmplitudeRateNoise levels = vshmm::amplitudeRateNoise(hmax, largest, xnorm);
  *noise                                 = levels.forward;
  if (*finite && vshmm::ambiguousAmplitudeRate(ritz, levels)) {
    PetscCall(LevelRitzValues(ts, level, ts->ptime, ts->vec_sol, ritz, finite, mask, PETSC_TRUE, own));
    *noise = levels.central;
    PetscCall(PetscInfo(ts, "Own block of level %" PetscInt_FMT " at t = %g: amplitude rates between %g and %g of the frequency, estimated again by central differences\n", level, (double)ts->ptime, levels.central, levels.forward));
  }
  PetscFunctionReturn(0);
}

/* Every level's Jacobian at (t, X) restricted to a Krylov space of the full field's Jacobian (the
   top level's): the Galerkin matrices V^T J_l V of the coupled stability analysis (core/coupling.hpp).
   Exact where the Krylov space is the whole space (states of up to 16 unknowns); otherwise it
   holds the full field's extreme modes, the fast ones. levels.n = 0 where a field is not finite. */
static PetscErrorCode CoupledLevelOperators(TS ts, PetscReal t, Vec X, vshmm::CoupledLevels &levels)
{
  TS_VSHMM                *vs      = (TS_VSHMM *)ts->data;
  const PetscInt           nscales = (PetscInt)vs->level_end.size(), top = nscales - 1;
  Vec                     *V, G0, Xp, W;
  PetscInt                 m, k;
  PetscReal                delta;
  std::vector<PetscScalar> H, h;

  PetscFunctionBegin;
  levels.n = 0;
  levels.jacobian.clear();
  PetscCall(LevelArnoldi(ts, top, t, X, &V, &m, H, &k, &delta));
  if (!k) {
    PetscCall(VecDestroyVecs(m + 1, &V));
    PetscFunctionReturn(0);
  }
  levels.jacobian.assign(nscales, std::vector<double>(k * k, 0.0));
  for (PetscInt j = 0; j < k; ++j)
    for (PetscInt i = 0; i < k; ++i) levels.jacobian[top][i + j * k] = PetscRealPart(H[i + j * (m + 1)]);
  PetscCall(VecDuplicate(X, &G0));
  PetscCall(VecDuplicate(X, &Xp));
  PetscCall(VecDuplicate(X, &W));
  h.resize(k);
  PetscBool finite = PETSC_TRUE;
  for (PetscInt level = 0; level < top && finite; ++level) {
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, t, X, G0));
    for (PetscInt j = 0; j < k; ++j) {
      PetscReal wn;
      PetscCall(VecWAXPY(Xp, delta, V[j], X));
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, t, Xp, W));
      PetscCall(VecAXPY(W, -1.0, G0));
      PetscCall(VecScale(W, 1.0 / delta));
      PetscCall(VecNorm(W, NORM_2, &wn));
      if (!std::isfinite(wn)) {
        finite = PETSC_FALSE;
        break;
      }
      PetscCall(VecMDot(W, k, V, h.data()));
      for (PetscInt i = 0; i < k; ++i) levels.jacobian[level][i + j * k] = PetscRealPart(h[i]);
    }
  }
  PetscCall(VecDestroyVecs(m + 1, &V));
  PetscCall(VecDestroy(&G0));
  PetscCall(VecDestroy(&Xp));
  PetscCall(VecDestroy(&W));
  levels.n = finite ? (int)k : 0;
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
  const StabilityCounting counting(vs);
  /* a level whose every mode grows at this state has no limiting mode here (a decaying level past
     a fold of its slow manifold, its fast variable on the repelling branch before it jumps): it
     keeps those of its last estimate, so that it is not taken for an oscillating level from here
     on (a medium van der Pol level of three, estimated past a fold, lost the fold checks and its
     savings for the rest of the run) */
  const std::vector<PetscReal>                         hmax     = vs->level_max_step;
  const std::vector<std::complex<double>>              worst    = vs->level_worst;
  const std::vector<std::vector<std::complex<double>>> limiting = vs->level_limiting;
  vs->level_radius.assign(nscales, 0.0);
  vs->level_max_step.assign(nscales, PETSC_INFINITY);
  vs->level_worst.assign(nscales, 0.0);
  vs->level_limiting.assign(nscales, {});
  vs->level_growth.assign(nscales, -PETSC_MAX_REAL);
  for (PetscInt level = 0; level < nscales; ++level) {
    PetscBool finite = PETSC_FALSE;
    PetscCall(LevelRitzValues(ts, level, ts->ptime, ts->vec_sol, ritz, &finite));
    if (!finite) {
      PetscCall(PetscInfo(ts, "Spectra at t = %g: the field of level %" PetscInt_FMT " is not finite near the state; skipped\n", (double)ts->ptime, level));
      continue;
    }
    for (const std::complex<double> &lambda : ritz) {
      vs->level_radius[level] = std::max(vs->level_radius[level], std::abs(lambda));
      vs->level_growth[level] = std::max(vs->level_growth[level], (PetscReal)lambda.real());
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
    if (vs->level_limiting[level].empty() && vs->level_radius[level] > 0 && (PetscInt)limiting.size() == nscales && !limiting[level].empty()) {
      vs->level_max_step[level] = hmax[level];
      vs->level_worst[level]    = worst[level];
      vs->level_limiting[level] = limiting[level];
    }
  }
  vs->spectra_time   = ts->ptime;
  vs->own_rates_time = PETSC_MIN_REAL; /* made again with these spectra where it is used */
  PetscFunctionReturn(0);
}

/* Level `level`'s spectral radius at the present state by kRadiusIterations steps of the power
   method on the Jacobian of its field f_0 + ... + f_level (forward differences), started from the
   vector the level's last call ended with: a cheap follower of a radius that moves with the
   solution between the levels' full spectra (TSVSHMMLevelSpectra_Private()), at the ends of
   -ts_vshmm_adapt's tries. 0 where the field is not finite near the state. Counted as the
   stability check's evaluations.
   speed (may be NULL): the 2-norm of the level's field at the state (evaluated anyway);
   growth (may be NULL): the last power step's Rayleigh quotient, the real part of the dominant
   eigenvalue once the vector has converged (positive: that mode grows at the state). */
PetscErrorCode TSVSHMMLevelRadius_Private(TS ts, PetscInt level, PetscReal *rho, PetscReal *speed, PetscReal *growth)
{
  TS_VSHMM       *vs = (TS_VSHMM *)ts->data;
  const PetscInt  K  = level;
  Vec             X  = ts->vec_sol, G0, Xp, W;
  PetscReal       xnorm, vnorm;
  const PetscReal t = ts->ptime;

  PetscFunctionBegin;
  *rho = 0;
  if (speed) *speed = 0;
  if (growth) *growth = 0;
  const StabilityCounting counting(vs);
  if ((PetscInt)vs->radius_vecs.size() <= level) vs->radius_vecs.resize(level + 1, nullptr);
  Vec &radius_vec = vs->radius_vecs[level];
  if (!radius_vec) {
    PetscCall(VecDuplicate(X, &radius_vec));
    PetscCall(DeterministicStart(radius_vec));
  }
  PetscCall(VecDuplicate(X, &G0));
  PetscCall(VecDuplicate(X, &Xp));
  PetscCall(VecDuplicate(X, &W));
  PetscCall(VecNorm(X, NORM_2, &xnorm));
  const PetscReal delta = std::sqrt(PETSC_MACHINE_EPSILON) * (1.0 + xnorm);
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, t, X, G0));
  if (speed) PetscCall(VecNorm(G0, NORM_2, speed));
  for (PetscInt it = 0; it < kRadiusIterations; ++it) {
    PetscCall(VecNormalize(radius_vec, &vnorm));
    if (!(vnorm > 0) || !std::isfinite(vnorm)) break;
    PetscCall(VecWAXPY(Xp, delta, radius_vec, X));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, t, Xp, W));
    PetscCall(VecAXPY(W, -1.0, G0));
    PetscCall(VecScale(W, 1.0 / delta));
    PetscCall(VecNorm(W, NORM_2, rho));
    if (growth) {
      PetscScalar vw;
      PetscCall(VecDot(W, radius_vec, &vw));
      *growth = PetscRealPart(vw);
    }
    if (!std::isfinite(*rho)) {
      *rho = 0;
      break;
    }
    PetscCall(VecCopy(W, radius_vec));
  }
  PetscCall(VecNorm(radius_vec, NORM_2, &vnorm));
  if (!(vnorm > 0) || !std::isfinite(vnorm)) PetscCall(VecDestroy(&radius_vec)); /* started again next time */
  PetscCall(VecDestroy(&G0));
  PetscCall(VecDestroy(&Xp));
  PetscCall(VecDestroy(&W));
  PetscFunctionReturn(0);
}

/* For a level of additive splits: a slow process in its own terms (its new splits' field
   G_l - G_{l-1}, which VSHMM slows; not the slower splits' terms it also evaluates) on the
   components they write (nonzero at the state or near it): the block of that field's Jacobian,
   as for component splits. Only an oscillation's amplitude rate counts (the block's other small
   Ritz values are not a slow process of the level alone). Sets vs->level_slowest[level]. */
static PetscErrorCode AdditiveOwnRate(TS ts, PetscInt level)
{
  TS_VSHMM                         *vs = (TS_VSHMM *)ts->data;
  Vec                               own, mask, Xp;
  std::vector<std::complex<double>> ritz;
  PetscInt                          n;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(ts->vec_sol, &own));
  PetscCall(VecDuplicate(ts->vec_sol, &mask));
  PetscCall(VecDuplicate(ts->vec_sol, &Xp));
  PetscCall(VecSet(mask, 0.0));
  PetscCall(VecCopy(ts->vec_sol, Xp));
  {
    PetscScalar *x;
    PetscInt     rstart;
    PetscCall(VecGetOwnershipRange(Xp, &rstart, NULL));
    PetscCall(VecGetLocalSize(Xp, &n));
    PetscCall(VecGetArray(Xp, &x));
    for (PetscInt i = 0; i < n; ++i) x[i] += 1e-3 * (1.0 + PetscAbsScalar(x[i])) * (1.0 + 0.5 * std::sin(1.7 * (double)(rstart + i) + 0.3));
    PetscCall(VecRestoreArray(Xp, &x));
  }
  for (Vec Y : {ts->vec_sol, Xp}) {
    const PetscScalar *g;
    PetscScalar       *w;
    PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, level, ts->ptime, Y, own));
    PetscCall(VecGetArrayRead(own, &g));
    PetscCall(VecGetArray(mask, &w));
    for (PetscInt i = 0; i < n; ++i)
      if (g[i] != 0.0) w[i] = 1.0;
    PetscCall(VecRestoreArray(mask, &w));
    PetscCall(VecRestoreArrayRead(own, &g));
  }
  PetscBool finite = PETSC_FALSE;
  double    noise;
  PetscCall(OwnBlockRitzValues(ts, level, mask, PETSC_TRUE, ritz, &finite, &noise));
  double rate = finite ? vshmm::slowestAmplitudeRate(ritz, noise) : 0.0;
  if (rate * TSVSHMMAmplitudeSpan_Private(ts) < kAmplitudeSpanChange) rate = 0; /* changes the amplitude by less than kAmplitudeSpanChange over the run */
  if (rate > 0) vs->level_slowest[level] = rate;
  PetscCall(PetscInfo(ts, "Own terms of level %" PetscInt_FMT " (additive splits) at t = %g: slowest amplitude rate %g (0: none)\n", level, (double)ts->ptime, rate));
  PetscCall(VecDestroy(&own));
  PetscCall(VecDestroy(&mask));
  PetscCall(VecDestroy(&Xp));
  PetscFunctionReturn(0);
}

/* The slowest rate of each faster level's own components (component splits only), at the present
   state (ts->vec_sol at ts->ptime, as the levels' spectra): Arnoldi on the block of the level's Jacobian on the components its new
   splits write. A scale that is a band of rates (relaxation rates 10 to 1000) has its slowest one
   here, which the level's spectral radius does not show; so has a transport block (a fine
   finite-volume region: its eigenvalues are all fast, but a perturbation crosses the region in
   the slow time, and the Krylov space sees that as small Ritz values); so has an oscillation whose
   amplitude decays or grows slowly (vshmm::slowestRate(): a damping at rate 0.1 of a rotation at
   1e4 is a slow process inside the fast level, which VSHMM slows with the level). Made only where it is used:
   the separation check and -ts_vshmm_adapt's error model (vshmmadapt.cpp). With them, each level's
   share of the state norm (its own components'), by which the micro step's amplitude bound weighs
   the fastest level's oscillations. */
/* W = J_K V, the Jacobian of the fastest level's field G_K at X applied to V by a forward difference
   from G = G_K(X). */
/* The same for level K's field (G = its field at X). */
static PetscErrorCode LevelJacobianApply(TS ts, PetscInt K, Vec X, Vec G, Vec V, Vec Xp, Vec W)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal xnorm, vnorm;

  PetscFunctionBegin;
  PetscCall(VecNorm(X, NORM_2, &xnorm));
  PetscCall(VecNorm(V, NORM_2, &vnorm));
  if (!(vnorm > 0)) {
    PetscCall(VecSet(W, 0.0));
    PetscFunctionReturn(0);
  }
  const PetscReal delta = std::sqrt(PETSC_MACHINE_EPSILON) * (1.0 + xnorm) / vnorm;
  PetscCall(VecWAXPY(Xp, delta, V, X));
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, ts->ptime, Xp, W));
  PetscCall(VecAXPY(W, -1.0, G));
  PetscCall(VecScale(W, 1.0 / delta));
  PetscFunctionReturn(0);
}

static PetscErrorCode FastestJacobianApply(TS ts, Vec X, Vec G, Vec V, Vec Xp, Vec W)
{
  return LevelJacobianApply(ts, (PetscInt)((TS_VSHMM *)ts->data)->level_end.size() - 1, X, G, V, Xp, W);
}

/* Whether any of level l's limiting modes (its spectra's, vs->level_limiting) oscillates. */
static bool LimitingModesOscillate(const TS_VSHMM *vs, PetscInt l)
{
  if ((PetscInt)vs->level_limiting.size() <= l) return false;
  for (const std::complex<double> &lambda : vs->level_limiting[l])
    if (vshmm::oscillates(lambda)) return true;
  return false;
}

static constexpr PetscReal kOffCentre = 2; /* a level's own field at the centre its oscillation is taken about, this many times its field at the state: not its centre */

/* Level K's oscillation's part of the state X, P: with additive splits -J_K G_K(X) / rho_K^2. With
   G_K(X) = J_K (X - C) near the centre C the level oscillates about, that is -J_K^2 (X - C) /
   rho_K^2: the oscillating modes at rate rho_K, the slower ones weighed by their squared frequency
   over rho_K^2, the slow ones not at all. The displacement from the centre, not from 0: a stiff
   bond r' = p, p' = -w^2 (r - 1) oscillates about r = 1, and -J_K^2 X / rho_K^2 (the form before
   2026-11-28) took r for its amplitude, a thousand times the bond's, whose phases crossed r = 0
   and read a frequency of 5.7e6 and a drive of 6e6: the micro step bounded 100 times below what
   RK4 needs there (docs/accuracy.md section 39). With component splits (mask) the level's own
   components themselves, every mode at its own weight (a quartet of rotations at 1000 to 2850: its
   beats are probed at their relative amplitudes) and exact for a nonlinear cycle about 0 (van der
   Pol's), unless the level's own field at that centre (X less them) is more than kOffCentre times
   its field at X, or not finite there: then, on the own components, the displacement (the same bond with component
   splits; one evaluation more, for oscillating levels only). G: level K's field at X; Xp a work
   vector. */
static PetscErrorCode LevelOscillationPart(TS ts, PetscInt K, Vec mask, Vec G, Vec Xp, Vec P)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  const PetscReal rho = vs->level_radius[K];
  if (mask) {
    /* the own components, an oscillation about 0 (a rotation, a limit cycle: their field vanishes
       there), unless the field at that centre moves them faster than at X: then the displacement */
    PetscCall(VecPointwiseMult(P, mask, ts->vec_sol));
    if (!LimitingModesOscillate(vs, K)) PetscFunctionReturn(0);
    PetscReal g, gc;
    PetscCall(VecWAXPY(Xp, -1.0, P, ts->vec_sol));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, ts->ptime, Xp, P)); /* the field at X less its own components */
    PetscCall(VecPointwiseMult(P, mask, P));
    PetscCall(VecNorm(P, NORM_2, &gc));
    PetscCall(VecPointwiseMult(P, mask, G));
    PetscCall(VecNorm(P, NORM_2, &g));
    PetscCall(VecPointwiseMult(P, mask, ts->vec_sol));
    if (std::isfinite(gc) && gc <= kOffCentre * g) PetscFunctionReturn(0); /* (not finite there, with a 1 / r term: no centre either) */
    PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT " oscillates about a centre away from 0 (its own field there %g, at the state %g): its oscillation's part is the displacement -J G / rho^2\n", K, (double)gc, (double)g));
  }
  PetscCall(LevelJacobianApply(ts, K, ts->vec_sol, G, G, Xp, P)); /* J G */
  PetscCall(VecScale(P, -1.0 / (rho * rho)));
  if (mask) PetscCall(VecPointwiseMult(P, mask, P));
  PetscFunctionReturn(0);
}

/* The largest slowest rate (vshmm::slowestRate()) of level `level`'s own block (mask) at the three
   phases X - P + cos(theta) P + sin(theta) Q, theta a quarter, half and three quarters turn, of a
   nonlinear oscillation, and `slowest` (its rate at X): a slow process inside the level is slow at
   every phase, a phase's own Jacobian is not (FastestLevelPlane(), TSVSHMMLevelOwnSlowest_Private()). */
static PetscErrorCode OwnSlowestOverPhases(TS ts, PetscInt level, Vec mask, Vec P, Vec Q, PetscReal *slowest)
{
  Vec X0 = ts->vec_sol, Xt;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(X0, &Xt));
  for (int quarter = 1; quarter < 4; ++quarter) {
    const PetscReal                   c = quarter == 2 ? -1 : 0, q = quarter == 1 ? 1 : quarter == 3 ? -1 : 0;
    std::vector<std::complex<double>> ritz;
    PetscBool                         ok = PETSC_FALSE;
    double                            noise;
    PetscErrorCode                    ierr;
    PetscCall(VecWAXPY(Xt, -1.0, P, X0));
    PetscCall(VecAXPBYPCZ(Xt, c, q, 1.0, P, Q));
    ts->vec_sol = Xt;
    ierr        = OwnBlockRitzValues(ts, level, mask, PETSC_FALSE, ritz, &ok, &noise);
    ts->vec_sol = X0;
    PetscCall(ierr);
    if (ok) *slowest = PetscMax(*slowest, vshmm::slowestRate(ritz, noise));
  }
  PetscCall(VecDestroy(&Xt));
  PetscFunctionReturn(0);
}

static constexpr PetscReal kNonlinearPlane = 0.1; /* the four phases' plane matrices differ by more than this of their mean: a nonlinear oscillation */

/* The fastest level's oscillation as a whole, on its plane (P, Q of FastestLevelDrive(), made
   orthonormal): the 2 x 2 matrix of J_K on the plane at four phases of it (X - P + cos(theta) P +
   sin(theta) Q), and their mean M. For a linear level (a rotation, a damped one) the four are the
   same. For a nonlinear one the Jacobian at the present state says little: the fastest level of a
   van der Pol oscillator, q' = p / eps, p' = (-q + (x - q^2) p) / eps, has the trace (x - q^2) / eps,
   which changes sign along the cycle, and at some phases real eigenvalues, one of them growing:
   at one state it seems to decay, at the next to oscillate, its amplitude rate (|Re lambda|) near
   0 at another. Where the four differ by more than kNonlinearPlane of M (vs->fastest_nonlinear,
   vs->fastest_mean_mode: M's eigenvalue) and M oscillates, the level oscillates (LevelDecays() in
   vshmmadapt.cpp; a mean that does not oscillate leaves the Jacobian at the state to judge: the
   four phases are an ellipse about the origin of the level's own components, not a chaotic
   attractor), and the slowest own rate of its own components is the largest of their slowest
   rates at the four phases (a slow process inside the level is slow at every phase). And by Liouville's formula the mean trace over
   a limit cycle is the rate at which its amplitude is attracted (the other Floquet exponent, the
   phase's, is 0; for a linear damped rotation half of it is the damping): vs->fastest_restore =
   -tr(M) / 2 where positive. A micro step's amplitude error then settles at its rate over that one
   instead of adding up over the run (AccurateMicroStep() in vshmmadapt.cpp). 12 evaluations of the
   fastest level (24 where nonlinear: a second pass at the mean's frequency; and with component
   splits three more estimates of its own block's Ritz values). docs/accuracy.md section 25. */
static PetscErrorCode FastestLevelPlane(TS ts, Vec P, Vec Q0, PetscReal rho, Vec mask)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec       E1, E2, Xt, Gt, Xp, W, Q;
  PetscReal n1, n2, M[4][4], mean[4];
  PetscBool finite;
  PetscReal omega = rho; /* the frequency Q was made with (FastestLevelDrive(): the level's radius) */

  PetscFunctionBegin;
  vs->fastest_restore   = 0;
  vs->fastest_nonlinear = PETSC_FALSE;
  vs->fastest_own_phase = 0;
  PetscCall(VecDuplicate(ts->vec_sol, &Q));
  PetscCall(VecDuplicate(ts->vec_sol, &E1));
  PetscCall(VecDuplicate(ts->vec_sol, &E2));
  PetscCall(VecDuplicate(ts->vec_sol, &Xt));
  PetscCall(VecDuplicate(ts->vec_sol, &Gt));
  PetscCall(VecDuplicate(ts->vec_sol, &Xp));
  PetscCall(VecDuplicate(ts->vec_sol, &W));
  PetscCall(VecCopy(Q0, Q));
  for (int pass = 0; pass < 2; ++pass) { /* a second pass at the mean eigenvalue's frequency (below) */
    finite              = PETSC_TRUE;
    vs->fastest_restore = 0;
    for (PetscReal &m : mean) m = 0;
    PetscCall(VecCopy(P, E1));
    PetscCall(VecNorm(E1, NORM_2, &n1));
    PetscCall(VecCopy(Q, E2));
    if (n1 > 0 && std::isfinite(n1)) {
      PetscScalar c;
      PetscCall(VecScale(E1, 1.0 / n1));
      PetscCall(VecDot(E2, E1, &c));
      PetscCall(VecAXPY(E2, -c, E1));
    }
    PetscCall(VecNorm(E2, NORM_2, &n2));
    if (!(n1 > 0 && std::isfinite(n1) && n2 > PETSC_SQRT_MACHINE_EPSILON * n1 && std::isfinite(n2))) { /* no plane: no oscillation */
      vs->fastest_nonlinear = PETSC_FALSE;
      vs->fastest_restore   = 0;
      break;
    }
    PetscCall(VecScale(E2, 1.0 / n2));
    const StabilityCounting counting(vs);
    const PetscInt          K = (PetscInt)vs->level_end.size() - 1;
    for (int quarter = 0; quarter < 4; ++quarter) {
      const PetscReal c = quarter == 0 ? 1 : quarter == 2 ? -1 : 0, q = quarter == 1 ? 1 : quarter == 3 ? -1 : 0;
      PetscScalar     d[4];
      PetscCall(VecWAXPY(Xt, -1.0, P, ts->vec_sol)); /* X - P + cos(theta) P + sin(theta) Q */
      PetscCall(VecAXPBYPCZ(Xt, c, q, 1.0, P, Q));
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, ts->ptime, Xt, Gt));
      PetscCall(FastestJacobianApply(ts, Xt, Gt, E1, Xp, W));
      PetscCall(VecDot(W, E1, &d[0])); /* (E1, J E1) */
      PetscCall(VecDot(W, E2, &d[2])); /* (E2, J E1) */
      PetscCall(FastestJacobianApply(ts, Xt, Gt, E2, Xp, W));
      PetscCall(VecDot(W, E1, &d[1])); /* (E1, J E2) */
      PetscCall(VecDot(W, E2, &d[3])); /* (E2, J E2) */
      for (int i = 0; i < 4; ++i) {
        M[quarter][i] = PetscRealPart(d[i]);
        mean[i] += M[quarter][i] / 4;
        finite = (finite && std::isfinite(M[quarter][i])) ? PETSC_TRUE : PETSC_FALSE;
      }
    }
    if (finite) {
      PetscReal size = 0, spread = 0;
      for (int i = 0; i < 4; ++i) size += mean[i] * mean[i];
      for (int quarter = 0; quarter < 4; ++quarter) {
        PetscReal e = 0;
        for (int i = 0; i < 4; ++i) e += (M[quarter][i] - mean[i]) * (M[quarter][i] - mean[i]);
        spread = PetscMax(spread, e);
      }
      const PetscReal trace = mean[0] + mean[3], det = mean[0] * mean[3] - mean[1] * mean[2], disc = trace * trace / 4 - det;
      vs->fastest_mean_mode = disc < 0 ? std::complex<double>(trace / 2, std::sqrt(-disc)) : std::complex<double>(trace / 2 + (trace < 0 ? -1 : 1) * std::sqrt(disc), 0);
      /* a trace within the forward differences' noise (a rotation, a Hamiltonian level: 0 at every phase) restores nothing */
      if (-trace / 2 > vshmm::kAmplitudeRateNoise * std::abs(vs->fastest_mean_mode)) vs->fastest_restore = -trace / 2;
      vs->fastest_nonlinear = (size > 0 && spread > kNonlinearPlane * kNonlinearPlane * size) ? PETSC_TRUE : PETSC_FALSE;
      PetscCall(PetscInfo(ts, "The fastest level's oscillation on its plane (a quarter turn at frequency %g), mean over four phases: trace %g, eigenvalue %g%+gi (amplitude restored at rate %g); the phases differ by %g of it%s\n", (double)omega, (double)trace,
                          (double)vs->fastest_mean_mode.real(), (double)vs->fastest_mean_mode.imag(), (double)vs->fastest_restore, (double)(size > 0 ? std::sqrt(spread / size) : 0), vs->fastest_nonlinear ? ": nonlinear, judged by the mean" : ""));
    }
    /* the quarter turn Q = G_K(X) / omega is made with the level's radius; a nonlinear oscillation's
     frequency (the mean eigenvalue's) can differ from it by a factor 2 or more, and the four phases
     then miss the cycle: once more with that frequency */
    const PetscReal freq = vs->fastest_mean_mode.imag();
    if (!(finite && vs->fastest_nonlinear && freq > 0 && std::isfinite(freq) && PetscAbsReal(freq - omega) > 0.1 * omega)) break;
    PetscCall(VecScale(Q, omega / freq));
    omega = freq;
  }
  PetscCall(VecDestroy(&E1));
  PetscCall(VecDestroy(&E2));
  PetscCall(VecDestroy(&Xt));
  PetscCall(VecDestroy(&Gt));
  PetscCall(VecDestroy(&Xp));
  PetscCall(VecDestroy(&W));
  if (vs->fastest_nonlinear && mask && vshmm::oscillates(vs->fastest_mean_mode)) PetscCall(OwnSlowestOverPhases(ts, (PetscInt)vs->level_end.size() - 1, mask, P, Q, &vs->fastest_own_phase)); /* at the other three phases */
  PetscCall(VecDestroy(&Q));
  PetscFunctionReturn(0);
}

/* Whether level L's modes may beat at all, without evaluations: its limiting modes hold two
   distinct fast frequencies a beat apart, and the problem is not declared linear (a linear field
   holds no product of the modes). */
static PetscErrorCode MayBeat(TS ts, PetscInt L, PetscBool *may)
{
  TS_VSHMM     *vs = (TS_VSHMM *)ts->data;
  TSProblemType type;

  PetscFunctionBegin;
  *may = PETSC_FALSE;
  if (L < 1 || !((PetscInt)vs->level_radius.size() > L && vs->level_radius[L] > 0) || (PetscInt)vs->level_limiting.size() <= L) PetscFunctionReturn(0);
  /* a beat's two frequencies both limit the level's step; a triad's or a quartet's need not (the
     slowest of its modes may be far below the level's radius): any fast oscillation of the level
     may hold one */
  bool fast = false;
  for (const std::complex<double> &lambda : vs->level_limiting[L]) fast = fast || (vshmm::oscillates(lambda) && std::abs(lambda) > vs->level_radius[L] / kBeatSeparation);
  if (!fast) PetscFunctionReturn(0);
  PetscCall(TSGetProblemType(ts, &type));
  *may = type == TS_LINEAR ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Two oscillations of level K's own splits whose frequencies differ by g make, in any product of
   them that a slower level's field holds, a beat at frequency g: a slow process inside the level.
   Savings slow it with the level, r_0 ... r_{K-1} times, and where it then turns less than once per
   macro step the slow steps see one relative phase of it, which coarser comparisons see as well:
   two fast rotations 10 apart (x' = -x + q1 q2, frequencies 1000 and 1010) ended 3-311 tolerances
   off, silently at 1e-1 (docs/accuracy.md section 26). The own splits' modes, not the whole
   level's: a frequency that a slower split shifts (the paper's oscillators, whose medium split
   moves one rotation by 1 / eps) turns in that split's steps too. For each of the kMaxBeats slowest
   beats of the modes in the oscillation's part of the state P (vshmm::beatFrequencies() on the Ritz
   values of an Arnoldi space of the own splits' Jacobian started at P, on the level's own
   components where mask is given), the slower levels' field averaged over eight common phases (each
   mode turned in its own plane by the same angle, vshmm::modesTurned(): each one's own oscillation
   averaged out, whatever its frequency) at four relative phases of the beat (the modes above its
   middle frequency a quarter turn further each time), less their mean, in vs->beat_phase. Only
   where the Arnoldi space is invariant (a few fast modes; P in a band wider than the space is not
   probed). Three or four modes whose frequencies make a slow combination while every pair's
   difference is fast (a triad wa + wb - wc, a quartet wa + wb - wc - wd, and the like with a mode
   taken twice or three times: vshmm::slowCombinations()) hold, in a product of them, the same kind
   of slow process: probed alike at four phases of that combination, averaged over the turns of the
   modes that leave it unchanged (x' = -x + 4 q1 q2 q3 at 1000, 1500 and 2490 ended 5.8 and 38.8
   tolerances off at 1e-1 and 1e-2 before: docs/accuracy.md section 26; x' = -x + 8 q1 q2 q3 q4 at
   1000, 1500, 2350 and 2840, 4.1 tolerances at 1e-1: section 34). What
   that does to the observables is measured by TSVSHMMAdaptBeats_Private(), and for fixed savings
   by the separation check (CheckBeats()). */
static PetscErrorCode LevelBeats(TS ts, PetscInt K, Vec P, Vec mask)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data; /* K: the level looked at (its modes beat; level K - 1's field holds their products) */
  PetscInt  N, m, k;
  Vec      *V, Y, Xs, F, Mean;
  PetscReal beta;

  PetscFunctionBegin;
  PetscBool may;
  PetscCall(MayBeat(ts, K, &may));
  if (!may) PetscFunctionReturn(0);
  PetscCall(VecNorm(P, NORM_2, &beta));
  if (!(beta > 0)) PetscFunctionReturn(0);
  /* nor where the slower field is affine in the oscillation's part (its second difference along P
     at the rounding's level: no product of the modes in it) */
  {
    Vec       F0, F1, F2, Xs;
    PetscReal d, n0, n1;
    PetscCall(VecDuplicate(ts->vec_sol, &F0));
    PetscCall(VecDuplicate(ts->vec_sol, &F1));
    PetscCall(VecDuplicate(ts->vec_sol, &F2));
    PetscCall(VecDuplicate(ts->vec_sol, &Xs));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, ts->vec_sol, F0));
    PetscCall(VecWAXPY(Xs, -0.5, P, ts->vec_sol));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, Xs, F1));
    PetscCall(VecAXPY(Xs, -0.5, P)); /* (not X - 2 P: along a line through P = 0, a product of three modes, odd, has no second difference there) */
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, Xs, F2));
    PetscCall(VecNorm(F0, NORM_2, &n0));
    PetscCall(VecNorm(F1, NORM_2, &n1));
    PetscCall(VecAXPBYPCZ(F2, 1.0, -2.0, 1.0, F0, F1)); /* F(X) - 2 F(X - P / 2) + F(X - P) */
    PetscCall(VecNorm(F2, NORM_2, &d));
    PetscCall(VecDestroy(&F0));
    PetscCall(VecDestroy(&F1));
    PetscCall(VecDestroy(&F2));
    PetscCall(VecDestroy(&Xs));
    if (std::isfinite(d) && d <= kAffineField * (n0 + n1)) PetscFunctionReturn(0);
  }
  std::vector<PetscScalar> H;
  PetscCall(VecGetSize(ts->vec_sol, &N));
  PetscCall(LevelArnoldi(ts, K, ts->ptime, ts->vec_sol, &V, &m, H, &k, NULL, mask, P, PETSC_FALSE, PETSC_TRUE));
  /* the modes of the Krylov space, with their eigenvectors */
  std::vector<PetscScalar>          B(k * k), vr(k * k), work(8 * k + 8);
  std::vector<PetscReal>            wr(k), wi(k);
  std::vector<std::complex<double>> ritz;
  PetscBLASInt                      n, lwork = (PetscBLASInt)work.size(), one = 1, info = 1;
  if (k > 0) {
    for (PetscInt j = 0; j < k; ++j)
      for (PetscInt i = 0; i < k; ++i) B[i + j * k] = H[i + j * (m + 1)];
    PetscCall(PetscBLASIntCast(k, &n));
    PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "V", &n, B.data(), &n, wr.data(), wi.data(), nullptr, &one, vr.data(), &n, work.data(), &lwork, &info));
  }
  if (!info)
    for (PetscInt i = 0; i < k; ++i) ritz.emplace_back(wr[i], wi[i]);
  if (!info) {
    /* the slowest difference of the fast frequencies that is no beat yet, watched from spectra to
       spectra: where it falls, the next spectra are estimated before it would become a beat
       (TSVSHMMBeatApproaching_Private()) */
    PetscReal watch = 0; /* kBeatSeparation g / (the slower frequency of the pair): a beat below 1 */
    for (const vshmm::Beat &b : vshmm::beatFrequencies(ritz, vs->level_radius[K] / kBeatSeparation, 1.0)) {
      const PetscReal r = b.frequency * kBeatSeparation / b.lower;
      if (r >= 1 && (!(watch > 0) || r < watch)) watch = r;
    }
    vs->beat_watch.resize(vs->level_end.size());
    TS_VSHMM::BeatWatch &w = vs->beat_watch[K];
    if (w.t < ts->ptime) { /* (looked at twice at one time: the earlier record stays) */
      w.r_before = w.r;
      w.t_before = w.t;
    }
    w.r = watch;
    w.t = ts->ptime;
  }
  std::vector<vshmm::Beat>        beats = info ? std::vector<vshmm::Beat>() : vshmm::beatFrequencies(ritz, vs->level_radius[K] / kBeatSeparation, kBeatSeparation);
  std::vector<vshmm::Combination> combinations; /* of three modes (triads) and four (quartets) */
  for (int order = 3; order <= 4 && !info; ++order) {
    const std::vector<vshmm::Combination> found = vshmm::slowCombinations(ritz, vs->level_radius[K] / kBeatSeparation, kBeatSeparation, order);
    combinations.insert(combinations.end(), found.begin(), found.begin() + std::min(found.size(), (size_t)kMaxBeats));
  }
  PetscReal hnorm = 0;
  for (PetscInt i = 0; i < k; ++i) hnorm = PetscMax(hnorm, PetscAbsScalar(H[i + (k - 1) * (m + 1)]));
  if ((!beats.empty() || !combinations.empty()) && k == m && m < N && !(PetscAbsScalar(H[k + (k - 1) * (m + 1)]) <= kInvariantKrylov * hnorm)) {
    PetscReal slowest = beats.empty() ? PETSC_MAX_REAL : beats[0].frequency;
    for (const vshmm::Combination &c : combinations) slowest = PetscMin(slowest, c.frequency);
    PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT "'s own splits' modes beat at %g (the slowest difference or combination of three or four of their frequencies), but its oscillation does not lie in an invariant Krylov space of %" PetscInt_FMT " vectors: not probed\n", K, (double)slowest, m));
    beats.clear();
    combinations.clear();
  }
  if (beats.empty() && combinations.empty()) {
    PetscCall(VecDestroyVecs(m + 1, &V));
    PetscFunctionReturn(0);
  }
  if ((PetscInt)beats.size() > kMaxBeats) beats.resize(kMaxBeats);
  /* each slow process probed: its frequency g, the number of common phases averaged over, and the
     angle of a mode of frequency w at common phase i and the process's relative phase j. A beat
     (two modes): every mode turned by i / 8 of a turn, those above the pair's middle frequency a
     quarter turn j further. A combination sum c_n w_n (three or four modes): the modes of each
     frequency but one (d, whose coefficient is +-1) turned by free angles theta_n, on a grid of
     8 (one or two free angles) or 4 (three) per angle, whose digits i counts through; those at
     w_d by c_d (-j / 4 of a turn - sum c_n theta_n), so that the combination's phase is -j quarter
     turns at every i; the modes of no frequency of it by the first free angle. Each mode's own
     phase and every other product of the modes of degree up to 5 average out (a triad wa + wb -
     wc: theta_c = alpha + beta + j / 4 of a turn, 64 phases). */
  struct Probe {
    double                                  g;
    int                                     samples;
    std::function<double(double, int, int)> angle;
  };
  std::vector<Probe> probes;
  const auto         same = [](double w, double f) { return std::fabs(w - f) <= vshmm::kDistinctFrequencies * f; };
  for (const vshmm::Beat &beat : beats) {
    const double split = 0.5 * (beat.lower + beat.upper);
    probes.push_back({beat.frequency, 8, [split](double w, int i, int j) { return i * PETSC_PI / 4 + (w > split ? j * PETSC_PI / 2 : 0.0); }});
  }
  for (const vshmm::Combination &comb : combinations) {
    size_t d = comb.c.size() - 1;
    while (std::abs(comb.c[d]) != 1) --d;                                  /* (slowCombinations() gives a coefficient +-1) */
    const int angles = (int)comb.c.size() - 1, grid = angles <= 2 ? 8 : 4; /* free angles, and the phases of each */
    int       samples = 1;
    for (int f = 0; f < angles; ++f) samples *= grid;
    probes.push_back({comb.frequency, samples, [comb, d, grid, same](double w, int i, int j) {
                        double theta0 = 0, sum = 0, mine = 0;
                        bool   found = false;
                        for (size_t n = 0, f = 0; n < comb.c.size(); ++n) {
                          if (n == d) continue;
                          const double theta = (i % grid) * 2 * PETSC_PI / grid;
                          i /= grid;
                          if (f++ == 0) theta0 = theta;
                          sum += comb.c[n] * theta;
                          if (same(w, comb.w[n])) mine = theta, found = true;
                        }
                        if (same(w, comb.w[d])) return comb.c[d] * (-j * PETSC_PI / 2 - sum);
                        return found ? mine : theta0;
                      }});
  }
  std::sort(probes.begin(), probes.end(), [](const Probe &a, const Probe &b) { return a.g < b.g; });
  if ((PetscInt)probes.size() > kMaxBeats) probes.resize(kMaxBeats);
  const std::vector<double> vrk(vr.begin(), vr.end());
  PetscCall(VecDuplicate(ts->vec_sol, &Y));
  PetscCall(VecDuplicate(ts->vec_sol, &Xs));
  PetscCall(VecDuplicate(ts->vec_sol, &F));
  PetscCall(VecDuplicate(ts->vec_sol, &Mean));
  while (vs->beat_phase.size() < 4 * (vs->beat_omega.size() + probes.size())) {
    vs->beat_phase.push_back(nullptr);
    PetscCall(VecDuplicate(ts->vec_sol, &vs->beat_phase.back()));
  }
  for (const Probe &probe : probes) {
    const size_t b      = vs->beat_omega.size();
    bool         finite = true;
    PetscCall(VecSet(Mean, 0.0));
    for (int j = 0; j < 4 && finite; ++j) { /* the combination a quarter turn further each time */
      Vec avg = vs->beat_phase[4 * b + j];
      PetscCall(VecSet(avg, 0.0));
      for (int i = 0; i < probe.samples && finite; ++i) { /* the common phases */
        const std::vector<double> y = vshmm::modesTurned(vrk, ritz, (int)k, [&](double w) { return probe.angle(w, i, j); });
        finite                      = !y.empty();
        if (!finite) break;
        std::vector<PetscScalar> c(y.begin(), y.end());
        for (PetscScalar &v : c) v *= beta;
        PetscCall(VecSet(Y, 0.0));
        PetscCall(VecMAXPY(Y, k, c.data(), V));
        if (mask) PetscCall(VecPointwiseMult(Y, Y, mask));
        PetscCall(VecWAXPY(Xs, -1.0, P, ts->vec_sol)); /* X - P + P turned */
        PetscCall(VecAXPY(Xs, 1.0, Y));
        PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, Xs, F));
        PetscCall(VecAXPY(avg, 1.0 / probe.samples, F));
      }
      PetscCall(VecAXPY(Mean, 0.25, avg));
    }
    if (!finite) continue;
    for (int j = 0; j < 4; ++j) PetscCall(VecAXPY(vs->beat_phase[4 * b + j], -1.0, Mean));
    vs->beat_omega.push_back(probe.g);
    vs->beat_level.push_back(K);
  }
  PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT "'s own splits' modes beat at %g%s (the slowest difference or combination of three or four of their frequencies: %" PetscInt_FMT " beats, %" PetscInt_FMT " combinations)\n", K, probes[0].g, probes.size() > 1 ? " and more" : "",
                      (PetscInt)beats.size(), (PetscInt)combinations.size()));
  PetscCall(VecDestroyVecs(m + 1, &V));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&Xs));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&Mean));
  PetscFunctionReturn(0);
}

/* How strongly the fastest level's oscillation drives the state through the slower levels' fields,
   per unit time and relative amplitude of the oscillation, over ||X||: a thin fast rotation that a
   slow variable squares (y' = -y + C u^2 with small u) holds little of the state but moves the slow
   variable by its whole size per unit time and relative amplitude, and a relative amplitude error
   E left by the micro step moves the slow variables by about E times this rate times the time
   they keep it (AllowedAmplitudeLoss() in vshmmadapt.cpp). vs->fastest_drive is that displacement
   per unit E: the drive's norm times the response of y' = J_K y + drive over half the run
   (vshmm::forcedResponse() on an Arnoldi space of J_K started at the drive; at most half the run),
   over ||X||. The full field's J_K, not the slower fields' alone: a drive of a fast component
   is rotated away by the fast field (the paper's oscillators: the medium split's y2^2 / eps pushes
   x1, which rotates at 1e6; with the slower fields' Jacobian their runs were 2-20x dearer).

   The oscillation's part of the state, P, is its displacement from the centre it oscillates about,
   -J_K G_K(X) / rho_K^2 (LevelOscillationPart(); on the fastest level's own components with
   component splits); a quarter turn on it is Q = G_K(X) / rho_K on the own components or J_K P /
   rho_K. The drive is the derivative
   of the slower levels' field G_{K-1} with respect to a relative change of the oscillation's
   amplitude (central differences), averaged over four phases of it (X - P + cos(theta) P +
   sin(theta) Q, theta a multiple of a quarter turn): only what the oscillation does to the slower
   levels on average adds up over the run, and the average over four phases is exact for fields of
   degree up to 3 in it (the terms linear in it, a slow advection of the fast modes, cancel). */
static PetscErrorCode FastestLevelDrive(TS ts, Vec mask, PetscReal n_all)
{
  TS_VSHMM      *vs = (TS_VSHMM *)ts->data;
  const PetscInt K  = (PetscInt)vs->level_end.size() - 1;
  Vec            P, Q, G, Y, Xs, Gp, Gm, D;
  PetscReal      n_d;

  PetscFunctionBegin;
  if (!((PetscInt)vs->level_radius.size() > K && vs->level_radius[K] > 0)) PetscFunctionReturn(0);
  const PetscReal rho = vs->level_radius[K], s = 1e-3;
  PetscCall(VecDuplicate(ts->vec_sol, &P));
  PetscCall(VecDuplicate(ts->vec_sol, &Q));
  PetscCall(VecDuplicate(ts->vec_sol, &G));
  PetscCall(VecDuplicate(ts->vec_sol, &Y));
  PetscCall(VecDuplicate(ts->vec_sol, &Xs));
  PetscCall(VecDuplicate(ts->vec_sol, &Gp));
  PetscCall(VecDuplicate(ts->vec_sol, &Gm));
  PetscCall(VecDuplicate(ts->vec_sol, &D));
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, ts->ptime, ts->vec_sol, G));
  PetscCall(LevelOscillationPart(ts, K, mask, G, Xs, P));
  if (mask) { /* the level's part of the state is its oscillation's: about a centre away from 0, the displacement (a damped rotation about u = y^2 = 75 took its whole u for its amplitude, the micro step 7-30 times below RK4's) */
    PetscReal np;
    PetscCall(VecNorm(P, NORM_2, &np));
    if (n_all > 0 && std::isfinite(np)) vs->fastest_share = PetscMin(vs->fastest_share, np / n_all);
  }
  if (mask) PetscCall(VecPointwiseMult(Q, mask, G)); /* a quarter turn on: G_K(X) / rho_K on the own components, or J_K P / rho_K */
  else PetscCall(FastestJacobianApply(ts, ts->vec_sol, G, P, Xs, Q));
  PetscCall(VecScale(Q, 1.0 / rho));
  PetscCall(FastestLevelPlane(ts, P, Q, rho, mask));
  PetscCall(VecSet(D, 0.0));
  if (vs->fastest_phase.empty()) {
    vs->fastest_phase.resize(8, nullptr);
    for (Vec &v : vs->fastest_phase) PetscCall(VecDuplicate(ts->vec_sol, &v));
  }
  for (int quarter = 0; quarter < 4; ++quarter) {
    const PetscReal c = quarter == 0 ? 1 : quarter == 2 ? -1 : 0, q = quarter == 1 ? 1 : quarter == 3 ? -1 : 0;
    PetscCall(VecAXPBYPCZ(Y, c, q, 0.0, P, Q));       /* the oscillation's part at this phase */
    PetscCall(VecWAXPY(Xs, 1.0 + s, Y, ts->vec_sol)); /* X - P + (1 + s) that part */
    PetscCall(VecAXPY(Xs, -1.0, P));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, Xs, Gp));
    PetscCall(VecAXPY(Xs, -2.0 * s, Y)); /* X - P + (1 - s) that part */
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, Xs, Gm));
    PetscCall(VecAXPBYPCZ(D, 1.0 / (8 * s), -1.0 / (8 * s), 1.0, Gp, Gm));
    PetscCall(VecAXPBYPCZ(vs->fastest_phase[2 * quarter], 0.5, 0.5, 0.0, Gp, Gm)); /* the field at this phase (to O(s^2)) */
    /* and half-way to the next quarter: eight phases show a part of the field that oscillates at
       twice the frequency (a squared fast variable) at every phase of it */
    PetscCall(VecAXPBYPCZ(Y, (c - q) * PETSC_SQRT2 / 2, (c + q) * PETSC_SQRT2 / 2, 0.0, P, Q));
    PetscCall(VecWAXPY(Xs, -1.0, P, ts->vec_sol));
    PetscCall(VecAXPY(Xs, 1.0, Y));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, K - 1, ts->ptime, Xs, vs->fastest_phase[2 * quarter + 1]));
  }
  PetscCall(VecSet(G, 0.0)); /* the phase average */
  for (Vec v : vs->fastest_phase) PetscCall(VecAXPY(G, 0.125, v));
  for (Vec v : vs->fastest_phase) PetscCall(VecAXPY(v, -1.0, G));
  PetscCall(VecNorm(D, NORM_2, &n_d));
  const PetscReal tau      = 0.5 * TSVSHMMAmplitudeSpan_Private(ts);
  PetscReal       response = tau;                                                                  /* what the slower levels make of the drive over half the run, per unit drive */
  if (n_d > 0 && std::isfinite(n_d) && n_d * tau > kNegligibleDrive * vs->fastest_share * n_all) { /* (at most tau where no mode grows: a negligible drive is left so) */
    Vec                     *V;
    PetscInt                 m, k;
    std::vector<PetscScalar> H;
    PetscCall(LevelArnoldi(ts, K, ts->ptime, ts->vec_sol, &V, &m, H, &k, NULL, nullptr, D));
    PetscCall(VecDestroyVecs(m + 1, &V));
    /* at most tau, what the drive does without any dynamics: growing slow modes amplify every error
       alike, which the tolerance's share per step does not count either (a chaotic slow system
       would otherwise bound the micro step to nothing) */
    if (k > 0) response = PetscMin(tau, vshmm::forcedResponse(std::vector<double>(H.begin(), H.end()), (int)k, (int)(m + 1), tau));
  }
  vs->fastest_drive = std::isfinite(n_d * response) ? n_d * response / n_all : 0.0; /* not finite near X: no information (the level's own part weighs alone) */
  PetscCall(PetscInfo(ts, "The slower levels' fields move the state by %g of its norm per unit time and relative amplitude of the fastest level's oscillation (phase average), %g over half the run\n", (double)(n_d / n_all), (double)vs->fastest_drive));
  vs->fastest_phase_now = PETSC_TRUE;
  PetscCall(VecDestroy(&P));
  PetscCall(VecDestroy(&Q));
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&Xs));
  PetscCall(VecDestroy(&Gp));
  PetscCall(VecDestroy(&Gm));
  PetscCall(VecDestroy(&D));
  PetscFunctionReturn(0);
}

/* How fast the explicit time dependence of each faster level's own splits moves it: ||dF_l/dt|| /
   (rho_l ||X||) by a forward difference in t, for l >= 1 (vs->level_time_rate). VSHMM advances one
   clock for every level, by the mesoscopic steps as well, so level l sees the time dependence of
   its splits r_0 ... r_{l-1} times faster than it is: a forcing sin(t / eps) in a fast split,
   which no time ratio may slow, is aliased by any savings (x' = 1 - x + 2 z^2, z' = -(z - x sin(t /
   1e-3)) / 1e-3: 3.8e-3 off with savings factor 0.01, 0.157 from 1 on). A slow forcing in a fast
   split (cos t) moves at rate 1 and is slowed like the level's own slow process. */
static PetscErrorCode LevelTimeRates(TS ts)
{
  TS_VSHMM      *vs      = (TS_VSHMM *)ts->data;
  const PetscInt nscales = (PetscInt)vs->level_end.size();
  Vec            F0, F1, Xa;

  PetscFunctionBegin;
  /* measured at set-up, and again later only where the splits depend on time at all (an autonomous
     split differs by exactly 0): a forcing's amplitude changes with the state */
  if (ts->steps > 0 && !vs->time_dependent) PetscFunctionReturn(0);
  vs->level_time_rate.assign(nscales, 0.0);
  if (nscales < 2) PetscFunctionReturn(0);
  const PetscReal t = ts->ptime, delta = std::sqrt(PETSC_MACHINE_EPSILON) * PetscMax(PetscAbsReal(t), PetscAbsReal(ts->time_step));
  PetscCall(VecDuplicate(ts->vec_sol, &F0));
  PetscCall(VecDuplicate(ts->vec_sol, &F1));
  PetscCall(VecDuplicate(ts->vec_sol, &Xa));
  /* at the state, and where the slowest level's field takes it within a macro step: a forcing whose
     amplitude is a slow variable at 0 (x sin(t / eps) from x = 0) shows there, at the step's end
     (t + DeltaT): a forcing cos(3 t) is stationary at t = 0 (rate 3e-8 there, 2.7 at t = 0.5), and
     the first macro step of DeltaT = 0.5 took time ratios of 35 for it, 3.3 tol at 1e-2 with an
     estimate of 0.07 (its error, non-monotone in the savings, the same at 35 and 69) */
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, 0, t, ts->vec_sol, F0));
  PetscCall(VecAYPX(F0, ts->time_step, ts->vec_sol));
  PetscCall(VecCopy(F0, Xa));
  for (int at = 0; at < 2; ++at) {
    Vec             X  = at == 0 ? ts->vec_sol : Xa;
    const PetscReal ta = at == 0 ? t : t + ts->time_step;
    PetscReal       xnorm;
    PetscCall(VecNorm(X, NORM_2, &xnorm));
    if (!(xnorm > 0) || !std::isfinite(xnorm)) continue;
    for (PetscInt level = 1; level < nscales; ++level) {
      if (!((PetscInt)vs->level_radius.size() > level && vs->level_radius[level] > 0)) continue;
      PetscReal d;
      PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, level, ta, X, F0));
      PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, level, ta + delta, X, F1));
      PetscCall(VecAXPY(F1, -1.0, F0));
      PetscCall(VecNorm(F1, NORM_2, &d));
      if (std::isfinite(d)) vs->level_time_rate[level] = PetscMax(vs->level_time_rate[level], d / (delta * vs->level_radius[level] * xnorm));
      if (d > 0) vs->time_dependent = PETSC_TRUE;
    }
  }
  if ((PetscInt)vs->level_time_rate_max.size() < nscales) vs->level_time_rate_max.resize(nscales, 0.0);
  for (PetscInt level = 1; level < nscales; ++level) {
    vs->level_time_rate_max[level] = PetscMax(vs->level_time_rate_max[level], vs->level_time_rate[level]);
    if (vs->level_time_rate[level] > 0)
      PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT " at t = %g: its splits' explicit time dependence moves at rate %g (spectral radius %g)\n", level, (double)t, (double)vs->level_time_rate[level], (double)vs->level_radius[level]));
  }
  PetscCall(VecDestroy(&F0));
  PetscCall(VecDestroy(&F1));
  PetscCall(VecDestroy(&Xa));
  PetscFunctionReturn(0);
}

/* The fastest level's own components at (near) an unstable equilibrium: a small part of the state
   (below kUnstableShare of its norm) and an own mode growing (Re lambda above the Ritz values'
   noise) kUnstableSeparation times faster than the slower level's spectral radius. They leave it
   when their amplitude has grown back from how small it became before: a slow passage through a
   bifurcation (a fast rotation whose damping x / eps changes sign as x drifts through 0 leaves
   u = 0 at the time the growth since 0 has made up the decay before it, not when x crosses 0). The
   savings slow the level's decay and growth alike, by time ratios that differ between the two,
   and its amplitude is far below anything a comparison of the slow values sees: that time, and
   the answer after it, can be wrong by O(1) (the rotation above left u = 0 at t = 1.8 instead of 2:
   89 tol at 1e-3, estimates 0.3). Said once per solve (an error with -ts_vshmm_check_separation
   error); nothing else changes. */
static PetscErrorCode CheckUnstableEquilibrium(TS ts, PetscInt level, const std::vector<std::complex<double>> &ritz, double noise)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (vs->unstable_warned || vs->check_separation == TSVSHMM_SEPARATION_OFF || !(vs->fastest_share < kUnstableShare) || (PetscInt)vs->level_radius.size() <= level) PetscFunctionReturn(0);
  const double    growth = vshmm::fastestGrowthRate(ritz, noise);
  const PetscReal slower = vs->level_radius[level - 1];
  if (!(growth > kUnstableSeparation * slower) || !(slower > 0)) PetscFunctionReturn(0);
  vs->unstable_warned = PETSC_TRUE;
  PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: the fastest level's own components (%g of the state norm) sit at an unstable equilibrium: a mode grows at rate %g (Re lambda), %g times the slower level's spectral radius (%g). When they leave it depends on how small they became before (a slow passage through a bifurcation), which the savings change; use a single-rate TS type (-ts_type rk), or -ts_vshmm_check_separation warn to run anyway",
             (double)ts->ptime, (double)vs->fastest_share, growth, growth / slower, (double)slower);
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: the fastest level's own components (%g of the state norm) sit at an unstable equilibrium: a mode grows at rate %g (Re lambda), %g times the slower level's spectral radius (%g). When they leave it depends on how small they became before (a slow passage through a bifurcation), and the savings slow the level's decay and growth by different time ratios: that time, and the answer after it, can be wrong by O(1) without the error estimates showing it. A single-rate TS type (-ts_type rk) is the right tool across such a passage. (-ts_vshmm_check_separation error makes this an error, off silences it.)\n",
                                (double)ts->ptime, (double)vs->fastest_share, growth, growth / slower, (double)slower));
  PetscFunctionReturn(0);
}

/* Whether every split of level `level`'s own is a component split (its IS a subset it writes). */
static bool ComponentLevel(const TS_VSHMM *vs, PetscInt level)
{
  for (PetscInt k = vs->level_end[level - 1]; k < vs->level_end[level]; ++k)
    if (vs->splits[k].additive) return false;
  return true;
}

/* The slowest rate of a level's own components (component splits) at ts->vec_sol, ts->ptime, as
   TSVSHMMLevelOwnRates_Private() estimates it; 0 where the level has additive splits or its Ritz
   values are not finite. The estimate is not stored. */
PetscErrorCode TSVSHMMLevelOwnSlowest_Private(TS ts, PetscInt level, PetscReal *slowest)
{
  TS_VSHMM                         *vs = (TS_VSHMM *)ts->data;
  std::vector<std::complex<double>> ritz;
  PetscBool                         finite = PETSC_FALSE;
  double                            noise;
  Vec                               mask;

  PetscFunctionBegin;
  *slowest = 0;
  if (!ComponentLevel(vs, level)) PetscFunctionReturn(0);
  const StabilityCounting counting(vs);
  PetscCall(VecDuplicate(ts->vec_sol, &mask));
  PetscCall(TSVSHMMWrittenComponents_Private(vs, vs->level_end[level - 1], vs->level_end[level], ts->ptime, mask));
  PetscCall(OwnBlockRitzValues(ts, level, mask, PETSC_FALSE, ritz, &finite, &noise));
  if (finite) *slowest = vshmm::slowestRate(ritz, noise);
  if (finite && level + 1 == (PetscInt)vs->level_end.size() && vs->fastest_nonlinear && vs->fastest_phase_now && vshmm::oscillates(vs->fastest_mean_mode)) {
    /* a nonlinear oscillation (FastestLevelPlane()): the largest of the slowest rates at four phases
       of it, the quarter turn G_K(X) / omega at the mean eigenvalue's frequency (a slow process
       inside the level is slow at every phase; the van der Pol oscillator's reads 8 at one phase
       and 1,500 at another) */
    Vec       P, Q, Xp;
    PetscReal phase = *slowest;
    PetscCall(VecDuplicate(ts->vec_sol, &P));
    PetscCall(VecDuplicate(ts->vec_sol, &Q));
    PetscCall(VecDuplicate(ts->vec_sol, &Xp));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, ts->ptime, ts->vec_sol, Q));
    PetscCall(LevelOscillationPart(ts, level, mask, Q, Xp, P));
    PetscCall(VecPointwiseMult(Q, mask, Q));
    PetscCall(VecScale(Q, 1.0 / vs->fastest_mean_mode.imag()));
    PetscCall(OwnSlowestOverPhases(ts, level, mask, P, Q, &phase));
    PetscCall(VecDestroy(&P));
    PetscCall(VecDestroy(&Q));
    PetscCall(VecDestroy(&Xp));
    if (phase > *slowest)
      PetscCall(PetscInfo(ts, "Own components of level %" PetscInt_FMT " at t = %g: slowest rate %g at this phase of its nonlinear oscillation, %g at the slowest of four\n", level, (double)ts->ptime, (double)*slowest, (double)phase));
    *slowest = phase;
  }
  PetscCall(VecDestroy(&mask));
  PetscFunctionReturn(0);
}

PetscErrorCode TSVSHMMLevelOwnRates_Private(TS ts)
{
  TS_VSHMM                         *vs      = (TS_VSHMM *)ts->data;
  const PetscInt                    nscales = (PetscInt)vs->level_end.size();
  std::vector<std::complex<double>> ritz;

  PetscFunctionBegin;
  if (vs->own_rates_time == vs->spectra_time && (PetscInt)vs->level_slowest.size() == nscales) PetscFunctionReturn(0);
  const StabilityCounting counting(vs);
  vs->level_slowest.assign(nscales, 0.0);
  vs->fastest_share     = 1.0;
  vs->fastest_drive     = 0.0;
  vs->fastest_restore   = 0.0;
  vs->fastest_nonlinear = PETSC_FALSE;
  vs->fastest_own_phase = 0.0;
  vs->fastest_phase_now = PETSC_FALSE;
  vs->beat_omega.clear();
  vs->beat_level.clear();
  for (PetscInt level = 1; level < nscales; ++level) {
    if (!ComponentLevel(vs, level)) {                            /* additive splits: the fastest level's part of the state as its field sees it, ||G_K(X)|| / (rho_K ||X||) (the stiffest modes count fully) */
      const bool oscillates = LimitingModesOscillate(vs, level); /* used by -ts_vshmm_adapt's micro step bound only, for oscillating modes */
      if (vs->adapt && oscillates && level == nscales - 1 && (PetscInt)vs->level_radius.size() > level && vs->level_radius[level] > 0) {
        Vec       G;
        PetscReal n_g, n_all;
        PetscCall(VecDuplicate(ts->vec_sol, &G));
        PetscCall(TSVSHMMEvaluateLevel_Private(vs, level, ts->ptime, ts->vec_sol, G));
        PetscCall(VecNorm(G, NORM_2, &n_g));
        PetscCall(VecNorm(ts->vec_sol, NORM_2, &n_all));
        PetscCall(VecDestroy(&G));
        if (n_all > 0 && std::isfinite(n_g)) vs->fastest_share = PetscMin(1.0, n_g / (vs->level_radius[level] * n_all));
        PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT " (additive splits) at t = %g: %g of the state norm by its field\n", level, (double)ts->ptime, (double)vs->fastest_share));
        if (n_all > 0 && std::isfinite(n_g)) PetscCall(FastestLevelDrive(ts, nullptr, n_all));
      }
      if (oscillates) PetscCall(AdditiveOwnRate(ts, level));
      continue;
    }
    Vec mask; /* 1 on the components the level's new splits write, added as their outputs are */
    PetscCall(VecDuplicate(ts->vec_sol, &mask));
    PetscCall(TSVSHMMWrittenComponents_Private(vs, vs->level_end[level - 1], vs->level_end[level], ts->ptime, mask));
    PetscBool finite = PETSC_FALSE;
    double    noise;
    PetscCall(OwnBlockRitzValues(ts, level, mask, PETSC_FALSE, ritz, &finite, &noise));
    if (level == nscales - 1) { /* the fastest level's part of the state (its own components'), for -ts_vshmm_adapt's micro step bound */
      Vec       own;
      PetscReal n_own, n_all;
      PetscCall(VecDuplicate(ts->vec_sol, &own));
      PetscCall(VecPointwiseMult(own, mask, ts->vec_sol));
      PetscCall(VecNorm(own, NORM_2, &n_own));
      PetscCall(VecNorm(ts->vec_sol, NORM_2, &n_all));
      PetscCall(VecDestroy(&own));
      if (n_all > 0 && std::isfinite(n_own)) vs->fastest_share = PetscMin(1.0, n_own / n_all);
      PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT " at t = %g: its own components hold %g of the state norm\n", level, (double)ts->ptime, (double)vs->fastest_share));
      if (vs->adapt && n_all > 0 && n_own > 0) PetscCall(FastestLevelDrive(ts, mask, n_all));
    }
    PetscCall(VecDestroy(&mask));
    if (!finite) continue;
    if (level == nscales - 1) PetscCall(CheckUnstableEquilibrium(ts, level, ritz, noise));
    double slowest = vshmm::slowestRate(ritz, noise);
    if (level == nscales - 1 && vs->fastest_nonlinear && vshmm::oscillates(vs->fastest_mean_mode) && vs->fastest_own_phase > slowest) { /* FastestLevelPlane() */
      PetscCall(PetscInfo(ts, "Own components of level %" PetscInt_FMT " at t = %g: slowest rate %g at this phase of its nonlinear oscillation, %g at the slowest of four\n", level, (double)ts->ptime, slowest, (double)vs->fastest_own_phase));
      slowest = vs->fastest_own_phase;
    }
    if (slowest > 0) vs->level_slowest[level] = slowest;
    PetscCall(PetscInfo(ts, "Own components of level %" PetscInt_FMT " at t = %g: slowest rate %g%s\n", level, (double)ts->ptime, (double)vs->level_slowest[level], level == nscales - 1 ? " (its part of the state: the line above)" : ""));
  }
  PetscCall(LevelTimeRates(ts));
  vs->own_rates_time = vs->spectra_time;
  if (vs->adapt) PetscCall(TSVSHMMLevelBeats_Private(ts));
  if (vs->adapt) PetscCall(TSVSHMMAdaptUnaveraged_Private(ts));
  if (vs->adapt) PetscCall(TSVSHMMAdaptBeats_Private(ts));
  PetscFunctionReturn(0);
}

/* Whether lambda, a limiting mode of level `level`'s field G_level = f_0 + ... + f_level, is a
   sustained oscillation of that level: its amplitude decays by less than e^kSustainedDecay over a
   macro step (a damped spiral's transient is a layer, which the comparisons see), and it turns faster
   than kOwnOscillation times the slower level's spectral radius or not kOwnOscillation times slower
   than the slowest mode of the level's own components (level_slowest). One slower on both counts
   is the slower levels' own dynamics, which G_level holds too (a slow oscillator at 0.85 under a fast relaxation at 1e3
   was taken for level 1's oscillation before 2026-11-28: a forcing 5.8e5 times the slow dynamics
   was said, and -ts_vshmm_adapt took no savings for a swing of 1e4 tolerances that was not there). */
static bool SustainedMode(const TS_VSHMM *vs, PetscInt level, const std::complex<double> &lambda, PetscReal DeltaT)
{
  if (!vshmm::oscillates(lambda) || !(std::fabs(lambda.real()) * DeltaT < kSustainedDecay)) return false;
  if (level == 0 || (PetscInt)vs->level_radius.size() < level || !(std::abs(lambda) <= kOwnOscillation * vs->level_radius[level - 1])) return true;
  /* and slower than every mode of the level's own components (where estimated): not theirs */
  return !((PetscInt)vs->level_slowest.size() > level && vs->level_slowest[level] > 0 && std::abs(lambda) < vs->level_slowest[level] / kOwnOscillation);
}

/* Whether level `level` has a sustained oscillation among its limiting modes (SustainedMode()). */
static bool SustainedOscillation(const TS_VSHMM *vs, PetscInt level, PetscReal DeltaT)
{
  if ((PetscInt)vs->level_limiting.size() <= level) return false;
  for (const std::complex<double> &lambda : vs->level_limiting[level])
    if (SustainedMode(vs, level, lambda, DeltaT)) return true;
  return false;
}

/* The largest frequency |lambda| of level `level`'s sustained oscillations among its limiting modes
   (0: none). */
static PetscReal SustainedFrequency(const TS_VSHMM *vs, PetscInt level, PetscReal DeltaT)
{
  PetscReal omega = 0;
  if ((PetscInt)vs->level_limiting.size() <= level) return 0;
  for (const std::complex<double> &lambda : vs->level_limiting[level])
    if (SustainedMode(vs, level, lambda, DeltaT)) omega = PetscMax(omega, std::abs(lambda));
  return omega;
}

/* How a faster level l+1 with a sustained oscillation (frequency omega, *frequency) forces the
   slower level's components at (t, X). Over a turn the faster level's state moves by about d = V /
   omega and, a quarter turn on, A / omega^2 (V its own splits' field, A = J V their change along
   it); the slower field F_l changes along d by w, an oscillating force on the slower components.
   *ratio: the largest |w_i| (both directions in quadrature) over rho_l (1 + |x_i|), rho_l level l's
   spectral radius: how much harder the force pushes them than their own dynamics (about 1 where the
   slower equations take the fast variables as an O(1) input, the paper's oscillators; large where
   the force is of the order of the fast frequency: a vibrating pivot, a particle in a fast
   oscillating field). The force swings the slower components in phase with it by xi = J_l w /
   omega^2, and where F_l's Jacobian turns with the oscillation too, the two correlate: the
   second-order drift (J_l(X + d) - J_l(X)) xi / 2 over a turn (a mixed second difference), on which
   Kapitza's pendulum stands inverted. *drift: its largest size over 1 + |x_i|, per unit time; savings
   that slow the oscillation by r multiply it by r^2 (CheckForcedSlowComponents()). 0 where level
   l+1 has no sustained oscillation. Split evaluations (2 of level l+1's own, up to 9 of level l)
   are the stability checks'. */
PetscErrorCode TSVSHMMForcingRatio_Private(TS ts, PetscReal t, Vec X, PetscInt l, PetscReal *ratio, PetscReal *drift, PetscReal *frequency)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec      *work;
  PetscReal vmax, xmax, omega;

  PetscFunctionBegin;
  *ratio     = 0;
  *drift     = 0;
  *frequency = 0;
  if ((PetscInt)vs->level_radius.size() <= l + 1 || !(vs->level_radius[l] > 0) || !SustainedOscillation(vs, l + 1, ts->time_step)) PetscFunctionReturn(0);
  omega      = SustainedFrequency(vs, l + 1, ts->time_step);
  *frequency = omega;
  if (!(omega > 0)) PetscFunctionReturn(0);
  const StabilityCounting counting(vs);
  PetscCall(VecDuplicateVecs(X, 8, &work));
  Vec V = work[0], A = work[1], F0 = work[2], F1 = work[3], F2 = work[4], F3 = work[5], W = work[6], Xp = work[7];
  PetscCall(VecNorm(X, NORM_INFINITY, &xmax));
  const PetscReal h = kDifferenceStep * (1 + xmax);
  PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, l + 1, t, X, V));
  PetscCall(VecNorm(V, NORM_INFINITY, &vmax));
  std::vector<PetscReal> drift2, force2;
  if (vmax > 0 && std::isfinite(vmax)) {
    PetscCall(VecWAXPY(Xp, h / vmax, V, X));
    PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, l + 1, t, Xp, A));
    PetscCall(VecAXPY(A, -1.0, V));
    PetscCall(VecScale(A, vmax / h)); /* J_f V: the acceleration */
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, l, t, X, F0));
    PetscInt n;
    PetscCall(VecGetLocalSize(X, &n));
    drift2.assign(n, 0.0);
    force2.assign(n, 0.0);
    for (int k = 0; k < 2; ++k) {
      /* the fast displacement d over a turn: V / omega, or A / omega^2 a quarter turn on */
      Vec             D     = k ? A : V;
      const PetscReal scale = k ? 1.0 / (omega * omega) : 1.0 / omega;
      PetscReal       dmax;
      PetscCall(VecNorm(D, NORM_INFINITY, &dmax));
      if (!(dmax > 0 && std::isfinite(dmax))) continue;
      /* the force w = F_l(X + d) - F_l(X) (a difference quotient along d, times |d|) */
      const PetscReal dd = h / dmax;
      PetscCall(VecWAXPY(Xp, dd, D, X));
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, l, t, Xp, W));
      PetscCall(VecAXPY(W, -1.0, F0));
      PetscCall(VecScale(W, scale / dd));
      /* the slow components' swing in phase with the force: xi = J_l w / omega^2 */
      PetscReal wmax;
      PetscCall(VecNorm(W, NORM_INFINITY, &wmax));
      if (!(wmax > 0 && std::isfinite(wmax))) continue;
      PetscCall(VecWAXPY(Xp, h / wmax, W, X));
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, l, t, Xp, F1));
      PetscCall(VecAXPY(F1, -1.0, F0));
      PetscCall(VecScale(F1, wmax / h / (omega * omega))); /* xi */
      PetscReal ximax;
      PetscCall(VecNorm(F1, NORM_INFINITY, &ximax));
      if (!(ximax > 0 && std::isfinite(ximax))) continue;
      /* the drift: the slow Jacobian's change along d applied to xi, a mixed second difference */
      const PetscReal dx = h / ximax;
      PetscCall(VecWAXPY(Xp, dd, D, X));
      PetscCall(VecAXPY(Xp, dx, F1));
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, l, t, Xp, F2)); /* F(X + d + xi) */
      PetscCall(VecWAXPY(Xp, dx, F1, X));
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, l, t, Xp, F3)); /* F(X + xi) */
      const PetscScalar *f2, *f3, *w;
      PetscCall(VecGetArrayRead(F2, &f2));
      PetscCall(VecGetArrayRead(F3, &f3));
      PetscCall(VecGetArrayRead(W, &w));
      for (PetscInt i = 0; i < n; ++i) {
        /* F(X+d+xi) - F(X+xi) - (F(X+d) - F(X)), with F(X+d) - F(X) = w dd / scale */
        const PetscReal m = PetscRealPart(f2[i] - f3[i] - PetscRealPart(w[i]) * dd / scale) / (dd * dx) * scale; /* along the displacement d = D scale and the swing xi */
        drift2[i] += 0.25 * m * m;
        force2[i] += PetscRealPart(w[i]) * PetscRealPart(w[i]);
      }
      PetscCall(VecRestoreArrayRead(W, &w));
      PetscCall(VecRestoreArrayRead(F3, &f3));
      PetscCall(VecRestoreArrayRead(F2, &f2));
    }
    const PetscScalar *x;
    PetscReal          most[2] = {0, 0};
    PetscCall(VecGetArrayRead(X, &x));
    for (PetscInt i = 0; i < n; ++i) {
      most[0] = PetscMax(most[0], PetscSqrtReal(drift2[i]) / (1 + PetscAbsScalar(x[i])));
      most[1] = PetscMax(most[1], PetscSqrtReal(force2[i]) / (vs->level_radius[l] * (1 + PetscAbsScalar(x[i]))));
    }
    PetscCall(VecRestoreArrayRead(X, &x));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, most, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)ts)));
    *drift = most[0];
    *ratio = most[1];
    PetscCall(PetscInfo(ts, "Separation check at t = %g: levels %d/%d: level %d's oscillation (frequency %g) forces level %d's components %g times as hard as their own dynamics, a second-order drift of %g of their size per unit time\n", (double)t, (int)l, (int)l + 1, (int)l + 1, (double)omega, (int)l, (double)most[1], (double)most[0]));
  }
  PetscCall(VecDestroyVecs(8, &work));
  PetscFunctionReturn(0);
}

/* The sampled quantities (the observables, or the state in the TS's weighted norm) that a faster
   level with a sustained oscillation moves on its own time scale at (t, X): they carry its phase,
   which VSHMM does not compute with savings below that level (vshmm::fastSwingSquares()). The
   quantities' derivatives along each such level's own splits and along the whole field (central
   differences for observables; the fields themselves for the state), and their swing in
   tolerances (RMS, as the weighted norm). *level: the fastest level whose swing exceeds `allowed`
   tolerances (-1: none); *which: the observable with the largest swing (-1: the state); *swing:
   its level's swing; *rate: the largest relative rate along that level's splits over the slower
   level's spectral radius. Split evaluations are the stability checks'. */
PetscErrorCode TSVSHMMFastQuantities_Private(TS ts, PetscReal t, Vec X, PetscReal allowed, PetscInt *level, PetscInt *which, PetscReal *swing, PetscReal *rate)
{
  TS_VSHMM           *vs  = (TS_VSHMM *)ts->data;
  const PetscInt      K   = (PetscInt)vs->level_end.size() - 1;
  const PetscReal     tol = TSVSHMMToleranceLevel_Private(ts);
  Vec                 G = nullptr, Xp = nullptr;
  std::vector<double> total, w; /* the quantities' derivatives along the whole field (empty: not yet), their weights */
  PetscReal           xmax, count = 0;

  PetscFunctionBegin;
  *level = -1;
  *which = -1;
  *swing = 0;
  *rate  = 0;
  if (!(tol > 0)) PetscFunctionReturn(0);
  const StabilityCounting counting(vs);
  PetscCall(VecNorm(X, NORM_INFINITY, &xmax));
  /* the quantities' derivatives along G (and their weights): by central differences of the
     observables, or G's local entries */
  const auto derivatives = [&](Vec F, std::vector<double> &d, bool *any) -> PetscErrorCode {
    PetscReal fmax;
    PetscFunctionBegin;
    PetscCall(VecNorm(F, NORM_INFINITY, &fmax));
    *any = fmax > 0 && std::isfinite(fmax);
    if (!*any) PetscFunctionReturn(0);
    if (vs->observables) {
      const PetscInt      n = vs->nobservables;
      std::vector<double> q0(n), qp(n), qm(n);
      const PetscReal     delta = kDifferenceStep * (1 + xmax) / fmax;
      if (!Xp) PetscCall(VecDuplicate(X, &Xp));
      PetscCall(TSVSHMMObservables_Private(ts, t, X, q0.data()));
      PetscCall(VecWAXPY(Xp, delta, F, X));
      PetscCall(TSVSHMMObservables_Private(ts, t, Xp, qp.data()));
      PetscCall(VecWAXPY(Xp, -delta, F, X));
      PetscCall(TSVSHMMObservables_Private(ts, t, Xp, qm.data()));
      d.resize(n);
      w.resize(n);
      for (PetscInt i = 0; i < n; ++i) {
        d[i] = (qp[i] - qm[i]) / (2 * delta);
        w[i] = ts->atol + ts->rtol * PetscAbsReal(q0[i]);
      }
      count = n;
    } else {
      const PetscScalar *x, *f, *va = nullptr, *vr = nullptr;
      PetscInt           n, N;
      PetscCall(VecGetLocalSize(X, &n));
      PetscCall(VecGetSize(X, &N));
      d.resize(n);
      w.resize(n);
      PetscCall(VecGetArrayRead(X, &x));
      PetscCall(VecGetArrayRead(F, &f));
      if (ts->vatol) PetscCall(VecGetArrayRead(ts->vatol, &va));
      if (ts->vrtol) PetscCall(VecGetArrayRead(ts->vrtol, &vr));
      for (PetscInt i = 0; i < n; ++i) {
        d[i] = PetscRealPart(f[i]);
        w[i] = (va ? PetscRealPart(va[i]) : ts->atol) + (vr ? PetscRealPart(vr[i]) : ts->rtol) * PetscAbsScalar(x[i]);
      }
      if (ts->vrtol) PetscCall(VecRestoreArrayRead(ts->vrtol, &vr));
      if (ts->vatol) PetscCall(VecRestoreArrayRead(ts->vatol, &va));
      PetscCall(VecRestoreArrayRead(F, &f));
      PetscCall(VecRestoreArrayRead(X, &x));
      count = N;
    }
    PetscFunctionReturn(0);
  };
  for (PetscInt l = 1; l <= K; ++l) {
    if ((PetscInt)vs->level_radius.size() <= l || !(vs->level_radius[l - 1] > 0) || !(vs->level_radius[l] > 0) || !SustainedOscillation(vs, l, ts->time_step)) continue;
    /* the swing's lower bound takes as the frequency the largest of the sustained oscillations of
       the levels from l up: a slower level's own splits can move a quantity with a faster level's
       phase (the paper's oscillators: the medium term moves I1 at rate 2 x1 y2^2 / eps, x1 turning
       with the fast level, a ripple of order eps in I1, not a medium oscillation), but a faster
       level's modes that only decay follow the slower ones and turn no quantity faster (a medium
       rotation's phase observed below a decaying fast level: bounded by the fast radius, the swing
       came out 100 times too small, 5 tol at 1e-1 unseen) */
    PetscReal rhoK = 0;
    for (PetscInt j = l; j <= K; ++j) rhoK = PetscMax(rhoK, SustainedFrequency(vs, j, ts->time_step));
    if (!(rhoK > 0)) rhoK = vs->level_radius.back();
    const PetscReal minRate = kFastQuantityRate * vs->level_radius[l - 1];
    bool            any;
    if (!G) PetscCall(VecDuplicate(X, &G));
    if (total.empty()) { /* the whole field, once: a quantity the level's splits move fast and the others move back (the stiff-spring chain's I, its oscillation written across the splits) does not turn */
      PetscCall(TSVSHMMEvaluateLevel_Private(vs, K, t, X, G));
      PetscCall(derivatives(G, total, &any));
      if (!any) break;
    }
    std::vector<double> own;
    PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, l, t, X, G));
    PetscCall(derivatives(G, own, &any));
    if (!any) continue;
    PetscReal sum = vshmm::fastSwingSquares(own, total, w, tol, minRate, rhoK), best = 0, bestRate = 0;
    PetscInt  bestWhich = -1;
    for (size_t i = 0; i < own.size(); ++i) {
      if (w[i] > 0) bestRate = PetscMax(bestRate, PetscAbsReal(own[i]) * tol / w[i] / vs->level_radius[l - 1]);
      const double one = vs->observables ? vshmm::fastSwingSquares({own[i]}, {total[i]}, {w[i]}, tol, minRate, rhoK) : 0.0;
      if (one > best) {
        best      = one;
        bestWhich = (PetscInt)i;
      }
    }
    if (!vs->observables) {
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ts)));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bestRate, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)ts)));
    }
    const PetscReal sw = count > 0 ? PetscSqrtReal(sum / count) : 0;
    PetscCall(PetscInfo(ts, "Level %" PetscInt_FMT " at t = %g: the sampled quantities that turn with it swing by %g tolerances (%s; up to %g times the slower level's radius along its own splits)\n", l, (double)t, (double)sw, vs->observables ? "observables" : "the state", (double)bestRate));
    if (sw > allowed) {
      *level = l;
      *which = bestWhich;
      *swing = sw;
      *rate  = bestRate;
    }
  }
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&Xp));
  PetscFunctionReturn(0);
}

/* Whether the full field's stiffest mode (the one that limits the micro step) is an oscillation
   (|Im lambda| > |Re lambda|): only then do the coupled-level and fast-energy checks run. Where the
   fastest scale is dissipative a slow level cannot pump energy into it, and the per-level check
   suffices. */
static bool TopLevelOscillates(const TS_VSHMM *vs)
{
  const size_t top = vs->level_end.size() - 1;
  if (vs->level_limiting.size() <= top || vs->level_limiting[top].empty()) return false;
  const std::complex<double> worst = vs->level_worst[top];
  return vshmm::oscillates(worst) && vs->level_radius[top] > 0;
}

/* The coupled levels (core/coupling.hpp): every level may be stable alone while their composition
   in a micro cycle grows a mode (a slow field that moves the fast variables). Stops with an error
   when the coupling grows some mode by more than kMaxCouplingGrowth over a macro step. */
static PetscErrorCode CheckCoupling(TS ts, PetscReal dt, const vshmm::MesoscopicSchedule &schedule)
{
  TS_VSHMM            *vs   = (TS_VSHMM *)ts->data;
  MPI_Comm             comm = PetscObjectComm((PetscObject)ts);
  const PetscReal      t = ts->ptime, DeltaT = ts->time_step;
  vshmm::CoupledLevels levels;

  PetscFunctionBegin;
  if (vs->level_end.size() < 2 || !TopLevelOscillates(vs)) PetscFunctionReturn(0);
  const StabilityCounting counting(vs);
  PetscCall(CoupledLevelOperators(ts, t, ts->vec_sol, levels));
  if (!levels.n) PetscFunctionReturn(0);
  /* The exact flow may grow a mode too (an unstable slow manifold): allowed, at the rate of the
     full field's eigenvalue with the largest real part */
  std::vector<std::complex<double>> lambda;
  std::vector<PetscScalar>          Jtop(levels.jacobian.back().begin(), levels.jacobian.back().end());
  PetscBool                         finite;
  double                            rate = 0;
  PetscCall(Eigenvalues(levels.n, levels.n, Jtop.data(), lambda, &finite));
  for (const std::complex<double> &l : lambda) rate = std::max(rate, l.real());
  const double                allowed = rate * DeltaT + std::log(kMaxCouplingGrowth);
  const vshmm::CouplingGrowth g       = vshmm::couplingGrowth(*vs->tableau, levels, schedule, DeltaT);
  PetscCall(PetscInfo(ts, "Stability check at t = %g: coupled levels (%d-dimensional Krylov space of the full field's Jacobian): the composition of the levels' steps grows some mode by %g over a macro step of %ld cycles%s (the exact flow by up to %g)\n", (double)t,
                      levels.n, std::exp(g.logGrowth), g.cycles, g.extrapolated ? ", extrapolated from its first steps" : "", std::exp(rate * DeltaT)));
  if (g.logGrowth <= allowed) PetscFunctionReturn(0);
  std::vector<double> savings(vs->savings_used.begin(), vs->savings_used.end());
  double              s = 0;
  try {
    s = vshmm::largestCouplingStableScaling(*vs->tableau, levels, *vs->kernel, dt, savings, std::vector<int>(vs->subintervals_used.begin(), vs->subintervals_used.end()), DeltaT, rate * DeltaT + std::log(kCouplingTarget));
  } catch (const std::exception &e) {
    SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM: %s", e.what());
  }
  std::string now, safe;
  for (size_t j = 0; j < savings.size(); ++j) {
    char buf[64];
    PetscCall(PetscSNPrintf(buf, sizeof(buf), "%s%g", j ? "," : "", savings[j]));
    now += buf;
    PetscCall(PetscSNPrintf(buf, sizeof(buf), "%s%.3g", j ? "," : "", savings[j] * s));
    safe += buf;
  }
  SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM stability check at t = %g: every level is stable alone, but their steps composed in a micro cycle grow some mode by a factor %g over a macro step (at most %g is tolerated): a slower level's field moves the variables of a faster one (for example the kinematics q' = p in the slow split of an oscillator chain), so its mesoscopic steps shear the fast oscillation and pump energy into it. %s Or use -ts_vshmm_adapt (its error estimate sees such growth), or -ts_vshmm_check_stability false to skip the check", (double)t, std::exp(g.logGrowth), std::exp(allowed),
          s > 0 ? ("Savings factors " + safe + " (now " + now + ", -ts_vshmm_savings_factors) keep it stable; a split that leaves the fast variables' kinematics to the fast scale may allow more.").c_str()
                : ("No savings factors keep it stable with the micro step " + std::to_string(dt) + " (savings factors " + now + "): the scales are not separated for VSHMM with these splits; use a smaller -ts_vshmm_micro_dt, splits that leave the fast variables' kinematics to the fast scale, or a single-rate TS type (-ts_type rk).")
                    .c_str());
}

/* The energy of the fastest scale's oscillation, for an oscillatory top level: with f the fastest
   split's field (G_K - G_{K-1}) and omega the top level's spectral radius,
     E = ||f(X)||^2 + ||f'(X) G_K(X)||^2 / omega^2
   (f' G_K by a finite difference along the full field), which for a harmonic oscillator
   x'' = -omega^2 x is 2 omega^2 times its energy whatever its phase. A slow scale whose steps
   shear the fast oscillation (the kinematics in the slow split of a stiff-spring chain) pumps
   energy into it although every linearised step is stable: the check warns when E has grown by
   more than kFastEnergyGrowth since the smallest value it has seen in the solve. */
static PetscErrorCode CheckFastEnergy(TS ts)
{
  TS_VSHMM       *vs  = (TS_VSHMM *)ts->data;
  const PetscInt  top = (PetscInt)vs->level_end.size() - 1;
  const PetscReal t   = ts->ptime;
  Vec             X   = ts->vec_sol, G, F, Xp;
  PetscReal       fnorm, dfnorm, xnorm, gnorm;

  PetscFunctionBegin;
  if (top < 1 || !TopLevelOscillates(vs)) PetscFunctionReturn(0);
  const double            omega = vs->level_radius[top];
  const StabilityCounting counting(vs);
  PetscCall(VecDuplicate(X, &G));
  PetscCall(VecDuplicate(X, &F));
  PetscCall(VecDuplicate(X, &Xp));
  /* f(X) = G_K(X) - G_{K-1}(X); G holds G_K(X) */
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, top, t, X, G));
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, top - 1, t, X, F));
  PetscCall(VecAYPX(F, -1.0, G));
  PetscCall(VecNorm(F, NORM_2, &fnorm));
  /* f(X + delta G) - f(X), over delta */
  PetscCall(VecNorm(X, NORM_2, &xnorm));
  PetscCall(VecNorm(G, NORM_2, &gnorm));
  const PetscReal delta = gnorm > 0 ? std::sqrt(PETSC_MACHINE_EPSILON) * (1.0 + xnorm) / gnorm : 0;
  dfnorm                = 0;
  if (delta > 0) {
    PetscCall(VecWAXPY(Xp, delta, G, X));
    PetscCall(VecScale(F, -1.0)); /* -f(X) */
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, top, t, Xp, G));
    PetscCall(VecAXPY(F, 1.0, G));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, top - 1, t, Xp, G));
    PetscCall(VecAXPY(F, -1.0, G));
    PetscCall(VecNorm(F, NORM_2, &dfnorm));
    dfnorm /= delta;
  }
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&Xp));
  const PetscReal E = fnorm * fnorm + dfnorm * dfnorm / (omega * omega);
  if (!std::isfinite(E)) PetscFunctionReturn(0);
  if (!(vs->fast_energy_min > 0) || E < vs->fast_energy_min) vs->fast_energy_min = E;
  const PetscReal growth = vs->fast_energy_min > 0 ? E / vs->fast_energy_min : 1;
  PetscCall(PetscInfo(ts, "Stability check at t = %g: energy of the fastest scale's oscillation (scale %s, frequency %g) %g, %g times the smallest seen in this solve\n", (double)t, vs->splits.back().name.c_str(), omega, (double)E, (double)growth));
  if (growth > kFastEnergyGrowth && growth > 2 * vs->fast_energy_warned) {
    vs->fast_energy_warned = growth;
    vs->stability_warnings++;
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: stability check at t = %g: the energy of the fastest scale's oscillation (split %s, frequency %g) has grown by a factor %g in this solve. Unless the problem itself pumps energy into its fast oscillation, VSHMM's mesoscopic steps do: a slower scale's field that moves the fast variables (for example the kinematics q' = p in the slow split of a stiff-spring chain) shears the fast oscillation at every step, and the slow variables come out wrong although every step is stable. Use smaller savings factors, splits that leave the fast variables' motion to the fast scale, -ts_vshmm_adapt, or a single-rate TS type. (Shown again only if it doubles; -info shows every check.)\n", (double)t,
                                  vs->splits.back().name.c_str(), omega, (double)growth));
  }
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
  const PetscReal dt = vs->micro_dt > 0 ? vs->micro_dt : DeltaT / kDefaultMicroStepsPerMacroStep;
  if (vs->adapt) {
    /* the adaptive choice keeps every step stable itself, but a micro step the user set stays as set:
       beyond the fastest level's stable step no choice of savings helps (the dissipative example
       with -ts_vshmm_micro_dt 1e-2 tried twelve times and stopped with NaN blamed on the slow split) */
    if (vs->micro_dt > 0 && !vs->level_limiting.empty() && !vs->level_limiting[top].empty())
      PetscCheck(dt <= vs->level_max_step[top] * (1 + 1e-10), comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM stability check at t = %g: level %" PetscInt_FMT " (all splits: %s) is unstable with the micro step dt = %g that -ts_vshmm_micro_dt (TSVSHMMSetMicroStep()) sets: the estimated eigenvalue %g%+gi (spectral radius %g) needs dt <= %g for TSRK %s. Use a smaller -ts_vshmm_micro_dt, or leave the micro step to -ts_vshmm_adapt", (double)t, top,
                 LevelSplits(vs, top).c_str(), (double)dt, vs->level_worst[top].real(), vs->level_worst[top].imag(), vs->level_radius[top], vs->level_max_step[top], rk);
    PetscFunctionReturn(0);
  }
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
  PetscCall(CheckCoupling(ts, dt, *schedule));
  PetscCall(CheckFastEnergy(ts));
  PetscFunctionReturn(0);
}

/* Whether a difference of two fast frequencies of a level that was no beat at the last spectra
   (vs->beat_watch, LevelBeats()) has been falling fast enough, between the last two spectra, to
   become one before t1 (its frequency at most 1 / kBeatSeparation of the slower of the pair): the
   spectra are then estimated again at the start of the step, so that the beat is probed when it
   turns slow, not at the next calibration (rotations at 1000 and 1500 - 333 t, whose beat turns
   slow at t = 1.2 and passes zero at 1.5: the spectra of 0, 0.1 and 1 saw no beat and the run at
   1e-3 ended 5.9 tol off silently, docs/accuracy.md section 34). */
PetscBool TSVSHMMBeatApproaching_Private(TS ts, PetscReal t1)
{
  const TS_VSHMM *vs = (const TS_VSHMM *)ts->data;
  for (const TS_VSHMM::BeatWatch &w : vs->beat_watch) {
    /* (a record of older spectra than the last is stale: the level was not looked at since) */
    if (!(w.r > 0 && w.r_before > 0 && w.t == vs->spectra_time && w.t > w.t_before && w.r < (1 - vshmm::kDistinctBeats) * w.r_before)) continue;
    if (w.t + (w.r - 1) * (w.t - w.t_before) / (w.r_before - w.r) <= t1) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}
/* The beats of the own oscillations of every faster level l >= 1 (LevelBeats(), in vs->beat_omega,
   vs->beat_level, vs->beat_phase), started at each level's LevelOscillationPart() (as
   FastestLevelDrive() takes the fastest level's). With each estimate of the spectra under -ts_vshmm_adapt
   (TSVSHMMLevelOwnRates_Private()) and once at set-up for the separation check of fixed savings.
   Counted as the stability check's evaluations. */
PetscErrorCode TSVSHMMLevelBeats_Private(TS ts)
{
  TS_VSHMM      *vs      = (TS_VSHMM *)ts->data;
  const PetscInt nscales = (PetscInt)vs->level_end.size();

  PetscFunctionBegin;
  vs->beat_omega.clear();
  vs->beat_level.clear();
  for (PetscInt L = 1; L < nscales; ++L) {
    PetscBool may;
    Vec       Osc, mask = nullptr;
    PetscCall(MayBeat(ts, L, &may));
    if (!may) continue;
    const StabilityCounting counting(vs);
    Vec                     G, Xp;
    PetscCall(VecDuplicate(ts->vec_sol, &Osc));
    PetscCall(VecDuplicate(ts->vec_sol, &Xp));
    if (ComponentLevel(vs, L)) {
      PetscCall(VecDuplicate(ts->vec_sol, &mask));
      PetscCall(TSVSHMMWrittenComponents_Private(vs, vs->level_end[L - 1], vs->level_end[L], ts->ptime, mask));
    }
    PetscCall(VecDuplicate(ts->vec_sol, &G));
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, L, ts->ptime, ts->vec_sol, G));
    PetscCall(LevelOscillationPart(ts, L, mask, G, Xp, Osc));
    PetscCall(VecDestroy(&G));
    PetscCall(VecDestroy(&Xp));
    PetscCall(LevelBeats(ts, L, Osc, mask));
    PetscCall(VecDestroy(&Osc));
    PetscCall(VecDestroy(&mask));
  }
  PetscFunctionReturn(0);
}

/* The splits against the TS's right-hand side function (TSSetRHSFunction()), once at set-up, at the
   initial state: TSVSHMM steps the splits only, so where their sum is not the function that every
   other TS type integrates (a component that no split writes, a term in two splits or in none, an
   IS that names the wrong components) it solves another problem, silently. Their difference is
   judged against the roundoff of the terms it sums: the largest output of any split. Counted as
   the stability check's evaluations; nothing when the TS has no RHS function (splits only; an
   IFunction is refused at set-up). */
PetscErrorCode TSVSHMMCheckSplitsSum_Private(TS ts)
{
  TS_VSHMM     *vs    = (TS_VSHMM *)ts->data;
  TSRHSFunction f     = nullptr;
  Vec           X     = ts->vec_sol, F, G, W;
  PetscReal     scale = 0, diff, fmax, gmax, fval = 0, gval = 0;
  PetscInt      at;

  PetscFunctionBegin;
  vs->splits_difference = -1;
  if (!vs->check_splits) PetscFunctionReturn(0);
  PetscCall(TSGetRHSFunction(ts, nullptr, &f, nullptr));
  if (!f) {
    PetscCall(PetscInfo(ts, "TSVSHMM: the TS has no RHS function, so the splits are not checked against it\n"));
    PetscFunctionReturn(0);
  }
  StabilityCounting counting(vs);
  PetscCall(VecDuplicate(X, &F));
  PetscCall(VecDuplicate(X, &G));
  PetscCall(VecDuplicate(X, &W));
  PetscCall(TSComputeRHSFunction(ts, ts->ptime, X, F));
  PetscCall(VecZeroEntries(G));
  for (PetscInt k = 0; k < (PetscInt)vs->splits.size(); ++k) {
    PetscReal norm;

    PetscCall(VecZeroEntries(W));
    PetscCall(TSComputeRHSFunction(vs->splits[k].subts, ts->ptime, X, vs->splits[k].F));
    vs->stability_evaluations++;
    PetscCall(TSVSHMMAddSplit_Private(vs, k, ts->ptime, vs->splits[k].F, W));
    PetscCall(VecNorm(W, NORM_INFINITY, &norm));
    scale = PetscMax(scale, norm);
    PetscCall(VecAXPY(G, 1.0, W));
  }
  PetscCall(VecNorm(F, NORM_INFINITY, &fmax));
  PetscCall(VecNorm(G, NORM_INFINITY, &gmax));
  PetscCall(VecWAXPY(W, -1.0, G, F));
  PetscCall(VecAbs(W));
  PetscCall(VecMax(W, &at, &diff));
  vs->splits_difference = diff / PetscMax(PetscMax(scale, fmax), PETSC_SMALL * PETSC_SMALL);
  if (std::isfinite(fmax) && std::isfinite(gmax) && diff > kSplitsSumTolerance * PetscMax(scale, fmax)) {
    PetscInt rstart, rend;

    PetscCall(VecGetOwnershipRange(X, &rstart, &rend));
    PetscReal local[2] = {0, 0}, both[2];
    if (at >= rstart && at < rend) {
      const PetscScalar *a, *b;

      PetscCall(VecGetArrayRead(F, &a));
      PetscCall(VecGetArrayRead(G, &b));
      local[0] = PetscRealPart(a[at - rstart]);
      local[1] = PetscRealPart(b[at - rstart]);
      PetscCall(VecRestoreArrayRead(F, &a));
      PetscCall(VecRestoreArrayRead(G, &b));
    }
    PetscCall(MPIU_Allreduce(local, both, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ts)));
    fval = both[0];
    gval = both[1];
    std::string names;
    for (const VSHMMSplit &s : vs->splits) names += (names.empty() ? "" : ", ") + s.name;
    PetscCall(TSVSHMMWarn_Private(ts,
                                  "TSVSHMM warning: the RHS splits (%s) do not add up to the TS's right-hand side function (TSSetRHSFunction()) at the initial state, t = %g: at component %" PetscInt_FMT
                                  " the function gives %g and the splits' sum %g, a difference of %g against split outputs up to %g in size. "
                                  "TSVSHMM steps the splits alone, so it would solve another problem than the one the function describes and other TS types (-ts_type rk) integrate. Check each split's IS (TSRHSSplitSetIS()) and terms: a component "
                                  "that no split writes, "
                                  "a term in two splits or in none. "
                                  "(-ts_vshmm_check_splits false skips this check.)\n",
                                  names.c_str(), (double)ts->ptime, at, (double)fval, (double)gval, (double)diff, (double)PetscMax(scale, fmax)));
  } else PetscCall(PetscInfo(ts, "TSVSHMM: the RHS splits add up to the RHS function at t = %g: largest difference %g, split outputs up to %g\n", (double)ts->ptime, (double)diff, (double)scale));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&W));
  PetscFunctionReturn(0);
}
