/*
  The public TSVSHMM interface: argument checks, then the type's composed implementation.
  Setting a parameter on a TS of another type does nothing (PetscTryMethod), as for TSRK.
*/
#include "vshmmimpl.hpp"

#include <cmath>

/*@
   TSVSHMMSetMicroStep - Sets the micro step dt with which the full field (all scales) is integrated

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
-  dt - the micro step, positive and smaller than the sampling interval (the TS time step)

   Options Database Key:
.  -ts_vshmm_micro_dt <dt> - the micro step

   Notes:
   dt must resolve the fastest scale: it is the step of an explicit Runge-Kutta method applied to
   the whole right-hand side. By default dt is one hundredth of the sampling interval.

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMGetMicroStep()`, `TSVSHMMSetSavingsFactors()`, `TSSetTimeStep()`
@*/
PetscErrorCode TSVSHMMSetMicroStep(TS ts, PetscReal dt)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveReal(ts, dt, 2);
  PetscCheck(std::isfinite(dt) && dt > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Micro step %g is invalid: -ts_vshmm_micro_dt must be positive and finite", (double)dt);
  PetscTryMethod(ts, "TSVSHMMSetMicroStep_C", (TS, PetscReal), (ts, dt));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetMicroStep - Gets the micro step dt of the full field

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  dt - the micro step (the default, one hundredth of the TS time step, if none was set)

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMSetMicroStep()`
@*/
PetscErrorCode TSVSHMMGetMicroStep(TS ts, PetscReal *dt)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(dt, 2);
  PetscUseMethod(ts, "TSVSHMMGetMicroStep_C", (TS, PetscReal *), (ts, dt));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetSavingsFactors - Sets the savings factors alpha_1, ..., alpha_K of the mesoscopic steps

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
.  n - the number of factors: the number of RHS splits less one (checked at set-up)
-  alpha - the factors, positive, slowest level first

   Options Database Key:
.  -ts_vshmm_savings_factors <a1,...,aK> - the savings factors

   Notes:
   Level l < K (the splits 0..l) takes mesoscopic steps h_{l+1} whose average over a kernel period
   is about alpha_{l+1} dt, so alpha_1 belongs to the slowest field alone and alpha_K to the field
   without the fastest scale. The paper's dissipative example uses alpha = (100, 10) with
   dt = 1e-4. By default every factor is 1 (no savings).

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMGetSavingsFactors()`, `TSVSHMMSetMicroStep()`, `TSVSHMMSetSubintervals()`
@*/
PetscErrorCode TSVSHMMSetSavingsFactors(TS ts, PetscInt n, const PetscReal alpha[])
{
  MPI_Comm comm;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)ts);
  PetscCheck(n >= 1, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_savings_factors needs at least one value (one per RHS split except the fastest), got %" PetscInt_FMT, n);
  VSHMMValidPointer(alpha, 3);
  for (PetscInt i = 0; i < n; ++i) PetscCheck(std::isfinite(alpha[i]) && alpha[i] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Savings factor %" PetscInt_FMT " is %g: -ts_vshmm_savings_factors values must be positive and finite", i + 1, (double)alpha[i]);
  PetscTryMethod(ts, "TSVSHMMSetSavingsFactors_C", (TS, PetscInt, const PetscReal[]), (ts, n, alpha));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMGetSavingsFactors - Gets the savings factors alpha_1, ..., alpha_K

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameters:
+  n - the number of factors (0 if none were set and the TS is not set up)
-  alpha - the factors, slowest level first (owned by the TS; do not free)

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMSetSavingsFactors()`
@*/
PetscErrorCode TSVSHMMGetSavingsFactors(TS ts, PetscInt *n, const PetscReal *alpha[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSVSHMMGetSavingsFactors_C", (TS, PetscInt *, const PetscReal *[]), (ts, n, alpha));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetSubintervals - Sets the number of kernel periods m_j of each mesoscopic step per sampling interval

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
.  n - the number of counts: the number of RHS splits less one (checked at set-up)
-  m - the counts, at least 1, slowest level first

   Options Database Key:
.  -ts_vshmm_subintervals <m1,...,mK> - the counts

   Notes:
   The mesoscopic step h_j follows the kernel over periods P_j = DeltaT / m_j. The paper uses
   m_1 = 1. The default is 1 for every level.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMGetSubintervals()`, `TSVSHMMSetSavingsFactors()`
@*/
PetscErrorCode TSVSHMMSetSubintervals(TS ts, PetscInt n, const PetscInt m[])
{
  MPI_Comm comm;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)ts);
  PetscCheck(n >= 1, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_subintervals needs at least one value (one per RHS split except the fastest), got %" PetscInt_FMT, n);
  VSHMMValidPointer(m, 3);
  for (PetscInt i = 0; i < n; ++i) PetscCheck(m[i] >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Subinterval count %" PetscInt_FMT " is %" PetscInt_FMT ": -ts_vshmm_subintervals values must be integers >= 1", i + 1, m[i]);
  PetscTryMethod(ts, "TSVSHMMSetSubintervals_C", (TS, PetscInt, const PetscInt[]), (ts, n, m));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMGetSubintervals - Gets the number of kernel periods m_j per sampling interval

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameters:
+  n - the number of counts (0 if none were set and the TS is not set up)
-  m - the counts, slowest level first (owned by the TS; do not free)

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetSubintervals()`
@*/
PetscErrorCode TSVSHMMGetSubintervals(TS ts, PetscInt *n, const PetscInt *m[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSVSHMMGetSubintervals_C", (TS, PetscInt *, const PetscInt *[]), (ts, n, m));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetKernel - Sets the kernel K(s) that shapes the variable mesoscopic steps

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
-  type - `TSVSHMM_KERNEL_COSINE` (default), `TSVSHMM_KERNEL_CONSTANT`, `TSVSHMM_KERNEL_POLYNOMIAL` or `TSVSHMM_KERNEL_EXPONENTIAL`

   Options Database Key:
.  -ts_vshmm_kernel <cosine,constant,polynomial,exponential> - the kernel

   Notes:
   Kernels that vanish at the ends of each period make the steps fine there, which resolves fast
   transients; the constant kernel gives constant mesoscopic steps alpha_j dt.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMKernelType`, `TSVSHMMGetKernel()`, `TSVSHMMSetKernelOrder()`
@*/
PetscErrorCode TSVSHMMSetKernel(TS ts, TSVSHMMKernelType type)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveEnum(ts, type, 2);
  PetscCheck(type >= TSVSHMM_KERNEL_COSINE && type <= TSVSHMM_KERNEL_EXPONENTIAL, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Unknown kernel %d: -ts_vshmm_kernel takes cosine, constant, polynomial or exponential", (int)type);
  PetscTryMethod(ts, "TSVSHMMSetKernel_C", (TS, TSVSHMMKernelType), (ts, type));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetKernel - Gets the kernel of the mesoscopic steps

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  type - the kernel

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetKernel()`
@*/
PetscErrorCode TSVSHMMGetKernel(TS ts, TSVSHMMKernelType *type)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(type, 2);
  PetscUseMethod(ts, "TSVSHMMGetKernel_C", (TS, TSVSHMMKernelType *), (ts, type));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetKernelOrder - Sets the order q of the polynomial kernel s^(q+1) (1-s)^(q+1) / B

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
-  q - the order, 0 <= q <= 16: the derivatives of order 0..q vanish at both ends

   Options Database Key:
.  -ts_vshmm_kernel_order <q> - the order

   Notes:
   The other kernels have a fixed order (cosine 1, constant -1, exponential infinite); setting an
   order other than theirs is an error at set-up.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetKernel()`, `TSVSHMMGetKernelOrder()`
@*/
PetscErrorCode TSVSHMMSetKernelOrder(TS ts, PetscInt q)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveInt(ts, q, 2);
  PetscCheck(q >= 0 && q <= vshmm::Kernel::kMaxPolynomialOrder, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Kernel order %" PetscInt_FMT " is out of range: -ts_vshmm_kernel_order takes 0..%d (polynomial kernel)", q, vshmm::Kernel::kMaxPolynomialOrder);
  PetscTryMethod(ts, "TSVSHMMSetKernelOrder_C", (TS, PetscInt), (ts, q));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetKernelOrder - Gets the order of the kernel: the derivatives of order 0..q vanish at both ends

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  q - the order (-1 for the constant kernel, PETSC_MAX_INT for the exponential one)

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetKernelOrder()`
@*/
PetscErrorCode TSVSHMMGetKernelOrder(TS ts, PetscInt *q)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(q, 2);
  PetscUseMethod(ts, "TSVSHMMGetKernelOrder_C", (TS, PetscInt *), (ts, q));
  if (*q == vshmm::Kernel::kInfiniteOrder) *q = PETSC_MAX_INT;
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMSetRKType - Sets the explicit Runge-Kutta method of every micro and mesoscopic step

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
-  type - a `TSRKType` (`TSRK4`, the default, `TSRK3`, `TSRK5DP`, ...) or a type registered with `TSRKRegister()`

   Options Database Key:
.  -ts_vshmm_rk_type <type> - the Runge-Kutta type

   Notes:
   The tableau is taken from PETSc's TSRK registry at set-up; an unknown type is an error there.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMGetRKType()`, `TSRKSetType()`, `TSRKRegister()`
@*/
PetscErrorCode TSVSHMMSetRKType(TS ts, TSRKType type)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(type, 2);
  PetscCheck(type[0], PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "-ts_vshmm_rk_type needs a TSRK type name, e.g. 4");
  PetscTryMethod(ts, "TSVSHMMSetRKType_C", (TS, TSRKType), (ts, type));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMGetRKType - Gets the Runge-Kutta type of the inner steps

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  type - the `TSRKType`

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetRKType()`
@*/
PetscErrorCode TSVSHMMGetRKType(TS ts, TSRKType *type)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(type, 2);
  PetscUseMethod(ts, "TSVSHMMGetRKType_C", (TS, TSRKType *), (ts, type));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMSetSplitOrder - Names the RHS splits of each scale, slowest scale first

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
.  n - the number of scales, at least two
-  names - for each scale a split name given to `TSRHSSplitSetIS()`, or several joined by '+'
           ("slow+slowbuffer"): every split of the TS appears once (checked at set-up)

   Options Database Key:
.  -ts_vshmm_splits <a,b+c,...> - the scales, slowest first

   Notes:
   By default each split is one scale, in the order in which the splits were created. A group
   a+b makes one scale whose field is the sum of the splits' outputs, e.g. TSMPRK's "slow" and
   "slowbuffer" splits of PETSc's multirate tutorials.

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMGetSplitOrder()`, `TSRHSSplitSetIS()`
@*/
PetscErrorCode TSVSHMMSetSplitOrder(TS ts, PetscInt n, const char *const names[])
{
  MPI_Comm comm;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)ts);
  PetscCheck(n >= 2, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_splits needs at least two scales, slowest first (split names, or groups of them as a+b), got %" PetscInt_FMT, n);
  VSHMMValidPointer(names, 3);
  for (PetscInt i = 0; i < n; ++i) PetscCheck(names[i] && names[i][0], comm, PETSC_ERR_ARG_WRONG, "-ts_vshmm_splits: name %" PetscInt_FMT " is empty", i + 1);
  PetscTryMethod(ts, "TSVSHMMSetSplitOrder_C", (TS, PetscInt, const char *const[]), (ts, n, names));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMGetSplitOrder - Gets the scales, slowest first, each as a split name or names joined by '+'

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameters:
+  n - the number of scales
-  names - each scale's split name, or names joined by '+' (owned by the TS; valid until the next call)

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMSetSplitOrder()`
@*/
PetscErrorCode TSVSHMMGetSplitOrder(TS ts, PetscInt *n, const char *const *names[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSVSHMMGetSplitOrder_C", (TS, PetscInt *, const char *const *[]), (ts, n, names));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetStabilityCheck - Turns the stability check of the micro and mesoscopic steps on or off

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
.  flg - `PETSC_TRUE` (the default) to check at set-up
-  interval - also check every that many macro steps; 0 (the default) for never

   Options Database Keys:
+  -ts_vshmm_check_stability <true,false> - check at set-up
-  -ts_vshmm_check_stability_interval <N> - also check every N macro steps

   Notes:
   The check estimates the eigenvalues of each level's field G_l = f_0 + ... + f_l at the
   current state by a few Arnoldi steps on finite-difference Jacobian products of the split
   functions (about 17 level-field evaluations per level; no Jacobian is needed). For every
   estimated eigenvalue lambda with Re(lambda) <= 0 the micro step dt must lie in the stability
   region of the inner Runge-Kutta method (|R(dt lambda)| <= 1). A mesoscopic level passes when
   its largest step does, or, as variable steps may exceed the limit near the kernel's peak,
   when its steps over a whole macro step damp the mode. A failure is an error that names the
   level, the step, the eigenvalue, the spectral radius, the largest stable step and the largest
   stable savings factor. Growing modes (Re(lambda) > 0) are the problem's own and are not checked.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMGetStabilityCheck()`, `TSVSHMMSetMicroStep()`, `TSVSHMMSetSavingsFactors()`
@*/
PetscErrorCode TSVSHMMSetStabilityCheck(TS ts, PetscBool flg, PetscInt interval)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveBool(ts, flg, 2);
  PetscValidLogicalCollectiveInt(ts, interval, 3);
  PetscCheck(interval >= 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Stability check interval %" PetscInt_FMT " is invalid: -ts_vshmm_check_stability_interval takes 0 (never) or a number of macro steps >= 1", interval);
  PetscTryMethod(ts, "TSVSHMMSetStabilityCheck_C", (TS, PetscBool, PetscInt), (ts, flg, interval));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetStabilityCheck - Tells whether and how often the stability check runs

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameters:
+  flg - whether it runs at set-up
-  interval - every how many macro steps it runs too (0: never)

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetStabilityCheck()`
@*/
PetscErrorCode TSVSHMMGetStabilityCheck(TS ts, PetscBool *flg, PetscInt *interval)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSVSHMMGetStabilityCheck_C", (TS, PetscBool *, PetscInt *), (ts, flg, interval));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMGetStatistics - Gets the work done since set-up: macro steps, micro cycles, and the
   right-hand-side evaluations of every split

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  stats - the statistics; its arrays are owned by the TS and valid until its next set-up

   Notes:
   Level l evaluates the splits 0..l at each Runge-Kutta stage, so per micro cycle split k is
   evaluated (K + 1 - k) s times for an s-stage method. -ts_view prints the same numbers.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMStatistics`, `TSVSHMMResetStatistics()`
@*/
PetscErrorCode TSVSHMMGetStatistics(TS ts, TSVSHMMStatistics *stats)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(stats, 2);
  PetscUseMethod(ts, "TSVSHMMGetStatistics_C", (TS, TSVSHMMStatistics *), (ts, stats));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMResetStatistics - Sets the work counters of a TSVSHMM to zero

   Logically Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMGetStatistics()`
@*/
PetscErrorCode TSVSHMMResetStatistics(TS ts)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscTryMethod(ts, "TSVSHMMResetStatistics_C", (TS), (ts));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetSplitCheck - Sets whether TSVSHMM checks at set-up that its RHS splits add up to the TS's right-hand side function

   Logically Collective

   Input Parameters:
+  ts  - the `TS` of type `TSVSHMM`
-  flg - `PETSC_TRUE` (the default) to check, `PETSC_FALSE` to skip the check

   Options Database Key:
.  -ts_vshmm_check_splits <true,false> - check at set-up

   Notes:
   TSVSHMM steps the RHS splits (`TSRHSSplitSetRHSFunction()`) and calls the TS's own right-hand
   side function (`TSSetRHSFunction()`), which every other TS type integrates, only for this check. Where
   the splits' sum is not that function (a component that no split writes, a term in two splits
   or in none, an IS that names other components than the split function writes), TSVSHMM solves
   another problem than `-ts_type rk` would, without any other sign. At set-up, at the initial
   state, the function and each split are evaluated once (counted with the stability check's
   split evaluations); where they differ by more than 1e-10 of the largest split output, a
   warning names the component with the largest difference and both values (on the warnings
   viewer, `TSVSHMMSetWarningsViewer()`); `-ts_view` prints the relative difference. A TS without
   an RHS function (splits only) is not checked; an implicit function (`TSSetIFunction()`) is an
   error at set-up, as for PETSc's explicit types. Differences that vanish at the initial
   state (a term that is zero there) are not seen.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMGetSplitCheck()`, `TSVSHMMSetStabilityCheck()`, `TSRHSSplitSetIS()`, `TSRHSSplitSetRHSFunction()`
@*/
PetscErrorCode TSVSHMMSetSplitCheck(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveBool(ts, flg, 2);
  PetscTryMethod(ts, "TSVSHMMSetSplitCheck_C", (TS, PetscBool), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetSplitCheck - Tells whether TSVSHMM checks at set-up that its RHS splits add up to the TS's right-hand side function

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  flg - `PETSC_TRUE` if it does

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetSplitCheck()`
@*/
PetscErrorCode TSVSHMMGetSplitCheck(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(flg, 2);
  PetscUseMethod(ts, "TSVSHMMGetSplitCheck_C", (TS, PetscBool *), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetAdapt - Makes TSVSHMM choose its micro step and savings factors from the TS tolerances

   Logically Collective

   Input Parameters:
+  ts  - the `TS` of type `TSVSHMM`
-  flg - `PETSC_TRUE` to choose the parameters that were not set, `PETSC_FALSE` to use them as set

   Options Database Key:
.  -ts_vshmm_adapt <true,false> - choose the parameters

   Notes:
   Each macro step (sampling interval, the TS time step, which stays as set) is compared with the
   same step taken with coarser parameters; the difference of the observables
   (`TSVSHMMSetObservables()`, by default the whole state), in the weighted norm of the TS
   tolerances (`TSSetTolerances()`, -ts_rtol, -ts_atol), is the error estimate. A step whose
   estimate exceeds its share of the tolerance, DeltaT / (final time - start time), is redone with
   finer parameters, and the parameters of the next step are the cheapest the measured error
   model allows. Parameters set with `TSVSHMMSetMicroStep()` or `TSVSHMMSetSavingsFactors()` stay
   fixed. Every step is kept stable using each level's estimated eigenvalues, and where the scales
   are not separated (see `TSVSHMMSetSeparationCheck()`) no savings are taken. The time ratios also
   keep the fastest level's oscillation turning at least once per macro step where leaving it
   unaveraged would cost more than half the tolerance, and keep a faster level's explicit time
   dependence (a forcing in time in its splits) a tenth of its rate as the level sees it. The estimate and
   the work spent on it are in `TSVSHMMGetStatistics()` and -ts_view; -info shows every choice.

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMSetObservables()`, `TSSetTolerances()`, `TSVSHMMGetStatistics()`
@*/
PetscErrorCode TSVSHMMSetAdapt(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveBool(ts, flg, 2);
  PetscTryMethod(ts, "TSVSHMMSetAdapt_C", (TS, PetscBool), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetAdapt - Tells whether TSVSHMM chooses its parameters from the TS tolerances

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  flg - `PETSC_TRUE` if it does

   Level: beginner

.seealso: `TSVSHMM`, `TSVSHMMSetAdapt()`
@*/
PetscErrorCode TSVSHMMGetAdapt(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(flg, 2);
  PetscUseMethod(ts, "TSVSHMMGetAdapt_C", (TS, PetscBool *), (ts, flg));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMSetObservables - Sets the slow quantities of interest to which the tolerance of `TSVSHMMSetAdapt()` applies

   Logically Collective

   Input Parameters:
+  ts  - the `TS` (of any type; see the notes)
.  n   - the number of quantities (at least 1)
.  f   - the function that computes them: f(ts, t, X, q, ctx) fills q[0..n-1] from the state X at time t; it must give the same values on every rank (it is collective; on several ranks TSVSHMM checks this at every call and stops with an error where they differ)
-  ctx - its context (may be NULL)

   Notes:
   Without observables the tolerance applies to the whole sampled state in the weighted norm of
   `TSErrorWeightedNorm()`, which is right where the fast variables are slaved to the slow ones
   (dissipative scales). Where they oscillate, the state at a sampled time carries the fast phases,
   which VSHMM does not compute accurately: name the slow quantities (for two oscillators, their
   energies or amplitudes). Each quantity q_i is weighed by atol + rtol |q_i|. Pass f = NULL to go
   back to the whole state. The components that only the slowest scale's splits write are
   controlled together with the observables (`TSVSHMMSetAdaptSlowComponents()`).

   Unlike the other TSVSHMM setters (which, as for `TSRK`, act only on a `TS` that is already of
   type `TSVSHMM`), this one may be called on a `TS` of any type, before `TSSetType()` or
   `TSSetFromOptions()`: the quantities belong to the problem, and they are kept on the `TS` for
   the `TSVSHMM` it becomes, so that `-ts_type vshmm` on the command line finds them.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetAdapt()`, `TSSetTolerances()`, `TSVSHMMSetAdaptSlowComponents()`
@*/
PetscErrorCode TSVSHMMSetObservables(TS ts, PetscInt n, PetscErrorCode (*f)(TS, PetscReal, Vec, PetscReal[], void *), void *ctx)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscCheck(!f || n >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMMSetObservables(): the number of observables is %" PetscInt_FMT ": it must be at least 1", n);
  /* kept on the TS whatever its type, for a TSVSHMM it becomes later (TSCreate_VSHMM()) */
  if (f) {
    TSVSHMMObservablesRecord *record;
    PetscContainer            container;

    PetscCall(PetscNew(&record));
    record->n   = n;
    record->f   = f;
    record->ctx = ctx;
    PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)ts), &container));
    PetscCall(PetscContainerSetPointer(container, record));
    PetscCall(PetscContainerSetUserDestroy(container, PetscContainerUserDestroyDefault));
    PetscCall(PetscObjectCompose((PetscObject)ts, kTSVSHMMObservablesKey, (PetscObject)container));
    PetscCall(PetscContainerDestroy(&container));
  } else PetscCall(PetscObjectCompose((PetscObject)ts, kTSVSHMMObservablesKey, nullptr));
  PetscTryMethod(ts, "TSVSHMMSetObservables_C", (TS, PetscInt, PetscErrorCode(*)(TS, PetscReal, Vec, PetscReal[], void *), void *), (ts, n, f, ctx));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetAdaptSlowComponents - Sets whether `TSVSHMMSetAdapt()` controls the error of the slow components together with the observables

   Logically Collective

   Input Parameters:
+  ts  - the `TS` of type `TSVSHMM`
-  flg - `PETSC_TRUE` (the default) to control them too, `PETSC_FALSE` to control the observables only

   Options Database Key:
.  -ts_vshmm_adapt_slow_components <true,false> - control the slow components too

   Notes:
   The slow components are those that only the slowest scale's splits write (component splits,
   `TSRHSSplitSetIS()`). Where the splits are additive (every index set covers every component)
   the fields' values tell: the slowest level's field nonzero and every faster split's term zero,
   at the initial state, it nudged along the whole field and the first two macro steps' starts. With observables
   (`TSVSHMMSetObservables()`) the error estimate of a macro step is the larger of the observables'
   difference and the slow components' difference, in the weighted norm of the TS tolerances:
   an error in a slow component that the observables do not show at the end of one macro step
   (the velocity of a slow oscillator whose position is observed) becomes their error at later
   sampled times, and an estimate of the observables alone misses it (such a run ended 12 times
   its tolerance off). Set `PETSC_FALSE` where slow components do not feed the observables (they
   are then left uncontrolled). Without observables the whole state is controlled anyway.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetAdapt()`, `TSVSHMMSetObservables()`, `TSVSHMMGetAdaptSlowComponents()`
@*/
PetscErrorCode TSVSHMMSetAdaptSlowComponents(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveBool(ts, flg, 2);
  PetscTryMethod(ts, "TSVSHMMSetAdaptSlowComponents_C", (TS, PetscBool), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetAdaptSlowComponents - Tells whether `TSVSHMMSetAdapt()` controls the slow components together with the observables

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  flg - `PETSC_TRUE` if it does

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetAdaptSlowComponents()`
@*/
PetscErrorCode TSVSHMMGetAdaptSlowComponents(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(flg, 2);
  PetscUseMethod(ts, "TSVSHMMGetAdaptSlowComponents_C", (TS, PetscBool *), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetAdaptGlobalEstimate - Makes `TSVSHMMSetAdapt()` estimate the error at each sampled time from a comparison carried through the run

   Logically Collective

   Input Parameters:
+  ts  - the `TS` of type `TSVSHMM`
-  flg - `PETSC_TRUE` to carry the comparison, `PETSC_FALSE` (the default) not to

   Options Database Key:
.  -ts_vshmm_adapt_global_estimate <true,false> - carry the comparison

   Notes:
   Each macro step's error estimate compares the step with the same step run with every error term
   doubled, both from the step's start: it measures the error the step makes (a local error), and
   the accuracy control adds these up. An error made early can grow later (an amplitude error of a
   nonlinear fast oscillator shifts its frequency, and the phase drifts for the rest of the run) or
   be damped (a dissipative slow equation); their sum does not show either. With this option a second
   solution, started with the run, is advanced after every accepted macro step with that step's
   comparison parameters; its difference from the solution, converted with the error model as a
   step's comparison is, estimates the error at the sampled time itself, propagated by the dynamics.
   It is reported in the statistics (`TSVSHMMStatistics` fields global_estimate and
   global_estimate_max), by -ts_view and -info; `TSGetTimeError()` (n = 0) gives it as a vector (the
   solution's estimated error, component by component). Where it exceeds twice the tolerance a
   warning says so, once per solve. Where it exceeds 4 times the sum of the steps' estimates (errors
   the dynamics grew) and the part of the tolerance a drift growing as the square of the time may
   have taken by then, the later macro steps' shares of the tolerance shrink by that ratio;
   otherwise it steers nothing (the Duffing oscillator's state: 1.3-2.0 tolerances off instead of
   2.1-5.6). It costs one more comparison run per macro step (5-77% more split evaluations on the
   measured problems). Its reliability is measured in docs/accuracy.md (section 21): it saw a phase
   drift the steps' estimates missed
   (5.6 tolerances off, estimated 6.9, the steps' sum 0.34) and follows the error over time where
   their sum only grows, but it is not a bound: below half the true error at 10 of 102 sampled
   times of the measured suite and in 11 of 39 outside runs (their sum: 7 and 2).

   Needs `TSVSHMMSetAdapt()`: the comparison doubles the error terms of the parameters the accuracy
   control chooses (an error at set-up otherwise).

   Level: advanced

.seealso: `TSVSHMM`, `TSVSHMMSetAdapt()`, `TSVSHMMGetAdaptGlobalEstimate()`, `TSVSHMMGetStatistics()`, `TSGetTimeError()`
@*/
PetscErrorCode TSVSHMMSetAdaptGlobalEstimate(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveBool(ts, flg, 2);
  PetscTryMethod(ts, "TSVSHMMSetAdaptGlobalEstimate_C", (TS, PetscBool), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetAdaptGlobalEstimate - Tells whether `TSVSHMMSetAdapt()` carries a comparison through the run to estimate the error at each sampled time

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  flg - `PETSC_TRUE` if it does

   Level: advanced

.seealso: `TSVSHMM`, `TSVSHMMSetAdaptGlobalEstimate()`
@*/
PetscErrorCode TSVSHMMGetAdaptGlobalEstimate(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(flg, 2);
  PetscUseMethod(ts, "TSVSHMMGetAdaptGlobalEstimate_C", (TS, PetscBool *), (ts, flg));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetScaleSeparations - Tells TSVSHMM how far apart the time scales of consecutive levels are, where the application knows it

   Logically Collective

   Input Parameters:
+  ts - the `TS` of type `TSVSHMM`
.  n - the number of separations: the number of scales less one (checked at set-up)
-  S - the separations, positive, slowest pair first: S_l is the rate of the slowest mode of scale
       l+1 over the rate of the fastest mode of scale l

   Options Database Key:
.  -ts_vshmm_scale_separations <S1,...,SK> - the separations

   Notes:
   Without them TSVSHMM takes S_l from the levels' estimated spectral radii: the fastest mode of
   each level. That is the separation where each scale has one rate (the paper's examples), but
   where a scale spans a band of rates (a cluster of Fourier modes) the separation that sets the
   averaging error is that of its slowest mode, which can be far smaller. For component splits
   (`TSRHSSplitSetIS()` with the components each scale writes) TSVSHMM also estimates the slowest
   rate of each faster level's own components itself; with additive splits it cannot. With
   `TSVSHMMSetAdapt()` the separations shape the error model: a time ratio r_l of the level pair
   beyond S_l slows the faster scale below the slower one, and the averaging error stops growing
   with r_l there (it saturates); the model knows this, so the error estimate stays true beyond
   it. The separation check (`TSVSHMMSetSeparationCheck()`) uses them too. The spectral examples
   pass the clusters' figures from `VSHMMSpectralGetScaleSeparations()`.

   Level: advanced

.seealso: `TSVSHMM`, `TSVSHMMGetScaleSeparations()`, `TSVSHMMSetAdapt()`, `TSVSHMMSetSeparationCheck()`
@*/
PetscErrorCode TSVSHMMSetScaleSeparations(TS ts, PetscInt n, const PetscReal S[])
{
  MPI_Comm comm;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)ts);
  PetscCheck(n >= 1, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_scale_separations needs at least one value (one per pair of consecutive scales), got %" PetscInt_FMT, n);
  VSHMMValidPointer(S, 3);
  for (PetscInt i = 0; i < n; ++i) PetscCheck(std::isfinite(S[i]) && S[i] > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Scale separation %" PetscInt_FMT " is %g: -ts_vshmm_scale_separations values must be positive and finite", i + 1, (double)S[i]);
  PetscTryMethod(ts, "TSVSHMMSetScaleSeparations_C", (TS, PetscInt, const PetscReal[]), (ts, n, S));
  PetscFunctionReturn(0);
}

/*@C
   TSVSHMMGetScaleSeparations - Gets the scale separations set with `TSVSHMMSetScaleSeparations()`

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameters:
+  n - the number of separations (0 if none were set)
-  S - the separations, slowest pair first (owned by the TS; do not free)

   Level: advanced

.seealso: `TSVSHMM`, `TSVSHMMSetScaleSeparations()`
@*/
PetscErrorCode TSVSHMMGetScaleSeparations(TS ts, PetscInt *n, const PetscReal *S[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSVSHMMGetScaleSeparations_C", (TS, PetscInt *, const PetscReal *[]), (ts, n, S));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetSeparationCheck - Sets what TSVSHMM does at set-up where the time scales of its RHS splits are not separated

   Logically Collective

   Input Parameters:
+  ts    - the `TS` of type `TSVSHMM`
-  check - `TSVSHMM_SEPARATION_OFF`, `TSVSHMM_SEPARATION_WARN` (the default) or `TSVSHMM_SEPARATION_ERROR`

   Options Database Key:
.  -ts_vshmm_check_separation <off,warn,error> - choose

   Notes:
   The check estimates the spectral radius of each level's field (the scales 0..l) and compares
   consecutive levels; for component splits it also estimates the slowest rate of each faster
   level's own components (the block of its Jacobian on them: a transport block, such as a fine
   finite-volume region, shows its slow crossing time there), and the separation of a pair is the
   smaller figure; separations set with `TSVSHMMSetScaleSeparations()` replace both. VSHMM samples
   the faster scales statistically; if no pair of levels is at
   least 10 apart, the components the faster splits write are part of the answer (for example a
   multirate finite-volume scheme whose fast region is twice as fast as the slow one) and VSHMM
   would return a wrong answer without knowing it. Then the check warns (on the warnings viewer,
   stderr by default: `TSVSHMMSetWarningsViewer()`) or stops with an
   error, and `TSVSHMMSetAdapt()` takes no savings.

   The check also measures how fast each faster level's own splits depend on time explicitly
   (||dF/dt|| / (rho ||X||)): VSHMM advances one clock for every level, so the savings factors make
   a level see that dependence r_0 ... r_{l-1} times faster than it is, and where that comes within
   a tenth of the level's spectral radius (a fast forcing sin(t / eps) in a fast split) the check
   warns or stops in the same way; `TSVSHMMSetAdapt()` keeps its time ratios below that bound.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetAdapt()`, `TSVSHMMSetStabilityCheck()`
@*/
PetscErrorCode TSVSHMMSetSeparationCheck(TS ts, TSVSHMMSeparationCheck check)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveEnum(ts, check, 2);
  PetscCheck(check >= TSVSHMM_SEPARATION_OFF && check <= TSVSHMM_SEPARATION_ERROR, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_check_separation (TSVSHMMSetSeparationCheck()): %d is not one of off, warn, error", (int)check);
  PetscTryMethod(ts, "TSVSHMMSetSeparationCheck_C", (TS, TSVSHMMSeparationCheck), (ts, check));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMGetSeparationCheck - Gets what TSVSHMM does where the time scales are not separated

   Not Collective

   Input Parameter:
.  ts - the `TS` of type `TSVSHMM`

   Output Parameter:
.  check - the setting

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetSeparationCheck()`
@*/
PetscErrorCode TSVSHMMGetSeparationCheck(TS ts, TSVSHMMSeparationCheck *check)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  VSHMMValidPointer(check, 2);
  PetscUseMethod(ts, "TSVSHMMGetSeparationCheck_C", (TS, TSVSHMMSeparationCheck *), (ts, check));
  PetscFunctionReturn(0);
}

/*@
   TSVSHMMSetWarningsViewer - Sets where TSVSHMM writes the warnings a user must see without asking

   Logically Collective

   Input Parameters:
+  ts     - the `TS` of type `TSVSHMM`
-  viewer - an ASCII `PetscViewer` on the communicator of ts (for example from
            `PetscViewerASCIIOpen()`), or NULL for no warnings at all

   Options Database Key:
.  -ts_vshmm_warnings_viewer <stderr,none,ascii:file> - stderr (the default), none, or a PETSc
   ASCII viewer: ascii:<file> (written from the start; ascii:<file>::append appends), ascii alone
   for stdout

   Notes:
   The warnings are those of the stability check (`TSVSHMMSetStabilityCheck()`: a level's
   largest step beyond its stable step, though damped over a macro step), of the separation
   check (`TSVSHMMSetSeparationCheck()`), of the accuracy control (`TSVSHMMSetAdapt()`: a macro
   step accepted far above its share of the tolerance) and of a split that produced Inf or NaN
   (the solve stops with `TS_DIVERGED_STEP_REJECTED` under -ts_error_if_step_fails false). They
   are printed by the first rank. Errors are raised as PETSc errors whatever the viewer;
   `PetscInfo()` (-info) gives the notes of every check; the statistics
   (`TSVSHMMGetStatistics()`) count the stability warnings. The TS keeps a reference to the
   viewer. By default the warnings go to `PETSC_STDERR` as it is when each is printed (so a
   program that redirects `PETSC_STDERR` gets them there); -ts_vshmm_warnings_viewer stderr goes
   back to that default.

   Level: intermediate

.seealso: `TSVSHMM`, `TSVSHMMSetStabilityCheck()`, `TSVSHMMSetSeparationCheck()`, `PetscViewerASCIIOpen()`
@*/
PetscErrorCode TSVSHMMSetWarningsViewer(TS ts, PetscViewer viewer)
{
  PetscBool ascii;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 1);
  if (viewer) {
    VSHMMValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
    PetscCheckSameComm(ts, 1, viewer, 2);
    PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
    PetscCheck(ascii, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "-ts_vshmm_warnings_viewer (TSVSHMMSetWarningsViewer()): the warnings viewer must be an ASCII viewer (stderr, none or ascii:<file>), not %s", ((PetscObject)viewer)->type_name);
  }
  PetscTryMethod(ts, "TSVSHMMSetWarningsViewer_C", (TS, PetscViewer), (ts, viewer));
  PetscFunctionReturn(0);
}
