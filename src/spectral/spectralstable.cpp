/*
  VSHMMSpectral: stable time steps from the operator's eigenvalues and the growth check.

  Stable steps: kArnoldiSteps Arnoldi steps on the Jacobian of F at the initial state (applied
  by finite differences of the operator, so a nonlinear term is linearised there; for the linear
  terms it is the operator itself) in the Parseval inner product, in which the diffusion
  operator is symmetric. The Ritz values approximate the extreme eigenvalues from inside, so the
  step for a Runge-Kutta method, the largest h with h lambda in its stability region for every
  Ritz value lambda (growing modes, Re lambda > 0.1 |lambda|, left out as TSVSHMM does), is
  scaled by kSafety. Computed once per set-up (a few dozen operator applications) and shared by
  every call.

  Growth check: a TS monitor (set by VSHMMSpectralSetUpTS()) compares, every kGrowthInterval
  steps and at the final time, the root-mean-square norm of the state (Parseval) with
  growth_factor times the a-priori bound of the scene's terms (GrowthModel in
  src/core/spectral/stable.hpp) and stops the solve with an error above it.
*/
#include "spectralimpl.hpp"

#include <climits>

#include <petscblaslapack.h>

#include "stability.hpp"

#include <cmath>

static constexpr int       kArnoldiSteps    = 40;
static constexpr PetscReal kSafety          = 0.9;
static constexpr PetscReal kGrowingMode     = 0.1;  /* Re lambda > this |lambda|: a growing mode, not limiting */
static constexpr PetscInt  kGrowthInterval  = 8;    /* the growth check looks at every 8th step */
static constexpr PetscReal kTruncationLooks = 64;   /* the truncation check looks after each 1/64 of a solve's span */
static constexpr PetscInt  kTruncationEvery = 1024; /* and at every 1024th step */
static constexpr PetscInt  kMaxWidenings    = 6;    /* -spectral_truncation_check widen: then it warns */
static constexpr PetscReal kWarnAgain       = 4;    /* a run warns again where the share grew this much since its last warning */
static constexpr PetscReal kSeparated       = 10;   /* clusters this far apart in time scale are separated (TSVSHMM's measure): a widening keeps them so */

PetscErrorCode VSHMMSpectralRitzValues_Private(MPI_Comm comm, spc::SpectralOperator &op, const std::vector<double> &c0, std::vector<std::complex<double>> &ritz, PetscInt *evaluations)
{
  const int                 n       = op.layout().size();
  const std::vector<double> weights = spc::parsevalWeights(op.layout());
  std::vector<double>       F0(n), cp(n), Fp(n);

  PetscFunctionBegin;
  const spc::SpectralOperator::Counters saved = op.counters();
  op.apply(c0.data(), F0.data());
  double norm = 0;
  for (int i = 0; i < n; ++i) norm += weights[i] * c0[i] * c0[i];
  const double delta = std::sqrt(PETSC_MACHINE_EPSILON) * (1.0 + std::sqrt(norm)); /* the start and Krylov vectors have unit norm */
  /* J v ~ (F(c0 + delta v) - F(c0)) / delta */
  spc::ArnoldiResult ar = spc::arnoldi(
    [&](const double *v, double *w) {
      for (int i = 0; i < n; ++i) cp[i] = c0[i] + delta * v[i];
      op.apply(cp.data(), Fp.data());
      for (int i = 0; i < n; ++i) w[i] = (Fp[i] - F0[i]) / delta;
    },
    weights, kArnoldiSteps);
  op.counters() = saved;
  if (evaluations) *evaluations = ar.k + 1; /* F(c0) and one per Arnoldi step */
  PetscCheck(ar.finite, comm, PETSC_ERR_FP, "The spectral operator is not finite near the initial state: no stable time step can be estimated");
  ritz.clear();
  if (ar.k > 0) {
    std::vector<PetscScalar> work(8 * ar.k + 8);
    std::vector<PetscReal>   wr(ar.k), wi(ar.k);
    PetscBLASInt             k, lwork = (PetscBLASInt)work.size(), one = 1, info;
    PetscCall(PetscBLASIntCast(ar.k, &k));
    PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &k, ar.H.data(), &k, wr.data(), wi.data(), nullptr, &one, nullptr, &one, work.data(), &lwork, &info));
    PetscCheck(!info, comm, PETSC_ERR_LIB, "LAPACK geev failed (info %d) on the Arnoldi matrix of the spectral operator", (int)info);
    for (int i = 0; i < ar.k; ++i) ritz.emplace_back(wr[i], wi[i]);
  }
  PetscFunctionReturn(0);
}

/* The Ritz values of the Jacobian of the operator op (the object's layout or the full one) at the
   initial state. */
static PetscErrorCode RitzAtInitialState(VSHMMSpectral sp, spc::SpectralOperator &op, std::vector<std::complex<double>> &ritz)
{
  std::vector<double> u0, c0(op.layout().size());

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSampleField_Private(sp, "u0", sp->data->u0, u0));
  op.analyze(u0.data(), c0.data());
  PetscCall(VSHMMSpectralRitzValues_Private(PetscObjectComm((PetscObject)sp), op, c0, ritz, nullptr));
  PetscFunctionReturn(0);
}

/* The Ritz values of the Jacobian of F at the initial state (cached until the next set-up). */
static PetscErrorCode OperatorRitzValues(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s = sp->data;
  std::vector<double> D, A;

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  if (s->ritz_done) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Eigen, sp, 0, 0, 0));
  PetscCall(VSHMMSpectralBuildCoefficients_Private(sp, D, A));
  s->radius_bound = spc::spectralRadiusBound(D, A, s->layout->modes().back());
  PetscCall(RitzAtInitialState(sp, *s->op, s->ritz));
  s->cache_valid = PETSC_FALSE; /* the operator's buffers were used */
  s->ritz_done   = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Eigen, sp, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The Butcher tableau of a TSRK type. */
