// Private data of a TSVSHMM (ts->data) and what the package shares with the type.
#pragma once

#include <petscvshmm.h>
#include "vshmmvalid.hpp"
#include <petsc/private/tsimpl.h>

#if defined(PETSC_USE_COMPLEX)
  #error "petsc-vshmm needs PETSc built with real scalars (Debian: petsc-dev, PETSC_ARCH x86_64-linux-gnu-real)"
#endif

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "adapt.hpp"
#include "kernel.hpp"
#include "rk.hpp"
#include "schedule.hpp"
#include "stability.hpp"

// One RHS split, with what it takes to add its output into a level's field. A scale is one split
// or a group of them (-ts_vshmm_splits a+b,c).
struct VSHMMSplit {
  std::string name;
  TS          subts    = nullptr;     // the split's sub-TS (owned by the TS's split list)
  IS          is       = nullptr;     // its components (owned by the split list)
  Vec         F        = nullptr;     // split-sized output of the split function
  PetscBool   additive = PETSC_FALSE; // IS = every locally owned component, in order, on every rank
  PetscBool   local    = PETSC_FALSE; // IS = a contiguous run of locally owned components on every rank
  PetscInt    offset   = 0;           // start of that run in the local array (local only)
  VecScatter  scatter  = nullptr;     // general IS: adds F into the full vector
};

struct TS_VSHMM {
  // Parameters (settable at any time; checked at set-up)
  PetscReal                 micro_dt = 0.0; // 0: DeltaT / kDefaultMicroStepsPerMacroStep
  std::vector<PetscReal>    savings;        // empty: all 1
  std::vector<PetscReal>    separations;    // per level pair, as the application knows them (TSVSHMMSetScaleSeparations()); empty: from the spectral radii
  std::vector<PetscInt>     subintervals;   // empty: all 1
  TSVSHMMKernelType         kernel_type  = TSVSHMM_KERNEL_COSINE;
  PetscInt                  kernel_order = PETSC_DEFAULT; // PETSC_DEFAULT: the kernel's own
  std::string               rk_type      = TSRK4;
  std::vector<std::string>  split_order;                                                // one entry per scale, "a" or "a+b"; empty: creation order
  std::vector<std::string>  split_order_out;                                            // for TSVSHMMGetSplitOrder()
  PetscBool                 check_stability    = PETSC_TRUE;                            // at set-up
  PetscBool                 check_splits       = PETSC_TRUE;                            // the splits' sum against the RHS function, at set-up
  PetscReal                 splits_difference  = -1;                                    // its result: |sum of the splits - RHS function| / largest split output (-1: not checked)
  PetscInt                  stability_interval = 0;                                     // also every that many macro steps (0: never)
  std::vector<const char *> split_order_c;                                              // for TSVSHMMGetSplitOrder()
  PetscBool                 adapt                                        = PETSC_FALSE; // choose the parameters not set from the TS tolerances
  TSVSHMMSeparationCheck    check_separation                             = TSVSHMM_SEPARATION_WARN;
  PetscInt                  nobservables                                 = 0; // 0: the whole state in the TS's weighted norm
  PetscErrorCode (*observables)(TS, PetscReal, Vec, PetscReal[], void *) = nullptr;
  void       *observables_ctx                                            = nullptr;
  PetscBool   adapt_slow_components                                      = PETSC_TRUE;  // with observables, the components only the slowest level's splits write are controlled too
  PetscBool   adapt_global                                               = PETSC_FALSE; // carry a comparison through the run: an estimate of the global error (TSVSHMMSetAdaptGlobalEstimate())
  PetscViewer warnings                                                   = nullptr;     // where the warnings go (NULL: PETSC_STDERR)
  PetscBool   warnings_none                                              = PETSC_FALSE; // no warnings at all (TSVSHMMSetWarningsViewer(ts, NULL))

  // Set-up state
  std::vector<VSHMMSplit>                    splits;    // in scale order
  std::vector<PetscInt>                      level_end; // level l evaluates splits [0, level_end[l])
  std::unique_ptr<vshmm::Tableau>            tableau;
  std::unique_ptr<vshmm::Kernel>             kernel;
  std::unique_ptr<vshmm::MesoscopicSchedule> schedule;     // for the current micro step; made at the first step
  std::vector<PetscReal>                     savings_used; // savings with defaults filled in
  std::vector<PetscInt>                      subintervals_used;
  Vec                                        Y = nullptr;  // stage state
  std::vector<Vec>                           K;            // stage derivatives
  Vec                                        X0 = nullptr; // previous sampled state (interpolation, rejection)
  std::vector<PetscLogEvent>                 level_events;

