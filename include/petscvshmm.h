/*
   petscvshmm.h - public interface of petsc-vshmm, the TSVSHMM time stepper for PETSc.

   TSVSHMM is the Variable Step Size Heterogeneous Multiscale Method of Lee and Engquist
   ("Fast integrators for dynamical systems with several temporal scales") for

       dx/dt = f_0(x) + f_1(x)/eps_1 + ... + f_K(x)/eps_K,   eps_K < ... < eps_1 << 1,

   where each scale f_k/eps_k is one TSRHSSplit of the TS (slowest first).
*/
#ifndef PETSCVSHMM_H
#define PETSCVSHMM_H

#include <petscts.h>

/*J
   TSVSHMM - the type name of the variable step size heterogeneous multiscale stepper, "vshmm"

   Level: beginner

.seealso: `TSSetType()`, `TSVSHMMInitializePackage()`
J*/
#define TSVSHMM "vshmm"

/*E
   TSVSHMMKernelType - the kernel K(s) on [0,1] that shapes the variable mesoscopic steps

$  TSVSHMM_KERNEL_COSINE      - K(s) = 1 + cos(2 pi (s - 1/2)), order q = 1 (the paper's kernel, the default)
$  TSVSHMM_KERNEL_CONSTANT    - K(s) = 1: constant mesoscopic steps (the paper's comparison)
$  TSVSHMM_KERNEL_POLYNOMIAL  - K(s) = s^(q+1) (1-s)^(q+1) / B(q+2,q+2), any order q
$  TSVSHMM_KERNEL_EXPONENTIAL - K(s) = exp(-1/(s(1-s))) / Z, infinitely smooth

   Options Database Key:
.  -ts_vshmm_kernel <cosine,constant,polynomial,exponential> - choose the kernel

   Level: intermediate

.seealso: `TSVSHMMSetKernel()`, `TSVSHMMSetKernelOrder()`
E*/
typedef enum {
  TSVSHMM_KERNEL_COSINE,
  TSVSHMM_KERNEL_CONSTANT,
  TSVSHMM_KERNEL_POLYNOMIAL,
  TSVSHMM_KERNEL_EXPONENTIAL
} TSVSHMMKernelType;
PETSC_EXTERN const char *const TSVSHMMKernelTypes[];

/*E
   TSVSHMMSeparationCheck - what TSVSHMM does when no pair of consecutive levels is separated in time scale

$  TSVSHMM_SEPARATION_OFF   - do not check
$  TSVSHMM_SEPARATION_WARN  - say so at set-up on the warnings viewer, stderr by default (the default)
$  TSVSHMM_SEPARATION_ERROR - stop with an error at set-up

   Options Database Key:
.  -ts_vshmm_check_separation <off,warn,error> - choose

   Level: intermediate

.seealso: `TSVSHMMSetSeparationCheck()`, `TSVSHMMSetAdapt()`
E*/
typedef enum {
  TSVSHMM_SEPARATION_OFF,
  TSVSHMM_SEPARATION_WARN,
  TSVSHMM_SEPARATION_ERROR
} TSVSHMMSeparationCheck;
PETSC_EXTERN const char *const TSVSHMMSeparationChecks[];

/*S
   TSVSHMMStatistics - the work a TSVSHMM has done since its set-up (or the last
   TSVSHMMResetStatistics())

   Fields:
+  macro_steps      - macro steps taken (sampling intervals DeltaT)
.  micro_cycles     - micro cycles: one micro step of the full field plus one mesoscopic step per slower level
.  nsplits          - number of RHS splits
.  nscales          - number of scales (levels): one per split, unless -ts_vshmm_splits groups them
.  rhs_evaluations  - calls of each split's right-hand-side function, in scale order (slowest first); nsplits entries
.  level_steps      - Runge-Kutta steps taken on each level (level l integrates the scales 0..l); nscales entries
.  level_evaluations - evaluations of each level's field G_l = f_0 + ... + f_l (one per RK stage); nscales entries
.  stability_checks - stability checks run (see TSVSHMMSetStabilityCheck())
.  stability_evaluations - split RHS evaluations spent by those checks and by the split check at set-up (not in the counts above)
.  stability_warnings - checks that found a level's largest step beyond its stable step, though damped over a macro step (warned on the warnings viewer, see TSVSHMMSetWarningsViewer())
.  error_estimate   - estimated error of the last macro step in the observables, in the TS's weighted norm (1 = the tolerance); 0 without -ts_vshmm_adapt
.  error_estimate_total - the sum of error_estimate over the macro steps: an estimate of the error at the current time
.  adapt_evaluations - split RHS evaluations spent on error estimation and rejected macro steps (not in rhs_evaluations)
.  adapt_rejections - macro steps redone with finer parameters
.  adapt_calibrations - macro steps at which every parameter's error term was measured
.  adapt_uncompared - accepted macro steps whose comparison was left out (nothing left to coarsen, the estimates far below their shares: the model's prediction stood in)
.  adapt_layer_estimates - tries of the first macro step estimated again from a second comparison (an initial layer, where the error grows faster than the error model's terms)
.  adapt_single_rate_from - the time from which -ts_vshmm_adapt took no savings because the tolerance was out of reach with them (finer savings did not lower the estimate, a single-rate step did), -1 if it did not happen
.  adapt_growth_probes - probes of how the slow dynamics grow an error (made where the slowest level's Jacobian has a growing mode; see "Accuracy on request" in docs/user-guide.md)
.  adapt_growth_rate - the growth rate of an error the last probe measured (per unit time; 0: none grows): each later macro step's share of the tolerance is shrunk by e^(rate (t_final - t))
.  global_estimate  - with -ts_vshmm_adapt_global_estimate, the error at the last sampled time estimated from the carried comparison (a second solution with every error term doubled), in the TS's weighted norm (1 = the tolerance); -1 without it
.  global_estimate_max - the largest global_estimate of the run (since TSVSHMMResetStatistics()); -1 without it
-  single_rate_evaluations - split RHS evaluations a single-rate TSRK of the same tableau would take over the same macro steps (every split at every stage) at each one's micro step, or with -ts_vshmm_adapt at the largest step the accuracy control's bounds allow (stable, resolving the fastest oscillation over the span, at least the micro step); rhs_evaluations plus adapt_evaluations above it means the savings did not pay for themselves

   Level: intermediate

.seealso: `TSVSHMMGetStatistics()`, `TSVSHMMResetStatistics()`
S*/
typedef struct {
  PetscInt64        macro_steps;
  PetscInt64        micro_cycles;
  PetscInt          nsplits;
  PetscInt          nscales;
  const PetscInt64 *rhs_evaluations;
  const PetscInt64 *level_steps;
  const PetscInt64 *level_evaluations;
  PetscInt64        stability_checks;
  PetscInt64        stability_evaluations;
  PetscInt64        stability_warnings;
  PetscReal         error_estimate;
  PetscReal         error_estimate_total;
  PetscInt64        adapt_evaluations;
  PetscInt64        adapt_rejections;
  PetscInt64        adapt_calibrations;
  PetscInt64        adapt_uncompared;
  PetscInt64        adapt_layer_estimates;
  PetscReal         adapt_single_rate_from;
  PetscInt64        adapt_growth_probes;
  PetscReal         adapt_growth_rate;
  PetscReal         global_estimate;
  PetscReal         global_estimate_max;
  PetscInt64        single_rate_evaluations;
} TSVSHMMStatistics;

