/*
  Accuracy on request for TSVSHMM (-ts_vshmm_adapt) and the separation check.

  The parameters are the micro step dt and the time ratios r_l of src/core/adapt.hpp (the savings
  factors follow from them). Each macro step is taken with the current parameters and compared
  with the same macro step from the same state taken with coarser parameters; the difference of
  the observables (or of the whole state), in the TS's weighted norm (-ts_rtol, -ts_atol), gives
  the error estimate:
  - at a calibration (the first macro step, after 1, 2, 4, 8 more, then every kRecalibrate; and
    on a retry far above its share or far above the model's prediction), one coarser run per
    parameter (dt -> 2 dt, r_l - 1 -> kRatioCoarsening (r_l - 1)) measures each parameter's own
    error term (the error model of adapt.hpp);
  - in between, one run with every term doubled rescales that model (at least kMinCycles /
    kCompareCycles cycles per macro step; where no parameter can be coarsened, the model's
    prediction or a run with dt halved).
  A macro step whose estimate exceeds its share of the tolerance, (DeltaT / (t_final - t_start))^gamma
  (errors of the sampled slow values add up partly like random ones, gamma = 1/2, up to coherently,
  gamma = 1, as measured from the signed estimates), is
  redone with finer parameters; after each accepted step the parameters for the next one are
  chosen as the cheapest the model allows for kSafety of that share. Where refining no longer
  lowers the estimate, the step is accepted and the user told once. Every step is kept inside the
  stability region of the inner Runge-Kutta method, using each level's estimated eigenvalues
  (estimated again at the state of each calibration and of a step that blew up).

  Each pair's error term in the model saturates (src/core/adapt.hpp), so that the comparison's
  small difference of two saturated runs is read as the large error it is: beyond the separation
  the application set (TSVSHMMSetScaleSeparations()), or, where the faster level only decays,
  where its transient slowed by the time ratio outlasts the macro step (an initial layer:
  vshmm::layerSaturations()); a decaying level's first ratio stays below that.

  The separation check compares the spectral radii of consecutive levels (or the separations set). VSHMM samples a faster
  level statistically; where no pair of levels is separated by at least kMinSeparation the faster
  components are part of the answer and VSHMM is the wrong tool.
*/
#include "vshmmimpl.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

static constexpr PetscReal kZeroEstimate           = 1e-3; /* of the share: the model's error after a comparison that changed nothing */
static constexpr PetscReal kMinSeparation          = 10;   /* a pair of levels this far apart in spectral radius is separated */
static constexpr PetscReal kForcedRatio            = 2;    /* a faster level's oscillation forcing the slower components this many times as hard as their own dynamics (TSVSHMMForcingRatio_Private(); the paper's oscillators 0.5-0.9) */
static constexpr PetscReal kForcedDrift            = 0.1;  /* and savings changing the second-order drift it makes by this much of the slow components' size over the run: said (CheckForcedSlowComponents()) */
static constexpr PetscReal kLostDecaySeparation    = 8;    /* a decaying pair separated at set-up has lost its separation below this (LostSeparation()) */
static constexpr PetscReal kInitialSeparation      = 10;   /* effective separation sigma_l of the first parameters */
static constexpr PetscReal kInitialDecaySeparation = 2;    /* the same where the faster level only decays */
static constexpr PetscReal kSaturationStart        = 0.5;  /* and r_l - 1 starts at most (layer) or at least (given separations) this part of the pair's saturation scale */
static constexpr PetscReal kSafety                 = 0.8;  /* the parameters aim at this fraction of a step's share */
static constexpr PetscInt  kRecalibrate            = 10;   /* macro steps between full measurements of the model */
static constexpr PetscInt  kMaxAttempts            = 12;   /* tries of one macro step */
static constexpr PetscInt  kMaxBlownTries          = 6;    /* tries in a row without an estimate (every comparison blew up) before the step fails */
static constexpr PetscInt  kMinCycles              = 5;    /* micro cycles per macro step at least */
static constexpr PetscReal kCompareCycles          = 2;    /* a comparison's cycle is at most this times the longer of the step's and DeltaT / kMinCycles */
static constexpr PetscReal kStableFraction         = 0.9;  /* of the largest stable step */
static constexpr PetscReal kDecayStableFraction    = 0.8;  /* of a decaying fastest level's largest stable micro step */
static constexpr PetscReal kFloorFactor            = 0.7;  /* a refinement that lowers the estimate by less than this has hit its floor */
static constexpr PetscReal kMinShare               = 1e-3; /* no error term is taken as less than this share of the estimate */
static constexpr PetscReal kRatioCoarsening        = 4;    /* a calibration's coarser r_l - 1 */
static constexpr PetscReal kFinerComparison        = 0.75; /* the micro step of a comparison where nothing can be coarsened */
static constexpr PetscReal kRadiusGrowth           = 1.1;  /* the fastest level's radius grown this much since the spectra were estimated: estimated again */
static constexpr PetscReal kRadiusFall             = 2;    /* a decaying level's radius fallen this much: estimated again */
static constexpr PetscReal kGrowingStep            = 2;    /* a growing mode at a try's end with dt |lambda| above this is not resolved: the micro step bounded to it */
static constexpr PetscReal kGrowingEnd             = 0.5;  /* a Rayleigh quotient above this fraction of the radius at a try's end: a growing fast mode */
static constexpr PetscInt  kMaxRadiusChecks        = 3;    /* FollowRatesAtTryEnd() per macro step at most */
static constexpr PetscReal kRelaxations            = 3;    /* and where it fell within a try, relaxes at least this many e-folds of its rate there per macro step in micro time */
static constexpr PetscReal kFinerTermShare         = 1.0;  /* a micro step term measured from the finer side below this share of the step's is not counted */
static constexpr PetscReal kComparableCoarsening   = 1.5;  /* a retry's r_l - 1 whose comparison cannot reach this factor of it is not coarsened */
static constexpr PetscReal kMaxCheaper             = 8;    /* after an accepted step the work may fall by this factor at most */
static constexpr PetscInt  kCoherenceSteps         = 4;    /* accepted steps before the budget measures how the errors add */
static constexpr PetscInt  kCoherenceKept          = 8;    /* and from this many on the largest measure stands where it is significant: */
static constexpr PetscReal kCoherenceSignificance = 2; /* the signed sum at least this many times what a random walk of the steps' errors reaches, e sqrt(k) (a chaotic fast level's estimates, noise, read gamma = 1 after 4 steps and 0.65 after 12, 5 times e, within the walk's 2 sqrt(12) e) */
static constexpr PetscReal kNegligibleSavings      = 0.05; /* a time ratio below 1 + this takes no savings */
static constexpr PetscReal kWarn                   = 2;    /* a step accepted with an estimate above this many shares is warned of */
static constexpr PetscReal kFloorAccept            = 4;    /* an estimate above this many shares is never taken as a noise floor */
static constexpr PetscReal kMissFactor             = 2;    /* a retry whose estimate is this many times the model's prediction measures the split again */
static constexpr PetscInt  kSavingsTests           = 3;    /* scales not separated: time ratios tested against a single-rate step at most this many times */
static constexpr PetscReal kWorthTesting           = 4;    /* the product of the time ratios at least this for a savings test */
static constexpr PetscReal kSavingsMargin          = 0.5;  /* and admitted where they differ by at most this fraction of the step's coherent share */
static constexpr PetscReal kUncomparedBelow        = 10;   /* a single-rate step pinned at its bounds after one below 1/this of its share, or a steady step where the slow dynamics grow an error after two: its comparison may be left out */
static constexpr PetscReal kSteadyBelow            = 2;    /* a steady step's last two estimates below 1/this of their shares: its comparison may be left out */
static constexpr PetscInt  kMaxUncompared          = 3;    /* at most this many steps in a row */
static constexpr PetscReal kSteadyFieldRise        = 4;    /* and the field at its end at most this many times that at the last step's end (a change within the step: a comparison) */
static constexpr PetscReal kOffManifold            = 10;   /* a field at a try's end that would move the state by this many times its norm plus its change in a macro step: a fast variable off its slow manifold, the try compared */
static constexpr PetscReal kPostponeBelow          = 10;   /* a scheduled calibration at a step whose estimate is below 1/this of its share waits a step */
static constexpr PetscReal kNegligibleTerm         = 0.1;  /* a calibration difference below this fraction of the largest: a negligible term */
static constexpr PetscInt  kNegligibleCalibrations = 2;    /* negligible in this many of a macro step's calibrations in a row: a retry's calibration does not measure it again */
static constexpr PetscInt  kTrustedCalibrations    = 2;    /* after this many calibrations a scheduled one is skipped where the model predicted the step's estimate */
static constexpr PetscReal kOscillationShare       = 1.0;  /* of the tolerance: the fastest level's oscillations' amplitude error over the run */
static constexpr PetscReal kOscillationSpanSteps   = 100;  /* macro steps taken as the run where it has no final time */
static constexpr PetscReal kMaxDearer              = 4;    /* and rise by this factor at most per try (the estimate is noisy: refining in steps wastes less) */
static constexpr PetscReal kOutOfReach             = 100;  /* shares: a macro step's tries with savings all above this are far out of reach */
static constexpr PetscReal kOutOfReachDearer       = 16;   /* and try single-rate steps where they cost at most this many times the last try */
static constexpr PetscReal kNegligibleEstimate     = 1e-3; /* a single-rate step pinned at its bounds after a step this far below its share is not compared */
static constexpr PetscReal kSecondScaling          = 1.5;  /* the initial layer's second comparison scales every term by this */
static constexpr PetscReal kLayerFitWindow         = 4;    /* and is made for estimates above the share by at most this factor */
static constexpr PetscReal kUnaveragedShare        = 0.5; /* of the tolerance: where a macro step that leaves the fastest oscillation unaveraged errs by more, it turns at least once per macro step (half: for a band of fast modes the measure, at one set of their relative phases, was 2-3x below the error) */
static constexpr PetscReal kBlowUpGrowth           = 1e6; /* a comparison this many times larger than its step and their start blew up */
static constexpr PetscReal kLagSaturated           = 8;   /* a comparison whose model factor E / d exceeds this takes the inherited lag scaled by kLagSaturated / factor (ComparisonStart()) */
/* The difference to a run that blew up: IEEE infinity, which std::isfinite() rejects (PETSC_INFINITY
   is PETSC_MAX_REAL / 4, a finite number, and was once read as an estimate of 4.5e307 tolerances) */
static constexpr PetscReal kPhaseSwing = 1; /* tolerances: where a faster level's phase swings the sampled quantities by more, its savings go (NoteFastQuantities(); a ripple below it, as the paper's oscillators' I1 at eps = 5e-3, 0.52 tolerances at 1e-3, is left to the comparisons) */
static constexpr PetscReal kStiffFirst      = 0.5;  /* the slowest level's spectral radius at least this part of the whole field's: the stiff split may have come first */
static constexpr PetscReal kFixedSwing      = 0.1;  /* fixed parameters: a faster level's phase in the sampled quantities is said where it swings them by this much relative to 1 + |q| */
static constexpr PetscReal kSpuriousMove    = 0.05; /* a micro step that moves the state by less than this times h |G|: a spurious rest (SpuriousRest()) */
static constexpr PetscReal kRestField       = 1e-6; /* unless h |G| is below this times |X| (a state at rest) */
static constexpr PetscReal kBlindTurn       = 0.35; /* radians per macro step of the slowest level's oscillation beyond which its signed errors cannot show coherence (OwnStepBudget()) */
static constexpr PetscReal kPhaseProjection = 0.5;  /* of a step's coherent share where the sampled quantities carry an oscillation's phase: the comparison sees the phase error projected at one phase */
static constexpr PetscReal kBlownUp         = std::numeric_limits<PetscReal>::infinity();
static constexpr PetscReal kAmplified       = 4;    /* the carried comparison's estimate above this many times the steps' sum: errors grown by the dynamics (StepBudget()) */
static constexpr PetscReal kMinGlobalScale  = 1e-3; /* a step's share shrinks by that at most to this part of it */
static constexpr PetscInt  kGrowthInterval  = 20;   /* accepted steps from a probe that found no growth to the next one's start (GrowthProbeAccepted()) */
static constexpr PetscInt  kGrowthRecheck   = 5;    /* and from one that found growth: a passing growth stops shrinking the shares soon */
static constexpr PetscReal kGrowthSaid      = 2;    /* errors grown by the slow dynamics are said where they exceed the tolerance and this many times the plain sum of the estimates */
static constexpr PetscInt  kGrowthStages    = 3;    /* a probe's rate: the smallest growth of its last this many macro steps */
static constexpr PetscReal kGrowthSteady    = 2;    /* where they grew steadily: the largest at most the smallest to this power, */
static constexpr PetscReal kGrowthSpread    = 0.1;  /* or within this of it in logarithm (an exponential growth; an error that an oscillation turns grows unevenly: Kapitza's pendulum, 1.53, 2.27, 1.15) */
static constexpr PetscInt  kGrowthMaxStages = 6;    /* an uneven growth is propagated for at most this many macro steps, then its mean growth taken, */
static constexpr PetscReal kGrowthFalling   = 0.75; /* unless its logarithm fell step after step to at most this part of the one before: a passing transient */
static constexpr PetscInt  kGrowthSteps     = 8;    /* a probe starts only where at least this many macro steps are left (up to three to measure, the rest to use the rate) */
static constexpr PetscReal kGrowthSize      = 1e-4; /* a probe's perturbation at most this part of the solution (weighted as the tolerance weighs) */
static constexpr PetscReal kGrowthPossible  = 0.1;  /* probes where the slowest level's Ritz values could grow an error by e^this over the run */
static constexpr PetscReal kGrowthStretch   = 2; /* or where the solution's motion over a macro step grew, step after step (kGrowthStages steps at least: one step's doubling can be an initial layer's), to this many times its size at the streak's start (the dissipative example's passing growth: 1.6) */
static constexpr PetscReal kFixedDamping    = 0.1;   /* fixed parameters: the fastest oscillation's amplitude lost to the micro step's damping over the run beyond which it is said (CheckMicroStepDamping()) */
static constexpr PetscInt  kSlowValueStates = 4;     /* states whose fields' values show additive splits' slow components (SlowComponentsFromValues()): the initial one, it nudged, the first two macro steps' starts */
static constexpr PetscReal kNudge           = 1e-6;  /* the nudge along the whole field, relative to 1 + ||X|| */
static constexpr PetscReal kObsStateSize    = 1e100; /* a state whose entries are below this cannot overflow an observable of degree 3: Inf or NaN from it is the observables function's */

const char *const TSVSHMMSeparationChecks[] = {"off", "warn", "error", "TSVSHMMSeparationCheck", "TSVSHMM_SEPARATION_", nullptr};

/* The tolerance's level, one number for the choices that need one (the first parameters, the micro
   step's accuracy bound, a probe's size, a swing counted in tolerances): the larger of -ts_rtol and
   -ts_atol, or where TSSetTolerances() gave vectors (which weigh the state, not the observables)
   and no observables are given, the smallest over the components of max(rtol_i, atol_i / (1 +
   |x_i|)) at the present state (tol where atol = rtol = tol; the relative tolerance where it is
   the larger, so that a component at 0 with a large atol does not set it: a level of 10 was read
   for vectors of 0.1 that gave atol 10 to a component starting at 0). With vectors alone and the
   scalars at PETSc's defaults the runs chose their first parameters for 1e-4 where the vectors
   asked 1e-2 (1.8x the work). */
PetscReal TSVSHMMToleranceLevel_Private(TS ts)
{
  TS_VSHMM *vs    = (TS_VSHMM *)ts->data;
  PetscReal level = PetscMax(ts->rtol, ts->atol);

  if (vs->observables || !(ts->vatol || ts->vrtol) || !ts->vec_sol) return level;
  const PetscScalar *x, *va = nullptr, *vr = nullptr;
  PetscInt           n;
  PetscReal          local = 0;
  if (VecGetLocalSize(ts->vec_sol, &n) || VecGetArrayRead(ts->vec_sol, &x)) return level;
  if (ts->vatol && VecGetArrayRead(ts->vatol, &va)) va = nullptr;
  if (ts->vrtol && VecGetArrayRead(ts->vrtol, &vr)) vr = nullptr;
  local = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < n; ++i) {
    const PetscReal a = PetscAbsScalar(x[i]), r = PetscMax(vr ? PetscRealPart(vr[i]) : ts->rtol, (va ? PetscRealPart(va[i]) : ts->atol) / (1 + a));
    if (std::isfinite(r) && r > 0) local = PetscMin(local, r);
  }
  if (va) (void)VecRestoreArrayRead(ts->vatol, &va);
  if (vr) (void)VecRestoreArrayRead(ts->vrtol, &vr);
  (void)VecRestoreArrayRead(ts->vec_sol, &x);
  PetscReal global = local;
  if (MPI_Allreduce(&local, &global, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)ts)) != MPI_SUCCESS) return level;
  return global < PETSC_MAX_REAL ? global : level;
}

/* -ts_vshmm_adapt's tolerances beyond the scalars' signs: observables are weighed by the scalar
   -ts_rtol and -ts_atol, so they need one of them positive; the whole state by TSErrorWeightedNorm(),
   which takes the vectors of TSSetTolerances() where given (the scalars may then be 0, as TSRK's
   adaptive steps accept), so every component needs a positive weight there. */
static PetscErrorCode CheckToleranceVectors(TS ts)
{
  TS_VSHMM *vs   = (TS_VSHMM *)ts->data;
  MPI_Comm  comm = PetscObjectComm((PetscObject)ts);

  PetscFunctionBegin;
  if (ts->rtol > 0 || ts->atol > 0) PetscFunctionReturn(0);
  PetscCheck(!vs->observables, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_adapt needs a positive tolerance for the observables (TSVSHMMSetObservables()), which the scalar tolerances weigh: -ts_rtol and -ts_atol (TSSetTolerances()) are both 0%s", (ts->vatol || ts->vrtol) ? " (the vectors of TSSetTolerances() weigh the state's components, not the observables)" : "");
  PetscCheck(ts->vatol || ts->vrtol, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_adapt needs a positive tolerance: -ts_rtol and -ts_atol (TSSetTolerances()) are both 0");
  const PetscScalar *va = nullptr, *vr = nullptr;
  PetscInt           n, bad            = -1, rstart;
  PetscCall(VecGetLocalSize(ts->vec_sol, &n));
  PetscCall(VecGetOwnershipRange(ts->vec_sol, &rstart, nullptr));
  if (ts->vatol) PetscCall(VecGetArrayRead(ts->vatol, &va));
  if (ts->vrtol) PetscCall(VecGetArrayRead(ts->vrtol, &vr));
  for (PetscInt i = 0; i < n && bad < 0; ++i) {
    const PetscReal a = va ? PetscRealPart(va[i]) : 0, r = vr ? PetscRealPart(vr[i]) : 0;
    if (!(std::isfinite(a) && std::isfinite(r) && a >= 0 && r >= 0 && (a > 0 || r > 0))) bad = rstart + i;
  }
  if (ts->vatol) PetscCall(VecRestoreArrayRead(ts->vatol, &va));
  if (ts->vrtol) PetscCall(VecRestoreArrayRead(ts->vrtol, &vr));
  PetscInt first;
  PetscCall(MPIU_Allreduce(&bad, &first, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(first < 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_adapt: with -ts_rtol and -ts_atol 0 the tolerance vectors of TSSetTolerances() weigh the state alone, and component %" PetscInt_FMT " has no positive tolerance there (every atol_i and rtol_i must be finite and non-negative, one of them positive)", first);
  PetscFunctionReturn(0);
}

/* The observables of X at t: the user's function, and on several ranks a check that it is
   collective (every rank the same values): a function that returns each rank's local part
   (forgetting the reduction) made the ranks take different decisions and the solve hang. Rank 0's
   values are then given to all, so that rounding differences of the user's reductions cannot part
   the ranks either. */
PetscErrorCode TSVSHMMObservables_Private(TS ts, PetscReal t, Vec X, PetscReal q[])
{
  TS_VSHMM   *vs   = (TS_VSHMM *)ts->data;
  MPI_Comm    comm = PetscObjectComm((PetscObject)ts);
  PetscMPIInt size;
  const auto  n = (size_t)vs->nobservables;

  PetscFunctionBegin;
  PetscCall(vs->observables(ts, t, X, q, vs->observables_ctx));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<PetscReal> range(2 * n + 2); /* max over the ranks of q_i, of -q_i, of "not finite" and of its negation */
  bool                   nonfinite = false;
  size_t                 first     = n; /* the first observable that is not finite */
  for (size_t i = 0; i < n; ++i) {
    const bool finite = std::isfinite(q[i]);
    range[i]          = finite ? q[i] : -PETSC_MAX_REAL;
    range[n + i]      = finite ? -q[i] : -PETSC_MAX_REAL;
    nonfinite |= !finite;
    if (!finite && first == n) first = i;
  }
  range[2 * n]     = nonfinite ? 1 : 0;
  range[2 * n + 1] = nonfinite ? 0 : -1;
  if (size > 1) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range.data(), (PetscMPIInt)range.size(), MPIU_REAL, MPIU_MAX, comm));
  const bool some = range[2 * n] > 0, all = range[2 * n + 1] == 0;
  PetscCheck(some == all, comm, PETSC_ERR_ARG_WRONG, "TSVSHMMSetObservables(): the observables function gave Inf or NaN on some ranks and finite values on others at t = %g: it is collective and must return the same values on every rank", (double)t);
  if (some && vs->obs_fault < 0) {
    /* Inf or NaN of a state of moderate size is the function's, not a blow-up of the run; the
       comparisons read it as one (an infinite difference) and the step's tries refine until they
       run out: the failure's message names the observable (an observable NaN from t = 0.6 on
       stopped with "no finite error estimate" and "or an observable was not finite" only). A
       state beyond kObsStateSize may overflow a polynomial observable: a blow-up. */
    PetscReal sum, largest;
    PetscCall(VecNorm(X, NORM_1, &sum)); /* the 1-norm: a NaN in any entry makes it NaN */
    PetscCall(VecNorm(X, NORM_INFINITY, &largest));
    if (std::isfinite(sum) && largest < kObsStateSize) {
      vs->obs_fault      = (PetscInt)(first < n ? first : 0);
      vs->obs_fault_time = t;
      vs->obs_fault_nan  = std::isnan(q[vs->obs_fault]) ? PETSC_TRUE : PETSC_FALSE;
    }
  }
  if (size == 1) PetscFunctionReturn(0);
  for (size_t i = 0; i < n && !some; ++i) {
    const PetscReal hi = range[i], lo = -range[n + i];
    PetscCheck(hi - lo <= kObservablesAgreement * PetscMax(PetscAbsReal(hi), PetscAbsReal(lo)), comm, PETSC_ERR_ARG_WRONG,
               "TSVSHMMSetObservables(): the observables function gave different values on different ranks at t = %g: observable %d (of %d) from %g to %g. It is collective and must return the same values on every rank: reduce the ranks' "
               "contributions "
               "(MPI_Allreduce(), or VecSum(), VecDot(), VecNorm(), which do); otherwise the ranks take different decisions",
               (double)t, (int)i, (int)n, (double)lo, (double)hi);
  }
  PetscCallMPI(MPI_Bcast(q, (PetscMPIInt)n, MPIU_REAL, 0, comm));
  PetscFunctionReturn(0);
}

/* The difference of the observables (or of the states) of Xa and Xb in the TS's weighted norm.
   record: it is a comparison's, and its signs (vs->obs_diff) and which part led (vs->slow_last,
   vs->slow_led) are kept for the step; PETSC_FALSE for measures that are no comparison (the
   unaveraged field, the carried comparison), which leave that record alone. */
static PetscErrorCode ObservableDifference(TS ts, PetscReal t, Vec Xa, Vec Xb, PetscReal *norm, PetscBool record = PETSC_TRUE)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  PetscReal xa, xb;
  PetscCall(VecNorm(Xa, NORM_1, &xa)); /* the 1-norm: a NaN in any entry makes it NaN (the max-norm may skip it) */
  PetscCall(VecNorm(Xb, NORM_1, &xb));
  if (!std::isfinite(xa) || !std::isfinite(xb)) { /* a run blew up */
    *norm = kBlownUp;
    PetscFunctionReturn(0);
  }
  if (!vs->observables) {
    PetscReal na, nr;
    PetscCall(TSErrorWeightedNorm(ts, Xa, Xb, NORM_2, norm, &na, &nr));
    PetscFunctionReturn(0);
  }
  vs->obs_a.assign(vs->nobservables, 0.0);
  vs->obs_b.assign(vs->nobservables, 0.0);
  PetscCall(TSVSHMMObservables_Private(ts, t, Xa, vs->obs_a.data()));
  PetscCall(TSVSHMMObservables_Private(ts, t, Xb, vs->obs_b.data()));
  PetscReal sum = 0;
  if (record) vs->obs_diff.assign(vs->nobservables, 0.0);
  for (PetscInt i = 0; i < vs->nobservables; ++i) {
    const PetscReal a = vs->obs_a[i], b = vs->obs_b[i];
    const PetscReal w = ts->atol + ts->rtol * PetscMax(PetscAbsReal(a), PetscAbsReal(b));
    const PetscReal e = (b - a) / w;
    if (record) vs->obs_diff[i] = std::isfinite(e) ? e : 0.0;
    sum += std::isfinite(e) ? e * e : kBlownUp;
  }
  *norm = std::sqrt(sum / vs->nobservables);
  if (vs->slow_mask) {
    /* the slow components, weighed as the observables: an error there that the observables do not
       show yet becomes theirs at later sampled times (a slow oscillator's velocity) */
    const PetscScalar *a, *b, *m, *va = nullptr, *vr = nullptr; /* the tolerances per component where TSSetTolerances() gave vectors */
    PetscInt           n;
    PetscReal          ssum = 0;
    PetscCall(VecGetLocalSize(Xa, &n));
    PetscCall(VecGetArrayRead(Xa, &a));
    PetscCall(VecGetArrayRead(Xb, &b));
    PetscCall(VecGetArrayRead(vs->slow_mask, &m));
    if (ts->vatol) PetscCall(VecGetArrayRead(ts->vatol, &va));
    if (ts->vrtol) PetscCall(VecGetArrayRead(ts->vrtol, &vr));
    for (PetscInt i = 0; i < n; ++i) {
      if (PetscRealPart(m[i]) == 0) continue;
      const PetscReal w = (va ? PetscRealPart(va[i]) : ts->atol) + (vr ? PetscRealPart(vr[i]) : ts->rtol) * PetscMax(PetscAbsScalar(a[i]), PetscAbsScalar(b[i]));
      const PetscReal e = PetscAbsScalar(b[i] - a[i]) / w;
      ssum += std::isfinite(e) ? e * e : kBlownUp;
    }
    if (ts->vatol) PetscCall(VecRestoreArrayRead(ts->vatol, &va));
    if (ts->vrtol) PetscCall(VecRestoreArrayRead(ts->vrtol, &vr));
    PetscCall(VecRestoreArrayRead(vs->slow_mask, &m));
    PetscCall(VecRestoreArrayRead(Xb, &b));
    PetscCall(VecRestoreArrayRead(Xa, &a));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ssum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ts)));
    const PetscReal slow = std::sqrt(ssum / vs->slow_count);
    if (record) vs->slow_last = slow > *norm ? PETSC_TRUE : PETSC_FALSE;
    if (slow > *norm) {
      *norm = slow;
      if (record) vs->slow_led++;
    }
  }
  PetscFunctionReturn(0);
}

/* mask = 1 where mask != 0 and other == 0, else 0; the global count of ones (the components one
   group of splits writes and another does not) */
static PetscErrorCode OnlyIn(TS ts, Vec other, Vec mask, PetscInt *total)
{
  PetscScalar       *m;
  const PetscScalar *w;
  PetscInt           n, count = 0;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(other, &n));
  PetscCall(VecGetArray(mask, &m));
  PetscCall(VecGetArrayRead(other, &w));
  for (PetscInt i = 0; i < n; ++i) {
    m[i] = (PetscRealPart(m[i]) != 0 && PetscRealPart(w[i]) == 0) ? 1.0 : 0.0;
    count += PetscRealPart(m[i]) != 0 ? 1 : 0;
  }
  PetscCall(VecRestoreArrayRead(other, &w));
  PetscCall(VecRestoreArray(mask, &m));
  PetscCall(MPIU_Allreduce(&count, total, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ts)));
  PetscFunctionReturn(0);
}

/* The fields' values at X (t): |G_0| into slowest and, where faster is given, the faster levels'
   own splits' |f| summed into it. Their evaluations count as -ts_vshmm_adapt's. */
static PetscErrorCode WrittenByValues(TS ts, PetscReal t, Vec X, Vec slowest, Vec faster)
{
  TS_VSHMM               *vs       = (TS_VSHMM *)ts->data;
  const TS_VSHMM::Counter counting = vs->counting;
  Vec                     own;

  PetscFunctionBegin;
  vs->counting = TS_VSHMM::COUNT_ADAPT;
  PetscCall(TSVSHMMEvaluateLevel_Private(vs, 0, t, X, slowest));
  PetscCall(VecAbs(slowest));
  if (faster) {
    PetscCall(VecDuplicate(X, &own));
    PetscCall(VecSet(faster, 0.0));
    for (PetscInt l = 1; l < (PetscInt)vs->level_end.size(); ++l) {
      PetscCall(TSVSHMMEvaluateOwnSplits_Private(vs, l, t, X, own));
      PetscCall(VecAbs(own));
      PetscCall(VecAXPY(faster, 1.0, own));
    }
    PetscCall(VecDestroy(&own));
  }
  vs->counting = counting;
  PetscFunctionReturn(0);
}

/* The slow components controlled with the observables (TSVSHMMSetAdaptSlowComponents()): those
   the slowest level's splits write and no faster split does, from the index sets. Where the splits
   are additive (every index set covers every component) the fields' values tell instead
   (SlowComponentsFromValues()): additive splits of x' = y, y' = -x - 0.1 y + 0.5 z, z' = -(z -
   sin x) / 1e-3, each returning zeros off its own terms, ended at 1.91 and 2.24 tolerances on x and
   x^2 + y^2 at 1e-3, the estimates summing to 0.27, where component splits met the tolerance: the
   first macro step's error in y, which the observables showed only later (docs/accuracy.md
   section 39). Not where there are as many observables as components (the sparse spectral
   examples' grid values, a transform of the whole state). */
static PetscErrorCode SlowComponentsFromValues(TS, PetscReal, Vec);
static PetscErrorCode SlowComponentsSetUp(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec       faster;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&vs->slow_mask));
  PetscCall(VecDestroy(&vs->slow_seen));
  PetscCall(VecDestroy(&vs->faster_seen));
  vs->slow_count     = 0;
  vs->slow_by_values = 0;
  if (!vs->observables || !vs->adapt_slow_components || vs->level_end.size() < 2) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ts->vec_sol, &vs->slow_mask));
  PetscCall(VecDuplicate(ts->vec_sol, &faster));
  PetscCall(TSVSHMMWrittenComponents_Private(vs, 0, vs->level_end[0], ts->ptime, vs->slow_mask));
  PetscCall(TSVSHMMWrittenComponents_Private(vs, vs->level_end[0], (PetscInt)vs->splits.size(), ts->ptime, faster));
  PetscCall(OnlyIn(ts, faster, vs->slow_mask, &vs->slow_count));
  PetscCall(VecDestroy(&faster));
  if (vs->slow_count > 0) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&vs->slow_mask));
  PetscInt N; /* as many observables as components (a transform of the whole state: the sparse spectral examples' grid values) show every error */
  PetscCall(VecGetSize(ts->vec_sol, &N));
  if (vs->nobservables >= N) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ts->vec_sol, &vs->slow_seen));
  PetscCall(VecDuplicate(ts->vec_sol, &vs->faster_seen));
  PetscCall(VecSet(vs->slow_seen, 0.0));
  PetscCall(VecSet(vs->faster_seen, 0.0));
  PetscCall(SlowComponentsFromValues(ts, ts->ptime, ts->vec_sol));
  if (vs->slow_seen) { /* and a state nudged along the whole field: an exact 0 of the initial state (p = 0 makes a fast rotation's q' = w p vanish) hides a term there */
    const TS_VSHMM::Counter counting = vs->counting;
    Vec                     G, Xn;
    PetscReal               gnorm, xnorm;
    PetscCall(VecDuplicate(ts->vec_sol, &G));
    PetscCall(VecDuplicate(ts->vec_sol, &Xn));
    vs->counting = TS_VSHMM::COUNT_ADAPT;
    PetscCall(TSVSHMMEvaluateLevel_Private(vs, (PetscInt)vs->level_end.size() - 1, ts->ptime, ts->vec_sol, G));
    vs->counting = counting;
    PetscCall(VecNorm(G, NORM_2, &gnorm));
    PetscCall(VecNorm(ts->vec_sol, NORM_2, &xnorm));
    if (gnorm > 0 && std::isfinite(gnorm)) {
      PetscCall(VecWAXPY(Xn, kNudge * (1 + xnorm) / gnorm, G, ts->vec_sol));
      PetscCall(SlowComponentsFromValues(ts, ts->ptime, Xn));
    }
    PetscCall(VecDestroy(&G));
    PetscCall(VecDestroy(&Xn));
  }
  PetscFunctionReturn(0);
}