static PetscErrorCode RKTableau(MPI_Comm comm, TSRKType type, std::unique_ptr<vshmm::Tableau> &tab)
{
  TS               rk;
  PetscInt         s, p;
  const PetscReal *a, *b, *c;

  PetscFunctionBegin;
  PetscCall(TSCreate(PETSC_COMM_SELF, &rk));
  PetscCall(TSSetType(rk, TSRK));
  PetscCall(TSRKSetType(rk, type));
  PetscCall(TSRKGetTableau(rk, &s, &a, &b, &c, nullptr, nullptr, nullptr, nullptr));
  PetscCall(TSRKGetOrder(rk, &p));
  try {
    tab = std::make_unique<vshmm::Tableau>(type, (int)p, (int)s, std::vector<double>(a, a + s * s), std::vector<double>(b, b + s), std::vector<double>(c, c + s));
  } catch (const std::exception &e) {
    PetscCall(TSDestroy(&rk));
    SETERRQ(comm, PETSC_ERR_ARG_WRONG, "TSRK type %s: %s", type, e.what());
  }
  PetscCall(TSDestroy(&rk));
  PetscFunctionReturn(0);
}

PetscErrorCode VSHMMSpectralStableStepOf_Private(MPI_Comm comm, const std::vector<std::complex<double>> &ritz, TSRKType type, PetscReal *dt)
{
  std::unique_ptr<vshmm::Tableau> tab;

  PetscFunctionBegin;
  PetscCall(RKTableau(comm, type, tab));
  const vshmm::StabilityFunction R(*tab);
  double                         h = PETSC_INFINITY;
  for (const std::complex<double> &lambda : ritz) {
    if (std::abs(lambda) == 0 || lambda.real() > kGrowingMode * std::abs(lambda)) continue;
    h = std::min(h, R.largestStableStep(lambda));
  }
  *dt = h < PETSC_INFINITY ? kSafety * h : PETSC_INFINITY; /* PETSC_INFINITY is finite: compared, not std::isfinite() */
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetStableTimeStep - A stable step of an explicit Runge-Kutta method for the
   scene's operator on the retained modes (every mode in mode dns), from an estimate of its
   extreme eigenvalues

   Collective (sets the object up if needed)

   Input Parameters:
+  sp - the object
-  type - a TSRK type (TSRK3, TSRK4, ...)

   Output Parameter:
.  dt - the step (PETSC_INFINITY if no eigenvalue limits it)

   Notes:
   Forty Arnoldi steps on the operator's Jacobian at the initial state (finite differences of the
   operator; the linear terms are exact) give Ritz values lambda; dt is 0.9 times the largest h
   with h lambda in the method's stability region for every Ritz value that does not grow
   (Re lambda <= 0.1 |lambda|). The estimate is made once per set-up (about 40 operator
   evaluations) and shared by later calls for any type. On the paper's scenes and the reduced test
   scenes dt lies between 0.7 and 0.9 times the largest stable RK3 step found by bisection
   (docs/spectral.md). The step of the whole operator is also the bound of TSVSHMM's micro step
   (the fastest level evaluates the whole field).

   Level: intermediate

.seealso: `VSHMMSpectralGetSpectralRadius()`, `VSHMMSpectralSetUp()`, `TSVSHMMSetMicroStep()`
@*/
PetscErrorCode VSHMMSpectralGetStableTimeStep(VSHMMSpectral sp, TSRKType type, PetscReal *dt)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidPointer(type, 2);
  VSHMMValidPointer(dt, 3);
  PetscCall(OperatorRitzValues(sp));
  PetscCall(VSHMMSpectralStableStepOf_Private(PetscObjectComm((PetscObject)sp), sp->data->ritz, type, dt));
  double radius = 0;
  for (const std::complex<double> &lambda : sp->data->ritz) radius = std::max(radius, std::abs(lambda));
  PetscCall(PetscInfo(sp, "stable step of TSRK %s: %g (spectral radius estimate %g, bound %g)\n", type, (double)*dt, radius, (double)sp->data->radius_bound));
  PetscFunctionReturn(0);
}

/* Whether F's Jacobian depends on the state: a burgers term, or a reaction with c2 or c3. */
static bool SceneIsNonlinear(const VSHMMSpectral_Data *s)
{
  for (const std::string &t : s->terms) {
    if (t == "burgers") return true;
    if (t == "reaction")
      for (size_t i = 2; i < s->reaction.size(); ++i)
        if (s->reaction[i] != 0) return true;
  }
  return false;
}

/*@C
   VSHMMSpectralGetStableTimeStepAt - A stable step of an explicit Runge-Kutta method for the
   operator linearised at a given state (`VSHMMSpectralGetStableTimeStep()` linearises at the
   initial state)

   Collective

   Input Parameters:
+  sp - the object
.  U - a state Vec (`VSHMMSpectralCreateVec()`)
-  type - a TSRK type (TSRK3, TSRK4, ...)

   Output Parameter:
.  dt - the step (PETSC_INFINITY if no eigenvalue limits it)

   Notes:
   For a scene whose Jacobian depends on the state (a burgers term, or a reaction with c2 or c3
   nonzero) this is a new estimate at U (forty Arnoldi steps: about 40 operator evaluations, event
   SpecEigen): a solution whose amplitude or gradients grow can need a smaller step than at u0.
   For a linear scene the Jacobian is the same at every state and the estimate of
   `VSHMMSpectralGetStableTimeStep()` is returned (no work).

   Level: intermediate

.seealso: `VSHMMSpectralGetStableTimeStep()`, `VSHMMSpectralGetSpectralRadius()`
@*/
PetscErrorCode VSHMMSpectralGetStableTimeStepAt(VSHMMSpectral sp, Vec U, TSRKType type, PetscReal *dt)
{
  VSHMMSpectral_Data               *s;
  const PetscScalar                *c;
  std::vector<std::complex<double>> ritz;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidHeaderSpecific(U, VEC_CLASSID, 2);
  VSHMMValidPointer(type, 3);
  VSHMMValidPointer(dt, 4);
  PetscCall(VSHMMSpectralSetUp(sp));
  s = sp->data;
  if (!SceneIsNonlinear(s)) {
    PetscCall(VSHMMSpectralGetStableTimeStep(sp, type, dt));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Eigen, sp, 0, 0, 0));
  PetscCall(VSHMMSpectralGetCoefficients_Private(sp, U, &c));
  const std::vector<double> cu(c, c + s->layout->size());
  PetscCall(VSHMMSpectralRestoreCoefficients_Private(sp, U, &c));
  PetscCall(VSHMMSpectralRitzValues_Private(PetscObjectComm((PetscObject)sp), *s->op, cu, ritz, nullptr));
  s->cache_valid = PETSC_FALSE; /* the operator's buffers were used */
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Eigen, sp, 0, 0, 0));
  PetscCall(VSHMMSpectralStableStepOf_Private(PetscObjectComm((PetscObject)sp), ritz, type, dt));
  double radius = 0;
  for (const std::complex<double> &lambda : ritz) radius = std::max(radius, std::abs(lambda));
  PetscCall(PetscInfo(sp, "stable step of TSRK %s at the given state: %g (spectral radius estimate %g)\n", type, (double)*dt, radius));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetSpectralRadius - The estimated spectral radius of the operator on the retained
   modes (the largest Ritz value of `VSHMMSpectralGetStableTimeStep()`) and an upper bound of it

   Collective (sets the object up if needed)

   Input Parameter:
.  sp - the object

   Output Parameters:
+  radius - the estimate (from inside: at most the true spectral radius), or NULL
-  bound - max|d| kmax^2 + max|a| kmax, kmax the largest retained wavenumber: a bound on the
           operator's norm, so on every eigenvalue, or NULL

   Level: intermediate

.seealso: `VSHMMSpectralGetStableTimeStep()`
@*/
PetscErrorCode VSHMMSpectralGetSpectralRadius(VSHMMSpectral sp, PetscReal *radius, PetscReal *bound)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(OperatorRitzValues(sp));
  if (radius) {
    *radius = 0;
    for (const std::complex<double> &l : sp->data->ritz) *radius = PetscMax(*radius, std::abs(l));
  }
  if (bound) *bound = sp->data->radius_bound;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralEstimateTimeStep - A stable step of the 3-stage Runge-Kutta method TSRK3 for the
   retained modes: `VSHMMSpectralGetStableTimeStep()` with TSRK3

   Collective (sets the object up if needed)

   Input Parameter:
.  sp - the object

   Output Parameter:
.  dt - the step

   Level: intermediate

.seealso: `VSHMMSpectralGetStableTimeStep()`
@*/
PetscErrorCode VSHMMSpectralEstimateTimeStep(VSHMMSpectral sp, PetscReal *dt)
{
  PetscFunctionBegin;
  PetscCall(VSHMMSpectralGetStableTimeStep(sp, TSRK3, dt));
  PetscFunctionReturn(0);
}

/* The growth model of the scene's terms. */
static PetscErrorCode SceneGrowthModel(VSHMMSpectral sp, spc::GrowthModel &model)
{
  VSHMMSpectral_Data *s = sp->data;
  std::vector<double> D, A;

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralBuildCoefficients_Private(sp, D, A));
  model = spc::GrowthModel();
  if (!D.empty()) model.addDiffusion(D, s->layout->modes().back());
  if (!A.empty()) {
    for (double &a : A) a = -a; /* the velocity */
    model.addAdvection(A);
  }
  spc::ExtraTerms extra;
  PetscCall(VSHMMSpectralBuildExtraTerms_Private(sp, extra));
  if (!extra.burgers.empty()) model.addBurgers(extra.burgers);
  if (!extra.rate.empty()) model.addReaction(extra.rate, extra.reaction);
  if (!extra.source.empty()) model.addSource(extra.source);
  PetscFunctionReturn(0);
}

/* The root-mean-square norm of a state (Parseval) and, if wanted, max|u| on the grid. */
static PetscErrorCode StateNorms(VSHMMSpectral sp, Vec U, PetscReal *norm, PetscReal *maxu)
{
  VSHMMSpectral_Data *s = sp->data;
  const PetscScalar  *x;
  PetscInt            lo, hi;
  PetscReal           sum = 0;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  PetscCall(VecGetArrayRead(U, &x));
  for (PetscInt i = lo; i < hi; ++i) sum += s->weights[i] * PetscRealPart(x[i - lo] * x[i - lo]);
  PetscCall(VecRestoreArrayRead(U, &x));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)sp)));
  *norm = std::sqrt(sum);
  if (maxu) {
    std::vector<PetscReal> u(s->N);
    PetscCall(VSHMMSpectralGetGridValues(sp, U, u.data()));
    *maxu = 0;
    for (PetscReal v : u) *maxu = PetscMax(*maxu, PetscAbsReal(v)); /* NaN stays out: the norm catches it */
  }
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGrowthMonitor - The TS monitor of the growth check (set by `VSHMMSpectralSetUpTS()`):
   stops the solve with an error when the solution's norm exceeds the bound of the scene's terms
   times the growth factor

   Collective

   Input Parameters:
+  ts - the TS
.  step - the step number
.  t - the time
.  U - the state
-  ctx - the VSHMMSpectral

   Notes:
   The norm is the root mean square of u over the grid (Parseval on the retained coefficients),
   checked at every 8th step and at the TS's final time (a blow-up grows geometrically, so a few
   steps later is as good; the check costs one pass over the state). The first call (and any
   call at a time before the last one checked, a new run) takes the state as the initial one.
   With the factor 0 (-spectral_growth_bound 0, `VSHMMSpectralSetGrowthBound()`) it does
   nothing. See docs/spectral.md for the bound of each term.

   Level: developer