PETSC_EXTERN PetscErrorCode TSVSHMMInitializePackage(void);
PETSC_EXTERN PetscErrorCode TSVSHMMFinalizePackage(void);

PETSC_EXTERN PetscErrorCode TSVSHMMSetMicroStep(TS, PetscReal);
PETSC_EXTERN PetscErrorCode TSVSHMMGetMicroStep(TS, PetscReal *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetSavingsFactors(TS, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode TSVSHMMGetSavingsFactors(TS, PetscInt *, const PetscReal *[]);
PETSC_EXTERN PetscErrorCode TSVSHMMSetSubintervals(TS, PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode TSVSHMMGetSubintervals(TS, PetscInt *, const PetscInt *[]);
PETSC_EXTERN PetscErrorCode TSVSHMMSetKernel(TS, TSVSHMMKernelType);
PETSC_EXTERN PetscErrorCode TSVSHMMGetKernel(TS, TSVSHMMKernelType *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetKernelOrder(TS, PetscInt);
PETSC_EXTERN PetscErrorCode TSVSHMMGetKernelOrder(TS, PetscInt *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetRKType(TS, TSRKType);
PETSC_EXTERN PetscErrorCode TSVSHMMGetRKType(TS, TSRKType *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetSplitOrder(TS, PetscInt, const char *const[]);
PETSC_EXTERN PetscErrorCode TSVSHMMGetSplitOrder(TS, PetscInt *, const char *const *[]);
PETSC_EXTERN PetscErrorCode TSVSHMMSetStabilityCheck(TS, PetscBool, PetscInt);
PETSC_EXTERN PetscErrorCode TSVSHMMGetStabilityCheck(TS, PetscBool *, PetscInt *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetAdapt(TS, PetscBool);
PETSC_EXTERN PetscErrorCode TSVSHMMGetAdapt(TS, PetscBool *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetSplitCheck(TS, PetscBool);
PETSC_EXTERN PetscErrorCode TSVSHMMGetSplitCheck(TS, PetscBool *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetAdaptSlowComponents(TS, PetscBool);
PETSC_EXTERN PetscErrorCode TSVSHMMGetAdaptSlowComponents(TS, PetscBool *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetAdaptGlobalEstimate(TS, PetscBool);
PETSC_EXTERN PetscErrorCode TSVSHMMGetAdaptGlobalEstimate(TS, PetscBool *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetObservables(TS, PetscInt, PetscErrorCode (*)(TS, PetscReal, Vec, PetscReal[], void *), void *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetScaleSeparations(TS, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode TSVSHMMGetScaleSeparations(TS, PetscInt *, const PetscReal *[]);
PETSC_EXTERN PetscErrorCode TSVSHMMSetSeparationCheck(TS, TSVSHMMSeparationCheck);
PETSC_EXTERN PetscErrorCode TSVSHMMGetSeparationCheck(TS, TSVSHMMSeparationCheck *);
PETSC_EXTERN PetscErrorCode TSVSHMMSetWarningsViewer(TS, PetscViewer);
PETSC_EXTERN PetscErrorCode TSVSHMMGetStatistics(TS, TSVSHMMStatistics *);
PETSC_EXTERN PetscErrorCode TSVSHMMResetStatistics(TS);

#endif