  // What each level's field looks like near the state (stability and separation checks, adapt)
  std::vector<PetscReal>                         level_radius;                    // spectral radius estimate of the Jacobian of G_l
  std::vector<PetscReal>                         level_max_step;                  // largest stable step of the inner RK for its limiting modes (inf: none)
  std::vector<std::complex<double>>              level_worst;                     // the mode that sets it
  std::vector<std::vector<std::complex<double>>> level_limiting;                  // decaying or oscillating Ritz values
  std::vector<PetscReal>                         level_growth;                    // the largest real part of each level's Ritz values (growing modes included)
  std::vector<PetscReal>                         level_slowest;                   // smallest |Ritz value| of the block of the level's own components (0: not estimated)
  PetscReal                                      fastest_share     = 1;           // the fastest level's part of the state (TSVSHMMLevelOwnRates_Private(); 1: not estimated)
  PetscReal                                      fastest_drive     = 0;           // how far the slower levels' fields move the state over the run per relative amplitude error of the fastest level's oscillation (over ||X||; 0: not estimated)
  PetscBool                                      fastest_nonlinear = PETSC_FALSE; // its plane's Jacobian differs with the phase (FastestLevelPlane()): judged by fastest_mean_mode
  std::complex<double>                           fastest_mean_mode = 0;           // the eigenvalue of the mean of the plane's Jacobian over four phases
  PetscReal                                      fastest_own_phase = 0;           // the largest slowest own rate of its own components at three other phases (nonlinear, component splits)
  PetscReal              fastest_restore = 0;   // how fast the fastest level's oscillation restores its amplitude: minus half its Jacobian's trace on the oscillation's plane, averaged over four phases (FastestLevelDrive(); 0: none, or not estimated)
  std::vector<Vec>       fastest_phase;         // the slower levels' field at four phases of the fastest level's oscillation less its phase average (FastestLevelDrive(); empty: not estimated)
  PetscReal              unaveraged        = 0; // -ts_vshmm_adapt: the weighted error of a macro step that leaves that phase-dependent part unaveraged (1 = the tolerance; 0: none)
  PetscReal              unaveraged_omega  = 0; // and the slowest frequency of the fastest level's limiting oscillations
  PetscReal              unaveraged_max    = 0; // the largest unaveraged of the solve (the relative phases of a band of fast modes change it)
  PetscBool              fastest_phase_now = PETSC_FALSE; // fastest_phase is of the present spectra
  std::vector<PetscReal> beat_omega;                      // the beats of the faster levels' own oscillations probed at the present spectra (TSVSHMMLevelBeats_Private(); vshmm::beatFrequencies())
  std::vector<PetscInt>  beat_level;                      // and the level of each
  std::vector<Vec>       beat_phase;                      // per beat, the slower levels' field averaged over the common phase at four relative phases of the beat, less their mean
  std::vector<PetscReal> beat_bound;                      // -ts_vshmm_adapt, per level: the slowest beat of the solve whose relative phase, held until the slower levels forget it, moves the observables by more than kUnaveragedShare (0: none)
  std::vector<PetscReal> beat_effect;                     // and that measure (1 = the tolerance)
  PetscBool              beat_warned = PETSC_FALSE;       // told of it in this solve
  struct BeatWatch {
    PetscReal r = 0, t = 0, r_before = 0, t_before = 0;
  };
  std::vector<BeatWatch> beat_watch;  // -ts_vshmm_adapt, per level: the slowest difference of its own fast frequencies that is no beat yet, as r = 10 g / the slower of the pair (a beat below 1; 0: none), at the last spectra (t) and the ones before
  std::vector<PetscReal> beat_slowed; // -ts_vshmm_adapt, per level L: the largest product r_0 ... r_{L-1} of the solve's accepted macro steps (how far savings have slowed level L's oscillations)
  PetscBool              beats_checked      = PETSC_FALSE;    // the separation check of fixed savings looked for beats (once, at set-up)
  PetscBool              unaveraged_unknown = PETSC_FALSE;    // the fastest level oscillates, but its oscillation had no amplitude to measure unaveraged with (a state on its slow manifold, or at rest)
  std::vector<PetscReal> level_time_rate;                     // per level l >= 1: how fast its own splits' explicit time dependence moves, ||dF_l/dt|| / (rho_l ||X||) (0: none or not estimated)
  std::vector<PetscReal> level_time_rate_max;                 // -ts_vshmm_adapt: the largest of the solve per level
  PetscBool              time_dependent     = PETSC_FALSE;    // some faster level's splits depend on time explicitly (found by LevelTimeRates())
  PetscBool              time_rates_checked = PETSC_FALSE;    // the separation check compared the savings with them (once per solve, at set-up)
  PetscReal              own_rates_time     = PETSC_MIN_REAL; // when level_slowest was estimated (with the spectra of that time)
  PetscReal              spectra_time       = PETSC_MIN_REAL; // when they were estimated