.seealso: `VSHMMSpectralSetGrowthBound()`, `VSHMMSpectralSetUpTS()`
@*/
PetscErrorCode VSHMMSpectralGrowthMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  VSHMMSpectral       sp = (VSHMMSpectral)ctx;
  VSHMMSpectral_Data *s;
  spc::GrowthModel    model;
  PetscReal           norm, maxu = 0;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 5);
  s = sp->data;
  if (s->growth_factor <= 0) PetscFunctionReturn(0);
  if (s->growth_started && t >= s->growth.time() && step % kGrowthInterval) { /* checked every few steps, and at the end of a solve */
    PetscReal tmax;
    PetscCall(TSGetMaxTime(ts, &tmax));
    if (t < tmax - 1e-12 * PetscMax(1.0, PetscAbsReal(tmax))) PetscFunctionReturn(0);
  }
  if (!s->growth_started || t < s->growth.time()) {
    PetscCall(SceneGrowthModel(sp, model));
    PetscCall(StateNorms(sp, U, &norm, &maxu));
    s->growth           = spc::GrowthBound(model, t, norm, maxu);
    s->growth_needs_max = model.needsMax() ? PETSC_TRUE : PETSC_FALSE;
    s->growth_max       = maxu;
    s->growth_started   = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Growth, sp, 0, 0, 0));
  PetscCall(StateNorms(sp, U, &norm, s->growth_needs_max ? &maxu : nullptr));
  s->growth.advance(t, PetscMax(maxu, s->growth_max));
  s->growth_max           = maxu;
  const PetscReal allowed = s->growth_factor * s->growth.bound();
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Growth, sp, 0, 0, 0));
  if (!(norm <= allowed)) {
    PetscReal dt = 0;
    PetscCall(VSHMMSpectralGetStableTimeStep(sp, TSRK3, &dt));
    SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_NOT_CONVERGED, "The solution blew up at t = %g: its L2 norm (RMS over the grid, Parseval) %g %s %g, -%sspectral_growth_bound %g times the bound %g that the scene's terms allow (initial norm %g). The time step is probably unstable: the operator's stable step is %g for TSRK3 (VSHMMSpectralGetStableTimeStep()); lower -ts_dt, or for TSVSHMM -ts_vshmm_micro_dt or the savings factors. -%sspectral_growth_bound 0 switches the check off", (double)t, (double)norm, std::isfinite(norm) ? "exceeds" : "(Inf or NaN) is not below", (double)allowed, VSHMMSpectralPrefix(sp),
            (double)s->growth_factor, (double)s->growth.bound(), (double)s->growth.initialNorm(), (double)dt, VSHMMSpectralPrefix(sp));
  }
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetGrowthBound - Sets the factor of the growth check: a solve stops with an error
   when the solution's L2 norm exceeds factor times the bound the scene's terms allow

   Logically collective

   Input Parameters:
+  sp - the object
-  factor - 0 (no check) or at least 1; default 10

   Options Database Key:
.  -spectral_growth_bound <factor> - the factor

   Level: intermediate

.seealso: `VSHMMSpectralGrowthMonitor()`, `VSHMMSpectralSetUpTS()`
@*/
PetscErrorCode VSHMMSpectralSetGrowthBound(VSHMMSpectral sp, PetscReal factor)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCheck(std::isfinite(factor) && (factor == 0 || factor >= 1), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "The growth bound factor (-%sspectral_growth_bound) must be 0 (no check) or a finite factor >= 1, got %g", VSHMMSpectralPrefix(sp), (double)factor);
  sp->data->growth_factor = factor;
  PetscFunctionReturn(0);
}

/*@
   VSHMMSpectralSetTruncationCheck - Sets what the truncation check of a sparse run does when the
   dynamics drive the wavenumbers that the clusters leave out beyond the clusters' tolerance

   Logically collective

   Input Parameters:
+  sp - the object
-  check - `VSHMMSPECTRAL_TRUNCATION_NONE`, `VSHMMSPECTRAL_TRUNCATION_WARN` (default), `VSHMMSPECTRAL_TRUNCATION_ERROR` or `VSHMMSPECTRAL_TRUNCATION_WIDEN`

   Options Database Key:
.  -spectral_truncation_check <none,warn,error,widen> - the same

   Notes:
   With `VSHMMSPECTRAL_TRUNCATION_WIDEN` the check records, instead of a warning, the buffers
   (`-spectral_cluster_buffers`) that would hold the wavenumbers it names. The program sees it with
   `VSHMMSpectralGetTruncationWidening()` (e.g. in a post-step function that ends the solve with
   `TSSetConvergedReason()`), calls `VSHMMSpectralWidenClusters()`, creates its state and TS again
   and runs from its initial state: the examples do (docs/spectral.md, "Widening the clusters and
   running again"). Where the widened clusters would not be separated (a time-scale ratio below
   10) it asks for every wavenumber (a direct simulation) if its figure passes the tolerance in the
   TS's own measure (atol + rtol ||u||), and warns otherwise. After six widenings, or where the
   model of the wavenumbers named rests on advection's detuning (which reads up to several times
   above the truth), the check warns as with `VSHMMSPECTRAL_TRUNCATION_WARN`, and so it does at
   the end of a solve that ran on for more than a step after a request not applied.

   Level: intermediate

.seealso: `VSHMMSpectralTruncationMonitor()`, `VSHMMSpectralSetClusterTolerance()`, `VSHMMSpectralGetStatistics()`, `VSHMMSpectralWidenClusters()`
@*/
PetscErrorCode VSHMMSpectralSetTruncationCheck(VSHMMSpectral sp, VSHMMSpectralTruncationCheck check)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCheck(check >= VSHMMSPECTRAL_TRUNCATION_NONE && check <= VSHMMSPECTRAL_TRUNCATION_WIDEN, PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "Unknown truncation check %d (-%sspectral_truncation_check): none (0), warn (1), error (2) or widen (3)", (int)check, VSHMMSpectralPrefix(sp));
  sp->data->truncation_check = check;
  PetscFunctionReturn(0);
}

/* The clusters widened by `buffers` (one per cluster), without overlaps (spc::widenClusters()). */
static PetscErrorCode WidenedClusters(VSHMMSpectral sp, const std::vector<int> &buffers, spc::ClusterSet *widened)
{
  VSHMMSpectral_Data *s = sp->data;
  spc::ClusterSet     current;

  PetscFunctionBegin;
  current.N = (int)s->N;
  for (const auto &m : s->cluster_modes) current.clusters.emplace_back(m.begin(), m.end());
  try {
    *widened = spc::widenClusters(current, buffers);
  } catch (const std::exception &e) {
    SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_LIB, "widening the clusters: %s", e.what());
  }
  PetscFunctionReturn(0);
}