/* The slow components from the fields' values: the slowest field seen nonzero at one of the states
   looked at, the faster levels' own splits zero at all of them. A state can hide a component
   (x' = y is 0 where y = 0, as at a rest start): the initial state, it nudged along the whole
   field (SlowComponentsSetUp()) and the first two macro steps' starts are looked at, then the mask
   stands. */
static PetscErrorCode SlowComponentsFromValues(TS ts, PetscReal t, Vec X)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec       slowest, faster;

  PetscFunctionBegin;
  if (!vs->slow_seen || vs->slow_by_values >= kSlowValueStates) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(X, &slowest));
  PetscCall(VecDuplicate(X, &faster));
  PetscCall(WrittenByValues(ts, t, X, slowest, faster));
  PetscCall(VecAXPY(vs->slow_seen, 1.0, slowest));
  PetscCall(VecAXPY(vs->faster_seen, 1.0, faster));
  PetscInt open; /* components no faster split has written yet: none, and no later state can show one */
  PetscCall(VecSet(slowest, 1.0));
  PetscCall(OnlyIn(ts, vs->faster_seen, slowest, &open));
  PetscCall(VecCopy(vs->slow_seen, slowest));
  PetscCall(OnlyIn(ts, vs->faster_seen, slowest, &vs->slow_count));
  PetscCall(VecDestroy(&faster));
  PetscCall(VecDestroy(&vs->slow_mask));
  if (vs->slow_count > 0) vs->slow_mask = slowest;
  else PetscCall(VecDestroy(&slowest));
  if (++vs->slow_by_values == kSlowValueStates || open == 0) {
    vs->slow_by_values = kSlowValueStates;
    PetscCall(VecDestroy(&vs->slow_seen));
    PetscCall(VecDestroy(&vs->faster_seen));
  }
  PetscCall(PetscInfo(ts, "Adapt: at t = %g the fields' values show %" PetscInt_FMT " slow component%s (the slowest field writes them, no faster split does): controlled with the observables\n", (double)t, vs->slow_count, vs->slow_count == 1 ? "" : "s"));
  PetscFunctionReturn(0);
}

static bool FasterLevelsDecay(TS_VSHMM *);

/* The components a comparison's end state is carried from into the next step's comparison
   (ComparisonStart()): those the faster levels' splits write and no slowest split does (their
   index sets). Where a slowest split is additive, every component is in its index set, and the
   fields' values tell instead (LagComponentsFromValues(), where an end state is first carried in; the
   dissipative example's -split_kind additive: each split returns a full-size term with its own
   component only); only where the faster levels decay at the initial state (nothing is carried
   where one oscillates). None with a single level. */
static PetscErrorCode LagComponentsSetUp(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec       slowest;
  PetscInt  total = 0;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&vs->lag_mask));
  PetscCall(VecDestroy(&vs->lag_carried));
  PetscCall(VecDestroy(&vs->lag_next));
  vs->lag_valid = vs->lag_next_valid = vs->lag_by_values = PETSC_FALSE;
  vs->lag_count                                          = 0;
  vs->lag_inherited                                      = 0;
  if (vs->level_end.size() < 2) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ts->vec_sol, &vs->lag_mask));
  PetscCall(VecDuplicate(ts->vec_sol, &slowest));
  PetscCall(TSVSHMMWrittenComponents_Private(vs, 0, vs->level_end[0], ts->ptime, slowest));
  PetscCall(TSVSHMMWrittenComponents_Private(vs, vs->level_end[0], (PetscInt)vs->splits.size(), ts->ptime, vs->lag_mask));
  PetscCall(OnlyIn(ts, slowest, vs->lag_mask, &total));
  PetscCall(VecDestroy(&slowest));
  vs->lag_count = total;
  if (total == 0) {
    PetscCall(VecDestroy(&vs->lag_mask));
    vs->lag_by_values = FasterLevelsDecay(vs) ? PETSC_TRUE : PETSC_FALSE; /* the mask from the values, when first needed */
  }
  if (vs->lag_mask || vs->lag_by_values) {
    PetscCall(VecDuplicate(ts->vec_sol, &vs->lag_carried));
    PetscCall(VecDuplicate(ts->vec_sol, &vs->lag_next));
  }
  PetscFunctionReturn(0);
}

/* The components only faster levels write, from the fields' values at X (t): a faster level's own
   splits nonzero, the slowest field zero; into lag_mask (created here), and the components where
   lag_mask already was 0 stay 0. A component the slowest field writes at a later state leaves the
   mask there (ComparisonStart()). Its evaluations count as -ts_vshmm_adapt's. */
static PetscErrorCode LagComponentsFromValues(TS ts, PetscReal t, Vec X)
{
  TS_VSHMM  *vs = (TS_VSHMM *)ts->data;
  Vec        slowest;
  const bool first = !vs->lag_mask;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(X, &slowest));
  if (first) PetscCall(VecDuplicate(X, &vs->lag_mask)); /* the faster levels' own splits, |f| summed */
  PetscCall(WrittenByValues(ts, t, X, slowest, first ? vs->lag_mask : nullptr));
  PetscCall(OnlyIn(ts, slowest, vs->lag_mask, &vs->lag_count));
  PetscCall(VecDestroy(&slowest));
  if (vs->lag_count == 0) { /* nothing to carry: none from now on */
    PetscCall(VecDestroy(&vs->lag_mask));
    PetscCall(VecDestroy(&vs->lag_carried));
    PetscCall(VecDestroy(&vs->lag_next));
    vs->lag_by_values = PETSC_FALSE;
    vs->lag_valid     = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Schedule(TS ts, const vshmm::AdaptParameters &p, std::unique_ptr<vshmm::MesoscopicSchedule> &schedule)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  vs->savings_used = vshmm::savingsFromTimeRatios(p.ratios);
  PetscCall(TSVSHMMCreateSchedule_Private(ts, p.microStep, schedule));
  PetscFunctionReturn(0);
}

/* The schedule that samples a state DeltaT after the start of the last macro step (TSInterpolate()):
   the last accepted step's parameters, its cycles at most DeltaT / kMinCycles (the ratios, then
   the micro step, shrunk where not set). */
PetscErrorCode TSVSHMMAdaptSampleSchedule_Private(TS ts, PetscReal DeltaT, std::unique_ptr<vshmm::MesoscopicSchedule> &schedule)
{
  TS_VSHMM              *vs = (TS_VSHMM *)ts->data;
  vshmm::AdaptParameters p  = vs->adapt_used;

  PetscFunctionBegin;
  vshmm::fitCycle(p, DeltaT / kMinCycles, !vs->savings.empty(), vs->micro_dt > 0);
  PetscCall(Schedule(ts, p, schedule));
  PetscFunctionReturn(0);
}

/* A macro step with p from the state in X, in place, counted as estimation work; the solve's record
   of a non-finite split output is left as it was (a run that only measures does not stop the solve:
   a non-finite result counts as an infinitely large difference). */
static PetscErrorCode EstimationStep(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT, Vec X)
{
  TS_VSHMM                                  *vs = (TS_VSHMM *)ts->data;
  std::unique_ptr<vshmm::MesoscopicSchedule> schedule;
  const PetscInt                             saved_split = vs->nonfinite_split;
  const PetscReal                            saved_time  = vs->nonfinite_time;

  PetscFunctionBegin;
  PetscCall(Schedule(ts, p, schedule));
  vs->counting = TS_VSHMM::COUNT_ADAPT;
  PetscCall(TSVSHMMRunMacroStep_Private(ts, *schedule, t0, DeltaT, X, nullptr));
  vs->counting        = TS_VSHMM::COUNT_STEPS;
  vs->nonfinite_split = saved_split;
  vs->nonfinite_time  = saved_time;
  PetscFunctionReturn(0);
}

/* A try or a comparison: the macro step with p from the step's start (vs->X0) into X. */
static PetscErrorCode TrialStep(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT, Vec X)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(((TS_VSHMM *)ts->data)->X0, X));
  PetscCall(EstimationStep(ts, p, t0, DeltaT, X));
  PetscFunctionReturn(0);
}

/* The largest micro step that keeps the amplitude of the fastest level's oscillating modes (its
   limiting Ritz values with |Im| > |Re|) within kOscillationShare of the tolerance over the whole
   run, with the time ratios of p: a micro step near the stability limit of an oscillation damps
   it (RK4 at |lambda| dt = 2.5 takes half its amplitude per step), and once the fast energy is gone
   from the run and from its comparisons alike, no estimate sees the error it leaves in the slow
   quantities (a slow variable driven by the fast energy, u' = -v/eps, v' = u/eps, y' = -y + u^2).
   The amplitude error counts with the level's part of the state (TSVSHMMLevelOwnRates_Private():
   its own components' norm, or for additive splits ||G_K(X)|| / (rho_K ||X||)): the stiffest
   wavenumbers of a sparse spectral advection scene hold about 5e-3 of ||u||, and their damping is
   not the answer's error. dtMax where the fastest level has no oscillating mode. */
/* The run the accuracy control answers for: from the solve's start (or the last restart of the
   accuracy control) to the final time, or to the last step where TSSetMaxSteps() ends the solve
   first (PETSc's default final time is PETSC_MAX_REAL: a solve bounded by its steps alone had no
   final time, and one with a far final time, -ts_max_time 1e300 -ts_max_steps 20, gave each step
   1e-300 of the tolerance: 620 million evaluations for 20 steps); 0 where neither bounds it. */
static PetscReal RunSpan(TS ts)
{
  const TS_VSHMM *vs    = (TS_VSHMM *)ts->data;
  const PetscReal start = vs->adapt_ready ? vs->adapt_tstart : ts->ptime;
  PetscReal       span  = ts->max_time - start;

  if (!(span > 0 && std::isfinite(span) && span < PETSC_MAX_REAL / 2)) span = 0;
  if (ts->max_steps < PETSC_MAX_INT && ts->max_steps > ts->steps && ts->time_step > 0) {
    const PetscReal bySteps = (ts->ptime - start) + (PetscReal)(ts->max_steps - ts->steps) * ts->time_step;
    span                    = span > 0 ? PetscMin(span, bySteps) : bySteps;
  }
  return span;
}

/* The run over which the micro step's amplitude error adds up: RunSpan(), kOscillationSpanSteps
   macro steps where there is no final time. */
PetscReal TSVSHMMAmplitudeSpan_Private(TS ts)
{
  const PetscReal span = RunSpan(ts);
  return PetscMax(span > 0 ? span : kOscillationSpanSteps * ts->time_step, ts->time_step);
}

/* What a relative amplitude error E of the fastest level's oscillations at the end of the run costs
   the state, over E: the level's own part of the state, plus what the slower levels' fields make of
   the error over the run (TSVSHMMLevelOwnRates_Private(): a thin fast rotation that a slow variable
   squares). */
static PetscReal AmplitudeWeight(TS ts)
{
  const TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  return vs->fastest_share + vs->fastest_drive;
}

/* The fastest level's oscillations' amplitude error allowed over the run, relative: the tolerance
   over AmplitudeWeight(). 1 or more: the modes may lose all of their amplitude, and the state would
   still be within the tolerance. */
static PetscReal AllowedAmplitudeLoss(TS ts)
{
  const PetscReal tol = PetscMax(TSVSHMMToleranceLevel_Private(ts), 1e-12);
  return kOscillationShare * tol / PetscMax(AmplitudeWeight(ts), 1e-12);
}

/* How far a macro step moves the observables where it leaves the fastest level's oscillation
   unaveraged: the slower levels' field at eight phases of the oscillation less its phase average
   (FastestLevelDrive()), each over DeltaT, in the weighted measure (1 = the tolerance; the largest
   of the eight). Where the time ratios slow the fastest level so far that it turns less than once
   within a macro step of micro time, the slow steps see one phase of it, and the sampled slow
   variables carry that phase's part of the field over the step: the error saturates at about this
   size, and coarser comparisons, which see the same phase, do not show it (Bounds()). Also the
   slowest frequency of the fastest level's limiting oscillations. */
PetscErrorCode TSVSHMMAdaptUnaveraged_Private(TS ts)
{
  TS_VSHMM *vs    = (TS_VSHMM *)ts->data;
  PetscReal omega = 0, worst = 0;
  Vec       Xs;

  PetscFunctionBegin;
  vs->unaveraged         = 0;
  vs->unaveraged_omega   = 0;
  vs->unaveraged_unknown = PETSC_FALSE;
  if (!vs->adapt || vs->level_limiting.empty()) PetscFunctionReturn(0);
  const size_t K = vs->level_limiting.size() - 1;
  /* the fastest level's own oscillations within kInitialSeparation of its radius: not a slower
     level's mode it also holds, nor a Ritz value of a band's inside that the Arnoldi space has not
     converged to (12.6 against a band of 1,000-1,875 took every saving) */
  const PetscReal slow = (K > 0 && vs->level_radius.size() > K) ? PetscMax(kMinSeparation * vs->level_radius[K - 1], vs->level_radius[K] / kInitialSeparation) : 0;
  for (const std::complex<double> &lambda : vs->level_limiting.back())
    if (vshmm::oscillates(lambda) && std::abs(lambda) > slow) omega = omega > 0 ? PetscMin(omega, PetscAbsReal(lambda.imag())) : PetscAbsReal(lambda.imag());
  if (!(K > 0 && omega > 0 && std::isfinite(omega))) PetscFunctionReturn(0);
  vs->unaveraged_omega = omega;
  if (!vs->fastest_phase_now) { /* no amplitude of the oscillation at this state to turn (FastestLevelDrive() did not run) */
    vs->unaveraged_unknown = PETSC_TRUE;
    PetscCall(PetscInfo(ts, "Adapt: the fastest level oscillates (slowest frequency %g) but holds no part of the state to measure its unaveraged field with: it turns at least once per macro step\n", (double)omega));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(ts->vec_sol, &Xs));
  for (Vec phase : vs->fastest_phase) {
    PetscReal d;
    PetscCall(VecWAXPY(Xs, ts->time_step, phase, ts->vec_sol));
    PetscCall(ObservableDifference(ts, ts->ptime, ts->vec_sol, Xs, &d, PETSC_FALSE));
    if (std::isfinite(d)) worst = PetscMax(worst, d);
  }
  PetscCall(VecDestroy(&Xs));
  vs->unaveraged     = worst;
  vs->unaveraged_max = PetscMax(vs->unaveraged_max, worst);
  PetscCall(PetscInfo(ts, "Adapt: a macro step that leaves the fastest level's oscillation (slowest frequency %g) unaveraged moves the observables by %g of the tolerance\n", (double)omega, (double)worst));
  PetscFunctionReturn(0);
}

/* How long one relative phase of beat b (vs->beat_omega[b], of level L = vs->beat_level[b]) counts as
   held where savings slow it below a turn per macro step: its part of the field adds up over the
   steps until the slower levels forget it, over at least 1 / rho_{L-1}, their fastest rate (at
   least DeltaT, at most half the run); a beat turning slower than the run moves a relative phase
   only g span of a half turn, so its part is counted at that fraction. */
static PetscReal BeatReach(TS ts, size_t b)
{
  const TS_VSHMM *vs     = (TS_VSHMM *)ts->data;
  const PetscInt  L      = vs->beat_level[b];
  const PetscReal span   = TSVSHMMAmplitudeSpan_Private(ts);
  const PetscReal memory = PetscMin(0.5 * span, PetscMax(ts->time_step, vs->level_radius[L - 1] > 0 ? 1.0 / vs->level_radius[L - 1] : 0.5 * span));
  return memory * PetscMin(1.0, vs->beat_omega[b] * span / PETSC_PI);
}

/* What the beats of the faster levels' own oscillations do to the observables (TSVSHMMLevelBeats_Private():
   the slower field at four relative phases of each beat, less their mean), held as BeatReach() holds
   it. Where that moves the observables by more than kUnaveragedShare, level L's beat bounds the savings
   (vs->beat_bound[L], Bounds()): it turns at least once per macro step in micro time. */
PetscErrorCode TSVSHMMAdaptBeats_Private(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec       Xs;

  PetscFunctionBegin;
  if (!vs->adapt || vs->beat_omega.empty()) PetscFunctionReturn(0);
  vs->beat_bound.resize(vs->level_end.size(), 0.0);
  vs->beat_effect.resize(vs->level_end.size(), 0.0);
  PetscCall(VecDuplicate(ts->vec_sol, &Xs));
  for (size_t b = 0; b < vs->beat_omega.size() && b < vs->beat_level.size() && 4 * b + 3 < vs->beat_phase.size(); ++b) {
    const PetscInt  L = vs->beat_level[b];
    const PetscReal g = vs->beat_omega[b], reach = BeatReach(ts, b);
    PetscReal       beat = 0;
    for (int j = 0; j < 4; ++j) {
      PetscReal d;
      PetscCall(VecWAXPY(Xs, reach, vs->beat_phase[4 * b + j], ts->vec_sol));
      PetscCall(ObservableDifference(ts, ts->ptime, ts->vec_sol, Xs, &d, PETSC_FALSE));
      if (std::isfinite(d)) beat = PetscMax(beat, d);
    }
    PetscCall(PetscInfo(ts, "Adapt: level %" PetscInt_FMT "'s modes beat at %g: one relative phase of the beat held over %g moves the observables by %g of the tolerance\n", L, (double)g, (double)reach, (double)beat));
    if (!(beat > kUnaveragedShare)) continue;
    if (!(vs->beat_bound[L] > 0) || g < (1 - vshmm::kDistinctBeats) * vs->beat_bound[L]) {
      vs->beat_bound[L]  = g;
      vs->beat_effect[L] = beat;
    } else if (g <= (1 + vshmm::kDistinctBeats) * vs->beat_bound[L]) vs->beat_effect[L] = PetscMax(vs->beat_effect[L], beat); /* the same beat again */
    if (!vs->beat_warned && vs->savings.empty()) {                                                                            /* (savings the user set: the separation check says it, CheckBeats()) */
      const PetscReal speedup = PetscMax(1.0, vs->beat_bound[L] * ts->time_step / (2 * PETSC_PI));
      const PetscReal slowed  = L < (PetscInt)vs->beat_slowed.size() ? vs->beat_slowed[L] : 1.0;
      vs->beat_warned         = PETSC_TRUE;
      /* found during the run, after steps whose savings slowed the level (by any factor: a beat at g
         loses g DeltaT (1 - 1 / r) of its relative phase per macro step slowed r times; one first
         step at r = 1.0033, then single-rate steps, left the run below 5.9 tol off): the beat's
         relative phase now is the savings', not the solution's, and the bound cannot give it
         back. A beat whose frequency falls towards zero during the run (a resonance reached:
         rotations at 1000 and 1500 - 333 t, x' = -x + q1 q2, 4.2 tol off at 1e-2 with the
         estimates at 0.8: docs/accuracy.md section 34) depends on the fast phase at the passage,
         which no savings keep */
      char late[512] = "";
      if (slowed > 1 + 1e-9)
        PetscCall(PetscSNPrintf(late, sizeof(late),
                                " It was found during the run, after macro steps whose savings slowed level %d's oscillations up to %g times: the beat's relative phase is now the savings', not the solution's, and the observables may already be off "
                                "by up to that measure, which the error estimates do not "
                                "see (a resonance reached during the run depends on the fast phase at the time, which savings do not keep: a single-rate TS type, -ts_type rk, follows it).",
                                (int)L, (double)slowed));
      PetscCall(
        TSVSHMMWarn_Private(ts,
                            "TSVSHMM warning (-ts_vshmm_adapt): at t = %g oscillations of level %d's own splits beat at frequency %g (the difference of two of their frequencies, or a combination of three or four: w1 + w2 - w3, a triad, or w1 + w2 - "
                            "w3 - w4, a quartet), a slow process "
                            "inside that level: savings slow it with the "
                            "level, and one relative phase "
                            "of it held moves the observables by %g times the tolerance. The savings now keep it turning at least once per macro step (the time ratios up to r_%d in product at most %g%s).%s%s This warning is given once per solve.\n",
                            (double)ts->ptime, (int)L, (double)vs->beat_bound[L], (double)vs->beat_effect[L], (int)L - 1, (double)speedup, speedup > 1 ? "" : ": none", late, speedup > 1 || L + 1 < (PetscInt)vs->level_end.size() || late[0] ? "" : " Without savings a single-rate TS type (-ts_type rk) does the same work without VSHMM's estimates."));
    }
  }
  PetscCall(VecDestroy(&Xs));
  PetscFunctionReturn(0);
}

/* The fastest level's oscillating limiting modes, and the mean mode of four phases of a nonlinear
   one that oscillates (at every phase, not at this one only: FastestLevelPlane()); empty where it
   does not oscillate or has no spectra yet. */
static std::vector<std::complex<double>> FastestOscillations(const TS_VSHMM *vs)
{
  std::vector<std::complex<double>> modes;
  if (vs->level_limiting.empty()) return modes;
  for (const std::complex<double> &lambda : vs->level_limiting.back())
    if (vshmm::oscillates(lambda)) modes.push_back(lambda);
  if (vs->fastest_nonlinear && vs->fastest_phase_now && vshmm::oscillates(vs->fastest_mean_mode)) modes.push_back(vs->fastest_mean_mode);
  return modes;
}

/* The time the fastest level's oscillation takes to restore its own amplitude (a limit cycle,
   FastestLevelPlane()), -1 where it does not (nor from four phases that are not an oscillation). */
static PetscReal RestoreTime(const TS_VSHMM *vs)
{
  return (vs->fastest_restore > 0 && (!vs->fastest_nonlinear || vshmm::oscillates(vs->fastest_mean_mode))) ? 1.0 / vs->fastest_restore : -1.0;
}

static PetscReal AccurateMicroStep(TS ts, const vshmm::AdaptParameters &p, PetscReal dtMax)
{
  TS_VSHMM                               *vs    = (TS_VSHMM *)ts->data;
  const std::vector<std::complex<double>> modes = FastestOscillations(vs);

  if (modes.empty() || !(dtMax > 0) || !std::isfinite(dtMax)) return dtMax;
  const PetscReal span   = TSVSHMMAmplitudeSpan_Private(ts);
  PetscReal       ratios = 1;
  for (double r : p.ratios) ratios *= r;
  /* the level's amplitude error counts with its part of the state; the modes lose at most their
     whole amplitude: where that is within the tolerance there is no bound, otherwise their summed
     log amplitude error is kept within tol / share (the lost fraction 1 - exp(-E) is at most E).
     Where the tolerance applies to the state itself (no observables), the level's own part of it
     carries the modes' phase as well, whose error the steps add coherently (a rotation keeps a
     phase lag; the whole state of a stiff-spring chain at 1e-3 ended 3.6 tol off, all of it RK4's
     lag of the fast springs, the comparisons' estimates summing to 2.1 with shares for errors of
     random sign): it counts with the level's part of the state. (Observables that turn with the
     level, NoteFastQuantities(), were measured within 1.5 tol without it: their comparisons
     already chose a finer micro step.) A phase costs at most two amplitudes (the modes turned
     over): where that is within the tolerance there is no bound either (a spectral advection's
     fastest modes, 0.2% of its coefficients, cut the micro step 4-6 times at 1e-2 for nothing). */
  const PetscReal allowed = AllowedAmplitudeLoss(ts);
  const PetscReal phase   = vs->observables ? 0 : vs->fastest_share / PetscMax(AmplitudeWeight(ts), 1e-12);
  if (!(allowed < 1) && !(allowed < 2 * phase)) return dtMax;
  /* an oscillation that restores its own amplitude (FastestLevelPlane(): a limit cycle attracts
     at its mean trace) keeps a micro step's amplitude error for about 1 / that rate of its own time,
     not for the run: the van der Pol oscillator of docs/accuracy.md section 25 had its micro step
     bound 5-10 times below what its tolerance needed, and VSHMM took 5-9 times the evaluations of a
     plain RK4. Its phase error still adds up over the run. */
  const PetscReal restore = RestoreTime(vs);
  const PetscReal dt      = vshmm::largestAccurateStep(vshmm::StabilityFunction(*vs->tableau), modes, dtMax, span / ratios, allowed, phase, restore);
  if (dt < dtMax)
    (void)(PetscInfo(ts, "Adapt: the fastest level's oscillations (%d modes, weight %g in the state%s%s) bound the micro step to %g (was %g)\n", (int)modes.size(), (double)AmplitudeWeight(ts), phase > 0 ? ", their phase counted" : "", restore > 0 && restore < span / ratios ? ", amplitude restored" : "", (double)dt, (double)dtMax));
  return dt;
}

static PetscBool LevelDecays(TS_VSHMM *, PetscInt);

/* The fraction of level l's largest stable step that its steps may take: kStableFraction, and
   kDecayStableFraction for the micro step where the fastest level only decays. Near the limit an
   explicit step hardly damps a decaying mode (RK4: |R(z)| = 0.94 at 0.99 of its limit, 0.65 at
   0.9, 0.44 at 0.8), so the fast variables no longer relax to their slow manifold within a few
   micro steps, and a spectrum estimated at another state (an initial layer moves it by 20%) puts
   the step past the limit. */
static PetscReal StableFraction(TS_VSHMM *vs, size_t l)
{
  return (l + 1 == vs->level_max_step.size() && LevelDecays(vs, (PetscInt)l)) ? kDecayStableFraction : kStableFraction;
}

/* The largest micro step the library chooses: the fastest level's stable fraction of its limit. */
static PetscReal StableMicroStep(TS_VSHMM *vs)
{
  return vs->level_max_step.empty() ? PETSC_INFINITY : StableFraction(vs, vs->level_max_step.size() - 1) * vs->level_max_step.back();
}

static PetscReal Separation(TS_VSHMM *, PetscInt);
static PetscBool LevelDecays(TS_VSHMM *, PetscInt);
static bool      LostSeparation(TS_VSHMM *, PetscInt);

/* Whether every level faster than the slowest only decays (no oscillating limiting mode). */
static bool FasterLevelsDecay(TS_VSHMM *vs)
{
  for (PetscInt l = 1; l < (PetscInt)vs->level_end.size(); ++l)
    if (!LevelDecays(vs, l)) return false;
  return true;
}

/* Whether a decaying level's rate fell at the end of a try of the present macro step
   (FollowRatesAtTryEnd()). */
static bool RateFell(const TS_VSHMM *vs)
{
  for (PetscReal r : vs->adapt_end_rates)
    if (r > 0) return true;
  return false;
}

/* The largest step of a single-rate TSRK of the same tableau within the run's bounds: stable for
   the whole field, at least kMinCycles per macro step, and resolving the fastest oscillation over
   the whole span (no savings slow it): what the run's work is set against
   (TSVSHMMAdaptCheckCost_Private()). */
static PetscReal SingleRateStep(TS ts, PetscReal DeltaT)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal h  = StableMicroStep(vs);

  if (!std::isfinite(h) || h > DeltaT / kMinCycles) h = DeltaT / kMinCycles;
  vshmm::AdaptParameters single = vs->adapt_params;
  single.ratios.assign(single.ratios.size(), 1.0);
  return AccurateMicroStep(ts, single, h);
}

/* The bounds of the choice: user-set parameters, stability, enough cycles per macro step. */
static vshmm::AdaptBounds Bounds(TS ts, PetscReal DeltaT)
{
  TS_VSHMM          *vs = (TS_VSHMM *)ts->data;
  vshmm::AdaptBounds b;

  b.fixedMicroStep = vs->micro_dt > 0 ? true : false;
  b.fixedRatios    = !vs->savings.empty() || (vs->no_separation && vs->adapt_verified.empty());
  b.maxMicroStep   = StableMicroStep(vs);
  if (!std::isfinite(b.maxMicroStep) || b.maxMicroStep > DeltaT / kMinCycles) b.maxMicroStep = DeltaT / kMinCycles;
  if (!b.fixedMicroStep) b.maxMicroStep = AccurateMicroStep(ts, vs->adapt_params, b.maxMicroStep);
  b.maxCycle = DeltaT / kMinCycles;
  for (size_t l = 0; l < vs->adapt_no_savings.size(); ++l)
    if (vs->adapt_no_savings[l]) {
      b.maxRatio.resize(vs->adapt_no_savings.size(), PETSC_INFINITY);
      b.maxRatio[l] = 1.0;
    }
  for (size_t l = 0; l + 1 < vs->level_radius.size(); ++l) {
    /* a faster level that oscillates is never slowed below the slower one (sigma_l / r_l >= 1): a
       term measured as negligible would otherwise coarsen by 2x per choice without limit (the
       oscillators at tol 1.5e-3, t = 0.8: r_2 = 11,787 against a separation of 1,000) */
    const PetscReal S = Separation(vs, (PetscInt)l);
    if (std::isfinite(S) && S > 1 && !LevelDecays(vs, (PetscInt)l + 1)) {
      b.maxRatio.resize(vs->level_radius.size() - 1, PETSC_INFINITY);
      b.maxRatio[l] = PetscMin(b.maxRatio[l], S);
    }
    if (LostSeparation(vs, (PetscInt)l) || (l < vs->adapt_phase.size() && vs->adapt_phase[l] >= 0)) { /* NoteLostSeparation(), NoteFastQuantities() */
      b.maxRatio.resize(vs->level_radius.size() - 1, PETSC_INFINITY);
      b.maxRatio[l] = 1.0;
    }
  }
  /* level l (>= 1) sped up at most `speedup` relative to the clock: r_0 ... r_{l-1} <= speedup, by
     bounding r_{l-1} with the slower ratios as they are */
  const auto boundSpeedup = [&](size_t l, PetscReal speedup) {
    PetscReal slower = 1;
    for (size_t j = 0; j + 1 < l && j < vs->adapt_params.ratios.size(); ++j) slower *= vs->adapt_params.ratios[j];
    b.maxRatio.resize(vs->level_radius.size() - 1, PETSC_INFINITY);
    b.maxRatio[l - 1] = PetscMin(b.maxRatio[l - 1], PetscMax(1.0, speedup / slower));
  };
  /* the fastest level turns at least once per macro step in micro time, DeltaT / (r_0 ... r_{K-1}) */
  if ((vs->unaveraged_unknown || vs->unaveraged_max > kUnaveragedShare) && vs->unaveraged_omega > 0 && vs->level_radius.size() > 1) boundSpeedup(vs->level_radius.size() - 1, vs->unaveraged_omega * DeltaT / (2 * PETSC_PI));
  /* and so does a level whose own modes beat where that moves the observables
     (TSVSHMMAdaptBeats_Private()): for a beat slower than a turn per macro step, no savings */
  for (size_t L = 1; L < vs->beat_bound.size() && L < vs->level_radius.size(); ++L)
    if (vs->beat_bound[L] > 0) boundSpeedup(L, vs->beat_bound[L] * DeltaT / (2 * PETSC_PI));
  /* a level whose splits depend on time explicitly sees that dependence r_0 ... r_{l-1} times
     faster than it is (one clock for every level): it stays kMinSeparation below the level's
     radius (LevelTimeRates() in vshmmstability.cpp; a fast forcing sin(t / eps) allows no savings),
     and within the tolerance of it: the level lags what it follows by about that ratio, an error
     no comparison measures (at time ratios of 35 against a forcing cos(3 t) in a fast split of
     radius 1000, the error of a macro step was the same at 69: x' = -x + z, z' = -(z - cos(3 t) x)
     / 1e-3 with DeltaT = 0.5 ended 3.3 tol off at 1e-2, silently) */
  const PetscReal tol = PetscMax(TSVSHMMToleranceLevel_Private(ts), 1e-12);
  for (size_t l = 1; l < vs->level_time_rate_max.size() && l < vs->level_radius.size(); ++l)
    if (vs->level_time_rate_max[l] > 0 && vs->level_radius[l] > 0) boundSpeedup(l, vs->level_radius[l] * PetscMin(1.0 / kMinSeparation, tol) / vs->level_time_rate_max[l]);
  /* a decaying faster level whose rate fell within the try (FollowRatesAtTryEnd(): a fold of its slow
     manifold, where the rate goes to 0) relaxes kRelaxations e-folds of its rate at the try's end
     per macro step in micro time */
  for (size_t l = 1; l < vs->adapt_end_rates.size() && l < vs->level_radius.size(); ++l)
    if (vs->adapt_end_rates[l] > 0 && LevelDecays(vs, (PetscInt)l)) boundSpeedup(l, vs->adapt_end_rates[l] * DeltaT / kRelaxations);
  if (vs->no_separation && vs->savings.empty() && !vs->adapt_verified.empty()) { /* savings up to those a single-rate step confirmed */
    bool any = false;
    b.maxRatio.resize(vs->adapt_verified.size(), PETSC_INFINITY);
    for (size_t l = 0; l < vs->adapt_verified.size(); ++l) {
      b.maxRatio[l] = PetscMin(b.maxRatio[l], vs->adapt_verified[l]);
      any           = any || b.maxRatio[l] > 1.0;
    }
    b.fixedRatios = !any;
  }
  return b;
}

