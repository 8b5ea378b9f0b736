/*
  VSHMMSpectral: the state Vec, the full right-hand side, one additive TSRHSSplit per cluster and
  the physical-space cache they share.

  Cost of a VSHMM level (splits 0..l called one after another with the same state Vec):
    fft evaluation: the first split called with a new state (Vec id, object state, t) computes
    u_x on the grid (one c2r of size N) and the products with the coefficient fields (O(N));
    the following splits of the same state reuse them. Each split then needs the transform of
    the products on its own cluster only: by direct sums over the grid (n_j N flops for n_j
    modes) while the modes projected so for this state stay below the cost of one r2c, else by
    one r2c (size N, once per state, shared). So level l costs one c2r plus
    min(r2c, sum_{j<=l} n_j N), and the full field one c2r plus one r2c (per term kind).
    Burgers and reaction terms add u on a padded grid (one c2r of size M) and one r2c of size M
    per term, always by FFT (no direct projection); the source adds its stored coefficients.
    matrix evaluation (linear and affine terms only): split j multiplies the rows of cluster j of the dense
    operator on the retained modes, (rows of cluster j) x (retained reals) flops: level l pays
    for its own clusters' rows only.
*/
#include "spectralimpl.hpp"

#include <cmath>

/*@C
   VSHMMSpectralCreateVec - Creates a state Vec (the retained coefficients, spread over the ranks)

   Collective

   Input Parameter:
.  sp - the object

   Output Parameter:
.  U - the Vec

   Level: beginner

.seealso: `VSHMMSpectralSetInitialCondition()`
@*/
PetscErrorCode VSHMMSpectralCreateVec(VSHMMSpectral sp, Vec *U)
{
  VSHMMSpectral_Data *s;
  PetscMPIInt         size;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidPointer(U, 2);
  PetscCall(VSHMMSpectralSetUp(sp));
  s = sp->data;
  PetscCall(VecCreate(PetscObjectComm((PetscObject)sp), U));
  PetscCall(VecSetSizes(*U, PETSC_DECIDE, s->layout->size()));
  PetscCall(VecSetFromOptions(*U));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)sp), &size));
  if (size > 1 && !s->gather) PetscCall(VecScatterCreateToAll(*U, &s->gather, &s->Useq));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetInitialCondition - Sets U to the retained coefficients of u0 sampled on the grid

   Collective

   Input Parameters:
+  sp - the object
-  U  - a state Vec

   Notes:
   In mode sparse the initial state is the restriction of u0's coefficients to the retained
   wavenumbers (no shrinkage).

   Level: beginner