  // Accuracy control (-ts_vshmm_adapt)
  vshmm::AdaptParameters adapt_params;                            // micro step and time ratios for the next macro step
  vshmm::AdaptParameters adapt_used;                              // those of the last accepted macro step
  PetscReal              adapt_single_rate_step = 0;              // and the step of a single-rate TSRK within its bounds (single_rate_evaluations)
  PetscReal              adapt_last_ratio       = PETSC_MAX_REAL; // the last accepted step's estimate over its share
  PetscReal              adapt_prev_ratio       = PETSC_MAX_REAL; // the one before it
  PetscInt               adapt_uncompared       = 0;              // accepted steps in a row whose comparison was left out
  PetscBool              adapt_off_manifold     = PETSC_FALSE;    // the last try ended with a decaying fast variable off its slow manifold (its comparison is made)
  PetscReal              adapt_try_speed        = 0;              // the field's norm at the end of the present try (FollowRatesAtTryEnd(); 0: not measured)
  PetscReal              adapt_end_speed        = 0;              // and at the end of the last accepted step (a steady step's end must not jump from it: SteadyStep())
  PetscBool              rest_track             = PETSC_FALSE;    // -ts_vshmm_adapt: a try keeps its last micro step's stages (SpuriousRest())
  std::vector<Vec>       rest_stages;                             // they, swapped with K after each of its micro steps (no copy)
  PetscReal              rest_h     = 0;                          // and its micro step
  PetscBool              rest_found = PETSC_FALSE;                // a try came to a spurious rest: the stable steps are estimated again at the next macro step
  std::vector<PetscReal> adapt_end_rates;                         // per level: its radius at the last try's end where a decaying level's fell there (the spectra are estimated again at the next step) (bounds the savings of the step's tries; 0: none)
  vshmm::ErrorModel      adapt_model;
  PetscBool              adapt_ready = PETSC_FALSE; // initial parameters chosen
  std::vector<PetscBool> adapt_no_savings;          // per time ratio: no savings for the rest of the solve (they were negligible)
  std::vector<PetscReal> adapt_candidate;           // scales not separated: the time ratios to test against a single-rate step (empty: none)
  std::vector<PetscReal> adapt_verified;            // the time ratios that test admitted, adapt's upper bound (empty: not tested yet)
  PetscInt               adapt_since_calibration = 0;
  PetscBool              adapt_calibrated        = PETSC_FALSE; // the model's split between the terms was measured
  PetscInt               adapt_calibrated_times  = 0;           // calibrations in this solve
  PetscBool              adapt_postponed         = PETSC_FALSE; // the due calibration waited one step (its step was far below its share)
  std::vector<PetscReal> adapt_merged;                          // per level pair: its separation where adapt took no savings between a decaying pair less than kInitialDecaySeparation apart (0: not merged)
  std::vector<PetscInt>  adapt_negligible;                      // per parameter: this macro step's calibrations in a row that measured its term as negligible
  std::vector<double>    adapt_negligible_reach;                // per parameter: the coarsest value (dt, or r_l) at which its last calibration measured it
  PetscReal              adapt_tstart    = 0.0;                 // the time the solve started (the error budget runs from it)
  PetscBool              no_separation   = PETSC_FALSE;         // no pair of levels is separated
  PetscReal              separation_time = 0.0;                 // the time of the check that gave that verdict
  PetscReal              separated_from  = -1;                  // adapt: the time a later check found the scales separated (-1: not so)
  std::vector<PetscReal> adapt_lost;                            // per level pair: the time from which its faster level (oscillating, or decaying and separated at set-up) is no longer separated from it, so no savings between them (-1: separated)
  std::vector<bool>      adapt_separated_start;                 // per level pair: separated (kMinSeparation) at the accuracy control's set-up
  PetscBool              lost_warned = PETSC_FALSE;             // told that a pair lost its separation
  std::vector<PetscReal> adapt_phase; // per level pair: the time from which a faster level with a sustained oscillation moves the sampled quantities on its own scale (they carry its phase), so no savings between them (-1: none)
  PetscBool              phase_warned           = PETSC_FALSE;    // told that the sampled quantities carry a faster level's phase
  PetscBool              unstable_warned        = PETSC_FALSE;    // told that the fastest level sits at an unstable equilibrium
  PetscBool              floor_warned           = PETSC_FALSE;    // told that the estimate does not fall
  PetscReal              adapt_floor_dt         = 0;              // the micro step of the last step accepted at a floor without savings left: later steps do not refine below it (0: none)
  PetscReal              adapt_single_rate_from = -1;             // the start of the macro step from which the tolerance left no savings (-1: none)
  PetscReal              adapt_end              = PETSC_MIN_REAL; // the end of the last accepted macro step (a macro step that starts before it starts a new run)
  PetscReal              adapt_end_norm         = 0;              // the solution's 1-norm there (a later step from another state: the solution was changed between the steps)
  Vec                    Xtrial = nullptr, Xbase = nullptr;
  Vec                    Xcarried       = nullptr;                     // the carried comparison: a second solution, every error term doubled, from the run's start (adapt_global)
  PetscReal              carried_time   = PETSC_MIN_REAL;              // the time it has reached (a macro step from another time, or from a changed state, starts it again)
  PetscReal              carried_factor = 1;                           // the error model's conversion of its difference into an error estimate
  PetscReal              carried_fsum = 0, carried_weight = 0;         // the steps' conversion factors weighed by their estimates, and the weights' sum
  PetscReal              global_estimate = 0, global_estimate_max = 0; // that estimate at the last sampled time, the largest of the run (tolerance units)
  PetscBool              global_warned    = PETSC_FALSE;               // told that it exceeds the tolerance
  PetscInt               carried_restarts = 0;                         // times it blew up and started again from the solution
  Vec                    growth_X = nullptr, growth_Y = nullptr;       // the growth probe (GrowthProbe()): a perturbed solution (a compared step's comparison end state, propagated), and its run
  PetscReal              growth_time  = PETSC_MIN_REAL;                // the time growth_X is at (a macro step from there propagates it)
  PetscReal              growth_norm  = 0;                             // the solution's 1-norm then (another state there: the probe is dropped)
  PetscInt               growth_stage = 0;                             // propagations of the present perturbation so far (-1: none started)
  std::vector<PetscReal> growth_recent;                                // the present probe's last growth factors (kGrowthStages at most)
  PetscInt               growth_due              = 0;                  // the accepted step from which the next probe starts
  PetscBool              growth_measured         = PETSC_FALSE;        // a propagation was measured in the step being taken
  PetscReal              growth_factor           = 0;                  // and its growth factor
  PetscReal              growth_rate             = 0;                  // the slow dynamics' growth rate of an error (per unit time; 0: none measured, or none that grows)
  PetscReal              growth_rate_max         = 0;                  // the largest such rate of the solve (the warning's)
  PetscInt64             growth_probes           = 0;                  // probes completed (statistics)
  PetscBool              growth_warned           = PETSC_FALSE;        // told that errors made before the rate was known exceed the tolerance
  PetscBool              growth_damped           = PETSC_FALSE;        // a probe of the run found an error damped (a growth found later is a phase: StepBudget())
  PetscReal              growth_amplified        = 0;                  // the steps' estimates, each grown by the growth measured after it (GrowthProbeAccepted())
  PetscReal              growth_amplified_before = 0;                  // growth_amplified before the present probe's first step
  PetscReal              growth_probe_estimates  = 0;                  // and the estimates of the probe's steps (an uneven growth is undone: GrowthProbeAccepted())
  PetscReal              growth_log_sum          = 0;                  // the present probe's growths' logarithms, summed (its mean growth where it stays uneven)
  PetscInt               growth_log_count        = 0;                  // and their number
  PetscReal              growth_move             = 0;                  // the solution's motion over the last macro step on the slowest level's components (weighted)
  PetscReal              growth_streak           = 0;                  // that motion at the start of the present streak of steps whose motion grew (GrowthProbeAccepted())
  PetscInt               growth_streak_steps     = 0;                  // and the streak's steps
  Vec                    slow_mask               = nullptr;            // 1 on the slow components (written by the slowest level's splits only) where they are controlled with the observables
  Vec                    slow_seen = nullptr, faster_seen = nullptr;   // additive splits: |G_0| and the faster levels' own |f| summed over the states looked at (SlowComponentsFromValues())
  PetscInt               slow_by_values = 0;                           // the states looked at so far (0: slow_mask from the index sets)
  Vec                    lag_mask       = nullptr;                     // 1 on the components only faster levels' splits write (none where a slowest split is additive): where a comparison's end state is carried into the next one's start
  PetscBool              lag_by_values  = PETSC_FALSE;                 // lag_mask from the fields' values (additive splits): a component the slowest field is seen to write leaves it
  PetscInt               lag_count      = 0;                           // the components on lag_mask (global)
  PetscInt64             lag_inherited  = 0;                           // comparisons that started from the last one's end state on them (-ts_view)
  Vec                    lag_carried = nullptr, lag_next = nullptr;    // the last accepted step's comparison end state less the solution's there, on lag_mask; the candidate from the latest comparison
  PetscBool              lag_valid = PETSC_FALSE, lag_next_valid = PETSC_FALSE;
  vshmm::AdaptParameters lag_p, lag_q, lag_next_p, lag_next_q; // the step's and its comparison's parameters that made them
  PetscInt               slow_count = 0;                       // their number (global)
  PetscInt64             slow_led   = 0;                       // differences in which they led (statistics)
  PetscBool              slow_last  = PETSC_FALSE;             // they led the last difference
  PetscBool              step_slow  = PETSC_FALSE;             // they led the last comparison of the step being taken
  PetscReal              finer_term = 0;                       // the last calibration's micro step term measured from the finer side and counted (0: none)
  std::vector<Vec>       radius_vecs;                          // the power method's vector of each level (TSVSHMMLevelRadius_Private())
  PetscReal              radius_baseline = 0;                  // its radius at the levels' last full spectra (adapt)
  PetscInt               slow_steps      = 0;                  // accepted steps whose estimate they led
  std::vector<PetscReal> obs_a, obs_b;
  std::vector<PetscReal> obs_diff;                   // the last ObservableDifference, signed and weighted, per observable
  std::vector<PetscReal> step_signed;                // that of the last comparison of the step being taken
  std::vector<PetscReal> adapt_signed;               // the accepted steps' estimated errors, signed, summed (tolerance units)
  PetscReal              adapt_coherence      = 0.5; // the largest exponent gamma of the errors' growth measured significant so far (OwnStepBudget())
  PetscInt               adapt_accepted       = 0;   // accepted macro steps of this solve
  PetscInt               adapt_start_accepted = 0;   // those accepted before adapt started again (SeparationChanged())
  PetscReal              error_estimate = 0, error_estimate_total = 0, error_estimate_squares = 0;
  PetscInt64             adapt_evaluations = 0, adapt_rejections = 0, adapt_calibrations = 0;
  PetscInt64             adapt_uncompared_total  = 0; // accepted steps whose comparison was left out (statistics)
  PetscInt64             adapt_layer_fits        = 0; // tries estimated again from a second comparison (LayerEstimate(); statistics)
  PetscInt64             single_rate_evaluations = 0; // what a single-rate TSRK of the same tableau would take at the micro step of each accepted macro step (statistics, -ts_view, TSVSHMMAdaptCheckCost_Private())
  PetscInt64             run_start_work          = 0; // the split evaluations (steps and estimates) and single_rate_evaluations when this run started (StartRun())
  PetscInt64             run_start_single_rate   = 0;
  PetscReal              run_largest_ratio       = 1;           // -ts_vshmm_adapt: the largest product of time ratios of this run's accepted macro steps
  PetscBool              cost_warned             = PETSC_FALSE; // told in this run that it cost more than single-rate steps