/* Every step of p inside StableFraction() of each level's largest stable step (all parameters;
   with keepMicroStep the micro step stays as it is and the ratios are bounded with it). */
static void LimitAllToStableSteps(TS_VSHMM *vs, vshmm::AdaptParameters &p, bool keepMicroStep = false)
{
  std::vector<double> hmax(vs->level_max_step.size());

  for (size_t l = 0; l < hmax.size(); ++l) hmax[l] = StableFraction(vs, l) * vs->level_max_step[l];
  if (keepMicroStep && !hmax.empty()) hmax.back() = PETSC_INFINITY;
  vshmm::limitToStableSteps(p, vs->kernel->value(0.5), hmax);
}

/* The same for the parameters the library chooses; those the user set are kept (a micro step the
   user set bounds the ratios as it is, not as the stable fraction would lower it). */
static void LimitToStableSteps(TS ts, vshmm::AdaptParameters &p)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  if (vs->micro_dt > 0 && !vs->savings.empty()) return; /* nothing is the library's to choose */
  LimitAllToStableSteps(vs, p, vs->micro_dt > 0);
  if (!(vs->micro_dt > 0)) p.microStep = AccurateMicroStep(ts, p, p.microStep);
  if (!vs->savings.empty()) p.ratios = vshmm::timeRatiosFromSavings(vs->savings);
}

/* The fastest level's radius the stable steps were made for, as FollowFastestRate() compares it:
   the larger of the levels' spectra's (Arnoldi) and the power method's at the same state (its
   vector is carried from step to step and converges from below; on a non-normal field its
   estimate can exceed the spectral radius). */
static PetscErrorCode RadiusBaseline(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal rho;

  PetscFunctionBegin;
  PetscCall(TSVSHMMLevelRadius_Private(ts, (PetscInt)vs->level_end.size() - 1, &rho, NULL, NULL));
  vs->radius_baseline = PetscMax(rho, vs->level_radius.empty() ? 0.0 : vs->level_radius.back());
  PetscFunctionReturn(0);
}

/* Each level's spectrum and stable step estimated again at the present state (ts->vec_sol at
   ts->ptime), and the parameters the library chooses brought inside the new stable steps. */
static PetscErrorCode UpdateStableSteps(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (vs->spectra_time == ts->ptime) PetscFunctionReturn(0);
  PetscCall(TSVSHMMLevelSpectra_Private(ts));
  PetscCall(TSVSHMMLevelOwnRates_Private(ts));
  PetscCall(RadiusBaseline(ts));
  LimitToStableSteps(ts, vs->adapt_params);
  PetscFunctionReturn(0);
}

/* The try's time ratios brought inside the bounds that keep a level whose rate fell relaxing
   (Bounds()); *redo where they changed. */
static PetscErrorCode KeepRelaxing(TS ts, PetscReal DeltaT, PetscBool *redo)
{
  TS_VSHMM                *vs = (TS_VSHMM *)ts->data;
  const vshmm::AdaptBounds b  = Bounds(ts, DeltaT);

  PetscFunctionBegin;
  /* savings factors the user set stay as set: brought down here, they came back at the next step
     (LimitToStableSteps()), and the retry between took the micro step made for them, 1e-9 for a
     DeltaT of 0.1 (docs/accuracy.md section 30) */
  if (b.fixedRatios) PetscFunctionReturn(0);
  for (size_t l = 0; l < b.maxRatio.size() && l < vs->adapt_params.ratios.size(); ++l)
    if (vs->adapt_params.ratios[l] > 1.001 * PetscMax(1.0, b.maxRatio[l])) {
      vs->adapt_params.ratios[l] = PetscMax(1.0, b.maxRatio[l]);
      *redo                      = PETSC_TRUE;
    }
  if (*redo) PetscCall(PetscInfo(ts, "Adapt: the try taken again with the savings that keep the levels whose rate fell relaxing\n"));
  PetscFunctionReturn(0);
}

/* The fastest level's radius at the end of the try just taken (vs->Xbase at t1), by a few power
   steps (TSVSHMMLevelRadius_Private(), at every macro step). Where it has grown by kRadiusGrowth
   past the radius the steps were made for, the levels' spectra are estimated at that state too,
   each level's largest stable step and radius taken as the tighter of the two states', and the
   parameters brought inside them (*redo: the micro step or the cycle shrank, the try is taken
   again). A fast rate that grows with the solution (z' = 1000 x (x - z) as x goes from 0.2 to 1:
   the rate 5x) otherwise took the micro step past its stability limit between calibrations: the
   few fast steps of a macro step with savings do not blow up, the comparison at the same micro
   step sees nothing, and x ended 7.9 tol off at 1e-2, silently; a fast rotation whose frequency
   grows from 0 within the first step (1000 x with x from 0) lost its amplitude there at the micro
   step chosen for frequency 0, which the slow variable driven by its energy showed only later
   (3 tol at 1e-2). The same look follows the folds of a decaying level's slow manifold (its rate
   fallen, its dominant mode growing at the end, a fast variable ended off the manifold: below,
   and docs/accuracy.md section 17), for the fastest level and each decaying medium one. */
static PetscErrorCode NoteLostSeparation(TS, PetscReal);

/* Whether a try's micro steps came to a spurious rest: a fixed point of the Runge-Kutta map where
   the field is not zero. Past the stability limit of a state that a nonlinear stiff term makes
   stiffer (C' = (B - C - C^3) / 1e-5, rate 1e5 (1 + 3 C^2): within the limit at C = 0, past it on
   the slow manifold at C = 0.78) the micro steps can settle at a state where the step maps X to
   itself while G(X) is large, and the rate there looks stable (the three-level chemistry at
   DeltaT = 0.5, 1e-2: C = 0.47 for 0.78, 3.5 tol, silently; its comparison rests there too). A
   consistent step moves the state by (R(z) - 1) / z times h |G|: at least 0.14 within 0.9 of RK4's
   real limit, 0.26-0.32 for fast variables that follow their slow manifold with savings, and
   0.002-0.03 at those rests. The try's last micro step (its stages, swapped out of the way by
   TSVSHMMRunMacroStep_Private(): no copy, no evaluation) moving by less than kSpuriousMove h |G|,
   with h |G| not negligible against the state, is a rest. */
static PetscErrorCode SpuriousRest(TS ts, PetscReal t0, PetscReal t1, PetscBool *spurious)
{
  TS_VSHMM      *vs     = (TS_VSHMM *)ts->data;
  const PetscInt stages = vs->tableau->stages;
  PetscReal      norms[3];
  PetscScalar    w[vshmm::Tableau::kMaxStages];

  PetscFunctionBegin;
  *spurious = PETSC_FALSE;
  if (!(vs->rest_h > 0) || !FasterLevelsDecay(vs)) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < stages; ++i) w[i] = vs->rest_h * vs->tableau->b[i];
  PetscCall(VecSet(vs->Xtrial, 0.0)); /* the step's move, h sum_i b_i k_i */
  PetscCall(VecMAXPY(vs->Xtrial, stages, w, vs->rest_stages.data()));
  PetscCall(VecNormBegin(vs->Xtrial, NORM_2, &norms[0]));
  PetscCall(VecNormBegin(vs->rest_stages[0], NORM_2, &norms[1]));
  PetscCall(VecNormBegin(vs->Xbase, NORM_2, &norms[2]));
  PetscCall(VecNormEnd(vs->Xtrial, NORM_2, &norms[0]));
  PetscCall(VecNormEnd(vs->rest_stages[0], NORM_2, &norms[1]));
  PetscCall(VecNormEnd(vs->Xbase, NORM_2, &norms[2]));
  const PetscReal field = vs->rest_h * norms[1];
  if (!(field > kRestField * norms[2]) || !std::isfinite(norms[0])) PetscFunctionReturn(0);
  *spurious = norms[0] < kSpuriousMove * field ? PETSC_TRUE : PETSC_FALSE;
  if (*spurious)
    PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: its last micro step %g moved the state by %g of h |G| = %g (|X| %g): a spurious rest of the micro steps, the try is redone with half the micro step\n", (double)t0, (double)t1, (double)vs->rest_h, (double)(norms[0] / field), (double)field, (double)norms[2]));
  PetscFunctionReturn(0);
}

static PetscErrorCode FollowRatesAtTryEnd(TS ts, PetscReal t1, PetscBool *redo)
{
  TS_VSHMM                                      *vs = (TS_VSHMM *)ts->data;
  const PetscReal                                t0 = ts->ptime, cycle = vshmm::cycleLength(vs->adapt_params), dt = vs->adapt_params.microStep;
  Vec                                            X0 = ts->vec_sol;
  PetscReal                                      rho;
  std::vector<PetscReal>                         hmax, radius;
  std::vector<std::complex<double>>              worst;
  std::vector<std::vector<std::complex<double>>> limiting;
  PetscErrorCode                                 ierr;

  PetscFunctionBegin;
  const PetscReal base   = vs->radius_baseline;
  PetscReal       growth = 0, speed = 0, xnorm = 0, moved = 0;
  *redo       = PETSC_FALSE;
  ts->vec_sol = vs->Xbase;
  ts->ptime   = t1;
  ierr        = TSVSHMMLevelRadius_Private(ts, (PetscInt)vs->level_end.size() - 1, &rho, &speed, &growth);
  if (!ierr) ierr = VecNorm(vs->Xbase, NORM_2, &xnorm);
  if (!ierr) ierr = VecWAXPY(vs->Xtrial, -1.0, X0, vs->Xbase);
  if (!ierr) ierr = VecNorm(vs->Xtrial, NORM_2, &moved);
  /* the field at the end of the try against the sampled motion: where every faster level decays
     the fast variables end each macro step on their slow manifold, where the field moves the state
     by about its change over a step (ts->time_step |F| <= the change plus the state; with savings
     the fast variables lag the manifold by the product of the time ratios times more, and their
     field is that much larger); far more is a fast variable stopped off it, and the try is compared
     however small its last estimates (the van der Pol oscillator, single-rate at the micro step of
     a state before the fold, went through the jump at h rho = 4.1 uncompared and ended at x = 1.59,
     off its branch at 1.98: 77 tol off at 1e-3, silently) */
  PetscReal slowed = 1;
  for (double r : vs->adapt_params.ratios) slowed *= r;
  vs->adapt_off_manifold = (!ierr && FasterLevelsDecay(vs) && std::isfinite(speed) && ts->time_step * speed > kOffManifold * slowed * (xnorm + moved)) ? PETSC_TRUE : PETSC_FALSE;
  vs->adapt_try_speed    = (!ierr && std::isfinite(speed)) ? speed : 0;
  /* a decaying fastest level whose rate fell by kRadiusFall since the spectra were estimated (a fold
     of its slow manifold ahead, where the rate goes to 0): the rate at the end bounds the savings
     of this step (Bounds(): the level relaxes in micro time), and the spectra are estimated again
     at the next macro step (the van der Pol oscillator at eps = 1e-3 took the micro step of a
     state near the fold, rate 1,600, into the jump, rate 3,000, where RK4 is unstable: it came to
     rest on the repelling middle branch, uncompared, 8.7 tol off). Where its dominant mode grows
     at the end (the state past a fold, the fast variable not jumped yet: the same oscillator with
     savings 12.6 crossed the fold a step late, and the comparison with doubled terms, as late, saw
     1/100 of the error) the try is taken again without savings of the fastest level. */
  const PetscInt  K     = (PetscInt)vs->level_end.size() - 1;
  const PetscBool grows = (!ierr && LevelDecays(vs, K) && rho > 0 && growth > kGrowingEnd * rho) ? PETSC_TRUE : PETSC_FALSE;
  PetscBool       fell  = (!ierr && LevelDecays(vs, K) && rho > 0 && (grows || rho * kRadiusFall < base)) ? PETSC_TRUE : PETSC_FALSE;
  vs->adapt_end_rates.resize(K + 1, 0.0);
  if (fell) {
    vs->adapt_end_rates[K] = grows ? PETSC_SMALL : rho;
    ierr                   = PetscInfo(ts, "Adapt: the fastest level's radius %s %g times within the macro step [%g, %g]%s\n", rho < base ? "fell" : "grew", (double)(rho < base ? base / rho : rho / base), (double)t0, (double)t1, grows ? " and its dominant mode grows at the end" : "");
  }
  /* the same for each decaying medium level, against the radius of its last spectra (a fold in a
     medium level of three: y' = -x + (w - x) / 10, x' = (y - x^3 / 3 + x) / 1e-2, w' = -(w - x) /
     1e-4 crossed its folds with savings 9, 9.8 tol at 1e-1) */
  for (PetscInt l = 1; l < K && !ierr; ++l) {
    PetscReal rl, gl;
    if (!LevelDecays(vs, l) || (PetscInt)vs->level_radius.size() <= l) continue;
    ierr = TSVSHMMLevelRadius_Private(ts, l, &rl, NULL, &gl);
    if (ierr || !(rl > 0)) continue;
    const PetscBool growsl = gl > kGrowingEnd * rl ? PETSC_TRUE : PETSC_FALSE;
    if (!growsl && rl > vs->level_radius[l]) vs->level_radius[l] = rl; /* the baseline of the next fall: its rate back after a jump */
    if (!growsl && !(rl * kRadiusFall < vs->level_radius[l])) continue;
    vs->adapt_end_rates[l] = growsl ? PETSC_SMALL : rl;
    fell                   = PETSC_TRUE;
    ierr = PetscInfo(ts, "Adapt: level %" PetscInt_FMT "'s radius fell %g times within the macro step [%g, %g]%s\n", l, (double)(vs->level_radius[l] / rl), (double)t0, (double)t1, growsl ? " and its dominant mode grows at the end" : "");
  }
  /* a millionfold growth of the fastest rate within one macro step is a blow-up (the try's state
     grew without bound, finite yet: three levels started from a zero state had a medium
     rate of 6e18 at the end of their first try), not a rate to take the micro step from */
  /* an oscillating faster level slowed by the savings whose own slowest rate (an amplitude rate)
     has come within kMinSeparation of the slower level's radius by the try's end: a process inside
     it that the savings slow (NoteLostSeparation(), below; a rotation damped by a slow variable
     from 0, DeltaT = 0.5: separated at t = 0, 0.39 apart at the end of the first step, taken with
     time ratios of 11 and 25 tol off at 1e-3, silently) */
  std::vector<PetscReal> ownEnd(K + 1, 0.0);
  PetscReal              slowedTo = 1;
  for (PetscInt l = 1; l <= K && !ierr; ++l) {
    slowedTo *= vs->adapt_params.ratios[l - 1];
    if (LevelDecays(vs, l) || !(slowedTo > 1.0) || (PetscInt)vs->separations.size() >= l || (PetscInt)vs->level_slowest.size() <= l) continue;
    ierr = TSVSHMMLevelOwnSlowest_Private(ts, l, &ownEnd[l]);
  }
  const PetscBool grew = (!ierr && rho > kRadiusGrowth * base && !(rho > kBlowUpGrowth * base)) ? PETSC_TRUE : PETSC_FALSE;
  if (grew) { /* the start's spectra, kept where they are the tighter */
    hmax     = vs->level_max_step;
    radius   = vs->level_radius;
    worst    = vs->level_worst;
    limiting = vs->level_limiting;
    ierr     = TSVSHMMLevelSpectra_Private(ts);
  }
  ts->vec_sol = X0;
  ts->ptime   = t0;
  PetscCall(ierr);

  /* a growing fast mode at the end whose rate the micro step does not resolve (dt rho above
     kGrowingStep): not a fold but the try's own instability on its way to a blow-up (the
     Oregonator's fast variable, falling towards its pole at x = -q within a macro step whose
     fastest rate grew 346 times, ended past it at dt rho = 470, finite; the step was accepted and
     the next one failed with Inf). The micro step is bounded by kGrowingStep / rho until the
     spectra are estimated again (next step), and the try taken again. Not past a millionfold
     growth (a blow-up, above: the micro step would be cut to 1e-32). */
  const PetscBool unresolved = (grows && dt * rho > kGrowingStep && !(rho > kBlowUpGrowth * base)) ? PETSC_TRUE : PETSC_FALSE;
  {
    bool slower = false; /* an own rate at the end below the one the spectra gave */
    for (PetscInt l = 1; l <= K; ++l)
      if (ownEnd[l] > 0 && ownEnd[l] < vs->level_slowest[l]) {
        PetscCall(PetscInfo(ts, "Adapt: level %" PetscInt_FMT "'s own slowest rate is %g at the end of the macro step [%g, %g] (%g at its spectra)\n", l, (double)ownEnd[l], (double)t0, (double)t1, (double)vs->level_slowest[l]));
        vs->level_slowest[l] = ownEnd[l];
        slower               = true;
      }
    if (slower) {
      const std::vector<double> before = vs->adapt_params.ratios;
      PetscCall(NoteLostSeparation(ts, t1));
      if (vs->adapt_params.ratios != before) *redo = PETSC_TRUE;
    }
  }
  if (!grew) {
    if (unresolved) {
      vs->level_max_step.back() = PetscMin(vs->level_max_step.back(), kGrowingStep / rho);
      LimitToStableSteps(ts, vs->adapt_params);
      if (vs->adapt_params.microStep < 0.999 * dt) *redo = PETSC_TRUE;
    }
    if (fell) PetscCall(KeepRelaxing(ts, t1 - t0, redo));
    PetscFunctionReturn(0);
  }
  for (size_t l = 0; l < hmax.size() && l < vs->level_max_step.size(); ++l) {
    if (hmax[l] < vs->level_max_step[l]) { /* the start's limit is the tighter */
      vs->level_max_step[l] = hmax[l];
      vs->level_worst[l]    = worst[l];
      vs->level_limiting[l] = limiting[l];
    }
    vs->level_radius[l] = PetscMax(vs->level_radius[l], radius[l]);
  }
  vs->spectra_time    = t0; /* the spectra of the step [t0, t1] */
  vs->radius_baseline = PetscMax(rho, vs->level_radius.back());
  if (unresolved) vs->level_max_step.back() = PetscMin(vs->level_max_step.back(), kGrowingStep / rho);
  LimitToStableSteps(ts, vs->adapt_params);
  if (fell) PetscCall(KeepRelaxing(ts, t1 - t0, redo));
  *redo = (*redo || vs->adapt_params.microStep < 0.999 * dt || vshmm::cycleLength(vs->adapt_params) < 0.999 * cycle) ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscInfo(ts, "Adapt: the fastest level's radius grew %g times within the macro step [%g, %g]: spectra of its end state too; micro step %g (was %g)%s\n", (double)(base > 0 ? rho / base : PETSC_INFINITY), (double)t0, (double)t1,
                      (double)vs->adapt_params.microStep, (double)dt, *redo ? ", the try taken again" : ""));
  PetscFunctionReturn(0);
}

/* A micro step found at the edge of stability by tries that blew up (TSVSHMMAdaptStep_Private()):
   the fastest level's largest stable step taken as this micro step, so that the steps keep their
   stable fraction of it (StableFraction()), and the parameters brought inside. */
static PetscErrorCode EdgeMargin(TS ts, PetscReal t0, PetscReal t1)
{
  TS_VSHMM       *vs = (TS_VSHMM *)ts->data;
  const PetscReal dt = vs->adapt_params.microStep;

  PetscFunctionBegin;
  if (!vs->level_max_step.empty()) vs->level_max_step.back() = PetscMin(vs->level_max_step.back(), dt);
  LimitToStableSteps(ts, vs->adapt_params);
  PetscCall(
    PetscInfo(ts, "Adapt: macro step [%g, %g]: the micro step %g is at the edge of stability (a coarser one blew up within the stable steps of t = %g): redone with %g\n", (double)t0, (double)t1, (double)dt, (double)t0, (double)vs->adapt_params.microStep));
  PetscFunctionReturn(0);
}

/* The separation of the level pair (l, l+1): as the application set it, or the ratio of the levels'
   spectral radii. */
static PetscReal RadiusRatio(TS_VSHMM *vs, PetscInt l)
{
  return vs->level_radius[l] > 0 ? vs->level_radius[l + 1] / vs->level_radius[l] : PETSC_INFINITY;
}

/* The slowest rate of the own components of the levels faster than l (every one of them is slowed
   by r_l) over level l's spectral radius (0: not estimated, additive splits). */
static PetscInt SlowestFasterLevel(TS_VSHMM *vs, PetscInt l)
{
  PetscInt slowest = -1;
  for (PetscInt j = l + 1; j < (PetscInt)vs->level_slowest.size(); ++j)
    if (vs->level_slowest[j] > 0 && (slowest < 0 || vs->level_slowest[j] < vs->level_slowest[slowest])) slowest = j;
  return slowest;
}

static PetscReal OwnRatio(TS_VSHMM *vs, PetscInt l)
{
  const PetscInt j = SlowestFasterLevel(vs, l);
  if (j < 0) return 0;
  return vs->level_radius[l] > 0 ? vs->level_slowest[j] / vs->level_radius[l] : PETSC_INFINITY;
}

static PetscReal Separation(TS_VSHMM *vs, PetscInt l)
{
  if ((PetscInt)vs->separations.size() > l) return vs->separations[l];
  const PetscReal own = OwnRatio(vs, l);
  return own > 0 ? PetscMin(own, RadiusRatio(vs, l)) : RadiusRatio(vs, l);
}

/* Whether level l's limiting modes only decay (no oscillating one sets its stable step): its
   transients end, an initial layer among them. */
static PetscBool LevelDecays(TS_VSHMM *vs, PetscInt l)
{
  if ((PetscInt)vs->level_worst.size() <= l || (PetscInt)vs->level_limiting.size() <= l || vs->level_limiting[l].empty()) return PETSC_FALSE;
  /* a nonlinear oscillation of the fastest level that oscillates on the mean of four phases of it
     (FastestLevelPlane()) oscillates, whatever the Jacobian at this phase (van der Pol's has real
     eigenvalues at some). Not the other way: a mean that does not oscillate does not make a level
     that oscillates here decay (a chaotic fast level, Lorenz's, whose four phases about the origin
     of its components are not states of its attractor: its mean read a growing real mode, and its
     run took 638 million evaluations instead of 47 million) */
  if (l + 1 == (PetscInt)vs->level_end.size() && vs->fastest_nonlinear && vs->fastest_phase_now && vshmm::oscillates(vs->fastest_mean_mode)) return PETSC_FALSE;
  return vshmm::oscillates(vs->level_worst[l]) ? PETSC_FALSE : PETSC_TRUE;
}

/* Whether pair l is less than kMinSeparation apart by the estimates (not by separations the
   application set), where its faster level oscillates (a process inside it as slow as the slower
   level, which savings would slow with it), or only decays, was separated at the accuracy
   control's set-up and is now less than kLostDecaySeparation apart (a relaxation that slows as it
   nears its manifold: z' = -(z - x)^3 / eps relaxes at 3 (z - x)^2 / eps, below the slow rate by
   t = 0.8 from (1, 0) at eps = 1e-3, and the error its savings left in z drove x for the rest of
   the run, 7.4 tol off at 1e-4 with estimates of 0.6: docs/accuracy.md section 23). Below 8, not
   10, so that a pair at the threshold is not judged lost and found again by rounding (a band of
   rates whose slowest is 10 times the slower radius did so, with other counts on one and on two
   ranks). A decaying pair that starts less than kMinSeparation apart (2 to 10: the dissipative
   example's medium and fast levels, 4.55) keeps the savings adapt gives it (NoteLostSeparation();
   Bounds() takes none). */
static bool LostSeparation(TS_VSHMM *vs, PetscInt l)
{
  const PetscReal S = Separation(vs, l);
  if ((PetscInt)vs->separations.size() > l || !std::isfinite(S) || !(S < kMinSeparation)) return false;
  return !LevelDecays(vs, l + 1) || (l < (PetscInt)vs->adapt_separated_start.size() && vs->adapt_separated_start[l] && S < kLostDecaySeparation);
}

/* The saturation scale of each level pair's error term in adapt's model: the separation set by the
   application; otherwise where the faster level's transient, slowed by the time ratio, outlasts
   the macro step (vshmm::layerSaturations(): an initial layer; the chain's measured s_0 = 10 =
   DeltaT / e, docs/accuracy.md section 3), with the slowest rate of the faster level's own
   components (component splits) or its spectral radius. Where those components have a band of
   rates (their slowest rate more than kInitialSeparation times closer to the slower level than its
   spectral radius), the term saturates beyond that slowest rate over the slower level's radius,
   if that is smaller. */
static std::vector<double> Saturations(TS ts, const vshmm::AdaptParameters &p)
{
  TS_VSHMM           *vs = (TS_VSHMM *)ts->data;
  const PetscInt      K  = (PetscInt)p.ratios.size();
  std::vector<double> rate(K + 1, 0.0); /* decaying levels only: an oscillation's averaging error does not saturate */
  for (PetscInt l = 1; l <= K; ++l)
    if (LevelDecays(vs, l)) rate[l] = ((PetscInt)vs->level_slowest.size() > l && vs->level_slowest[l] > 0) ? vs->level_slowest[l] : ((PetscInt)vs->level_radius.size() > l ? vs->level_radius[l] : 0);
  std::vector<double> s = vshmm::layerSaturations(p, ts->time_step, rate);
  for (PetscInt l = 0; l < K; ++l) {
    if ((PetscInt)vs->separations.size() > l) s[l] = vs->separations[l];
    else if (OwnRatio(vs, l) > 0 && OwnRatio(vs, l) < RadiusRatio(vs, l) / kInitialSeparation) s[l] = s[l] > 0 ? PetscMin(s[l], OwnRatio(vs, l)) : OwnRatio(vs, l);
  }
  return s;
}

/* A steady step, whose comparison is left out (the model's prediction stands in): where every
   faster level decays, a step that cannot be coarsened (micro step and cycle at their bounds),
   after two accepted steps below their shares (kSteadyBelow) whose estimates agreed
   within kMissFactor, at most kMaxUncompared steps in a row; where a growth probe has found the
   slow dynamics growing an error, far below their shares (kUncomparedBelow). Not where the field
   at the step's end is more than kSteadyFieldRise times that at the last step's end: something
   changed within the step (a switch in a fast level's equilibrium, whose jump the savings slow:
   a lag that no prediction sees). */
static bool SteadyStep(TS_VSHMM *vs, const vshmm::AdaptParameters &p, const vshmm::AdaptBounds &b)
{
  const PetscReal last = vs->adapt_last_ratio, prev = vs->adapt_prev_ratio;

  if (!vs->adapt_calibrated || !FasterLevelsDecay(vs) || vs->adapt_uncompared >= kMaxUncompared) return false;
  if (!(b.maxCycle > 0) || vshmm::cycleLength(p) < 0.999 * b.maxCycle || (!b.fixedMicroStep && p.microStep < 0.999 * b.maxMicroStep)) return false; /* something left to coarsen */
  if (vs->adapt_end_speed > 0 && vs->adapt_try_speed > kSteadyFieldRise * vs->adapt_end_speed) return false;                                        /* the field at its end jumped: something changed within the step */
  const bool steady = last < kMissFactor * prev;                                                                                                    /* not rising: a fall only makes the model's prediction (the last estimate) an overestimate */
  /* where the slow dynamics grow every step's error, far below their shares only */
  const PetscReal below = vs->growth_rate > 0 ? kUncomparedBelow : kSteadyBelow;
  return last < 1.0 / below && prev < 1.0 / below && steady;
}

/* The first time ratios of -ts_vshmm_adapt as if every pair were separated. */
static std::vector<double> SeparatedRatios(TS ts)
{
  TS_VSHMM              *vs = (TS_VSHMM *)ts->data;
  const PetscInt         K  = (PetscInt)vs->level_end.size() - 1;
  vshmm::AdaptParameters p; /* Saturations() reads its ratios only */

  p.ratios.assign(K, 1.0);
  for (PetscInt l = 0; l < K; ++l) {
    /* Where the application set the separations, sigma_l = kInitialSeparation (its separations are
       the pairs' saturation scales, and the estimate sees them), and where the faster level only
       decays at least 1 + s_l / 2, halfway to its saturation: where the fastest modes are few
       times faster than the slowest of the faster level, sigma_l = 10 for the fastest ones left
       next to no savings (the diffsource scene of docs/spectral.md: separation 10.2, radius ratio
       29.5, a first ratio of 2.96 at 59 micro cycles, half the run's work; 6.1 now). Otherwise a
       faster level that only decays starts at sigma_l = kInitialDecaySeparation, but at most
       1 + s_l / 2 (Saturations(): near and beyond the saturation scale a coarser comparison
       changes little, and an error there, an initial layer, could not be seen); one that
       oscillates at kInitialSeparation. */
    const PetscBool given = (PetscInt)vs->separations.size() > l ? PETSC_TRUE : PETSC_FALSE;
    const PetscBool decay = (!given && LevelDecays(vs, l + 1)) ? PETSC_TRUE : PETSC_FALSE;
    const PetscReal S     = given ? RadiusRatio(vs, l) : Separation(vs, l); /* a slow rate inside a faster level (OwnRatio()) starts the ratio low */
    p.ratios[l]           = PetscMax(1.0, PetscMin(S / (decay ? kInitialDecaySeparation : kInitialSeparation), 1e8));
    if (given && LevelDecays(vs, l + 1)) p.ratios[l] = PetscMax(p.ratios[l], 1.0 + kSaturationStart * PetscMin(vs->separations[l], S)); /* (a separation beyond the radius ratio is not one) */
    if (decay) {
      const std::vector<double> sat = Saturations(ts, p);
      if (sat[l] > 0) p.ratios[l] = PetscMin(p.ratios[l], 1.0 + kSaturationStart * sat[l]);
    }
  }
  return p.ratios;
}