/*@
   VSHMMSpectralGetTruncationWidening - Tells whether the truncation check (with
   `VSHMMSPECTRAL_TRUNCATION_WIDEN`) asks for wider clusters

   Not collective

   Input Parameter:
.  sp - the object

   Output Parameters:
+  pending - `PETSC_TRUE` where a widening was asked for and `VSHMMSpectralWidenClusters()` has not applied it yet
-  t - the time of the check that asked for it (pass NULL if not wanted)

   Notes:
   A program that restarts calls this in a post-step function (`TSSetPostStep()`) and ends the
   solve with `TSSetConvergedReason(ts, TS_CONVERGED_USER)` where it is true, and after each
   `TSSolve()`; the same on every rank.

   Level: intermediate

.seealso: `VSHMMSpectralSetTruncationCheck()`, `VSHMMSpectralWidenClusters()`
@*/
PetscErrorCode VSHMMSpectralGetTruncationWidening(VSHMMSpectral sp, PetscBool *pending, PetscReal *t)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscValidBoolPointer(pending, 2);
  *pending = sp->data->widen_buffers.empty() ? PETSC_FALSE : PETSC_TRUE;
  if (t) *t = sp->data->widen_time;
  PetscFunctionReturn(0);
}

/*@
   VSHMMSpectralWidenClusters - Widens the clusters as the truncation check asked for
   (`VSHMMSPECTRAL_TRUNCATION_WIDEN`) and sets the object up again on them

   Collective

   Input Parameter:
.  sp - the object

   Output Parameter:
.  widened - `PETSC_TRUE` where the clusters were widened (a widening was pending)

   Notes:
   Each cluster gains the buffer the check named for it, as `-spectral_cluster_buffers` adds one:
   the distance of the left-out wavenumbers it modelled largest to their nearest cluster, at least
   half the width of the band of retained wavenumbers nearest to each; a wavenumber that two
   clusters' buffers reach goes to the nearer (`spc::widenClusters()`). The number of clusters and
   the detection's figures stay (no detection again), but where the check asked for every
   wavenumber: then one cluster of all of them (a direct simulation). The state's size
   changes: the program destroys its Vec and TS, creates them again (`VSHMMSpectralCreateVec()`,
   `VSHMMSpectralSetInitialCondition()`, `VSHMMSpectralSetUpTS()`) and runs from the initial state.
   The field evaluations of the stopped run are added to the statistics' `widening_evaluations`.

   Level: intermediate

.seealso: `VSHMMSpectralGetTruncationWidening()`, `VSHMMSpectralSetTruncationCheck()`, `VSHMMSpectralGetStatistics()`
@*/
PetscErrorCode VSHMMSpectralWidenClusters(VSHMMSpectral sp, PetscBool *widened)
{
  VSHMMSpectral_Data *s;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscValidBoolPointer(widened, 2);
  s        = sp->data;
  *widened = PETSC_FALSE;
  if (s->widen_buffers.empty()) PetscFunctionReturn(0);
  if (s->widen_all) { /* every wavenumber in one cluster: a direct simulation (the examples' explicit sparse method on one cluster) */
    s->widened.N = (int)s->N;
    s->widened.clusters.assign(1, {});
    for (int k = 0; k <= spc::maxWavenumber((int)s->N); ++k) s->widened.clusters[0].push_back(k);
    s->widen_all = PETSC_FALSE;
  } else PetscCall(WidenedClusters(sp, s->widen_buffers, &s->widened));
  s->widening_evaluations += s->stats.field_evaluations;
  s->widenings++;
  s->widen_buffers.clear();
  PetscCall(PetscInfo(sp, "truncation check: clusters widened (%d of at most %d widenings): %s\n", (int)s->widenings, (int)kMaxWidenings, s->widened.format().c_str()));
  sp->setupcalled = PETSC_FALSE;
  PetscCall(VSHMMSpectralSetUp(sp));
  *widened = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The operator on every wavenumber (Layout::full()) of the scene's fields D, A, extra, made once
   per set-up: the truncation check's and the DNS's stable step. */
static PetscErrorCode FullOperator(VSHMMSpectral sp, const std::vector<double> &D, const std::vector<double> &A, const spc::ExtraTerms &extra)
{
  VSHMMSpectral_Data *s = sp->data;

  PetscFunctionBegin;
  if (s->full_op) PetscFunctionReturn(0);
  s->full_layout = std::make_unique<spc::Layout>(spc::Layout::full((int)s->N));
  try {
    s->full_op = std::make_unique<spc::SpectralOperator>(*s->full_layout, D, A, extra, spc::Planner::Estimate);
  } catch (const std::exception &e) {
    SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_LIB, "Spectral operator on every wavenumber: %s", e.what());
  }
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetDNSStableTimeStep - The stable step of an explicit Runge-Kutta method for the
   scene's operator on every wavenumber (what a direct simulation, mode dns, steps by), in either mode

   Collective (sets the object up if needed)

   Input Parameters:
+  sp - the object
-  type - a TSRK type (TSRK3, TSRK4, ...)

   Output Parameter:
.  dt - the step (PETSC_INFINITY if no eigenvalue limits it)

   Notes:
   As `VSHMMSpectralGetStableTimeStep()` (forty Arnoldi steps at the initial state, 0.9 of the
   estimated limit), on the operator of every wavenumber: in mode dns the same value; in sparse
   mode about 41 evaluations on every mode, once per set-up. The examples set a sparse run's work
   against the DNS's at this step (docs/spectral.md, "Output contract").

   Level: intermediate

.seealso: `VSHMMSpectralGetStableTimeStep()`
@*/
PetscErrorCode VSHMMSpectralGetDNSStableTimeStep(VSHMMSpectral sp, TSRKType type, PetscReal *dt)
{
  VSHMMSpectral_Data *s;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidPointer(type, 2);
  VSHMMValidPointer(dt, 3);
  PetscCall(VSHMMSpectralSetUp(sp));
  s = sp->data;
  if (s->mode != VSHMMSPECTRAL_MODE_SPARSE) {
    PetscCall(VSHMMSpectralGetStableTimeStep(sp, type, dt));
    PetscFunctionReturn(0);
  }
  if (!s->dns_ritz_done) {
    if (!s->full_op) {
      std::vector<double> D, A;
      spc::ExtraTerms     extra;
      PetscCall(VSHMMSpectralBuildCoefficients_Private(sp, D, A));
      PetscCall(VSHMMSpectralBuildExtraTerms_Private(sp, extra));
      PetscCall(FullOperator(sp, D, A, extra));
    }
    PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Eigen, sp, 0, 0, 0));
    PetscCall(RitzAtInitialState(sp, *s->full_op, s->dns_ritz));
    s->dns_ritz_done = PETSC_TRUE;
    PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Eigen, sp, 0, 0, 0));
  }
  PetscCall(VSHMMSpectralStableStepOf_Private(PetscObjectComm((PetscObject)sp), s->dns_ritz, type, dt));
  PetscCall(PetscInfo(sp, "stable step of TSRK %s on every wavenumber: %g\n", type, (double)*dt));
  PetscFunctionReturn(0);
}