.seealso: `VSHMMSpectralCreateVec()`
@*/
PetscErrorCode VSHMMSpectralSetInitialCondition(VSHMMSpectral sp, Vec U)
{
  std::vector<double> u, c;
  PetscInt            lo, hi;
  PetscScalar        *x;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidHeaderSpecific(U, VEC_CLASSID, 2);
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(VSHMMSpectralSampleField_Private(sp, "u0", sp->data->u0, u));
  c.resize(sp->data->layout->size());
  sp->data->op->analyze(u.data(), c.data());
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  PetscCall(VecGetArray(U, &x));
  for (PetscInt i = lo; i < hi; ++i) x[i - lo] = c[i];
  PetscCall(VecRestoreArray(U, &x));
  sp->data->growth_started     = PETSC_FALSE; /* the growth and truncation checks start from this state */
  sp->data->truncation_started = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode VSHMMSpectralGetCoefficients_Private(VSHMMSpectral sp, Vec U, const PetscScalar **c)
{
  VSHMMSpectral_Data *s = sp->data;
  PetscMPIInt         size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)sp), &size));
  if (size == 1) PetscCall(VecGetArrayRead(U, c));
  else {
    if (!s->gather) PetscCall(VecScatterCreateToAll(U, &s->gather, &s->Useq));
    PetscCall(VecScatterBegin(s->gather, U, s->Useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(s->gather, U, s->Useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(s->Useq, c));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode VSHMMSpectralRestoreCoefficients_Private(VSHMMSpectral sp, Vec U, const PetscScalar **c)
{
  PetscFunctionBegin;
  if (sp->data->gather) PetscCall(VecRestoreArrayRead(sp->data->Useq, c));
  else PetscCall(VecRestoreArrayRead(U, c));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetGridValues - u(x_j), j = 0..N-1, of a state, on every rank

   Collective

   Input Parameters:
+  sp - the object
-  U  - a state Vec

   Output Parameter:
.  u - N values (caller's array)

   Level: intermediate

.seealso: `VSHMMSpectralGetModeMagnitudes()`, `VSHMMSpectralReadGridValues()`
@*/
PetscErrorCode VSHMMSpectralGetGridValues(VSHMMSpectral sp, Vec U, PetscReal u[])
{
  const PetscScalar *c;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidHeaderSpecific(U, VEC_CLASSID, 2);
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(VSHMMSpectralGetCoefficients_Private(sp, U, &c));
  sp->data->op->synthesize(c, u);
  PetscCall(VSHMMSpectralRestoreCoefficients_Private(sp, U, &c));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetModeMagnitudes - |c_k| of the retained wavenumbers of a state, on every rank,
   in the order of `VSHMMSpectralGetModes()`

   Collective

   Input Parameters:
+  sp - the object
-  U  - a state Vec

   Output Parameter:
.  mags - one value per retained wavenumber (caller's array): Fourier series coefficients; the
          unitary DFT magnitude is sqrt(N) |c_k|

   Level: intermediate

.seealso: `VSHMMSpectralGetModes()`, `VSHMMSpectralGetGridValues()`
@*/
PetscErrorCode VSHMMSpectralGetModeMagnitudes(VSHMMSpectral sp, Vec U, PetscReal mags[])
{
  const PetscScalar *c;
  const spc::Layout *l;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidHeaderSpecific(U, VEC_CLASSID, 2);
  PetscCall(VSHMMSpectralSetUp(sp));
  l = sp->data->layout.get();
  PetscCall(VSHMMSpectralGetCoefficients_Private(sp, U, &c));
  for (int i = 0; i < l->modeCount(); ++i) {
    const int k = l->mode(i), o = l->offset(i);
    mags[i] = spc::isRealOnly(l->N(), k) ? std::fabs(c[o]) : std::hypot(c[o], c[o + 1]);
  }
  PetscCall(VSHMMSpectralRestoreCoefficients_Private(sp, U, &c));
  PetscFunctionReturn(0);
}

/* u_x and its products with the fields for the state (U, t), unless they are those of the last call. */
static PetscErrorCode EnsurePhysical(VSHMMSpectral sp, Vec U, PetscReal t)
{
  VSHMMSpectral_Data *s = sp->data;
  PetscObjectId       id;
  PetscObjectState    state;
  const PetscScalar  *c;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetId((PetscObject)U, &id));
  PetscCall(PetscObjectStateGet((PetscObject)U, &state));
  if (s->cache_valid && id == s->cache_id && state == s->cache_state && t == s->cache_t) {
    s->stats.cache_hits++;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Physical, sp, 0, 0, 0));
  PetscCall(VSHMMSpectralGetCoefficients_Private(sp, U, &c));
  s->op->computePhysical(c);
  PetscCall(VSHMMSpectralRestoreCoefficients_Private(sp, U, &c));
  PetscCall(PetscLogFlops(2.5 * s->N * std::log2((double)s->N) + 2.0 * s->N));
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Physical, sp, 0, 0, 0));
  s->stats.inverse_ffts += s->op->inversePerState();
  s->cache_valid  = PETSC_TRUE;
  s->cache_id     = id;
  s->cache_state  = state;
  s->cache_t      = t;
  s->fft_done     = PETSC_FALSE;
  s->direct_spent = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode EnsureForward(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s = sp->data;

  PetscFunctionBegin;
  if (s->fft_done) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_ForwardFFT, sp, 0, 0, 0));
  s->op->computeForward();
  const int kinds = s->op->forwardPerState();
  PetscCall(PetscLogFlops(kinds * 2.5 * s->N * std::log2((double)s->N)));
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_ForwardFFT, sp, 0, 0, 0));
  s->stats.forward_ffts += kinds;
  s->fft_done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The dense operator's rows [rb, re) times the state, into s->out (matrix evaluation). */
static PetscErrorCode ApplyDenseRows(VSHMMSpectral sp, Vec U, int rb, int re)
{
  VSHMMSpectral_Data *s = sp->data;
  const PetscScalar  *c;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_MatVec, sp, 0, 0, 0));
  PetscCall(VSHMMSpectralGetCoefficients_Private(sp, U, &c));
  s->dense->applyRows(rb, re, c, s->out.data());
  PetscCall(VSHMMSpectralRestoreCoefficients_Private(sp, U, &c));
  PetscCall(PetscLogFlops(2.0 * (re - rb) * s->layout->size()));
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_MatVec, sp, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* F's entries [ob, oe) from vals (vals[0] is entry ob); with zero_rest the other owned entries are zeroed. */
static PetscErrorCode WriteRange(Vec F, PetscInt ob, PetscInt oe, const double *vals, bool zero_rest)
{
  PetscInt     lo, hi;
  PetscScalar *f;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(F, &lo, &hi));
  PetscCall(VecGetArray(F, &f));
  if (zero_rest)
    for (PetscInt i = lo; i < hi; ++i) f[i - lo] = 0.0;
  for (PetscInt i = PetscMax(lo, ob); i < PetscMin(hi, oe); ++i) f[i - lo] = vals[i - ob];
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralRHSFunction - The full right-hand side F(u) on the retained coefficients (the
   `TSRHSFunction` set by `VSHMMSpectralSetUpTS()`; ctx is the VSHMMSpectral)

   Collective

   Level: developer