/* Where the scales are not separated, the time ratios to test against a single-rate step
   (VerifySavings()): the separated start `ratios`, where they make the micro cycle at least
   kWorthTesting times longer than the micro step (the test, and the calibration that follows an
   admission, cost more than smaller savings save: on the hand-set clusters of nonlinear.yaml the
   candidate 1.48, 1, 1 was admitted and the run cost 1.2-1.7x more) and every faster level decays
   (an oscillating level's savings shift its phases, and on the sparse-spectral advection scenes
   the admitted ones cost more than they saved); empty otherwise. */
static std::vector<double> SavingsCandidate(TS ts, const std::vector<double> &ratios)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal R  = 1;

  for (double r : ratios) R *= r;
  const bool worth = R >= kWorthTesting && FasterLevelsDecay(vs);
  return worth ? ratios : std::vector<double>();
}

/* The separation of every consecutive pair of levels at the present spectra, as the check prints
   it: the largest (*best), the figures, and whether any is a slow rate inside a faster level. */
static PetscErrorCode SeparationFigures(TS ts, PetscReal *best, std::string &figures, bool *own)
{
  TS_VSHMM      *vs      = (TS_VSHMM *)ts->data;
  const PetscInt nscales = (PetscInt)vs->level_end.size();

  PetscFunctionBegin;
  *best = 0;
  *own  = false;
  figures.clear();
  for (PetscInt l = 0; l + 1 < nscales; ++l) {
    const PetscReal S = Separation(vs, l);
    char            text[256];
    if ((PetscInt)vs->separations.size() > l) PetscCall(PetscSNPrintf(text, sizeof(text), "%slevels %" PetscInt_FMT "/%" PetscInt_FMT ": %.3g (set with -ts_vshmm_scale_separations)", l ? "; " : "", l, l + 1, (double)S));
    else if (OwnRatio(vs, l) > 0 && OwnRatio(vs, l) < RadiusRatio(vs, l))
      PetscCall(PetscSNPrintf(text, sizeof(text), "%slevels %" PetscInt_FMT "/%" PetscInt_FMT ": %.3g (spectral radius %.3g, slowest rate of level %" PetscInt_FMT "'s own %s %.3g)", l ? "; " : "", l, l + 1, (double)S, (double)vs->level_radius[l], SlowestFasterLevel(vs, l),
                              vs->splits[vs->level_end[SlowestFasterLevel(vs, l)] - 1].additive ? "terms (an oscillation's amplitude rate)" : "components", (double)vs->level_slowest[SlowestFasterLevel(vs, l)]));
    else PetscCall(PetscSNPrintf(text, sizeof(text), "%slevels %" PetscInt_FMT "/%" PetscInt_FMT ": %.3g (spectral radii %.3g, %.3g)", l ? "; " : "", l, l + 1, (double)S, (double)vs->level_radius[l], (double)vs->level_radius[l + 1]));
    figures += text;
    *best = PetscMax(*best, S);
    *own  = *own || (OwnRatio(vs, l) > 0 && OwnRatio(vs, l) < RadiusRatio(vs, l));
  }
  PetscFunctionReturn(0);
}

/* The savings factors the run steps with (the user's, or the defaults) against the explicit time
   dependence of the faster levels' splits (LevelTimeRates() in vshmmstability.cpp): level l sees it
   r_0 ... r_{l-1} times faster than it is, and where that comes within kMinSeparation of the
   level's spectral radius the level follows a forcing that is not there (a fast forcing sin(t /
   eps) is aliased by any savings). Said at set-up (an error with -ts_vshmm_check_separation
   error); -ts_vshmm_adapt with savings of its own bounds its time ratios instead (Bounds()). */
static PetscErrorCode CheckTimeRates(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (vs->check_separation == TSVSHMM_SEPARATION_OFF || (vs->adapt && vs->savings.empty()) || vs->time_rates_checked) PetscFunctionReturn(0); /* once, at set-up */
  vs->time_rates_checked            = PETSC_TRUE;
  const std::vector<double> r       = vshmm::timeRatiosFromSavings(vs->savings_used);
  PetscReal                 speedup = 1;
  for (size_t l = 1; l < vs->level_time_rate.size() && l < vs->level_radius.size() && l - 1 < r.size(); ++l) {
    speedup *= r[l - 1];
    const PetscReal nu = vs->level_time_rate[l], rho = vs->level_radius[l];
    if (!(nu > 0) || !(rho > 0) || !(nu * speedup > rho / kMinSeparation)) continue;
    std::string names;
    for (PetscInt k = vs->level_end[l - 1]; k < vs->level_end[l]; ++k) names += std::string(names.empty() ? "'" : ", '") + vs->splits[k].name + "'";
    PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: the RHS split(s) %s of level %d depend explicitly on time at rate %g (||dF/dt|| / (rho ||X||)), and the savings factors make the level see that dependence %g times faster, %g against its spectral radius %g: VSHMM advances one clock for every level, so the level follows a forcing that is not there. Make the fast time dependence a variable of the state (an oscillator in the fast split, (c, s)' = omega (-s, c)), use -ts_vshmm_adapt (it takes no savings that would), or a single-rate TS type (-ts_type rk); -ts_vshmm_check_separation warn runs anyway",
               (double)ts->ptime, names.c_str(), (int)l, (double)nu, (double)speedup, (double)(nu * speedup), (double)rho);
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: the RHS split(s) %s of level %d depend explicitly on time at rate %g (||dF/dt|| / (rho ||X||)), and the savings factors make the level see that dependence %g times faster, %g against its spectral radius %g: VSHMM advances one clock for every level, so the level follows a forcing that is not there and its answer will be wrong by an amount it cannot estimate. Make the fast time dependence a variable of the state (an oscillator in the fast split, (c, s)' = omega (-s, c)), use -ts_vshmm_adapt (it takes no savings that would), or a single-rate TS type (-ts_type rk). (-ts_vshmm_check_separation error makes this an error, off silences it.)\n",
                                  (double)ts->ptime, names.c_str(), (int)l, (double)nu, (double)speedup, (double)(nu * speedup), (double)rho));
  }
  PetscFunctionReturn(0);
}

/* Fixed savings that slow a beat of the fastest level's own oscillations (two frequencies a slow
   rate g apart: TSVSHMMLevelBeats_Private()) below a turn per macro step, r_0 ... r_{L-1} > g
   DeltaT / 2 pi, where one relative phase of it, held until the slower levels forget it (as
   TSVSHMMAdaptUnaveraged_Private() holds it), moves a component of the state by more than
   kFixedSwing relative to 1 + |x_i|: the slow steps see one relative phase, and the answer is wrong
   (x' = -x + q1 q2 with rotations at 1000 and 1010, time ratio 100: x(2) 0.37 for 0.046). Said (an
   error with -ts_vshmm_check_separation error), once, at set-up; -ts_vshmm_adapt with the savings
   left to it keeps the beat turning instead. */
static PetscErrorCode CheckBeats(TS ts)
{
  TS_VSHMM      *vs = (TS_VSHMM *)ts->data;
  const PetscInt K  = (PetscInt)vs->level_end.size() - 1;
  Vec            D;

  PetscFunctionBegin;
  if (vs->check_separation == TSVSHMM_SEPARATION_OFF || (vs->adapt && vs->savings.empty()) || vs->beats_checked || K < 1) PetscFunctionReturn(0);
  vs->beats_checked             = PETSC_TRUE;
  const std::vector<double> r   = vshmm::timeRatiosFromSavings(vs->savings_used);
  PetscReal                 all = 1;
  for (double x : r) all *= x;
  if (!(all > 1.0 + kNegligibleSavings)) PetscFunctionReturn(0);
  PetscCall(TSVSHMMLevelBeats_Private(ts));
  if (vs->beat_omega.empty()) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(ts->vec_sol, &D));
  for (size_t b = 0; b < vs->beat_omega.size() && b < vs->beat_level.size() && 4 * b + 3 < vs->beat_phase.size(); ++b) {
    const PetscInt  L = vs->beat_level[b];
    const PetscReal g = vs->beat_omega[b], allowed = PetscMax(1.0, g * ts->time_step / (2 * PETSC_PI)), reach = BeatReach(ts, b);
    PetscReal       speedup = 1; /* level L's: r_0 ... r_{L-1} */
    for (PetscInt l = 0; l < L && l < (PetscInt)r.size(); ++l) speedup *= r[l];
    if (!(speedup > allowed)) continue;
    PetscReal swing = 0;
    for (int j = 0; j < 4; ++j) { /* |reach D_i| / (1 + |x_i|), the largest component */
      PetscReal m;
      PetscCall(VecCopy(ts->vec_sol, D));
      PetscCall(VecAbs(D));
      PetscCall(VecShift(D, 1.0));
      PetscCall(VecPointwiseDivide(D, vs->beat_phase[4 * b + j], D));
      PetscCall(VecNorm(D, NORM_INFINITY, &m));
      if (std::isfinite(m)) swing = PetscMax(swing, reach * m);
    }
    PetscCall(PetscInfo(ts, "Separation check at t = %g: level %" PetscInt_FMT "'s own oscillations beat at %g; one relative phase of it held over %g moves the state by %g relative to 1 + |x_i|\n", (double)ts->ptime, L, (double)g, (double)reach, (double)swing));
    if (!(swing > kFixedSwing)) continue;
    PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: oscillations of level %d's own splits beat at frequency %g (the difference of two of their frequencies, or a combination of three or four: w1 + w2 - w3, a triad, or w1 + w2 - w3 - w4, a quartet), a slow process inside that level, and the savings factors slow it %g times, to less than a turn per macro step (the time ratios up to r_%d in product at most %g keep one): one relative phase of the beat held moves the state by %g relative to 1 + |x_i|, so the answer will be wrong by an amount VSHMM cannot estimate. Use smaller savings factors, -ts_vshmm_adapt without them, or a single-rate TS type (-ts_type rk); -ts_vshmm_check_separation warn runs anyway",
               (double)ts->ptime, (int)L, (double)g, (double)speedup, (int)L - 1, (double)allowed, (double)swing);
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: oscillations of level %d's own splits beat at frequency %g (the difference of two of their frequencies, or a combination of three or four: w1 + w2 - w3, a triad, or w1 + w2 - w3 - w4, a quartet), a slow process inside that level, and the savings factors slow it %g times, to less than a turn per macro step (the time ratios up to r_%d in product at most %g keep one): one relative phase of the beat held moves the state by %g relative to 1 + |x_i|, so the answer will be wrong by an amount VSHMM cannot estimate. Use smaller savings factors, -ts_vshmm_adapt without them, or a single-rate TS type (-ts_type rk). (-ts_vshmm_check_separation error makes this an error, off silences it.)\n",
                                  (double)ts->ptime, (int)L, (double)g, (double)speedup, (int)L - 1, (double)allowed, (double)swing));
    break;
  }
  PetscCall(VecDestroy(&D));
  PetscFunctionReturn(0);
}

/* Fixed savings (no -ts_vshmm_adapt) where some pair of levels is separated, so that the check
   below finds the scales separated, but a pair whose faster level oscillates is less than
   kMinSeparation apart: the savings slow that level's oscillation relative to the slower level by
   the pair's time ratio, and its phase drifts with every turn, by an amount no part of VSHMM
   estimates. Three levels at rates 0.5, 3 and 1e3 (x' = -x / 2 + u + (p^2 + q^2) / 10, the medium
   level a rotation at 3 forced by x, the fast one at 1e3) to t = 2: x = 0.152 with the savings
   factors 1, 10 (time ratio 1.09 between the slow and the medium level), 1.05 with 100, 10, -0.29
   with the defaults, for 0.325, silently: the check looked only for no pair separated. Said per
   pair (an error with -ts_vshmm_check_separation error); -ts_vshmm_adapt takes no savings there
   itself (LostSeparation(), NoteLostSeparation()). A pair whose faster level only decays is left
   alone: slowed, a relaxing level lags its slow manifold by the time ratio times its lag, an error
   the savings set and hand tuning measures (the paper's sparse diffusion scene: clusters 1.9 and
   8.5 apart with savings across them, within the explicit sparse method's error). */
static PetscErrorCode CheckSlowedOscillations(TS ts)
{
  TS_VSHMM                 *vs     = (TS_VSHMM *)ts->data;
  const PetscInt            K      = (PetscInt)vs->level_end.size() - 1;
  const std::vector<double> ratios = vshmm::timeRatiosFromSavings(vs->savings_used);
  std::string               pairs, names;

  PetscFunctionBegin;
  for (PetscInt l = 0; l < K && l < (PetscInt)ratios.size(); ++l) {
    const PetscReal S = Separation(vs, l);
    if (!(S < kMinSeparation) || LevelDecays(vs, l + 1) || !(ratios[l] > 1.0 + kNegligibleSavings)) continue;
    char pair[256];
    PetscCall(PetscSNPrintf(pair, sizeof pair, "levels %d/%d are %.3g apart and level %d oscillates; the savings slow it by the time ratio %.3g (savings factor alpha_%d = %g), to an effective separation of %.3g", (int)l, (int)l + 1, (double)S, (int)l + 1, (double)ratios[l], (int)l + 1,
                            (double)vs->savings_used[l], (double)(S / ratios[l])));
    pairs += (pairs.empty() ? "" : "; ") + std::string(pair);
    std::string scale;
    for (PetscInt j = 0; j <= K; ++j) {
      for (PetscInt k = j > 0 ? vs->level_end[j - 1] : 0; k < vs->level_end[j]; ++k) scale += (k > (j > 0 ? vs->level_end[j - 1] : 0) ? "+" : "") + vs->splits[k].name;
      if (j < K) scale += j == l ? "+" : ",";
    }
    names = scale;
  }
  if (pairs.empty()) PetscFunctionReturn(0);
  PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: %s. VSHMM samples a faster level statistically; a slowed oscillation that is not faster than the slower level is part of the answer, and its phase drifts by an amount VSHMM cannot estimate. Give the two levels one scale (-ts_vshmm_splits %s), use -ts_vshmm_adapt (it takes no savings between them), or a single-rate TS type (-ts_type rk); -ts_vshmm_check_separation warn runs anyway",
             (double)ts->ptime, pairs.c_str(), names.c_str());
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: %s. VSHMM samples a faster level statistically; a slowed oscillation that is not faster than the slower level is part of the answer, and its phase drifts by an amount VSHMM cannot estimate: the answer will be wrong. Give the two levels one scale (-ts_vshmm_splits %s), use -ts_vshmm_adapt (it takes no savings between them), or a single-rate TS type (-ts_type rk). (-ts_vshmm_check_separation error makes this an error, off silences it.)\n",
                                (double)ts->ptime, pairs.c_str(), names.c_str()));
  PetscFunctionReturn(0);
}

/* Fixed savings (no -ts_vshmm_adapt): a faster level whose oscillation forces the slower level's
   components much harder than their own dynamics move them (TSVSHMMForcingRatio_Private(): kappa
   times) makes them swing at its frequency, and where the slower field's Jacobian turns with the
   oscillation too, the correlation of that swing with it drifts the slow dynamics (the
   second-order averaging of a fast force: Kapitza's pendulum stands inverted on it). Savings that
   slow the faster level by r enlarge the swing in phase with the force r^2 times, and the drift
   with it: where the change over the run exceeds kForcedDrift of the slow components' size, the
   answer is wrong, and no comparison of VSHMM runs (each with savings) shows it (Kapitza's
   pendulum, kappa 13.5, a drift of 0.56 per unit time: savings factor 0.05 ended 0.14 off, 1 ended
   0.37 off, 10 and 100 spun it round, silently). The paper's oscillators (kappa 0.9 and 0.5) and a
   force without a turning Jacobian (x' = -x + q^2: no drift) are not concerned. */
static PetscErrorCode CheckForcedSlowComponents(TS ts)
{
  TS_VSHMM                 *vs     = (TS_VSHMM *)ts->data;
  const PetscInt            K      = (PetscInt)vs->level_end.size() - 1;
  const std::vector<double> ratios = vshmm::timeRatiosFromSavings(vs->savings_used);
  const PetscReal           span   = TSVSHMMAmplitudeSpan_Private(ts);
  std::string               pairs;

  PetscFunctionBegin;
  for (PetscInt l = 0; l < K && l < (PetscInt)ratios.size(); ++l) {
    if (!(ratios[l] > 1.0)) continue; /* (even small savings: a drift of the order of the slow dynamics changes by 2 (r - 1) of itself) */
    PetscReal kappa, drift, omega;
    PetscCall(TSVSHMMForcingRatio_Private(ts, ts->ptime, ts->vec_sol, l, &kappa, &drift, &omega));
    const PetscReal change = drift * (ratios[l] * ratios[l] - 1) * span; /* over the run, relative to 1 + |x| */
    if (!(kappa > kForcedRatio && change > kForcedDrift)) continue;
    char pair[400];
    PetscCall(PetscSNPrintf(pair, sizeof pair, "level %d's oscillation (frequency %.3g) forces level %d's components %.3g times as hard as their own dynamics, and their swing drifts them by %.3g of their size per unit time; the savings slow the oscillation by the time ratio %.3g (savings factor alpha_%d = %g), which multiplies that drift by %.3g: a change of about %.3g of their size over the run", (int)l + 1, (double)omega, (int)l, (double)kappa, (double)drift, (double)ratios[l], (int)l + 1,
                            (double)vs->savings_used[l], (double)(ratios[l] * ratios[l]), (double)change));
    pairs += (pairs.empty() ? "" : "; ") + std::string(pair);
  }
  if (pairs.empty()) PetscFunctionReturn(0);
  PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: %s. A fast force on slow components (a vibrating pivot, a particle in a fast oscillating field) acts on the slow dynamics through the swing it gives them, which slowing the force enlarges: VSHMM's averaging does not apply. Use a single-rate TS type (-ts_type rk), or -ts_vshmm_adapt (its comparisons refuse such savings); -ts_vshmm_check_separation warn runs anyway",
             (double)ts->ptime, pairs.c_str());
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: %s. A fast force on slow components (a vibrating pivot, a particle in a fast oscillating field) acts on the slow dynamics through the swing it gives them, which slowing the force enlarges: VSHMM's averaging does not apply, and the answer will be wrong by an amount it cannot estimate. Use a single-rate TS type (-ts_type rk), or -ts_vshmm_adapt (its comparisons refuse such savings). (-ts_vshmm_check_separation error makes this an error, off silences it.)\n",
                                (double)ts->ptime, pairs.c_str()));
  PetscFunctionReturn(0);
}

/* Fixed parameters (no -ts_vshmm_adapt): where the fastest level oscillates, the Runge-Kutta
   method's |R(i omega dt)| < 1 at the micro step damps its amplitude at every one of its steps, and
   over the run that can take most of it (three levels, the fastest a rotation at 1,000 driving the
   slow variable through its energy: the default micro step DeltaT / 100 = 1e-3, h omega = 1, stable,
   left 1.3e-3 of the energy 1 at t = 2, and x was wrong, silently). No comparison sees a loss that
   every run shares; -ts_vshmm_adapt bounds the micro step by it (AccurateMicroStep()). Said where
   more than kFixedDamping of the amplitude goes over the run (an oscillation that restores
   its own amplitude keeps the loss over the time it takes to restore it, as there); with the
   stability check (-ts_vshmm_check_stability false silences it). */
static PetscErrorCode CheckMicroStepDamping(TS ts)
{
  TS_VSHMM                               *vs    = (TS_VSHMM *)ts->data;
  const std::vector<std::complex<double>> modes = FastestOscillations(vs);
  PetscReal                               omega = 0;

  PetscFunctionBegin;
  if (modes.empty()) PetscFunctionReturn(0);
  for (const std::complex<double> &lambda : modes) omega = PetscMax(omega, std::abs(lambda.imag()));
  const PetscReal dt     = vs->micro_dt > 0 ? vs->micro_dt : ts->time_step / kDefaultMicroStepsPerMacroStep;
  PetscReal       ratios = 1;
  for (double r : vshmm::timeRatiosFromSavings(vs->savings_used)) ratios *= r;
  const PetscReal span = TSVSHMMAmplitudeSpan_Private(ts);
  const PetscReal ok   = vshmm::largestAccurateStep(vshmm::StabilityFunction(*vs->tableau), modes, dt, span / ratios, kFixedDamping, 0.0, RestoreTime(vs));
  if (!(ok < 0.999 * dt)) PetscFunctionReturn(0);
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: the micro step dt = %g damps the fastest scale's oscillation (frequency %g, h omega = %.3g) by more than %g of its amplitude over the run (TSRK %s: |R(i omega dt)| < 1 at each of its %.3g steps to t = %g), energy that no part of VSHMM sees: its part of the answer is lost. A micro step of at most %g keeps the loss within %g; -ts_vshmm_adapt bounds it by the tolerance. (-ts_vshmm_check_stability false silences this.)\n", (double)dt, (double)omega, (double)(omega * dt), (double)kFixedDamping,
                                vs->tableau->name.c_str(), (double)(span / (dt * ratios)), (double)(ts->ptime + span), (double)ok, (double)kFixedDamping));
  PetscFunctionReturn(0);
}

/* The separation check: spectral radii of consecutive levels (or the separations set). */
PetscErrorCode TSVSHMMCheckSeparation_Private(TS ts)
{
  TS_VSHMM      *vs      = (TS_VSHMM *)ts->data;
  MPI_Comm       comm    = PetscObjectComm((PetscObject)ts);
  const PetscInt nscales = (PetscInt)vs->level_end.size();

  PetscFunctionBegin;
  if (vs->check_separation == TSVSHMM_SEPARATION_OFF && !vs->adapt) PetscFunctionReturn(0);
  if (vs->spectra_time != ts->ptime || (PetscInt)vs->level_radius.size() != nscales) PetscCall(TSVSHMMLevelSpectra_Private(ts));
  PetscCall(TSVSHMMLevelOwnRates_Private(ts));
  PetscReal   best;
  std::string figures;
  bool        own;
  PetscCall(SeparationFigures(ts, &best, figures, &own));
  vs->no_separation   = best < kMinSeparation ? PETSC_TRUE : PETSC_FALSE;
  vs->separation_time = ts->ptime;
  PetscCall(CheckTimeRates(ts));
  PetscCall(CheckBeats(ts));
  PetscCall(PetscInfo(ts, "Separation check at t = %g: %s\n", (double)ts->ptime, figures.c_str()));
  if (!vs->adapt && vs->check_stability) PetscCall(CheckMicroStepDamping(ts));
  if (!vs->no_separation && !vs->adapt && vs->check_separation != TSVSHMM_SEPARATION_OFF) PetscCall(CheckSlowedOscillations(ts));
  if (!vs->no_separation && !vs->adapt && vs->check_separation != TSVSHMM_SEPARATION_OFF) PetscCall(CheckForcedSlowComponents(ts));
  if (!vs->no_separation || vs->check_separation == TSVSHMM_SEPARATION_OFF) PetscFunctionReturn(0);
  const char *what = (vs->separations.empty() && !own) ? "ratio of the spectral radii of consecutive levels" : "separation of consecutive levels";
  /* the slowest level alone as stiff as the whole field: the stiff split may have come first (the
     scales are taken in creation order; a fast split created before the slow one gave "not
     separated" with nothing to say why) */
  std::string order;
  if (nscales > 1 && vs->level_radius[0] > 0 && vs->level_radius[0] >= kStiffFirst * vs->level_radius.back()) {
    std::string reversed; /* two scales: the other order */
    for (PetscInt l = nscales - 1; l >= 0 && nscales == 2; --l) {
      std::string scale;
      for (PetscInt k = l > 0 ? vs->level_end[l - 1] : 0; k < vs->level_end[l]; ++k) scale += (scale.empty() ? "" : "+") + vs->splits[k].name;
      reversed += (reversed.empty() ? "" : ",") + scale;
    }
    char radii[64];
    PetscCall(PetscSNPrintf(radii, sizeof radii, "%.3g of %.3g", (double)vs->level_radius[0], (double)vs->level_radius.back()));
    order = " The slowest scale alone (the first, split '" + vs->splits[0].name + "') is as stiff as the whole field (spectral radius " + radii + "): the scales are taken slowest first, in the order the RHS splits were created or as -ts_vshmm_splits (TSVSHMMSetSplitOrder()) gives them; if a stiff split came first, give the order (" + (nscales == 2 ? "here: -ts_vshmm_splits " + reversed : std::string("-ts_vshmm_splits with the split names, slowest first")) + ").";
  }
  PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, comm, PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: the time scales of the RHS splits are not separated (%s, at least %g needed: %s). VSHMM samples the faster scales statistically and would change the answer here; use a single-rate TS type (-ts_type rk) or a multirate one (-ts_type mprk), or -ts_vshmm_check_separation warn to run anyway.%s",
             (double)ts->ptime, what, (double)kMinSeparation, figures.c_str(), order.c_str());
  const bool tested = vs->adapt && vs->savings.empty() && !SavingsCandidate(ts, SeparatedRatios(ts)).empty(); /* the first time ratios as if separated, tested against a single-rate step */
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: the time scales of the RHS splits are not separated (%s, at least %g needed: %s). VSHMM samples the faster scales statistically and %s; a single-rate TS type (-ts_type rk) or a multirate one (-ts_type mprk) is the right tool.%s (-ts_vshmm_check_separation error makes this an error, off silences it.)\n",
                                (double)ts->ptime, what, (double)kMinSeparation, figures.c_str(),
                                !(vs->adapt && vs->savings.empty()) ? "its answer will be wrong by an amount it cannot estimate"
                                : tested                            ? "-ts_vshmm_adapt therefore takes savings only where a comparison with a single-rate macro step admits them (every faster level decays)"
                                                                    : "-ts_vshmm_adapt therefore takes no savings (every level steps with the micro step) unless the levels' spectra, estimated again with its calibrations, show them separated later",
                                order.c_str()));
  PetscFunctionReturn(0);
}

/* The accepted steps' history that the step rules read (coherence, steady steps, the end's field):
   none yet (a new run, or adapt's parameters chosen again). */
static void ResetStepHistory(TS_VSHMM *vs)
{
  vs->adapt_signed.clear();
  vs->adapt_coherence      = 0.5;
  vs->adapt_accepted       = 0;
  vs->adapt_start_accepted = 0;
  vs->adapt_last_ratio     = PETSC_MAX_REAL;
  vs->adapt_prev_ratio     = PETSC_MAX_REAL;
  vs->adapt_uncompared     = 0;
  vs->adapt_end_speed      = 0;
  vs->adapt_try_speed      = 0;
}

PetscErrorCode TSVSHMMAdaptReset_Private(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&vs->Xtrial));
  for (Vec &k : vs->rest_stages) PetscCall(VecDestroy(&k));
  vs->rest_stages.clear();
  vs->rest_found = PETSC_FALSE;
  PetscCall(VecDestroy(&vs->Xcarried));
  PetscCall(VecDestroy(&vs->Xbase));
  PetscCall(VecDestroy(&vs->growth_X));
  PetscCall(VecDestroy(&vs->growth_Y));
  vs->growth_time  = PETSC_MIN_REAL;
  vs->growth_stage = 0;
  vs->growth_recent.clear();
  vs->growth_due              = 0;
  vs->growth_measured         = PETSC_FALSE;
  vs->growth_rate             = 0;
  vs->growth_warned           = PETSC_FALSE;
  vs->growth_amplified        = 0;
  vs->growth_amplified_before = 0;
  vs->growth_rate_max         = 0;
  vs->growth_probe_estimates  = 0;
  vs->growth_log_sum          = 0;
  vs->growth_log_count        = 0;
  vs->growth_damped           = PETSC_FALSE;
  vs->growth_move             = 0;
  vs->growth_streak           = 0;
  vs->growth_streak_steps     = 0;
  PetscCall(VecDestroy(&vs->slow_mask));
  PetscCall(VecDestroy(&vs->slow_seen));
  PetscCall(VecDestroy(&vs->faster_seen));
  vs->slow_by_values = 0;
  PetscCall(VecDestroy(&vs->lag_mask));
  PetscCall(VecDestroy(&vs->lag_carried));
  PetscCall(VecDestroy(&vs->lag_next));
  vs->lag_valid = vs->lag_next_valid = PETSC_FALSE;
  vs->slow_count                     = 0;
  vs->slow_steps                     = 0;
  vs->adapt_ready                    = PETSC_FALSE;
  vs->adapt_since_calibration        = 0;
  vs->adapt_calibrated               = PETSC_FALSE;
  vs->adapt_calibrated_times         = 0;
  vs->adapt_postponed                = PETSC_FALSE;
  vs->no_separation                  = PETSC_FALSE;
  vs->separated_from                 = -1;
  vs->adapt_lost.clear();
  vs->lost_warned = PETSC_FALSE;
  vs->adapt_phase.clear();
  vs->phase_warned    = PETSC_FALSE;
  vs->unstable_warned = PETSC_FALSE;
  vs->adapt_no_savings.clear();
  vs->adapt_merged.clear();
  ResetStepHistory(vs);
  vs->floor_warned           = PETSC_FALSE;
  vs->global_warned          = PETSC_FALSE;
  vs->carried_time           = PETSC_MIN_REAL;
  vs->global_estimate        = 0;
  vs->global_estimate_max    = 0;
  vs->carried_restarts       = 0;
  vs->adapt_floor_dt         = 0;
  vs->adapt_single_rate_from = -1;
  vs->adapt_end              = PETSC_MIN_REAL;
  vs->adapt_end_norm         = 0;
  PetscFunctionReturn(0);
}

/* The micro step adapt starts from at the present spectra: the user's, or (an oscillating fastest
   mode must be followed accurately: dt |lambda| <= tol^(1/p); one that only decays need not (its
   error decays with it), nor one whose whole part of the state is within the tolerance (the
   amplitude bound's reasoning, AccurateMicroStep())) at the stability limit, also where that is
   longer than DeltaT / 100 (a fast level 9 times the slow rate with DeltaT = 1 took 2,500
   evaluations from DeltaT / 100, 320 from its stability limit). */
static PetscReal FirstMicroStep(TS ts)
{
  TS_VSHMM       *vs     = (TS_VSHMM *)ts->data;
  const PetscInt  K      = (PetscInt)vs->level_end.size() - 1;
  const PetscReal DeltaT = ts->time_step, tol = PetscMax(TSVSHMMToleranceLevel_Private(ts), 1e-12), rho = vs->level_radius[K];

  if (vs->micro_dt > 0) return vs->micro_dt;
  const PetscBool oscillating = LevelDecays(vs, K) ? PETSC_FALSE : PETSC_TRUE;
  PetscReal       dt          = DeltaT / kDefaultMicroStepsPerMacroStep;
  if (!oscillating && vs->level_max_step[K] < PETSC_INFINITY) dt = PetscMax(dt, PetscMin(StableMicroStep(vs), DeltaT / kMinCycles));
  if (rho > 0 && oscillating && AllowedAmplitudeLoss(ts) < 1) dt = PetscMin(dt, std::pow(tol, 1.0 / vs->tableau->order) / rho);
  return PetscMin(dt, StableMicroStep(vs));
}