/* The truncation check's model: the left-out wavenumbers of the sparse layout, their decay rates
   (mean(d) k^2 for diffusion, less the mean linear rate r c1 of a reaction) and the left-out
   part of the initial data u0; the operator on every wavenumber that gives their forcing. */
static PetscErrorCode StartTruncationModel(VSHMMSpectral sp, PetscReal t)
{
  VSHMMSpectral_Data *s = sp->data;
  std::vector<double> D, A, u0;
  spc::ExtraTerms     extra;

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralBuildCoefficients_Private(sp, D, A));
  PetscCall(VSHMMSpectralBuildExtraTerms_Private(sp, extra));
  const int N = (int)s->N;
  PetscCall(FullOperator(sp, D, A, extra));
  double meanD = 0, linear = 0, meanA = 0;
  for (double d : D) meanD += d / N;
  for (double a : A) meanA += a / N;
  if (!extra.rate.empty()) {
    for (double r : extra.rate) linear += r * extra.reaction[1] / N;
  }
  PetscCall(VSHMMSpectralSampleField_Private(sp, "u0", s->u0, u0));
  std::vector<double> c0(s->full_layout->size());
  s->full_op->analyze(u0.data(), c0.data());
  const std::vector<double> m0 = VSHMMSpectralFullMagnitudes(*s->full_layout, c0.data());
  std::vector<int>          modes;
  std::vector<double>       rates, weights, a0;
  const std::vector<int>   &kept = s->layout->modes(); /* sorted within each cluster */
  s->truncation_detuned.clear();
  for (int k = 0; k <= spc::maxWavenumber(N); ++k) {
    if (s->layout->indexOf(k) >= 0) continue;
    int dist = N;
    for (int q : kept) dist = std::min(dist, std::abs(k - q));
    modes.push_back(k);
    rates.push_back(meanD * k * k - linear + std::abs(meanA) * dist);
    s->truncation_detuned.push_back(std::abs(meanA) * dist > std::abs(meanD * k * k - linear));
    weights.push_back(spc::isRealOnly(N, k) ? 1.0 : 2.0);
    a0.push_back(m0[k]);
  }
  s->truncation = spc::TruncationModel(modes, rates, weights, t, a0);
  modes.clear();
  rates.clear();
  weights.clear();
  for (int k : kept) { /* the damped ones: on the others (advection, Burgers alone) the feedback turns with their phases */
    if (!(meanD * k * k - linear > 0)) continue;
    modes.push_back(k);
    rates.push_back(meanD * k * k - linear);
    weights.push_back(spc::isRealOnly(N, k) ? 1.0 : 2.0);
  }
  s->feedback                = spc::TruncationModel(modes, rates, weights, t, {});
  s->truncation_started      = PETSC_TRUE;
  s->truncation_warned       = PETSC_FALSE;
  s->truncation_warned_share = 0;
  s->stats.truncation_share  = 0;
  s->stats.truncation_time   = t;
  PetscFunctionReturn(0);
}

/* The buffers of -spectral_cluster_buffers that would retain the wavenumbers `named` (each one's
   distance to its nearest cluster); with `grow`, at least half the width of the band of
   consecutive retained wavenumbers nearest to each (a widening that only reaches the modes named
   lags a cascade, e.g. a steepening Burgers front, by one ring of wavenumbers per restart). */
static std::vector<int> TruncationBuffers(const VSHMMSpectral_Data *s, const std::vector<int> &named, bool grow)
{
  const int        nclust = (int)s->cluster_modes.size();
  std::vector<int> buffers(nclust, 0);

  for (int k : named) {
    int best = 0, dist = INT_MAX, near = 0;
    for (int j = 0; j < nclust; ++j)
      for (PetscInt q : s->cluster_modes[j])
        if (std::abs(k - (int)q) < dist) {
          dist = std::abs(k - (int)q);
          best = j;
          near = (int)q;
        }
    if (grow && dist < INT_MAX) {
      const std::vector<PetscInt> &m  = s->cluster_modes[best]; /* sorted within a cluster */
      const auto                   i  = std::lower_bound(m.begin(), m.end(), (PetscInt)near) - m.begin();
      size_t                       lo = (size_t)i, hi = (size_t)i;
      while (lo > 0 && m[lo - 1] == m[lo] - 1) --lo;
      while (hi + 1 < m.size() && m[hi + 1] == m[hi] + 1) ++hi;
      dist = std::max(dist, (int)(hi - lo + 2) / 2);
    }
    buffers[best] = std::max(buffers[best], dist);
  }
  return buffers;
}

/* The truncation check's message: the share, the wavenumbers that hold most of it, and the buffers
   of -spectral_cluster_buffers that would retain them. */
