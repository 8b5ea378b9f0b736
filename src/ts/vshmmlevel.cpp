/*
  The levels of TSVSHMM: evaluation of a level's field G_l = f_0 + ... + f_l from the RHS splits
  (with the watch for Inf/NaN), one macro step of Runge-Kutta steps of the levels along the
  schedule of the mesoscopic steps, and the log event of each level.

  Used by the stepper (vshmm.cpp), the stability check (vshmmstability.cpp) and the accuracy
  control (vshmmadapt.cpp); it calls none of them.
*/
#include "vshmmimpl.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

static std::vector<PetscLogEvent> TSVSHMMLevelEvents; /* one per level, registered on demand */

/* The log event of one level ("VSHMMLevel<l>"), registered the first time it is needed. */
PetscErrorCode TSVSHMMGetLevelEvent_Private(PetscInt level, PetscLogEvent *event)
{
  PetscFunctionBegin;
  while ((PetscInt)TSVSHMMLevelEvents.size() <= level) {
    char          name[64];
    PetscLogEvent e;

    std::snprintf(name, sizeof(name), "VSHMMLevel%d", (int)TSVSHMMLevelEvents.size());
    PetscCall(PetscLogEventRegister(name, TS_CLASSID, &e));
    TSVSHMMLevelEvents.push_back(e);
  }
  *event = TSVSHMMLevelEvents[level];
  PetscFunctionReturn(0);
}