/* The time ratios adapt starts from, by the separation check's verdict (vs->no_separation). */
static PetscErrorCode FirstRatios(TS ts, vshmm::AdaptParameters &p)
{
  TS_VSHMM      *vs = (TS_VSHMM *)ts->data;
  const PetscInt K  = (PetscInt)vs->level_end.size() - 1;

  PetscFunctionBegin;
  vs->adapt_candidate.clear();
  vs->adapt_verified.clear();
  if (!vs->savings.empty()) p.ratios = vshmm::timeRatiosFromSavings(vs->savings);
  else {
    p.ratios = SeparatedRatios(ts);
    vs->adapt_merged.clear();
    if (vs->no_separation) { /* not separated: no savings until a comparison with a single-rate step admits some (VerifySavings()) */
      vs->adapt_candidate = SavingsCandidate(ts, p.ratios);
      PetscCall(PetscInfo(ts, "Adapt: the scales are not separated: no savings%s\n", vs->adapt_candidate.empty() ? "" : " until a single-rate macro step admits them"));
      p.ratios.assign(K, 1.0);
    } else
      for (PetscInt l = 0; l < K; ++l) {
        /* a decaying pair not even kInitialDecaySeparation apart, among separated ones: no savings
           between them (their start is r_l = 1, which a calibration cannot coarsen: its term
           read 0, and the choice took the ratio as free; the dissipative example at eps = 3e-2,
           pair 1/2 1.31 apart, raised r_2 to 3.1, an effective separation of 0.4, and the
           first step's estimate stayed at 8 shares over 11 tries) */
        const PetscReal S = Separation(vs, l);
        if ((PetscInt)vs->separations.size() > l || !LevelDecays(vs, l + 1) || S > kInitialDecaySeparation) continue;
        vs->adapt_no_savings.resize(K, PETSC_FALSE);
        vs->adapt_no_savings[l] = PETSC_TRUE;
        vs->adapt_merged.resize(K, 0.0);
        vs->adapt_merged[l] = S;
        PetscCall(PetscInfo(ts, "Adapt: levels %" PetscInt_FMT "/%" PetscInt_FMT " are %.3g apart: no savings between them\n", l, l + 1, (double)S));
      }
    const vshmm::AdaptBounds b = Bounds(ts, ts->time_step); /* inside the bounds every later choice keeps */
    for (size_t l = 0; l < b.maxRatio.size() && l < p.ratios.size(); ++l) p.ratios[l] = PetscMin(p.ratios[l], PetscMax(1.0, b.maxRatio[l]));
  }
  PetscFunctionReturn(0);
}

/* The first parameters: from each level's spectral radius and the tolerance. */
PetscErrorCode TSVSHMMAdaptSetUp_Private(TS ts)
{
  TS_VSHMM      *vs      = (TS_VSHMM *)ts->data;
  const PetscInt nscales = (PetscInt)vs->level_end.size(), K = nscales - 1;

  PetscFunctionBegin;
  if (!vs->adapt) PetscFunctionReturn(0);
  /* the tolerances are the weights of the error estimate: a zero one divides by zero where the
     other is zero too (every estimate infinite, every step refined to the limit), a negative or
     non-finite one makes the estimate meaningless */
  PetscCheck(std::isfinite(ts->rtol) && std::isfinite(ts->atol) && ts->rtol >= 0 && ts->atol >= 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_adapt: the tolerances -ts_rtol %g and -ts_atol %g (TSSetTolerances()) must be finite and non-negative",
             (double)ts->rtol, (double)ts->atol);
  PetscCall(CheckToleranceVectors(ts));
  if (vs->observables) { /* at the initial state: a function that returns NaN (an entry of q[] not set) would make every estimate infinite */
    std::vector<PetscReal> q0(vs->nobservables, 0.0);
    PetscCall(TSVSHMMObservables_Private(ts, ts->ptime, ts->vec_sol, q0.data()));
    for (PetscInt i = 0; i < vs->nobservables; ++i)
      PetscCheck(std::isfinite(q0[i]), PetscObjectComm((PetscObject)ts), PETSC_ERR_FP, "TSVSHMMSetObservables(): observable %" PetscInt_FMT " (of %" PetscInt_FMT ") is %g at the initial state (t = %g): the observables function must set q[0..%" PetscInt_FMT "] to finite values", i, vs->nobservables, (double)q0[i],
                 (double)ts->ptime, vs->nobservables - 1);
  }
  PetscCall(VecDuplicate(ts->vec_sol, &vs->Xtrial));
  PetscCall(VecDuplicate(ts->vec_sol, &vs->Xbase));
  PetscCall(SlowComponentsSetUp(ts));
  if (vs->spectra_time != ts->ptime || (PetscInt)vs->level_radius.size() != nscales) PetscCall(TSVSHMMLevelSpectra_Private(ts));
  PetscCall(LagComponentsSetUp(ts));
  PetscCall(RadiusBaseline(ts));
  vs->adapt_separated_start.assign(K, false); /* LostSeparation() of a decaying pair */
  for (PetscInt l = 0; l < K; ++l) vs->adapt_separated_start[l] = Separation(vs, l) >= kMinSeparation;
  const PetscReal DeltaT = ts->time_step, tol = PetscMax(TSVSHMMToleranceLevel_Private(ts), 1e-12);
  vs->adapt_tstart = ts->ptime; /* the error budget and the micro step's amplitude bound run from here */

  vshmm::AdaptParameters &p = vs->adapt_params;
  p.microStep               = FirstMicroStep(ts);
  PetscCall(FirstRatios(ts, p));
  LimitToStableSteps(ts, p);
  const vshmm::AdaptBounds b = Bounds(ts, DeltaT);
  vshmm::fitCycle(p, b.maxCycle, b.fixedRatios, true); /* enough cycles per macro step */
  if (vs->micro_dt > 0) {                              /* a micro step the user set is kept: said where it damps the fastest oscillation beyond the tolerance */
    const PetscReal dtOk = AccurateMicroStep(ts, p, vs->micro_dt);
    if (dtOk < 0.999 * vs->micro_dt)
      PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): the micro step set (-ts_vshmm_micro_dt %g) loses more than the tolerance %g of the amplitude of the fastest scale's oscillation (frequency %g) over the run, and the error estimate cannot see that loss (the energy leaves every comparison too). A micro step of at most %g keeps it; leave the micro step to -ts_vshmm_adapt.\n",
                                    (double)vs->micro_dt, (double)(kOscillationShare * tol), (double)vs->level_radius[K], (double)dtOk));
  }
  if (vs->kernel_type == TSVSHMM_KERNEL_CONSTANT && K > 0)
    /* measured with each kernel on the suite of docs/accuracy.md (section 23): only the constant
       kernel, which weighs the faster levels' state right after each slow step fully, missed */
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): the constant kernel (-ts_vshmm_kernel constant) does not vanish at the ends of its period, and the error estimate of -ts_vshmm_adapt is not reliable with it: where the faster "
                                      "scales start off their slow manifold (an initial layer) its averaging error saturates as the savings grow, and the comparison with every error term doubled sees a fraction of it (measured: a 4-scale relaxation "
                                      "chain at tol 1e-3 ended 3.7 tolerances off, its first macro step estimated 18 times too low); where they oscillate it costs up to 1,600 times the work. Use a kernel that vanishes at the ends of its period: "
                                      "cosine (the default) or polynomial.\n"));
  if (vs->kernel_type == TSVSHMM_KERNEL_EXPONENTIAL && K > 0)
    /* measured on the outside problems of docs/accuracy.md (tools/adapt_outside.py, section 23):
       the one silent miss above 2 tolerances with a kernel that vanishes at its ends */
    PetscCall(
      TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): with the exponential kernel (-ts_vshmm_kernel exponential) the error estimate of -ts_vshmm_adapt was measured less reliable where the faster scales start off their slow "
                              "manifold (an initial layer): a three-level reaction at tol 1e-2 ended 4 tolerances off, its first macro step estimated 5 times too low (0.36 tolerances with the cosine kernel). Use the cosine kernel (the default) or "
                              "the polynomial one.\n"));
  vs->savings_used   = vshmm::savingsFromTimeRatios(p.ratios);
  vs->adapt_model    = vshmm::ErrorModel();
  vs->adapt_ready    = PETSC_TRUE;
  vs->error_estimate = vs->error_estimate_total = vs->error_estimate_squares = 0;
  vs->unaveraged_max                                                         = vs->unaveraged;
  vs->level_time_rate_max                                                    = vs->level_time_rate;
  ResetStepHistory(vs);
  PetscCall(PetscInfo(ts, "Adapt: first parameters dt = %g, cycle %g (DeltaT %g), tolerance %g\n", (double)p.microStep, (double)vshmm::cycleLength(p), (double)DeltaT, (double)tol));
  PetscFunctionReturn(0);
}

static PetscReal OwnStepBudget(TS, PetscReal);

/* A macro step's share of the tolerance (OwnStepBudget()), shrunk by e^(mu (T - t1)) where the
   growth probe measured the slow dynamics growing an error at the rate mu (the growth probe, below:
   an error made in this step grows so by the run's end T), and shrunk where the carried comparison
   (CarryComparison()) shows the errors grown by the dynamics far beyond the steps' own: its
   estimate above kAmplified times the sum of the steps' estimates since it started (carried_weight;
   not the statistics' sum, which TSVSHMMResetStatistics() zeroes) (not the estimate's noise: on the
   oscillators and every problem of docs/accuracy.md it stays within 4 times it) and above the part
   of the tolerance a drift growing as the square of the time allows by the step's end (a phase
   driven by accumulated amplitude errors: the Duffing oscillator's state). The share shrinks by
   that ratio (down to kMinGlobalScale of it): the later steps' errors, which the dynamics will
   grow as they grew the earlier ones, are made smaller; the errors already made stay (the Duffing
   oscillator to t = 10 at 1e-2: 5.6 tol without, 1.5 with). */
static PetscReal StepBudget(TS ts, PetscReal DeltaT)
{
  TS_VSHMM       *vs   = (TS_VSHMM *)ts->data;
  PetscReal       own  = OwnStepBudget(ts, DeltaT);
  const PetscReal span = RunSpan(ts);

  if (vs->growth_rate > 0 && span > 0) {
    /* as far ahead as the run's end; where an earlier probe of the run found an error damped, the
       growth is a phase of the dynamics (a slow equation whose Jacobian changes sign), and it is
       taken only until the probe that checks it again */
    const PetscReal rest = vs->adapt_tstart + span - (ts->ptime + DeltaT), ahead = vs->growth_damped ? PetscMin(rest, (kGrowthRecheck + kGrowthStages) * DeltaT) : rest;
    if (ahead > 0) own = PetscMax(own * std::exp(-vs->growth_rate * ahead), kMinGlobalScale * own);
  }

  if (vs->adapt_global && vs->carried_time == ts->ptime && span > 0 && vs->global_estimate > kAmplified * vs->carried_weight) {
    const PetscReal done = PetscMin(1.0, (ts->ptime + DeltaT - vs->adapt_tstart) / span), allowed = kSafety * done * done;
    if (vs->global_estimate > allowed) return PetscMax(own * allowed / vs->global_estimate, kMinGlobalScale * own);
  }
  return own;
}

/* Whether the slowest level oscillates, undamped over the run, by more than kBlindTurn radians
   per macro step (its limiting Ritz values): its errors in phase add up step by step, while their
   projection on the observables turns sign within a few steps, so that the signed sums of
   OwnStepBudget() never exceed a random walk's (at 8 steps, 2 sqrt(8) e needs a turn below 0.35
   per step: the sum of a turning projection stays below e / sin(turn / 2)). */
static bool SlowestLevelTurns(TS_VSHMM *vs, PetscReal DeltaT, PetscReal span)
{
  if (vs->level_limiting.empty()) return false;
  for (const std::complex<double> &z : vs->level_limiting[0])
    if (vshmm::oscillates(z) && std::abs(z.imag()) * DeltaT > kBlindTurn && std::abs(z.real()) * span < 1) return true;
  return false;
}

/* Whether parameters take no savings (every time ratio 1): their only error is the Runge-Kutta
   steps' at the micro step, which on an undamped oscillation is a phase error of one sign. */
static bool SingleRate(const vshmm::AdaptParameters &p)
{
  if (p.ratios.empty()) return false;
  for (double r : p.ratios)
    if (r != 1.0) return false;
  return true;
}

/* Each macro step's own share of the tolerance (the weighted norm's 1 over the run), (DeltaT / span)^gamma: gamma = 1/2 where the steps'
   errors add like a random walk (the sum of N of them grows like sqrt(N)), gamma = 1 where they add
   coherently (like N: a drift, the stiff-spring chain's I, the dissipative example's xi at eps =
   1e-4). With observables gamma is measured from the signed estimates of the accepted steps: their
   sum S against their mean size e over k >= 4 steps, S ~ e k^gamma, the largest significant
   gamma so far kept (vs->adapt_coherence); without observables, and before, 1/2. Where the slow
   components (SlowComponentsSetUp()) have led an accepted step's estimate and the slowest level
   oscillates, 1: their signed sums cannot show a velocity error rotated into the position. And 1
   where the last step was single-rate and the slowest level turns by more than kBlindTurn per
   macro step (SlowestLevelTurns()): the steps' phase errors add up while the signed sums stay
   within a random walk's (x1' = 20 x2 + z, x2' = -20 x1, z' = -(z - x1^2) / 1e-2, not separated,
   single-rate: 3.9 tol at 1e-3 with estimates summing to 2.3, silently; docs/accuracy.md section
   28). */
static PetscReal OwnStepBudget(TS ts, PetscReal DeltaT)
{
  TS_VSHMM       *vs   = (TS_VSHMM *)ts->data;
  const PetscReal span = RunSpan(ts);

  if (!(span > 0)) return 1.0;
  if (vs->slow_steps > 0 && !LevelDecays(vs, 0)) return PetscMin(1.0, DeltaT / span);
  if (SlowestLevelTurns(vs, DeltaT, span) && SingleRate(vs->adapt_used)) return PetscMin(1.0, DeltaT / span);
  for (PetscReal from : vs->adapt_phase) /* the sampled quantities carry an oscillation's phase (NoteFastQuantities()): its error, a phase drift, adds up step by step while its sign turns with the oscillation, and a comparison sees it projected on the quantities at one phase (between none and all of it, half on the average) */
    if (from >= 0) return PetscMin(1.0, kPhaseProjection * DeltaT / span);
  PetscReal gamma = 0.5;
  if (vs->adapt_accepted >= kCoherenceSteps && !vs->adapt_signed.empty() && vs->error_estimate_total > 0) {
    PetscReal S = 0;
    for (PetscReal x : vs->adapt_signed) S += x * x;
    S                    = std::sqrt(S / (PetscReal)vs->adapt_signed.size());
    const PetscReal ebar = vs->error_estimate_total / (PetscReal)vs->adapt_accepted;
    if (S > 0 && ebar > 0) gamma = PetscMin(1.0, PetscMax(0.5, std::log(S / ebar) / std::log((PetscReal)vs->adapt_accepted)));
    /* the largest gamma measured significant so far stands (after kCoherenceKept steps, with S
       above kCoherenceSignificance times a random walk's e sqrt(k)): a signed sum that passes
       through 0 (the errors of an oscillating slow variable change sign with it) does not show
       errors that stopped adding up; measured at that moment, gamma fell to 1/2 and the shares
       rose tenfold, and the error added up again (x' = -y + sin 3t, y' = -(y - cos(t) sin x) /
       1e-3 to t = 10 at 1e-2: gamma 0.94 at t = 3.3, 1/2 at t = 5.1 and 7.5, x 2.2 tol off at t =
       8.8, silently; 0.46 with it) */
    if (vs->adapt_accepted >= kCoherenceKept && S > kCoherenceSignificance * ebar * PetscSqrtReal((PetscReal)vs->adapt_accepted)) vs->adapt_coherence = PetscMax(vs->adapt_coherence, gamma);
    gamma = PetscMax(gamma, vs->adapt_coherence);
  }
  return PetscMin(1.0, PetscPowReal(DeltaT / span, gamma));
}

/* The work of a try that is not kept goes to the estimation work; the solve's counters are restored. */
static void DiscardTry(TS_VSHMM *vs, const std::vector<PetscInt64> &rhs0, const std::vector<PetscInt64> &lev0)
{
  for (size_t k = 0; k < rhs0.size(); ++k) vs->adapt_evaluations += vs->rhs_evaluations[k] - rhs0[k];
  vs->rhs_evaluations   = rhs0;
  vs->level_evaluations = lev0;
  vs->adapt_rejections++;
}

/* A comparison run's parameters: q kept inside the stability region but never finer than p in any
   parameter (a comparison may coarsen a parameter the user set: it only measures). */
static vshmm::AdaptParameters Comparison(TS ts, const vshmm::AdaptParameters &p, vshmm::AdaptParameters q)
{
  /* at least kMinCycles / kCompareCycles micro cycles per macro step: with many levels, every
     ratio doubled multiplies the cycle by about 2^K, and a comparison with less than one cycle per
     macro step measures nothing */
  const PetscReal maxCycle = kCompareCycles * PetscMax(vshmm::cycleLength(p), ts->time_step / kMinCycles);
  LimitAllToStableSteps((TS_VSHMM *)ts->data, q);
  vshmm::fitCycle(q, maxCycle, false, true);
  q.microStep = PetscMax(q.microStep, p.microStep);
  for (size_t l = 0; l < q.ratios.size(); ++l) q.ratios[l] = PetscMax(q.ratios[l], p.ratios[l]);
  return q;
}

/* Whether a comparison q of p is coarser in some parameter (its micro step or its cycle), not the
   same run at every stability bound. */
static bool Coarser(const vshmm::AdaptParameters &p, const vshmm::AdaptParameters &q)
{
  return q.microStep > p.microStep * 1.01 || vshmm::cycleLength(q) > vshmm::cycleLength(p) * 1.01;
}

/* Whether the comparison run (vs->Xtrial) blew up: not finite, or kBlowUpGrowth times larger than
   the step it is compared with (vs->Xbase) and its start (vs->X0). Both started from X0 with
   parameters that differ by a factor 2 in each error term; a finite but astronomically large
   comparison is an unstable run, not an error estimate. */
static PetscErrorCode ComparisonBlewUp(TS ts, PetscBool *blown)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal trial, base, start;

  PetscFunctionBegin;
  PetscCall(VecNorm(vs->Xtrial, NORM_1, &trial));
  PetscCall(VecNorm(vs->Xbase, NORM_1, &base));
  PetscCall(VecNorm(vs->X0, NORM_1, &start));
  *blown = (!std::isfinite(trial) || (std::isfinite(base) && trial > kBlowUpGrowth * (base + start))) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The comparison's start: the step's start, and on the components only faster levels write
   (LagComponentsSetUp()) the end state of the last accepted step's comparison carried in, as far as
   this comparison's parameters change the error model's terms (|M(q) - M(p)| over that one's, at most
   1). Where the faster levels only decay, savings slow their relaxation by the time ratios, and the
   faster variables end a macro step behind their slow manifold by a lag that grows with the
   ratios; the next step starts from it. Where that relaxation, slowed, lasts about a macro step
   (the dissipative example at eps = 3e-3: the medium level's rate 2 xi / eps over r_0 = 80 against
   DeltaT = 0.1), the step's error comes from the lag it inherits, which a comparison from the same
   start shares: its estimates were 10 to 200 times below the steps' errors (2.1-3.0 tol, silently;
   docs/accuracy.md section 22). A comparison that inherits its own lag measures it.
   Only a step's first try inherits (`inherit`): a retry's finer parameters cannot change the lag
   the solution starts from, and a comparison that kept inheriting the last step's found no
   parameters that lowered its estimate (the dissipative example at eps = 1e-2, tol 1e-2: three
   tries at one estimate, then a floor); the next step's first try measures the lag the retry left.
   An oscillating faster level keeps a phase, not a lag: nothing is carried there. Where the model's
   terms saturate, the carried lag is scaled down (kLagSaturated, below). */
static PetscReal      Estimate(const vshmm::ErrorModel &, const vshmm::AdaptParameters &, const vshmm::AdaptParameters &, PetscReal);
static PetscErrorCode ComparisonStart(TS ts, const vshmm::AdaptParameters &p, const vshmm::AdaptParameters &q, PetscReal t0, PetscBool inherit, Vec X)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal norm;

  PetscFunctionBegin;
  PetscCall(VecCopy(vs->X0, X));
  if (!inherit || !vs->lag_valid || !vs->lag_carried || vs->adapt_end != t0 || !FasterLevelsDecay(vs)) PetscFunctionReturn(0);
  PetscCall(VecNorm(vs->X0, NORM_1, &norm));
  if (norm != vs->adapt_end_norm) PetscFunctionReturn(0); /* the solution changed between the steps */
  if (vs->lag_by_values) {                                /* the components from the values where first needed; one the slowest field writes here leaves them */
    PetscCall(LagComponentsFromValues(ts, t0, vs->X0));
    if (!vs->lag_mask) PetscFunctionReturn(0);
    PetscCall(VecPointwiseMult(vs->lag_carried, vs->lag_carried, vs->lag_mask));
  }
  const PetscReal now = PetscAbsReal(vs->adapt_model.total(q) - vs->adapt_model.total(p)), then = PetscAbsReal(vs->adapt_model.total(vs->lag_q) - vs->adapt_model.total(vs->lag_p));
  PetscReal       scale = (std::isfinite(now) && std::isfinite(then) && then > 0) ? PetscMin(1.0, now / then) : 1.0;
  /* the comparison's difference is converted by the model's factor M(p) / (M(q) - M(p)), large where
     the terms saturate (doubling them changes the error little); the inherited lag does not
     saturate so, and converted by that factor it read 10 times a step's true error (the paper's
     sparse diffusion scene at 1e-2, factor 28: the step retried, 1,019 evaluations instead of 630):
     beyond kLagSaturated it is scaled down by the excess */
  const PetscReal factor = Estimate(vs->adapt_model, p, q, 1.0);
  if (std::isfinite(factor) && factor > kLagSaturated) scale *= kLagSaturated / factor;
  PetscCall(VecAXPY(X, scale, vs->lag_carried));
  vs->lag_inherited++;
  PetscCall(PetscInfo(ts, "Adapt: the comparison starts from the last one's end state on the %" PetscInt_FMT " components only faster levels write (scaled by %g)\n", vs->lag_count, (double)scale));
  PetscFunctionReturn(0);
}

/* The growth probe: how the slow dynamics grow an error that a macro step leaves. The steps'
   shares of the tolerance assume that the errors of the sampled quantities add up (randomly or
   coherently); an unstable slow equation grows each one for the rest of the run, e^(mu (T - t))
   for an error made at t, and no step's comparison sees that (a saddle of the slow variable, x' =
   x - 1 + z / 2, z' = -(z - cos x) / 1e-3 from x = 0.59, mu = 0.72 to t = 4: 1.8 / 3.1 / 6.7 tol
   at 1e-3 / 5e-4 / 1e-4, the steps' estimates summing to 0.3-0.9, silently; docs/accuracy.md
   section 35). A probe perturbs the solution at a macro step's start by kGrowthSize of its weight
   on every component the slowest level writes (GrowthProbeBegin()), propagates the perturbed
   solution over the step beside the solution's own run (in the step's first comparison, with its
   parameters and from its start offset, so that a carried lag is the same in both; where the step
   has none, with the step's parameters against the solution), and takes the perturbation's size at
   the step's end over its size at the start (PerturbationSize(): weighted as the tolerance
   weighs, on the slowest level's components, where the faster ones follow them within a step).
   While it grows, the perturbation is propagated over the next step too (rescaled, on the slowest
   level's components), for kGrowthStages steps; the smallest growth g over them gives the rate
   mu = ln(g) / DeltaT (one step's growth can be a passing transient), and StepBudget() shrinks
   each later step's share by e^(mu (T - t1)). Without lag_mask (additive splits) the first step
   only settles the perturbation (its faster components decay or feed the slower ones within it)
   and the growth counts from the second. A probe is made where an error could grow: the slowest
   level's own Jacobian has a mode that could grow it by e^kGrowthPossible over the run, or the
   solution's own motion over a macro step (a tangent of the flow, which the linearized dynamics
   carry as they carry an error) grew step after step, for kGrowthStages steps at least, to
   kGrowthStretch times its size (a coupling
   through the faster levels that the slowest level's Jacobian does not show: x' = -x + 2 z, z' =
   -(z - x - 0.01) / eps grows as e^t with the slowest level's Jacobian -1); and where it can be
   used: at least kGrowthSteps macro steps left. First at the run's first step, then kGrowthRecheck
   steps after a probe that found growth (a passing growth stops shrinking the shares soon: the
   dissipative example at eps = 3e-2 grew an error 1.10-1.13 times per step at t = 0.6-0.9 only),
   kGrowthInterval after one that did not. It costs one comparison run per step it propagates over
   (a step's own run where the step has no comparison). The errors made before the first rate was
   known grow too: where they exceed the tolerance by the final time (at the growth measured
   since), the user is told at the solve's last step. */
static PetscErrorCode GrowthProbeBegin(TS, PetscReal, PetscInt);
/* In a macro step's first comparison: a probe begun or continued here propagates its perturbed
   solution with the comparison's parameters from the comparison's start offset, in growth_Y
   (*probe: run it beside the comparison, GrowthMeasure()). */
/* Whether a probe's perturbed solution waits at the step's start t0 (not from another run, nor a
   solution changed between the steps). */
static PetscErrorCode GrowthPerturbedAt(TS ts, PetscReal t0, PetscBool *at)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal norm;

  PetscFunctionBegin;
  *at = PETSC_FALSE;
  if (vs->growth_stage < 1 || vs->growth_time != t0) PetscFunctionReturn(0);
  PetscCall(VecNorm(vs->X0, NORM_1, &norm));
  *at = norm == vs->growth_norm ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode GrowthProbeStart(TS ts, PetscReal t0, PetscBool inherit, PetscBool *probe)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  *probe = PETSC_FALSE;
  if (!inherit || vs->growth_measured) PetscFunctionReturn(0);
  PetscCall(GrowthProbeBegin(ts, t0, vs->adapt_accepted));
  PetscCall(GrowthPerturbedAt(ts, t0, probe));
  if (!*probe) PetscFunctionReturn(0);
  if (!vs->growth_Y) PetscCall(VecDuplicate(vs->X0, &vs->growth_Y));
  PetscCall(VecWAXPY(vs->growth_Y, -1.0, vs->X0, vs->Xtrial)); /* the comparison's start offset */
  PetscCall(VecAXPY(vs->growth_Y, 1.0, vs->growth_X));
  *probe = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The size of the perturbation b - a of a solution a on the components the slowest level writes
   (off lag_mask; every component without it), weighted as TSErrorWeightedNorm() weighs (with the
   tolerances' vectors where TSSetTolerances() gave them), root mean square. */
static PetscErrorCode PerturbationSize(TS ts, Vec a, Vec b, PetscReal *size, PetscBool slowOnly = PETSC_FALSE)
{
  TS_VSHMM          *vs = (TS_VSHMM *)ts->data;
  const PetscScalar *xa, *xb, *m = nullptr, *sm = nullptr, *va = nullptr, *vr = nullptr;
  PetscInt           n;
  PetscReal          sum[2] = {0, 0};
  /* slowOnly, additive splits: on the slow components the fields' values showed (SlowComponentsFromValues()),
     not on a fast rotation's components, whose perturbation turns with its phase and was read as
     growths of 1.1, 19, 2.5, 1.9 from step to step (a fast Duffing rotation: "the tolerance is not
     met", 14-2,200 tolerances said, 0.4-0.8 true) */
  const Vec slow = (slowOnly && !vs->lag_mask && vs->slow_by_values > 0 && vs->slow_mask) ? vs->slow_mask : nullptr;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(a, &n));
  PetscCall(VecGetArrayRead(a, &xa));
  PetscCall(VecGetArrayRead(b, &xb));
  if (vs->lag_mask) PetscCall(VecGetArrayRead(vs->lag_mask, &m));
  if (slow) PetscCall(VecGetArrayRead(slow, &sm));
  if (ts->vatol) PetscCall(VecGetArrayRead(ts->vatol, &va));
  if (ts->vrtol) PetscCall(VecGetArrayRead(ts->vrtol, &vr));
  for (PetscInt i = 0; i < n; ++i) {
    if (m && PetscRealPart(m[i]) != 0) continue;
    if (sm && PetscRealPart(sm[i]) == 0) continue;
    const PetscReal w = (va ? PetscRealPart(va[i]) : ts->atol) + (vr ? PetscRealPart(vr[i]) : ts->rtol) * PetscMax(PetscAbsScalar(xa[i]), PetscAbsScalar(xb[i]));
    const PetscReal e = PetscAbsScalar(xb[i] - xa[i]) / w;
    sum[0] += e * e;
    sum[1] += 1;
  }
  if (ts->vrtol) PetscCall(VecRestoreArrayRead(ts->vrtol, &vr));
  if (ts->vatol) PetscCall(VecRestoreArrayRead(ts->vatol, &va));
  if (sm) PetscCall(VecRestoreArrayRead(slow, &sm));
  if (m) PetscCall(VecRestoreArrayRead(vs->lag_mask, &m));
  PetscCall(VecRestoreArrayRead(b, &xb));
  PetscCall(VecRestoreArrayRead(a, &xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ts)));
  *size = sum[1] > 0 ? std::sqrt(sum[0] / sum[1]) : 0;
  PetscFunctionReturn(0);
}

/* The perturbed solution growth_Y (at t0 + DeltaT: growth_X propagated) against the solution `base`
   there: its growth over the step, and growth_Y made the propagated perturbation. */
static PetscErrorCode GrowthMeasure(TS ts, Vec base, PetscReal t0, PetscReal DeltaT)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal d0, D;

  PetscFunctionBegin;
  PetscCall(PerturbationSize(ts, vs->X0, vs->growth_X, &d0, PETSC_TRUE));
  PetscCall(PerturbationSize(ts, base, vs->growth_Y, &D, PETSC_TRUE));
  PetscCall(VecAXPY(vs->growth_Y, -1.0, base));
  vs->growth_measured = (std::isfinite(D) && std::isfinite(d0) && d0 > 0) ? PETSC_TRUE : PETSC_FALSE;
  vs->growth_factor   = vs->growth_measured ? D / d0 : 0;
  PetscCall(PetscInfo(ts, "Adapt: growth probe, step %" PetscInt_FMT " over [%g, %g]: a perturbation of %g became %g (factor %g)\n", vs->growth_stage, (double)t0, (double)(t0 + DeltaT), (double)d0, (double)D, (double)vs->growth_factor));
  PetscFunctionReturn(0);
}

/* growth_X: the solution plus the perturbation dX (overwritten), on the slowest level's components */
static PetscErrorCode GrowthPerturb(TS ts, Vec dX, PetscReal t1)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  Vec       fast;

  PetscFunctionBegin;
  if (!vs->growth_X) PetscCall(VecDuplicate(ts->vec_sol, &vs->growth_X));
  if (vs->lag_mask) {
    PetscCall(VecDuplicate(dX, &fast));
    PetscCall(VecPointwiseMult(fast, dX, vs->lag_mask));
    PetscCall(VecAXPY(dX, -1.0, fast));
    PetscCall(VecDestroy(&fast));
  } else if (vs->slow_by_values > 0 && vs->slow_mask) PetscCall(VecPointwiseMult(dX, dX, vs->slow_mask)); /* additive splits: on the slow components their values showed (PerturbationSize()) */
  PetscCall(VecWAXPY(vs->growth_X, 1.0, ts->vec_sol, dX));
  {
    /* at most kGrowthSize of the solution (relative, weighted): a perturbation that small grows as the linearized dynamics grow it (a comparison's difference at 1e-1 taken as the perturbation, 40% of the oscillators' slow state, made a run that blew up) */
    PetscReal       size;
    const PetscReal most = kGrowthSize / PetscMax(TSVSHMMToleranceLevel_Private(ts), PETSC_SMALL);
    PetscCall(PerturbationSize(ts, ts->vec_sol, vs->growth_X, &size));
    if (size > most) PetscCall(VecAXPBY(vs->growth_X, 1.0 - most / size, most / size, ts->vec_sol));
  }
  vs->growth_time = t1;
  PetscCall(VecNorm(ts->vec_sol, NORM_1, &vs->growth_norm));
  PetscFunctionReturn(0);
}

/* A probe starts at the step's start t0 where one is due (`before`: the steps accepted before this one) and the slowest level's own Jacobian
   has a mode that could grow an error noticeably over the run (its Ritz values, vs->level_growth;
   a coupling through the faster levels can grow it too, unseen here): the solution with every
   component the slowest level writes moved by kGrowthSize of its weight (atol + rtol |x|), the
   same sign throughout (a direction that the propagations turn towards the fastest growth). */