  // Statistics since set-up
  enum Counter {
    COUNT_STEPS,
    COUNT_STABILITY,
    COUNT_ADAPT
  };
  Counter                 counting         = COUNT_STEPS; // where split evaluations are counted
  PetscInt64              macro_steps      = 0;
  PetscInt64              micro_cycles     = 0;
  PetscInt64              stability_checks = 0, stability_evaluations = 0, stability_warnings = 0;
  PetscReal               fast_energy_min    = 0;         // smallest energy of the fastest scale's oscillation seen by the stability checks of this solve
  PetscReal               fast_energy_warned = 0;         // its growth when last warned
  std::vector<PetscReal>  warned_ratio;                   // per level: largest step / stable step when last warned
  std::vector<PetscInt64> rhs_evaluations;                // per split
  std::vector<PetscInt64> level_steps, level_evaluations; // per level (scale)

  // First non-finite split output seen on this rank in the current macro step
  PetscReal  nonfinite_time  = PETSC_MAX_REAL;
  PetscInt   nonfinite_split = -1, nonfinite_level = -1;
  PetscInt   obs_fault         = -1;                           // the first observable this macro step's tries found not finite for a finite state (-1: none)
  PetscReal  obs_fault_time    = 0;                            // where
  PetscBool  obs_fault_nan     = PETSC_FALSE;                  // NaN (else Inf)
  PetscInt   current_level     = 0;                            // the level whose field is being evaluated
  PetscInt64 field_evaluations = 0, nonfinite_evaluation = -1; // level-field evaluations so far (the same on every rank); the faulty one
};

