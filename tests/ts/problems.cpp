#include "problems.hpp"

#include <cmath>
#include <functional>

namespace {

struct SplitCtx {
  SplitProblem         *problem;
  PetscInt              scale;
  SplitKind             kind;
  std::vector<PetscInt> components; // the split's IS on this rank: F's local entry i is component components[i]
};

std::vector<SplitCtx> &Contexts(SplitProblem *p)
{
  static std::vector<std::pair<SplitProblem *, std::vector<SplitCtx>>> all;
  for (auto &e : all)
    if (e.first == p) return e.second;
  all.push_back({p, {}});
  return all.back().second;
}

// Follows the level TSVSHMM is evaluating: the level whose evaluation count moved since the last
// call (none moved: the same level evaluation as the last call; the stability check's count
// moved: level -1).
PetscErrorCode FollowCall(SplitProblem *p, int split, PetscReal t, bool *inject)
{
  TSVSHMMStatistics st;
  PetscReal         t0;

  PetscFunctionBeginUser;
  PetscCall(TSVSHMMGetStatistics(p->ts, &st));
  if ((PetscInt)p->seen_evaluations.size() != st.nscales) { // a new set-up: counts start at 0
    p->seen_evaluations.assign(st.nscales, 0);
    p->seen_stability = 0;
  }
  for (PetscInt l = 0; l < st.nscales; ++l)
    if (st.level_evaluations[l] != p->seen_evaluations[l]) p->level = (int)l;
  if (st.stability_evaluations != p->seen_stability) p->level = -1;
  p->seen_evaluations.assign(st.level_evaluations, st.level_evaluations + st.nscales);
  p->seen_stability = st.stability_evaluations;
  if ((int)p->split_calls.size() < (int)p->terms.size()) p->split_calls.resize(p->terms.size(), 0);
  const long call = ++p->split_calls[split];
  PetscCall(TSGetTime(p->ts, &t0));
  if (p->trace) p->trace->push_back(SplitCall{split, call, p->level, t, t0});
  *inject = split == p->nan_split && call == p->nan_call;
  PetscFunctionReturn(0);
}

PetscErrorCode SplitFunction(TS, PetscReal t, Vec X, Vec F, void *vctx)
{
  SplitCtx                *ctx = (SplitCtx *)vctx;
  SplitProblem            *p   = ctx->problem;
  const PetscScalar       *xa;
  PetscScalar             *fa;
  std::vector<PetscScalar> full(p->n);

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->gather, X, p->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->gather, X, p->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->xall, &xa));
  p->terms[ctx->scale](p->params, t, xa, full.data());
  PetscCall(VecRestoreArrayRead(p->xall, &xa));
  if (ctx->scale == (PetscInt)p->terms.size() - 1) {
    p->calls++;
    if ((p->nan_after_calls >= 0 && p->calls > p->nan_after_calls) || t > p->nan_after_time) full[p->n - 1] = NAN;
  }
  if (p->trace || p->nan_split >= 0) {
    bool inject;
    PetscCall(FollowCall(p, (int)ctx->scale, t, &inject));
    if (inject)
      for (PetscInt i = 0; i < p->n; ++i) full[i] = NAN;
  }
  PetscCall(VecGetArray(F, &fa));
  for (size_t i = 0; i < ctx->components.size(); ++i) fa[i] = full[ctx->components[i]];
  PetscCall(VecRestoreArray(F, &fa));
  PetscFunctionReturn(0);
}