static PetscErrorCode GrowthProbeBegin(TS ts, PetscReal t0, PetscInt before)
{
  TS_VSHMM       *vs   = (TS_VSHMM *)ts->data;
  const PetscReal span = RunSpan(ts);

  PetscFunctionBegin;
  const PetscBool possible = ((!vs->level_growth.empty() && vs->level_growth[0] * span > kGrowthPossible) || (vs->growth_streak_steps >= kGrowthStages && vs->growth_move >= kGrowthStretch * vs->growth_streak)) ? PETSC_TRUE : PETSC_FALSE;
  if (vs->growth_stage != 0 || before < vs->growth_due || !(span > 0) || !(possible || vs->growth_rate > 0)) PetscFunctionReturn(0);             /* (a rate in effect is measured again) */
  if (vs->adapt_tstart + span - t0 < (vs->growth_rate > 0 ? kGrowthStages : kGrowthSteps) * ts->time_step * (1 - 1e-10)) PetscFunctionReturn(0); /* too few steps left to measure and use a rate (a rate in effect is measured again while it can be) */
  const PetscScalar *x, *m = nullptr, *va = nullptr, *vr = nullptr;
  PetscScalar       *y;
  PetscInt           n;
  const PetscReal    c = kGrowthSize / PetscMax(TSVSHMMToleranceLevel_Private(ts), PETSC_SMALL);
  if (!vs->growth_X) PetscCall(VecDuplicate(vs->X0, &vs->growth_X));
  PetscCall(VecGetLocalSize(vs->X0, &n));
  PetscCall(VecGetArrayRead(vs->X0, &x));
  PetscCall(VecGetArray(vs->growth_X, &y));
  if (vs->lag_mask) PetscCall(VecGetArrayRead(vs->lag_mask, &m));
  if (ts->vatol) PetscCall(VecGetArrayRead(ts->vatol, &va));
  if (ts->vrtol) PetscCall(VecGetArrayRead(ts->vrtol, &vr));
  for (PetscInt i = 0; i < n; ++i) y[i] = x[i] + ((m && PetscRealPart(m[i]) != 0) ? 0 : c * ((va ? PetscRealPart(va[i]) : ts->atol) + (vr ? PetscRealPart(vr[i]) : ts->rtol) * PetscAbsScalar(x[i])));
  if (ts->vrtol) PetscCall(VecRestoreArrayRead(ts->vrtol, &vr));
  if (ts->vatol) PetscCall(VecRestoreArrayRead(ts->vatol, &va));
  if (m) PetscCall(VecRestoreArrayRead(vs->lag_mask, &m));
  PetscCall(VecRestoreArray(vs->growth_X, &y));
  PetscCall(VecRestoreArrayRead(vs->X0, &x));
  vs->growth_time  = t0;
  vs->growth_stage = 1;
  PetscCall(VecNorm(vs->X0, NORM_1, &vs->growth_norm));
  PetscFunctionReturn(0);
}

/* After an accepted macro step: the probe's perturbation propagated where the step's first
   comparison did not (a probe begun at the step's start where one is due), its growth taken, and
   the probe continued or ended; at the solve's last step, the errors made before the first rate
   said where they grew beyond the tolerance. */
static PetscErrorCode GrowthProbeAccepted(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  {
    /* the solution's own motion over the step on the slowest level's components: a tangent of the
       flow (for an autonomous field), which the linearized dynamics carry as they carry an error;
       where it grew step after step to kGrowthStretch times its size at the start of the streak,
       an error can grow so too (a coupling through the faster levels that the slowest level's
       Jacobian does not show: x' = -x + 2 z, z' = -(z - x - 0.01) / eps grows as e^t) */
    PetscReal move;
    PetscCall(PerturbationSize(ts, vs->X0, ts->vec_sol, &move));
    if (!(vs->growth_move > 0 && move > vs->growth_move && vs->adapt_end == t0)) { /* the streak starts again */
      vs->growth_streak       = move;
      vs->growth_streak_steps = 0;
    } else vs->growth_streak_steps++;
    vs->growth_move = move;
  }
  if (!vs->growth_measured) PetscCall(GrowthProbeBegin(ts, t0, vs->adapt_accepted - 1)); /* (counted with this step already) */
  PetscBool at = PETSC_FALSE;
  if (!vs->growth_measured) PetscCall(GrowthPerturbedAt(ts, t0, &at));
  if (at) { /* no first comparison propagated it: with the step's parameters, against the solution */
    if (!vs->growth_Y) PetscCall(VecDuplicate(vs->X0, &vs->growth_Y));
    PetscCall(VecCopy(vs->growth_X, vs->growth_Y));
    PetscCall(EstimationStep(ts, p, t0, DeltaT, vs->growth_Y));
    PetscCall(GrowthMeasure(ts, ts->vec_sol, t0, DeltaT));
  }
  const PetscBool measured = vs->growth_measured;
  vs->growth_measured      = PETSC_FALSE;
  const PetscReal span = RunSpan(ts), T = vs->adapt_tstart + span;
  const PetscBool last = (t0 + DeltaT >= ts->max_time - 1e-10 * DeltaT || ts->steps + 1 >= ts->max_steps || (span > 0 && t0 + 1.5 * DeltaT > T)) ? PETSC_TRUE : PETSC_FALSE;
  /* the steps' estimates, each grown by the growth measured after it (over this step: the probe's, or at the rate in effect) */
  const PetscReal E = std::isfinite(vs->error_estimate) ? vs->error_estimate : 0;
  if (measured && vs->growth_stage == 1) { /* the probe's first step: what the estimates would add up to without its growth, should it turn out uneven */
    vs->growth_amplified_before = vs->growth_amplified;
    vs->growth_probe_estimates  = 0;
    vs->growth_log_sum          = 0;
    vs->growth_log_count        = 0;
  }
  if (measured) vs->growth_probe_estimates += E;
  vs->growth_amplified = vs->growth_amplified * (measured ? vs->growth_factor : std::exp(vs->growth_rate * DeltaT)) + E;
  if (vs->growth_stage >= 1 && !measured) { /* not propagated (the solution changed between the steps): a probe starts again */
    vs->growth_stage = 0;
    vs->growth_recent.clear();
  }
  if (measured) {
    /* without lag_mask the first step's perturbation holds faster components too, which decay (or
       feed the slower ones) within it: that step only settles it, and the growth counts from the next */
    const PetscBool settling = (!vs->lag_mask && vs->growth_stage == 1) ? PETSC_TRUE : PETSC_FALSE;
    if (!settling) {
      vs->growth_log_sum += std::log(vs->growth_factor);
      vs->growth_log_count++;
      vs->growth_recent.push_back(vs->growth_factor);
      if (vs->growth_recent.size() > (size_t)kGrowthStages) vs->growth_recent.erase(vs->growth_recent.begin());
    }
    const PetscBool growing = (settling || vs->growth_factor > 1) ? PETSC_TRUE : PETSC_FALSE;
    const PetscBool full    = vs->growth_recent.size() == (size_t)kGrowthStages ? PETSC_TRUE : PETSC_FALSE;
    PetscBool       steady  = PETSC_FALSE;
    if (growing && full) {
      /* a rate only from a steady growth: an error turned by an oscillation grows unevenly for a
         part of its turn (weights that differ by component, a fast phase in a slow component) and
         shrinks later; taken as a rate for the rest of the run it shrank the shares a hundredfold
         (Kapitza's pendulum: factors 1.53, 2.27, 1.15, "e^(1.4 t)"; the saddles' within 3%) */
      const auto [lo, hi] = std::minmax_element(vs->growth_recent.begin(), vs->growth_recent.end());
      steady              = (std::log(*hi) <= kGrowthSteady * std::log(*lo) || std::log(*hi) - std::log(*lo) <= kGrowthSpread) ? PETSC_TRUE : PETSC_FALSE;
      if (steady) vs->growth_rate = std::log(*lo) / DeltaT;
    }
    if (growing && !last && (!full || (!steady && vs->growth_stage < kGrowthMaxStages))) { /* growing so far (unevenly: until it is steady, or for kGrowthMaxStages steps): propagated over the next step too */
      PetscCall(GrowthPerturb(ts, vs->growth_Y, t0 + DeltaT));
      vs->growth_stage++;
    } else {
      PetscBool lasting = growing;
      PetscBool passing = PETSC_FALSE;
      if (growing && full && !steady) {
        /* a growth whose logarithm falls step after step, each at most kGrowthFalling of the one
           before, is a transient passing: what it has left is about the last one's times q / (1 -
           q), and a rate, if any, is the last one's (a slow equation settling, factors 2.12, 1.91,
           1.38, 1.17, 1.09, 1.045: their mean, e^(3.3 t), said the tolerance was missed 73 times,
           with the errors 0.61 tol) */
        PetscReal q = 0;
        passing     = PETSC_TRUE;
        for (size_t i = 1; i < vs->growth_recent.size() && passing; ++i) {
          const PetscReal before = std::log(vs->growth_recent[i - 1]), now = std::log(vs->growth_recent[i]);
          passing = (before > 0 && now > 0 && now <= kGrowthFalling * before) ? PETSC_TRUE : PETSC_FALSE;
          q       = PetscMax(q, now / before);
        }
        if (passing) {
          const PetscReal last = std::log(vs->growth_recent.back());
          lasting              = last * q / (1 - q) > std::log(kGrowthSaid) ? PETSC_TRUE : PETSC_FALSE;
          if (lasting) vs->growth_rate = last / DeltaT;
        }
      }
      if (growing && full && !steady && !passing) { /* uneven to the probe's end: its mean growth over the probe, where it grew */
        const PetscReal mean = vs->growth_log_count > 0 ? vs->growth_log_sum / (PetscReal)vs->growth_log_count : 0;
        lasting              = mean > 0 ? PETSC_TRUE : PETSC_FALSE;
        if (lasting) vs->growth_rate = mean / DeltaT;
      }
      if (!lasting) {
        /* damped: no growth that lasts, and the probe's steps' estimates add up as they are (an
           oscillation grows an error for a part of its turn and shrinks it later: Kapitza's
           pendulum, 1.53, 2.27, 1.15, then 0.98, counted 4x was said to miss the tolerance at
           0.15 tol) */
        vs->growth_amplified = vs->growth_amplified_before + vs->growth_probe_estimates;
        vs->growth_rate      = 0;
        vs->growth_damped    = PETSC_TRUE;
      }
      vs->growth_rate_max = PetscMax(vs->growth_rate_max, vs->growth_rate);
      PetscCall(PetscInfo(ts, "Adapt: growth probe ended at t = %g after %" PetscInt_FMT " macro steps: rate %g%s\n", (double)(t0 + DeltaT), vs->growth_stage, (double)vs->growth_rate, growing && full && !steady ? (passing ? " (a growth falling step after step: a passing transient, its last step's)" : " (an uneven growth: its mean)") : ""));
      vs->growth_stage = 0;
      vs->growth_recent.clear();
      vs->growth_probes++;
      vs->growth_due = vs->adapt_accepted + (vs->growth_rate > 0 ? kGrowthRecheck : kGrowthInterval);
    }
  }
  if (!vs->growth_warned && last && vs->growth_amplified > 1 && vs->growth_amplified > kGrowthSaid * vs->error_estimate_total) {
    /* the solve's last macro step: the errors grown by the dynamics (the steps before a growth was
       measured had shares that did not allow for it; an error of a step's own that adds up step by
       step grows as the solution does) exceed the tolerance, and by more than the plain sum of the
       estimates would say */
    vs->growth_warned = PETSC_TRUE;
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): the slow dynamics grew the errors of the sampled values (an unstable slow equation: the probes measured up to e^(%g t)). The macro steps' error estimates, each grown by the growth measured after it, add up to about %g times the tolerance at t = %g (their plain sum is %g): the tolerance is not met. The later macro steps took shares of the tolerance shrunk by the growth, too late for the errors made before it was measured. Tighten -ts_rtol/-ts_atol by that factor, or use a single-rate TS type. This warning is given once per solve.\n",
                                  (double)vs->growth_rate_max, (double)vs->growth_amplified, (double)(t0 + DeltaT), (double)vs->error_estimate_total));
  }
  PetscFunctionReturn(0);
}

/* The comparison of the macro step just taken from X0 (ComparisonStart()) into Xbase with p: the same step with every
   error term doubled (vshmm::termsScaled). Under the model its difference d is the error of p
   (Estimate); the faster levels' phase at the sampling time makes it noisy (a factor 3 either way
   on the oscillators). A comparison that blew up (ComparisonBlewUp()) is tried again with the micro step
   of p; if that blew up too, d is infinite (no estimate: the step is redone with every parameter
   finer). */
static PetscErrorCode Compare(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT, PetscBool predict, PetscBool inherit, vshmm::AdaptParameters *q, PetscReal *d)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscFunctionBegin;
  *q = Comparison(ts, p, vshmm::termsScaled(p, 2.0, vs->tableau->order));
  if (!Coarser(p, *q)) {
    /* every parameter at its stability bound: no coarser run exists, and the same run would differ
       by nothing (an estimate of 0 that the choice would read as room to coarsen). Where the model
       has been measured the estimate is its prediction (no run: *d < 0); otherwise the comparison
       is the step with the micro step at kFinerComparison (a finer run, 1.33 times the step's cost;
       halved it cost twice the step, for an estimate as good: RK4's error falls 3.2x at 3/4; Estimate()
       reads it with the model's split) */
    if (predict) {
      *d = -1;
      PetscFunctionReturn(0);
    }
    *q = vshmm::coarsened(p, 0, kFinerComparison);
  }
  PetscBool blown;
  vs->lag_next_valid = PETSC_FALSE;
  PetscCall(ComparisonStart(ts, p, *q, t0, inherit, vs->Xtrial));
  PetscBool probe;
  PetscCall(GrowthProbeStart(ts, t0, inherit, &probe));
  PetscCall(EstimationStep(ts, *q, t0, DeltaT, vs->Xtrial));
  PetscCall(ComparisonBlewUp(ts, &blown));
  if (blown && q->microStep > p.microStep) {
    /* the coarser micro step is unstable: the comparison takes p's micro step with the other
       terms doubled, or, where none is left to double (the same run again, which would differ by
       exactly 0: Robertson's kinetics accepted such a step at ten times its share), the micro step
       at kFinerComparison */
    q->microStep = p.microStep;
    if (!(vshmm::cycleLength(*q) > vshmm::cycleLength(p) * 1.01)) *q = vshmm::coarsened(p, 0, kFinerComparison);
    PetscCall(PetscInfo(ts, "Adapt: the comparison with a coarser micro step blew up; comparing with dt %g, cycle %g\n", (double)q->microStep, (double)vshmm::cycleLength(*q)));
    PetscCall(ComparisonStart(ts, p, *q, t0, inherit, vs->Xtrial));
    probe = PETSC_FALSE; /* the start's lag changed with q: the perturbation goes with the step's parameters (GrowthProbeAccepted()) */
    PetscCall(EstimationStep(ts, *q, t0, DeltaT, vs->Xtrial));
    PetscCall(ComparisonBlewUp(ts, &blown));
  }
  if (blown) {
    /* the coarser savings are unstable (the levels' stable steps were estimated at another state,
       or the composed cycle grows where each level alone does not): p is near the edge, and a
       difference of that size is no estimate */
    PetscCall(PetscInfo(ts, "Adapt: the comparison with dt %g, cycle %g blew up: no estimate\n", (double)q->microStep, (double)vshmm::cycleLength(*q)));
    *d = kBlownUp;
    vs->obs_diff.clear();
    vs->step_signed.clear();
    vs->step_slow = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  PetscCall(ObservableDifference(ts, t0 + DeltaT, vs->Xbase, vs->Xtrial, d));
  PetscCall(PetscInfo(ts, "Adapt: comparison dt %g, cycle %g: difference %g\n", (double)q->microStep, (double)vshmm::cycleLength(*q), (double)*d));
  if (vs->lag_next) { /* its end state less the step's (on the faster levels' components once known), for the next step's comparison */
    PetscCall(VecWAXPY(vs->lag_next, -1.0, vs->Xbase, vs->Xtrial));
    if (vs->lag_mask) PetscCall(VecPointwiseMult(vs->lag_next, vs->lag_next, vs->lag_mask));
    vs->lag_next_valid = PETSC_TRUE;
    vs->lag_next_p     = p;
    vs->lag_next_q     = *q;
  }
  if (probe) {
    PetscCall(EstimationStep(ts, *q, t0, DeltaT, vs->growth_Y));
    PetscCall(GrowthMeasure(ts, vs->Xtrial, t0, DeltaT));
  }
  vs->step_signed = vs->obs_diff;
  vs->step_slow   = vs->slow_last; /* the calibrations and the layer's second comparison that may follow do not change it */
  PetscFunctionReturn(0);
}

/* A retry after the first accepted step does not coarsen a time ratio to where its comparison could
   not double r_l - 1 (the stability bound of level l's step): that term would go unmeasured, and the
   model's share for it, measured at other states and ratios, is all the estimate would know of it.
   The dissipative example at eps = 1e-4, tol 2e-3 retried the step at t = 1.1 with r_1 refined 2.4x
   and r_2 coarsened into its bound (307 -> 502): the change of r_1 sets off a transient in the
   medium level that the fast level, slowed by r_2, follows late, and the slow variable took an
   error of 5 shares against an estimate of 0.06. In the initial layer's tries (no step accepted
   yet) the ratios move freely: the layer's estimates guard them (the chains' first steps). */
static PetscErrorCode KeepComparableRatios(TS ts, const vshmm::AdaptParameters &p, vshmm::AdaptParameters &next)
{
  TS_VSHMM              *vs = (TS_VSHMM *)ts->data;
  vshmm::AdaptParameters q  = vshmm::termsScaled(next, 2.0, vs->tableau->order);

  PetscFunctionBegin;
  LimitAllToStableSteps(vs, q);
  for (size_t l = 0; l < next.ratios.size(); ++l)
    if (next.ratios[l] > p.ratios[l] && q.ratios[l] - 1.0 < kComparableCoarsening * (next.ratios[l] - 1.0)) {
      PetscCall(PetscInfo(ts, "Adapt: the retry keeps time ratio %d at %g (%g would leave its comparison at its stability bound)\n", (int)l + 1, (double)p.ratios[l], (double)next.ratios[l]));
      next.ratios[l] = p.ratios[l];
    }
  PetscFunctionReturn(0);
}

/* The error of p from the difference d to the comparison q, converted with the model. Where the
   model expects no net change (a micro step held at its stability limit in the comparison, so its
   term falls while the others rise, the rise small where a pair's term saturates), d is taken as
   the sum of the changes' sizes. */
static PetscReal Estimate(const vshmm::ErrorModel &model, const vshmm::AdaptParameters &p, const vshmm::AdaptParameters &q, PetscReal d)
{
  const PetscReal before = model.total(p), predicted = model.total(q) - before;
  if (!std::isfinite(d)) return d;
  if (predicted > 0) return d * before / predicted;
  PetscReal changes = 0;
  for (int i = 0; i <= (int)model.c.size(); ++i) changes += PetscAbsReal(model.term(q, i) - model.term(p, i));
  return changes > 0 ? d * before / changes : d;
}

/* The carried comparison (TSVSHMMSetAdaptGlobalEstimate()): a second solution, started with the
   run and advanced after each accepted macro step over the same interval with that step's
   comparison parameters (every error term doubled, as Compare() takes them). Its difference from
   the solution is what the two runs' errors have become by the sampled time, propagated by the
   dynamics (damped by a dissipative slow equation, grown by a shear: an amplitude error that shifts
   a frequency), converted as the steps' own comparisons were (below): an estimate of the error
   at the sampled time, where the steps' own estimates sum local ones. One comparison run per macro
   step more (5-77% more work on the suite of docs/accuracy.md). */
static PetscErrorCode CarryComparison(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT, PetscReal E, PetscReal d)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal start, D;

  PetscFunctionBegin;
  if (!vs->Xcarried) PetscCall(VecDuplicate(ts->vec_sol, &vs->Xcarried));
  PetscCall(VecNorm(vs->X0, NORM_1, &start));
  if (vs->carried_time != t0 || start != vs->adapt_end_norm) { /* a new run, or a solution changed between steps: started again from it */
    PetscCall(VecCopy(vs->X0, vs->Xcarried));
    vs->global_estimate = 0;
    vs->carried_weight  = 0;
    vs->carried_fsum    = 0;
  }
  vshmm::AdaptParameters q = Comparison(ts, p, vshmm::termsScaled(p, 2.0, vs->tableau->order));
  if (!Coarser(p, q)) q = vshmm::coarsened(p, 0, kFinerComparison);
  PetscCall(EstimationStep(ts, q, t0, DeltaT, vs->Xcarried));
  PetscCall(ObservableDifference(ts, t0 + DeltaT, ts->vec_sol, vs->Xcarried, &D, PETSC_FALSE)); /* measured as the comparisons are, outside their record */
  PetscReal carried, solution;
  PetscCall(VecNorm(vs->Xcarried, NORM_1, &carried));
  PetscCall(VecNorm(ts->vec_sol, NORM_1, &solution));
  vs->carried_time = t0 + DeltaT;
  if (!std::isfinite(D) || !(carried <= kBlowUpGrowth * (solution + start))) {
    /* the doubled terms are unstable here (a comparison's steps at the edge of a stability region
       the solution's stay inside): no estimate from it; it starts again from the solution, and the
       estimate counts from there */
    PetscCall(VecCopy(ts->vec_sol, vs->Xcarried));
    vs->carried_weight = 0;
    vs->carried_fsum   = 0;
    vs->carried_restarts++;
    PetscCall(PetscInfo(ts, "Adapt: the carried comparison blew up at t = %g: started again from the solution (the global estimate keeps %g)\n", (double)(t0 + DeltaT), (double)vs->global_estimate));
    PetscFunctionReturn(0);
  }
  /* the difference holds every step's contribution, each to be converted as its step's own
     comparison was (E / d: the model's conversion, or an initial layer's second comparison; the
     model's for a step without a comparison): their mean weighed by the steps' estimates (one step's
     factor alone, 14.6 where its model expected almost no change, read a difference of 0.9 as 13
     tolerances) */
  const PetscReal model  = Estimate(vs->adapt_model, p, q, 1.0);
  const PetscReal factor = (d > 0 && std::isfinite(d) && std::isfinite(E)) ? E / d : (std::isfinite(model) && model > 0 ? model : 1.0);
  const PetscReal w      = std::isfinite(E) && E > 0 ? E : 0;
  vs->carried_fsum += w * factor;
  vs->carried_weight += w;
  vs->carried_factor      = vs->carried_weight > 0 ? vs->carried_fsum / vs->carried_weight : factor;
  vs->global_estimate     = D * vs->carried_factor;
  vs->global_estimate_max = PetscMax(vs->global_estimate_max, vs->global_estimate);
  PetscCall(
    PetscInfo(ts, "Adapt: the carried comparison at t = %g: global estimate %g (difference %g, factor %g); the macro steps' estimates sum to %g\n", (double)(t0 + DeltaT), (double)vs->global_estimate, (double)D, (double)vs->carried_factor, (double)vs->error_estimate_total));
  if (!vs->global_warned && !(vs->global_estimate <= kWarn)) {
    vs->global_warned = PETSC_TRUE;
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt_global_estimate): at t = %g the carried comparison estimates the error of the sampled %s at %g times the tolerance (the macro steps' own estimates sum to %g): errors made in earlier macro steps grew in later ones (an amplitude error that shifts a frequency, an unstable slow equation), or the savings move what the comparisons do not measure. The tolerance is not met. Tighten -ts_rtol/-ts_atol, put the tolerance on slow quantities (TSVSHMMSetObservables()), or use a single-rate TS type. This warning is given once per solve.\n", (double)(t0 + DeltaT), vs->observables ? "observables" : "state",
                                  (double)vs->global_estimate, (double)vs->error_estimate_total));
  }
  PetscFunctionReturn(0);
}

/* The error model's split between the terms: one comparison run per parameter, the micro step
   doubled or r_l - 1 times kRatioCoarsening (vshmm::coarsened; each costs 1/2 or 1/4 of the step). A parameter whose coarser run is not finite stays where it is. */
/* A level whose time ratio r saves less than kNegligibleSavings (r - 1 below it) saves almost no work
   but still samples the faster scales: it takes no savings (r = 1, alpha = 0) for the rest of the
   solve, which removes its error term. It is applied to the choice after an accepted step, not to
   the retries of a step (an initial layer refines the ratios fast and must keep the way back open),
   Without this, a problem whose slow quantities carry a part
   of the fast phase (any savings shift it: the stiff-spring chain's I) drives r towards 1
   geometrically, and the micro step down with it, without ever meeting the tolerance. */
static void SnapNegligibleSavings(TS_VSHMM *vs, vshmm::AdaptParameters &p, const vshmm::AdaptBounds &bounds)
{
  /* nor where a fold of the fastest level's slow manifold took the savings back for this step only
     (FollowRatesAtTryEnd(): its rate fell, or its mode grew, within the step): a bistable fast variable
     driven across its folds stayed single-rate for the rest of the run after its first jump; nor a
     pair whose savings its lost separation took back (NoteLostSeparation(): while so) */
  if (bounds.fixedRatios || RateFell(vs)) return;
  vs->adapt_no_savings.resize(p.ratios.size(), PETSC_FALSE);
  for (size_t l = 0; l < p.ratios.size(); ++l)
    if (p.ratios[l] - 1.0 < kNegligibleSavings && !(l < vs->adapt_lost.size() && vs->adapt_lost[l] >= 0)) {
      p.ratios[l]             = 1.0;
      vs->adapt_no_savings[l] = PETSC_TRUE;
    }
}