static PetscErrorCode TruncationMessage(VSHMMSpectral sp, PetscReal t, PetscReal share, PetscReal norm, const std::string &note, std::string &text)
{
  VSHMMSpectral_Data    *s       = sp->data;
  const char            *pre     = VSHMMSpectralPrefix(sp);
  const auto             named   = s->truncation.largest(0.25 * s->cluster_tol * norm);
  const std::vector<int> buffers = TruncationBuffers(s, named, false);
  const int              nclust  = (int)buffers.size();
  char                   buf[1280];

  PetscFunctionBegin;
  std::string list;
  for (int j = 0; j < nclust; ++j) list += (j ? "," : "") + std::to_string(buffers[j]);
  PetscCall(PetscSNPrintf(buf, sizeof(buf),
                          "truncation check at t = %g: the dynamics drive the wavenumbers that the clusters leave out to about %.3g of ||u|| (a model of them as forced, damped modes), above the clusters' tolerance -%sspectral_cluster_tolerance %g: "
                          "the sparse solution misses at least about that much. Most of it is in the wavenumbers %s. Widen the clusters to hold them "
                          "(-%sspectral_cluster_buffers %s, or -%sspectral_clusters), or let the detection look longer (-%sspectral_cluster_detect_times: its direct simulation sees the fast time scales, not what the slow dynamics create later). "
                          "(-%sspectral_truncation_check %s, none silences it.)",
                          (double)t, (double)share, pre, (double)s->cluster_tol, spc::formatModes(named).c_str(), pre, list.c_str(), pre, pre, pre, s->truncation_check == VSHMMSPECTRAL_TRUNCATION_ERROR ? "warn makes this a warning" : "error makes this an error"));
  text = buf + note;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralTruncationMonitor - The TS monitor of the truncation check (set by
   `VSHMMSpectralSetUpTS()` in sparse mode): warns (or stops the solve) when the dynamics drive the
   wavenumbers that the clusters leave out beyond the clusters' tolerance

   Collective

   Input Parameters:
+  ts - the TS
.  step - the step number
.  t - the time
.  U - the state
-  ctx - the VSHMMSpectral

   Notes:
   At the first step (the start of a run: also any step at a time before the last look), after
   each 1/64 of the solve's span (so at every TSVSHMM macro step of a short run), at every 1024th
   step and at the TS's final time, the full operator is evaluated on the state (zero on the
   left-out wavenumbers): its components f_k on the left-out wavenumbers force them. Each is
   modelled as a damped mode a_k' = -lambda_k a_k + |f_k| (`spc::TruncationModel`; lambda_k =
   mean(d) k^2 for diffusion, less a reaction's mean linear rate, plus |mean(a)| times the
   distance to the nearest retained wavenumber for advection, which detunes the forcing), from
   the left-out part of u0. A second evaluation, with the left-out modes at their modelled
   amplitudes in the phase of their forcing, gives what they change in the damped retained
   modes' tendency: the feedback the sparse run does not have, modelled the same way. Where the
   two together exceed the clusters' tolerance (`VSHMMSpectralSetClusterTolerance()`) times the
   solution's norm at a look after the start, the check says so once per solve (or stops the
   solve), naming the left-out wavenumbers of the largest modelled amplitudes and the buffers
   that would hold them. The largest share is in `VSHMMSpectralGetStatistics()`. It measures the
   clusters, not TSVSHMM's own error; on the explicit sparse method it read 0.8-1.5 times the error
   against a converged DNS, on advection up to 3 times above (docs/spectral.md, "The truncation
   check").

   Options Database Key:
.  -spectral_truncation_check <warn,error,widen,none> - what a failed check does (default warn; widen: `VSHMMSpectralSetTruncationCheck()`)

   Level: developer

.seealso: `VSHMMSpectralSetUpTS()`, `VSHMMSpectralGrowthMonitor()`, `VSHMMSpectralSetClusterTolerance()`
@*/
PetscErrorCode VSHMMSpectralTruncationMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  VSHMMSpectral       sp = (VSHMMSpectral)ctx;
  VSHMMSpectral_Data *s;
  PetscReal           tmax, norm;
  const PetscScalar  *c;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 5);
  s = sp->data;
  if (s->truncation_check == VSHMMSPECTRAL_TRUNCATION_NONE || s->mode != VSHMMSPECTRAL_MODE_SPARSE) PetscFunctionReturn(0);
  PetscCall(TSGetMaxTime(ts, &tmax));
  const bool start = !s->truncation_started || t < s->truncation.time();
  if (start) PetscCall(StartTruncationModel(sp, t));
  else {
    const bool at_end = t >= tmax - 1e-12 * PetscMax(1.0, PetscAbsReal(tmax));
    const bool due    = t - s->truncation.time() >= (tmax - s->truncation.startTime()) / kTruncationLooks || step % kTruncationEvery == 0;
    if (!at_end && !due) PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Truncation, sp, 0, 0, 0));
  PetscCall(StateNorms(sp, U, &norm, nullptr));
  const int           N = (int)s->N;
  std::vector<double> coef(s->full_layout->size(), 0.0), F(s->full_layout->size());
  PetscCall(VSHMMSpectralGetCoefficients_Private(sp, U, &c));
  for (int i = 0; i < s->layout->modeCount(); ++i) {
    const int k = s->layout->mode(i), o = s->layout->offset(i), fo = s->full_layout->offset(s->full_layout->indexOf(k));
    for (int r = 0; r < spc::realsOf(N, k); ++r) coef[fo + r] = PetscRealPart(c[o + r]);
  }
  PetscCall(VSHMMSpectralRestoreCoefficients_Private(sp, U, &c));
  s->full_op->apply(coef.data(), F.data());
  const std::vector<double> mF   = VSHMMSpectralFullMagnitudes(*s->full_layout, F.data());
  const std::vector<int>   &left = s->truncation.modes();
  std::vector<double>       forcing(left.size());
  for (size_t i = 0; i < left.size(); ++i) forcing[i] = mF[left[i]];
  s->truncation.advance(t, forcing);
  /* the left-out modes at their modelled amplitudes, in the phase of their forcing, and what
     they change in the retained modes' tendency (the feedback the sparse run does not have) */
  std::vector<double> dF(F.size()); /* F with the left-out modes, then less F */
  for (size_t i = 0; i < left.size(); ++i) {
    if (!(forcing[i] > 0)) continue;
    const int    fo = s->full_layout->offset(s->full_layout->indexOf(left[i]));
    const double g  = s->truncation.amplitudes()[i] / forcing[i];
    for (int r = 0; r < spc::realsOf(N, left[i]); ++r) coef[fo + r] = g * F[fo + r];
  }
  s->full_op->apply(coef.data(), dF.data());
  for (size_t i = 0; i < dF.size(); ++i) dF[i] -= F[i];
  const std::vector<double> mChange = VSHMMSpectralFullMagnitudes(*s->full_layout, dF.data());
  const std::vector<int>   &damped  = s->feedback.modes();
  std::vector<double>       change(damped.size());
  for (size_t i = 0; i < damped.size(); ++i) change[i] = mChange[damped[i]];
  s->feedback.advance(t, change);
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Truncation, sp, 0, 0, 0));
  const PetscReal share = norm > 0 ? std::hypot(s->truncation.norm(), s->feedback.norm()) / norm : 0;
  PetscCall(PetscInfo(sp, "truncation check at t = %g: the left-out wavenumbers modelled at %g of ||u|| (themselves %g, their feedback on the retained ones %g; -spectral_cluster_tolerance %g)\n", (double)t, (double)share,
                      (double)(norm > 0 ? s->truncation.norm() / norm : 0), (double)(norm > 0 ? s->feedback.norm() / norm : 0), (double)s->cluster_tol));
  if (share > s->stats.truncation_share) {
    s->stats.truncation_share = share;
    s->stats.truncation_time  = t;
  }
  const bool  widen = s->truncation_check == VSHMMSPECTRAL_TRUNCATION_WIDEN;
  std::string note;
  if (widen && !s->widen_buffers.empty()) { /* asked for and not applied: said at the end of a later solve */
    const bool at_end = t >= tmax - 1e-12 * PetscMax(1.0, PetscAbsReal(tmax));
    if (!(at_end && t > s->widen_time && step > s->widen_step + 1)) PetscFunctionReturn(0); /* a post-step that stops the solve ends it one step after the request */
    char buf[256];
    PetscCall(PetscSNPrintf(buf, sizeof(buf), " (-%sspectral_truncation_check widen: the widening it asked for at t = %g was not applied by VSHMMSpectralWidenClusters().)", VSHMMSpectralPrefix(sp), (double)s->widen_time));
    note = buf;
  } else if (widen && s->widenings >= kMaxWidenings) {
    char buf[256];
    PetscCall(PetscSNPrintf(buf, sizeof(buf), " (-%sspectral_truncation_check widen: the clusters were widened %d times already.)", VSHMMSpectralPrefix(sp), (int)s->widenings));
    note = buf;
  }
  if (!start && s->cluster_tol > 0 && share > s->cluster_tol && (!s->truncation_warned || share > kWarnAgain * s->truncation_warned_share)) { /* the initial data's own truncation counts where it lasts */
    std::vector<int> named = s->truncation.largest(0.25 * s->cluster_tol * norm);
    if (named.empty()) named = s->truncation.largest(0.25 * s->truncation.norm()); /* the share is their feedback: the modes that drive it */
    bool detuned = false;                                                          /* a rate set by advection's detuning: the model reads up to several times above the truth there; 0.8-1.5 times it elsewhere */
    for (int k : named) detuned = detuned || s->truncation_detuned[std::lower_bound(left.begin(), left.end(), k) - left.begin()];
    if (widen && note.empty() && detuned)
      note = " (-" + std::string(VSHMMSpectralPrefix(sp)) + "spectral_truncation_check widen: not widened, as the model of the wavenumbers named rests on advection's detuning, where it reads up to several times above the truth.)";
    std::vector<int> buffers;
    if (widen && note.empty()) { /* clusters separated before stay so: wider ones of no savings would take about the work of a direct simulation */
      spc::ClusterSet     candidate;
      std::vector<double> D, A;
      buffers = TruncationBuffers(s, named, true);
      PetscCall(WidenedClusters(sp, buffers, &candidate));
      PetscCall(VSHMMSpectralBuildCoefficients_Private(sp, D, A));
      std::vector<std::vector<PetscInt>> modes;
      for (const auto &c : candidate.clusters) modes.emplace_back(c.begin(), c.end());
      const std::vector<PetscReal> after = VSHMMSpectralClusterSeparations_Private(modes, D, A);
      bool                         lost  = false;
      for (size_t j = 0; j < after.size() && j < s->separations.size() && note.empty(); ++j)
        if (s->separations[j] >= kSeparated && after[j] < kSeparated) {
          lost = true;
          char buf[512];
          PetscCall(PetscSNPrintf(buf, sizeof(buf), " (-%sspectral_truncation_check widen: not widened, as the clusters that hold them would be %.3g apart in time scale, clusters %d and %d (%.3g now), not separated: VSHMM would take no savings on them, and a direct simulation, -%sspectral_mode dns, is the tool at this tolerance.)", VSHMMSpectralPrefix(sp), (double)after[j], (int)j, (int)j + 1,
                                  (double)s->separations[j], VSHMMSpectralPrefix(sp)));
          note = buf;
        }
      PetscReal atol, rtol;
      PetscCall(TSGetTolerances(ts, &atol, NULL, &rtol, NULL));
      bool unseparated = false; /* clusters already too close for savings: their widening costs about the DNS's work too */
      for (PetscReal S : s->separations) unseparated = unseparated || S < kSeparated;
      if ((lost || unseparated) && share * norm > atol + rtol * norm) { /* beyond the tolerance in the TS's own measure too (atol + rtol |u|): no savings are left, so every wavenumber, a direct simulation, rather than a wrong answer */
        note.clear();
        s->widen_all = PETSC_TRUE;
      }
    }
    if (widen && note.empty()) { /* the buffers that hold the named wavenumbers, for VSHMMSpectralWidenClusters() */
      s->widen_buffers = buffers;
      s->widen_time    = t;
      s->widen_step    = step;
      PetscCall(PetscInfo(sp, "truncation check at t = %g: %g of ||u|| modelled beyond -spectral_cluster_tolerance %g: a widening of the clusters is asked for (VSHMMSpectralGetTruncationWidening())\n", (double)t, (double)share, (double)s->cluster_tol));
      PetscFunctionReturn(0);
    }
    std::string text;
    PetscCall(TruncationMessage(sp, t, share, norm, note, text));
    s->truncation_warned       = PETSC_TRUE;
    s->truncation_warned_share = share;
    PetscCheck(s->truncation_check != VSHMMSPECTRAL_TRUNCATION_ERROR, PetscObjectComm((PetscObject)sp), PETSC_ERR_NOT_CONVERGED, "%s", text.c_str());
    PetscCall(PetscFPrintf(PetscObjectComm((PetscObject)sp), PETSC_STDERR, "VSHMMSpectral warning: %s\n", text.c_str()));
  }
  PetscFunctionReturn(0);
}