/* Whether a comparison with a single-rate step admitted savings where the scales are not
   separated (VerifySavings() in vshmmadapt.cpp). */
static inline bool TSVSHMMSavingsAdmitted_Private(const TS_VSHMM *vs)
{
  for (PetscReal r : vs->adapt_verified)
    if (r > 1.0) return true;
  return false;
}

static constexpr PetscInt  kDefaultMicroStepsPerMacroStep = 100;
static constexpr PetscReal kMinMicroStepFraction          = 1e-13; /* dt / DeltaT below this cannot advance time */
static constexpr PetscReal kObservablesAgreement          = 1e-10; /* the observables' spread over the ranks, relative to their size, above which they disagree */
static constexpr PetscReal kSplitsSumTolerance            = 1e-10; /* the splits' sum against the RHS function, relative to the largest output (TSVSHMMCheckSplitsSum_Private()) */

/* vshmm.cpp: the type */
/* TSVSHMMSetObservables() on a TS of any type: composed on the TS under this key, read by TSCreate_VSHMM() */
struct TSVSHMMObservablesRecord {
  PetscInt n;
  PetscErrorCode (*f)(TS, PetscReal, Vec, PetscReal[], void *);
  void *ctx;
};
static constexpr const char *kTSVSHMMObservablesKey = "TSVSHMMObservables";
PETSC_INTERN PetscErrorCode  TSCreate_VSHMM(TS);
/* vshmmwarnings.cpp: the one channel of the warnings a user must see without asking */
PETSC_INTERN PetscErrorCode TSVSHMMWarn_Private(TS, const char[], ...) PETSC_ATTRIBUTE_FORMAT(2, 3);
/* vshmmlevel.cpp: the levels' fields and steps, their log events */
PETSC_INTERN PetscErrorCode TSVSHMMEvaluateLevel_Private(TS_VSHMM *, PetscInt, PetscReal, Vec, Vec);
PETSC_INTERN PetscErrorCode TSVSHMMEvaluateOwnSplits_Private(TS_VSHMM *, PetscInt, PetscReal, Vec, Vec);
PETSC_INTERN PetscErrorCode TSVSHMMAddSplit_Private(TS_VSHMM *, PetscInt, PetscReal, Vec, Vec);               /* G += output F of split k, in place or by its scatter */
PETSC_INTERN PetscErrorCode TSVSHMMWrittenComponents_Private(TS_VSHMM *, PetscInt, PetscInt, PetscReal, Vec); /* mask = 0, then += 1 on every component splits [first, end) write */
PETSC_INTERN PetscErrorCode TSVSHMMCreateSchedule_Private(TS, PetscReal, std::unique_ptr<vshmm::MesoscopicSchedule> &);
PETSC_INTERN PetscErrorCode TSVSHMMRunMacroStep_Private(TS, const vshmm::MesoscopicSchedule &, PetscReal, PetscReal, Vec, vshmm::MacroStepCounts *);
/* the split evaluations of the steps and of -ts_vshmm_adapt's estimates and rejected tries so far */
static inline PetscInt64 TSVSHMMWork_Private(const TS_VSHMM *vs)
{
  PetscInt64 work = vs->adapt_evaluations;
  for (PetscInt64 n : vs->rhs_evaluations) work += n;
  return work;
}
/* a macro step's micro cycles and level steps added to the statistics */
static inline void TSVSHMMAddCounts_Private(TS_VSHMM *vs, const vshmm::MacroStepCounts &counts)
{
  vs->micro_cycles += counts.cycles;
  for (size_t l = 0; l < counts.levelSteps.size(); ++l) vs->level_steps[l] += counts.levelSteps[l];
}
PETSC_INTERN PetscErrorCode TSVSHMMGetLevelEvent_Private(PetscInt, PetscLogEvent *);
PETSC_INTERN PetscErrorCode TSVSHMMResetLevelEvents_Private(void);
/* vshmmstability.cpp: spectra of the levels, the stability check */
PETSC_INTERN PetscErrorCode TSVSHMMCheckStability_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMCheckSplitsSum_Private(TS); /* at set-up: the splits' sum against the TS's RHS function */
PETSC_INTERN PetscErrorCode TSVSHMMLevelSpectra_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMLevelOwnRates_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMLevelOwnSlowest_Private(TS, PetscInt, PetscReal *);                                                      /* the slowest own rate of a level at ts->vec_sol (component splits; 0 otherwise), not stored */
PETSC_INTERN PetscErrorCode TSVSHMMForcingRatio_Private(TS, PetscReal, Vec, PetscInt, PetscReal *, PetscReal *, PetscReal *);               /* how hard a faster level's oscillation forces the slower components */
PETSC_INTERN PetscErrorCode TSVSHMMFastQuantities_Private(TS, PetscReal, Vec, PetscReal, PetscInt *, PetscInt *, PetscReal *, PetscReal *); /* sampled quantities a faster level moves on its own scale */
/* vshmmadapt.cpp: the separation check, accuracy control */
PETSC_INTERN PetscErrorCode TSVSHMMCheckSeparation_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMLevelRadius_Private(TS, PetscInt, PetscReal *, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode TSVSHMMAdaptCheckSeparation_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMAdaptCheckCost_Private(TS); /* at a solve's last macro step: more work than single-rate steps? */
PETSC_INTERN PetscErrorCode TSVSHMMAdaptStep_Private(TS, PetscReal, PetscReal);
PETSC_INTERN PetscErrorCode TSVSHMMObservables_Private(TS, PetscReal, Vec, PetscReal[]); /* the user's observables, checked to agree on every rank */
PETSC_INTERN PetscErrorCode TSVSHMMAdaptSetUp_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMAdaptReset_Private(TS);
PETSC_INTERN PetscReal      TSVSHMMAmplitudeSpan_Private(TS);
PETSC_INTERN PetscReal      TSVSHMMToleranceLevel_Private(TS); /* one number for the tolerance (its vectors' level where TSSetTolerances() gave them) */
PETSC_INTERN PetscErrorCode TSVSHMMAdaptUnaveraged_Private(TS);
PETSC_INTERN PetscErrorCode TSVSHMMLevelBeats_Private(TS);                                                                   /* the faster levels' beats (vs->beat_omega, vs->beat_level, vs->beat_phase) */
PETSC_INTERN PetscBool      TSVSHMMBeatApproaching_Private(TS, PetscReal);                                                   /* -ts_vshmm_adapt: a difference of fast frequencies falling towards a beat before the time */
PETSC_INTERN PetscErrorCode TSVSHMMAdaptBeats_Private(TS);                                                                   /* -ts_vshmm_adapt: what they do to the observables (vs->beat_bound) */
PETSC_INTERN PetscErrorCode TSVSHMMAdaptSampleSchedule_Private(TS, PetscReal, std::unique_ptr<vshmm::MesoscopicSchedule> &); /* for a state inside the last macro step (TSInterpolate()) */
PETSC_INTERN PetscErrorCode TSVSHMMCheckFastQuantities_Private(TS, PetscReal);                                               /* fixed savings: said where the sampled quantities carry a faster level's phase */