static PetscErrorCode Calibrate(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT, vshmm::AdaptBounds &bounds, PetscBool retry)
{
  TS_VSHMM                           *vs = (TS_VSHMM *)ts->data;
  const PetscInt                      K  = (PetscInt)p.ratios.size();
  std::vector<vshmm::AdaptParameters> coarse(K + 1);
  std::vector<double>                 d(K + 1, 0.0);
  std::vector<bool>                   skipped(K + 1, false);
  bool                                finerInShare = false; /* the micro step's term, measured from the finer side, was not counted */

  PetscFunctionBegin;
  vs->finer_term = 0;
  if (!retry || vs->adapt_negligible.size() != (size_t)K + 1) {
    vs->adapt_negligible.assign(K + 1, 0);
    vs->adapt_negligible_reach.assign(K + 1, 0.0);
  }
  for (PetscInt i = 0; i <= K; ++i) {
    /* measured as negligible by this macro step's last calibrations, up to a parameter at least as
       coarse as p's: not run again (a ratio the retries coarsened past the calibration's reach is
       measured again: the oscillators at 1.5e-3, t = 0.8, doubled r_2 each try from 200 to 11,787
       on a term measured negligible at 200) */
    if (retry && vs->adapt_negligible[i] >= kNegligibleCalibrations && (i ? p.ratios[i - 1] : p.microStep) <= vs->adapt_negligible_reach[i]) {
      coarse[i]  = p;
      skipped[i] = true;
      PetscCall(PetscInfo(ts, "Adapt: calibration of parameter %" PetscInt_FMT ": negligible in the last %" PetscInt_FMT " calibrations of this macro step, not measured again\n", i, vs->adapt_negligible[i]));
      continue;
    }
    coarse[i] = Comparison(ts, p, vshmm::coarsened(p, (int)i, i ? kRatioCoarsening : 2.0));
    /* one parameter at a time: the others as in p */
    if (i > 0) coarse[i].microStep = p.microStep;
    for (PetscInt l = 0; l < K; ++l)
      if (l != i - 1) coarse[i].ratios[l] = p.ratios[l];
    if (i == 0 && vs->adapt_accepted == vs->adapt_start_accepted && !bounds.fixedMicroStep && !(coarse[0].microStep > 1.01 * p.microStep)) {
      /* the micro step at its stability bound: measured by a finer run (kFinerComparison), not left
         at 0. In an initial layer the fast transient, taken at h |lambda| near the stability limit,
         can be most of the error (the 2-scale chain with DeltaT = 0.5 at 1e-3: x0(0.5) 3.85 tol
         off, 0.34 tol with it measured; docs/accuracy.md section 12). So also in the first step
         with savings after scales found separated later (SeparationChanged()): its fast rates
         may grow within the step past the stable step estimated at its start (z' = 1000 x (x - z)
         from x = 0: 1.66 tol in that step, with the micro step's term unmeasured) */
      coarse[0] = vshmm::coarsened(p, 0, kFinerComparison);
    }
    PetscReal di = 0;
    if (vshmm::cycleLength(coarse[i]) > vshmm::cycleLength(p) * 1.01 || (i == 0 && coarse[0].microStep < p.microStep / 1.01)) {
      PetscCall(TrialStep(ts, coarse[i], t0, DeltaT, vs->Xtrial));
      PetscCall(ObservableDifference(ts, t0 + DeltaT, vs->Xbase, vs->Xtrial, &di));
    }
    if (!std::isfinite(di)) { /* coarser is unstable: this parameter stays where it is, its error term unmeasured */
      di = 0;
      if (i == 0) bounds.maxMicroStep = p.microStep;
      else {
        bounds.maxRatio.resize(K, PETSC_INFINITY);
        bounds.maxRatio[i - 1] = p.ratios[i - 1];
      }
      coarse[i] = p;
    }
    if (i == 0 && coarse[0].microStep < p.microStep / 1.01 && di / (1.0 - PetscPowRealInt(kFinerComparison, vs->tableau->order)) < kFinerTermShare * StepBudget(ts, DeltaT)) {
      /* a micro step term measured from the finer side within the step's share: the layer's
         transient is resolved; counted, it would only move work to a finer micro step (the
         dissipative example at 1e-1: 1.6x the work with a quarter of the share as the bound) */
      PetscCall(PetscInfo(ts, "Adapt: calibration of parameter 0: the finer micro step %g changes the observables by %g, a term within the step's share: not counted\n", (double)coarse[0].microStep, (double)di));
      di           = 0;
      coarse[0]    = p;
      finerInShare = true;
    }
    if (i == 0 && coarse[0].microStep < p.microStep / 1.01) vs->finer_term = di / (1.0 - PetscPowRealInt(kFinerComparison, vs->tableau->order));
    d[i]                          = di;
    vs->adapt_negligible_reach[i] = i ? coarse[i].ratios[i - 1] : coarse[i].microStep;
    PetscCall(PetscInfo(ts, "Adapt: calibration of parameter %" PetscInt_FMT ": dt %g, cycle %g, difference %g\n", i, (double)coarse[i].microStep, (double)vshmm::cycleLength(coarse[i]), (double)di));
  }
  PetscReal largest = 0;
  for (double x : d) largest = PetscMax(largest, PetscAbsReal(x));
  for (PetscInt i = 0; i <= K; ++i)
    if (!skipped[i]) vs->adapt_negligible[i] = PetscAbsReal(d[i]) <= kNegligibleTerm * largest ? vs->adapt_negligible[i] + 1 : 0;
  if (finerInShare) vs->adapt_negligible[0] = PetscMax(vs->adapt_negligible[0], kNegligibleCalibrations); /* the step's retries do not measure it again */
  vs->adapt_model = vshmm::ErrorModel::fromDifferences(p, coarse, d, vs->tableau->order, Saturations(ts, p));
  if (!(vs->adapt_model.total(p) > 0)) vs->adapt_model = vshmm::ErrorModel::equalShares(p, vs->tableau->order, 1.0, Saturations(ts, p));
  vs->adapt_calibrations++;
  vs->adapt_calibrated_times++;
  vs->adapt_since_calibration = 0;
  vs->adapt_calibrated        = PETSC_TRUE;
  vs->adapt_postponed         = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Where the separation check found the scales not separated, adapt's steps take no savings: the
   estimate compares runs with savings, and it can be blind to what savings do there (a slow
   process inside a fast level, slowed with it, is slowed in the comparison too). After the first
   macro step, taken single-rate (its result in vs->Xbase, from vs->X0), the savings adapt would
   start from were the scales separated (vs->adapt_candidate) are tested against it: the same
   macro step with those time ratios and the same micro step. Their difference is the savings'
   own error in that step; where it is within kSavingsMargin of the step's share of the tolerance
   as if every step's error added up coherently (kSafety tol DeltaT / span), the savings are
   admitted, as the upper
   bound of adapt's choice for the rest of the solve (Bounds()); otherwise again with r_l - 1
   scaled to half what would pass (the savings' error grows with r_l - 1), kSavingsTests tests in
   all, and then none. The candidate ratios, the difference and the decision
   are shown with -info; the decision by -ts_view. */
static PetscErrorCode VerifySavings(TS ts, const vshmm::AdaptParameters &p, PetscReal t0, PetscReal DeltaT)
{
  TS_VSHMM       *vs       = (TS_VSHMM *)ts->data;
  const PetscInt  K        = (PetscInt)p.ratios.size();
  const PetscReal span     = RunSpan(ts);
  const PetscReal fraction = span > 0 ? PetscMin(1.0, DeltaT / span) : 1.0 / kOscillationSpanSteps;
  const PetscReal budget   = kSafety * fraction; /* in units of the tolerance */

  PetscFunctionBegin;
  vs->adapt_verified.assign(K, 1.0);
  vshmm::AdaptParameters q = p;
  q.ratios                 = vs->adapt_candidate;
  for (int attempt = 0; attempt < kSavingsTests; ++attempt) {
    const vshmm::AdaptBounds b = Bounds(ts, DeltaT);
    LimitAllToStableSteps(vs, q);
    vshmm::fitCycle(q, b.maxCycle, false, true);
    q.microStep = p.microStep;
    bool any    = false;
    for (double r : q.ratios) any = any || r - 1.0 >= kNegligibleSavings;
    if (!any) break;
    PetscReal d;
    PetscCall(TrialStep(ts, q, t0, DeltaT, vs->Xtrial));
    PetscCall(ObservableDifference(ts, t0 + DeltaT, vs->Xbase, vs->Xtrial, &d));
    std::string ratios;
    for (double r : q.ratios) ratios += (ratios.empty() ? "" : ",") + std::to_string(r);
    PetscCall(PetscInfo(ts, "Adapt: the scales are not separated; savings tested against the single-rate macro step [%g, %g]: time ratios %s differ by %g of the tolerance (admitted up to %g)\n", (double)t0, (double)(t0 + DeltaT), ratios.c_str(), (double)d, (double)(kSavingsMargin * budget)));
    if (std::isfinite(d) && d <= kSavingsMargin * budget) {
      vs->adapt_verified = q.ratios;
      break;
    }
    const PetscReal scale = (std::isfinite(d) && d > 0) ? 0.5 * kSavingsMargin * budget / d : 0.0;
    for (double &r : q.ratios) r = 1.0 + (r - 1.0) * scale;
  }
  if (TSVSHMMSavingsAdmitted_Private(vs)) vs->adapt_calibrated = PETSC_FALSE; /* the error model's split is measured again with the savings */
  PetscFunctionReturn(0);
}

/* In the first macro step of the accuracy control (an initial layer, where the faster variables
   start off their slow manifold) the comparison's difference d overstates the error 2.5-4 times:
   the slow error grows faster than linearly as the comparison doubles the terms (the fastest level
   is slowed by the product of the ratios), which the model's terms, additive in r_l - 1, do not
   know (docs/accuracy.md section 3, "How reliable the estimate is in an initial layer"). A second
   comparison with every term scaled by kSecondScaling gives the exponent of that growth and the
   error from it (vshmm::errorFromTwoComparisons(): 0.55-1.2 times the true error there, against
   2.5-4 times). Made only where both comparisons scale every term exactly (none was cut by a
   stability or cycle bound) and where the step's estimate is above its share by at most
   kLayerFitWindow (where a truer estimate can decide the step). *Efit < 0: not made. */
static PetscErrorCode LayerEstimate(TS ts, const vshmm::AdaptParameters &p, const vshmm::AdaptParameters &q, PetscReal d, PetscReal t0, PetscReal DeltaT, PetscReal *Efit)
{
  TS_VSHMM                    *vs    = (TS_VSHMM *)ts->data;
  const int                    order = vs->tableau->order;
  const vshmm::AdaptParameters q2 = vshmm::termsScaled(p, 2.0, order), q1 = vshmm::termsScaled(p, kSecondScaling, order);
  const vshmm::AdaptParameters q1c   = Comparison(ts, p, q1);
  const auto                   Equal = [](const vshmm::AdaptParameters &a, const vshmm::AdaptParameters &b) {
    bool same = PetscAbsReal(a.microStep / b.microStep - 1) < 1e-9;
    for (size_t l = 0; l < a.ratios.size(); ++l) same = same && PetscAbsReal(a.ratios[l] / b.ratios[l] - 1) < 1e-9;
    return same;
  };
  PetscReal d1;

  PetscFunctionBegin;
  *Efit = -1;
  if (!Equal(q, q2) || !Equal(q1c, q1)) PetscFunctionReturn(0);
  PetscCall(TrialStep(ts, q1, t0, DeltaT, vs->Xtrial));
  PetscCall(ObservableDifference(ts, t0 + DeltaT, vs->Xbase, vs->Xtrial, &d1));
  if (!(std::isfinite(d1) && d1 > 0)) PetscFunctionReturn(0);
  double kappa;
  *Efit = vshmm::errorFromTwoComparisons(d1, kSecondScaling, d, 2.0, &kappa);
  PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: a second comparison (every term x %g) differs by %g against %g: the error grows as the terms to the power %g, estimate %g\n", (double)t0, (double)(t0 + DeltaT), (double)kSecondScaling, (double)d1, (double)d, kappa, (double)*Efit));
  vs->adapt_layer_fits++;
  PetscFunctionReturn(0);
}

/* Adapt starts again from the parameters just set in vs->adapt_params (a separation verdict that
   changed, a merged pair now separated): brought inside the stable steps and the cycle bound, the
   error model measured again, the next step treated as a first (its micro step's term measured
   from the finer side, Calibrate()). */
static void StartAgain(TS ts)
{
  TS_VSHMM               *vs = (TS_VSHMM *)ts->data;
  vshmm::AdaptParameters &p  = vs->adapt_params;

  LimitToStableSteps(ts, p);
  const vshmm::AdaptBounds b = Bounds(ts, ts->time_step);
  vshmm::fitCycle(p, b.maxCycle, b.fixedRatios, true);
  vs->adapt_model          = vshmm::ErrorModel();
  vs->adapt_calibrated     = PETSC_FALSE;
  vs->adapt_start_accepted = vs->adapt_accepted;
}

/* The separation check's verdict changed (vs->no_separation against `before`): adapt starts again
   from the parameters the new verdict gives at the present spectra (FirstMicroStep(),
   FirstRatios()), with the split between the terms measured again. Scales found not separated
   are checked again at every estimate of the levels' spectra (the calibrations; a periodic check
   with -ts_vshmm_check_stability_interval checks both ways): a state can show the faster levels
   far slower than the dynamics make them a moment later (chemical kinetics whose intermediate
   species start at 0: a rate proportional to the species' concentration is 0 there), and the
   check at set-up would then leave the whole solve without savings. Said where the verdict is
   lifted (the warning of the check before told the user that VSHMM was the wrong tool). */
static PetscErrorCode SeparationChanged(TS ts, PetscBool before, PetscReal tbefore)
{
  TS_VSHMM               *vs = (TS_VSHMM *)ts->data;
  vshmm::AdaptParameters &p  = vs->adapt_params;

  PetscFunctionBegin;
  if (vs->no_separation == before || !vs->savings.empty() || !vs->adapt_ready) PetscFunctionReturn(0);
  if (vs->adapt_single_rate_from < 0) vs->adapt_no_savings.clear();
  p.microStep = FirstMicroStep(ts);
  PetscCall(FirstRatios(ts, p));
  if (vs->adapt_single_rate_from >= 0)
    for (double &r : p.ratios) r = 1.0;
  StartAgain(ts);
  if (!vs->no_separation) {
    PetscReal   best;
    std::string figures;
    bool        own;
    PetscCall(SeparationFigures(ts, &best, figures, &own));
    vs->separated_from = ts->ptime;
    PetscCall(PetscInfo(ts, "Adapt: the scales are separated at t = %g: savings from here on (micro step %g, cycle %g)\n", (double)ts->ptime, (double)p.microStep, (double)vshmm::cycleLength(p)));
    if (vs->check_separation != TSVSHMM_SEPARATION_OFF)
      PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM: separation check at t = %g: the time scales of the RHS splits are separated now (%s). The check at t = %g found them not separated at a state where the faster levels were slower (an initial state whose fast modes are not yet excited, typically); -ts_vshmm_adapt takes savings from t = %g on.\n",
                                    (double)ts->ptime, figures.c_str(), (double)tbefore, (double)ts->ptime));
  }
  PetscFunctionReturn(0);
}

/* Decaying level pairs merged at set-up (FirstRatios(): less than kInitialDecaySeparation apart)
   checked again at the spectra just estimated: where a pair is now kMinSeparation apart, it takes
   savings from its separated start on, with the error model measured again. Three levels whose
   medium rate is proportional to the slow variable, which starts at 0 (x' = 1 - x + (y - x)/5 +
   (z - x)/10, y' = 1000 x (x - y), z' = 1e5 (y - z)), had levels 0/1 1 apart at the initial
   state and 500 apart a step later, and took no savings between them for the whole solve. */
static PetscErrorCode RecheckMergedPairs(TS ts)
{
  TS_VSHMM                 *vs    = (TS_VSHMM *)ts->data;
  vshmm::AdaptParameters   &p     = vs->adapt_params;
  const std::vector<double> start = SeparatedRatios(ts);
  bool                      any   = false;

  PetscFunctionBegin;
  for (size_t l = 0; l < vs->adapt_merged.size() && l < p.ratios.size(); ++l) {
    if (!(vs->adapt_merged[l] > 0)) continue;
    const PetscReal S = Separation(vs, (PetscInt)l);
    if (!(S >= kMinSeparation) || !LevelDecays(vs, (PetscInt)l + 1)) continue;
    PetscCall(PetscInfo(ts, "Adapt: levels %d/%d are %g apart at t = %g (%g at set-up): savings between them from here on\n", (int)l, (int)l + 1, (double)S, (double)ts->ptime, (double)vs->adapt_merged[l]));
    vs->adapt_merged[l] = 0;
    if (l < vs->adapt_no_savings.size()) vs->adapt_no_savings[l] = PETSC_FALSE;
    p.ratios[l] = start[l];
    any         = true;
  }
  if (!any) PetscFunctionReturn(0);
  StartAgain(ts);
  PetscFunctionReturn(0);
}

/* Separated scales whose oscillating faster level came within kMinSeparation of the slower one at
   the spectra just estimated: a process inside it as slow as the slower level (its amplitude damped
   at a rate a slow variable sets), which savings would slow with it. Bounds() takes no savings
   between them while so, from this step's first try on (the levels' spectra at tseen: the start
   of the step, or the end of its try, FollowRatesAtTryEnd()); said once per solve (an error with
   -ts_vshmm_check_separation error), as the check at set-up says it. A Duffing rotation damped by
   a slow variable x that starts at 0 (q' = p / eps, p' = -(q + q^3) / eps - x p / 2, x' = -x + q^2,
   eps = 1e-3) was separated at t = 0, 0.012 apart at t = 0.1, took time ratios of 3.6 there and
   ended 1.7 tol off at 1e-3, silently (the damping ran 3.6x too slowly; the comparison, whose
   error saturates in r, read 0.1 of the step's share where the step took 5.5). A pair separated
   again starts from its separated ratios (SeparatedRatios()), the split between the terms measured
   again: from (3, 0, 0) the dissipative example's medium level has no rate (-2 eta / eps = 0), the
   pair took r_0 = 1 in the first step, which was then dropped as negligible savings for the whole
   solve though the pair was 11,000 apart 0.1 later (2.2x the work of the additive splits, whose own
   rate is judged otherwise). */
static PetscErrorCode NoteLostSeparation(TS ts, PetscReal tseen)
{
  TS_VSHMM      *vs   = (TS_VSHMM *)ts->data;
  const PetscInt K    = (PetscInt)vs->level_end.size() - 1;
  bool           lost = false;

  PetscFunctionBegin;
  vs->adapt_lost.resize(K, -1.0);
  bool regained = false, decays = false; /* decays: a pair whose faster level only decays lost it */
  for (PetscInt l = 0; l < K; ++l) {
    const bool now = LostSeparation(vs, l);
    if (!now && vs->adapt_lost[l] >= 0 && l < (PetscInt)vs->adapt_params.ratios.size() && vs->adapt_params.ratios[l] == 1.0) {
      vs->adapt_params.ratios[l] = vs->savings.empty() ? SeparatedRatios(ts)[l] : vshmm::timeRatiosFromSavings(vs->savings)[l]; /* savings the user set stay */
      regained                   = true;
      PetscCall(PetscInfo(ts, "Adapt: levels %" PetscInt_FMT "/%" PetscInt_FMT " are separated again at t = %g (%g apart): savings between them from their separated start\n", l, l + 1, (double)tseen, (double)Separation(vs, l)));
    }
    if (!now) vs->adapt_lost[l] = -1;
    else if (vs->adapt_lost[l] < 0) {
      vs->adapt_lost[l] = ts->ptime;
      lost              = true;
      decays            = decays || LevelDecays(vs, l + 1);
    }
    if (now && l < (PetscInt)vs->adapt_params.ratios.size()) vs->adapt_params.ratios[l] = 1.0; /* from this step's first try on */
  }
  if (regained && vs->adapt_ready) StartAgain(ts);
  if (!lost || vs->lost_warned) PetscFunctionReturn(0);
  PetscReal   best;
  std::string figures;
  bool        own;
  PetscCall(SeparationFigures(ts, &best, figures, &own));
  PetscCall(PetscInfo(ts, "Adapt: separation at t = %g: %s; a level within %g of the slower one takes no savings from t = %g\n", (double)tseen, figures.c_str(), (double)kMinSeparation, (double)ts->ptime));
  if (vs->check_separation == TSVSHMM_SEPARATION_OFF) PetscFunctionReturn(0);
  vs->lost_warned = PETSC_TRUE;
  const char *why = decays ? "a faster level that only decays relaxes, at its slowest rate, less than that much faster than the slower level moves (a relaxation that slows near its slow manifold, or a band of rates that reaches down towards the "
                             "slower level), and savings would slow it further"
                           : "a faster level oscillates and a process inside it (its amplitude's rate) is as slow as the slower level, which savings would slow with it";
  PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: the time scales of the RHS splits are no longer separated (at least %g needed: %s): %s; use a single-rate TS type (-ts_type rk), or -ts_vshmm_check_separation warn to run anyway (-ts_vshmm_adapt then takes no savings between those levels while so)", (double)tseen, (double)kMinSeparation,
             figures.c_str(), why);
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: the time scales of the RHS splits are no longer separated (at least %g needed: %s): %s. -ts_vshmm_adapt takes no savings between those levels while so (-ts_view names them); where it lasts, a single-rate TS type (-ts_type rk) is the right tool. (-ts_vshmm_check_separation error makes this an error, off silences it.)\n", (double)tseen, (double)kMinSeparation,
                                figures.c_str(), why));
  PetscFunctionReturn(0);
}

/* Said once per solve (an error with -ts_vshmm_check_separation error): the sampled quantities
   carry the phase of level `level`'s oscillation (TSVSHMMFastQuantities_Private()). */
static PetscErrorCode SayFastQuantities(TS ts, PetscReal t, PetscInt level, PetscInt which, PetscReal swing, PetscReal rate, PetscBool adapting)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  char      what[64];

  PetscFunctionBegin;
  if (vs->phase_warned || vs->check_separation == TSVSHMM_SEPARATION_OFF) PetscFunctionReturn(0);
  vs->phase_warned = PETSC_TRUE;
  if (which >= 0) PetscCall(PetscSNPrintf(what, sizeof what, "observable %" PetscInt_FMT " (of %" PetscInt_FMT ")", which, vs->nobservables));
  else PetscCall(PetscSNPrintf(what, sizeof what, "the sampled state (no observables set)"));
  PetscCheck(vs->check_separation != TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP, "TSVSHMM separation check at t = %g: %s moves with level %" PetscInt_FMT "'s oscillation (%g times the slower level's spectral radius along that level's own splits, swinging by at least %g tolerances): VSHMM samples that level statistically and does not compute its phase, so with savings below it the sampled values are not the solution's. Name slow quantities as observables (TSVSHMMSetObservables(): energies, actions, averages), use a single-rate TS type (-ts_type rk), or -ts_vshmm_check_separation warn to run anyway", (double)t, what, level, (double)rate, (double)swing);
  if (adapting)
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: %s moves with level %" PetscInt_FMT "'s oscillation (%g times the slower level's spectral radius along that level's own splits, swinging by at least %g tolerances). VSHMM samples that level statistically and does not compute its phase: -ts_vshmm_adapt takes no savings below level %" PetscInt_FMT " (-ts_view names the pairs), a single-rate method there, where -ts_type rk is the right tool. The tolerance belongs on slow quantities (TSVSHMMSetObservables(): energies, actions, averages). %s(-ts_vshmm_check_separation error makes this an error, off silences it.)\n", (double)t, what, level, (double)rate, (double)swing, level, vs->adapt_global ? "" : "The error estimates are each macro step's own; a phase error that grows over the run (an amplitude error that shifts a nonlinear oscillation's frequency) is seen by -ts_vshmm_adapt_global_estimate. "));
  else
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning: separation check at t = %g: %s moves with level %" PetscInt_FMT "'s oscillation (%g times the slower level's spectral radius along that level's own splits, swinging by at least %g tolerances). VSHMM samples that level statistically and does not compute its phase: with the savings set below it, the sampled values are one phase of the oscillation, not the solution's. Name slow quantities as observables (TSVSHMMSetObservables(): energies, actions, averages), or take no savings below level %" PetscInt_FMT " (-ts_type rk). (-ts_vshmm_check_separation error makes this an error, off silences it.)\n", (double)t, what, level, (double)rate, (double)swing, level));
  PetscFunctionReturn(0);
}

/* Whether p takes savings on a pair (time ratio above 1) not yet taken back by NoteFastQuantities(). */
static bool PhaseSavings(const TS_VSHMM *vs, const vshmm::AdaptParameters &p)
{
  for (size_t l = 0; l < p.ratios.size(); ++l)
    if (p.ratios[l] > 1.0 && !(l < vs->adapt_phase.size() && vs->adapt_phase[l] >= 0)) return true;
  return false;
}

/* At the end of a try (state vs->Xbase at t1): where a faster level with a sustained oscillation
   moves the sampled quantities on its own time scale (an observable that carries its phase, or the
   state with such a level in it), savings below that level make the sampled values one phase of
   the oscillation, an error the comparisons do not measure (the phase differs between the step and
   its comparison as it does from the solution: x' = -x + q^2, q' = p / eps, p' = -q / eps observed
   through x and q ended 2.2-2.5 tol off at 1e-1 and 1e-2 with estimates of 0.9, silently, and took
   24 million evaluations at 1e-3). The pairs below it take no savings from this step on, the try
   is taken again, and the user is told. */
static PetscErrorCode NoteFastQuantities(TS ts, PetscReal t1, const vshmm::AdaptBounds &bounds, PetscBool *redo)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscInt  level, which;
  PetscReal swing, rate;

  PetscFunctionBegin;
  *redo = PETSC_FALSE;
  PetscCall(TSVSHMMFastQuantities_Private(ts, t1, vs->Xbase, kPhaseSwing, &level, &which, &swing, &rate));
  if (level < 1) PetscFunctionReturn(0);
  bool taken = false;
  for (PetscInt l = 0; l < level && l < (PetscInt)vs->adapt_params.ratios.size(); ++l) {
    if (vs->adapt_params.ratios[l] > 1.0) taken = true;
    if (bounds.fixedRatios) continue;
    vs->adapt_phase.resize(vs->adapt_params.ratios.size(), -1.0);
    if (vs->adapt_phase[l] < 0) vs->adapt_phase[l] = ts->ptime;
    vs->adapt_params.ratios[l] = 1.0;
  }
  if (!taken) PetscFunctionReturn(0);
  PetscCall(PetscInfo(ts, "Adapt: at t = %g the sampled quantities move with level %" PetscInt_FMT "'s oscillation (swing %g tolerances): %s\n", (double)t1, level, (double)swing, bounds.fixedRatios ? "the savings are set, kept" : "no savings below it from this step on, the try taken again"));
  PetscCall(SayFastQuantities(ts, t1, level, which, swing, rate, PETSC_TRUE));
  if (!bounds.fixedRatios) *redo = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The same for a run with fixed parameters (no -ts_vshmm_adapt), at the sampled state at t: only
   said, the parameters are the user's. */
PetscErrorCode TSVSHMMCheckFastQuantities_Private(TS ts, PetscReal t)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscInt  level, which;
  PetscReal swing, rate;

  PetscFunctionBegin;
  if (vs->phase_warned || vs->check_separation == TSVSHMM_SEPARATION_OFF || vs->level_limiting.empty()) PetscFunctionReturn(0);
  const std::vector<double> ratios = vshmm::timeRatiosFromSavings(vs->savings_used);
  bool                      any    = false;
  for (double r : ratios) any = any || r > 1.0;
  if (!any) PetscFunctionReturn(0);
  /* no tolerance was asked for (the TS's default ones): said where the swing is a tenth of the quantities */
  PetscCall(TSVSHMMFastQuantities_Private(ts, t, ts->vec_sol, kFixedSwing / PetscMax(TSVSHMMToleranceLevel_Private(ts), PETSC_SMALL), &level, &which, &swing, &rate));
  if (level < 1) PetscFunctionReturn(0);
  any = false;
  for (PetscInt l = 0; l < level && l < (PetscInt)ratios.size(); ++l) any = any || ratios[l] > 1.0;
  if (any) PetscCall(SayFastQuantities(ts, t, level, which, swing, rate, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* Scales not separated at the last check: checked again at the spectra just estimated (and merged
   pairs among separated scales, RecheckMergedPairs(), and oscillating pairs that lost their
   separation, NoteLostSeparation()). */
static PetscErrorCode RecheckSeparation(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (!vs->savings.empty() || vs->spectra_time != ts->ptime) PetscFunctionReturn(0);
  if (!vs->no_separation) {
    PetscCall(NoteLostSeparation(ts, ts->ptime));
    PetscCall(RecheckMergedPairs(ts));
    PetscFunctionReturn(0);
  }
  const PetscReal tbefore = vs->separation_time;
  PetscReal       best;
  std::string     figures;
  bool            own;
  PetscCall(SeparationFigures(ts, &best, figures, &own));
  PetscCall(PetscInfo(ts, "Adapt: separation at t = %g: %s\n", (double)ts->ptime, figures.c_str()));
  if (best < kMinSeparation) PetscFunctionReturn(0);
  vs->no_separation   = PETSC_FALSE;
  vs->separation_time = ts->ptime;
  PetscCall(SeparationChanged(ts, PETSC_TRUE, tbefore));
  PetscFunctionReturn(0);
}

/* At a solve's last macro step (-ts_vshmm_adapt): the run's work, its estimates and rejected tries
   included, against what a single-rate TSRK of the same tableau takes over each accepted macro step
   at the largest step the run's bounds allow it (SingleRateStep(): stable, resolving the fastest
   oscillation over the span; at least the micro step) (vs->single_rate_evaluations). Before
   2026-11-28 at the micro step itself, which adapt can drive far below that (a non-normal fast level
   at 1e-3: 8 times below its stability limit, so the run was said to cost 1.8 times single-rate
   steps where a plain RK4 at its stable step took 12 times less). Those single-rate steps are
   stable for every level and have no averaging error, so a run that cost more saved nothing: the savings
   the tolerance allowed were too small to pay for their comparisons (a faster level with a band of
   rates whose slowest one is a few tens of times the slow level's: separated, yet time ratios about
   1.6 at 1e-1). Said once per run, not where the separation check, a beat or the accuracy control
   already took the savings away and said so. */
PetscErrorCode TSVSHMMAdaptCheckCost_Private(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (vs->cost_warned || vs->no_separation || vs->adapt_single_rate_from >= 0 || vs->beat_warned) PetscFunctionReturn(0); /* said already, with the single-rate type */
  const PetscInt64 work   = TSVSHMMWork_Private(vs) - vs->run_start_work;
  const PetscInt64 single = vs->single_rate_evaluations - vs->run_start_single_rate;
  PetscCall(
    PetscInfo(ts, "Adapt: this run to t = %g took %" PetscInt64_FMT " split RHS evaluations (estimates included); single-rate TSRK %s steps at the largest steps its bounds allow %" PetscInt64_FMT "\n", (double)ts->ptime, work, vs->tableau->name.c_str(), single));
  if (work <= single) PetscFunctionReturn(0);
  vs->cost_warned = PETSC_TRUE;
  PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): this run to t = %g took %" PetscInt64_FMT " split RHS evaluations, its error estimates and rejected tries included: %.3g times what single-rate TSRK %s steps take over the same span (%" PetscInt64_FMT ") at the largest step its bounds allow (stable for every level, resolving the fastest oscillation, at least its micro step), which have no averaging error. The savings the tolerance allowed (time ratios at most %.3g in product) did not pay for their comparisons: for a run like this one (its tolerance, sampling interval and length: a longer run spreads the first macro steps' calibrations) a single-rate TS type (-ts_type rk, with its own step control) is the better tool.\n",
                                (double)ts->ptime, work, (double)work / (double)single, vs->tableau->name.c_str(), single, (double)vs->run_largest_ratio));
  PetscFunctionReturn(0);
}

/* The periodic separation check of TSStep_VSHMM() with -ts_vshmm_adapt: the check, and adapt's
   parameters where its verdict changed. */
PetscErrorCode TSVSHMMAdaptCheckSeparation_Private(TS ts)
{
  TS_VSHMM       *vs      = (TS_VSHMM *)ts->data;
  const PetscBool before  = vs->no_separation;
  const PetscReal tbefore = vs->separation_time;

  PetscFunctionBegin;
  PetscCall(TSVSHMMCheckSeparation_Private(ts));
  PetscCall(SeparationChanged(ts, before, tbefore));
  PetscFunctionReturn(0);
}

/* The time ratios of p, comma-separated, for -info and -ts_adapt_monitor */
static std::string RatiosText(const vshmm::AdaptParameters &p)
{
  std::string ratios;
  for (double r : p.ratios) ratios += (ratios.empty() ? "" : ",") + std::to_string(r);
  return ratios;
}

/* -ts_adapt_monitor (TSAdaptSetMonitor() on the TS's TSAdapt, as PETSc's adaptive controllers
   print theirs): a line per try of a macro step that got an estimate, what became of it, and the
   parameters it ran with. */
static PetscErrorCode MonitorTry(TS ts, const char *outcome, PetscReal t0, PetscReal DeltaT, PetscInt attempt, const vshmm::AdaptParameters &p, PetscInt64 cycles, PetscReal E, PetscReal budget)
{
  TSAdapt adapt;

  PetscFunctionBegin;
  PetscCall(TSGetAdapt(ts, &adapt));
  if (!adapt->monitor) PetscFunctionReturn(0);
  const std::string ratios = RatiosText(p);
  PetscCall(PetscViewerASCIIAddTab(adapt->monitor, ((PetscObject)adapt)->tablevel));
  PetscCall(PetscViewerASCIIPrintf(adapt->monitor, "    TSAdapt vshmm: step %3" PetscInt_FMT " %s t=%-11g+%10.3e try %" PetscInt_FMT " estimate %.3e of its share %.3e (%.3g), micro step %.3e, time ratios %s, %" PetscInt64_FMT " micro cycles\n", ts->steps, outcome, (double)t0, (double)DeltaT, attempt, (double)E, (double)budget, (double)(E / budget),
                                   (double)p.microStep, ratios.c_str(), cycles));
  PetscCall(PetscViewerASCIISubtractTab(adapt->monitor, ((PetscObject)adapt)->tablevel));
  PetscFunctionReturn(0);
}