PetscErrorCode FullFunction(TS, PetscReal t, Vec X, Vec F, void *vctx)
{
  SplitProblem            *p = (SplitProblem *)vctx;
  const PetscScalar       *xa;
  PetscScalar             *fa;
  std::vector<PetscScalar> full(p->n), sum(p->n, 0.0);
  PetscInt                 rstart, rend;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->gather, X, p->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->gather, X, p->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->xall, &xa));
  std::vector<SplitProblem::Term> terms = p->terms;
  terms.insert(terms.end(), p->full_extra.begin(), p->full_extra.end());
  for (auto term : terms) {
    term(p->params, t, xa, full.data());
    for (PetscInt i = 0; i < p->n; ++i) sum[i] += full[i];
  }
  PetscCall(VecRestoreArrayRead(p->xall, &xa));
  PetscCall(VecGetOwnershipRange(X, &rstart, &rend));
  PetscCall(VecGetArray(F, &fa));
  for (PetscInt i = rstart; i < rend; ++i) fa[i - rstart] = sum[i];
  PetscCall(VecRestoreArray(F, &fa));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CreateSplitTS(MPI_Comm comm, SplitProblem *p, SplitKind kind, const std::vector<PetscReal> &x0, const std::vector<std::string> &names, TS *ts, Vec *x, const std::vector<int> &creation)
{
  PetscInt       rstart, rend;
  const PetscInt nscales = (PetscInt)p->terms.size();

  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, x));
  PetscCall(VecSetSizes(*x, PETSC_DECIDE, p->n));
  PetscCall(VecSetFromOptions(*x));
  PetscCall(VecGetOwnershipRange(*x, &rstart, &rend));
  for (PetscInt i = rstart; i < rend; ++i) PetscCall(VecSetValue(*x, i, x0[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(*x));
  PetscCall(VecAssemblyEnd(*x));
  PetscCall(VecScatterCreateToAll(*x, &p->gather, &p->xall));

  PetscCall(TSCreate(comm, ts));
  PetscCall(TSSetType(*ts, TSVSHMM));
  p->ts = *ts;
  PetscCall(TSSetRHSFunction(*ts, nullptr, FullFunction, p));
  std::vector<SplitCtx> &ctxs = Contexts(p);
  ctxs.assign(nscales, SplitCtx{p, 0, kind, {}});
  PetscMPIInt rank, size;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  for (PetscInt c = 0; c < nscales; ++c) {
    const PetscInt         k     = creation.empty() ? c : creation[c];
    std::vector<PetscInt> &comps = ctxs[k].components;
    IS                     is;
    ctxs[k].scale = k;
    /* scale k's components: every component (additive) or component k, with the components beyond
       nscales - 1 for the last scale (component) */
    const bool     additive = kind == SplitKind::Additive || ((kind == SplitKind::Mixed || kind == SplitKind::Scattered) && k % 2 == 0);
    const PetscInt lo = additive ? 0 : k, hi = additive || k == nscales - 1 ? p->n : k + 1;
    if (kind == SplitKind::Scattered) {
      /* all of them listed on the last rank, in decreasing order: owned by other ranks, and unsorted */
      if (rank == size - 1)
        for (PetscInt i = hi - 1; i >= lo; --i) comps.push_back(i);
    } else if (kind == SplitKind::Component && !p->components.empty()) {
      for (PetscInt i : p->components[k])
        if ((i >= rstart && i < rend) || ((i < 0 || i >= p->n) && rank == size - 1)) comps.push_back(i); /* one beyond the state on the last rank (a bad IS) */
    } else {
      for (PetscInt i = PetscMax(lo, rstart); i < PetscMin(hi, rend); ++i) comps.push_back(i);
    }
    PetscCall(ISCreateGeneral(comm, (PetscInt)comps.size(), comps.data(), PETSC_COPY_VALUES, &is));
    PetscCall(TSRHSSplitSetIS(*ts, names[k].c_str(), is));
    PetscCall(TSRHSSplitSetRHSFunction(*ts, names[k].c_str(), nullptr, SplitFunction, &ctxs[k]));
    PetscCall(ISDestroy(&is));
  }
  PetscCall(TSSetSolution(*ts, *x));
  PetscCall(TSSetExactFinalTime(*ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscFunctionReturn(0);
}

PetscErrorCode DestroySplitTS(SplitProblem *p, TS *ts, Vec *x)
{
  PetscFunctionBeginUser;
  PetscCall(TSDestroy(ts));
  PetscCall(VecDestroy(x));
  PetscCall(VecScatterDestroy(&p->gather));
  PetscCall(VecDestroy(&p->xall));
  PetscFunctionReturn(0);
}

PetscErrorCode GatherState(SplitProblem *p, Vec x, std::vector<PetscReal> &out)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->gather, x, p->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->gather, x, p->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->xall, &a));
  out.assign(a, a + p->n);
  PetscCall(VecRestoreArrayRead(p->xall, &a));
  PetscFunctionReturn(0);
}

static void DissipativeSlow(const void *vp, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  (void)vp;
  const PetscReal s = x[0] + x[1] + x[2];
  f[0]              = std::sin(s) - s * s / 20;
  f[1] = f[2] = 0;
}
static void DissipativeMedium(const void *vp, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscReal eps = ((const DissipativeParams *)vp)->eps;
  f[0] = f[2] = 0;
  f[1]        = (3 * x[0] * x[0] - x[1] * x[1] + x[2] * x[2]) / eps;
}
static void DissipativeFast(const void *vp, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscReal eps = ((const DissipativeParams *)vp)->eps;
  f[0] = f[1] = 0;
  f[2]        = (x[0] - x[1] - x[2]) / (eps * eps);
}

static void DissipativeSlowHalf(const void *vp, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  DissipativeSlow(vp, t, x, f);
  for (int i = 0; i < 3; ++i) f[i] /= 2;
}

void DissipativeProblemWithSlowHalves(SplitProblem *p, const DissipativeParams *params)
{
  p->n      = 3;
  p->terms  = {DissipativeSlowHalf, DissipativeSlowHalf, DissipativeMedium, DissipativeFast};
  p->params = params;
}

void DissipativeProblem(SplitProblem *p, const DissipativeParams *params)
{
  p->n      = 3;
  p->terms  = {DissipativeSlow, DissipativeMedium, DissipativeFast};
  p->params = params;
}

static void ChainSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = std::sin(x[1]) - x[0] / 2;
  f[1] = f[2] = f[3] = 0;
}
static void ChainScale1(const void *vp, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[2] = f[3] = 0;
  f[1]               = (x[0] - x[1]) / ((const ChainParams *)vp)->e1;
}
static void ChainScale2(const void *vp, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = f[3] = 0;
  f[2]               = (x[1] + x[0] - x[2]) / ((const ChainParams *)vp)->e2;
}
static void ChainScale3(const void *vp, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = f[2] = 0;
  f[3]               = (x[2] - x[3]) / ((const ChainParams *)vp)->e3;
}

void ChainProblem(SplitProblem *p, const ChainParams *params)
{
  p->n      = 4;
  p->terms  = {ChainSlow, ChainScale1, ChainScale2, ChainScale3};
  p->params = params;
}

static PetscErrorCode CaptureHandler(MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  CapturedError *e = (CapturedError *)ctx;
  if (p == PETSC_ERROR_INITIAL && e->message.empty() && mess) e->message = mess;
  return n;
}

CapturedError CaptureError(const std::function<PetscErrorCode()> &f)
{
  CapturedError e;
  PetscPushErrorHandler(CaptureHandler, &e);
  e.code = f();
  PetscPopErrorHandler();
  return e;
}