/* Forgets the level events (PetscFinalize(): a later PetscInitialize() registers them again). */
PetscErrorCode TSVSHMMResetLevelEvents_Private(void)
{
  PetscFunctionBegin;
  TSVSHMMLevelEvents.clear();
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Evaluation of a level's field G_l = f_0 + ... + f_l                                          */

/* Remembers the first non-finite split output of this rank in the current macro step. */
static inline void NoteNonFinite(TS_VSHMM *vs, PetscInt k, PetscReal t)
{
  if (vs->nonfinite_split < 0) {
    vs->nonfinite_split      = k;
    vs->nonfinite_level      = vs->current_level;
    vs->nonfinite_time       = t;
    vs->nonfinite_evaluation = vs->field_evaluations;
  }
}

static inline bool AllFinite(const PetscScalar *f, PetscInt n)
{
  bool ok = true;
  for (PetscInt i = 0; i < n; ++i) ok &= (bool)std::isfinite(PetscRealPart(f[i]));
  return ok;
}

/* G += F, the output of split k (one split: a scale may be a group of them), checking F for Inf/NaN
   locally (no reduction) while no fault is known. */
PetscErrorCode TSVSHMMAddSplit_Private(TS_VSHMM *vs, PetscInt k, PetscReal t, Vec F, Vec G)
{
  VSHMMSplit        &split = vs->splits[k];
  const PetscScalar *f;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(F, &n));
  if (split.local) {
    PetscScalar *g;
    bool         ok = true;

    PetscCall(VecGetArrayRead(F, &f));
    PetscCall(VecGetArray(G, &g));
    g += split.offset;
    for (PetscInt i = 0; i < n; ++i) {
      g[i] += f[i];
      ok &= (bool)std::isfinite(PetscRealPart(f[i]));
    }
    PetscCall(VecRestoreArray(G, &g));
    PetscCall(VecRestoreArrayRead(F, &f));
    if (!ok) NoteNonFinite(vs, k, t);
  } else {
    if (vs->nonfinite_split < 0) {
      PetscCall(VecGetArrayRead(F, &f));
      if (!AllFinite(f, n)) NoteNonFinite(vs, k, t);
      PetscCall(VecRestoreArrayRead(F, &f));
    }
    PetscCall(VecScatterBegin(split.scatter, F, G, ADD_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(split.scatter, F, G, ADD_VALUES, SCATTER_FORWARD));
  }
  PetscFunctionReturn(0);
}

/* mask = the number of splits among [first, end) that write each component (0 where none does):
   each split's output of ones added as its values are. */
PetscErrorCode TSVSHMMWrittenComponents_Private(TS_VSHMM *vs, PetscInt first, PetscInt end, PetscReal t, Vec mask)
{
  PetscFunctionBegin;
  PetscCall(VecSet(mask, 0.0));
  for (PetscInt k = first; k < end; ++k) {
    PetscCall(VecSet(vs->splits[k].F, 1.0));
    PetscCall(TSVSHMMAddSplit_Private(vs, k, t, vs->splits[k].F, mask));
  }
  PetscFunctionReturn(0);
}

/* G = f_first(t,Y) + ... + f_{end-1}(t,Y): each split function called with the full state
   (counting: the calls count as the steps', per split). */
static PetscErrorCode EvaluateSplits(TS_VSHMM *vs, PetscInt first, PetscInt end, PetscReal t, Vec Y, Vec G, PetscBool counting)
{
  PetscFunctionBegin;
  for (PetscInt k = first; k < end; ++k) {
    VSHMMSplit &split = vs->splits[k];

    if (k == first && split.additive) { /* the first additive split writes G itself */
      PetscCall(TSComputeRHSFunction(split.subts, t, Y, G));
      if (counting) vs->rhs_evaluations[k]++;
      if (vs->nonfinite_split < 0) {
        const PetscScalar *g;
        PetscInt           n;

        PetscCall(VecGetLocalSize(G, &n));
        PetscCall(VecGetArrayRead(G, &g));
        if (!AllFinite(g, n)) NoteNonFinite(vs, k, t);
        PetscCall(VecRestoreArrayRead(G, &g));
      }
      continue;
    }
    if (k == first) PetscCall(VecZeroEntries(G));
    PetscCall(TSComputeRHSFunction(split.subts, t, Y, split.F));
    if (counting) vs->rhs_evaluations[k]++;
    PetscCall(TSVSHMMAddSplit_Private(vs, k, t, split.F, G));
  }
  PetscFunctionReturn(0);
}

/* G = f_0(t,Y) + ... + f_level(t,Y): each split function called with the full state. */
PetscErrorCode TSVSHMMEvaluateLevel_Private(TS_VSHMM *vs, PetscInt level, PetscReal t, Vec Y, Vec G)
{
  PetscFunctionBegin;
  vs->current_level = level;
  vs->field_evaluations++; /* every rank evaluates every level field: a clock common to all ranks */
  const PetscBool counting = vs->counting == TS_VSHMM::COUNT_STEPS ? PETSC_TRUE : PETSC_FALSE;
  if (counting) vs->level_evaluations[level]++;
  else if (vs->counting == TS_VSHMM::COUNT_STABILITY) vs->stability_evaluations += vs->level_end[level]; /* split calls */
  else vs->adapt_evaluations += vs->level_end[level];
  PetscCall(EvaluateSplits(vs, 0, vs->level_end[level], t, Y, G, counting));
  PetscFunctionReturn(0);
}

/* G = the sum of the level's own splits only (those new to it), for the stability checks (counted
   as theirs or as -ts_vshmm_adapt's, never as the steps'). level >= 1. */
PetscErrorCode TSVSHMMEvaluateOwnSplits_Private(TS_VSHMM *vs, PetscInt level, PetscReal t, Vec Y, Vec G)
{
  PetscFunctionBegin;
  const PetscInt first = vs->level_end[level - 1], n = vs->level_end[level] - first;
  vs->current_level = level;
  vs->field_evaluations++;
  if (vs->counting == TS_VSHMM::COUNT_STABILITY) vs->stability_evaluations += n;
  else vs->adapt_evaluations += n;
  PetscCall(EvaluateSplits(vs, first, vs->level_end[level], t, Y, G, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* The vector operations of one explicit Runge-Kutta step of one level, on PETSc Vecs. */
struct LevelStepOps {
  TS_VSHMM *vs;
  Vec       X;
  PetscInt  level;

  int stage(int i, double ti, const double *w)
  {
    Vec Yi = X;
    if (i > 0) {
      PetscCall(VecCopy(X, vs->Y));
      PetscCall(VecMAXPY(vs->Y, i, w, vs->K.data()));
      Yi = vs->Y;
    }
    return TSVSHMMEvaluateLevel_Private(vs, level, ti, Yi, vs->K[i]);
  }
  int update(int s, const double *w) { return VecMAXPY(X, s, w, vs->K.data()); }
};

/* ------------------------------------------------------------------------------------------ */
/* One macro step                                                                               */

/* One macro step of length DeltaT from t0 with the given schedule, on X. */
PetscErrorCode TSVSHMMRunMacroStep_Private(TS ts, const vshmm::MesoscopicSchedule &schedule, PetscReal t0, PetscReal DeltaT, Vec X, vshmm::MacroStepCounts *counts)
{
  TS_VSHMM    *vs = (TS_VSHMM *)ts->data;
  LevelStepOps ops{vs, X, 0};

  PetscFunctionBegin;
  int err = vshmm::runMacroStep(
    schedule, DeltaT,
    [&](int level, double tau, double h) -> int {
      ops.level = level;
      PetscCall(PetscLogEventBegin(vs->level_events[level], ts, 0, 0, 0));
      PetscCall(vshmm::explicitRungeKuttaStep(*vs->tableau, ops, t0 + tau, h));
      if (vs->rest_track && level + 1 == (int)vs->level_end.size()) { /* a micro step of an adaptive try: its stages kept, by a swap (SpuriousRest()) */
        std::swap(vs->K, vs->rest_stages);
        vs->rest_h = h;
      }
      PetscCall(PetscLogEventEnd(vs->level_events[level], ts, 0, 0, 0));
      return 0;
    },
    counts);
  PetscCall(err);
  PetscFunctionReturn(0);
}

/* The schedule of the mesoscopic steps for micro step dt. */
PetscErrorCode TSVSHMMCreateSchedule_Private(TS ts, PetscReal dt, std::unique_ptr<vshmm::MesoscopicSchedule> &schedule)
{
  TS_VSHMM *vs = (TS_VSHMM *)ts->data;

  PetscFunctionBegin;
  try {
    schedule = std::make_unique<vshmm::MesoscopicSchedule>(*vs->kernel, dt, std::vector<double>(vs->savings_used.begin(), vs->savings_used.end()), std::vector<int>(vs->subintervals_used.begin(), vs->subintervals_used.end()));
  } catch (const std::exception &e) {
    SETERRQ(PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "TSVSHMM: %s", e.what());
  }
  PetscFunctionReturn(0);
}