/* One macro step with accuracy control; the accepted result is left in ts->vec_sol. */
PetscErrorCode TSVSHMMAdaptStep_Private(TS ts, PetscReal t0, PetscReal DeltaT)
{
  TS_VSHMM       *vs     = (TS_VSHMM *)ts->data;
  const PetscInt  K      = (PetscInt)vs->level_end.size() - 1;
  const PetscReal budget = StepBudget(ts, DeltaT), t1 = t0 + DeltaT;
  const int       order = vs->tableau->order;

  PetscFunctionBegin;
  if (!vs->adapt_ready) PetscCall(TSVSHMMAdaptSetUp_Private(ts));
  const PetscBool later = (ts->max_time - t1 > 0.5 * DeltaT && ts->steps + 1 < ts->max_steps) ? PETSC_TRUE : PETSC_FALSE; /* a later macro step follows */
  /* the split between the terms is measured when a later macro step can use it: at the first, then
     after 1, 2, 4, 8 macro steps (a first measurement may fall in an initial transient), then every
     kRecalibrate */
  const PetscInt interval  = vs->adapt_calibrated_times >= 5 ? kRecalibrate : PetscMin(kRecalibrate, (PetscInt)1 << PetscMax(vs->adapt_calibrated_times - 1, 0));
  PetscBool      calibrate = (later && (!vs->adapt_calibrated || vs->adapt_since_calibration >= interval)) ? PETSC_TRUE : PETSC_FALSE;
  /* the levels' stable steps follow the state: estimated again with each calibration, and after a
     first macro step that had to be refined (an initial layer: a state off the slow manifold can
     have other eigenvalues than the solution a step later; the dissipative example's full field
     has spectral radius 9.1e3 at t = 0 and 1.09e4 at t = 0.1, 20% more, and with the micro step
     at 0.9 of the initial limit its comparisons ran at the limit until the next calibration).
     A first step accepted as it was tried is no layer, and the estimate (an Arnoldi run per
     level, 12% of the sparse-spectral diffusion scenes' work at 1e-2) is not made again. */
  if (calibrate || (vs->adapt_accepted == 1 && vs->adapt_rejections > 0) || RateFell(vs) || vs->rest_found || TSVSHMMBeatApproaching_Private(ts, t1)) PetscCall(UpdateStableSteps(ts));
  vs->rest_found = PETSC_FALSE;
  vs->adapt_end_rates.assign(vs->level_end.size(), 0.0);
  if (t0 != vs->adapt_tstart) PetscCall(SlowComponentsFromValues(ts, t0, vs->X0)); /* additive splits: a later state may show a slow component the first hid */
  if (vs->spectra_time == ts->ptime) {
    PetscCall(RecheckSeparation(ts));
    if (!vs->adapt_calibrated) calibrate = later;
  }
  vshmm::AdaptBounds     bounds     = Bounds(ts, DeltaT);
  PetscReal              Emin       = PETSC_MAX_REAL; /* the lowest estimate of this macro step's tries */
  PetscInt               stalled    = 0;
  PetscInt               blown      = 0;              /* tries in a row without a finite estimate */
  PetscReal              predicted  = PETSC_MAX_REAL; /* the model's error of the try after a rejection */
  PetscBool              singleRate = PETSC_FALSE;    /* the tries are the savings' limit: none (a floor above the share, below) */
  vshmm::AdaptParameters beforeSingleRate;            /* the try that found that floor */
  PetscBool              edgeFound     = PETSC_FALSE; /* a try blew up within the stable steps of this state */
  PetscBool              edgeMargin    = PETSC_FALSE; /* the micro step was bounded by a blow-up's edge (EdgeMargin()) */
  PetscInt               radiusChecks  = 0;           /* the fastest radius at the end of a try was checked (FollowRatesAtTryEnd()) */
  PetscReal              floorEstimate = 0;           /* and its estimate */

  using Try = std::pair<vshmm::AdaptParameters, PetscReal>;
  std::vector<Try> tried; /* this macro step's tries with savings and their estimates (a floor's cheapest, below) */
  for (PetscInt attempt = 0;; ++attempt) {
    vshmm::AdaptParameters &p = vs->adapt_params;
    vs->nonfinite_split       = -1;
    vs->nonfinite_time        = PETSC_MAX_REAL;
    if (attempt == 0) vs->obs_fault = -1;

    /* The macro step with the current parameters, counted as the solve's work */
    std::unique_ptr<vshmm::MesoscopicSchedule> schedule;
    vshmm::MacroStepCounts                     counts;
    const std::vector<PetscInt64>              rhs0 = vs->rhs_evaluations, lev0 = vs->level_evaluations;
    PetscCall(Schedule(ts, p, schedule));
    PetscCall(VecCopy(vs->X0, vs->Xbase));
    if (vs->rest_stages.size() != vs->K.size()) {
      vs->rest_stages.assign(vs->K.size(), nullptr);
      for (Vec &k : vs->rest_stages) PetscCall(VecDuplicate(vs->Xbase, &k));
    }
    vs->rest_track = PETSC_TRUE;
    vs->rest_h     = 0;
    PetscCall(TSVSHMMRunMacroStep_Private(ts, *schedule, t0, DeltaT, vs->Xbase, &counts));
    vs->rest_track = PETSC_FALSE;
    PetscReal xnorm;
    PetscCall(VecNorm(vs->Xbase, NORM_1, &xnorm));
    if (!std::isfinite(xnorm) && attempt + 1 < kMaxAttempts) { /* blew up: redo within the stable steps of the present state, or with every parameter finer */
      DiscardTry(vs, rhs0, lev0);
      if (vs->spectra_time != ts->ptime) {
        const PetscReal cycle = vshmm::cycleLength(p), dt = p.microStep;
        PetscCall(UpdateStableSteps(ts));
        bounds = Bounds(ts, DeltaT);
        if (p.microStep < dt || vshmm::cycleLength(p) < cycle) {
          PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g] try %" PetscInt_FMT " is not finite: within the stable steps at t = %g\n", (double)t0, (double)t1, attempt, (double)t0));
          continue;
        }
      }
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g] try %" PetscInt_FMT " is not finite: every parameter finer\n", (double)t0, (double)t1, attempt));
      edgeFound = PETSC_TRUE;
      if (!bounds.fixedMicroStep) p.microStep *= 0.5;
      if (!bounds.fixedRatios)
        for (double &r : p.ratios) r = 1.0 + (r - 1.0) / 4;
      continue;
    }

    /* at the end of the first kMaxRadiusChecks tries of a macro step (a fast rate that grew within
       it; a retry's end may be past a fold where the first try's was not: the van der Pol
       oscillator's try at time ratio 5.6, and a retry that coarsened the ratio from 12 to 24,
       ended on the repelling branch) */
    if (radiusChecks < kMaxRadiusChecks && attempt + 1 < kMaxAttempts && PhaseSavings(vs, p)) {
      PetscBool redo;
      PetscCall(NoteFastQuantities(ts, t1, bounds, &redo));
      if (redo) {
        DiscardTry(vs, rhs0, lev0);
        bounds = Bounds(ts, DeltaT);
        continue;
      }
    }
    vs->adapt_try_speed = 0;
    if (radiusChecks < kMaxRadiusChecks && attempt + 1 < kMaxAttempts) {
      PetscBool redo;
      radiusChecks++;
      PetscCall(FollowRatesAtTryEnd(ts, t1, &redo));
      if (redo) {
        DiscardTry(vs, rhs0, lev0);
        bounds = Bounds(ts, DeltaT);
        continue;
      }
    }
    if (edgeFound && !edgeMargin && !bounds.fixedMicroStep && attempt + 1 < kMaxAttempts) {
      /* the first try to stay finite after tries that blew up within the stable steps of this
         state (estimated here already: the fast rates grow within the step, as in Robertson's
         kinetics, whose intermediate species has rate 0 at the initial state and 1,750 two time
         units later): its micro step lies between half the stability limit of somewhere in the
         step and that limit, where a decaying fast mode is hardly damped (|R| near 1) and its
         error goes unmeasured (no comparison can coarsen it; Robertson's first step took 0.48 tol
         against an estimate of 0.08, its fast species negative at the end). The step is redone
         with the stable fraction of that micro step as the bound (StableFraction()). */
      edgeMargin = PETSC_TRUE;
      PetscCall(EdgeMargin(ts, t0, t1));
      DiscardTry(vs, rhs0, lev0);
      bounds = Bounds(ts, DeltaT);
      continue;
    }

    /* Its error, and (when calibrating, or before the first refinement) the split between the terms */
    vshmm::AdaptParameters q;
    PetscReal              d;
    if (vs->adapt_model.c.size() != (size_t)K || !(vs->adapt_model.total(p) > 0)) vs->adapt_model = vshmm::ErrorModel::equalShares(p, order, 1.0, Saturations(ts, p));
    /* a single-rate step (no savings) at the largest micro step the bounds allow, whose last step
       was far below its share: nothing is left to choose and a Runge-Kutta method's error does not
       jump by orders of magnitude between steps; the model's prediction stands in for the
       comparison (with the micro step at 3/4, 1.33 times the step's work). Below kNegligibleEstimate
       always; below 1 / kUncomparedBelow of the share at most kMaxUncompared steps in a row (then
       one is compared: the sparse-spectral advection scenes, not separated, single-rate at their
       stability limit with estimates of 0.5-2% of the share, spent two thirds of their work on
       comparisons) */
    const bool modelled = attempt == 0 && !calibrate && vs->adapt_model.total(p) > 0;
    const bool small    = vs->adapt_last_ratio < kNegligibleEstimate || (vs->adapt_last_ratio < 1.0 / kUncomparedBelow && vs->adapt_uncompared < kMaxUncompared);
    bool       pinned   = modelled && small && !vs->adapt_off_manifold && p.microStep >= 0.999 * bounds.maxMicroStep;
    for (double r : p.ratios) pinned = pinned && r == 1.0;
    const bool steady = modelled && !vs->adapt_off_manifold && SteadyStep(vs, p, bounds);
    if (vs->adapt_off_manifold && modelled)
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: the fast variables ended it off their slow manifold (the field would move the state by more than %g times its norm and change in a macro step): compared\n", (double)t0, (double)t1, (double)kOffManifold));
    if (steady && !pinned)
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: at the cycle and micro step bounds, the last two estimates %g and %g of their shares: no comparison\n", (double)t0, (double)t1, (double)vs->adapt_prev_ratio, (double)vs->adapt_last_ratio));
    if (pinned || steady) d = -1;
    else PetscCall(Compare(ts, p, t0, DeltaT, (modelled && vs->adapt_calibrated && !vs->adapt_off_manifold) ? PETSC_TRUE : PETSC_FALSE, attempt == 0 ? PETSC_TRUE : PETSC_FALSE, &q, &d));
    PetscReal E = d < 0 ? vs->adapt_model.total(p) : Estimate(vs->adapt_model, p, q, d);
    if (calibrate && FasterLevelsDecay(vs) && attempt == 0 && vs->adapt_calibrated_times >= kTrustedCalibrations && d > 0 && std::isfinite(E) && E > 0) {
      /* a scheduled measurement of the split that the model has just predicted: it predicted this
         step's estimate within kMissFactor (from the last step's, with this step's parameters), so
         the split stands and is not measured again until the next one is due. Only where every
         faster level decays: an oscillating level's estimates scatter by about 3x with its phase
         (docs/accuracy.md section 1), within the factor by chance (the oscillators at 1e-3, t = 4,
         took 4x the work with the split unmeasured). */
      const PetscReal prediction = vs->adapt_model.total(p);
      if (E < kMissFactor * prediction && prediction < kMissFactor * E) {
        PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: the model predicted the estimate (%g, predicted %g): no calibration\n", (double)t0, (double)t1, (double)E, (double)prediction));
        calibrate = PETSC_FALSE;
        vs->adapt_calibrated_times++;
        vs->adapt_since_calibration = -1; /* counted up with this step */
        vs->adapt_postponed         = PETSC_FALSE;
      }
    }
    if (calibrate && attempt == 0 && vs->adapt_calibrated && FasterLevelsDecay(vs) && d > 0 && std::isfinite(E) && E < budget / kUncomparedBelow && bounds.maxCycle > 0 && vshmm::cycleLength(p) >= 0.999 * bounds.maxCycle &&
        (bounds.fixedMicroStep || p.microStep >= 0.999 * bounds.maxMicroStep)) {
      /* a scheduled measurement of the split at a step far below its share that nothing can
         coarsen (cycle and micro step at their bounds: the work is the cycle's, and moving error
         between the time ratios does not change it): the split would choose nothing, and is not
         measured until the next one is due (the six-scale chain at 1e-1 spent 42% of its work on
         such measurements, at estimates of 0.5% of the share) */
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: estimate %g far below its share %g with nothing to coarsen: no calibration\n", (double)t0, (double)t1, (double)E, (double)budget));
      calibrate = PETSC_FALSE;
      vs->adapt_calibrated_times++;
      vs->adapt_since_calibration = -1; /* counted up with this step */
      vs->adapt_postponed         = PETSC_FALSE;
    }
    if (calibrate && attempt == 0 && vs->adapt_calibrated && !vs->adapt_postponed && FasterLevelsDecay(vs) && d > 0 && std::isfinite(E) && E < budget / kPostponeBelow) {
      /* a scheduled measurement of the split at a step far below its share: the parameters are
         about to coarsen (by up to kMaxCheaper in work), and the measurement, one run per
         parameter at this step's cost, is made at the next step's cheaper parameters instead
         (once: it is still due there) */
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g]: estimate %g far below its share %g: the calibration waits for the next step\n", (double)t0, (double)t1, (double)E, (double)budget));
      calibrate           = PETSC_FALSE;
      vs->adapt_postponed = PETSC_TRUE;
    }
    if (calibrate || (E > budget && !vs->adapt_calibrated) || (attempt > 0 && (E > kFloorAccept * budget || (E > budget && E > kMissFactor * predicted)))) {
      PetscCall(Calibrate(ts, p, t0, DeltaT, bounds, (!calibrate && attempt > 0) ? PETSC_TRUE : PETSC_FALSE));
      calibrate = PETSC_FALSE;
      E         = Estimate(vs->adapt_model, p, q, d);
      /* a micro step term the calibration measured from the finer side (at its stability bound) and
         counted: measured directly at this step, where the comparison could not change it; its
         effect on the comparison, read through the model (whose micro step term falls with the
         savings), can be far smaller (z' = 1000 x (x - z) after its scales separated: 0.009 against
         a term of 1.5 shares measured, and 1.66 tol taken in the step) */
      if (vs->finer_term > 0 && std::isfinite(E)) E = PetscMax(E, vs->finer_term);
    }
    PetscReal Elayer = -1; /* the layer's estimate from two comparisons (LayerEstimate()), where made */
    if (vs->adapt_accepted == 0 && FasterLevelsDecay(vs) && d > 0 && std::isfinite(d) && E > budget && E <= kLayerFitWindow * budget) PetscCall(LayerEstimate(ts, p, q, d, t0, DeltaT, &Elayer));
    if (std::isfinite(E) && E > 0) {
      vs->adapt_model.scale(E / vs->adapt_model.total(p));
      vs->adapt_model.floorShares(p, kMinShare);
    } else if (E == 0 && vs->adapt_model.total(p) > 0) {
      /* a comparison that changed nothing (a state at rest, observables that do not move): the model
         at kZeroEstimate of the share, so that the parameters coarsen; it stood at its unmeasured
         equal shares of a whole tolerance, and each such step refined them (a solution at rest
         from 0 took 48,828 evaluations to t = 1 at 1e-3, 1,056 now) */
      vs->adapt_model.scale(kZeroEstimate * budget / vs->adapt_model.total(p));
    }
    const PetscReal Echoice = E > 0 ? E : vs->adapt_model.total(p); /* the present error the choice starts from */

    /* The parameters for the next try or the next macro step: the work may fall by
       sqrt(target / E) (at most kMaxCheaper) and rise by kMaxDearer per choice */
    vshmm::AdaptParameters next   = p;
    const PetscReal        target = kSafety * budget;
    /* the least-work parameters of the present error Enow under the model m (moving error between
       the terms, as the calibration measured them), and from there towards the target, with the
       work limited */
    /* The first macro step accepted at its first try, every faster level decaying: its parameters
       were a guess from the spectra, and its estimate is the first measurement of them; the work
       may fall by the whole target / E (at most kMaxCheaper), not its square root, which damps the
       noise between consecutive measured choices (kept there: with the whole factor on every step
       the dissipative example at eps = 1e-4, 1e-3 ended 6.59 tol off, docs/accuracy.md section 9).
       A run of four macro steps spent half its work on its first two (the diffreact scene of
       docs/spectral.md: 15, 11, 7 and 7 micro cycles; 15, 8, 6, 6 now). */
    const PetscBool firstGuess = (vs->adapt_accepted == 0 && attempt == 0 && FasterLevelsDecay(vs)) ? PETSC_TRUE : PETSC_FALSE;
    const auto      Choose     = [&](const vshmm::ErrorModel &m, PetscReal Enow, PetscReal maxDearer) {
      const vshmm::AdaptParameters same     = vshmm::chooseParameters(p, m, Enow, bounds);
      vshmm::AdaptParameters       chosen   = vshmm::chooseParameters(p, m, target, bounds);
      const PetscReal              toTarget = PetscMax(1.0, target / PetscMax(Enow, PETSC_SMALL));
      vshmm::limitWorkChange(chosen, same, PetscMin(kMaxCheaper, firstGuess ? toTarget : PetscSqrtReal(toTarget)), maxDearer);
      return chosen;
    };
    if (std::isfinite(E)) next = Choose(vs->adapt_model, Echoice, kMaxDearer);
    PetscBool refinable = vs->adapt_model.total(next) < 0.9 * vs->adapt_model.total(p) ? PETSC_TRUE : PETSC_FALSE; /* the model expects a clearly lower error */
    if (!std::isfinite(E) || (E > kFloorAccept * budget && !refinable)) {                                          /* no estimate, or far off and the model is stuck: every parameter finer */
      next = p;
      if (!bounds.fixedMicroStep) next.microStep *= 0.5;
      if (!bounds.fixedRatios)
        for (double &r : next.ratios) r = 1.0 + (r - 1.0) / 4;
      refinable = (next.microStep < p.microStep || vshmm::cycleLength(next) < vshmm::cycleLength(p)) ? PETSC_TRUE : PETSC_FALSE;
    }
    LimitToStableSteps(ts, next);
    const std::string ratios = RatiosText(p);
    PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g] try %" PetscInt_FMT ": dt %g, time ratios %s, cycle %g, %" PetscInt64_FMT " cycles; estimate %g of its share %g\n", (double)t0, (double)t1, attempt, (double)p.microStep, ratios.c_str(), (double)vshmm::cycleLength(p),
                        counts.cycles, (double)E, (double)budget));
    /* a floor: twice, finer parameters did not lower the estimate clearly below the lowest of
       this macro step's tries (an estimate that rose with a refinement and fell back is noise,
       not progress), near the share (or the savings cannot be taken back any further); far above
       it, the savings go on falling (their limit, no savings, is a single-rate Runge-Kutta method
       with the micro step) */
    stalled           = (attempt > 0 && E > kFloorFactor * Emin) ? stalled + 1 : 0;
    PetscBool savings = PETSC_FALSE; /* savings the choice may still take back */
    for (double r : p.ratios) savings = (r > 1.0 + 1e-6 && !bounds.fixedRatios) ? PETSC_TRUE : savings;
    const PetscBool floor     = (stalled >= 2 && (E <= kFloorAccept * budget || !savings)) ? PETSC_TRUE : PETSC_FALSE;
    Emin                      = PetscMin(Emin, E);
    const PetscReal Ecompared = E; /* the comparison's estimate, the measure of every later step */
    if (savings && !singleRate && std::isfinite(E)) tried.emplace_back(p, E);
    if (Elayer >= 0 && Elayer <= budget) {
      /* the layer's own estimate accepts the step, and the next step's parameters are chosen from
         it as from any step's estimate (the model scaled by it), not from the comparison's (2.5-4
         times the layer's error, which would refine them for a layer that is over): they kept this
         step's parameters before, and the dissipative example's second macro step at eps = 1e-2,
         tol 1e-2 took 146 micro cycles with an estimate of a twelfth of its share (64 now) */
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g] try %" PetscInt_FMT " accepted on the layer's estimate %g (the comparison's %g)\n", (double)t0, (double)t1, attempt, (double)Elayer, (double)E));
      E    = Elayer;
      next = p;
      if (Elayer > 0) {
        vshmm::ErrorModel layer = vs->adapt_model;
        layer.scale(Elayer / layer.total(p));
        next = Choose(layer, Elayer, kMaxDearer);
        LimitToStableSteps(ts, next);
      }
    }
    blown = std::isfinite(E) ? 0 : blown + 1;
    if (std::isfinite(xnorm) && (blown >= kMaxBlownTries || (!std::isfinite(E) && !(E > budget && refinable && !floor && attempt + 1 < kMaxAttempts)))) {
      /* the step ran, but no comparison of it stayed finite (in kMaxBlownTries tries in a row,
         each with every parameter finer, or in the last try): no estimate, and accepting the step
         would be a guess (y' = y^2 past its blow-up at t = 1 was accepted so, with a warning, and
         failed a step later). A step whose own result is not finite goes on to the split check
         instead, which names the split. */
      PetscCall(VecCopy(vs->X0, ts->vec_sol));
      DiscardTry(vs, rhs0, lev0);
      ts->reason      = TS_DIVERGED_STEP_REJECTED;
      char cause[320] = "a comparison run blew up: the solution may grow without bound there, or the savings are unstable; or an observable was not finite";
      if (vs->obs_fault >= 0) /* the observables function's, found at a finite state (TSVSHMMObservables_Private()) */
        PetscCall(PetscSNPrintf(cause, sizeof(cause), "the observables function returned %s for observable %d (of %d) at t = %g, for a state whose entries are all finite: it must return finite values wherever the solution is finite", vs->obs_fault_nan ? "NaN" : "Inf",
                                (int)vs->obs_fault, (int)vs->nobservables, (double)vs->obs_fault_time));
      PetscCheck(!ts->errorifstepfailed, PetscObjectComm((PetscObject)ts), PETSC_ERR_NOT_CONVERGED, "TSVSHMM (-ts_vshmm_adapt): no finite error estimate for the macro step from t = %g to %g after %" PetscInt_FMT " tries: the comparisons of the last %" PetscInt_FMT " gave no finite difference, down to the micro step %g (%s); the solution was left at t = %g (use -ts_error_if_step_fails false to stop with TS_DIVERGED_STEP_REJECTED instead)", (double)t0, (double)t1, attempt + 1, blown,
                 (double)p.microStep, cause, (double)t0);
      PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM (-ts_vshmm_adapt): no finite error estimate for the macro step from t = %g to %g after %" PetscInt_FMT " tries (the comparisons of the last %" PetscInt_FMT " gave no finite difference: %s); the solve stops with TS_DIVERGED_STEP_REJECTED at t = %g\n", (double)t0, (double)t1, attempt + 1, blown, cause, (double)t0));
      PetscFunctionReturn(0);
    }
    /* far out of reach: three tries with savings, each refined, none within kOutOfReach shares (the
       oscillators at 1e-9, whose I1 swings with the fast phase by 2e6 tolerances: estimates of
       4e4-5e5 shares while the savings halved and the work doubled each try, a run without end) */
    const bool farOut = savings && !singleRate && attempt >= 2 && std::isfinite(E) && Emin > kOutOfReach * budget; /* (a finite estimate: comparisons that blew up have their own path) */
    if ((floor || farOut) && savings && E > budget && !singleRate && attempt + 1 < kMaxAttempts) {
      /* a floor above the share while savings are left: their limit, none (every time ratio 1, the
         same micro step: a single-rate Runge-Kutta step of the whole field), is tried where it
         costs at most kMaxDearer times this try (vshmm::workRate(): the levels' steps a micro cycle
         takes). Where the tolerance asks for more than the separation gives (effects of the order
         of the scale ratio in the slow values: the oscillators at eps = 1e-2, tol 1e-3) no savings
         meet it, and accepting the floor leaves an error the estimates do not fall below. Where
         the savings are large (the oscillators at eps = 1e-3: products of ratios of thousands)
         the single-rate step is far too dear and the floor stands. Far out of reach (above) it is
         tried where it costs up to kOutOfReachDearer times this try: the oscillators at 1e-9 went
         single-rate at 5.5 times the work of their third try, and ended within 0.11 tol in 4 s;
         without that bound the dissipative example at eps = 1e-4, 1e-3 (first-step tries above 100
         shares in an initial layer, single-rate steps far dearer) took 540 times the work. */
      vshmm::AdaptParameters    single = p;
      const std::vector<double> cost(vs->level_end.begin(), vs->level_end.end());
      for (double &r : single.ratios) r = 1.0;
      const PetscReal dearer = vshmm::workRate(single, cost) / vshmm::workRate(p, cost);
      if (dearer <= kMaxDearer || (farOut && dearer <= kOutOfReachDearer)) {
        PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g] try %" PetscInt_FMT ": the estimate %g does not fall below its share %g with the savings: tried without them (single-rate, %g times the work)\n", (double)t0, (double)t1, attempt, (double)E, (double)budget, (double)dearer));
        PetscCall(MonitorTry(ts, "rejected (a floor: tried without savings)", t0, DeltaT, attempt, p, counts.cycles, E, budget));
        DiscardTry(vs, rhs0, lev0);
        beforeSingleRate = p;
        floorEstimate    = E;
        singleRate       = PETSC_TRUE;
        stalled          = 0;
        predicted        = PETSC_MAX_REAL;
        p                = single;
        continue;
      }
    }
    /* below the micro step at which an earlier step found a floor without savings left, finer micro
       steps are not tried again: the estimate is noise there (a chaotic fast level: two runs that
       differ in the micro step diverge within the step, and a slow variable driven by a Lorenz
       system at eps = 1e-3, tol 1e-3, refined the micro step from 1.4e-4 to 3e-8 over 20 steps,
       549 million evaluations, each step's estimate going up and down by 10x) */
    const PetscBool pastFloor = (!savings && vs->adapt_floor_dt > 0 && next.microStep < kFloorFactor * vs->adapt_floor_dt) ? PETSC_TRUE : PETSC_FALSE;
    if (E > budget && refinable && !floor && !pastFloor && attempt + 1 < kMaxAttempts) { /* redo with finer parameters */
      PetscCall(MonitorTry(ts, "rejected", t0, DeltaT, attempt, p, counts.cycles, E, budget));
      DiscardTry(vs, rhs0, lev0);
      if (vs->adapt_accepted > 0) PetscCall(KeepComparableRatios(ts, p, next));
      predicted = vs->adapt_model.total(next);
      p         = next;
      continue;
    }
    if (!bounds.fixedMicroStep && attempt + 1 < kMaxAttempts) { /* a try about to be accepted: at a spurious rest of its micro steps? */
      PetscBool spurious;
      PetscCall(SpuriousRest(ts, t0, t1, &spurious));
      if (spurious) {
        PetscCall(MonitorTry(ts, "rejected (a spurious rest of the micro steps)", t0, DeltaT, attempt, p, counts.cycles, E, budget));
        DiscardTry(vs, rhs0, lev0);
        vs->rest_found = PETSC_TRUE;
        p.microStep *= 0.5;
        predicted = PETSC_MAX_REAL;
        continue;
      }
    }
    if (E > budget) {
      /* the next macro step starts from the parameters accepted here (the refinement that did
         not meet the share is not carried on: past an initial layer the estimate falls again) */
      next                  = p;
      const PetscBool noise = (floor && savings) ? PETSC_TRUE : PETSC_FALSE;
      if (noise && (vs->adapt_accepted > 0 || !FasterLevelsDecay(vs))) {
        /* finer parameters did not lower the estimate: the next step starts from the cheapest of
           this step's tries whose estimate was within the floor's band, not from the finest (the
           oscillators to t = 8 at 1e-1 found such floors from t = 4 on and carried each
           refinement into the next steps: cycles 14-40 times shorter, 3.3 million evaluations
           where the sweep's configurations with the same error take 48,000). Not after a first
           macro step whose faster levels only decay: its floor is an initial layer, over a step
           later (the five-scale chain's second step from the layer's first try ended 0.44 tol
           off, 0.26 from the layer's own) */
        const std::vector<double> cost(vs->level_end.begin(), vs->level_end.end());
        for (const auto &t : tried)
          if (t.second <= E / kFloorFactor && vshmm::workRate(t.first, cost) < vshmm::workRate(next, cost)) next = t.first;
      }
      if (floor && !savings) vs->adapt_floor_dt = p.microStep;
      const char *why = noise        ? "finer parameters do not lower the estimate"
                        : floor      ? "finer micro steps do not lower the estimate, and the savings factors are set or none are left"
                        : pastFloor  ? "finer micro steps did not lower the estimate of an earlier step (a floor), and none are tried below it"
                        : !refinable ? "the error model puts the error in parameters that cannot be refined (user-set parameters or stability bounds)"
                                     : "too many tries";
      PetscCall(PetscInfo(ts, "Adapt: macro step [%g, %g] accepted with estimate %g above its share %g: %s\n", (double)t0, (double)t1, (double)E, (double)budget, why));
      if (!vs->floor_warned && E > kWarn * budget) {
        vs->floor_warned = PETSC_TRUE;
        PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): the macro step [%g, %g] is accepted with an error estimate of %g times its share of the tolerance (%s). %s The run goes on; the estimates are in the statistics (TSVSHMMGetStatistics(), -ts_view). This warning is given once per solve.\n", (double)t0, (double)t1, (double)(E / budget), why, noise ? "The sampled values carry a part VSHMM does not resolve (typically fast fluctuations, or an initial layer: the faster variables start off their slow manifold, and in the first macro steps the savings factors change the slow values by an amount that does not fall with them): a tolerance this far below -ts_rtol/-ts_atol is out of reach for VSHMM here." : "Loosen the tolerance, or leave the micro step and savings factors to -ts_vshmm_adapt, or use a single-rate TS type."));
      }
    }
    PetscCall(MonitorTry(ts, E > budget ? "accepted above its share" : "accepted", t0, DeltaT, attempt, p, counts.cycles, E, budget));
    PetscCall(VecCopy(vs->Xbase, ts->vec_sol));
    TSVSHMMAddCounts_Private(vs, counts);
    vs->error_estimate = E;
    vs->error_estimate_total += E;
    vs->error_estimate_squares += E * E;
    vs->adapt_accepted++;
    if (vs->slow_mask && vs->step_slow && d > 0) vs->slow_steps++;
    if (vs->observables && std::isfinite(E) && d > 0 && vs->step_signed.size() == (size_t)vs->nobservables) { /* the signed error, for the budget's gamma */
      vs->adapt_signed.resize(vs->nobservables, 0.0);
      for (PetscInt i = 0; i < vs->nobservables; ++i) vs->adapt_signed[i] += vs->step_signed[i] * E / d;
    }
    if (vs->adapt_global) PetscCall(CarryComparison(ts, p, t0, DeltaT, E, d));
    PetscCall(GrowthProbeAccepted(ts, p, t0, DeltaT));
    {
      PetscReal signedRms = -1;
      if (!vs->adapt_signed.empty()) {
        signedRms = 0;
        for (PetscReal x : vs->adapt_signed) signedRms += x * x;
        signedRms = PetscSqrtReal(signedRms / (PetscReal)vs->adapt_signed.size());
      }
      PetscCall(PetscInfo(ts, "Adapt: the accepted steps' estimates at t = %g: sum %g, root of the sum of squares %g, signed sum %g\n", (double)t1, (double)vs->error_estimate_total, (double)PetscSqrtReal(vs->error_estimate_squares), (double)signedRms));
    }
    if (vs->lag_next) {
      /* the comparison's end state carried into the next step's (ComparisonStart()); a step without
         a comparison keeps the last one, a comparison that blew up drops it. Not from a run's first
         macro step: it holds the initial layer, and its comparison's faster variables end off their
         manifold by the layer's own transient, not by a lag (carried, it charged the second step
         with it: the chains 6-19% dearer at the same errors) */
      if (d >= 0 && std::isfinite(d) && vs->lag_next_valid && vs->adapt_accepted > 1) {
        std::swap(vs->lag_carried, vs->lag_next);
        vs->lag_p     = vs->lag_next_p;
        vs->lag_q     = vs->lag_next_q;
        vs->lag_valid = PETSC_TRUE;
      } else if (!(d < 0)) vs->lag_valid = PETSC_FALSE;
      vs->lag_next_valid = PETSC_FALSE;
    }
    vs->adapt_since_calibration++;
    vs->savings_used           = vshmm::savingsFromTimeRatios(p.ratios); /* what this step used (for view and getters) */
    vs->adapt_used             = p;
    vs->adapt_single_rate_step = PetscMax(p.microStep, SingleRateStep(ts, DeltaT)); /* a single-rate run's step: at least the micro step */
    vs->beat_slowed.resize(p.ratios.size() + 1, 1.0);                               /* how far the savings have slowed each level's oscillations (a beat found later lost its phase: TSVSHMMAdaptBeats_Private()) */
    PetscReal slowed = 1;
    for (size_t L = 1; L <= p.ratios.size(); ++L) {
      slowed *= p.ratios[L - 1];
      vs->beat_slowed[L] = PetscMax(vs->beat_slowed[L], slowed);
    }
    vs->adapt_end = t1;
    PetscCall(VecNorm(ts->vec_sol, NORM_1, &vs->adapt_end_norm));
    vs->adapt_end_speed  = vs->adapt_try_speed;
    vs->adapt_prev_ratio = vs->adapt_last_ratio;
    /* the rules that leave a later step's comparison out (SteadyStep(), a pinned step) compare estimates of one kind: the comparison's */
    vs->adapt_last_ratio = std::isfinite(Ecompared) && Ecompared >= 0 ? Ecompared / budget : PETSC_MAX_REAL;
    vs->adapt_uncompared = d < 0 ? vs->adapt_uncompared + 1 : 0;
    if (d < 0) vs->adapt_uncompared_total++;
    if (singleRate) {
      /* accepted without savings: where a faster level oscillates its phases now follow the true
         dynamics, and savings taken up again would shift them by an amount of the order of the
         scale ratio at once (the floor seen): none for the rest of the solve. Fast variables that
         decay onto the slow manifold keep no such memory; the next step starts from the savings
         that found the floor (an initial layer may be what set it). */
      if (FasterLevelsDecay(vs)) next = beforeSingleRate;
      else {
        vs->adapt_no_savings.assign(next.ratios.size(), PETSC_TRUE);
        for (double &r : next.ratios) r = 1.0;
        if (vs->adapt_single_rate_from < 0) { /* the first such step of the solve (the savings are gone for the rest): said once */
          vs->adapt_single_rate_from = t0;
          PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM warning (-ts_vshmm_adapt): the tolerance (rtol %g, atol %g%s) is out of reach with savings: in the macro step [%g, %g] the error estimate stayed at %g times its share with finer savings factors and micro steps, and fell to %g without savings. The rest of the solve takes none (one Runge-Kutta step of the whole field per micro step, with VSHMM's error estimates on top). The scales are not separated enough for VSHMM at this tolerance (their ratio shows in the slow values); a single-rate TS type (-ts_type rk -ts_adapt_type basic) does the same work without the estimates, or loosen the tolerance. This warning is given once per solve.\n",
                                        (double)ts->rtol, (double)ts->atol, (ts->vatol || ts->vrtol) && !vs->observables ? "; the vectors of TSSetTolerances() on the components" : "", (double)t0, (double)t1, (double)(floorEstimate / budget), (double)(E / budget)));
        }
      }
    }
    SnapNegligibleSavings(vs, next, bounds); /* after an accepted step only: the retries of an initial layer take the savings down on their way to a start */
    if (!vs->adapt_candidate.empty() && vs->adapt_verified.empty()) {
      PetscCall(VerifySavings(ts, p, t0, DeltaT));
      if (TSVSHMMSavingsAdmitted_Private(vs)) {
        next.ratios = vs->adapt_verified;
        LimitToStableSteps(ts, next);
        vshmm::fitCycle(next, Bounds(ts, DeltaT).maxCycle, false, true);
      }
    }
    p = next;
    break;
  }
  PetscFunctionReturn(0);
}
