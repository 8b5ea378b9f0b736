/*
  TSVSHMM: the variable step size heterogeneous multiscale method for several time scales.

  The PETSc glue: set-up from the TS's RHS splits, one macro step per TSStep, options, view.
  The numerical core (kernel, step schedule, Runge-Kutta stepping) lives in src/core.
*/
#include "vshmmimpl.hpp"

#include "vshmmoptions.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

const char *const TSVSHMMKernelTypes[] = {"cosine", "constant", "polynomial", "exponential", "TSVSHMMKernelType", "TSVSHMM_KERNEL_", nullptr};

static constexpr PetscReal kTimeBack = 1e-9; /* of DeltaT: a macro step starting this far before the last one's end starts a new run */

static vshmm::KernelType CoreKernelType(TSVSHMMKernelType type)
{
  switch (type) {
  case TSVSHMM_KERNEL_CONSTANT:
    return vshmm::KernelType::Constant;
  case TSVSHMM_KERNEL_POLYNOMIAL:
    return vshmm::KernelType::Polynomial;
  case TSVSHMM_KERNEL_EXPONENTIAL:
    return vshmm::KernelType::Exponential;
  default:
    return vshmm::KernelType::Cosine;
  }
}

/* ------------------------------------------------------------------------------------------ */
/* Set-up                                                                                       */

static PetscErrorCode TSVSHMMTearDown_Private(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  for (VSHMMSplit &split : vs->splits) {
    PetscCall(VecDestroy(&split.F));
    PetscCall(VecScatterDestroy(&split.scatter));
  }
  vs->splits.clear();
  vs->level_end.clear();
  PetscCall(VecDestroy(&vs->Y));
  PetscCall(VecDestroy(&vs->X0));
  for (Vec &v : vs->radius_vecs) PetscCall(VecDestroy(&v));
  vs->radius_vecs.clear();
  for (Vec &v : vs->fastest_phase) PetscCall(VecDestroy(&v));
  vs->fastest_phase.clear();
  for (Vec &v : vs->beat_phase) PetscCall(VecDestroy(&v));
  vs->beat_phase.clear();
  vs->beat_omega.clear();
  vs->beat_level.clear();
  for (Vec &k : vs->K) PetscCall(VecDestroy(&k));
  vs->K.clear();
  vs->schedule.reset();
  PetscCall(TSVSHMMAdaptReset_Private(ts));
  vs->tableau.reset();
  vs->kernel.reset();
  PetscFunctionReturn(0);
}

/* The TS's splits in creation order, as "a, b, c" for messages. */
static std::string SplitNames(TS ts)
{
  std::string s;
  for (TS_RHSSplitLink l = ts->tsrhssplit; l; l = l->next) s += std::string(s.empty() ? "" : ", ") + l->splitname;
  return s.empty() ? std::string("none") : s;
}

/* The splits in scale order (slowest first) and where each scale's group of splits ends: one
   split per scale in creation order, or the scales of -ts_vshmm_splits ("a,b+c,d"). */
static PetscErrorCode OrderSplits(TS ts, std::vector<TS_RHSSplitLink> &links, std::vector<PetscInt> &scale_end)
{
  TS_VSHMM *vs   = (TS_VSHMM *)ts->data;
  MPI_Comm  comm = PetscObjectComm((PetscObject)ts);

  PetscFunctionBegin;
  links.clear();
  scale_end.clear();
  PetscCheck(ts->num_rhs_splits >= 2, comm, PETSC_ERR_ARG_WRONGSTATE, "TSVSHMM needs at least two RHS splits, one per time scale, but the TS has %" PetscInt_FMT ": declare each scale with TSRHSSplitSetIS() and TSRHSSplitSetRHSFunction()", ts->num_rhs_splits);
  if (vs->split_order.empty()) {
    for (TS_RHSSplitLink l = ts->tsrhssplit; l; l = l->next) {
      links.push_back(l);
      scale_end.push_back((PetscInt)links.size());
    }
  } else {
    for (const std::string &scale : vs->split_order) {
      std::stringstream in(scale);
      std::string       name;
      while (std::getline(in, name, '+')) {
        TS_RHSSplitLink found = nullptr;
        PetscCheck(!name.empty(), comm, PETSC_ERR_ARG_WRONG, "-ts_vshmm_splits (TSVSHMMSetSplitOrder()): scale '%s' has an empty split name", scale.c_str());
        for (TS_RHSSplitLink l = ts->tsrhssplit; l; l = l->next)
          if (name == l->splitname) found = l;
        PetscCheck(found, comm, PETSC_ERR_ARG_WRONG, "Unknown split '%s' in -ts_vshmm_splits (TSVSHMMSetSplitOrder()): the TS's splits are %s", name.c_str(), SplitNames(ts).c_str());
        for (TS_RHSSplitLink l : links) PetscCheck(l != found, comm, PETSC_ERR_ARG_WRONG, "Split '%s' appears twice in -ts_vshmm_splits (TSVSHMMSetSplitOrder()): list every split once", name.c_str());
        links.push_back(found);
      }
      PetscCheck(!scale.empty() && scale.back() != '+', comm, PETSC_ERR_ARG_WRONG, "-ts_vshmm_splits (TSVSHMMSetSplitOrder()): scale '%s' has an empty split name", scale.c_str());
      scale_end.push_back((PetscInt)links.size());
    }
    PetscCheck((PetscInt)links.size() == ts->num_rhs_splits, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_splits (TSVSHMMSetSplitOrder()) names %d splits but the TS has %" PetscInt_FMT " (%s): list every split once, slowest scale first (a+b puts two splits in one scale)",
               (int)links.size(), ts->num_rhs_splits, SplitNames(ts).c_str());
    PetscCheck(scale_end.size() >= 2, comm, PETSC_ERR_ARG_WRONG, "-ts_vshmm_splits (TSVSHMMSetSplitOrder()) puts every split in one scale: TSVSHMM needs at least two scales");
  }
  for (TS_RHSSplitLink l : links) {
    TSRHSFunction f;

    PetscCall(TSGetRHSFunction(l->ts, nullptr, &f, nullptr));
    PetscCheck(f, comm, PETSC_ERR_ARG_WRONGSTATE, "Split '%s' has no right-hand-side function: call TSRHSSplitSetRHSFunction()", l->splitname);
  }
  PetscFunctionReturn(0);
}

/* How a split's output is added into a full vector: in place (its IS is a contiguous run of
   locally owned components on every rank) or by a scatter. */