.seealso: `VSHMMSpectralSetUpTS()`
@*/
PetscErrorCode VSHMMSpectralRHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  VSHMMSpectral       sp = (VSHMMSpectral)ctx;
  VSHMMSpectral_Data *s;

  PetscFunctionBegin;
  (void)ts;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 5);
  s = sp->data;
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_RHS, sp, 0, 0, 0));
  s->stats.rhs_calls++;
  s->stats.field_evaluations++;
  if (s->dense) PetscCall(ApplyDenseRows(sp, U, 0, s->layout->size()));
  else {
    PetscCall(EnsurePhysical(sp, U, t));
    PetscCall(EnsureForward(sp));
    s->op->extractForward(0, s->layout->modeCount(), s->out.data());
  }
  PetscCall(WriteRange(F, 0, s->layout->size(), s->out.data(), false));
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_RHS, sp, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Split j: P_j F (the right-hand side projected on cluster j) in every entry, zeros outside cluster j. */
static PetscErrorCode SplitRHS(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  SplitCtx           *split = (SplitCtx *)ctx;
  VSHMMSpectral       sp    = split->sp;
  VSHMMSpectral_Data *s     = sp->data;
  const int           j = (int)split->j, mb = s->layout->clusterModeBegin(j), me = s->layout->clusterModeEnd(j);
  const int           ob = s->layout->clusterOffsetBegin(j), oe = s->layout->clusterOffsetEnd(j);

  PetscFunctionBegin;
  (void)ts;
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Split, sp, 0, 0, 0));
  s->stats.split_calls++;
  if (j == 0) s->stats.field_evaluations++;
  if (s->dense) PetscCall(ApplyDenseRows(sp, U, ob, oe));
  else {
    PetscCall(EnsurePhysical(sp, U, t));
    bool direct = false;
    if (!s->fft_done) {
      if (s->projection == VSHMMSPECTRAL_PROJECTION_DIRECT) direct = true;
      else if (s->projection == VSHMMSPECTRAL_PROJECTION_AUTO) direct = !s->op->hasPadded() && s->direct_spent + (me - mb) <= s->op->directModesPerForward();
    }
    if (direct) {
      PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_ProjDirect, sp, 0, 0, 0));
      s->op->projectDirect(mb, me, s->out.data(), ob);
      const int kinds = (s->op->hasDiffusion() ? 1 : 0) + (s->op->hasAdvection() ? 1 : 0);
      PetscCall(PetscLogFlops(4.0 * kinds * (me - mb) * s->N));
      PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_ProjDirect, sp, 0, 0, 0));
      s->direct_spent += me - mb;
      s->stats.direct_modes += me - mb;
    } else {
      PetscCall(EnsureForward(sp));
      s->op->extractForward(mb, me, s->out.data(), ob);
    }
  }
  PetscCall(WriteRange(F, ob, oe, s->out.data(), true));
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Split, sp, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetUpTS - Gives the TS the full right-hand side and, in mode sparse, one additive
   RHS split per cluster ("K0" slowest, "K1", ...)

   Collective

   Input Parameters:
+  sp - the object
-  ts - the TS (with its solution Vec set)

   Notes:
   Split j returns P_j F, the right-hand side projected on cluster j, in every entry of a
   full-size vector (zeros outside cluster j): the splits add up to the full right-hand side.
   The physical-space field of a state is computed once and shared by the splits called with
   that state (same Vec, object state and time), as TSVSHMM does on each level.
   It declares the problem type: `TS_NONLINEAR` with the terms burgers or a reaction of degree 2
   or 3, else `TS_LINEAR` (diffusion, advection, source and an affine reaction), so an implicit TS
   type solves each stage by Newton's method, or by one linear solve where that is exact.
   It also sets the TS monitor `VSHMMSpectralGrowthMonitor()`, which stops the solve with an error
   when the solution grows beyond what the scene's terms allow (-spectral_growth_bound; 0: never).

   Level: beginner

.seealso: `VSHMMSpectralSetUp()`, `TSRHSSplitSetIS()`
@*/
PetscErrorCode VSHMMSpectralSetUpTS(VSHMMSpectral sp, TS ts)
{
  VSHMMSpectral_Data *s;
  Vec                 U;
  PetscInt            lo, hi;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidHeaderSpecific(ts, TS_CLASSID, 2);
  PetscCall(VSHMMSpectralSetUp(sp));
  s = sp->data;
  PetscCall(TSSetRHSFunction(ts, NULL, VSHMMSpectralRHSFunction, sp));
  PetscCall(TSSetProblemType(ts, s->op && s->op->isNonlinear() ? TS_NONLINEAR : TS_LINEAR));                              /* implicit types: Newton, or one linear solve per stage */
  PetscCall(TSMonitorSet(ts, VSHMMSpectralGrowthMonitor, sp, NULL));                                                      /* the growth check, spectralstable.cpp */
  if (sp->data->mode == VSHMMSPECTRAL_MODE_SPARSE) PetscCall(TSMonitorSet(ts, VSHMMSpectralTruncationMonitor, sp, NULL)); /* the truncation check */
  if (s->mode != VSHMMSPECTRAL_MODE_SPARSE) PetscFunctionReturn(0);
  PetscCall(TSGetSolution(ts, &U));
  PetscCheck(U, PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONGSTATE, "VSHMMSpectralSetUpTS(): call TSSetSolution() first");
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  s->split_ctx.assign(s->layout->clusterCount(), SplitCtx{sp, 0});
  for (int j = 0; j < s->layout->clusterCount(); ++j) {
    IS   is;
    char name[32];

    s->split_ctx[j].j = j;
    PetscCall(PetscSNPrintf(name, sizeof(name), "K%d", j));
    PetscCall(ISCreateStride(PetscObjectComm((PetscObject)sp), hi - lo, lo, 1, &is));
    PetscCall(TSRHSSplitSetIS(ts, name, is));
    PetscCall(TSRHSSplitSetRHSFunction(ts, name, NULL, SplitRHS, &s->split_ctx[j]));
    PetscCall(ISDestroy(&is));
  }
  PetscFunctionReturn(0);
}