static PetscErrorCode SetUpSplit(TS ts, TS_RHSSplitLink link, VSHMMSplit &split)
{
  Vec             X    = ts->vec_sol;
  MPI_Comm        comm = PetscObjectComm((PetscObject)X);
  const PetscInt *idx;
  PetscInt        nis, rstart, rend;
  VecType         vtype;
  int             flags[2];

  PetscFunctionBegin;
  split.name  = link->splitname;
  split.subts = link->ts;
  split.is    = link->is;
  PetscCall(ISGetLocalSize(split.is, &nis));
  PetscCall(VecGetOwnershipRange(X, &rstart, &rend));
  PetscInt N, range[2]; /* the IS's smallest and largest component over the ranks (the max of -min and max) */
  PetscCall(VecGetSize(X, &N));
  PetscCall(ISGetMinMax(split.is, &range[0], &range[1])); /* PETSC_MAX_INT, PETSC_MIN_INT where empty */
  range[0] = -range[0];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 2, MPIU_INT, MPI_MAX, comm));
  PetscCheck(range[1] < N && -range[0] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Split '%s': its IS (TSRHSSplitSetIS()) names component %" PetscInt_FMT ", outside the solution's components 0..%" PetscInt_FMT, split.name.c_str(), range[1] >= N ? range[1] : -range[0], N - 1);
  PetscCall(ISGetIndices(split.is, &idx));
  bool contiguous = true;
  for (PetscInt i = 1; i < nis && contiguous; ++i) contiguous = idx[i] == idx[0] + i;
  bool owned   = nis == 0 || (idx[0] >= rstart && idx[0] + nis <= rend);
  split.offset = nis ? idx[0] - rstart : 0;
  PetscCall(ISRestoreIndices(split.is, &idx));
  flags[0] = contiguous && owned;
  flags[1] = flags[0] && nis == rend - rstart;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_LAND, comm));
  split.local    = flags[0] ? PETSC_TRUE : PETSC_FALSE;
  split.additive = flags[1] ? PETSC_TRUE : PETSC_FALSE;

  PetscCall(VecCreate(comm, &split.F));
  PetscCall(VecSetSizes(split.F, nis, PETSC_DETERMINE));
  PetscCall(VecGetType(X, &vtype));
  PetscCall(VecSetType(split.F, vtype));
  if (!split.local) {
    PetscCall(VecScatterCreate(split.F, nullptr, X, split.is, &split.scatter));
    /* a component named twice (on one rank or on two) would receive the split's value twice */
    Vec       count;
    PetscInt  at;
    PetscReal most;
    PetscCall(VecDuplicate(X, &count));
    PetscCall(VecSet(split.F, 1.0));
    PetscCall(VecScatterBegin(split.scatter, split.F, count, ADD_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(split.scatter, split.F, count, ADD_VALUES, SCATTER_FORWARD));
    PetscCall(VecMax(count, &at, &most));
    PetscCall(VecDestroy(&count));
    PetscCheck(most <= 1, comm, PETSC_ERR_ARG_WRONG, "Split '%s': its IS (TSRHSSplitSetIS()) names component %" PetscInt_FMT " %d times (on one rank or on several): each component once", split.name.c_str(), at, (int)most);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ParameterError(MPI_Comm comm, const char *what)
{
  SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM: %s", what);
}

/* The inner Runge-Kutta tableau, taken from PETSc's TSRK registry. */
static PetscErrorCode GetRKTableau(MPI_Comm comm, const std::string &type, std::unique_ptr<vshmm::Tableau> &tab)
{
  TS               rk;
  PetscInt         s, p;
  const PetscReal *A, *b, *c;
  PetscErrorCode   ierr;

  PetscFunctionBegin;
  PetscCall(TSCreate(PETSC_COMM_SELF, &rk));
  PetscCall(TSSetType(rk, TSRK));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  ierr = TSRKSetType(rk, type.c_str());
  PetscCall(PetscPopErrorHandler());
  if (ierr) {
    PetscCall(TSDestroy(&rk));
    SETERRQ(comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown inner Runge-Kutta type '%s' in -ts_vshmm_rk_type (TSVSHMMSetRKType()): use a TSRK type, one of 1fe, 2a, 2b, 3, 3bs, 4, 5f, 5dp, 5bs, 6vr, 7vr, 8vr, or one registered with TSRKRegister()", type.c_str());
  }
  PetscCall(TSRKGetTableau(rk, &s, &A, &b, &c, nullptr, nullptr, nullptr, nullptr));
  PetscCall(TSRKGetOrder(rk, &p));
  try {
    tab = std::make_unique<vshmm::Tableau>(type, (int)p, (int)s, std::vector<double>(A, A + s * s), std::vector<double>(b, b + s), std::vector<double>(c, c + s));
  } catch (const std::exception &e) {
    PetscCall(TSDestroy(&rk));
    SETERRQ(comm, PETSC_ERR_ARG_WRONG, "-ts_vshmm_rk_type %s: %s", type.c_str(), e.what());
  }
  PetscCall(TSDestroy(&rk));
  PetscFunctionReturn(0);
}

/* PETSc features that TSVSHMM does not support are refused at set-up, before any work, rather
   than accepted and ignored or failing in mid-run with PETSc's generic "No method ...":
   - an adaptive TSAdapt: the macro step is the sampling interval DeltaT (the TS time step), fixed;
     accuracy control is -ts_vshmm_adapt, which chooses the micro step and savings factors;
   - events (TSSetEventHandler()): locating an event needs a dense output of every component,
     which VSHMM does not have (only the sampled states are accurate for the slow variables);
   - adjoint and forward sensitivities, quadrature in the forward run, TSTrajectory: they need
     the derivative of the macro step (its stages), which VSHMM does not form;
   - pre-stage and post-stage hooks: a macro step has no stages of its own (see TSStep_VSHMM()). */
static PetscErrorCode TSVSHMMCheckSupported_Private(TS ts)
{
  MPI_Comm  comm = PetscObjectComm((PetscObject)ts);
  PetscBool none = PETSC_TRUE;

  PetscFunctionBegin;
  if (ts->adapt && ((PetscObject)ts->adapt)->type_name) PetscCall(PetscObjectTypeCompare((PetscObject)ts->adapt, TSADAPTNONE, &none));
  PetscCheck(none, comm, PETSC_ERR_SUP, "TSVSHMM does not support the time step adaptivity TSAdapt '%s' (-ts_adapt_type): its macro step is the sampling interval DeltaT, the TS time step, and stays fixed. Use -ts_adapt_type none (the default of TSVSHMM); for accuracy control use -ts_vshmm_adapt with -ts_rtol/-ts_atol (TSVSHMMSetAdapt())",
             ((PetscObject)ts->adapt)->type_name);
  PetscCheck(!ts->event, comm, PETSC_ERR_SUP, "TSVSHMM does not support events (TSSetEventHandler()): only the sampled states are accurate for the slow variables, so an event cannot be located within a macro step. Detect it in a TSMonitor or post-step function on the sampled states instead");
  PetscCheck(!ts->trajectory, comm, PETSC_ERR_SUP, "TSVSHMM does not support TSTrajectory (TSSetSaveTrajectory(), -ts_save_trajectory) or the adjoint solve (TSAdjointSolve()), which needs it: VSHMM does not form the derivative of its macro step. Use a TSRK type for adjoint sensitivities");
  PetscCheck(!ts->vecs_sensi, comm, PETSC_ERR_SUP, "TSVSHMM does not support adjoint sensitivities (TSSetCostGradients(), TSAdjointSolve()): VSHMM does not form the derivative of its macro step. Use a TSRK type for adjoint sensitivities");
  PetscCheck(!ts->forward_solve && !ts->mat_sensip, comm, PETSC_ERR_SUP, "TSVSHMM does not support forward sensitivities (TSForwardSetSensitivities()): VSHMM does not form the derivative of its macro step. Use a TSRK type for forward sensitivities");
  PetscCheck(!ts->costintegralfwd, comm, PETSC_ERR_SUP, "TSVSHMM does not support evaluating a cost integral in the forward run (TSCreateQuadratureTS() with fwd = PETSC_TRUE): integrate the quantity in a TSMonitor on the sampled states instead");
  TSIFunction ifunction = nullptr;
  DM          dm;
  PetscCall(TSGetDM(ts, &dm));
  PetscCall(DMTSGetIFunction(dm, &ifunction, nullptr));
  PetscCheck(!ifunction, comm, PETSC_ERR_ARG_INCOMP, "TSVSHMM is an explicit integrator: it steps the RHS splits (TSRHSSplitSetRHSFunction()) and cannot use an implicit function definition (TSSetIFunction()), which it would ignore. Give the right-hand side with TSSetRHSFunction() and its splits, or use an implicit TS type (-ts_type arkimex, bdf)");
  PetscCheck(!ts->prestage && !ts->poststage, comm, PETSC_ERR_SUP, "TSVSHMM does not call pre-stage or post-stage functions (TSSetPreStage(), TSSetPostStage()): a macro step has no stages of its own, its inner Runge-Kutta stages belong to the levels' fields. Use TSSetPreStep() / TSSetPostStep(), called around every macro step");
  PetscFunctionReturn(0);
}

/* Fixed parameters whose mean micro cycle, dt (1 + alpha_1 + ... + alpha_K), is longer than the
   shortest kernel period DeltaT / m_j: less than one micro cycle per period, so the mesoscopic
   steps are cut at the period's end and the savings factors do not act as given, and the kernel
   does not average (the dissipative example with savings factors 1000, 10 and the micro step
   1e-4, one cycle of 0.1 per macro step of 0.1: xi(2) 4.8% off, against 0.6% with 100, 10).
   Said at set-up; -ts_vshmm_adapt keeps at least five cycles per macro step itself. */
static PetscErrorCode CheckCycleLength(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (vs->adapt || vs->savings.empty()) PetscFunctionReturn(0);
  const PetscReal dt    = vs->micro_dt > 0 ? vs->micro_dt : ts->time_step / kDefaultMicroStepsPerMacroStep;
  PetscReal       cycle = dt;
  PetscInt        m     = 1;
  for (PetscReal a : vs->savings_used) cycle += a * dt;
  for (PetscInt mj : vs->subintervals_used) m = PetscMax(m, mj);
  const PetscReal period = ts->time_step / (PetscReal)m;
  if (!(cycle > period)) PetscFunctionReturn(0);
  PetscCall(TSVSHMMWarn_Private(ts,
                                "TSVSHMM warning: the savings factors (-ts_vshmm_savings_factors) with the micro step dt = %g make a mean micro cycle dt (1 + alpha_1 + ... + alpha_K) = %g, longer than the kernel's period DeltaT / m = %g "
                                "(sampling interval %g%s): %g micro cycles per period, so the mesoscopic steps are cut at the period's end, the savings factors do not act as given and the kernel does not average. "
                                "Use savings factors or a micro step (-ts_vshmm_micro_dt) that give many cycles per period, a longer sampling interval (-ts_dt), or -ts_vshmm_adapt.\n",
                                (double)dt, (double)cycle, (double)period, (double)ts->time_step, m > 1 ? ", subintervals" : "", (double)(period / cycle)));
  PetscFunctionReturn(0);
}

/* What a run starts from, at set-up and where the time is set back (TSStep_VSHMM()): the levels'
   spectra and the checks at the present state, and the accuracy control. */
static PetscErrorCode StartRun(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  vs->spectra_time       = PETSC_MIN_REAL;
  vs->own_rates_time     = PETSC_MIN_REAL;
  vs->time_dependent     = PETSC_FALSE;
  vs->time_rates_checked = PETSC_FALSE;
  vs->level_time_rate_max.clear();
  vs->beat_bound.clear(); /* a beat found in an earlier run does not bound this one's savings */
  vs->beat_effect.clear();
  vs->beat_slowed.clear();
  vs->beat_watch.clear();
  vs->beat_warned           = PETSC_FALSE;
  vs->beats_checked         = PETSC_FALSE;
  vs->cost_warned           = PETSC_FALSE; /* this run's work against single-rate steps (TSVSHMMAdaptCheckCost_Private()) */
  vs->run_largest_ratio     = 1;
  vs->run_start_single_rate = vs->single_rate_evaluations;
  vs->run_start_work        = TSVSHMMWork_Private(vs);
  for (Vec &v : vs->radius_vecs) PetscCall(VecDestroy(&v)); /* the power method's start vectors */
  vs->radius_vecs.clear();
  if (vs->check_stability) PetscCall(TSVSHMMCheckStability_Private(ts));
  PetscCall(CheckCycleLength(ts));
  PetscCall(TSVSHMMCheckSeparation_Private(ts));
  PetscCall(TSVSHMMAdaptSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSSetUp_VSHMM(TS ts)
{
  TS_VSHMM                    *vs   = (TS_VSHMM *)ts->data;
  MPI_Comm                     comm = PetscObjectComm((PetscObject)ts);
  std::vector<TS_RHSSplitLink> links;

  PetscFunctionBegin;
  PetscCall(TSVSHMMTearDown_Private(ts));
  PetscCall(TSVSHMMCheckSupported_Private(ts));
  std::vector<PetscInt> scale_end;
  PetscCall(OrderSplits(ts, links, scale_end));
  const PetscInt nscales = (PetscInt)scale_end.size(), K = nscales - 1;

  /* Method parameters */
  if (vs->savings.empty()) vs->savings_used.assign(K, 1.0);
  else {
    PetscCheck((PetscInt)vs->savings.size() == K, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_savings_factors (TSVSHMMSetSavingsFactors()) has %d values but there are %" PetscInt_FMT " scales (RHS splits), so it needs %" PetscInt_FMT ": one savings factor alpha_j per scale except the fastest, slowest first",
               (int)vs->savings.size(), nscales, K);
    vs->savings_used = vs->savings;
  }
  PetscCheck(vs->separations.empty() || (PetscInt)vs->separations.size() == K, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_scale_separations (TSVSHMMSetScaleSeparations()) has %d values but there are %" PetscInt_FMT " scales (RHS splits), so it needs %" PetscInt_FMT ": one separation per pair of consecutive scales, slowest pair first",
             (int)vs->separations.size(), nscales, K);
  if (vs->subintervals.empty()) vs->subintervals_used.assign(K, 1);
  else {
    PetscCheck((PetscInt)vs->subintervals.size() == K, comm, PETSC_ERR_ARG_SIZ, "-ts_vshmm_subintervals (TSVSHMMSetSubintervals()) has %d values but there are %" PetscInt_FMT " scales (RHS splits), so it needs %" PetscInt_FMT ": one subinterval count m_j >= 1 per scale except the fastest, slowest first",
               (int)vs->subintervals.size(), nscales, K);
    vs->subintervals_used = vs->subintervals;
  }
  PetscCheck(!vs->adapt_global || vs->adapt, comm, PETSC_ERR_ARG_INCOMP, "-ts_vshmm_adapt_global_estimate (TSVSHMMSetAdaptGlobalEstimate()) needs -ts_vshmm_adapt (TSVSHMMSetAdapt()): the carried comparison doubles the error terms of the parameters the accuracy control chooses");
  PetscCheck(std::isfinite(ts->time_step) && ts->time_step > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM: the TS time step (the sampling interval DeltaT) is %g: set a positive one with TSSetTimeStep() or -ts_dt", (double)ts->time_step);
  PetscCheck(vs->micro_dt == 0.0 || vs->micro_dt > kMinMicroStepFraction * ts->time_step, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_micro_dt (TSVSHMMSetMicroStep()) is %g, below the time resolution of the sampling interval DeltaT = %g: the micro step must exceed %g DeltaT",
             (double)vs->micro_dt, (double)ts->time_step, (double)kMinMicroStepFraction);
  PetscCheck(vs->micro_dt == 0.0 || vs->micro_dt < ts->time_step, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_micro_dt (TSVSHMMSetMicroStep()) is %g, not smaller than the sampling interval DeltaT = %g (the TS time step, -ts_dt): the micro step must be a small fraction of DeltaT",
             (double)vs->micro_dt, (double)ts->time_step);

  /* Kernel */
  if (vs->kernel_order != PETSC_DEFAULT && vs->kernel_type != TSVSHMM_KERNEL_POLYNOMIAL) {
    std::unique_ptr<vshmm::Kernel> probe = vshmm::Kernel::create(CoreKernelType(vs->kernel_type));
    PetscCheck(probe->order() == vs->kernel_order, comm, PETSC_ERR_ARG_INCOMP, "-ts_vshmm_kernel_order %" PetscInt_FMT " does not apply to the %s kernel, whose order is fixed; only the polynomial kernel takes an order (0..%d)", vs->kernel_order, TSVSHMMKernelTypes[vs->kernel_type], vshmm::Kernel::kMaxPolynomialOrder);
  }
  try {
    vs->kernel = vshmm::Kernel::create(CoreKernelType(vs->kernel_type), vs->kernel_order == PETSC_DEFAULT ? 1 : (int)vs->kernel_order);
  } catch (const std::exception &e) {
    PetscCall(ParameterError(comm, e.what()));
  }
  PetscCall(GetRKTableau(comm, vs->rk_type, vs->tableau));

  /* Work vectors and scales */
  PetscCheck(ts->vec_sol, comm, PETSC_ERR_ARG_WRONGSTATE, "TSVSHMM: call TSSetSolution() before TSSetUp()");
  PetscCall(VecDuplicate(ts->vec_sol, &vs->Y));
  PetscCall(VecDuplicate(ts->vec_sol, &vs->X0));
  vs->K.assign(vs->tableau->stages, nullptr);
  for (Vec &k : vs->K) PetscCall(VecDuplicate(ts->vec_sol, &k));
  vs->splits.resize(links.size());
  for (size_t k = 0; k < links.size(); ++k) PetscCall(SetUpSplit(ts, links[k], vs->splits[k]));
  vs->level_end = scale_end;

  vs->level_events.resize(nscales);
  for (PetscInt l = 0; l < nscales; ++l) PetscCall(TSVSHMMGetLevelEvent_Private(l, &vs->level_events[l]));
  PetscCall(TSVSHMMResetStatistics(ts));
  PetscCall(TSVSHMMCheckSplitsSum_Private(ts));
  PetscCall(StartRun(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSReset_VSHMM(TS ts)
{
  PetscFunctionBegin;
  PetscCall(TSVSHMMTearDown_Private(ts));
  PetscFunctionReturn(0);
}

/* A parameter changed after set-up: the next TSSetUp() (TSSolve() calls it) sets up again. */
static PetscErrorCode TSVSHMMInvalidateSetUp_Private(TS ts)
{
  PetscFunctionBegin;
  if (ts->setupcalled) {
    PetscCall(TSVSHMMTearDown_Private(ts));
    ts->setupcalled = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* One macro step                                                                               */

/*
  TSStep_VSHMM - one macro step of length DeltaT (the TS time step) from the sampled state at
  t0 = ts->ptime: micro cycles of the full field and the mesoscopic steps of the slower levels
  until t0 + DeltaT exactly (TSVSHMMRunMacroStep_Private(), or TSVSHMMAdaptStep_Private() with
  -ts_vshmm_adapt, which may also try and reject trial steps).

  - ts->vec_sol is advanced in place to the sampled state at t0 + DeltaT; vs->X0 keeps the one at
    t0 (for TSInterpolate_VSHMM() and to roll back a failed step).
  - ts->ptime becomes t0 + DeltaT (ts->max_time exactly for a last step that ends on it);
    TSStep() itself sets ts->ptime_prev and counts ts->steps. ts->time_step is never changed.
  - ts->reason is left alone on success (TSSolve() sets the converged reasons). When a split
    returns Inf or NaN anywhere in the macro step, ts->vec_sol is restored to the state at t0,
    ts->ptime stays t0 and ts->reason = TS_DIVERGED_STEP_REJECTED, or an error is raised with
    -ts_error_if_step_fails (one reduction per macro step finds the earliest such output).
  - TS_EXACTFINALTIME_MATCHSTEP is handled here: other types leave it to TSAdaptChoose(), which
    shortens the step to end on the final time, but TSVSHMM uses no TSAdapt (DeltaT is the
    sampling interval), so the last macro step is shortened here instead, without changing
    ts->time_step: it is a macro step of the shorter length (its kernel periods shrink with it).
  - TSPreStage()/TSPostStage() are not called: a macro step has no stages of its own. Its
    thousands of inner Runge-Kutta stages belong to the fields G_l of the levels, not to the
    TS's right-hand side, and the stage states are not states of the TS's ODE. TSSetUp_VSHMM()
    refuses pre- and post-stage functions; TSPreStep()/TSPostStep() are called by TSSolve()
    around every macro step.
*/
static PetscErrorCode TSStep_VSHMM(TS ts)
{
  TS_VSHMM *vs   = (TS_VSHMM *)ts->data;
  MPI_Comm  comm = PetscObjectComm((PetscObject)ts);
  PetscReal t0 = ts->ptime, DeltaT = ts->time_step;
  PetscBool last = PETSC_FALSE;

  PetscFunctionBegin;
  if ((PetscInt)vs->splits.size() != ts->num_rhs_splits) { /* splits added after set-up */
    PetscCall(PetscInfo(ts, "The TS has %" PetscInt_FMT " RHS splits, %d at set-up: setting up again\n", ts->num_rhs_splits, (int)vs->splits.size()));
    PetscCall(TSSetUp_VSHMM(ts));
  }
  PetscCheck(std::isfinite(DeltaT) && DeltaT > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM: the TS time step (the sampling interval DeltaT) is %g: it must be positive", (double)DeltaT);
  if (ts->exact_final_time == TS_EXACTFINALTIME_MATCHSTEP && ts->max_time - (t0 + DeltaT) < 1e-10 * DeltaT) { /* the last macro step ends on the final time */
    DeltaT = ts->max_time - t0;
    last   = PETSC_TRUE;
  }
  if (vs->adapt && vs->adapt_ready && t0 < vs->adapt_end - kTimeBack * DeltaT) {
    /* the time was set back (TSSetTime() before another TSSolve(): an ensemble member, a restart):
       a new run, started as at set-up from the present state (the accuracy control kept the last
       run's parameters, error model, running sums and checks: a second solve from t = 0 took other
       parameters than the first, and its error estimate was the sum of both runs) */
    PetscCall(PetscInfo(ts, "The time was set back to %g (the last macro step ended at %g): the checks and the accuracy control start again\n", (double)t0, (double)vs->adapt_end));
    PetscCall(TSVSHMMAdaptReset_Private(ts));
    PetscCall(StartRun(ts));
  }
  const PetscReal dt = vs->micro_dt > 0 ? vs->micro_dt : ts->time_step / kDefaultMicroStepsPerMacroStep;
  PetscCheck(dt > kMinMicroStepFraction * DeltaT || last, comm, PETSC_ERR_ARG_OUTOFRANGE, "-ts_vshmm_micro_dt %g is below the time resolution of the macro step DeltaT = %g: the micro step must exceed %g DeltaT", (double)dt, (double)DeltaT, (double)kMinMicroStepFraction);
  if (vs->stability_interval > 0 && ts->steps > 0 && ts->steps % vs->stability_interval == 0) {
    PetscCall(TSVSHMMCheckStability_Private(ts));
    if (vs->adapt) PetscCall(TSVSHMMAdaptCheckSeparation_Private(ts));
  }
  if (!vs->adapt && (!vs->schedule || vs->schedule->microStep() != dt)) PetscCall(TSVSHMMCreateSchedule_Private(ts, dt, vs->schedule));
  PetscCall(VecCopy(ts->vec_sol, vs->X0));
  vs->nonfinite_split = -1;
  vs->nonfinite_time  = PETSC_MAX_REAL;
  if (vs->adapt) {
    PetscCall(TSVSHMMAdaptStep_Private(ts, t0, DeltaT));
    if (ts->reason == TS_DIVERGED_STEP_REJECTED) PetscFunctionReturn(0); /* no estimate: the solution stays at t0 */
  } else {
    vshmm::MacroStepCounts counts;
    PetscCall(TSVSHMMRunMacroStep_Private(ts, *vs->schedule, t0, DeltaT, ts->vec_sol, &counts));
    TSVSHMMAddCounts_Private(vs, counts);
    if (ts->steps == 0 || (vs->stability_interval > 0 && ts->steps % vs->stability_interval == 0)) PetscCall(TSVSHMMCheckFastQuantities_Private(ts, t0 + DeltaT)); /* after the first macro step and with the periodic checks */
  }
  vs->macro_steps++;

  /* One reduction per macro step: the earliest Inf/NaN of any split on any rank, in the order of
     evaluation (not of time: NaN from one rank reaches the splits of another at the same time t,
     in the next level's evaluation). */
  const int nsplits = (int)vs->splits.size();
  struct {
    double when;  /* the field evaluation's number, exact in a double */
    int    where; /* level * nsplits + split, or -1 */
  } fault = {(double)vs->nonfinite_evaluation, vs->nonfinite_split < 0 ? -1 : (int)(vs->nonfinite_level * nsplits + vs->nonfinite_split)};
  if (fault.where < 0) fault.when = PETSC_MAX_REAL; /* ranks without a fault lose the MINLOC */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fault, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm));
  if (fault.where >= 0 && fault.when < PETSC_MAX_REAL) {
    const int split = fault.where % nsplits, level = fault.where / nsplits;
    PetscReal t_fault = vs->nonfinite_split >= 0 && (double)vs->nonfinite_evaluation == fault.when ? vs->nonfinite_time : PETSC_MAX_REAL;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &t_fault, 1, MPIU_REAL, MPIU_MIN, comm)); /* the time of that evaluation */
    const char *name  = vs->splits[split].name.c_str();
    int         scale = 0; /* the scale the split belongs to */
    while (vs->level_end[scale] <= split) scale++;

    PetscCall(VecCopy(vs->X0, ts->vec_sol)); /* keep the last good sampled state */
    ts->reason = TS_DIVERGED_STEP_REJECTED;
    PetscCheck(!ts->errorifstepfailed, comm, PETSC_ERR_FP, "TSVSHMM: split '%s' (scale %d) produced Inf or NaN at t = %.17g, evaluated for level %d, in the macro step from t = %g to %g; the solution was left at t = %g (use -ts_error_if_step_fails false to stop with TS_DIVERGED_STEP_REJECTED instead)", name, scale, (double)t_fault, level, (double)t0, (double)(t0 + DeltaT), (double)t0);
    PetscCall(PetscInfo(ts, "Split '%s' (scale %d) produced Inf or NaN at t = %.17g, evaluated for level %d; stopping with TS_DIVERGED_STEP_REJECTED at t = %g\n", name, scale, (double)t_fault, level, (double)t0));
    PetscCall(TSVSHMMWarn_Private(ts, "TSVSHMM: split '%s' (scale %d) produced Inf or NaN at t = %.17g, evaluated for level %d; the solve stops with TS_DIVERGED_STEP_REJECTED at t = %g\n", name, scale, (double)t_fault, level, (double)t0));
    PetscFunctionReturn(0);
  }
  { /* what a single-rate TSRK of the same tableau takes over this macro step: at its micro step, or
       with -ts_vshmm_adapt at the largest step the bounds allow (SingleRateStep()) */
    const PetscReal h = vs->adapt ? PetscMax(vs->adapt_used.microStep, vs->adapt_single_rate_step) : dt;
    vs->single_rate_evaluations += (PetscInt64)std::ceil(DeltaT / h - 1e-9) * vs->tableau->stages * nsplits;
    if (vs->adapt) {
      PetscReal ratio = 1;
      for (double r : vs->adapt_used.ratios) ratio *= r;
      vs->run_largest_ratio = PetscMax(vs->run_largest_ratio, ratio);
    }
  }
  ts->ptime = last ? ts->max_time : t0 + DeltaT;
  if (vs->adapt && (ts->ptime >= ts->max_time - 1e-10 * DeltaT || ts->steps + 1 >= ts->max_steps)) PetscCall(TSVSHMMAdaptCheckCost_Private(ts)); /* the solve's last macro step */
  PetscFunctionReturn(0);
}

/* Sampled states are the method's output: a state at t inside the last macro step [t0, t1] is
   sampled by a macro step of length t - t0 from the state at t0, with the last step's parameters
   (-ts_vshmm_adapt: fitted to at least its cycles per macro step), as -ts_exact_final_time
   matchstep would land on t; its work counts as the steps'. The linear interpolant of the two
   samples, used before, erred by DeltaT^2 / 8 |x''| unseen by any estimate (x' = -y + sin(9 t) at
   t = 1.05, DeltaT = 0.1: 6.8 tol at 1e-3 with -ts_vshmm_adapt, 0.43 with matchstep). */
static PetscErrorCode TSInterpolate_VSHMM(TS ts, PetscReal t, Vec X)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscReal t0 = ts->ptime_prev, t1 = ts->ptime;
  PetscReal theta = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;

  PetscFunctionBegin;
  const PetscBool sampled = (t > t0 && t < t1 && (vs->adapt ? !vs->adapt_used.ratios.empty() : vs->schedule != nullptr)) ? PETSC_TRUE : PETSC_FALSE;
  if (!sampled) { /* the ends themselves (or nothing stepped yet) */
    if (X == ts->vec_sol) PetscCall(VecAXPBY(X, 1.0 - theta, theta, vs->X0));
    else PetscCall(VecAXPBYPCZ(X, 1.0 - theta, theta, 0.0, vs->X0, ts->vec_sol));
    PetscFunctionReturn(0);
  }
  std::unique_ptr<vshmm::MesoscopicSchedule> fitted; /* -ts_vshmm_adapt: the last step's parameters fitted to t - t0 */
  const vshmm::MesoscopicSchedule           *schedule = vs->schedule.get();
  if (vs->adapt) {
    PetscCall(TSVSHMMAdaptSampleSchedule_Private(ts, t - t0, fitted));
    schedule = fitted.get();
  }
  Vec                    Y = X;
  vshmm::MacroStepCounts counts;
  if (X == ts->vec_sol) PetscCall(VecDuplicate(X, &Y));
  PetscCall(VecCopy(vs->X0, Y));
  PetscCall(TSVSHMMRunMacroStep_Private(ts, *schedule, t0, t - t0, Y, &counts));
  TSVSHMMAddCounts_Private(vs, counts);
  if (Y != X) {
    PetscCall(VecCopy(Y, X));
    PetscCall(VecDestroy(&Y));
  }
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Options and view                                                                             */

/* What -help shows for -ts_vshmm_warnings_viewer: stderr (the default), none, or the file's name. */
static PetscErrorCode WarningsViewerName(TS ts, std::string &name)
{
  TS_VSHMM   *vs   = (TS_VSHMM *)ts->data;
  const char *file = nullptr;

  PetscFunctionBegin;
  if (vs->warnings_none) name = "none";
  else if (!vs->warnings) name = "stderr";
  else {
    PetscCall(PetscViewerFileGetName(vs->warnings, &file));
    name = file && file[0] ? std::string("ascii:") + file : std::string("ascii");
  }
  PetscFunctionReturn(0);
}

/* Every option with PETSc's readers (src/common/vshmmoptions.hpp: an option without a value, an
   empty list item and an integer beyond PetscInt are refused, a value PETSc cannot read is an
   error naming the option); the setters check the values. */
static PetscErrorCode TSSetFromOptions_VSHMM(TS ts, PetscOptionItems *PetscOptionsObject)
{
  TS_VSHMM      *vs  = (TS_VSHMM *)ts->data;
  PetscObject    obj = (PetscObject)ts;
  const PetscInt K   = PetscMax(1, ts->num_rhs_splits - 1); /* for -help: the defaults' length */
  PetscBool      set;

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, "VSHMM multiscale ODE solver options");
  {
    PetscReal dt = vs->micro_dt > 0 ? vs->micro_dt : ts->time_step / kDefaultMicroStepsPerMacroStep;
    PetscCall(VSHMMOptionsReal(PetscOptionsObject, obj, "-ts_vshmm_micro_dt", "Micro step dt of the full field (default: DeltaT/100)", "TSVSHMMSetMicroStep", &dt, &set));
    if (set) PetscCall(TSVSHMMSetMicroStep(ts, dt));

    std::vector<PetscReal> alpha = vs->savings.empty() ? std::vector<PetscReal>(K, 1.0) : vs->savings;
    PetscCall(VSHMMOptionsRealList(PetscOptionsObject, obj, "-ts_vshmm_savings_factors", "Savings factors alpha_1,...,alpha_K, slowest level first (default: all 1)", "TSVSHMMSetSavingsFactors", alpha, &set));
    if (set) PetscCall(TSVSHMMSetSavingsFactors(ts, (PetscInt)alpha.size(), alpha.data()));

    std::vector<PetscReal> seps = vs->separations;
    PetscCall(VSHMMOptionsRealList(PetscOptionsObject, obj, "-ts_vshmm_scale_separations", "Time-scale separation of each pair of consecutive scales, slowest pair first: the slowest rate of the faster scale over the fastest rate of the slower (default: ratios of the levels' spectral radii)", "TSVSHMMSetScaleSeparations", seps, &set));
    if (set) PetscCall(TSVSHMMSetScaleSeparations(ts, (PetscInt)seps.size(), seps.data()));

    std::vector<PetscInt> m = vs->subintervals.empty() ? std::vector<PetscInt>(K, 1) : vs->subintervals;
    PetscCall(VSHMMOptionsIntList(PetscOptionsObject, obj, "-ts_vshmm_subintervals", "Subinterval counts m_1,...,m_K (periods of the kernel per DeltaT), slowest level first (default: all 1)", "TSVSHMMSetSubintervals", m, &set));
    if (set) PetscCall(TSVSHMMSetSubintervals(ts, (PetscInt)m.size(), m.data()));

    TSVSHMMKernelType kernel = vs->kernel_type;
    PetscCall(VSHMMOptionsEnum(PetscOptionsObject, obj, "-ts_vshmm_kernel", "Kernel of the mesoscopic steps", "TSVSHMMSetKernel", TSVSHMMKernelTypes, &kernel, &set));
    if (set) PetscCall(TSVSHMMSetKernel(ts, kernel));

    PetscInt q;
    PetscCall(TSVSHMMGetKernelOrder(ts, &q));
    PetscCall(VSHMMOptionsInt(PetscOptionsObject, obj, "-ts_vshmm_kernel_order", "Order q of the polynomial kernel (derivatives 0..q vanish at the ends)", "TSVSHMMSetKernelOrder", &q, &set));
    if (set) PetscCall(TSVSHMMSetKernelOrder(ts, q));

    std::string rk = vs->rk_type;
    PetscCall(VSHMMOptionsString(PetscOptionsObject, obj, "-ts_vshmm_rk_type", "TSRK type of the inner steps", "TSVSHMMSetRKType", "a TSRK type name (4, 3bs, 5dp, ...)", rk, &set));
    if (set) PetscCall(TSVSHMMSetRKType(ts, rk.c_str()));

    PetscBool check    = vs->check_stability, iset;
    PetscInt  interval = vs->stability_interval;
    PetscCall(VSHMMOptionsBool(PetscOptionsObject, obj, "-ts_vshmm_check_stability", "Check the steps against the stability region of the inner Runge-Kutta method at set-up", "TSVSHMMSetStabilityCheck", &check, &set));
    PetscCall(VSHMMOptionsInt(PetscOptionsObject, obj, "-ts_vshmm_check_stability_interval", "Also check every this many macro steps (0: only at set-up)", "TSVSHMMSetStabilityCheck", &interval, &iset));
    if (set || iset) PetscCall(TSVSHMMSetStabilityCheck(ts, check, interval));

    PetscBool splits = vs->check_splits;
    PetscCall(VSHMMOptionsBool(PetscOptionsObject, obj, "-ts_vshmm_check_splits", "Check at set-up that the RHS splits add up to the TS's RHS function", "TSVSHMMSetSplitCheck", &splits, &set));
    if (set) PetscCall(TSVSHMMSetSplitCheck(ts, splits));

    PetscBool adapt = vs->adapt;
    PetscCall(VSHMMOptionsBool(PetscOptionsObject, obj, "-ts_vshmm_adapt", "Choose the micro step and savings factors not set from the TS tolerances -ts_rtol, -ts_atol", "TSVSHMMSetAdapt", &adapt, &set));
    if (set) PetscCall(TSVSHMMSetAdapt(ts, adapt));
    PetscBool slow = vs->adapt_slow_components;
    PetscCall(VSHMMOptionsBool(PetscOptionsObject, obj, "-ts_vshmm_adapt_slow_components", "With observables, control the error of the slow components (written by the slowest splits only) too", "TSVSHMMSetAdaptSlowComponents", &slow, &set));
    if (set) PetscCall(TSVSHMMSetAdaptSlowComponents(ts, slow));
    PetscBool global = vs->adapt_global;
    PetscCall(VSHMMOptionsBool(PetscOptionsObject, obj, "-ts_vshmm_adapt_global_estimate", "With -ts_vshmm_adapt, carry a second solution with every error term doubled through the run: an estimate of the error at each sampled time (TSGetTimeError())", "TSVSHMMSetAdaptGlobalEstimate", &global, &set));
    if (set) PetscCall(TSVSHMMSetAdaptGlobalEstimate(ts, global));

    TSVSHMMSeparationCheck sep = vs->check_separation;
    PetscCall(VSHMMOptionsEnum(PetscOptionsObject, obj, "-ts_vshmm_check_separation", "What to do where the scales are not separated", "TSVSHMMSetSeparationCheck", TSVSHMMSeparationChecks, &sep, &set));
    if (set) PetscCall(TSVSHMMSetSeparationCheck(ts, sep));

    std::vector<std::string> scales;
    PetscCall(VSHMMOptionsStringList(PetscOptionsObject, obj, "-ts_vshmm_splits", "The scales, slowest first: RHS split names, or groups of them joined by + (default: each split a scale, in creation order)", "TSVSHMMSetSplitOrder", scales, &set));
    if (set) {
      std::vector<const char *> names;
      for (const std::string &scale : scales) names.push_back(scale.c_str());
      PetscCall(TSVSHMMSetSplitOrder(ts, (PetscInt)names.size(), names.data()));
    }

    std::string warnings;
    PetscCall(WarningsViewerName(ts, warnings));
    PetscCall(VSHMMOptionsString(PetscOptionsObject, obj, "-ts_vshmm_warnings_viewer", "Where the warnings go (stability and separation checks, accuracy, Inf/NaN): stderr, none, or a PETSc ASCII viewer ascii:<file>", "TSVSHMMSetWarningsViewer", "stderr, none, or an ASCII viewer ascii[:file] (ascii alone: stdout)", warnings, &set));
    if (set) {
      PetscViewer viewer = nullptr;
      if (warnings == "none") PetscCall(TSVSHMMSetWarningsViewer(ts, nullptr));
      else if (warnings == "stderr") { /* the default: PETSC_STDERR at the time of each warning */ PetscCall(PetscViewerDestroy(&vs->warnings));
        vs->warnings_none = PETSC_FALSE;
      } else {
        PetscViewerFormat format;
        PetscCall(
          VSHMMOptionRead(obj, "-ts_vshmm_warnings_viewer", "stderr, none, or an ASCII viewer ascii[:file]", [&]() { return PetscOptionsGetViewer(PetscObjectComm(obj), obj->options, obj->prefix, "-ts_vshmm_warnings_viewer", &viewer, &format, &set); }));
        PetscCall(TSVSHMMSetWarningsViewer(ts, viewer));
        PetscCall(PetscViewerDestroy(&viewer));
      }
    }
  }
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSView_VSHMM(TS ts, PetscViewer viewer)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  PetscBool iascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(0);
  if (vs->splits.empty() || !vs->kernel || !vs->tableau) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  VSHMM: not set up yet; kernel %s, inner Runge-Kutta type %s\n", TSVSHMMKernelTypes[vs->kernel_type], vs->rk_type.c_str()));
    PetscFunctionReturn(0);
  }
  const PetscInt nscales = (PetscInt)vs->level_end.size();
  const int      q       = vs->kernel->order();
  if (q == vshmm::Kernel::kInfiniteOrder) PetscCall(PetscViewerASCIIPrintf(viewer, "  VSHMM: %" PetscInt_FMT " scales (RHS splits, slowest first), kernel %s (infinitely smooth)\n", nscales, vs->kernel->name().c_str()));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  VSHMM: %" PetscInt_FMT " scales (RHS splits, slowest first), kernel %s (order q = %d)\n", nscales, vs->kernel->name().c_str(), q));
  if (vs->adapt && vs->macro_steps > 0)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  micro step dt = %g (%s), sampling interval DeltaT = %g\n", (double)vs->adapt_used.microStep, vs->micro_dt > 0 ? "set" : "chosen by -ts_vshmm_adapt for the last macro step", (double)ts->time_step));
  else if (vs->micro_dt > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  micro step dt = %g, sampling interval DeltaT = %g\n", (double)vs->micro_dt, (double)ts->time_step));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  micro step dt = DeltaT/%d = %g (default), sampling interval DeltaT = %g\n", (int)kDefaultMicroStepsPerMacroStep, (double)(ts->time_step / kDefaultMicroStepsPerMacroStep), (double)ts->time_step));
  {
    const vshmm::StabilityFunction R(*vs->tableau);
    PetscCall(PetscViewerASCIIPrintf(viewer, "  inner Runge-Kutta: TSRK %s (order %d, %d stages; stable for h |lambda| <= %.4g on the negative real axis, %.4g on the imaginary axis)\n", vs->tableau->name.c_str(), vs->tableau->order, vs->tableau->stages, R.realLimit(), R.imaginaryLimit()));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "  scale  split                 step         savings factor  subintervals  RHS evaluations\n"));
  for (PetscInt l = 0, k = 0; l < nscales; ++l) {
    for (; k < vs->level_end[l]; ++k) {
      const VSHMMSplit &split = vs->splits[k];
      if (l < nscales - 1)
        PetscCall(PetscViewerASCIIPrintf(viewer, "  %5" PetscInt_FMT "  %-20s  h_%-3" PetscInt_FMT "        %-14g  %-12" PetscInt_FMT "  %" PetscInt64_FMT "\n", l, split.name.c_str(), l + 1, (double)vs->savings_used[l], vs->subintervals_used[l], vs->rhs_evaluations[k]));
      else PetscCall(PetscViewerASCIIPrintf(viewer, "  %5" PetscInt_FMT "  %-20s  dt (micro)   %-14s  %-12s  %" PetscInt64_FMT "\n", l, split.name.c_str(), "-", "-", vs->rhs_evaluations[k]));
    }
  }
  PetscInt64 steps = 0, evals = 0;
  for (PetscInt64 n : vs->level_steps) steps += n;
  for (PetscInt64 n : vs->rhs_evaluations) evals += n;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  work: %" PetscInt64_FMT " macro steps, %" PetscInt64_FMT " micro cycles, %" PetscInt64_FMT " Runge-Kutta steps, %" PetscInt64_FMT " split RHS evaluations\n", vs->macro_steps, vs->micro_cycles, steps, evals));
  if (vs->single_rate_evaluations > 0) {
    const PetscInt64 all = evals + (vs->adapt ? vs->adapt_evaluations : 0);
    PetscCall(PetscViewerASCIIPrintf(viewer, "  single-rate TSRK %s steps at %s would take %" PetscInt64_FMT " split RHS evaluations: this run's work%s is %.3g times that\n", vs->tableau->name.c_str(), vs->adapt ? "the largest step the accuracy control's bounds allow (stable, resolving the fastest oscillation; at least the micro step) in each macro step" : "the micro step of each macro step", vs->single_rate_evaluations, vs->adapt ? " with its estimates and rejected tries" : "",
                                     (double)all / (double)vs->single_rate_evaluations));
  }
  if (vs->adapt) {
    std::string admitted; /* scales not separated: the time ratios a single-rate step admitted */
    for (PetscReal r : vs->adapt_verified) admitted += (admitted.empty() ? "" : ", ") + std::to_string(r).substr(0, 6);
    const bool any = TSVSHMMSavingsAdmitted_Private(vs);
    char       from[32];
    char       separated[32];
    PetscCall(PetscSNPrintf(from, sizeof from, "%g", (double)vs->adapt_single_rate_from));
    PetscCall(PetscSNPrintf(separated, sizeof separated, "%g", (double)vs->separated_from));
    const std::string what = !vs->savings.empty()                                          ? "set"
                             : !vs->no_separation && vs->adapt_single_rate_from >= 0       ? "none from t = " + std::string(from) + " on (the tolerance is out of reach with savings: single-rate Runge-Kutta steps)"
                             : !vs->no_separation && vs->separated_from >= 0               ? "chosen from t = " + std::string(separated) + " on (the scales were not separated before)"
                             : !vs->no_separation                                          ? "chosen"
                             : any                                                         ? "chosen up to the time ratios " + admitted + " (scales not separated; admitted by a comparison with a single-rate macro step)"
                             : !vs->adapt_candidate.empty() && !vs->adapt_verified.empty() ? "none (scales not separated; a comparison with a single-rate macro step admitted none)"
                                                                                           : "none (scales not separated)";
    char              rtol[64], atol[64], tols[320]; /* the vectors of TSSetTolerances() weigh the state's components (the slow components beside the observables too); the observables take the scalars */
    if (ts->vrtol) PetscCall(PetscSNPrintf(rtol, sizeof rtol, "rtol per component (a vector)"));
    else PetscCall(PetscSNPrintf(rtol, sizeof rtol, "rtol %g", (double)ts->rtol));
    if (ts->vatol) PetscCall(PetscSNPrintf(atol, sizeof atol, "atol per component (a vector)"));
    else PetscCall(PetscSNPrintf(atol, sizeof atol, "atol %g", (double)ts->atol));
    if (!vs->observables) PetscCall(PetscSNPrintf(tols, sizeof tols, "%s, %s on the whole state (weighted norm)", rtol, atol));
    else if (ts->vatol || ts->vrtol) PetscCall(PetscSNPrintf(tols, sizeof tols, "rtol %g, atol %g on the observables; %s, %s on the slow components", (double)ts->rtol, (double)ts->atol, rtol, atol));
    else PetscCall(PetscSNPrintf(tols, sizeof tols, "rtol %g, atol %g on the observables", (double)ts->rtol, (double)ts->atol));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  accuracy control (-ts_vshmm_adapt): %s; savings factors %s\n", tols, what.c_str()));
    PetscCall(PetscViewerASCIIPrintf(viewer, "    error estimate: last macro step %g, sum over the run %g (1 = the tolerance; the steps' estimates added as of one sign: on the suite of docs/accuracy.md section 21 about twice the error at the sampled times in median, below half of it at 6%% of them); %" PetscInt64_FMT " calibrations, %" PetscInt64_FMT " rejected macro steps, %" PetscInt64_FMT " split RHS evaluations for estimates and rejected steps\n",
                                     (double)vs->error_estimate, (double)vs->error_estimate_total, vs->adapt_calibrations, vs->adapt_rejections, vs->adapt_evaluations));
    if (vs->adapt_global && vs->carried_time == PETSC_MIN_REAL) PetscCall(PetscViewerASCIIPrintf(viewer, "    global error estimate (-ts_vshmm_adapt_global_estimate, the carried comparison): no macro step yet\n"));
    else if (vs->adapt_global)
      PetscCall(PetscViewerASCIIPrintf(viewer, "    global error estimate (-ts_vshmm_adapt_global_estimate, the carried comparison): %g at t = %g, largest %g over the run (1 = the tolerance)%s\n", (double)vs->global_estimate, (double)vs->carried_time,
                                       (double)vs->global_estimate_max, vs->carried_restarts ? "; the comparison blew up and started again from the solution (the estimate counts the errors since)" : ""));
    if (vs->growth_probes > 0 && vs->growth_rate > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "    the slow dynamics grow an error (a growing mode of the slowest level's Jacobian, probed %" PetscInt64_FMT " time%s): the last probe measured e^(%g t), and each later macro step's share of the tolerance is shrunk by e^(%g (t_final - t))\n", vs->growth_probes, vs->growth_probes == 1 ? "" : "s",
                                       (double)vs->growth_rate, (double)vs->growth_rate));
    else if (vs->growth_probes > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "    the slow dynamics do not grow an error (a growing mode of the slowest level's Jacobian, probed %" PetscInt64_FMT " time%s: the last probe found none)\n", vs->growth_probes, vs->growth_probes == 1 ? "" : "s"));
    if (vs->observables && vs->slow_count > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "    with the observables, the %" PetscInt_FMT " slow component%s (written by the slowest splits only%s, -ts_vshmm_adapt_slow_components): %" PetscInt64_FMT " of the differences led by %s\n", vs->slow_count, vs->slow_count == 1 ? "" : "s", vs->slow_by_values > 0 ? ", seen from the fields' values" : "", vs->slow_led, vs->slow_count == 1 ? "it" : "them"));
    else if (vs->observables && !vs->adapt_slow_components) PetscCall(PetscViewerASCIIPrintf(viewer, "    the observables only (-ts_vshmm_adapt_slow_components false)\n"));
    if (vs->lag_mask)
      PetscCall(PetscViewerASCIIPrintf(viewer, "    a macro step's first comparison starts from the last one's end state on the %" PetscInt_FMT " component%s only faster levels write (%s; the lag of decaying faster levels): %" PetscInt64_FMT " so far\n", vs->lag_count, vs->lag_count == 1 ? "" : "s", vs->lag_by_values ? "seen from the fields' values" : "their index sets", vs->lag_inherited));
    for (size_t l = 0; l < vs->adapt_merged.size(); ++l)
      if (vs->adapt_merged[l] > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    levels %d/%d: no savings between them (they are %.3g apart, less than 2, and the faster only decays)\n", (int)l, (int)l + 1, (double)vs->adapt_merged[l]));
    for (size_t l = 0; l < vs->adapt_phase.size(); ++l)
      if (vs->adapt_phase[l] >= 0)
        PetscCall(PetscViewerASCIIPrintf(viewer, "    levels %d/%d: no savings between them from t = %g on (the sampled quantities carry a faster level's phase: separation check)\n", (int)l, (int)l + 1, (double)vs->adapt_phase[l]));
    for (size_t l = 0; l < vs->adapt_lost.size(); ++l)
      if (vs->adapt_lost[l] >= 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    levels %d/%d: no savings between them from t = %g on (no longer separated from the slower level: separation check)\n", (int)l, (int)l + 1, (double)vs->adapt_lost[l]));
    if (vs->adapt_uncompared_total > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "    %" PetscInt64_FMT " macro steps without a comparison (nothing left to coarsen and the estimates far below their shares: the model's prediction stood in)\n", vs->adapt_uncompared_total));
    if (vs->adapt_layer_fits > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    first macro step (an initial layer): tries estimated again from a second comparison %" PetscInt64_FMT "\n", vs->adapt_layer_fits));
    bool saturating = false;
    for (double x : vs->adapt_model.saturation) saturating = saturating || (x > 0 && std::isfinite(x));
    if (saturating) { /* where each pair's error term stops growing (an initial layer, a band of rates, the separations set) */
      PetscCall(PetscViewerASCIIPrintf(viewer, "    error model: each level pair's term saturates at r_l - 1 ="));
      for (double x : vs->adapt_model.saturation) {
        if (x > 0 && std::isfinite(x)) PetscCall(PetscViewerASCIIPrintf(viewer, " %.3g", x));
        else PetscCall(PetscViewerASCIIPrintf(viewer, " -"));
      }
      PetscCall(PetscViewerASCIIPrintf(viewer, " (- linear; time ratios of the last macro step:"));
      for (double r : vs->adapt_used.ratios) PetscCall(PetscViewerASCIIPrintf(viewer, " %.4g", r));
      PetscCall(PetscViewerASCIIPrintf(viewer, ")\n"));
    }
  }
  if (!vs->level_radius.empty() && vs->level_radius.size() == vs->level_end.size()) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  spectral radius of each level's Jacobian (t = %g):", (double)vs->spectra_time));
    for (PetscReal r : vs->level_radius) PetscCall(PetscViewerASCIIPrintf(viewer, " %.3g", (double)r));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  }
  bool slowest = false;
  for (PetscReal r : vs->level_slowest) slowest = slowest || r > 0;
  if (slowest) {
    std::string list;
    for (PetscReal r : vs->level_slowest) {
      char item[32];
      PetscCall(PetscSNPrintf(item, sizeof(item), r > 0 ? " %.3g" : " -", (double)r));
      list += item;
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "  slowest rate of each level's own components (component splits; additive: an oscillation's amplitude rate in its own splits):%s\n", list.c_str()));
  }
  if (vs->adapt && vs->fastest_phase_now && (vs->fastest_nonlinear || vs->fastest_restore > 0))
    PetscCall(PetscViewerASCIIPrintf(viewer, "  the fastest level's oscillation over four phases of it: mean eigenvalue %.3g%+.3gi, its amplitude restored at rate %.3g%s\n", vs->fastest_mean_mode.real(), vs->fastest_mean_mode.imag(), (double)vs->fastest_restore,
                                     !vs->fastest_nonlinear                                                            ? ""
                                     : std::abs(vs->fastest_mean_mode.imag()) > std::abs(vs->fastest_mean_mode.real()) ? " (nonlinear: oscillating by the mean, its own slowest rate the largest of the four phases')"
                                                                                                                       : " (nonlinear; the mean does not oscillate: the Jacobian at the state judged)"));
  for (size_t L = 1; vs->adapt && L < vs->beat_bound.size(); ++L) {
    if (vs->beat_bound[L] > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "  level %d's own oscillations beat at %.3g (a slow process inside it; one relative phase held moves the observables by %.3g tolerances): savings keep it turning once per macro step, the time ratios up to r_%d in product at most %.3g\n", (int)L,
                                       (double)vs->beat_bound[L], (double)vs->beat_effect[L], (int)L - 1, (double)PetscMax(1.0, vs->beat_bound[L] * ts->time_step / (2 * PETSC_PI))));
  }
  if (!vs->separations.empty()) {
    std::string list;
    for (PetscReal S : vs->separations) {
      char item[32];
      PetscCall(PetscSNPrintf(item, sizeof(item), " %g", (double)S));
      list += item;
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "  scale separations (set, TSVSHMMSetScaleSeparations()):%s\n", list.c_str()));
  }
  if (!vs->check_splits) PetscCall(PetscViewerASCIIPrintf(viewer, "  split check: off\n"));
  else if (!ts->setupcalled) PetscCall(PetscViewerASCIIPrintf(viewer, "  split check: at set-up\n"));
  else if (vs->splits_difference < 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  split check: none (the TS has no RHS function to check the splits' sum against)\n"));
  else
    PetscCall(PetscViewerASCIIPrintf(viewer, "  split check at set-up: the splits' sum differs from the RHS function by %g of the largest split output%s\n", (double)vs->splits_difference, vs->splits_difference > kSplitsSumTolerance ? " (warned: they do not add up)" : ""));
  if (!vs->check_stability && vs->stability_interval == 0) PetscCall(PetscViewerASCIIPrintf(viewer, "  stability check: off\n"));
  else if (vs->stability_interval > 0)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  stability check: %s set-up and every %" PetscInt_FMT " macro steps; %" PetscInt64_FMT " checks, %" PetscInt64_FMT " split RHS evaluations, %" PetscInt64_FMT " warnings\n", vs->check_stability ? "at" : "not at", vs->stability_interval, vs->stability_checks, vs->stability_evaluations, vs->stability_warnings));
  else
    PetscCall(PetscViewerASCIIPrintf(viewer, "  stability check: at set-up; %" PetscInt64_FMT " checks, %" PetscInt64_FMT " split RHS evaluations, %" PetscInt64_FMT " warnings\n", vs->stability_checks, vs->stability_evaluations, vs->stability_warnings));
  if (vs->adapt && vs->stability_evaluations > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "    (its split RHS evaluations include -ts_vshmm_adapt's estimates of the levels' spectra at its calibrations)\n"));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Type-specific setters and getters (composed on the TS)                                      */

static PetscErrorCode TSVSHMMSetMicroStep_VSHMM(TS ts, PetscReal dt)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->micro_dt = dt;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetMicroStep_VSHMM(TS ts, PetscReal *dt)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  *dt = vs->micro_dt > 0 ? vs->micro_dt : ts->time_step / kDefaultMicroStepsPerMacroStep;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetSavingsFactors_VSHMM(TS ts, PetscInt n, const PetscReal a[])
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->savings.assign(a, a + n);
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetSavingsFactors_VSHMM(TS ts, PetscInt *n, const PetscReal *a[])
{
  TS_VSHMM                     *vs = (TS_VSHMM *)ts->data;
  const std::vector<PetscReal> &v  = vs->savings.empty() ? vs->savings_used : vs->savings;

  PetscFunctionBegin;
  if (n) *n = (PetscInt)v.size();
  if (a) *a = v.empty() ? nullptr : v.data();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetScaleSeparations_VSHMM(TS ts, PetscInt n, const PetscReal S[])
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->separations.assign(S, S + n);
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetScaleSeparations_VSHMM(TS ts, PetscInt *n, const PetscReal *S[])
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (n) *n = (PetscInt)vs->separations.size();
  if (S) *S = vs->separations.empty() ? nullptr : vs->separations.data();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetSubintervals_VSHMM(TS ts, PetscInt n, const PetscInt m[])
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->subintervals.assign(m, m + n);
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetSubintervals_VSHMM(TS ts, PetscInt *n, const PetscInt *m[])
{
  TS_VSHMM                    *vs = (TS_VSHMM *)ts->data;
  const std::vector<PetscInt> &v  = vs->subintervals.empty() ? vs->subintervals_used : vs->subintervals;

  PetscFunctionBegin;
  if (n) *n = (PetscInt)v.size();
  if (m) *m = v.empty() ? nullptr : v.data();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetKernel_VSHMM(TS ts, TSVSHMMKernelType type)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->kernel_type = type;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetKernel_VSHMM(TS ts, TSVSHMMKernelType *type)
{
  PetscFunctionBegin;
  *type = ((TS_VSHMM *)ts->data)->kernel_type;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetKernelOrder_VSHMM(TS ts, PetscInt q)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->kernel_order = q;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetKernelOrder_VSHMM(TS ts, PetscInt *q)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (vs->kernel_type == TSVSHMM_KERNEL_POLYNOMIAL) *q = vs->kernel_order == PETSC_DEFAULT ? 1 : vs->kernel_order;
  else *q = vshmm::Kernel::create(CoreKernelType(vs->kernel_type))->order();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetRKType_VSHMM(TS ts, TSRKType type)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->rk_type = type;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetRKType_VSHMM(TS ts, TSRKType *type)
{
  PetscFunctionBegin;
  *type = ((TS_VSHMM *)ts->data)->rk_type.c_str();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetSplitOrder_VSHMM(TS ts, PetscInt n, const char *const names[])
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  vs->split_order.assign(names, names + n);
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetSplitOrder_VSHMM(TS ts, PetscInt *n, const char *const *names[])
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  vs->split_order_out.clear();
  if (!vs->splits.empty()) { /* as set up: one entry per scale, "a" or "a+b" */
    for (size_t l = 0, k = 0; l < vs->level_end.size(); ++l) {
      std::string scale;
      for (; (PetscInt)k < vs->level_end[l]; ++k) scale += (scale.empty() ? "" : "+") + vs->splits[k].name;
      vs->split_order_out.push_back(scale);
    }
  } else if (!vs->split_order.empty()) vs->split_order_out = vs->split_order;
  else
    for (TS_RHSSplitLink l = ts->tsrhssplit; l; l = l->next) vs->split_order_out.push_back(l->splitname);
  vs->split_order_c.clear();
  for (const std::string &scale : vs->split_order_out) vs->split_order_c.push_back(scale.c_str());
  if (n) *n = (PetscInt)vs->split_order_c.size();
  if (names) *names = vs->split_order_c.empty() ? nullptr : vs->split_order_c.data();
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetStabilityCheck_VSHMM(TS ts, PetscBool flg, PetscInt interval)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  vs->check_stability    = flg;
  vs->stability_interval = interval;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetStabilityCheck_VSHMM(TS ts, PetscBool *flg, PetscInt *interval)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (flg) *flg = vs->check_stability;
  if (interval) *interval = vs->stability_interval;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetAdapt_VSHMM(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->adapt = flg;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetAdapt_VSHMM(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  *flg = ((TS_VSHMM *)ts->data)->adapt;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetObservables_VSHMM(TS ts, PetscInt n, PetscErrorCode (*f)(TS, PetscReal, Vec, PetscReal[], void *), void *ctx)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  vs->nobservables    = f ? n : 0;
  vs->observables     = f;
  vs->observables_ctx = ctx;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetSplitCheck_VSHMM(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->check_splits = flg;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetSplitCheck_VSHMM(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  *flg = ((TS_VSHMM *)ts->data)->check_splits;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetAdaptSlowComponents_VSHMM(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->adapt_slow_components = flg;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetAdaptSlowComponents_VSHMM(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  *flg = ((TS_VSHMM *)ts->data)->adapt_slow_components;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetAdaptGlobalEstimate_VSHMM(TS ts, PetscBool flg)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->adapt_global = flg;
  PetscCall(TSVSHMMInvalidateSetUp_Private(ts));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetAdaptGlobalEstimate_VSHMM(TS ts, PetscBool *flg)
{
  PetscFunctionBegin;
  *flg = ((TS_VSHMM *)ts->data)->adapt_global;
  PetscFunctionReturn(0);
}

/* TSGetTimeError(): the carried comparison's difference from the solution at the last sampled
   time, converted as its global estimate is (an estimate of the solution's error vector) */
static PetscErrorCode TSGetTimeError_VSHMM(TS ts, PetscInt n, Vec *X)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  PetscCheck(n == 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP, "TSVSHMM: TSGetTimeError() gives the estimate at the last sampled time only (n = 0), not n = %" PetscInt_FMT, n);
  PetscCheck(vs->adapt_global, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TSVSHMM: TSGetTimeError() needs -ts_vshmm_adapt_global_estimate (TSVSHMMSetAdaptGlobalEstimate()) with -ts_vshmm_adapt");
  PetscCheck(X && *X, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_NULL, "TSVSHMM: TSGetTimeError() fills a vector the caller created (VecDuplicate() of the solution)");
  if (!vs->Xcarried || vs->carried_time != ts->ptime) {
    PetscCall(VecSet(*X, 0.0)); /* no macro step taken yet */
    PetscFunctionReturn(0);
  }
  PetscCall(VecWAXPY(*X, -1.0, ts->vec_sol, vs->Xcarried));
  PetscCall(VecScale(*X, vs->carried_factor));
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetSeparationCheck_VSHMM(TS ts, TSVSHMMSeparationCheck check)
{
  PetscFunctionBegin;
  ((TS_VSHMM *)ts->data)->check_separation = check;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetSeparationCheck_VSHMM(TS ts, TSVSHMMSeparationCheck *check)
{
  PetscFunctionBegin;
  *check = ((TS_VSHMM *)ts->data)->check_separation;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMSetWarningsViewer_VSHMM(TS ts, PetscViewer viewer)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  if (viewer) PetscCall(PetscObjectReference((PetscObject)viewer));
  PetscCall(PetscViewerDestroy(&vs->warnings));
  vs->warnings      = viewer;
  vs->warnings_none = viewer ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMGetStatistics_VSHMM(TS ts, TSVSHMMStatistics *stats)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  stats->macro_steps             = vs->macro_steps;
  stats->micro_cycles            = vs->micro_cycles;
  stats->nsplits                 = (PetscInt)vs->rhs_evaluations.size();
  stats->nscales                 = (PetscInt)vs->level_steps.size();
  stats->rhs_evaluations         = vs->rhs_evaluations.empty() ? nullptr : vs->rhs_evaluations.data();
  stats->level_steps             = vs->level_steps.empty() ? nullptr : vs->level_steps.data();
  stats->level_evaluations       = vs->level_evaluations.empty() ? nullptr : vs->level_evaluations.data();
  stats->stability_checks        = vs->stability_checks;
  stats->stability_evaluations   = vs->stability_evaluations;
  stats->stability_warnings      = vs->stability_warnings;
  stats->error_estimate          = vs->error_estimate;
  stats->error_estimate_total    = vs->error_estimate_total;
  stats->adapt_evaluations       = vs->adapt_evaluations;
  stats->adapt_rejections        = vs->adapt_rejections;
  stats->adapt_calibrations      = vs->adapt_calibrations;
  stats->adapt_uncompared        = vs->adapt_uncompared_total;
  stats->adapt_layer_estimates   = vs->adapt_layer_fits;
  stats->adapt_single_rate_from  = vs->adapt_single_rate_from;
  stats->adapt_growth_probes     = vs->growth_probes;
  stats->adapt_growth_rate       = vs->growth_rate;
  stats->global_estimate         = vs->adapt_global ? vs->global_estimate : -1;
  stats->global_estimate_max     = vs->adapt_global ? vs->global_estimate_max : -1;
  stats->single_rate_evaluations = vs->single_rate_evaluations;
  PetscFunctionReturn(0);
}

static PetscErrorCode TSVSHMMResetStatistics_VSHMM(TS ts)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;
  size_t    n = vs->splits.size(), nscales = vs->level_end.size();

  PetscFunctionBegin;
  vs->macro_steps             = 0;
  vs->micro_cycles            = 0;
  vs->stability_checks        = 0;
  vs->stability_evaluations   = 0;
  vs->stability_warnings      = 0;
  vs->error_estimate          = 0;
  vs->error_estimate_total    = 0;
  vs->error_estimate_squares  = 0;
  vs->global_estimate_max     = 0;
  vs->adapt_evaluations       = 0;
  vs->adapt_rejections        = 0;
  vs->adapt_calibrations      = 0;
  vs->adapt_uncompared_total  = 0;
  vs->adapt_layer_fits        = 0;
  vs->growth_probes           = 0;
  vs->single_rate_evaluations = 0;
  vs->slow_led                = 0;
  vs->warned_ratio.assign(nscales, 0.0);
  vs->fast_energy_min    = 0;
  vs->fast_energy_warned = 0;
  vs->rhs_evaluations.assign(n, 0);
  vs->level_steps.assign(nscales, 0);
  vs->level_evaluations.assign(nscales, 0);
  PetscFunctionReturn(0);
}

#define VSHMM_METHODS(X) \
  X(TSVSHMMSetMicroStep) \
  X(TSVSHMMGetMicroStep) \
  X(TSVSHMMSetSavingsFactors) \
  X(TSVSHMMGetSavingsFactors) \
  X(TSVSHMMSetSubintervals) \
  X(TSVSHMMGetSubintervals) \
  X(TSVSHMMSetKernel) \
  X(TSVSHMMGetKernel) \
  X(TSVSHMMSetKernelOrder) \
  X(TSVSHMMGetKernelOrder) \
  X(TSVSHMMSetRKType) \
  X(TSVSHMMGetRKType) \
  X(TSVSHMMSetSplitOrder) \
  X(TSVSHMMGetSplitOrder) \
  X(TSVSHMMSetStabilityCheck) \
  X(TSVSHMMGetStabilityCheck) \
  X(TSVSHMMSetSplitCheck) \
  X(TSVSHMMGetSplitCheck) \
  X(TSVSHMMSetAdapt) \
  X(TSVSHMMGetAdapt) \
  X(TSVSHMMSetObservables) \
  X(TSVSHMMSetAdaptSlowComponents) \
  X(TSVSHMMGetAdaptSlowComponents) \
  X(TSVSHMMSetAdaptGlobalEstimate) \
  X(TSVSHMMGetAdaptGlobalEstimate) \
  X(TSVSHMMSetScaleSeparations) \
  X(TSVSHMMGetScaleSeparations) \
  X(TSVSHMMSetSeparationCheck) \
  X(TSVSHMMGetSeparationCheck) \
  X(TSVSHMMSetWarningsViewer) \
  X(TSVSHMMGetStatistics) \
  X(TSVSHMMResetStatistics)

static PetscErrorCode TSDestroy_VSHMM(TS ts)
{
  PetscFunctionBegin;
  PetscCall(TSReset_VSHMM(ts));
  PetscCall(PetscViewerDestroy(&((TS_VSHMM *)ts->data)->warnings));
#define VSHMM_UNCOMPOSE(name) PetscCall(PetscObjectComposeFunction((PetscObject)ts, #name "_C", nullptr));
  VSHMM_METHODS(VSHMM_UNCOMPOSE)
#undef VSHMM_UNCOMPOSE
  delete (TS_VSHMM *)ts->data;
  ts->data = nullptr;
  PetscFunctionReturn(0);
}

/*MC
   TSVSHMM - the Variable Step Size Heterogeneous Multiscale Method for ODEs and PDEs with several
   time scales (Lee and Engquist)

   The right-hand side is given as one RHS split per time scale (TSRHSSplitSetIS() and
   TSRHSSplitSetRHSFunction()), slowest first:

$    dx/dt = f_0(x) + f_1(x)/eps_1 + ... + f_K(x)/eps_K

   Each split function returns its scale's term (with its 1/eps_k factor) for the split's
   components: a split whose IS holds every component is an additive term of the field, a split
   with a subset is a component split as in TSMPRK. Level l integrates G_l = f_0 + ... + f_l. One
   TSStep is one macro step: the TS time step is the sampling interval DeltaT. A macro step repeats
   micro cycles until it reaches t_n + DeltaT exactly: one step of the full field G_K with the micro
   step dt, then one step of G_l for l = K-1, ..., 0 with the mesoscopic step

$    h_j(t) = alpha_j dt K(Theta^{-1}(((t - t_n) mod P_j) / P_j)),   P_j = DeltaT / m_j,  j = l + 1,

   where K is the kernel, Theta its antiderivative, alpha_j the savings factors and m_j the
   subinterval counts. Every step is one step of an explicit Runge-Kutta method from the TSRK
   registry. Only the sampled states (at multiples of DeltaT) are accurate for the slow variables.

   The warnings a user must see (stability and separation checks, accuracy control, a split that
   produced Inf or NaN) go to one ASCII viewer, stderr by default (`TSVSHMMSetWarningsViewer()`);
   notes go through `PetscInfo()` (-info), the work done through `TSVSHMMGetStatistics()` and
   -ts_view.

   Options Database Keys:
+  -ts_vshmm_micro_dt <dt> - micro step of the full field (default DeltaT/100)
.  -ts_vshmm_savings_factors <a1,...,aK> - savings factors, slowest level first (default all 1)
.  -ts_vshmm_subintervals <m1,...,mK> - kernel periods per sampling interval (default all 1)
.  -ts_vshmm_kernel <cosine,constant,polynomial,exponential> - kernel (default cosine)
.  -ts_vshmm_kernel_order <q> - order of the polynomial kernel (default 1)
.  -ts_vshmm_rk_type <type> - TSRK type of every inner step (default 4)
.  -ts_vshmm_splits <a,b+c,...> - the scales, slowest first: split names, or groups joined by '+' (default: each split a scale, in creation order)
.  -ts_vshmm_check_stability <true,false> - check the steps against the stability region at set-up (default true)
.  -ts_vshmm_check_stability_interval <N> - also check every N macro steps (default 0: never)
.  -ts_vshmm_check_splits <true,false> - check at set-up that the RHS splits add up to the TS's RHS function (default true)
.  -ts_vshmm_adapt <true,false> - choose the micro step and savings factors not set from -ts_rtol, -ts_atol (default false)
.  -ts_vshmm_adapt_slow_components <true,false> - with observables, control the slow components too (default true)
.  -ts_vshmm_adapt_global_estimate <true,false> - with -ts_vshmm_adapt, estimate the error at each sampled time with a carried comparison (default false; `TSGetTimeError()`)
.  -ts_vshmm_check_separation <off,warn,error> - what to do where the scales are not separated (default warn)
.  -ts_vshmm_scale_separations <S1,...,SK> - the separation of each pair of consecutive scales where the application knows it (default: from the levels' spectral radii)
-  -ts_vshmm_warnings_viewer <stderr,none,ascii:file> - where the warnings go (default stderr)

   Level: intermediate

.seealso: `TSCreate()`, `TS`, `TSSetType()`, `TSRHSSplitSetIS()`, `TSVSHMMSetSavingsFactors()`,
          `TSVSHMMSetMicroStep()`, `TSVSHMMGetStatistics()`, `TSVSHMMSetWarningsViewer()`, `TSMPRK`
M*/
PETSC_INTERN PetscErrorCode TSCreate_VSHMM(TS ts)
{
  PetscFunctionBegin;
  ts->ops->setup          = TSSetUp_VSHMM;
  ts->ops->step           = TSStep_VSHMM;
  ts->ops->interpolate    = TSInterpolate_VSHMM;
  ts->ops->reset          = TSReset_VSHMM;
  ts->ops->destroy        = TSDestroy_VSHMM;
  ts->ops->setfromoptions = TSSetFromOptions_VSHMM;
  ts->ops->view           = TSView_VSHMM;
  ts->ops->gettimeerror   = TSGetTimeError_VSHMM;
  ts->default_adapt_type  = TSADAPTNONE;
  ts->usessnes            = PETSC_FALSE;
  ts->data                = new TS_VSHMM();
#define VSHMM_COMPOSE(name) PetscCall(PetscObjectComposeFunction((PetscObject)ts, #name "_C", name##_VSHMM));
  VSHMM_METHODS(VSHMM_COMPOSE)
#undef VSHMM_COMPOSE
  PetscContainer observables = nullptr; /* set with TSVSHMMSetObservables() while the TS had another type */
  PetscCall(PetscObjectQuery((PetscObject)ts, kTSVSHMMObservablesKey, (PetscObject *)&observables));
  if (observables) {
    TSVSHMMObservablesRecord *record;

    PetscCall(PetscContainerGetPointer(observables, (void **)&record));
    PetscCall(TSVSHMMSetObservables_VSHMM(ts, record->n, record->f, record->ctx));
  }
  PetscFunctionReturn(0);
}
