// PETSc-level tests of the accuracy control (-ts_vshmm_adapt) and the separation check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <unistd.h>
#include <utility>
#include <numeric>

#include "problems.hpp"

namespace {

// Converged DNS of the dissipative example (eps = 1e-2, x0 = (5, -10, 5)): docs/dissipative.md.
constexpr double kXiAt1 = 2.5925732631;

struct Guard {
  explicit Guard(const char *options) { PetscOptionsInsertString(nullptr, options); }
  ~Guard() { PetscOptionsClear(nullptr); }
};

struct AdaptRun {
  std::vector<PetscReal> x;
  TSVSHMMStatistics      stats{};
  PetscInt64             evaluations = 0;
  std::vector<PetscReal> savings;
  PetscReal              micro_dt = 0;
};

// The slow variable xi as the observable of -ts_vshmm_adapt.
PetscErrorCode XiObservable(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[0];
  PetscFunctionReturn(0);
}

PetscErrorCode SolveDissipativeAdapt(const char *options, PetscReal tfinal, AdaptRun *run, bool observeXi = false, PetscReal eps = 1e-2, SplitKind kind = SplitKind::Component, std::vector<PetscReal> x0 = {5, -10, 5})
{
  Guard             guard(options);
  DissipativeParams params;
  SplitProblem      p;
  TS                ts;
  Vec               x;
  PetscInt          n;
  const PetscReal  *a;

  PetscFunctionBeginUser;
  params.eps = eps;
  DissipativeProblem(&p, &params);
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, kind, x0, {"slow", "medium", "fast"}, &ts, &x));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, tfinal));
  PetscCall(TSSetMaxSteps(ts, 100000));
  if (observeXi) PetscCall(TSVSHMMSetObservables(ts, 1, XiObservable, &p));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, x));
  PetscCall(GatherState(&p, x, run->x));
  PetscCall(TSVSHMMGetStatistics(ts, &run->stats));
  run->evaluations = std::accumulate(run->stats.rhs_evaluations, run->stats.rhs_evaluations + run->stats.nsplits, (PetscInt64)0);
  PetscCall(TSVSHMMGetSavingsFactors(ts, &n, &a));
  run->savings.assign(a, a + n);
  PetscCall(TSVSHMMGetMicroStep(ts, &run->micro_dt));
  PetscCall(DestroySplitTS(&p, &ts, &x));
  PetscFunctionReturn(0);
}

// Two scales only twice apart, as in PETSc's multirate finite-volume tutorials: x' = -x + y,
// y' = -2 y + x (component splits). Nothing is separated.
void WeakSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1];
  f[1] = 0;
}
void WeakFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -2.0 * x[1] + x[0];
}

PetscErrorCode SolveWeak(const char *options, std::vector<PetscReal> *xout, std::vector<PetscReal> *savings)
{
  Guard            guard(options);
  SplitProblem     p;
  TS               ts;
  Vec              x;
  PetscInt         n;
  const PetscReal *a;

  PetscFunctionBeginUser;
  p.n     = 2;
  p.terms = {WeakSlow, WeakFast};
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {1, 0}, {"slow", "fast"}, &ts, &x));
  PetscCall(TSSetTimeStep(ts, 0.5));
  PetscCall(TSSetMaxTime(ts, 1.0));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, x));
  PetscCall(GatherState(&p, x, *xout));
  PetscCall(TSVSHMMGetSavingsFactors(ts, &n, &a));
  savings->assign(a, a + n);
  PetscCall(DestroySplitTS(&p, &ts, &x));
  PetscFunctionReturn(0);
}

// A slow variable driven by a fast *band*: x' = -x + mean_i y_i, y_i' = lambda_i (x / 2 - y_i) with
// lambda_i = 10, 31.6, 100, 316, 1000 (component splits slow, fast). On the slow manifold
// y_i = x / 2 and x' = -x / 2. The levels' spectral radii are about 1000 apart, but the band's
// slowest mode only 10 times the slow rate: that is the separation that sets the averaging error.
constexpr int kBand = 5;
void          BandSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  PetscScalar mean = 0;
  for (int i = 1; i <= kBand; ++i) mean += x[i] / kBand;
  f[0] = -x[0] + mean;
  for (int i = 1; i <= kBand; ++i) f[i] = 0;
}
void BandFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  for (int i = 1; i <= kBand; ++i) f[i] = 10.0 * std::pow(10.0, 0.5 * (i - 1)) * (0.5 * x[0] - x[i]);
}

// The state at T of x' = sum of the terms (with params; at time t) from x by RK4 with step h.
std::vector<double> Rk4State(const std::vector<SplitProblem::Term> &terms, const void *params, std::vector<double> x, double T, double h)
{
  const size_t        n = x.size();
  std::vector<double> k[4], y(n), f(n);
  auto                rhs = [&](double t, const std::vector<double> &z, std::vector<double> &out) {
    out.assign(n, 0.0);
    for (SplitProblem::Term term : terms) {
      term(params, t, z.data(), f.data());
      for (size_t i = 0; i < n; ++i) out[i] += f[i];
    }
  };
  const long steps = std::lround(T / h);
  for (long s = 0; s < steps; ++s) {
    const double t = s * h;
    rhs(t, x, k[0]);
    for (size_t i = 0; i < n; ++i) y[i] = x[i] + 0.5 * h * k[0][i];
    rhs(t + 0.5 * h, y, k[1]);
    for (size_t i = 0; i < n; ++i) y[i] = x[i] + 0.5 * h * k[1][i];
    rhs(t + 0.5 * h, y, k[2]);
    for (size_t i = 0; i < n; ++i) y[i] = x[i] + h * k[2][i];
    rhs(t + h, y, k[3]);
    for (size_t i = 0; i < n; ++i) x[i] += h / 6 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
  }
  return x;
}

// x[0] at T of the same.
double Rk4Reference(const std::vector<SplitProblem::Term> &terms, const void *params, std::vector<double> x, double T, double h)
{
  return Rk4State(terms, params, std::move(x), T, h)[0];
}

// Rk4Reference() at step h, checked against step `check`: a reference shown converged (the two
// agree to `agree`).
double ConvergedReference(const std::vector<SplitProblem::Term> &terms, const void *params, const std::vector<double> &x, double T, double h, double check, double agree = 1e-10)
{
  const double ref = Rk4Reference(terms, params, x, T, h);
  EXPECT_NEAR(ref, Rk4Reference(terms, params, x, T, check), agree);
  return ref;
}

// x(t) of the band problem by RK4 with step h from x = 1, y_i = 1/2 (on the slow manifold).
std::vector<double> BandInitial()
{
  std::vector<double> x0(kBand + 1, 0.5);
  x0[0] = 1;
  return x0;
}
double BandReference(double T, double h)
{
  return Rk4Reference({BandSlow, BandFast}, nullptr, BandInitial(), T, h);
}

PetscErrorCode X0Observable(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[0];
  PetscFunctionReturn(0);
}

// Solves p (splits of `kind` named `names`) from x0 with the sampling interval DeltaT to T, with
// the observables nobs, f, ctx of -ts_vshmm_adapt.
PetscErrorCode SolveObserving(const char *options, SplitProblem &p, const std::vector<PetscReal> &x0, const std::vector<std::string> &names, PetscReal DeltaT, PetscReal T, AdaptRun *run, SplitKind kind, PetscInt nobs, PetscErrorCode (*f)(TS, PetscReal, Vec, PetscReal[], void *), void *ctx, const std::function<PetscErrorCode(TS, Vec)> &beforeSolve = nullptr)
{
  Guard guard(options);
  TS    ts;
  Vec   x;

  PetscFunctionBeginUser;
  p.n = (PetscInt)x0.size();
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, kind, x0, names, &ts, &x));
  PetscCall(TSSetTimeStep(ts, DeltaT));
  PetscCall(TSSetMaxTime(ts, T));
  PetscCall(TSVSHMMSetObservables(ts, nobs, f, ctx));
  PetscCall(TSSetFromOptions(ts));
  if (beforeSolve) PetscCall(beforeSolve(ts, x));
  PetscCall(TSSolve(ts, x));
  PetscCall(GatherState(&p, x, run->x));
  PetscCall(TSVSHMMGetStatistics(ts, &run->stats));
  run->evaluations = std::accumulate(run->stats.rhs_evaluations, run->stats.rhs_evaluations + run->stats.nsplits, (PetscInt64)0);
  {
    PetscInt         n;
    const PetscReal *alpha;
    PetscCall(TSVSHMMGetSavingsFactors(ts, &n, &alpha));
    run->savings.assign(alpha, alpha + n);
  }
  PetscCall(DestroySplitTS(&p, &ts, &x));
  PetscFunctionReturn(0);
}

// x[0] and x[1] as the observables.
PetscErrorCode X0X1Observables(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[0];
  q[1] = x[1];
  PetscFunctionReturn(0);
}

// The same with x[0] the observable.
PetscErrorCode SolveObservingX0(const char *options, SplitProblem &p, const std::vector<PetscReal> &x0, const std::vector<std::string> &names, PetscReal DeltaT, PetscReal T, AdaptRun *run, SplitKind kind = SplitKind::Component)
{
  return SolveObserving(options, p, x0, names, DeltaT, T, run, kind, 1, X0Observable, &p);
}

// solve(options with the warnings written to one temporary file for every rank, its name made on
// the first); what TSVSHMM said is returned in *said on every rank.
PetscErrorCode Saying(const std::string &options, const std::function<PetscErrorCode(const char *)> &solve, std::string *said)
{
  char        path[] = "/tmp/vshmm_said_XXXXXX";
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (!rank) {
    const int fd = mkstemp(path);
    PetscCheck(fd >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "no temporary file");
    close(fd);
  }
  PetscCallMPI(MPI_Bcast(path, sizeof(path), MPI_CHAR, 0, PETSC_COMM_WORLD));
  const std::string    all  = options + " -ts_vshmm_warnings_viewer ascii:" + path;
  const PetscErrorCode ierr = solve(all.c_str());
  std::ifstream        in(path);
  said->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD)); /* every rank has read it */
  if (!rank) std::remove(path);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

// SolveObservingX0() saying (Saying()).
PetscErrorCode SolveObservingX0Saying(const std::string &options, SplitProblem &p, const std::vector<PetscReal> &x0, PetscReal DeltaT, PetscReal T, AdaptRun *run, std::string *said, SplitKind kind = SplitKind::Component)
{
  return Saying(
    options,
    [&](const char *all) {
      return SolveObservingX0(all, p, x0, {"slow", "fast"}, DeltaT, T, run, kind);
    },
    said);
}

// Solves the two-scale problem `terms` (component splits slow {x[0]}, fast; x[0] observed) from x0
// to T with the sampling interval DeltaT and -ts_vshmm_adapt at tolerance tol (-ts_rtol and
// -ts_atol), and expects x[0](T) within bound tol (1 + |x[0]|) of a converged RK4 reference (step
// h, agreeing with step `check` to `agree`).
AdaptRun ExpectWithinTolerance(const std::vector<SplitProblem::Term> &terms, const std::vector<double> &x0, double T, double tol, double h, double check, double bound = 1, double agree = 1e-10, double DeltaT = 0.1, const void *params = nullptr)
{
  SplitProblem p;
  AdaptRun     run;
  p.terms                      = terms;
  p.params                     = params;
  const double         ref     = ConvergedReference(terms, params, x0, T, h, check, agree);
  const std::string    options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
  const PetscErrorCode ierr    = SolveObservingX0(options.c_str(), p, x0, {"slow", "fast"}, DeltaT, T, &run);
  EXPECT_EQ(ierr, 0) << options;
  if (ierr || run.x.empty()) return run;
  EXPECT_LE(std::abs(run.x[0] - ref), bound * tol * (1 + std::abs(ref))) << options << ", DeltaT " << DeltaT << ": x[0](" << T << ") = " << run.x[0] << ", reference " << ref;
  return run;
}

PetscErrorCode SolveBand(const char *options, PetscReal DeltaT, PetscReal T, AdaptRun *run)
{
  SplitProblem p;
  p.terms = {BandSlow, BandFast};
  return SolveObservingX0(options, p, BandInitial(), {"slow", "fast"}, DeltaT, T, run);
}

// A slow variable driven by the energy of a fast rotation: y' = -y + u^2 + 0.3 sin(y),
// u' = -v / eps - d u, v' = u / eps - d v (eps = 1e-3; component splits slow {y}, fast {u, v}).
// Averaged: y' = -y + A^2 / 2 + 0.3 sin(y), A the rotation's amplitude (A = 1 for d = 0). With
// d = 0.1 the fast level carries a slow process (its amplitude decays at rate 0.1, slower than y).
struct RotationParams {
  double eps = 1e-3, damping = 0, coupling = 1; // coupling C: y' = -y + C u^2 + 0.3 sin(y)
};
void RotationSlow(const void *ctx, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const RotationParams *p = (const RotationParams *)ctx;
  f[0]                    = -x[0] + p->coupling * x[1] * x[1] + 0.3 * std::sin(x[0]);
  f[1] = f[2] = 0;
}
void RotationFast(const void *ctx, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const RotationParams *p = (const RotationParams *)ctx;
  f[0]                    = 0;
  f[1]                    = -x[2] / p->eps - p->damping * x[1];
  f[2]                    = x[1] / p->eps - p->damping * x[2];
}

// The same rotation, damped, as the fastest of three levels: y' = -y + z + u^2 (slow {y}),
// z' = (cos y - z) / 1e-2 (medium {z}), the rotation (fast {u, v}) at 1 / eps^2 = 1e4.
void TriSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] + x[2] * x[2];
  f[1] = f[2] = f[3] = 0;
}
void TriMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[2] = f[3] = 0;
  f[1]               = (std::cos(x[0]) - x[1]) / 1e-2;
}
void TriFast(const void *ctx, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const RotationParams *p = (const RotationParams *)ctx;
  f[0] = f[1] = 0;
  f[2]        = -x[3] / (p->eps * p->eps) - p->damping * x[2];
  f[3]        = x[2] / (p->eps * p->eps) - p->damping * x[3];
}

// y(T) of the rotation problem from (0.5, 1, 0) by RK4 with step h.
double RotationReference(const RotationParams &params, double T, double h)
{
  return Rk4Reference({RotationSlow, RotationFast}, &params, {0.5, 1, 0}, T, h);
}

// y(T) of the rotation problem by RK4 at h = 5e-6, shown converged: h = 1e-5 agrees to 1e-8.
double ConvergedRotationReference(const RotationParams &params, double T)
{
  const double ref = RotationReference(params, T, 5e-6);
  EXPECT_NEAR(ref, RotationReference(params, T, 1e-5), 1e-8) << "the RK4 reference is not converged";
  return ref;
}

// The options of accuracy on request at rtol = atol = tol.
std::string AdaptOptions(double tol)
{
  char options[128];
  snprintf(options, sizeof(options), "-ts_vshmm_adapt -ts_rtol %g -ts_atol %g", tol, tol);
  return options;
}

PetscErrorCode SolveRotation(const char *options, const RotationParams &params, PetscReal T, AdaptRun *run, PetscReal u0 = 1, SplitKind kind = SplitKind::Component)
{
  SplitProblem p;
  p.terms  = {RotationSlow, RotationFast};
  p.params = &params;
  return SolveObservingX0(options, p, {0.5, u0, 0}, {"slow", "fast"}, 0.1, T, run, kind);
}

// First-order upwind advection (a = 1, periodic) on [0, 1) with 16 coarse cells (h = 1/20) and, in
// place of 4 of them, 48 cells 12 times finer: the slow split writes the coarse cells, the fast
// split the fine ones (as PETSc's multirate finite-volume tutorials with -hratio 12). The radii of
// the two levels are about 12 apart, but the fine cells carry the transported solution. (Until the
// split check of TSVSHMMSetSplitCheck(), the slow split's IS was component 0 alone, the default of
// CreateSplitTS(): the splits did not add up to the RHS function, and the check said so.)
constexpr int kCoarse = 16, kFine = 48, kFvCells = kCoarse + kFine;
bool          FineCell(int i)
{
  return i >= 8 && i < 8 + kFine;
}
double CellWidth(int i)
{
  return FineCell(i) ? 0.05 / 12 : 0.05;
}
void FvSlow(const void *, PetscReal, const PetscScalar *u, PetscScalar *f)
{
  for (int i = 0; i < kFvCells; ++i) f[i] = FineCell(i) ? 0.0 : -(u[i] - u[(i + kFvCells - 1) % kFvCells]) / CellWidth(i);
}
void FvFast(const void *, PetscReal, const PetscScalar *u, PetscScalar *f)
{
  for (int i = 0; i < kFvCells; ++i) f[i] = FineCell(i) ? -(u[i] - u[(i + kFvCells - 1) % kFvCells]) / CellWidth(i) : 0.0;
}

PetscErrorCode SetUpFv(const char *options)
{
  Guard        guard(options);
  SplitProblem p;
  TS           ts;
  Vec          x;

  PetscFunctionBeginUser;
  p.n     = kFvCells;
  p.terms = {FvSlow, FvFast};
  p.components.resize(2);
  for (int i = 0; i < kFvCells; ++i) p.components[FineCell(i) ? 1 : 0].push_back(i);
  std::vector<PetscReal> u0(kFvCells);
  double                 xc = 0;
  for (int i = 0; i < kFvCells; ++i) u0[i] = std::sin(2 * M_PI * (xc + 0.5 * CellWidth(i))), xc += CellWidth(i);
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, u0, {"slow", "fast"}, &ts, &x));
  PetscCall(TSSetTimeStep(ts, 0.025));
  PetscCall(TSSetMaxTime(ts, 0.025));
  PetscCall(TSVSHMMSetMicroStep(ts, 1e-4));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSetUp(ts));
  PetscCall(TSSolve(ts, x));
  PetscCall(DestroySplitTS(&p, &ts, &x));
  PetscFunctionReturn(0);
}

} // namespace

// The radii of a fine finite-volume region and the coarse cells are about 12 apart, which passed
// the check when it compared radii only; the fine cells' own block (a transport: its eigenvalues
// are all -1/h_f, its Krylov space holds the slow crossing) has Ritz values far below that, and
// the check now finds the scales not separated.
TEST(VSHMMSeparation, AFineTransportRegionIsNotSeparated)
{
  const CapturedError e = CaptureError([&] { return SetUpFv("-ts_vshmm_check_separation error"); });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("not separated (separation of consecutive levels"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("slowest rate of level 1's own components"), std::string::npos) << e.message;
}

// A band of fast rates, 10 to 1000, against a slow rate of 1/2 (DeltaT = 0.5, to t = 4, x(4) of
// RK4 with h = 1e-4; h = 5e-5 agrees to 12 digits). The spectral radii say the levels are 1000
// apart, and savings taken from them slow the band's slowest mode below the slow scale, where the
// averaging error saturates. Judged by the radii alone, the estimate was blind: at tol 1e-2 the
// error was 2.3 tol (3,512 + 3,108 evaluations). TSVSHMM estimates the slowest rate of the fast
// split's own components (component splits), 10, and the model sees the saturation: 0.78 tol
// (6,676 + 6,260; 12,996 in all since the first ratio starts from that slowest rate; 0.76 tol with
// 6,700 + 6,488 since it is capped at 1 + s_l / 2 and scheduled calibrations the model predicted
// are skipped); with the separation given, 1.02 tol (5,832 + 6,676: the first ratios then start at
// sigma 10, not at the decaying level's sigma 2 capped by the saturation; 5,832 + 6,512 since the
// skipped calibrations). With the micro step of a decaying fastest level at 0.8 of its stability
// limit (not 0.9): 0.77 tol with 7,396 + 7,108, and with the separation 1.05 tol with 6,388 + 7,096.
// The first macro step's calibration measures the micro step's term from the finer side (the micro
// step at its stability bound; docs/accuracy.md section 12): the same errors with 7,396 + 7,956 and
// 6,388 + 7,168. A macro step's first comparison inherits the faster levels' lag (section 22):
// 0.61 and 0.80 tol with 8,704 + 10,672 and 7,744 + 7,976. (The band's slowest rate 10 against the
// slow radius 1 sits at the separation threshold 10 from t = 0.5 to 2; a decaying pair separated
// at set-up is judged to have lost its separation below 8 only, section 23: judged at 10, the
// first run flipped between lost and found by rounding, 23,292 evaluations on one rank and 22,788
// on two.) The step after a first macro step accepted at its first try goes the whole way to its
// target (section 33): 0.61 tol with 8,704 + 10,624 (the given separation's run the same).
TEST(VSHMMAdapt, ABandOfFastRatesIsSeen)
{
  const double T = 4, ref = BandReference(T, 1e-4), tol = 1e-2;
  EXPECT_NEAR(ref, BandReference(T, 5e-5), 1e-10);
  const struct {
    const char *options;
    PetscInt64  work;
  } cases[] = {{"-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 19328}, {"-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_scale_separations 10", 15720}};
  for (const auto &c : cases) {
    AdaptRun run;
    ASSERT_EQ(SolveBand(c.options, 0.5, T, &run), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), 1.5 * tol * (1 + std::abs(ref))) << c.options << ": x(4) = " << run.x[0] << ", reference " << ref;
    EXPECT_EQ(run.evaluations + run.stats.adapt_evaluations, c.work) << c.options << ": error " << std::abs(run.x[0] - ref) / (tol * (1 + std::abs(ref))) << " tol, " << run.evaluations << " + " << run.stats.adapt_evaluations;
  }
}

// A micro step near the stability limit of a fast oscillation damps it (RK4 at omega dt = 2.5
// halves its amplitude per step). The fast energy then leaves the run and every comparison alike,
// and the estimate cannot see the error: the slow variable driven by u^2 ended 3.1 and 2.6 tol off
// at tol 1e-1 and 1e-2 (estimates 0.27 and 1.26 tol). The micro step now keeps the amplitude of the
// fastest level's oscillations within the tolerance over the run (weighted by the level's part of the state): 0.38 and 0.42 tol.
TEST(VSHMMAdapt, AFastRotationKeepsItsEnergy)
{
  const RotationParams params;
  const double         T = 2, ref = ConvergedRotationReference(params, T);
  for (const double tol : {1e-1, 1e-2}) {
    const std::string options = AdaptOptions(tol);
    AdaptRun          run;
    ASSERT_EQ(SolveRotation(options.c_str(), params, T, &run), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), 0.8 * tol * (1 + std::abs(ref))) << options << ": y(2) = " << run.x[0] << ", reference " << ref;
    EXPECT_GT(std::sqrt(run.x[1] * run.x[1] + run.x[2] * run.x[2]), 1 - tol) << options << ": the fast amplitude is lost";
  }
}

// A slow rotation that turns 2 radians a macro step, driven by a fast variable not separated from
// it: x1' = 20 x2 + z, x2' = -20 x1, z' = -(z - x1^2) / 1e-2 (additive splits: slow writes x1, x2,
// fast z) from (1, 0, 0), x1 and x2 observed, DeltaT = 0.1, tol 1e-3, to t = 2. The steps are
// single-rate (not separated) and their phase errors add up, while the signed sums of the
// estimates turn with the rotation and stay within a random walk's: x1(2) was 2.9 tol off with
// estimates summing to 2.3, silently. Each single-rate step now takes DeltaT / span of the
// tolerance: 0.8 tol. With eps = 1e-3 (separated, savings, tol 1e-2) the steps' errors, mostly
// the savings', did not add up (0.37 tol before and now, 12,408 evaluations): their shares stay
// measured (42,672 evaluations for 0.09 tol with the coherent shares taken there too).
void TurnSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 20 * x[1] + x[2];
  f[1] = -20 * x[0];
  f[2] = 0;
}
void TurnFast(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 0;
  f[2] = -(x[2] - x[0] * x[0]) / *(const double *)params;
}
TEST(VSHMMAdapt, AFastTurningSlowRotationAddsItsPhaseErrors)
{
  for (const double eps : {1e-2, 1e-3}) {
    const double              tol = eps == 1e-2 ? 1e-3 : 1e-2;
    const std::vector<double> ref = Rk4State({TurnSlow, TurnFast}, &eps, {1, 0, 0}, 2, 5e-6), check = Rk4State({TurnSlow, TurnFast}, &eps, {1, 0, 0}, 2, 1e-5);
    for (int i = 0; i < 2; ++i) ASSERT_NEAR(ref[i], check[i], 1e-9);
    SplitProblem      p;
    AdaptRun          run;
    const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none " + AdaptOptions(tol);
    p.terms                   = {TurnSlow, TurnFast};
    p.params                  = &eps;
    ASSERT_EQ(SolveObserving(options.c_str(), p, {1, 0, 0}, {"slow", "fast"}, 0.1, 2, &run, SplitKind::Additive, 2, X0X1Observables, &p), 0);
    for (int i = 0; i < 2; ++i) EXPECT_LE(std::abs(run.x[i] - ref[i]), 1.5 * tol * (1 + std::abs(ref[i]))) << "eps " << eps << ": x" << i + 1 << "(2) = " << run.x[i] << ", reference " << ref[i];
    if (eps == 1e-3) EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 25000) << "steps with savings took the coherent shares";
  }
}

// Micro steps that come to a spurious rest: A' = -A + B, B' = (A - 2 B + C) / 3e-3, C' = (B - C -
// C^3) / 1e-5 (component splits slow {A}, medium {B}, fast {C}) from (2, 0, 0), A observed,
// DeltaT = 0.5, tol 1e-2, to t = 1. The fast rate 1e5 (1 + 3 C^2) grows from 1e5 to 2.8e5 on the
// slow manifold, and the first step's micro step, within RK4's limit at C = 0, came to rest at a
// fixed point of the RK4 map where C' is 5e4 and the rate looks stable: A(1) 7.1 tol off, silently.
// The try's last micro step now shows the rest (it moves the state by 0.002 of h |G|) and the try
// is redone with half the micro step: 0.54 tol. RK4 references at 2e-6 and 4e-6.
void RestSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1];
  f[1] = 0;
  f[2] = 0;
}
void RestMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = (x[0] - 2 * x[1] + x[2]) / 3e-3;
  f[2] = 0;
}
void RestFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 0;
  f[2] = (x[1] - x[2] - x[2] * x[2] * x[2]) / 1e-5;
}
TEST(VSHMMAdapt, MicroStepsAtASpuriousRestAreRedone)
{
  const double ref = ConvergedReference({RestSlow, RestMedium, RestFast}, nullptr, {2, 0, 0}, 1, 2e-6, 4e-6, 1e-9), tol = 1e-2;
  SplitProblem p;
  AdaptRun     run;
  p.terms = {RestSlow, RestMedium, RestFast};
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_warnings_viewer none", p, {2, 0, 0}, {"slow", "medium", "fast"}, 0.5, 1, &run), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << "A(1) = " << run.x[0] << ", reference " << ref;
}

// A micro step the user sets is kept, but where it damps the fast rotation beyond the tolerance
// over the run (omega dt = 2.5: half the amplitude per step) the user is told at set-up; a micro
// step within the bound raises nothing.
TEST(VSHMMAdapt, AUserMicroStepThatDampsTheRotationIsWarnedOf)
{
  const RotationParams params;
  PetscMPIInt          rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const char *warning = "TSVSHMM warning (-ts_vshmm_adapt): the micro step set (-ts_vshmm_micro_dt 0.0025) loses more than the tolerance 0.1 of the amplitude of the fastest scale's oscillation (frequency 1000.";
  for (const char *dt : {"0.0025", "2e-05"}) {
    const std::string options = std::string("-ts_vshmm_adapt -ts_rtol 1e-1 -ts_atol 1e-1 -ts_vshmm_micro_dt ") + dt;
    AdaptRun          run;
    testing::internal::CaptureStderr();
    const PetscErrorCode ierr = SolveRotation(options.c_str(), params, 0.2, &run);
    const std::string    err  = testing::internal::GetCapturedStderr();
    ASSERT_EQ(ierr, 0) << options;
    if (rank == 0 && std::string(dt) == "0.0025") EXPECT_NE(err.find(warning), std::string::npos) << err;
    else EXPECT_EQ(err.find("micro step set"), std::string::npos) << options << ": " << err;
  }
}

// -ts_vshmm_adapt with the constant kernel is warned of at set-up (docs/accuracy.md section 23: its
// averaging error in an initial layer saturates with the savings, and the 4-scale relaxation chain
// at tol 1e-3 ended 3.7 tol off with its first step estimated 18 times too low), and so is the
// exponential kernel (a three-level reaction of tools/adapt_outside.py at 1e-2 4 tol off, its
// first step estimated 5 times too low); the cosine kernel raises neither.
TEST(VSHMMAdapt, TheConstantKernelIsWarnedOf)
{
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (const char *kernel : {"constant", "cosine", "exponential"}) {
    const std::string options = std::string("-ts_vshmm_adapt -ts_rtol 1e-1 -ts_atol 1e-1 -ts_vshmm_kernel ") + kernel;
    AdaptRun          run;
    testing::internal::CaptureStderr();
    const PetscErrorCode ierr = SolveDissipativeAdapt(options.c_str(), 0.2, &run, true);
    const std::string    err  = testing::internal::GetCapturedStderr();
    ASSERT_EQ(ierr, 0) << options;
    if (rank == 0 && std::string(kernel) == "constant") EXPECT_NE(err.find("the constant kernel (-ts_vshmm_kernel constant) does not vanish at the ends of its period"), std::string::npos) << err;
    else EXPECT_EQ(err.find("constant kernel"), std::string::npos) << options << ": " << err;
    if (rank == 0 && std::string(kernel) == "exponential") EXPECT_NE(err.find("with the exponential kernel (-ts_vshmm_kernel exponential) the error estimate of -ts_vshmm_adapt was measured less reliable"), std::string::npos) << err;
    else EXPECT_EQ(err.find("exponential kernel"), std::string::npos) << options << ": " << err;
  }
}

// A thin fast rotation (u0 = 0.02: its components hold 0.04 of the state's norm) can lose at most
// that much, below the tolerance 0.1: the micro step that damps it (omega dt = 2.5) raises no
// warning, and adapt's micro step is not bound by its amplitude (with the bound weighted but not
// capped by the rotation's whole amplitude the warning came, and the paper's advection scene took
// 182,967 evaluations instead of 143,531 for the same error).
TEST(VSHMMAdapt, AThinFastRotationDoesNotBoundTheMicroStep)
{
  const RotationParams params;
  PetscMPIInt          rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (const double u0 : {0.02, 1.0}) {
    AdaptRun run;
    testing::internal::CaptureStderr();
    const PetscErrorCode ierr = SolveRotation("-ts_vshmm_adapt -ts_rtol 1e-1 -ts_atol 1e-1 -ts_vshmm_micro_dt 0.0025", params, 0.2, &run, u0);
    const std::string    err  = testing::internal::GetCapturedStderr();
    ASSERT_EQ(ierr, 0) << "u0 = " << u0;
    if (rank != 0) continue;
    if (u0 < 1) EXPECT_EQ(err.find("micro step set"), std::string::npos) << "u0 = " << u0 << ": " << err;
    else EXPECT_NE(err.find("micro step set"), std::string::npos) << "u0 = " << u0 << ": " << err;
  }
}

// Where the tolerance asks for more than the separation gives, finer savings do not lower the
// estimate (a floor above the share): their limit, no savings, is tried, and where it meets the
// share the rest of the solve is single-rate, said once by default. The rotation at eps = 1e-2
// (frequency 100, 1.6 turns per macro step) at tol 1e-2: before, the floor was accepted at 2.9
// shares with a warning to loosen the tolerance, 19,168 evaluations (steps and estimates) for
// 0.17 tol; now 13,048 for 0.21 tol. At tol 1e-1 the savings meet the share: no such message.
TEST(VSHMMAdapt, AToleranceOutOfReachWithSavingsIsMetWithout)
{
  RotationParams params;
  params.eps = 1e-2;
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const double T = 2, ref = ConvergedRotationReference(params, T);
  for (const double tol : {1e-1, 1e-2}) {
    const std::string options = AdaptOptions(tol);
    AdaptRun          run;
    testing::internal::CaptureStderr();
    const PetscErrorCode ierr = SolveRotation(options.c_str(), params, T, &run);
    const std::string    err  = testing::internal::GetCapturedStderr();
    ASSERT_EQ(ierr, 0) << options;
    EXPECT_LE(std::abs(run.x[0] - ref), 0.5 * tol * (1 + std::abs(ref))) << options << ": y(2) = " << run.x[0] << ", reference " << ref;
    const bool out = err.find("is out of reach with savings") != std::string::npos;
    if (tol < 0.05) {
      if (rank == 0) EXPECT_TRUE(out) << err;
      EXPECT_EQ(run.savings[0], 0.0) << options;
      EXPECT_GE(run.stats.adapt_single_rate_from, 0.0) << options; // from one of the first macro steps on (their savings are
      EXPECT_LE(run.stats.adapt_single_rate_from, 0.5) << options; // at most 0.6 already: the rotation turns 1.6 times a macro step)
      EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 15000) << options;
    } else {
      EXPECT_FALSE(out) << err;
      EXPECT_GT(run.savings[0], 0.0) << options;
      EXPECT_EQ(run.stats.adapt_single_rate_from, -1.0) << options;
    }
  }
}

// A tolerance far out of reach with savings: the rotation at eps = 1e-3 at tol 1e-8 to t = 0.1, whose
// slow y carries a ripple of u^2's fast phase far larger than that. Three tries with savings all far
// above their shares (kOutOfReach) take single-rate steps where they cost at most kOutOfReachDearer
// times the last try: y(0.1) within 2e-12, 345,784 evaluations. Before, the tries halved the savings
// and doubled the work each, to the twelfth: 1.1e8 evaluations, y 8.8e-5 (5,800 tol) off.
TEST(VSHMMAdapt, AToleranceFarOutOfReachGoesSingleRate)
{
  RotationParams params;
  const double   T = 0.1, ref = RotationReference(params, T, 1.25e-6);
  ASSERT_NEAR(ref, RotationReference(params, T, 2.5e-6), 1e-11) << "the RK4 reference is not converged";
  AdaptRun run;
  ASSERT_EQ(SolveRotation("-ts_vshmm_adapt -ts_rtol 1e-8 -ts_atol 1e-8 -ts_vshmm_warnings_viewer none", params, T, &run), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), 1e-8 * (1 + std::abs(ref))) << "y(0.1) = " << run.x[0] << ", reference " << ref;
  EXPECT_EQ(run.stats.adapt_single_rate_from, 0.0);
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 2000000); /* 345,784; 1.1e8 before, 5,800 tol off */
}

// Far out of reach, the single-rate step is tried only where it costs at most 16 times the last try:
// the dissipative example at eps = 1e-4, 1e-3 to t = 2 has three first-step tries above 100 shares
// (its initial layer) and single-rate steps far dearer; tried at any cost they took 2.4e8
// evaluations (4.4e5 with the bound, the same as before the far-out rule).
TEST(VSHMMAdapt, FarOutOfReachSingleRateStepsAreTriedOnlyWhereAffordable)
{
  AdaptRun run;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_warnings_viewer none", 2.0, &run, true, 1e-4), 0);
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 2000000);
  EXPECT_EQ(run.stats.adapt_single_rate_from, -1.0);
}

// Where every faster level decays, a scheduled calibration the model predicted (the step's
// estimate within 2x of its prediction) is skipped; where a level oscillates its estimates scatter
// by about 3x with the phase, within 2x by chance, and every scheduled calibration is made: the
// first macro step and after 1, 2, 4, 8 more, 5 over the 20 macro steps of the rotation (with the
// skip there: 3 and 4 at tol 1e-1 and 1e-2, and the oscillators at 1e-3, t = 4, took 4x the work).
TEST(VSHMMAdapt, AnOscillatingLevelIsCalibratedOnSchedule)
{
  const RotationParams params;
  for (const char *options : {"-ts_vshmm_adapt -ts_rtol 1e-1 -ts_atol 1e-1", "-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2"}) {
    AdaptRun run;
    ASSERT_EQ(SolveRotation(options, params, 2, &run), 0);
    EXPECT_GE(run.stats.adapt_calibrations, 5) << options;
  }
}

// Two relaxations 9 apart (not separated): y' = -y + z (slow {y}), z' = -9 (z - g(y)) (fast {z}),
// DeltaT = 1 to t = 4. With g = 1/2 and z(0) = 1/2 the fast variable sits on its slow manifold and
// savings change nothing: the time ratio adapt would start from were the levels separated (4.5)
// is tested against the first, single-rate macro step (they differ by 1e-6 of the tolerance) and
// admitted (savings factor 1.5 at the end). The micro step is set (0.01): adapt's own would start
// at the fast level's stability limit, 0.25, where DeltaT / 5 already bounds the micro cycle and
// no savings are left to test.
// With g = cos(3 y) the fast variable lags behind a moving target, and savings, which slow its
// relaxation, move y: the first test differs by 5.4 tolerances at 1e-2, the second (r - 1 scaled
// to fit) would save nothing, and no savings are taken.
struct RelaxParams {
  bool   moving = false;
  double rate   = 9; // of the fast relaxation
};
void RelaxSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1];
  f[1] = 0;
}
void RelaxFast(const void *ctx, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const RelaxParams *p = (const RelaxParams *)ctx;
  f[0]                 = 0;
  f[1]                 = -p->rate * (x[1] - (p->moving ? std::cos(3.0 * x[0]) : 0.5));
}

TEST(VSHMMAdapt, SavingsAreTestedWhereTheScalesAreNotSeparated)
{
  for (const bool moving : {false, true}) {
    RelaxParams  params;
    SplitProblem p;
    params.moving    = moving;
    p.terms          = {RelaxSlow, RelaxFast};
    p.params         = &params;
    const double T   = 4;
    const double ref = ConvergedReference({RelaxSlow, RelaxFast}, &params, {1.0, 0.5}, T, 1e-4, 5e-5);
    for (const double tol : {1e-2, 1e-3}) {
      const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_vshmm_micro_dt 0.01 -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
      AdaptRun          run;
      ASSERT_EQ(SolveObservingX0(options.c_str(), p, {1.0, 0.5}, {"slow", "fast"}, 1.0, T, &run), 0);
      EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << options << (moving ? " (moving)" : " (resting)") << ": y(4) = " << run.x[0] << ", reference " << ref << ", savings " << (run.savings.empty() ? -1.0 : run.savings[0]);
      if (!moving) EXPECT_GT(run.savings.size() == 1 ? run.savings[0] : 0.0, 0.5) << options << ": the savings were not admitted";
      else EXPECT_EQ(run.savings.size() == 1 ? run.savings[0] : -1.0, 0.0) << options << ": savings admitted where they move y by 5 tolerances in the first macro step";
    }
  }
}

// Two relaxations 5 apart: the ratio adapt would start from (2.5) saves too little to be worth a
// test (and the calibration an admission brings), so none is made and no savings are taken, even
// on the slow manifold where they would be harmless (micro step 0.01 set, as above).
TEST(VSHMMAdapt, SmallSavingsAreNotTested)
{
  RelaxParams  params;
  SplitProblem p;
  params.rate = 5;
  p.terms     = {RelaxSlow, RelaxFast};
  p.params    = &params;
  AdaptRun run;
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_vshmm_micro_dt 0.01 -ts_rtol 1e-2 -ts_atol 1e-2", p, {1.0, 0.5}, {"slow", "fast"}, 1.0, 4, &run), 0);
  EXPECT_EQ(run.savings.size() == 1 ? run.savings[0] : -1.0, 0.0);
}

// Robertson's kinetics with y1 = 1 - y2 - y3 eliminated: y3' = 3e7 y2^2 (slow), y2' = 0.04 (1 - y2 -
// y3) - 1e4 y2 y3 - 3e7 y2^2 (fast), from y2 = y3 = 0. At the initial state every rate of the fast
// species is 0.04 or less (its rates are proportional to the concentrations): the separation check
// at set-up finds the levels 1.5 apart, not separated. A moment later the fast species relaxes at
// rate 2,000 and more against the slow 0.5. Checked again with the spectra adapt estimates later,
// the scales are found separated after the first macro step and savings are taken from there on
// (before: none, for the whole solve, after a warning that VSHMM was the wrong tool).
void RobertsonSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 3e7 * x[1] * x[1];
  f[1] = 0;
}
void RobertsonFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 0.04 * (1 - x[0] - x[1]) - 1e4 * x[1] * x[0] - 3e7 * x[1] * x[1];
}

TEST(VSHMMAdapt, ScalesSeparatedLaterTakeSavings)
{
  SplitProblem p;
  p.terms          = {RobertsonSlow, RobertsonFast};
  const double T   = 4;
  const double ref = ConvergedReference({RobertsonSlow, RobertsonFast}, nullptr, {0.0, 0.0}, T, 2e-5, 4e-5);
  for (const double tol : {1e-1, 1e-2, 1e-3}) {
    const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
    AdaptRun          run;
    ASSERT_EQ(SolveObservingX0(options.c_str(), p, {0.0, 0.0}, {"slow", "fast"}, 0.5, T, &run), 0);
    /* at 1e-3 within 2 tol (1.25): the savings' error grows more slowly than r - 1 near the cycle
       bound, and the comparison reads it low (docs/accuracy.md section 13) */
    EXPECT_LE(std::abs(run.x[0] - ref), (tol < 5e-3 ? 2 : 1) * tol * (1 + std::abs(ref))) << options << ": y3(4) = " << run.x[0] << ", reference " << ref;
    ASSERT_EQ(run.savings.size(), 1u);
    EXPECT_GT(run.savings[0], 10.0) << options << ": no savings taken after the scales separated";
  }
  /* One macro step to t = 1: its tries blow up within the stable steps of the initial state (rate
     0.04) until the micro step is finite, then at the stability limit of the step's end, where the
     fast species hardly relaxes and no comparison can coarsen the micro step: 1.36 tol at 1e-3,
     estimated at 0.02, before the step was redone with the stable fraction of that micro step */
  const double ref1 = Rk4Reference({RobertsonSlow, RobertsonFast}, nullptr, {0.0, 0.0}, 1.0, 2e-5);
  EXPECT_NEAR(ref1, Rk4Reference({RobertsonSlow, RobertsonFast}, nullptr, {0.0, 0.0}, 1.0, 4e-5), 1e-10);
  AdaptRun run;
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3", p, {0.0, 0.0}, {"slow", "fast"}, 1.0, 1.0, &run), 0);
  EXPECT_LE(std::abs(run.x[0] - ref1), 1e-3 * (1 + std::abs(ref1))) << "one macro step: y3(1) = " << run.x[0] << ", reference " << ref1;
}

// A fast rate that grows with the solution: x' = 1 - x + (z - x) / 2 (slow), z' = 1000 x (x - z)
// (fast, rate 1000 x) from x = z = 0.2 to T = 4 (the rate from 200 to about 1,000). Between the
// calibrations, which estimate the levels' spectra, the fastest level's radius is followed by a few
// power steps at every macro step, and the spectra are estimated again where it grew by 10%:
// before, the micro step went past the stability limit as x grew, the few fast steps a macro step
// with savings takes did not blow up, the comparison at the same micro step saw nothing, and x(4)
// ended 6.5 tol off at 1e-2 without a word. From x = z = 0 the scales are not separated at the
// initial state (rate 0) and separated after the first macro step; the first step with savings
// then measures the micro step's term from the finer side (without: 1.66 tol at 1e-2 in that step).
void GrowingSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] + 0.5 * (x[1] - x[0]);
  f[1] = 0;
}
void GrowingFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 1000 * x[0] * (x[0] - x[1]);
}

TEST(VSHMMAdapt, AFastRateThatGrowsKeepsTheMicroStepStable)
{
  for (const double x0 : {0.2, 0.0})
    for (const double tol : {1e-1, 1e-2}) ExpectWithinTolerance({GrowingSlow, GrowingFast}, {x0, x0}, x0 > 0 ? 4 : 1.5, tol, 1e-5, 2e-5, 1, 1e-10, 0.5);
}

// A fast rotation whose frequency grows from 0 with the slow variable it drives: x' = 1 - x +
// (u^2 + v^2 - 1)/2, (u, v)' = 1000 x (v, -u) - (u, v)/2 from x = 0, (u, v) = (1, 0), DeltaT = 0.1
// to t = 1. The micro step chosen at the initial state (frequency 0) damped the rotation within
// the first macro step as the frequency grew to 93; x showed its lost energy only in the steps
// after, whose estimates saw nothing of it: 2.97 tol at 1e-2. The fastest radius at the end of
// each macro step's first try (93 against 1) now brings the spectra of that state in and the step
// is taken again within them.
void GrowingRotationSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] + 0.5 * (x[1] * x[1] + x[2] * x[2] - 1);
  f[1] = f[2] = 0;
}
void GrowingRotationFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 1000 * x[0] * x[2] - 0.5 * x[1];
  f[2] = -1000 * x[0] * x[1] - 0.5 * x[2];
}

TEST(VSHMMAdapt, AFastRotationWhoseFrequencyGrowsFromZeroKeepsItsEnergy)
{
  ExpectWithinTolerance({GrowingRotationSlow, GrowingRotationFast}, {0.0, 1.0, 0.0}, 1, 1e-2, 2e-6, 4e-6);
}

// A slow variable driven by the energy of a fast rotation: x' = 1 - x + 3 (u^2 - 0.245),
// (u, v)' = 1000 (1 + 0.3 x) (v, -u) from x = 0, (u, v) = (0.7, 0), DeltaT = 0.1, to t = 0.5. The
// term 3 u^2 oscillates with amplitude 0.735 at twice the rotation's frequency. The first time
// ratios (82) slowed the rotation to less than a turn per macro step in micro time: the slow steps
// saw one phase of it, x took 0.735 DeltaT of it as it was, and the comparison with doubled terms,
// which sees the same phase, differed by little (estimate 0.11 shares; 3.8 tol at t = 0.1, 2.1 at
// t = 0.5). Where such a step would err by more than half the tolerance (measured from the slower
// field at eight phases of the rotation), the time ratios keep at least one turn per macro step.
void UnaveragedSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] + 3 * (x[1] * x[1] - 0.245);
  f[1] = f[2] = 0;
}
void UnaveragedFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscScalar omega = 1000 * (1 + 0.3 * x[0]);
  f[0]                    = 0;
  f[1]                    = omega * x[2];
  f[2]                    = -omega * x[1];
}

TEST(VSHMMAdapt, AFastRotationTurnsAtLeastOnceInAMacroStep)
{
  ExpectWithinTolerance({UnaveragedSlow, UnaveragedFast}, {0.0, 0.7, 0.0}, 0.5, 1e-2, 1e-6, 2e-6, 0.5);
}

// The same with a band of eight rotations, frequencies 1000 (1 + k/8) (1 + 0.3 x), k = 0..7, x
// driven by their mean u_k^2 (phases 0.7 k at t = 0), to t = 2. The turn is the band's slowest
// frequency's, among the oscillating Ritz values within a decade of the level's radius: a Ritz
// value of 12.6 from the band's inside, taken as its slowest, left no savings from t = 0.3 on
// (207,120 evaluations against 22,320).
constexpr int kRotations = 8;
void          BandRotationsSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  PetscScalar mean = 0;
  for (int k = 0; k < kRotations; ++k) mean += x[1 + 2 * k] * x[1 + 2 * k] / kRotations;
  f[0] = 1 - x[0] + 3 * (mean - 0.245);
  for (int i = 1; i <= 2 * kRotations; ++i) f[i] = 0;
}
void BandRotationsFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  for (int k = 0; k < kRotations; ++k) {
    const PetscScalar omega = 1000 * (1 + k / 8.0) * (1 + 0.3 * x[0]);
    f[1 + 2 * k]            = omega * x[2 + 2 * k];
    f[2 + 2 * k]            = -omega * x[1 + 2 * k];
  }
}

TEST(VSHMMAdapt, ABandOfFastRotationsTurnsAtItsSlowestFrequency)
{
  std::vector<double> x0(1 + 2 * kRotations, 0.0);
  for (int k = 0; k < kRotations; ++k) {
    x0[1 + 2 * k] = 0.7 * std::cos(0.7 * k);
    x0[2 + 2 * k] = 0.7 * std::sin(0.7 * k);
  }
  const AdaptRun run = ExpectWithinTolerance({BandRotationsSlow, BandRotationsFast}, x0, 2, 1e-2, 1e-6, 2e-6);
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 60000);
}

// A fast level forced at a fast rate in time: x' = 1 - x + 2 z^2, z' = -(z - (1 + x) sin(t / eps) /
// 2) / eps (eps = 1e-3) from (0.2, 0), DeltaT = 0.1. VSHMM advances one clock for every level, so
// with savings the fast level sees the forcing r times faster than it is: any savings alias it
// (x(1) 1.4 tol off at 1e-2 before, 2.8 at t = 0.4). -ts_vshmm_adapt now takes none there (the
// level's explicit time dependence, ||dF/dt|| / (rho ||X||) = 1,000-3,000, against its radius
// 1,000); with savings set the separation check says so at set-up (an error with
// -ts_vshmm_check_separation error). A slow forcing in time in the fast split (cos t) is no such
// dependence (rate about 1) and keeps its savings.
void ForcedSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] + 2 * x[1] * x[1];
  f[1] = 0;
}
void FastForcedFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - 0.5 * (1 + x[0]) * PetscSinReal(t / 1e-3)) / 1e-3;
}
void SlowForcedFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - 0.5 * (1 + x[0]) * PetscCosReal(t)) / 1e-3;
}

TEST(VSHMMAdapt, AFastForcingInTimeTakesNoSavings)
{
  const AdaptRun run = ExpectWithinTolerance({ForcedSlow, FastForcedFast}, {0.2, 0.0}, 1, 1e-2, 1e-6, 2e-6);
  ASSERT_EQ(run.savings.size(), 1u);
  EXPECT_EQ(run.savings[0], 0.0);
}

// The forcing's amplitude a slow variable at 0: z' = -(z - x sin(t / eps)) / eps from (0, 0). At the
// initial state the fast split does not depend on time; the rate is also measured where the
// slowest level's field takes the state within a macro step (x = DeltaT there), and the first
// step takes no savings (to t = 0.3 at 1e-3: 3.1 tol when found only after the first step).
void ZeroForcedFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - x[0] * PetscSinReal(t / 1e-3)) / 1e-3;
}

TEST(VSHMMAdapt, AFastForcingWhoseAmplitudeStartsAtZeroIsFoundAtSetUp)
{
  ExpectWithinTolerance({ForcedSlow, ZeroForcedFast}, {0.0, 0.0}, 0.3, 1e-3, 1e-6, 2e-6, 1.5);
}

TEST(VSHMMAdapt, AFastForcingInTimeIsReportedAtSetUp)
{
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (const bool fast : {true, false}) {
    SplitProblem p;
    p.terms = {ForcedSlow, fast ? FastForcedFast : SlowForcedFast};
    AdaptRun run;
    testing::internal::CaptureStderr();
    const PetscErrorCode ierr = SolveObservingX0("-ts_vshmm_savings_factors 10 -ts_vshmm_micro_dt 1e-4", p, {0.2, 0.0}, {"slow", "fast"}, 0.1, 0.2, &run);
    const std::string    err  = testing::internal::GetCapturedStderr();
    ASSERT_EQ(ierr, 0);
    if (rank != 0) continue;
    if (fast) EXPECT_NE(err.find("'fast' of level 1 depend explicitly on time"), std::string::npos) << err;
    else EXPECT_EQ(err.find("depend explicitly on time"), std::string::npos) << err;
  }
  SplitProblem        p;
  const CapturedError e = CaptureError([&] {
    p.terms = {ForcedSlow, FastForcedFast};
    AdaptRun run;
    return SolveObservingX0("-ts_vshmm_savings_factors 10 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_check_separation error", p, {0.2, 0.0}, {"slow", "fast"}, 0.1, 0.2, &run);
  });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("'fast' of level 1 depend explicitly on time"), std::string::npos) << e.message;
}

// A slow variable driven by a chaotic fast level: x' = -x + a^2 / 100, (a, b, c)' = Lorenz-63
// (10, 28, 8/3) / 1e-3, from (0, 1, 1, 20), DeltaT = 0.1, to t = 2 at tol 1e-3, below the slow
// variable's chaotic fluctuation (RK4 references at 2e-6, 1e-6 and 5e-7 differ by 1e-3). Two runs
// that differ in the micro step diverge within a macro step, so the estimate is noise; the steps
// found floors, and each later step refined the micro step again (1.4e-4 down to 3e-8: 549 million
// evaluations, 55 s). Below the micro step of the last floor no finer one is tried: 47 million.
void LorenzSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] * x[1] / 100;
  f[1] = f[2] = f[3] = 0;
}
void LorenzFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 10 * (x[2] - x[1]) / 1e-3;
  f[2] = (x[1] * (28 - x[3]) - x[2]) / 1e-3;
  f[3] = (x[1] * x[2] - 8.0 / 3 * x[3]) / 1e-3;
}

// A nonlinear fast oscillator (Duffing) drives a slow variable, the tolerance on the whole state:
// x' = -x + q^2, q' = p / eps, p' = -(q + q^3) / eps - x p / 2 (eps = 1e-3; component splits slow
// {x}, fast {q, p}). The sampled state carries the fast phase, so adapt steps it single-rate; each
// step's small amplitude error shifts the frequency (q^3), and the phase drifts by it for the rest
// of the run: at tol 1e-1 the state ends 3.0 tolerances off at t = 2 while the steps' estimates
// sum to 0.38 (docs/accuracy.md section 21). The carried comparison
// (-ts_vshmm_adapt_global_estimate) sees it: far above 4 times the steps' sum, it shrinks the later
// steps' shares (1.8 tolerances off), its estimate is within 2x of that error, the warning says the
// tolerance is not met, and TSGetTimeError() gives an error vector of the true error's size.
// Its slow split x' = -x + q^2 is also that of the damped rotation and of the observed phase below.
void DampedByXSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] * x[1];
  f[1] = f[2] = 0;
}
void DuffingFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = x[2] / 1e-3;
  f[2] = -(x[1] + x[1] * x[1] * x[1]) / 1e-3 - 0.5 * x[0] * x[2];
}

struct GlobalRun {
  std::vector<PetscReal> x, error; // the solution, TSGetTimeError()'s vector
  TSVSHMMStatistics      stats{};
  PetscInt64             evaluations = 0;
};

PetscErrorCode SolveDuffing(const char *options, PetscReal T, GlobalRun *run)
{
  Guard        guard(options);
  SplitProblem p;
  TS           ts;
  Vec          x, e;
  PetscBool    global;

  PetscFunctionBeginUser;
  p.n     = 3;
  p.terms = {DampedByXSlow, DuffingFast};
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {0, 1, 0}, {"slow", "fast"}, &ts, &x));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, T));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, x));
  PetscCall(GatherState(&p, x, run->x));
  PetscCall(TSVSHMMGetStatistics(ts, &run->stats));
  run->evaluations = std::accumulate(run->stats.rhs_evaluations, run->stats.rhs_evaluations + run->stats.nsplits, run->stats.adapt_evaluations);
  PetscCall(TSVSHMMGetAdaptGlobalEstimate(ts, &global));
  if (global) {
    PetscCall(VecDuplicate(x, &e));
    PetscCall(TSGetTimeError(ts, 0, &e));
    PetscCall(GatherState(&p, e, run->error));
    PetscCall(VecDestroy(&e));
  }
  PetscCall(DestroySplitTS(&p, &ts, &x));
  PetscFunctionReturn(0);
}

TEST(VSHMMAdapt, TheCarriedComparisonSeesAPhaseDriftTheStepsDoNot)
{
  const double              T = 2, tol = 1e-1;
  const std::vector<double> ref = Rk4State({DampedByXSlow, DuffingFast}, nullptr, {0, 1, 0}, T, 5e-6), check = Rk4State({DampedByXSlow, DuffingFast}, nullptr, {0, 1, 0}, T, 1e-5);
  for (int i = 0; i < 3; ++i) ASSERT_NEAR(ref[i], check[i], 1e-5) << "the RK4 reference is not converged"; /* 4.9e-6: RK4's error at 5e-6 is about 1/15 of it, 3e-6 of the tolerance's weight */
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const std::string base = AdaptOptions(tol);
  GlobalRun         plain, carried;
  ASSERT_EQ(SolveDuffing((base + " -ts_vshmm_warnings_viewer none").c_str(), T, &plain), 0);
  testing::internal::CaptureStderr();
  const PetscErrorCode ierr = SolveDuffing((base + " -ts_vshmm_adapt_global_estimate").c_str(), T, &carried);
  const std::string    err  = testing::internal::GetCapturedStderr();
  ASSERT_EQ(ierr, 0);
  ASSERT_EQ(carried.x.size(), 3u);
  ASSERT_EQ(carried.error.size(), 3u);
  // the weighted error of a state, as TSErrorWeightedNorm() weighs it (2-norm, rtol = atol = tol)
  const auto weighted = [&](const std::vector<PetscReal> &x) {
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
      const double w = tol + tol * std::max(std::abs(x[i]), std::abs(ref[i])), e = x[i] - ref[i];
      sum += (e / w) * (e / w);
    }
    return std::sqrt(sum / 3);
  };
  const double before = weighted(plain.x), error = weighted(carried.x);
  EXPECT_GT(before, 2.0) << "the drift this test is about is gone: the steps' estimates sum to " << plain.stats.error_estimate_total;
  EXPECT_LT(plain.stats.error_estimate_total, before / 3);
  EXPECT_LT(error, 0.75 * before) << "the later steps were not tightened";
  EXPECT_GT(carried.stats.global_estimate, error / 2) << "true error " << error;
  EXPECT_LT(carried.stats.global_estimate, 2 * error) << "true error " << error;
  EXPECT_GE(carried.stats.global_estimate_max, carried.stats.global_estimate);
  double dot = 0, n1 = 0, n2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double e = carried.x[i] - ref[i];
    dot += e * carried.error[i], n1 += e * e, n2 += carried.error[i] * carried.error[i];
  }
  /* the vector's size; its direction is rough at a phase error this large */
  EXPECT_GT(std::sqrt(n2), 0.5 * std::sqrt(n1)) << "TSGetTimeError() " << carried.error[0] << " " << carried.error[1] << " " << carried.error[2] << ", true error " << carried.x[0] - ref[0] << " " << carried.x[1] - ref[1] << " " << carried.x[2] - ref[2];
  EXPECT_LT(std::sqrt(n2), 2 * std::sqrt(n1));
  EXPECT_GT(dot, 0);
  if (rank == 0) EXPECT_NE(err.find("TSVSHMM warning (-ts_vshmm_adapt_global_estimate): at t = "), std::string::npos) << err;
  EXPECT_GT(carried.evaluations, plain.evaluations);
  EXPECT_EQ(plain.stats.global_estimate, -1);
}

// TSGetTimeError() needs the carried comparison; n = 0 only.
TEST(VSHMMAdapt, TSGetTimeErrorNeedsTheCarriedComparison)
{
  Guard        guard("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none");
  SplitProblem p;
  TS           ts;
  Vec          x, e;
  p.n     = 3;
  p.terms = {DampedByXSlow, DuffingFast};
  ASSERT_EQ(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {0, 1, 0}, {"slow", "fast"}, &ts, &x), 0);
  ASSERT_EQ(TSSetTimeStep(ts, 0.1), 0);
  ASSERT_EQ(TSSetMaxTime(ts, 0.1), 0);
  ASSERT_EQ(TSSetFromOptions(ts), 0);
  ASSERT_EQ(VecDuplicate(x, &e), 0);
  CapturedError c = CaptureError([&]() { return TSGetTimeError(ts, 0, &e); });
  EXPECT_NE(c.code, 0);
  EXPECT_NE(c.message.find("TSGetTimeError() needs -ts_vshmm_adapt_global_estimate"), std::string::npos) << c.message;
  ASSERT_EQ(TSVSHMMSetAdaptGlobalEstimate(ts, PETSC_TRUE), 0);
  PetscBool flg = PETSC_FALSE;
  ASSERT_EQ(TSVSHMMGetAdaptGlobalEstimate(ts, &flg), 0);
  EXPECT_TRUE(flg);
  ASSERT_EQ(TSGetTimeError(ts, 0, &e), 0); /* before any macro step: zero */
  PetscReal norm = -1;
  ASSERT_EQ(VecNorm(e, NORM_INFINITY, &norm), 0);
  EXPECT_EQ(norm, 0);
  c = CaptureError([&]() { return TSGetTimeError(ts, -1, &e); });
  EXPECT_NE(c.code, 0);
  EXPECT_NE(c.message.find("the last sampled time only (n = 0), not n = -1"), std::string::npos) << c.message;
  ASSERT_EQ(TSSolve(ts, x), 0);
  ASSERT_EQ(TSGetTimeError(ts, 0, &e), 0);
  ASSERT_EQ(VecNorm(e, NORM_INFINITY, &norm), 0);
  EXPECT_GT(norm, 0);
  VecDestroy(&e);
  DestroySplitTS(&p, &ts, &x);
}

TEST(VSHMMAdapt, AChaoticFastLevelDoesNotRefineBelowItsFloor)
{
  SplitProblem p;
  p.terms = {LorenzSlow, LorenzFast};
  AdaptRun run;
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3", p, {0.0, 1.0, 1.0, 20.0}, {"slow", "fast"}, 0.1, 2.0, &run), 0);
  EXPECT_TRUE(std::isfinite(run.x[0]));
  EXPECT_NEAR(run.x[0], 0.544, 5e-3); // the references' 0.5427-0.5441
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 100000000);
}

// A van der Pol relaxation oscillator (Lienard form): y' = -x (slow), x' = (y - x^3 / 3 + x) / eps
// (fast) from (y, x) = (2/3, 2), DeltaT = 0.1. The fast variable follows the outer branches of
// the cubic; at its folds (x = +-1, where its rate (x^2 - 1) / eps goes to 0) it jumps to the
// other branch, every 0.8 time units. With savings the fold was crossed late: the slowed fast
// variable stayed on the middle, repelling branch for a macro step (growing, not decaying), the
// comparison with doubled terms, as late, saw a hundredth of the error, and y ended 5.9 tol off at
// 1e-1 by t = 3.7; at 1e-2 the micro step of a state near the fold (rate 1,600) was taken into
// the jump (rate 3,000), where RK4 is unstable and came to rest on the middle branch, and y ended
// 8.7 tol off. The fastest radius at a step's end, followed every step, now brings the spectra in
// again where it fell by half, bounds the step's savings by its end rate, and takes none where its
// mode grows there.
struct VanDerPolParams {
  double eps = 1e-3;
};
void VanDerPolSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[1];
  f[1] = 0;
}
void VanDerPolFast(const void *ctx, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = (x[0] - x[1] * x[1] * x[1] / 3 + x[1]) / ((const VanDerPolParams *)ctx)->eps;
}

TEST(VSHMMAdapt, ARelaxationOscillatorJumpsAtItsFolds)
{
  struct Case {
    double eps, DeltaT, T, tol;
  };
  /* the fourth: DeltaT 0.2, a single-rate step at the micro step of a state before the fold went
     through the jump at h rho = 4.1 uncompared and ended off the branch (x = 1.59, the branch at
     1.98): 67 tol at t = 3.6; the fifth: a retry that coarsened the time ratio ended on the
     repelling branch (only the first try's end was looked at), 6.4 tol at t = 5.4 */
  for (const Case c : {Case{1e-3, 0.1, 3.7, 1e-1}, Case{1e-3, 0.1, 3.7, 1e-2}, Case{1e-4, 0.1, 3.7, 1e-1}, Case{1e-3, 0.2, 3.6, 1e-3}, Case{1e-3, 0.2, 5.4, 1e-1}}) {
    VanDerPolParams params;
    params.eps = c.eps;
    ExpectWithinTolerance({VanDerPolSlow, VanDerPolFast}, {2.0 / 3, 2.0}, c.T, c.tol, c.eps / 100, c.eps / 200, 1, 1e-8, c.DeltaT, &params);
  }
}

// The same fold in a medium level of three: y' = -x + (w - x) / 10 (slow), x' = (y - x^3 / 3 + x) /
// 1e-2 (medium), w' = -(w - x) / 1e-4 (fastest, slaved to x) from (2/3, 2, 2), DeltaT = 0.1, y
// observed. Only the fastest level's radius was followed: the medium level crossed its folds
// with time ratio 9 (9.8 tol at 1e-1 by t = 2.3). With the medium level followed too, its spectra
// estimated past a fold (every mode growing, none limiting) made it an oscillating level for the
// rest of the run, its folds no longer looked at (34 tol at t = 4, 1e-2).
void MediumFoldSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[1] + 0.1 * (x[2] - x[1]);
  f[1] = f[2] = 0;
}
void MediumFoldMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[2] = 0;
  f[1]        = (x[0] - x[1] * x[1] * x[1] / 3 + x[1]) / 1e-2;
}
void MediumFoldFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = 0;
  f[2]        = -(x[2] - x[1]) / 1e-4;
}

TEST(VSHMMAdapt, AMediumLevelJumpsAtItsFolds)
{
  SplitProblem p;
  p.terms                      = {MediumFoldSlow, MediumFoldMedium, MediumFoldFast};
  const std::vector<double> x0 = {2.0 / 3, 2.0, 2.0};
  for (const std::pair<double, double> c : {std::pair<double, double>{1e-1, 2.3}, std::pair<double, double>{1e-2, 4.0}}) {
    const double      tol = c.first, T = c.second;
    const double      ref     = ConvergedReference({MediumFoldSlow, MediumFoldMedium, MediumFoldFast}, nullptr, x0, T, 1e-5, 5e-6, 1e-8);
    const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
    AdaptRun          run;
    ASSERT_EQ(SolveObservingX0(options.c_str(), p, x0, {"slow", "medium", "fast"}, 0.1, T, &run), 0);
    /* within 2 tol, the issue's bound (measured at most 0.5 and 1.2 tol over the sampled times: a
       jump's timing, which the local estimates bound only step by step) */
    EXPECT_LE(std::abs(run.x[0] - ref), 2 * tol * (1 + std::abs(ref))) << options << ": y(" << T << ") = " << run.x[0] << ", reference " << ref;
  }
}

// The Oregonator (two-variable form): z' = x - z (slow), x' = (x (1 - x) - z (x - q) / (x + q)) /
// 1e-2 (fast, q = 8e-4) from (z, x) = (0.2, 0.5), DeltaT = 0.1. x falls from 0.5 towards q within
// the third macro step, its rate growing from about 100 to 12,000 and more: the try's micro step
// (0.014) stayed finite but went past the pole at x = -q (a growing mode at its end, dt rho = 470),
// the step was accepted, and the next failed with Inf at t = 0.3. A growing mode at a try's end
// that the micro step does not resolve now bounds the micro step to it.
void OregonatorSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[1] - x[0];
  f[1] = 0;
}
void OregonatorFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscReal q = 8e-4;
  f[0]              = 0;
  f[1]              = (x[1] * (1 - x[1]) - x[0] * (x[1] - q) / (x[1] + q)) / 1e-2;
}

TEST(VSHMMAdapt, AFastVariableFallingTowardsAPoleIsResolved)
{
  ExpectWithinTolerance({OregonatorSlow, OregonatorFast}, {0.2, 0.5}, 1, 1e-1, 2e-6, 1e-6, 1, 1e-9);
}

// A bistable fast variable driven across its folds by a slow forcing: s' = z - s (slow),
// z' = -(z^3 - z - 0.8 cos t) / eps (fast, eps = 1e-3) from (s, z) = (0, 1.2), DeltaT = 0.1, to
// t = 8, s observed. z follows one outer branch of the cubic until 0.8 cos t passes the fold
// (+-0.385), then jumps to the other: twice per period. The first jump took the savings back for
// its step (the fast mode grew at the step's end), and the ratio left at 1 was taken as a
// negligible saving, kept for the rest of the run (single-rate, 5x the work).
void HysteresisSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[1] - x[0];
  f[1] = 0;
}
void HysteresisFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] * x[1] * x[1] - x[1] - 0.8 * PetscCosReal(t)) / 1e-3;
}

TEST(VSHMMAdapt, SavingsComeBackAfterAFold)
{
  const AdaptRun run = ExpectWithinTolerance({HysteresisSlow, HysteresisFast}, {0.0, 1.2}, 8, 1e-1, 1e-5, 5e-6, 1, 1e-8);
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 50000) << "the savings are not taken again after the first jump";
}

// A damped fast spiral from rest: x' = 1 - x y, y' = w, w' = -1e6 (y - cos x) - 100 w from
// (0.5, 0, 0), DeltaT = 0.1, to t = 0.5. The fast components are 0 at the initial state: there is
// no oscillation to measure the slower field at its phases with, and the first ratios (20) slowed
// the spiral's first turn (y from 0 to cos x and back) past the macro step (1.1 tol at t = 0.5 at
// 1e-2; 6 tol later, where x' grows). Until it can be measured, the ratios keep a turn per macro step.
void SpiralSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] * x[1];
  f[1] = f[2] = 0;
}
void SpiralFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = x[2];
  f[2] = -1e6 * (x[1] - PetscCosReal(x[0])) - 100 * x[2];
}

TEST(VSHMMAdapt, ADampedFastSpiralFromRestTurnsAtLeastOnceInAMacroStep)
{
  ExpectWithinTolerance({SpiralSlow, SpiralFast}, {0.5, 0.0, 0.0}, 0.5, 1e-2, 1e-6, 2e-6, 0.6);
}

// Three levels whose medium rate is proportional to the slow variable, which starts at 0:
// x' = 1 - x + (y - x)/5 + (z - x)/10, y' = 1000 x (x - y), z' = 1e5 (y - z) from 0, DeltaT = 0.5
// to t = 4. At the initial state levels 0/1 are 1 apart (the medium rate is 0) and adapt takes no
// savings between them; a step later they are about 500 apart. Checked again with the spectra adapt
// estimates later, the pair takes savings from then on (before: none for the whole solve, 248,000
// evaluations at 1e-2 for 0.02 tol).
void MergedSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] + 0.2 * (x[1] - x[0]) + 0.1 * (x[2] - x[0]);
  f[1] = f[2] = 0;
}
void MergedMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[2] = 0;
  f[1]        = 1000 * x[0] * (x[0] - x[1]);
}
void MergedFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = 0;
  f[2]        = 1e5 * (x[1] - x[2]);
}

TEST(VSHMMAdapt, APairMergedAtTheInitialStateTakesSavingsOnceSeparated)
{
  SplitProblem p;
  p.terms          = {MergedSlow, MergedMedium, MergedFast};
  const double T   = 4;
  const double ref = ConvergedReference({MergedSlow, MergedMedium, MergedFast}, nullptr, {0.0, 0.0, 0.0}, T, 1e-5, 5e-6);
  for (const double tol : {1e-1, 1e-2}) {
    const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
    AdaptRun          run;
    ASSERT_EQ(SolveObservingX0(options.c_str(), p, {0.0, 0.0, 0.0}, {"slow", "medium", "fast"}, 0.5, T, &run), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << options << ": x(4) = " << run.x[0] << ", reference " << ref;
    ASSERT_EQ(run.savings.size(), 2u);
    EXPECT_GT(run.savings[0], 10.0) << options << ": no savings between levels 0 and 1 after they separated";
  }
}

// A separated relaxation pair whose target starts to move half-way: y' = -y + z (slow {y}),
// z' = -1000 (z - g(t, y)), g from 1/2 to cos(3 y) around t = 2 (tanh, width 0.1), DeltaT = 0.1 to
// t = 4. Once a step can coarsen nothing (micro step and cycle at their bounds) and its last two
// estimates were far below their shares and the last did not rise (more than 2x), its comparison is
// left out, at most 3 steps in a row (the model's prediction stands in): 14 and 9 steps at 1e-2 and
// 1e-3, and y(4) is within the tolerance across the change (0.005 and 0.03 of it).
void SwitchFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  const double s = 0.5 * (1 + std::tanh(10 * (t - 2)));
  f[0]           = 0;
  f[1]           = -1000 * (x[1] - (0.5 + (std::cos(3.0 * x[0]) - 0.5) * s));
}

TEST(VSHMMAdapt, SteadyStepsLeaveOutTheirComparisons)
{
  SplitProblem p;
  p.terms          = {RelaxSlow, SwitchFast};
  const double T   = 4;
  const double ref = ConvergedReference({RelaxSlow, SwitchFast}, nullptr, {1.0, 0.5}, T, 1e-5, 5e-6);
  for (const double tol : {1e-2, 1e-3}) {
    const std::string options = "-ts_vshmm_adapt -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
    AdaptRun          run;
    ASSERT_EQ(SolveObservingX0(options.c_str(), p, {1.0, 0.5}, {"slow", "fast"}, 0.1, T, &run), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << options << ": y(4) = " << run.x[0] << ", reference " << ref;
    /* 16 and 12 steps since two estimates below half their shares let a step go uncompared (14
       and 9 below a tenth, docs/accuracy.md section 37; 15 and 9 before the largest significant coherence measured was kept,
       docs/accuracy.md section 24; 16 and 9 before a macro step's first comparison inherited the faster
       levels' lag; 15 and 8 while a scheduled calibration of a step with nothing to coarsen
       was made; 13 and 8 while a fall of the estimate by more than 2x forced a comparison too; 12
       and 7 while the micro step started at DeltaT / 100, not at the fast level's stability
       limit); without the limit of 3 in a row 19 and 12 then */
    EXPECT_EQ(run.stats.adapt_uncompared, tol > 5e-3 ? 16 : 12) << options;
  }
}

// An oscillating fastest level is not tested for savings: the rotation 1000 times faster than y,
// declared 5 apart (-ts_vshmm_scale_separations 5, not separated), would start from time ratio
// 135 were it separated, but savings shift an oscillation's phase, which one macro step does not
// show (on the advection scenes the admitted savings cost more than they saved): none are taken.
TEST(VSHMMAdapt, AnOscillatingLevelIsNotTestedForSavings)
{
  const RotationParams params;
  const double         T = 1, ref = RotationReference(params, T, 5e-6), tol = 1e-2;
  AdaptRun             run;
  ASSERT_EQ(SolveRotation("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_scale_separations 5 -ts_vshmm_warnings_viewer none", params, T, &run), 0);
  EXPECT_EQ(run.savings.size() == 1 ? run.savings[0] : -1.0, 0.0);
  EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << "y(1) = " << run.x[0] << ", reference " << ref;
}

// A thin fast rotation that the slow variable squares strongly: y' = -y + 1000 u^2 + 0.3 sin(y),
// u(0) = 0.03 (the rotation holds 0.05 of the state's norm but its energy moves y by its whole size).
// The micro step's amplitude bound weighs the rotation by what the slow field makes of its
// amplitude (the drive, averaged over its phase, through the linearised dynamics over the run),
// not by its part of the state alone: weighed so, the micro step damped the rotation and y(2) was
// 2.9 tol off at 1e-1 and 3.4 tol at 1e-2, without a word. Component and additive splits alike
// (for additive splits the rotation's part of the state is -J^2 X / rho^2).
TEST(VSHMMAdapt, AThinFastRotationThatDrivesTheSlowVariableBoundsTheMicroStep)
{
  RotationParams params;
  params.coupling = 1000;
  const double u0 = 0.03, T = 2;
  const double ref = ConvergedReference({RotationSlow, RotationFast}, &params, {0.5, u0, 0}, T, 5e-6, 1e-5, 1e-8);
  for (const SplitKind kind : {SplitKind::Component, SplitKind::Additive})
    for (const double tol : {1e-1, 1e-2}) {
      const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
      AdaptRun          run;
      ASSERT_EQ(SolveRotation(options.c_str(), params, T, &run, u0, kind), 0);
      EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << options << (kind == SplitKind::Additive ? " (additive)" : " (component)") << ": y(2) = " << run.x[0] << ", reference " << ref;
    }
}

// A slow process inside the fast level (the rotation damped at rate 0.1, slower than the slow
// variable's rate 1): VSHMM slows it with the level, by the savings. The levels' spectral radii
// are 1000 apart, but the separation check sees the amplitude's rate among the fast level's own
// modes and finds the scales not separated; with -ts_vshmm_adapt no savings are taken and the
// tolerance is met (before: the savings slowed the damping, 2.2 tol at 1e-2 on a three-scale
// version of this problem, 29 tol at 1e-3, without a word).
TEST(VSHMMSeparation, ASlowDampingInsideTheFastLevelIsNotSeparated)
{
  RotationParams params;
  params.damping        = 0.1;
  const double        T = 2, ref = ConvergedRotationReference(params, T), tol = 1e-2;
  const CapturedError e = CaptureError([&] {
    AdaptRun run;
    return SolveRotation("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100 -ts_vshmm_check_separation error", params, T, &run);
  });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("levels 0/1: 0.136 (spectral radius 0.737"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("slowest rate of level 1's own components 0.1"), std::string::npos) << e.message;
  AdaptRun run;
  ASSERT_EQ(SolveRotation("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_warnings_viewer none", params, T, &run), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << "y(2) = " << run.x[0] << ", reference " << ref;
}

// A fast rotation whose damping a slow variable sets, from 0: x' = -x + q^2 (slow {x}),
// q' = p / eps, p' = -q / eps - 4 x p (fast {q, p}), eps = 1e-3, from x = 0, (q, p) = (1, 0). At
// t = 0 the levels are 1000 apart; at t = 0.1 the rotation's amplitude decays at 2 x = 0.094, a
// tenth of the slow rate: a process inside the fast level that savings slow with it. The own rate
// is estimated again at the end of a try that slows the level, and where the separation is lost
// the pair takes no savings from that step on (its try taken again), and at every later spectra
// estimate while so. Before: the savings stayed, the damping ran several times too slowly, the
// comparisons, whose error saturates in r, read a few hundredths of a share, and x(1) ended 6.0
// tol off at 1e-3, silently (0.85 tol with the check at the next step's spectra only); with
// DeltaT = 0.5, 25 tol (the first step, taken whole with time ratios of 11; 0.2 now). Said once,
// and an error with -ts_vshmm_check_separation error.
void DampedByXFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = x[2] / 1e-3;
  f[2] = -x[1] / 1e-3 - 4 * x[0] * x[2];
}

TEST(VSHMMSeparation, AFastLevelThatLosesItsSeparationTakesNoSavings)
{
  const AdaptRun run  = ExpectWithinTolerance({DampedByXSlow, DampedByXFast}, {0.0, 1.0, 0.0}, 1, 1e-3, 1e-5, 2e-5, 1.5, 1e-8);
  const AdaptRun wide = ExpectWithinTolerance({DampedByXSlow, DampedByXFast}, {0.0, 1.0, 0.0}, 1, 1e-3, 1e-5, 2e-5, 1.5, 1e-8, 0.5);
  EXPECT_LT(wide.evaluations + wide.stats.adapt_evaluations, 200000); /* 99,228; 596,736 where the own rate at the try's end only moved the error model */
  ASSERT_EQ(run.savings.size(), 1u);
  EXPECT_EQ(run.savings[0], 0.0); /* no savings at the end */
  const CapturedError e = CaptureError([&] {
    AdaptRun     r;
    SplitProblem p;
    p.terms = {DampedByXSlow, DampedByXFast};
    return SolveObservingX0("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_check_separation error", p, {0.0, 1.0, 0.0}, {"slow", "fast"}, 0.1, 1, &r);
  });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("separation check at t = 0.1: the time scales of the RHS splits are no longer separated"), std::string::npos) << e.message;
}

// A slow passage through a Hopf bifurcation of the fast level: y' = -y + u^2 + v^2 (slow {y}),
// (u, v)' = (mu u - v - u r^2, u + mu v - v r^2) / eps (fast {u, v}), r^2 = u^2 + v^2,
// eps = 1e-3, mu = -0.5 + t / 2 (a slow drift through 0 at t = 1), from y = 0, (u, v) = (0.5, 0).
// Until t = 1 the rotation decays to about e^-250; after it u = 0 is unstable, and the rotation
// leaves it when the growth since t = 1 has made up that decay (at t = 2, as a converged RK4 finds
// it), not when mu crosses 0. The savings slow the decay and the growth by different time ratios
// and the amplitude is far below what a comparison of y sees: -ts_vshmm_adapt at 1e-3 left u = 0
// early, y(2) 76 tol off with estimates summing to 0.3 tol, silently (89 tol with mu a slow
// variable of the state: u = 0 left at t = 1.8). Now said (an error with
// -ts_vshmm_check_separation error) once a spectra estimate finds the fastest level's own
// components a tiny part of the state with a mode growing much faster than the slow rate; a drift
// that keeps mu < 0 is not.
struct HopfParams {
  double drift = 0.5; // mu = -0.5 + drift t
};
void HopfSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] * x[1] + x[2] * x[2];
  f[1] = f[2] = 0;
}
void HopfFast(const void *ctx, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  const double mu = -0.5 + ((const HopfParams *)ctx)->drift * t, r2 = x[1] * x[1] + x[2] * x[2];
  f[0] = 0;
  f[1] = (mu * x[1] - x[2] - x[1] * r2) / 1e-3;
  f[2] = (x[1] + mu * x[2] - x[2] * r2) / 1e-3;
}

TEST(VSHMMSeparation, AFastLevelAtAnUnstableEquilibriumIsSaid)
{
  for (const double drift : {0.5, 0.1}) {
    HopfParams          params;
    const CapturedError e = CaptureError([&] {
      params.drift = drift;
      AdaptRun     r;
      SplitProblem p;
      p.terms  = {HopfSlow, HopfFast};
      p.params = &params;
      return SolveObservingX0("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_check_separation error", p, {0.0, 0.5, 0.0}, {"slow", "fast"}, 0.1, 2, &r);
    });
    if (drift > 0.2) {
      EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
      EXPECT_NE(e.message.find("the fastest level's own components"), std::string::npos) << e.message;
      EXPECT_NE(e.message.find("sit at an unstable equilibrium"), std::string::npos) << e.message;
    } else EXPECT_EQ(e.code, 0) << "mu < 0 throughout: " << e.message;
  }
}

// Observables that carry the fast phase: x' = -x + q^2 (slow {x}), q' = p / eps, p' = -q / eps
// (fast {q, p}), eps = 1e-3, from (0, 1, 0), observed through x and q. Exactly q = cos(t / eps),
// x = (1 - e^-t) / 2 + (cos(w t) + w sin(w t) - e^-t) / (2 (1 + w^2)), w = 2 / eps. VSHMM samples
// the rotation statistically: with savings the sampled q is one phase of it, not the solution's,
// and a comparison sees a phase as different as the solution's. -ts_vshmm_adapt ended 2.2 and 2.5
// tol off at 1e-1 and 1e-2 with estimates of 0.9 of the tolerance, silently, and took 24 million
// evaluations at 1e-3. Now the try's end state shows q moving along the fast level's own splits
// about 500 times faster than the slow radius, swinging by tens of tolerances: no savings, said.
void PhaseFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = x[2] / 1e-3;
  f[2] = -x[1] / 1e-3;
}
struct PhaseObserved {
  SplitProblem *p;
  bool          phase;      // observe q too
  double        ripple = 0; // the first observable is x + ripple q
};
PetscErrorCode PhaseObservables(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;
  const PhaseObserved   *o = (const PhaseObserved *)ctx;

  PetscFunctionBeginUser;
  PetscCall(GatherState(o->p, X, x));
  q[0] = x[0] + o->ripple * x[1];
  if (o->phase) q[1] = x[1];
  PetscFunctionReturn(0);
}
PetscErrorCode SolvePhase(const char *options, bool phase, PetscReal T, AdaptRun *run, double ripple = 0)
{
  SplitProblem  p;
  PhaseObserved o{&p, phase, ripple};
  p.terms = {DampedByXSlow, PhaseFast}; /* x' = -x + q^2: the slow split of the damped rotation above */
  return SolveObserving(options, p, {0.0, 1.0, 0.0}, {"slow", "fast"}, 0.1, T, run, SplitKind::Component, phase ? 2 : 1, PhaseObservables, &o);
}

TEST(VSHMMSeparation, ObservablesThatCarryTheFastPhaseTakeNoSavings)
{
  const double T = 0.9, w = 2 / 1e-3, q = std::cos(T / 1e-3); /* at T = 0.9, q's error is 1.43 and 1.68 tol (at 1, 0.55 and 0.81) */
  const double x = (1 - std::exp(-T)) / 2 + (std::cos(w * T) + w * std::sin(w * T) - std::exp(-T)) / (2 * (1 + w * w));
  for (const double tol : {1e-1, 1e-2}) {
    AdaptRun          run;
    const std::string options = "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
    ASSERT_EQ(SolvePhase(options.c_str(), true, T, &run), 0);
    EXPECT_LE(std::abs(run.x[1] - q), 2 * tol * (1 + std::abs(q))) << "q(T) = " << run.x[1] << ", exact " << q << " at tol " << tol; /* 2.2 and 2.5 tol before */
    EXPECT_LE(std::abs(run.x[0] - x), 2 * tol * (1 + std::abs(x))) << "x(T) = " << run.x[0] << ", exact " << x;
    ASSERT_EQ(run.savings.size(), 1u);
    EXPECT_EQ(run.savings[0], 0.0);
    EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 500000); /* 24 million at 1e-3 before */
  }
  /* said: an error on request, with adapt and with savings set; observing x alone says nothing */
  for (const char *options : {"-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_check_separation error", "-ts_vshmm_savings_factors 100 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_check_separation error"}) {
    const CapturedError e = CaptureError([&] {
      AdaptRun r;
      return SolvePhase(options, true, 0.3, &r);
    });
    EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP) << options;
    EXPECT_NE(e.message.find("observable 1 (of 2) moves with level 1's oscillation"), std::string::npos) << e.message;
  }
  for (const char *options : {"-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_check_separation error", "-ts_vshmm_savings_factors 100 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_check_separation error"}) {
    const CapturedError e = CaptureError([&] {
      AdaptRun r;
      return SolvePhase(options, false, 0.3, &r);
    });
    EXPECT_EQ(e.code, 0) << options << ": " << e.message;
  }
  /* x + q / 20: a ripple of 5% with the fast phase, about 400 of the TS's default tolerances 1e-4. With
     fixed savings, where no tolerance was asked for, it is said only from a tenth of the quantity
     on; asked for 1e-3, the savings go */
  {
    const CapturedError e = CaptureError([&] {
      AdaptRun r;
      return SolvePhase("-ts_vshmm_savings_factors 100 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_check_separation error -ts_vshmm_check_stability_interval 1", false, 0.3, &r, 0.05);
    });
    EXPECT_EQ(e.code, 0) << e.message;
    AdaptRun r;
    ASSERT_EQ(SolvePhase("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_warnings_viewer none", false, 0.3, &r, 0.05), 0);
    ASSERT_EQ(r.savings.size(), 1u);
    EXPECT_EQ(r.savings[0], 0.0);
  }
}

// The medium phase observed under a decaying fast level: x' = -x + u^2 (slow), (u, v)' = (v, -u) /
// 1e-3 (medium), w' = -(w - u) / 1e-5 (fast), additive splits, from (0, 1, 0, 1), x and u observed,
// to t = 0.9 at 1e-1. Bounding the swing of u by the fast level's radius (1e5) made it 100 times too
// small: 5 tol at 1e-1 unseen (99.8 at 1e-2). A decaying faster level turns nothing faster: the
// frequency is that of the sustained oscillations (1e3), the savings below the medium level go.
void MediumPhaseSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] * x[1];
  f[1] = f[2] = f[3] = 0;
}
void MediumPhaseMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[3] = 0;
  f[1]        = x[2] / 1e-3;
  f[2]        = -x[1] / 1e-3;
}
void MediumPhaseFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = f[2] = 0;
  f[3]               = -(x[3] - x[1]) / 1e-5;
}
PetscErrorCode SolveMediumPhase(const char *options, AdaptRun *run)
{
  SplitProblem p;
  p.terms = {MediumPhaseSlow, MediumPhaseMedium, MediumPhaseFast};
  return SolveObserving(options, p, {0.0, 1.0, 0.0, 1.0}, {"slow", "medium", "fast"}, 0.1, 0.9, run, SplitKind::Additive, 2, X0X1Observables, &p);
}

TEST(VSHMMSeparation, AMediumPhaseUnderADecayingFastLevelIsFound)
{
  const double u = std::cos(0.9 / 1e-3);
  AdaptRun     run;
  ASSERT_EQ(SolveMediumPhase("-ts_vshmm_adapt -ts_rtol 1e-1 -ts_atol 1e-1 -ts_vshmm_warnings_viewer none", &run), 0);
  EXPECT_LE(std::abs(run.x[1] - u), 2 * 1e-1 * (1 + std::abs(u))) << "u(0.9) = " << run.x[1] << ", exact " << u; /* 0.02 tol; 5 tol before */
  const CapturedError e = CaptureError([&] {
    AdaptRun r;
    return SolveMediumPhase("-ts_vshmm_adapt -ts_rtol 1e-1 -ts_atol 1e-1 -ts_vshmm_check_separation error", &r);
  });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("observable 1 (of 2) moves with level 1's oscillation"), std::string::npos) << e.message;
}

// A van der Pol oscillator as the fast level: y' = -y + x1^2 / 4 (slow {y}), x1' = x2 / eps,
// x2' = (-x1 + (1 - x1^2) x2) / eps (fast {x1, x2}), eps = 1e-3. At (x1, x2) = (1, 0) its Jacobian
// is a rotation, but forward differences of the nonlinear field give its Ritz values a real part
// of about 1.8e-8 of the frequency (their truncation error).
void VdpSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + 0.25 * x[1] * x[1];
  f[1] = f[2] = 0;
}
void VdpFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = x[2] / 1e-3;
  f[2] = (-x[1] + (1 - x[1] * x[1]) * x[2]) / 1e-3;
}

// An amplitude rate of 1e-7 of the frequency (the rotation at 1e3 damped at 1e-4) is below the
// noise of forward differences (1e-6 of |lambda|): such real parts are estimated again by central
// differences, which find it (and the pair is not separated: the damping is slower than y), while
// van der Pol's truncation noise of the same size disappears (its pair stays separated). With
// forward differences and a threshold of 1e-8 van der Pol was called unseparated too.
TEST(VSHMMSeparation, AnAmplitudeRateInForwardDifferencesNoiseIsJudgedByCentralDifferences)
{
  RotationParams params;
  params.damping        = 1e-4;
  const CapturedError e = CaptureError([&] {
    AdaptRun run;
    return SolveRotation("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100 -ts_vshmm_check_separation error", params, 0.1, &run);
  });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("slowest rate of level 1's own components 0.0001"), std::string::npos) << e.message;
  AdaptRun     run;
  SplitProblem p;
  p.terms = {VdpSlow, VdpFast};
  EXPECT_EQ(SolveObservingX0("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100 -ts_vshmm_check_separation error", p, {0.5, 1, 0}, {"slow", "fast"}, 0.1, 0.1, &run), 0);
}

// The same damped rotation written with additive splits (each split returns its term for every
// component): the fast split's own terms on the components they write (u, v) carry the damping,
// which is found; the slower split's terms are not counted (on the paper's oscillators they carry
// real parts of 3.3e-6 of the frequency that VSHMM does average correctly). The undamped rotation
// passes. A rate that changes the amplitude by less than 5% over the run is not counted (a
// sparse-spectral advection cluster's own block: 6.4e-5, over t = 8).
TEST(VSHMMSeparation, ASlowDampingInsideAFastAdditiveSplitIsNotSeparated)
{
  // damped at 0.1 (20% of amplitude over t = 2): found; undamped, or damped at 0.01 (2% over the
  // run, under the 5% counted): separated
  for (const double damping : {0.1, 0.0, 0.01}) {
    RotationParams params;
    params.eps            = 1e-2;
    params.damping        = damping;
    const CapturedError e = CaptureError([&] {
      AdaptRun run;
      return SolveRotation("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 10 -ts_vshmm_check_separation error", params, 2.0, &run, 1, SplitKind::Additive);
    });
    if (damping > 0.05) {
      EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
      EXPECT_NE(e.message.find("slowest rate of level 1's own terms (an oscillation's amplitude rate) 0.1)"), std::string::npos) << e.message;
    } else EXPECT_EQ(e.code, 0) << "damping " << damping << ": " << e.message;
  }
}

// The slow damping in the fastest of three levels is slowed by every time ratio, r_0 too: the pair
// 0/1 is judged by it as well (the slowest own rate of every faster level), and neither pair is
// separated (the radii alone: 99.5 and 100).
TEST(VSHMMSeparation, ASlowRateTwoLevelsUpCountsForThePairBelow)
{
  RotationParams params;
  params.eps            = 1e-2;
  params.damping        = 0.1;
  const CapturedError e = CaptureError([&] {
    Guard        guard("-ts_vshmm_micro_dt 1e-5 -ts_vshmm_savings_factors 10,10 -ts_vshmm_check_separation error");
    SplitProblem p;
    TS           ts;
    Vec          x;
    p.n      = 4;
    p.terms  = {TriSlow, TriMedium, TriFast};
    p.params = &params;
    PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {0.5, 0, 1, 0}, {"slow", "medium", "fast"}, &ts, &x));
    PetscCall(TSSetTimeStep(ts, 0.1));
    PetscCall(TSSetMaxTime(ts, 0.1));
    PetscCall(TSSetFromOptions(ts));
    const PetscErrorCode ierr = TSSolve(ts, x);
    PetscCall(DestroySplitTS(&p, &ts, &x));
    return ierr;
  });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("levels 0/1: 0.1 (spectral radius 1, slowest rate of level 2's own components 0.1)"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("levels 1/2: 0.001"), std::string::npos) << e.message;
}

// Tolerance in, accuracy out: the sampled slow variable is within the tolerance of the converged
// DNS, the estimate is reported, and user-set parameters stay fixed.
TEST(VSHMMAdapt, DissipativeExampleMeetsTheTolerance)
{
  // whole state (PETSc's weighted norm) at 1e-1, the observable xi at 1e-2
  for (double tol : {1e-1, 1e-2}) {
    AdaptRun run;
    ASSERT_EQ(SolveDissipativeAdapt(AdaptOptions(tol).c_str(), 1.0, &run, tol < 0.1), 0);
    EXPECT_LE(std::abs(run.x[0] - kXiAt1), 2 * tol * (1 + kXiAt1)) << "tol " << tol;
    EXPECT_GT(run.stats.error_estimate_total, 0.0);
    EXPECT_GE(run.stats.adapt_calibrations, 1);
    EXPECT_GT(run.stats.adapt_evaluations, 0);
    EXPECT_EQ(run.stats.macro_steps, 10);
  }
  AdaptRun fixed;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_micro_dt 5e-5", 0.5, &fixed), 0);
  EXPECT_EQ(fixed.micro_dt, 5e-5);
  AdaptRun savings;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_savings_factors 20,5", 0.5, &savings), 0);
  ASSERT_EQ(savings.savings.size(), 2u);
  EXPECT_NEAR(savings.savings[0], 20, 1e-9);
  EXPECT_NEAR(savings.savings[1], 5, 1e-9);
}

// The faster levels' lag is measured (ComparisonStart()): at eps = 3e-3 the medium level's rate
// 2 xi / eps, slowed by a time ratio of about 80, relaxes over most of a macro step, so each step
// starts from the lag the last one left, and a comparison from that same start measured 10 to 200
// times less than the steps' errors: xi(1.7) was 2.45 tolerances off at 3e-3, silently (2.38 with
// additive splits). A macro step's first comparison now starts from the end state of the last one
// on the components only faster levels write: those outside the slowest splits' index sets, or,
// with additive splits, where the slowest field is zero and a faster one is not.
// Reference: RK4 with dt = eps^2 / 8 and eps^2 / 16, which agree to 1e-10.
TEST(VSHMMAdapt, TheComparisonInheritsItsOwnLagOfTheFasterLevels)
{
  constexpr double kXiAt17 = 1.6005408968, tol = 3e-3;
  for (const SplitKind kind : {SplitKind::Component, SplitKind::Additive}) {
    AdaptRun run;
    ASSERT_EQ(SolveDissipativeAdapt(AdaptOptions(tol).c_str(), 1.7, &run, true, 3e-3, kind), 0);
    EXPECT_LE(std::abs(run.x[0] - kXiAt17), tol * (1 + kXiAt17)) << (kind == SplitKind::Additive ? "additive" : "component") << " splits";
    EXPECT_EQ(run.stats.macro_steps, 17);
  }
}

// A pair whose faster level had no rate at the initial state takes savings once it has one. From
// (3, 0, 0) eta's own rate -2 eta / eps is 0 at t = 0: levels 0/1 were not separated there, took
// no savings "while so", and the first step's time ratio r_0 = 1 was then taken as negligible
// savings and dropped for the rest of the solve, though 0.1 later the pair was 11,000 apart: to t =
// 2 at 1e-2, 97,848 evaluations for 0.02 tol (the additive splits, whose own rate is judged
// otherwise, took savings: 44,300). Now the pair starts again from its separated ratios once
// separated, with the split between the error terms measured again: 44,456 evaluations, 0.08 tol
// (52,944 where the choice raises r_0 from 1 instead; 60,848 without the new measurement).
// Reference: RK4 at dt = eps^2 / 8 and / 16 (equal to the printed digits).
TEST(VSHMMAdapt, APairSeparatedAgainTakesSavings)
{
  constexpr double kXiAt2 = 1.3909041021, tol = 1e-2;
  AdaptRun         run;
  ASSERT_EQ(SolveDissipativeAdapt(AdaptOptions(tol).c_str(), 2.0, &run, true, 5e-3, SplitKind::Component, {3, 0, 0}), 0);
  EXPECT_LE(std::abs(run.x[0] - kXiAt2), tol * (1 + kXiAt2));
  ASSERT_EQ(run.savings.size(), 2u);
  EXPECT_GT(run.savings[0], 5.0); // alpha_1 of the last macro step: 0 while r_0 stayed 1
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 50000);
}

// The -info output of one adaptive run of the dissipative example (xi observed, to t = 2), and
// whether this rank has it (PetscInfo() on a TS writes from its first rank; the others get an
// empty string).
PetscErrorCode CaptureInfo(const std::function<PetscErrorCode()> &solve, std::string *info, bool *written)
{
  char path[] = "/tmp/vshmm_adapt_info_XXXXXX";
  int  fd     = mkstemp(path);

  PetscFunctionBeginUser;
  PetscCheck(fd >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "no temporary file");
  close(fd);
  PetscCall(PetscInfoSetFile(path, "w"));
  PetscCall(PetscInfoAllow(PETSC_TRUE));
  const PetscErrorCode ierr = solve();
  PetscInfoAllow(PETSC_FALSE);
  PetscInfoSetFile(nullptr, "w");
  PetscCall(ierr);
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  *written               = rank == 0;
  const std::string file = std::string(path) + "." + std::to_string(rank); // PETSc appends the rank to the name
  std::ifstream     in(file);
  info->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::remove(file.c_str());
  std::remove(path);
  PetscFunctionReturn(0);
}

PetscErrorCode DissipativeAdaptInfo(const char *options, PetscReal eps, AdaptRun *run, std::string *info, bool *written)
{
  return CaptureInfo([&] { return SolveDissipativeAdapt(options, 2.0, run, true, eps); }, info, written);
}

// The paper's resonant oscillators (eps = 1e-3, examples/ode/oscillatory.c), additive splits of
// (x1, x2, y1, y2); observables I1 = x1^2 + y1^2, I2 = x2^2 + y2^2.
void OscSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -3 * x[0] * x[1] * x[1];
  f[1] = -x[1];
  f[2] = x[2] / 2;
  f[3] = -x[3] + 2 * x[0] * x[0] * x[3];
}
void OscMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[3] * x[3] / 1e-3;
  f[1] = -x[3] / 1e-3;
  f[2] = 0;
  f[3] = x[1] / 1e-3;
}
void OscFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[2] / 1e-6;
  f[1] = -x[3] / 1e-6;
  f[2] = x[0] / 1e-6;
  f[3] = x[1] / 1e-6;
}
PetscErrorCode OscObservables(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[0] * x[0] + x[2] * x[2];
  q[1] = x[1] * x[1] + x[3] * x[3];
  PetscFunctionReturn(0);
}

// The largest time ratio r_l of the tries in -info's "time ratios a,b,..." lines.
double LargestTimeRatio(const std::string &info, size_t l)
{
  double largest = 0;
  for (size_t at = info.find("time ratios "); at != std::string::npos; at = info.find("time ratios ", at + 1)) {
    size_t pos = at + 12;
    for (size_t j = 0; j < l; ++j) pos = info.find(',', pos) + 1;
    largest = std::max(largest, std::stod(info.substr(pos)));
  }
  return largest;
}

// A faster level that oscillates is never slowed below the slower one: r_l <= the pair's separation
// (here the radii's ratio, 1,000 for medium/fast). On the oscillators at 1.5e-3, t = 0.8, the first
// macro step's calibrations measured the medium/fast term as negligible, and each retry doubled r_2
// as the micro step fell, up to 11,787 (1,473 once a ratio past its calibration's reach is
// measured again): the fast rotation slowed below the medium one.
TEST(VSHMMAdapt, AnOscillatingFasterLevelIsNotSlowedBelowTheSlowerOne)
{
  SplitProblem p;
  AdaptRun     run;
  std::string  info;
  bool         written;
  p.n     = 4;
  p.terms = {OscSlow, OscMedium, OscFast};
  ASSERT_EQ(CaptureInfo(
              [&] {
                Guard guard("-ts_vshmm_adapt -ts_rtol 1.5e-3 -ts_atol 1.5e-3 -ts_vshmm_warnings_viewer none");
                TS    ts;
                Vec   x;
                PetscFunctionBeginUser;
                PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Additive, {1, 0.5, 0, 0.5}, {"slow", "medium", "fast"}, &ts, &x));
                PetscCall(TSSetTimeStep(ts, 0.8));
                PetscCall(TSSetMaxTime(ts, 0.8));
                PetscCall(TSVSHMMSetObservables(ts, 2, OscObservables, &p));
                PetscCall(TSSetFromOptions(ts));
                PetscCall(TSSolve(ts, x));
                PetscCall(GatherState(&p, x, run.x));
                PetscCall(DestroySplitTS(&p, &ts, &x));
                PetscFunctionReturn(0);
              },
              &info, &written),
            0);
  if (written) {
    const size_t at = info.find("levels 1/2: ");
    ASSERT_NE(at, std::string::npos);
    const double separation = std::stod(info.substr(at + 12));
    EXPECT_NEAR(separation, 1000, 2);
    EXPECT_GT(LargestTimeRatio(info, 1), 0.5 * separation);  // the bound is reached
    EXPECT_LE(LargestTimeRatio(info, 1), separation * 1.01); // -info prints it to 3 digits
  }
  // I1(0.8) within 2 tol of the converged reference (docs/ode-experiments.md)
  const double I1 = run.x[0] * run.x[0] + run.x[2] * run.x[2];
  EXPECT_LE(std::abs(I1 - 0.9917765569), 2 * 1.5e-3 * (1 + 0.9917765569));
}

// A comparison that blows up is no estimate. On the dissipative example with the savings factors
// set (10, 50: adapt keeps them and chooses the micro step; 20, 20 until a macro step's first
// comparison inherited the faster levels' lag, accuracy.md section 22, and 20, 5 until the stable
// steps were also estimated at the end of a step whose fast rate grew, section 13) the comparison
// of a later step's first try coarsens the micro step beyond what the medium level's steps keep
// stable with the savings set (a comparison may coarsen what the user set: it only measures): it
// is taken as "no estimate" (the step is redone with every parameter finer), not as an error of
// 1e307 tolerances scaled into the error model.
TEST(VSHMMAdapt, AComparisonThatBlowsUpIsNoEstimate)
{
  AdaptRun    run;
  std::string info;
  bool        written;
  ASSERT_EQ(DissipativeAdaptInfo("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_savings_factors 10,50", 1e-2, &run, &info, &written), 0);
  if (written) {
    EXPECT_NE(info.find("blew up: no estimate"), std::string::npos);
    EXPECT_EQ(info.find("e+307"), std::string::npos); // PETSC_INFINITY (finite) is not an estimate
  }
  EXPECT_LT(run.stats.error_estimate_total, 10.0); // the accepted steps' estimates, in tolerances
  constexpr double kXiAt2 = 1.4816640204;          // docs/dissipative.md (converged DNS)
  EXPECT_LE(std::abs(run.x[0] - kXiAt2), 2e-2 * (1 + kXiAt2));
}

// The levels' stable steps follow the state: the dissipative example's initial state is off its
// slow manifold, where the full field's spectral radius is 9.1e3 (largest stable RK4 micro step
// 3.06e-4); a macro step later it is 1.09e4 (2.53e-4). Estimated again after the first macro step,
// the later steps and their comparisons stay inside the new bound; with the initial estimate alone
// the comparisons of eps = 1e-2, 1e-3 ran at 2.75e-4 and blew up or read 10 times the share.
TEST(VSHMMAdapt, TheStableStepsAreEstimatedAgainAfterTheFirstStep)
{
  AdaptRun    run;
  std::string info;
  bool        written;
  ASSERT_EQ(DissipativeAdaptInfo("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", 1e-2, &run, &info, &written), 0);
  if (written) {
    EXPECT_EQ(info.find("blew up"), std::string::npos);
    // every later comparison's micro step at most 0.8 (a decaying fastest level's fraction) of the
    // largest stable step after the layer, radius 1.0e4 to 1.1e4 (those of the first step, [0,
    // 0.1], are inside the initial state's: 0.8 of 3.06e-4, 2.45e-4)
    const size_t later = info.find("macro step [0.1, 0.2]");
    ASSERT_NE(later, std::string::npos);
    size_t n = 0;
    for (size_t at = info.find("Adapt: comparison dt ", later); at != std::string::npos; at = info.find("Adapt: comparison dt ", at + 1), ++n) EXPECT_LE(std::stod(info.substr(at + 21)), 0.8 * 2.785 / 1.0e4 * 1.01);
    EXPECT_GE(n, 19u); // every later macro step compared at least once
  }
  constexpr double kXiAt2 = 1.4816640204; // docs/dissipative.md (converged DNS)
  EXPECT_LE(std::abs(run.x[0] - kXiAt2), 2e-3 * (1 + kXiAt2));
}

// The macro step after an initial layer accepted on the layer's own estimate (two comparisons,
// LayerEstimate()) takes parameters chosen from that estimate. The dissipative example at eps =
// 1e-2, tol 1e-2: the first step is accepted on the layer's 0.045 shares (its comparison read
// 0.24, above the share); the second step kept the first's parameters (146 micro cycles, estimate
// a twelfth of its share) and the run took 26,472 evaluations; chosen from the layer's estimate it
// takes 64 cycles and the run 23,700, xi(2) 0.18 tol off (0.02 before). docs/accuracy.md section 23.
TEST(VSHMMAdapt, TheStepAfterALayerIsChosenFromTheLayersEstimate)
{
  AdaptRun    run;
  std::string info;
  bool        written;
  ASSERT_EQ(DissipativeAdaptInfo("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 1e-2, &run, &info, &written), 0);
  if (written) {
    // the micro cycles of the last "macro step [t0, t1] try k: ..., N cycles;" line before `at`
    const auto Cycles = [&](const std::string &step, size_t at) {
      const size_t line = info.rfind("Adapt: macro step " + step + " try ", at);
      if (line == std::string::npos) return -1.0;
      const size_t end = info.find(" cycles;", line);
      return std::stod(info.substr(info.rfind(' ', end - 1) + 1));
    };
    const size_t accepted = info.find("accepted on the layer's estimate");
    ASSERT_NE(accepted, std::string::npos);
    const double layer = Cycles("[0., 0.1]", info.rfind("Adapt: macro step", accepted) - 1); // the try accepted
    const double next  = Cycles("[0.1, 0.2]", info.find("Adapt: macro step [0.1, 0.2] try 0:") + 1);
    ASSERT_GT(layer, 0);
    ASSERT_GT(next, 0);
    EXPECT_LE(next, 0.6 * layer); // 64 and 146 (146 when the parameters were kept)
  }
  constexpr double kXiAt2 = 1.4816640204; // docs/dissipative.md (converged DNS)
  EXPECT_LE(std::abs(run.x[0] - kXiAt2), 0.5e-2 * (1 + kXiAt2));
  EXPECT_LE(run.evaluations + run.stats.adapt_evaluations, 25000); // 26,472 with the parameters kept
}

// The micro step of a decaying fastest level keeps 0.8 of its stability limit. At 0.9 of the
// initial state's limit (3.06e-4 for the dissipative example's full field) the first macro step's
// tries ran near the limit of the state a step later (2.53e-4), where RK4 hardly damps the fast
// variable: finer savings meant more micro steps and larger estimates, and the first step was
// accepted as a floor at 2.2 times its share, 1.06 tol in truth; xi(1) at tol 1e-2 was 1.05 tol off
// (0.18 with the margin).
TEST(VSHMMAdapt, ADecayingFastestLevelKeepsAMarginToItsStabilityLimit)
{
  AdaptRun run;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 1.0, &run, true), 0);
  EXPECT_LE(std::abs(run.x[0] - kXiAt1), 0.5 * 1e-2 * (1 + kXiAt1));
}

// A retry after the first accepted step does not coarsen a time ratio to where its comparison
// cannot double it. The dissipative example at eps = 1e-4, tol 2e-3 (xi observed, to t = 2): the
// retry of the step at t = 1.1 refined r_1 2.4x and coarsened r_2 from 307 into its stability bound
// 502, where the comparison left it as it was; the medium level's transient after the change of
// r_1, followed late by the fast level, put an error of 5 shares into xi against an estimate of
// 0.06: xi was 3.5 tol off at t = 1.5 and 1.32 at t = 2 (0.41 and 0.17 with r_2 kept). Since a
// macro step's first comparison inherits the faster levels' lag (docs/accuracy.md section 22) the
// runs took other paths, and the rule acted at tol 4e-3 (r_2 kept at 203); since the step after an
// initial layer accepted on the layer's own estimate is chosen from that estimate (section 23) it
// acts at 2e-3 again (r_2 kept at 353 instead of 375). Reference: the averaged equation (its error
// is O(eps)).
TEST(VSHMMAdapt, ARetryDoesNotCoarsenARatioItsComparisonCannotMeasure)
{
  constexpr double kAveragedXiAt2 = 1.48172016; // tools/adapt_suite.py (averaged equation, RK4)
  AdaptRun         run;
  std::string      info;
  bool             written;
  for (const double tol : {2e-3, 4e-3}) {
    ASSERT_EQ(DissipativeAdaptInfo(AdaptOptions(tol).c_str(), 1e-4, &run, &info, &written), 0);
    if (written && tol < 3e-3) EXPECT_NE(info.find("the retry keeps time ratio 2"), std::string::npos);
    EXPECT_LE(std::abs(run.x[0] - kAveragedXiAt2), 0.5 * tol * (1 + kAveragedXiAt2)) << "tol " << tol;
  }
}

// A relaxation that slows as it nears its manifold: x' = -x + z, z' = -(z - x)^3 / eps (eps =
// 1e-3, from (1, 0), x observed, to t = 2). z relaxes at 3 (z - x)^2 / eps: 3,000 at t = 0, below 10
// times the slow rate by t = 0.2 and below the slow rate itself by t = 0.8. With the savings kept
// after the separation was lost, the error they left in z drove x for the rest of the run: at tol
// 1e-4 x(2) was 7.4 tol off with estimates summing to 0.6, at 5e-4 1.8, silently. A decaying pair
// separated at set-up that comes within 10 now takes no savings while so (docs/accuracy.md section
// 23): 0.35 and 0.46 tol. RK4 references at h = 5e-6 and 1e-5 agree to 1e-10.
void CubicSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1];
  f[1] = 0;
}
void CubicFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscReal d = PetscRealPart(x[1] - x[0]);
  f[0]              = 0;
  f[1]              = -d * d * d / 1e-3;
}
TEST(VSHMMAdapt, ARelaxationThatSlowsNearItsManifoldLosesItsSavings)
{
  for (const double tol : {1e-4, 5e-4}) ExpectWithinTolerance({CubicSlow, CubicFast}, {1.0, 0.0}, 2.0, tol, 5e-6, 1e-5, 1.0);
}

// The run's work against single-rate steps at the largest step its bounds allow (statistics
// single_rate_evaluations, and a warning at the solve's last macro step where the work with the
// estimates is larger). The relaxation above at 1e-2 loses its savings as it slows: 7,800 split
// evaluations with its estimates, 4.2 times the 1,840 of single-rate RK4 steps (2.1 times the
// 3,744 at its micro steps, the figure before 2026-11-28): said, once. The dissipative example (xi
// observed, 1e-2, to t = 1) saves (21,900 against 58,164; 87,252 at its micro steps): nothing
// said. With fixed parameters the
// count is that of the micro step: 5 macro steps of 2,000 micro steps, 4 stages, 3 splits. Where
// the separation check has said that the scales are not separated, this is not said again.
TEST(VSHMMAdapt, SavingsThatDoNotPayForTheirComparisonsAreSaid)
{
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const char  *warning = "did not pay for their comparisons";
  SplitProblem p;
  AdaptRun     cubic, diss, fixed;
  p.terms = {CubicSlow, CubicFast};
  testing::internal::CaptureStderr();
  PetscErrorCode ierr = SolveObservingX0("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, 2, &cubic);
  std::string    err  = testing::internal::GetCapturedStderr();
  ASSERT_EQ(ierr, 0);
  EXPECT_GT(cubic.evaluations + cubic.stats.adapt_evaluations, cubic.stats.single_rate_evaluations);
  EXPECT_GT(cubic.stats.single_rate_evaluations, 0);
  if (rank == 0) {
    const size_t at = err.find(warning);
    EXPECT_NE(at, std::string::npos) << err;
    EXPECT_EQ(err.find(warning, at + 1), std::string::npos) << "said more than once: " << err;
    EXPECT_NE(err.find("this run to t = 2. took"), std::string::npos) << err;
    EXPECT_NE(err.find("-ts_type rk"), std::string::npos) << err;
  }
  testing::internal::CaptureStderr();
  ierr = SolveDissipativeAdapt(AdaptOptions(1e-2).c_str(), 1.0, &diss, true);
  err  = testing::internal::GetCapturedStderr();
  ASSERT_EQ(ierr, 0);
  EXPECT_LT(2 * (diss.evaluations + diss.stats.adapt_evaluations), diss.stats.single_rate_evaluations);
  EXPECT_EQ(err.find(warning), std::string::npos) << err;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_micro_dt 5e-5 -ts_vshmm_savings_factors 20,5", 0.5, &fixed), 0);
  EXPECT_EQ(fixed.stats.single_rate_evaluations, 5 * 2000 * 4 * 3);
  /* scales not separated (two levels twice apart): the separation check said so, and no more */
  std::vector<PetscReal> x, savings;
  testing::internal::CaptureStderr();
  ierr = SolveWeak("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", &x, &savings);
  err  = testing::internal::GetCapturedStderr();
  ASSERT_EQ(ierr, 0);
  if (rank == 0) EXPECT_NE(err.find("not separated"), std::string::npos) << err;
  EXPECT_EQ(err.find(warning), std::string::npos) << err;
}

// A non-normal fast level (docs/accuracy.md section 38): x' = w, w' = -x - 0.1 w + 0.005 y1 (slow:
// x, w); y1' = -1e3 y1 + 1e5 y2, y2' = -1e3 (y2 - sin x) (fast: a double eigenvalue -1e3 and a
// coupling 1e5), from (1, 0, 0, sin 1 + 1), x observed, DeltaT 0.5, to t = 4 at 1e-3. The
// comparisons drive the micro step far below the fast level's stability limit (2.2e-3), so single-
// rate steps at the run's micro steps (the count before 2026-11-28) cost nearly what the run did
// (1.8 times less), where a plain RK4 at the stable step takes about 10 times less: the count is
// now at the largest step the run's bounds allow, and the warning says it.
void NonNormalSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[1];
  f[1] = -x[0] - 0.1 * x[1] + 0.005 * x[2];
  f[2] = f[3] = 0;
}
void NonNormalFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = 0;
  f[2]        = -1e3 * x[2] + 1e5 * x[3];
  f[3]        = -1e3 * (x[3] - PetscSinReal(PetscRealPart(x[0])));
}

TEST(VSHMMAdapt, TheWorkIsSetAgainstSingleRateStepsAtTheLargestStepTheBoundsAllow)
{
  SplitProblem p;
  AdaptRun     run;
  std::string  said;
  p.terms      = {NonNormalSlow, NonNormalFast};
  p.components = {{0, 1}, {2, 3}};
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", p, {1.0, 0.0, 0.0, PetscSinReal(1.0) + 1}, 0.5, 4, &run, &said), 0);
  const PetscInt64 work = run.evaluations + run.stats.adapt_evaluations;
  EXPECT_GT(work, 5 * run.stats.single_rate_evaluations) << work << " against " << run.stats.single_rate_evaluations;
  EXPECT_GE(run.stats.single_rate_evaluations, 4 * 8 * 4 * 2); /* at least 5 steps per macro step (every split at every stage) */
  EXPECT_NE(said.find("did not pay for their comparisons"), std::string::npos) << said;
}

// A slow oscillator under a fast relaxation (an outside probe's, 2026-11-28): x' = y, y' = -x -
// 0.1 y + 0.5 z (slow: x, y), z' = -(z - sin x) / 1e-3 (fast: z, which only decays). Level 1's field
// G_1 = f_0 + f_1 holds the slow oscillation (frequency 0.85), which was taken for level 1's own:
// savings set were said to make a forcing 5.8e5 times the slow dynamics drift the answer by 1.5e9 of
// its size (it was 7e-4 off), and -ts_vshmm_adapt took no savings for a swing of 1e4 tolerances. An
// oscillation of a faster level's field at most twice the slower level's spectral radius and slower
// than half the slowest mode of the level's own components is the slower level's own
// (SustainedMode()).
void SlowOscillatorSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[1];
  f[1] = -x[0] - 0.1 * x[1] + 0.5 * x[2];
  f[2] = 0;
}
void SlowOscillatorFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = 0;
  f[2]        = -(x[2] - PetscSinReal(PetscRealPart(x[0]))) / 1e-3;
}

TEST(VSHMMSeparation, ASlowOscillationInAFasterLevelsFieldIsTheSlowLevels)
{
  const std::vector<double> x0  = {1.0, 0.0, 0.0};
  const double              ref = ConvergedReference({SlowOscillatorSlow, SlowOscillatorFast}, nullptr, x0, 1, 1e-5, 5e-6, 1e-9);
  SplitProblem              p;
  AdaptRun                  run;
  std::string               said;
  p.terms      = {SlowOscillatorSlow, SlowOscillatorFast};
  p.components = {{0, 1}, {2}};
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_savings_factors 10 -ts_vshmm_micro_dt 1e-4", p, x0, 0.1, 1, &run, &said), 0);
  EXPECT_EQ(said.find("forces level 0"), std::string::npos) << said;
  EXPECT_LE(std::abs(run.x[0] - ref), 2e-3) << "x(1) = " << run.x[0] << ", reference " << ref;
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", p, x0, 0.1, 1, &run, &said), 0);
  EXPECT_EQ(said.find("moves with level"), std::string::npos) << said;
  EXPECT_EQ(said.find("forces level"), std::string::npos) << said;
  EXPECT_LE(std::abs(run.x[0] - ref), 2e-3 * (1 + std::abs(ref))) << "x(1) = " << run.x[0] << ", reference " << ref;
}

// The same problem with additive splits (each split returns a full-size term, zero off its own
// terms): no index set tells which components are slow, and the slow y, unobserved, took the first
// macro step's error (z not yet relaxed, the slow variables moving 9 times faster), which x showed
// only later: x(1) 1.9 tolerances off at 1e-3, every step's estimate far below its share. The
// fields' values show x and y slow (SlowComponentsFromValues()), and they are controlled with x as
// they are with component splits.
TEST(VSHMMAdapt, AdditiveSplitsSlowComponentsAreSeenFromTheFieldsValues)
{
  const std::vector<double> x0  = {1.0, 0.0, 0.0};
  const double              ref = ConvergedReference({SlowOscillatorSlow, SlowOscillatorFast}, nullptr, x0, 1, 1e-5, 5e-6, 1e-9), tol = 1e-3;
  SplitProblem              p;
  AdaptRun                  run;
  std::string               said;
  p.terms = {SlowOscillatorSlow, SlowOscillatorFast};
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", p, x0, 0.1, 1, &run, &said, SplitKind::Additive), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << "x(1) = " << run.x[0] << ", reference " << ref;
}

// A stiff bond and a slow angle (a planar molecule, an outside probe's; docs/accuracy.md section
// 39): x = (theta, p_theta, r, p_r), the bond at w = 1000 (1 + 0.2 cos theta) oscillating about
// r = 1 with amplitude 9e-4. The fastest level's oscillation was probed about r = 0 (its phases
// crossed the 1/r^3 terms: a frequency of 5.7e6 read, the micro step bound 100 times too low),
// and with component splits the bond's own block [[0, 1], [-w^2, 0]] read amplitude rates of 1e-6
// of w from the rounding of its finite differences ("not separated", no savings). Now its
// oscillation is taken about its centre and the noise levels scale with the block's entries over
// its eigenvalues: theta within the tolerance, at a few percent of the work before.
void MoleculeSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscReal th = PetscRealPart(x[0]), r = PetscRealPart(x[2]);
  f[0] = x[1] / (r * r);
  f[1] = -PetscSinReal(th) + 0.2 * 1e6 * (1 + 0.2 * PetscCosReal(th)) * PetscSinReal(th) * (r - 1) * (r - 1);
  f[2] = f[3] = 0;
}
void MoleculeFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscReal th = PetscRealPart(x[0]), r = PetscRealPart(x[2]), w = 1000 * (1 + 0.2 * PetscCosReal(th));
  f[0] = f[1] = 0;
  f[2]        = x[3];
  f[3]        = -w * w * (r - 1) + x[1] * x[1] / (r * r * r);
}

TEST(VSHMMAdapt, AStiffBondOscillatesAboutItsCentre)
{
  const std::vector<double> x0  = {1.0, 0.0, 1.0 + 1.0 / (1000 * (1 + 0.2 * std::cos(1.0))), 0.0};
  const double              ref = ConvergedReference({MoleculeSlow, MoleculeFast}, nullptr, x0, 2, 5e-6, 2.5e-6, 1e-9), tol = 1e-2;
  for (const SplitKind kind : {SplitKind::Component, SplitKind::Additive}) {
    SplitProblem p;
    AdaptRun     run;
    std::string  said;
    p.terms      = {MoleculeSlow, MoleculeFast};
    p.components = {{0, 1}, {2, 3}};
    ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", p, x0, 0.5, 2, &run, &said, kind), 0);
    const char *name = kind == SplitKind::Component ? "component splits" : "additive splits";
    EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << name << ": theta(2) = " << run.x[0] << ", reference " << ref;
    EXPECT_EQ(said.find("not separated"), std::string::npos) << name << ": " << said;
    EXPECT_LT(run.evaluations + run.stats.adapt_evaluations + run.stats.stability_evaluations, 100000) << name; /* RK4 meeting the tolerance: 2 x 4 x 13,334 steps */
  }
}

// Components of sizes 1e4 and 1e-2 (an outside probe's, docs/accuracy.md section 39): X' = -X / 2
// + 1e4 z, Y' = -Y + 1e-2 (X / 1e4) z (slow), z' = -(z - sin(X / 1e4 + Y / 1e-2)) / 1e-3 (fast),
// the whole state at 1e-3 to t = 4. A growth probe measured factors 2.12, 1.91, 1.38, 1.17, 1.09,
// 1.045, a transient settling; their mean was taken for a rate (e^(3.3 t)) and the run warned
// that the tolerance was missed 73 times (the error 0.61 tol). A growth falling step after step is
// a passing transient.
void SizesSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -0.5 * x[0] + 1e4 * x[2];
  f[1] = -x[1] + 1e-2 * (x[0] / 1e4) * x[2];
  f[2] = 0;
}
void SizesFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = 0;
  f[2]        = -(x[2] - PetscSinReal(PetscRealPart(x[0] / 1e4 + x[1] / 1e-2))) / 1e-3;
}

TEST(VSHMMAdapt, AGrowthThatFallsStepAfterStepIsATransient)
{
  const std::vector<double> x0  = {1e4, -0.5e-2, 0.0};
  const double              ref = ConvergedReference({SizesSlow, SizesFast}, nullptr, x0, 4, 1e-5, 5e-6, 1e-6);
  SplitProblem              p;
  AdaptRun                  run;
  std::string               said;
  p.terms      = {SizesSlow, SizesFast};
  p.components = {{0, 1}, {2}};
  ASSERT_EQ(Saying(
              "-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3",
              [&](const char *all) {
                return SolveObserving(all, p, x0, {"slow", "fast"}, 0.1, 4, &run, SplitKind::Component, 0, nullptr, nullptr);
              },
              &said),
            0);
  EXPECT_EQ(said.find("grew the errors"), std::string::npos) << said;
  EXPECT_LE(std::abs(run.x[0] - ref), 1e-3 * (1 + std::abs(ref))) << "X(4) = " << run.x[0] << ", reference " << ref;
}

// Tolerance vectors alone (TSSetTolerances() with the scalars 0, as TSRK's adaptive steps accept)
// weigh the whole state: before, -ts_vshmm_adapt refused them ("needs a positive tolerance"), and
// with the scalars left at PETSc's defaults it chose its first parameters for 1e-4 (on the
// components of sizes 1e4 and 1e-2 below, 1.8 times the work). Vectors equal to scalars give the
// scalars' run, step for step.
TEST(VSHMMAdapt, ToleranceVectorsAloneAreTheTolerance)
{
  const std::vector<double> x0 = {1e4, -0.5e-2, 0.0};
  AdaptRun                  scalars, vectors, defaults;
  const auto                vector = [](PetscReal scalar) {
    return [scalar](TS ts, Vec x) -> PetscErrorCode {
      Vec a, r;
      PetscFunctionBeginUser;
      PetscCall(VecDuplicate(x, &a));
      PetscCall(VecDuplicate(x, &r));
      PetscCall(VecSet(a, 1e-2));
      PetscCall(VecSet(r, 1e-2));
      PetscCall(TSSetTolerances(ts, scalar, a, scalar, r));
      PetscCall(VecDestroy(&a));
      PetscCall(VecDestroy(&r));
      PetscFunctionReturn(0);
    };
  };
  for (AdaptRun *run : {&scalars, &vectors, &defaults}) {
    SplitProblem p;
    p.terms             = {SlowOscillatorSlow, SlowOscillatorFast};
    p.components        = {{0, 1}, {2}};
    const char *options = run == &scalars ? "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-2 -ts_atol 1e-2" : "-ts_vshmm_adapt -ts_vshmm_warnings_viewer none";
    ASSERT_EQ(SolveObserving(options, p, x0, {"slow", "fast"}, 0.1, 4, run, SplitKind::Component, 0, nullptr, nullptr, run == &scalars ? std::function<PetscErrorCode(TS, Vec)>() : vector(run == &vectors ? 0.0 : (PetscReal)PETSC_DECIDE)), 0);
  }
  EXPECT_EQ(vectors.evaluations + vectors.stats.adapt_evaluations, scalars.evaluations + scalars.stats.adapt_evaluations);
  EXPECT_EQ(defaults.evaluations + defaults.stats.adapt_evaluations, scalars.evaluations + scalars.stats.adapt_evaluations);
  for (size_t i = 0; i < x0.size(); ++i) EXPECT_EQ(vectors.x[i], scalars.x[i]) << i;
}

// x' = 1 - x H, H = q^2 + p^2 + q^4 / 2 the energy of a fast Duffing rotation (q' = 1000 p, p' =
// -1000 (q + q^3)) that the slow split damps by 0.3 (x - 0.5) (additive splits), H and x observed,
// to t = 4 at 1e-2 (an outside probe's, docs/accuracy.md section 39). The growth probes measured
// their perturbation on every component, the rotation's too, whose part turns with its phase:
// factors 1.1, 19, 2.5, 1.9, and "the tolerance is not met", 2,180 tolerances said for 0.38 true. They
// now perturb and measure the slow component the fields' values show (x).
void DampedEnergySlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscScalar H = x[1] * x[1] + x[2] * x[2] + 0.5 * x[1] * x[1] * x[1] * x[1];
  f[0]                = 1 - x[0] * H;
  f[1]                = -0.3 * (x[0] - 0.5) * x[1];
  f[2]                = -0.3 * (x[0] - 0.5) * x[2];
}
void UndampedDuffingFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 1000 * x[2];
  f[2] = -1000 * (x[1] + x[1] * x[1] * x[1]);
}
PetscErrorCode DuffingObservables(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[1] * x[1] + x[2] * x[2] + 0.5 * std::pow(x[1], 4);
  q[1] = x[0];
  PetscFunctionReturn(0);
}

TEST(VSHMMAdapt, AFastRotationsPhaseIsNoGrowth)
{
  const std::vector<double> x0  = {0.0, 1.0, 0.0};
  const double              ref = ConvergedReference({DampedEnergySlow, UndampedDuffingFast}, nullptr, x0, 4, 1e-5, 5e-6, 1e-6);
  for (const double tol : {1e-1, 1e-2}) { /* at 1e-1 measuring on x alone, the perturbation still on q, p too, read a growth e^(14.7 t) */
    SplitProblem p;
    AdaptRun     run;
    std::string  said;
    p.terms                   = {DampedEnergySlow, UndampedDuffingFast};
    const std::string options = "-ts_vshmm_adapt -ts_rtol " + std::to_string(tol) + " -ts_atol " + std::to_string(tol);
    ASSERT_EQ(Saying(
                options,
                [&](const char *all) {
                  return SolveObserving(all, p, x0, {"slow", "fast"}, 0.1, 4, &run, SplitKind::Additive, 2, DuffingObservables, &p);
                },
                &said),
              0);
    EXPECT_EQ(said.find("grew the errors"), std::string::npos) << tol << ": " << said;
    EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << tol << ": x(4) = " << run.x[0] << ", reference " << ref;
  }
}

// A slow x driven by the squared amplitude A^2 of a fast rotation about a centre that moves with x
// (additive splits; an outside probe's, docs/accuracy.md section 39), x and A^2 observed, from p =
// 0: there the fast split's q' = 1000 p is exactly 0, and the fields' values at the initial state
// took q for a slow component; the first macro step's comparisons measured its fast phase and the
// run took no savings at all (252,640 split evaluations at 1e-1, RK4 102,400). The state nudged
// along the whole field shows the term.
void CentreSlow(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  const PetscScalar d = x[1] - 1 - 0.5 * x[0], A2 = d * d + x[2] * x[2];
  f[0] = -0.5 * x[0] + 0.8 * A2 + 0.5 * PetscSinReal(t);
  f[1] = 0.3 * (1 - A2) * d;
  f[2] = 0.3 * (1 - A2) * x[2];
}
void CentreFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = 1000 * x[2];
  f[2] = -1000 * (x[1] - 1 - 0.5 * x[0]);
}
PetscErrorCode CentreObservables(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;

  PetscFunctionBeginUser;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[0];
  q[1] = std::pow(x[1] - 1 - 0.5 * x[0], 2) + x[2] * x[2];
  PetscFunctionReturn(0);
}

TEST(VSHMMAdapt, AnExactZeroOfTheInitialStateHidesNoFastTerm)
{
  const std::vector<double> x0  = {0.0, 1.5, 0.0};
  const double              ref = ConvergedReference({CentreSlow, CentreFast}, nullptr, x0, 4, 1e-5, 5e-6, 1e-7);
  SplitProblem              p;
  AdaptRun                  run;
  p.terms = {CentreSlow, CentreFast};
  ASSERT_EQ(SolveObserving("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-1 -ts_atol 1e-1", p, x0, {"slow", "fast"}, 0.1, 4, &run, SplitKind::Additive, 2, CentreObservables, &p), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), 1e-1 * (1 + std::abs(ref))) << "x(4) = " << run.x[0] << ", reference " << ref;
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 60000);
}

// A damped fast rotation about a moving equilibrium (u, v) -> (y^2, 0), y ~ 8, under a medium y and
// a slow x (component splits, three scales; tolerance vectors with zero scalars, no observables;
// an outside probe's): the fastest level's own components held the state's norm, u ~ 75, and the
// micro step's amplitude bound took all of it for the oscillation's amplitude: micro steps 7-30
// times below RK4's, and the single-rate steps the cost check counts at that bound said the run
// cost 1.03 times them where a plain RK4 needs 38,400. Its part of the state is now the
// displacement from the centre.
void MovingCentreSlow(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + 0.02 * x[2] + 0.5 * PetscCosReal(t);
  f[1] = f[2] = f[3] = 0;
}
void MovingCentreMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[2] = f[3] = 0;
  f[1]               = -5 * (x[1] - 10 * PetscSinReal(PetscRealPart(x[0]) + 1));
}
void MovingCentreFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const PetscScalar d = x[2] - x[1] * x[1];
  f[0] = f[1] = 0;
  f[2]        = -200 * d - 2000 * x[3];
  f[3]        = 2000 * d - 200 * x[3];
}

TEST(VSHMMAdapt, ADampedRotationAboutAMovingCentreIsItsDisplacement)
{
  SplitProblem p;
  AdaptRun     run;
  p.terms            = {MovingCentreSlow, MovingCentreMedium, MovingCentreFast};
  p.components       = {{0}, {1}, {2, 3}};
  const auto vectors = [](TS ts, Vec x) -> PetscErrorCode {
    Vec a, r;
    PetscFunctionBeginUser;
    PetscCall(VecDuplicate(x, &a));
    PetscCall(VecDuplicate(x, &r));
    PetscCall(VecSet(a, 1e-2));
    PetscCall(VecSetValue(a, 1, 1e-1, INSERT_VALUES));
    PetscCall(VecSetValue(a, 2, 1.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(a));
    PetscCall(VecAssemblyEnd(a));
    PetscCall(VecSet(r, 1e-2));
    PetscCall(TSSetTolerances(ts, 0, a, 0, r));
    PetscCall(VecDestroy(&a));
    PetscCall(VecDestroy(&r));
    PetscFunctionReturn(0);
  };
  ASSERT_EQ(SolveObserving("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none", p, {0.0, 0.0, 0.0, 0.0}, {"slow", "medium", "fast"}, 0.1, 4, &run, SplitKind::Component, 0, nullptr, nullptr, vectors), 0);
  const std::vector<double> ref = Rk4State({MovingCentreSlow, MovingCentreMedium, MovingCentreFast}, nullptr, {0, 0, 0, 0}, 4, 1e-5), check = Rk4State({MovingCentreSlow, MovingCentreMedium, MovingCentreFast}, nullptr, {0, 0, 0, 0}, 4, 5e-6);
  EXPECT_NEAR(ref[0], check[0], 1e-8);
  EXPECT_LE(std::abs(run.x[0] - ref[0]), 1e-2 * (1 + std::abs(ref[0]))) << "x(4) = " << run.x[0] << ", reference " << ref[0];
  EXPECT_LT(run.stats.single_rate_evaluations, 100000) << "RK4 at its stable step: 38,400";
}

// A decaying pair of levels less than 2 apart, among separated ones, takes no savings. The
// dissipative example at eps = 3e-2 (xi observed, tol 3e-3, to t = 2): levels 1/2 are 1.31 apart
// (0/1: 667). Their start ratio r_2 = 1 cannot be coarsened by a calibration (r - 1 = 0 times 4),
// so its term read 0 and the choice took r_2 as free: it rose to 3.1 (the fast level slowed below
// the medium one), the first macro step's estimate stayed at 8 shares over 11 tries, and the run
// took 3.6e5 evaluations (5.0e4 at the tighter 1e-3). Now 12,476, xi(2) 0.07 tol off.
TEST(VSHMMAdapt, ADecayingPairLessThanTwoApartTakesNoSavings)
{
  constexpr double kXiAt2 = 1.4815043634; // RK4 dt = 5e-5 (1e-4 agrees to 2e-9)
  AdaptRun         run;
  std::string      info;
  bool             written;
  ASSERT_EQ(DissipativeAdaptInfo(AdaptOptions(3e-3).c_str(), 3e-2, &run, &info, &written), 0);
  if (written) EXPECT_NE(info.find("levels 1/2 are 1.31 apart: no savings between them"), std::string::npos);
  EXPECT_LE(std::abs(run.x[0] - kXiAt2), 3e-3 * (1 + kXiAt2));
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 50000);
  ASSERT_EQ(run.savings.size(), 2u);
  EXPECT_EQ(run.savings[1], 0.0); // alpha_2 = 0: r_2 = 1
}

// In an initial layer the comparison overstates the error 2.5-4 times (docs/accuracy.md section 3);
// a second comparison (every term x 1.5) measures how the error grows and re-estimates the tries of
// the first macro step whose estimate is at most 4 times its share. The dissipative example at
// 1e-3 (xi observed, to t = 2): a try of the first macro step is accepted on it, within its share
// where the comparison alone read it above (measured with the micro step at 0.9 of its stability
// limit: the sixth try, true error 0.207 tol against a share of 0.224); xi(2) stays within the
// tolerance. 7 rejections (10 before a macro step's first comparison inherited the faster levels'
// lag, docs/accuracy.md section 22; 8 before the first macro step measured the micro step's term
// from the finer side, section 12).
TEST(VSHMMAdapt, AnInitialLayerIsEstimatedFromTwoComparisons)
{
  AdaptRun run;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", 2.0, &run, true), 0);
  constexpr double kXiAt2 = 1.4816640204; // docs/dissipative.md (converged DNS)
  EXPECT_LE(std::abs(run.x[0] - kXiAt2), 1e-3 * (1 + kXiAt2));
  EXPECT_EQ(run.stats.adapt_layer_estimates, 1);
  EXPECT_EQ(run.stats.adapt_rejections, 7);
  // at 1e-2 the micro step's term, measured from the finer side in the first step, is above the
  // share: the tries refine the micro step below its stability bound, where the second comparison
  // can scale every term, and it is made once (none while that term was left at 0: the tries ran at
  // the bound, where no comparison can scale the micro step's term as the others)
  AdaptRun loose;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 1.0, &loose, true), 0);
  EXPECT_EQ(loose.stats.adapt_layer_estimates, 1);
}

// The dissipative example (component splits, DeltaT = 0.1) to tfinal with n observables f; the
// error code of TSSolve(), and where it succeeded the state, the converged reason and the time.
struct ObservedRun {
  std::vector<PetscReal> x;
  TSConvergedReason      reason = TS_CONVERGED_ITERATING;
  PetscReal              time   = -1;
};

PetscErrorCode SolveDissipativeObserved(const char *options, PetscReal tfinal, PetscInt n, PetscErrorCode (*f)(TS, PetscReal, Vec, PetscReal[], void *), ObservedRun *run)
{
  Guard             guard(options);
  DissipativeParams params;
  SplitProblem      p;
  TS                ts;
  Vec               x;

  PetscFunctionBeginUser;
  DissipativeProblem(&p, &params);
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {5, -10, 5}, {"slow", "medium", "fast"}, &ts, &x));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, tfinal));
  PetscCall(TSVSHMMSetObservables(ts, n, f, &p));
  PetscCall(TSSetFromOptions(ts));
  const PetscErrorCode ierr = TSSolve(ts, x);
  if (!ierr) {
    PetscCall(GatherState(&p, x, run->x));
    PetscCall(TSGetConvergedReason(ts, &run->reason));
    PetscCall(TSGetTime(ts, &run->time));
  }
  PetscCall(DestroySplitTS(&p, &ts, &x));
  return ierr;
}

// An observables function that leaves a quantity unset (NaN here) is an error at set-up naming it,
// not a run whose every estimate is infinite (each macro step refined to the try limit).
PetscErrorCode NaNSecondObservable(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(XiObservable(nullptr, 0, X, q, ctx));
  q[1] = std::numeric_limits<PetscReal>::quiet_NaN();
  PetscFunctionReturn(0);
}

TEST(VSHMMAdapt, ANonFiniteObservableIsAnError)
{
  ObservedRun         run;
  const CapturedError e = CaptureError([&] { return SolveDissipativeObserved("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 0.2, 2, NaNSecondObservable, &run); });
  EXPECT_EQ(e.code, PETSC_ERR_FP);
  EXPECT_NE(e.message.find("TSVSHMMSetObservables(): observable 1 (of 2) is nan. at the initial state (t = 0.)"), std::string::npos) << "message: " << e.message;
}

// A step without any finite estimate fails; it is not accepted as a guess. The observables here
// are finite at the initial state (the set-up check passes) and NaN ever after, so no comparison
// gives a finite difference: after 6 tries in a row, each with every parameter finer (7 tries in
// all: the first is taken again within the stable steps of its end state, whose fast rate grew), the solve
// stops with a PETSc error naming the macro step, or (-ts_error_if_step_fails false) with
// TS_DIVERGED_STEP_REJECTED and the solution left at the step's start.
PetscErrorCode LaterNaNObservable(TS ts, PetscReal t, Vec X, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(XiObservable(ts, t, X, q, ctx));
  if (t > 0) q[0] = std::numeric_limits<PetscReal>::quiet_NaN();
  PetscFunctionReturn(0);
}

TEST(VSHMMAdapt, AStepWithoutAFiniteEstimateFails)
{
  ObservedRun         run;
  const CapturedError e = CaptureError([&] { return SolveDissipativeObserved("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_warnings_viewer none", 0.3, 1, LaterNaNObservable, &run); });
  EXPECT_EQ(e.code, PETSC_ERR_NOT_CONVERGED);
  EXPECT_NE(e.message.find("no finite error estimate for the macro step from t = 0. to 0.1 after 7 tries: the comparisons of the last 6 gave no finite difference"), std::string::npos) << "message: " << e.message;
  ObservedRun stopped;
  ASSERT_EQ(SolveDissipativeObserved("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_warnings_viewer none -ts_error_if_step_fails false", 0.3, 1, LaterNaNObservable, &stopped), 0);
  EXPECT_EQ(stopped.reason, TS_DIVERGED_STEP_REJECTED);
  EXPECT_EQ(stopped.time, 0.0);
  ASSERT_EQ(stopped.x.size(), 3u);
  EXPECT_EQ(stopped.x[0], 5.0); // the initial state, untouched
  EXPECT_EQ(stopped.x[1], -10.0);
}

// An observables function that is not collective (each rank returns its own value, as a program
// that forgets to reduce its local sums): under -ts_vshmm_adapt the ranks took different decisions
// and the solve hung. Now an error at set-up naming the observable and the spread, on every rank;
// on one rank there is nothing to disagree and the run ends. A collective function runs as before.
static PetscErrorCode RankDependentObservable(TS ts, PetscReal, Vec X, PetscReal q[], void *)
{
  PetscMPIInt rank;
  PetscReal   norm;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)ts), &rank));
  PetscCall(VecNorm(X, NORM_2, &norm)); /* collective */
  q[0] = norm;
  q[1] = norm + rank; /* not */
  PetscFunctionReturn(0);
}
static PetscErrorCode CollectiveObservable(TS ts, PetscReal t, Vec X, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(RankDependentObservable(ts, t, X, q, ctx));
  q[1] = 2 * q[0];
  PetscFunctionReturn(0);
}

TEST(VSHMMSolver, ObservablesThatDifferBetweenRanksAreAnError)
{
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  for (const bool collective : {false, true}) {
    ObservedRun         run;
    const CapturedError e = CaptureError([&] { return SolveDissipativeObserved("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 0.2, 2, collective ? CollectiveObservable : RankDependentObservable, &run); });
    if (size > 1 && !collective) {
      EXPECT_EQ(e.code, PETSC_ERR_ARG_WRONG) << e.message;
      EXPECT_NE(e.message.find("TSVSHMMSetObservables(): the observables function gave different values on different ranks at t = 0.: observable 1 (of 2) from "), std::string::npos) << e.message;
    } else EXPECT_EQ(e.code, 0) << e.message;
  }
}

// An observables function that returns NaN (or Inf) for a finite state (a logarithm of a quantity
// that reached 0, an uninitialised entry): the comparisons read it as a blown-up run, the step's
// tries refined until they ran out and the solve stopped with "no finite error estimate", which
// named no observable. It still stops so (AStepWithoutAFiniteEstimateFails), and now names the
// observable, the value and the time, on one rank and on several.
static PetscErrorCode ObservableNaNAfter015(TS ts, PetscReal t, Vec X, PetscReal q[], void *)
{
  PetscReal norm;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(X, NORM_2, &norm));
  q[0] = norm;
  q[1] = t > 0.15 ? std::numeric_limits<PetscReal>::quiet_NaN() : 2 * norm;
  PetscFunctionReturn(0);
}

TEST(VSHMMSolver, ObservablesNotFiniteForAFiniteStateAreNamed)
{
  ObservedRun         run;
  const CapturedError e = CaptureError([&] { return SolveDissipativeObserved("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2", 0.4, 2, ObservableNaNAfter015, &run); });
  EXPECT_EQ(e.code, PETSC_ERR_NOT_CONVERGED) << e.message;
  EXPECT_NE(e.message.find("no finite error estimate for the macro step from t = 0.1 to 0.2"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("(the observables function returned NaN for observable 1 (of 2) at t = 0.2, for a state whose entries are all finite: it must return finite values wherever the solution is finite)"), std::string::npos) << e.message;
}

// A slow oscillator that a fast relaxing variable drives: x' = v, v' = -x + z/2, z' = (sin x - z)/eps,
// eps = 1e-3, from (1, 0, 0) to t = 4 (DeltaT = 0.1), with component splits slow {x, v} and fast
// {z} (on PETSC_COMM_SELF: each rank solves its own copy) and x alone as the observable. A time
// ratio r lags z behind sin x by about r eps, which damps the oscillation: within one macro step
// that moves v, and x only at later sampled times. Estimated on x alone, the run at tol 1e-3 ended
// 12 tol off (each step's estimate 0.1-0.2 of its share); with the slow components x, v controlled
// too (the default) and their errors taken to add coherently it ends within the tolerance.
double gSlowDamping = 0; /* v' = -x - c v + z/2: c = 4 makes the slow level only decay */

PetscErrorCode SlowOscillatorRHS(TS, PetscReal, Vec X, Vec F, void *ctx)
{
  const PetscInt     split = ctx ? *(const PetscInt *)ctx : -1; /* -1: the whole field */
  const PetscReal    eps   = 1e-3;
  const PetscScalar *x;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(F, &f));
  if (split < 0 || split == 0) {
    f[0] = x[1];
    f[1] = -x[0] - gSlowDamping * x[1] + 0.5 * x[2];
  }
  if (split < 0 || split == 1) f[split < 0 ? 2 : 0] = (PetscSinReal(x[0]) - x[2]) / eps;
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode FirstComponent(TS, PetscReal, Vec X, PetscReal q[], void *)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  q[0] = PetscRealPart(x[0]);
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

double gSlowVectorAtol = 0; // > 0: TSSetTolerances() with a vector atol, this on the slow components (1 on the fast one)

PetscErrorCode SolveSlowOscillator(const char *options, PetscReal *x0, PetscBool *slow, std::string *view, PetscInt64 *evaluations = nullptr)
{
  Guard          guard(options);
  TS             ts;
  Vec            X;
  IS             is[2];
  const PetscInt split[2] = {0, 1};
  PetscViewer    viewer;
  PetscMPIInt    rank;
  char           path[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscSNPrintf(path, sizeof path, "slow_oscillator_view_%d_%d.txt", (int)getpid(), (int)rank));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3, &X));
  PetscCall(VecSet(X, 0.0));
  PetscCall(VecSetValue(X, 0, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(X));
  PetscCall(VecAssemblyEnd(X));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSVSHMM));
  PetscCall(TSSetRHSFunction(ts, nullptr, SlowOscillatorRHS, nullptr));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 2, 0, 1, &is[0]));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 1, 2, 1, &is[1]));
  PetscCall(TSRHSSplitSetIS(ts, "slow", is[0]));
  PetscCall(TSRHSSplitSetIS(ts, "fast", is[1]));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "slow", nullptr, SlowOscillatorRHS, (void *)&split[0]));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "fast", nullptr, SlowOscillatorRHS, (void *)&split[1]));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, 4.0));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSVSHMMSetObservables(ts, 1, FirstComponent, nullptr));
  PetscCall(TSSetFromOptions(ts));
  if (gSlowVectorAtol > 0) {
    Vec A;
    PetscCall(VecDuplicate(X, &A));
    PetscCall(VecSet(A, gSlowVectorAtol));
    PetscCall(VecSetValue(A, 2, 1.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(A));
    PetscCall(VecAssemblyEnd(A));
    PetscCall(TSSetTolerances(ts, PETSC_DECIDE, A, PETSC_DECIDE, nullptr));
    PetscCall(VecDestroy(&A));
  }
  PetscCall(TSVSHMMGetAdaptSlowComponents(ts, slow));
  PetscCall(TSSolve(ts, X));
  PetscCall(VecGetValues(X, 1, &split[0], x0));
  if (evaluations) {
    TSVSHMMStatistics stats;
    PetscCall(TSVSHMMGetStatistics(ts, &stats));
    *evaluations = std::accumulate(stats.rhs_evaluations, stats.rhs_evaluations + stats.nsplits, stats.adapt_evaluations);
  }
  PetscCall(PetscViewerASCIIOpen(PETSC_COMM_SELF, path, &viewer));
  PetscCall(TSView(ts, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  view->clear();
  if (FILE *f = fopen(path, "r")) {
    char line[512];
    while (fgets(line, sizeof(line), f)) *view += line;
    fclose(f);
  }
  remove(path);
  PetscCall(ISDestroy(&is[0]));
  PetscCall(ISDestroy(&is[1]));
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

void SlowOscillatorTerm(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[1];
  f[1] = -x[0] - gSlowDamping * x[1] + 0.5 * x[2];
  f[2] = (std::sin(x[0]) - x[2]) / 1e-3;
}

// x(4) of the slow oscillator by RK4 with step h from (1, 0, 0).
double SlowOscillatorReference(double h)
{
  return Rk4Reference({SlowOscillatorTerm}, nullptr, {1.0, 0.0, 0.0}, 4.0, h);
}

TEST(VSHMMAdapt, TheSlowComponentsAreControlledWithTheObservables)
{
  const double ref = SlowOscillatorReference(1e-5), tol = 1e-3;
  EXPECT_NEAR(ref, SlowOscillatorReference(5e-6), 1e-9);
  PetscReal   x0;
  PetscBool   slow;
  std::string view;
  ASSERT_EQ(SolveSlowOscillator("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_warnings_viewer none", &x0, &slow, &view), 0);
  EXPECT_TRUE(slow);
  EXPECT_LE(std::abs(x0 - ref), tol * (1 + std::abs(ref))) << "x(4) = " << x0 << ", reference " << ref;
  EXPECT_NE(view.find("with the observables, the 2 slow components"), std::string::npos) << view;
  /* the observable alone: the run's error is that of the fault, 5-15 tol (12.2 measured) */
  ASSERT_EQ(SolveSlowOscillator("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_warnings_viewer none -ts_vshmm_adapt_slow_components false", &x0, &slow, &view), 0);
  EXPECT_FALSE(slow);
  EXPECT_GT(std::abs(x0 - ref), 5 * tol * (1 + std::abs(ref))) << "x(4) = " << x0 << ", reference " << ref;
  EXPECT_NE(view.find("the observables only (-ts_vshmm_adapt_slow_components false)"), std::string::npos) << view;
}

// The same with the slow level over-damped (v' = -x - 4 v + z/2: it only decays): the slow
// components still lead the estimate (47 of the differences at 1e-3), but their errors decay with
// the slow dynamics and the steps' shares follow the measured coherence: x(4) within the
// tolerance (0.46 tol) with 5,344 evaluations (5,048 before the first macro step measured the micro
// step's term from the finer side; 8,336, at 0.16 tol, with the shares DeltaT / span taken for an
// oscillating slow level).
TEST(VSHMMAdapt, TheSlowComponentsOfADecayingSlowLevelAreNotTakenAsCoherent)
{
  gSlowDamping     = 4;
  const double ref = SlowOscillatorReference(1e-5), tol = 1e-3;
  EXPECT_NEAR(ref, SlowOscillatorReference(5e-6), 1e-9);
  PetscReal   x0;
  PetscBool   slow;
  std::string view;
  PetscInt64  evaluations = 0;
  ASSERT_EQ(SolveSlowOscillator("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_warnings_viewer none", &x0, &slow, &view, &evaluations), 0);
  gSlowDamping = 0;
  EXPECT_LE(std::abs(x0 - ref), tol * (1 + std::abs(ref))) << "x(4) = " << x0 << ", reference " << ref;
  EXPECT_LT(evaluations, 6500);
  EXPECT_NE(view.find("with the observables, the 2 slow components"), std::string::npos) << view;
}

// A slow forcing inside the fast split that is stationary at the start: x' = -x + z (slow {x}),
// z' = -(z - cos(3t) x) / 1e-3 (fast {z}) from (1, 0), DeltaT = 0.5, to t = 0.5 at 1e-2. The
// split's time dependence was measured at the step's start only, where d/dt cos(3t) = 0 (rate
// 3e-8; 2.7 at t = 0.5): the first macro step took time ratios of 35, whose error is the same at 69
// (the comparison read a tenth of the share), and x(0.5) ended 3.3 tol off. Measured at the step's
// end too, the old bound (the level sees the forcing at most a tenth of its radius fast) still let
// 33 through, the same 3.3 tol; the bound is now the tolerance times the radius where that is
// smaller (the level lags what it follows by about that ratio, unmeasured): within the tolerance.
void StationaryForcingSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1];
  f[1] = 0;
}
void StationaryForcingFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - std::cos(3 * t) * x[0]) / 1e-3;
}

TEST(VSHMMAdapt, AFastSplitsSlowForcingStationaryAtTheStartIsMeasured)
{
  ExpectWithinTolerance({StationaryForcingSlow, StationaryForcingFast}, {1.0, 0.0}, 0.5, 1e-2, 1e-5, 2e-5, 1, 1e-9, 0.5);
}

// A state at rest until a slow forcing starts at t = 0.5: x' = -x + z + H(t - 0.5) (slow {x}),
// z' = -(z - x) / 1e-3 (fast {z}) from (0, 0), DeltaT = 0.1, to t = 1 at 1e-3. Until t = 0.5 every
// comparison changes nothing (estimate 0); the model stood at its unmeasured equal shares of a
// whole tolerance and each such step refined the parameters (48,828 evaluations to t = 1 for the
// state at rest throughout, 1,056 now). Now an estimate of 0 puts the model at a thousandth of the
// share and the parameters coarsen; the forcing is then followed within the tolerance, with a
// third of the work.
void AtRestSlow(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] + (t > 0.5 ? 1.0 : 0.0);
  f[1] = 0;
}
void AtRestFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - x[0]) / 1e-3;
}

TEST(VSHMMAdapt, AStateAtRestCoarsensItsParameters)
{
  const AdaptRun run = ExpectWithinTolerance({AtRestSlow, AtRestFast}, {0.0, 0.0}, 1, 1e-3, 1e-5, 2e-5, 1, 1e-5);
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 12000); /* 8,296; 24,404 when an estimate of 0 refined the parameters */
}

// A solve bounded by its step count alone (TSSetMaxSteps(), PETSc's default final time
// PETSC_MAX_REAL): x' = -y + sin 3t (slow {x}), y' = -(y - cos(t) sin x) / 1e-3 (fast {y}) from
// (1, 0), 20 macro steps of 0.1, at 1e-3. The accuracy control answers for the run to the last
// step, 2.0, as it does for a final time: the same run as with the final time 2, x(2) within 1.5
// tol (1.10 tol) of RK4 references at 1e-5 and 2e-5. Before, such a solve had no final time, each macro step
// took the whole tolerance, and x(2) ended 11 tol off (the sum of the estimates 10.7).
void StepCountSlow(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[1] + std::sin(3 * t);
  f[1] = 0;
}
void StepCountFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - std::cos(t) * std::sin(x[0])) / 1e-3;
}

TEST(VSHMMAdapt, ASolveBoundedByItsStepCountMeetsTheToleranceAtItsEnd)
{
  const double ref = ConvergedReference({StepCountSlow, StepCountFast}, nullptr, {1.0, 0.0}, 2, 1e-5, 2e-5, 1e-9);
  SplitProblem p;
  AdaptRun     run;
  p.terms = {StepCountSlow, StepCountFast};
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3 -ts_max_steps 20", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, PETSC_MAX_REAL, &run), 0);
  ASSERT_EQ(run.stats.macro_steps, 20);
  EXPECT_LE(std::abs(run.x[0] - ref), 1.5e-3 * (1 + std::abs(ref))) << "x(2) = " << run.x[0] << ", reference " << ref;
  AdaptRun timed; /* the same run with the final time 2 instead: the same steps */
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, 2, &timed), 0);
  EXPECT_NEAR(run.x[0], timed.x[0], 1e-12); /* up to the last step's end: 20 steps of 0.1, or the final time 2 */
  EXPECT_EQ(run.evaluations, timed.evaluations);
}

// The carried comparison converts each macro step's contribution as that step's own comparison
// was: on x' = -y + sin 3t, y' = -(y - cos(t) sin x) / 1e-3 from (1, 0) at 1e-3 (x
// observed) to t = 4, the step at t = 2 has a model that expects almost no change (its conversion
// factor 14.6); applied to the whole carried difference (0.9) it read 13 tolerances and warned,
// for a true error of 0.8. Weighed by the steps' estimates: within 2x of the true error at t = 4,
// no warning.
TEST(VSHMMAdapt, TheCarriedComparisonConvertsEachStepAsItsOwn)
{
  const double ref = ConvergedReference({StepCountSlow, StepCountFast}, nullptr, {1.0, 0.0}, 4, 1e-5, 2e-5, 1e-9);
  SplitProblem p;
  AdaptRun     run;
  PetscMPIInt  rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  p.terms = {StepCountSlow, StepCountFast};
  testing::internal::CaptureStderr();
  const PetscErrorCode ierr = SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_adapt_global_estimate -ts_rtol 1e-3 -ts_atol 1e-3", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, 4, &run);
  const std::string    err  = testing::internal::GetCapturedStderr();
  ASSERT_EQ(ierr, 0);
  const double error = std::abs(run.x[0] - ref) / (1e-3 * (1 + std::max(std::abs(ref), std::abs(run.x[0]))));
  EXPECT_GT(run.stats.global_estimate, error / 2) << "true error " << error;
  EXPECT_LT(run.stats.global_estimate, 2 * error) << "true error " << error;
  EXPECT_LT(run.stats.global_estimate_max, 2) << "true error at 4 " << error;
  if (rank == 0) EXPECT_EQ(err.find("-ts_vshmm_adapt_global_estimate"), std::string::npos) << err;
  AdaptRun plain; /* its estimate within 4 times the steps' sum: the option only measures, the run is the same */
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_warnings_viewer none", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, 4, &plain), 0);
  EXPECT_EQ(plain.x[0], run.x[0]);
  EXPECT_EQ(plain.evaluations, run.evaluations);
}

// The errors' coherence, once measured significant, stands. x' = -y + sin 3t, y' = -(y - cos(t) sin
// x) / 1e-3 from (1, 0), DeltaT = 0.1, x observed, at 1e-2 to t = 8.8: the signed sum of the steps'
// estimates grew like k^0.94 to t = 3.3 (gamma 0.94, each step's share 0.013 of the tolerance),
// then passed through 0 with x's oscillation (t = 5.1, 7.5), where gamma read 1/2 and the shares
// rose to 0.1; the error added up again from t = 6.8 on, and x(8.8) ended 2.2 tol off, silently.
// Kept (a gamma measured after at least 8 steps, with the signed sum at least twice a random
// walk's): 0.46 tol. A chaotic fast level's noise never reads significant
// (AChaoticFastLevelDoesNotRefineBelowItsFloor).
TEST(VSHMMAdapt, TheErrorsCoherenceOnceSignificantStands)
{
  constexpr double T = 8.8, tol = 1e-2;
  const double     ref = ConvergedReference({StepCountSlow, StepCountFast}, nullptr, {1.0, 0.0}, T, 1e-5, 2e-5, 1e-9);
  SplitProblem     p;
  AdaptRun         run;
  p.terms = {StepCountSlow, StepCountFast};
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-2 -ts_atol 1e-2", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, T, &run), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << "x(8.8) = " << run.x[0] << ", reference " << ref;
}

// A fast limit cycle whose amplitude the slow variable sets (van der Pol with Hopf parameter x):
// x' = 1 - x q^2 (slow {x}), q' = p / eps, p' = (-q + (x - q^2) p) / eps (fast {q, p}), eps = 1e-3,
// from (0.2, 0.5, 0) to t = 2 at 1e-1 (docs/accuracy.md section 25). Its Jacobian changes with the
// phase (the trace (x - q^2) / eps changes sign along the cycle): at one state its amplitude seemed
// to decay slowly (rate 8: separation lost, savings dropped for the rest of the run), at another
// the level seemed not to oscillate; and the micro step was bound by an amplitude error summed over
// the whole run, which the cycle restores at about x / eps. 110,992 evaluations with the estimates
// before; now 3,556 (without the restoring rate 19,316; judged at one phase 13,012; its own slowest
// rate at one phase at the spectra 6,400, at a try's end 6,652; the four phases at the level's
// radius, not the mean frequency, 11,848). A plain RK4 takes 8,000 full evaluations for 0.11 tol.
void CycleSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 1 - x[0] * x[1] * x[1];
  f[1] = f[2] = 0;
}
void CycleFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = x[2] / 1e-3;
  f[2] = (-x[1] + (x[0] - x[1] * x[1]) * x[2]) / 1e-3;
}

TEST(VSHMMAdapt, AFastLimitCycleIsJudgedOverItsPhases)
{
  const double ref = ConvergedReference({CycleSlow, CycleFast}, nullptr, {0.2, 0.5, 0.0}, 2, 1e-5, 5e-6, 1e-9);
  SplitProblem p;
  AdaptRun     run;
  p.terms = {CycleSlow, CycleFast};
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-1 -ts_atol 1e-1", p, {0.2, 0.5, 0.0}, {"slow", "fast"}, 0.1, 2, &run), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), 1e-1 * (1 + std::abs(ref))) << "x(2) = " << run.x[0] << ", reference " << ref;
  EXPECT_LT(run.evaluations + run.stats.adapt_evaluations, 5000) << "x(2) = " << run.x[0];
}

// Two fast rotations 10 apart whose beat drives a slow variable: x' = -x + q1 q2 (slow {x}), q1' = p1
// / eps, p1' = -q1 / eps, q2' = w p2 / eps, p2' = -w q2 / eps (fast), w = 1 + 10 eps, eps = 1e-3,
// from (0, 1, 0, 1, 0) to t = 2 at 1e-1. q1 q2 holds cos(10 t), a slow process inside the fast
// level that savings slow with it; frozen, it drove x to 0.37 (x(2) = 0.046: 3 tolerances off,
// estimate 1.06 tol, silently). LevelBeats() finds the beat in the fast split's own modes
// and its effect on x; the savings then keep it turning once per macro step (none here): x(2)
// within 1 tol of RK4 references (0.06 tol), with component and additive splits.
void BeatSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] * x[3];
  f[1] = f[2] = f[3] = f[4] = 0;
}
void BeatFast(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const double eps = 1e-3, w = 1 + (params ? *(const double *)params : 10.0) * eps; /* the beat: 10, or as given */
  f[0] = 0;
  f[1] = x[2] / eps;
  f[2] = -x[1] / eps;
  f[3] = w * x[4] / eps;
  f[4] = -w * x[3] / eps;
}

void BeatAffineSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] - x[3];
  f[1] = f[2] = f[3] = f[4] = 0;
}

TEST(VSHMMAdapt, ABeatOfTwoFastRotationsIsASlowProcess)
{
  const double ref = ConvergedReference({BeatSlow, BeatFast}, nullptr, {0.0, 1.0, 0.0, 1.0, 0.0}, 2, 1e-5, 5e-6, 1e-9);
  for (const SplitKind kind : {SplitKind::Component, SplitKind::Additive}) {
    SplitProblem p;
    AdaptRun     run;
    p.terms = {BeatSlow, BeatFast};
    ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-1 -ts_atol 1e-1", p, {0.0, 1.0, 0.0, 1.0, 0.0}, {"slow", "fast"}, 0.1, 2, &run, kind), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), 1e-1 * (1 + std::abs(ref))) << (kind == SplitKind::Additive ? "additive" : "component") << " splits: x(2) = " << run.x[0] << ", reference " << ref;
  }
}

// Three fast rotations in a triad resonance: x' = -x + 4 q1 q2 q3 (slow {x}), (q_i, p_i)' = w_i (p_i,
// -q_i) / eps (fast), w = (1, 1.5, 2.5 - 10 eps), eps = 1e-3, from (0, 1, 0, 1, 0, 1, 0) to t = 2
// at 1e-1: q1 q2 q3 holds cos(10 t), a slow combination w1 + w2 - w3 that no pair of the rotations
// shows as a beat (their differences, 500 and more, are as fast as they are). Before triads were
// probed x(2) was 5.8 tol off at 1e-1 and 39 at 1e-2, silently (docs/accuracy.md section 26); and
// the same for a rotation and one at about twice its frequency (x' = -x + 4 q1^2 q2, w = (1, 2 -
// 10 eps)): x(2) within the tolerance of RK4 references.
void TriadSlow(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const bool twice = params && *(const double *)params > 0;
  f[0]             = -x[0] + 4 * (twice ? x[1] * x[1] * x[3] : x[1] * x[3] * x[5]);
  f[1] = f[2] = f[3] = f[4] = f[5] = f[6] = 0;
}
void TriadFast(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const bool   twice = params && *(const double *)params > 0;
  const double eps = 1e-3, w[3] = {1, twice ? 2 - 10 * eps : 1.5, twice ? 3.7 : 2.5 - 10 * eps}; /* (the third rotation of the 2:1 case is a bystander) */
  f[0] = 0;
  for (int i = 0; i < 3; ++i) {
    f[1 + 2 * i] = w[i] * x[2 + 2 * i] / eps;
    f[2 + 2 * i] = -w[i] * x[1 + 2 * i] / eps;
  }
}

TEST(VSHMMAdapt, AThreeRotationTriadIsASlowProcess)
{
  for (const double twice : {0.0, 1.0}) {
    const double ref = ConvergedReference({TriadSlow, TriadFast}, &twice, {0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0}, 2, 2e-6, 1e-6, 1e-8);
    SplitProblem p;
    AdaptRun     run;
    p.terms  = {TriadSlow, TriadFast};
    p.params = &twice;
    ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-1 -ts_atol 1e-1", p, {0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0}, {"slow", "fast"}, 0.1, 2, &run), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), 1e-1 * (1 + std::abs(ref))) << (twice ? "2:1" : "triad") << ": x(2) = " << run.x[0] << ", reference " << ref;
  }
}

// Four fast rotations in a quartet resonance: x' = -x + 8 q1 q2 q3 q4 (slow {x}), (q_i, p_i)' = w_i
// (p_i, -q_i) / eps (fast), w = (1, 1.5, 2.35, 2.85 - 10 eps), eps = 1e-3, from (0, 1, 0, ...) to t =
// 2: the product holds cos(10 t), a slow combination w1 - w2 - w3 + w4 that no pair or triad of the
// rotations shows (the slowest of those, 2 w1 - w2 and 2 w3 - w2 - w4, are 500 and 2,650). Before
// combinations of four were probed x(2) was 4.1 tol off at 1e-1, silently (docs/accuracy.md section
// 34); and the same for a rotation and one at about three times its frequency (x' = -x + 8 q1^3 q2,
// w = (1, 3 - 10 eps): 3 w1 - w2). With -ts_vshmm_adapt x(2) is within the tolerance of RK4
// references; with fixed savings (micro step 2e-5, savings factor 99) the separation check says so.
void QuartetSlow(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const bool thrice = params && *(const double *)params > 0;
  f[0]              = -x[0] + 8 * (thrice ? x[1] * x[1] * x[1] * x[3] : x[1] * x[3] * x[5] * x[7]);
  for (int i = 1; i < 9; ++i) f[i] = 0;
}
void QuartetFast(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const bool   thrice = params && *(const double *)params > 0;
  const double eps = 1e-3, w[4] = {1, thrice ? 3 - 10 * eps : 1.5, thrice ? 4.4 : 2.35, thrice ? 5.3 : 2.85 - 10 * eps}; /* (the last two rotations of the 3:1 case are bystanders) */
  f[0] = 0;
  for (int i = 0; i < 4; ++i) {
    f[1 + 2 * i] = w[i] * x[2 + 2 * i] / eps;
    f[2 + 2 * i] = -w[i] * x[1 + 2 * i] / eps;
  }
}

TEST(VSHMMAdapt, AFourRotationQuartetIsASlowProcess)
{
  const std::vector<double> x0 = {0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0};
  for (const double thrice : {0.0, 1.0}) {
    const double ref = ConvergedReference({QuartetSlow, QuartetFast}, &thrice, x0, 2, 2e-6, 1e-6, 1e-8);
    SplitProblem p;
    AdaptRun     run;
    p.terms  = {QuartetSlow, QuartetFast};
    p.params = &thrice;
    ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-1 -ts_atol 1e-1", p, x0, {"slow", "fast"}, 0.1, 2, &run), 0);
    EXPECT_LE(std::abs(run.x[0] - ref), 1e-1 * (1 + std::abs(ref))) << (thrice ? "3:1" : "quartet") << ": x(2) = " << run.x[0] << ", reference " << ref;
    SplitProblem        q;
    AdaptRun            fixed;
    const CapturedError e = CaptureError([&] {
      q.terms  = {QuartetSlow, QuartetFast};
      q.params = &thrice;
      return SolveObservingX0("-ts_vshmm_micro_dt 2e-5 -ts_vshmm_savings_factors 99 -ts_vshmm_check_separation error", q, x0, {"slow", "fast"}, 0.1, 2, &fixed);
    });
    EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP) << (thrice ? "3:1" : "quartet");
    EXPECT_NE(e.message.find("beat at frequency 10"), std::string::npos) << e.message;
  }
}

// A beat that slows down through the run: x' = -x + q1 q2, tau' = 1 (slow {x, tau}), (q1, p1)' = (p1,
// -q1) / eps, (q2, p2)' = w (p2, -q2) / eps with w = 1 + 0.5 (1 - tau / 1.5) (fast), eps = 1e-3,
// from (0, 0, 1, 0, 1, 0): the beat (w - 1) / eps falls from 500 at t = 0 to 100 at t = 1.2, where
// it becomes a slow process, and to 0 at 1.5. The spectra of a run at 1e-2 were estimated at t =
// 0, 0.1 and 1 (no beat yet) and then at 1.6: the beat was found after the passage, and at 1e-3,
// with spectra at 0, 0.1 and 1 only, never (5.9 tol off, silently: docs/accuracy.md section 34).
// Now the falling difference of the frequencies is watched and the spectra estimated again before
// it would become a beat: by t = 1.3 the run says that the beat was found during the run, after
// savings (its relative phase, which the answer after the passage depends on, is then lost).
void PassSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[2] * x[4];
  f[1] = 1;
  f[2] = f[3] = f[4] = f[5] = 0;
}
void PassFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const double eps = 1e-3, w = 1 + 0.5 * (1 - x[1] / 1.5);
  f[0] = f[1] = 0;
  f[2]        = x[3] / eps;
  f[3]        = -x[2] / eps;
  f[4]        = w * x[5] / eps;
  f[5]        = -w * x[4] / eps;
}

TEST(VSHMMAdapt, ABeatReachedDuringTheRunIsFoundBeforeItsPassage)
{
  for (const char *tol : {"1e-2", "1e-3"}) {
    SplitProblem p;
    AdaptRun     run;
    std::string  said;
    p.terms      = {PassSlow, PassFast};
    p.components = {{0, 1}, {2, 3, 4, 5}};
    ASSERT_EQ(SolveObservingX0Saying(std::string("-ts_vshmm_adapt -ts_rtol ") + tol + " -ts_atol " + tol, p, {0.0, 0.0, 1.0, 0.0, 1.0, 0.0}, 0.1, 1.3, &run, &said), 0);
    EXPECT_NE(said.find("beat at frequency"), std::string::npos) << tol << ": " << said;
    EXPECT_NE(said.find("found during the run, after macro steps whose savings slowed level 1"), std::string::npos) << tol << ": " << said;
  }
}

// The same beat in the medium level of three: x' = -x + u1 u2 (slow), (u1, v1)' = (v1, -u1) / 1e-3,
// (u2, v2)' = 1.01 (v2, -u2) / 1e-3 (medium), w' = -(w - u1) / 1e-5 (fast, decaying), additive
// splits, from (0, 1, 0, 1, 0, 0) to t = 2 at 1e-2: x(2) within the tolerance of RK4 references.
// The savings r_0 slow the medium level and its beat; the beats of every faster level are probed.
void MediumBeatSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + x[1] * x[3];
  f[1] = f[2] = f[3] = f[4] = f[5] = 0;
}
void MediumBeatMedium(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  const double eps = 1e-3, w = 1 + 10 * eps;
  f[0] = f[5] = 0;
  f[1]        = x[2] / eps;
  f[2]        = -x[1] / eps;
  f[3]        = w * x[4] / eps;
  f[4]        = -w * x[3] / eps;
}
void MediumBeatFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = f[2] = f[3] = f[4] = 0;
  f[5]                             = -(x[5] - x[1]) / 1e-5;
}
PetscErrorCode MediumBeatX0(TS, PetscReal, Vec X, PetscReal q[], void *ctx)
{
  std::vector<PetscReal> x;
  PetscCall(GatherState((SplitProblem *)ctx, X, x));
  q[0] = x[0];
  return 0;
}

TEST(VSHMMAdapt, ABeatInAMediumLevelIsASlowProcess)
{
  const double ref = ConvergedReference({MediumBeatSlow, MediumBeatMedium, MediumBeatFast}, nullptr, {0.0, 1.0, 0.0, 1.0, 0.0, 0.0}, 2, 5e-6, 2.5e-6, 1e-9);
  SplitProblem p;
  AdaptRun     run;
  p.terms = {MediumBeatSlow, MediumBeatMedium, MediumBeatFast};
  ASSERT_EQ(SolveObserving("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-2 -ts_atol 1e-2", p, {0.0, 1.0, 0.0, 1.0, 0.0, 0.0}, {"slow", "medium", "fast"}, 0.1, 2, &run, SplitKind::Additive, 1, MediumBeatX0, &p), 0);
  EXPECT_LE(std::abs(run.x[0] - ref), 1e-2 * (1 + std::abs(ref))) << "x(2) = " << run.x[0] << ", reference " << ref;
}

// The same with fixed savings (savings factor 99, micro step 2e-5, to t = 2: x(2) 0.43 for 0.046): the
// separation check says that the savings freeze the beat, an error with -ts_vshmm_check_separation
// error; with rotations at equal frequencies (no beat) or 1000 apart (as fast as they are: no beat)
// it says nothing.
TEST(VSHMMAdapt, FixedSavingsThatFreezeABeatAreSaid)
{
  for (const double a : {10.0, 0.0, 1000.0}) {
    SplitProblem        p;
    AdaptRun            run;
    const CapturedError e = CaptureError([&] {
      p.terms  = {BeatSlow, BeatFast};
      p.params = &a;
      return SolveObservingX0("-ts_vshmm_micro_dt 2e-5 -ts_vshmm_savings_factors 99 -ts_vshmm_check_separation error", p, {0.0, 1.0, 0.0, 1.0, 0.0}, {"slow", "fast"}, 0.1, 2, &run);
    });
    if (a == 10.0) {
      EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
      EXPECT_NE(e.message.find("beat at frequency 10"), std::string::npos) << e.message;
    } else EXPECT_EQ(e.code, 0) << "a = " << a << ": " << e.message;
  }
  /* a slower field affine in the rotations (x' = -x + q1 - q2) holds no product to beat: not probed
     (3 evaluations of its second difference, not the 36 of the probe) */
  std::vector<PetscInt64> stability;
  for (const SplitProblem::Term slow : {BeatSlow, BeatAffineSlow}) {
    SplitProblem p;
    AdaptRun     run;
    p.terms = {slow, BeatFast};
    ASSERT_EQ(SolveObservingX0("-ts_vshmm_micro_dt 2e-5 -ts_vshmm_savings_factors 99 -ts_vshmm_warnings_viewer none", p, {0.0, 1.0, 0.0, 1.0, 0.0}, {"slow", "fast"}, 0.1, 0.2, &run), 0);
    stability.push_back(run.stats.stability_evaluations);
  }
  EXPECT_GE(stability[0] - stability[1], 30) << "probed " << stability[0] << ", affine " << stability[1];
}

// TSVSHMMSetObservables() on a TS that is not a TSVSHMM yet (a program that names its quantities of
// interest and takes the type from -ts_type vshmm, set after the call): the quantities are kept for
// the TSVSHMM the TS becomes, the same run as with the type set first. Before, the setter did
// nothing on another type (as the method parameters' setters, PETSc's way) and the tolerance
// applied to the whole state, silently. Cleared (f = NULL) before the type, they stay cleared.
struct CountedXi {
  SplitProblem *p     = nullptr;
  int           calls = 0;
};
PetscErrorCode CountingXiObservable(TS ts, PetscReal t, Vec X, PetscReal q[], void *ctx)
{
  PetscFunctionBeginUser;
  ((CountedXi *)ctx)->calls++;
  PetscCall(XiObservable(ts, t, X, q, ((CountedXi *)ctx)->p));
  PetscFunctionReturn(0);
}
PetscErrorCode SolveObservablesSetAround(int when, std::vector<PetscReal> &xout, int *calls)
{
  Guard             guard("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2");
  DissipativeParams params;
  SplitProblem      p;
  CountedXi         counted;
  TS                ts;
  Vec               x;

  PetscFunctionBeginUser;
  DissipativeProblem(&p, &params);
  counted.p = &p;
  PetscCall(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {5, -10, 5}, {"slow", "medium", "fast"}, &ts, &x));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, 0.3));
  if (when == 0) { /* before the type: set on a TSRK */
    PetscCall(TSSetType(ts, TSRK));
    PetscCall(TSVSHMMSetObservables(ts, 1, CountingXiObservable, &counted));
    PetscCall(TSSetType(ts, TSVSHMM));
  } else if (when == 1) PetscCall(TSVSHMMSetObservables(ts, 1, CountingXiObservable, &counted)); /* on the TSVSHMM */
  else { /* set, then cleared, before the type */ PetscCall(TSSetType(ts, TSRK));
    PetscCall(TSVSHMMSetObservables(ts, 1, CountingXiObservable, &counted));
    PetscCall(TSVSHMMSetObservables(ts, 0, nullptr, nullptr));
    PetscCall(TSSetType(ts, TSVSHMM));
  }
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, x));
  PetscCall(GatherState(&p, x, xout));
  *calls = counted.calls;
  PetscCall(DestroySplitTS(&p, &ts, &x));
  PetscFunctionReturn(0);
}

TEST(VSHMMAdapt, ObservablesSetBeforeTheTypeAreKept)
{
  std::vector<PetscReal> before, on, cleared;
  int                    calls_before = 0, calls_on = 0, calls_cleared = 0;
  ASSERT_EQ(SolveObservablesSetAround(0, before, &calls_before), 0);
  ASSERT_EQ(SolveObservablesSetAround(1, on, &calls_on), 0);
  ASSERT_EQ(SolveObservablesSetAround(2, cleared, &calls_cleared), 0);
  EXPECT_GT(calls_on, 0);
  EXPECT_EQ(calls_before, calls_on);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(before[i], on[i]) << "component " << i;
  EXPECT_EQ(calls_cleared, 0);
}

// Savings factors the user set stay as set under -ts_vshmm_adapt, also where a try with them blows
// up: the dissipative example with -ts_vshmm_savings_factors 1e6,1e6 (a mean cycle of 200 at the
// micro step 1e-4, far beyond the sampling interval 0.1). Its second macro step's tries ended with
// the fastest rate grown 1.3e5 times; the try after that was taken with time ratios brought down
// to 1 (the savings that keep a level whose rate fell relaxing) but the micro step made for the
// user's savings at that grown rate, 1e-9: 1e8 micro cycles a try, a run without end. Now the
// ratios stay, the micro step alone is refined, and the run ends (warned: the estimate stays above
// its share with these savings). With the fault back the test does not end (CTest's timeout).
TEST(VSHMMAdapt, SavingsFactorsTheUserSetStayAsSetWhereATryBlowsUp)
{
  AdaptRun run;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_savings_factors 1e6,1e6 -ts_vshmm_warnings_viewer none", 0.3, &run), 0);
  ASSERT_EQ(run.savings.size(), 2u);
  EXPECT_EQ(run.savings[0], 1e6);
  EXPECT_EQ(run.savings[1], 1e6);
  EXPECT_LT(run.stats.adapt_evaluations, 1000000);
}

// A micro step the user set beyond the fastest level's stable step is an error at set-up under
// -ts_vshmm_adapt as without it: no savings can make it stable (the dissipative example with
// -ts_vshmm_micro_dt 1e-2 tried twelve times, accepted a step with an infinite estimate and
// stopped with NaN blamed on the slow split). 1e-4, within the step 3.06e-4, runs.
TEST(VSHMMAdapt, AMicroStepTheUserSetBeyondTheStableStepIsAnErrorAtSetUp)
{
  AdaptRun            run;
  const CapturedError e = CaptureError([&] { return SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_micro_dt 1e-2 -ts_vshmm_warnings_viewer none", 0.2, &run, true); });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_OUTOFRANGE);
  EXPECT_NE(e.message.find("-ts_vshmm_micro_dt"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("needs dt <= 0.000306"), std::string::npos) << e.message;
  EXPECT_EQ(run.evaluations, 0);
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_warnings_viewer none", 0.2, &run, true), 0);
  EXPECT_EQ(run.micro_dt, 1e-4);
}

// A final time inside a macro step with -ts_exact_final_time interpolate: x' = -y + sin 9t (slow
// {x}), y' = -(y - cos(t) sin x) / 1e-3 (fast {y}) from (1, 0) to t = 1.05, DeltaT = 0.1, at 1e-3.
// The state at 1.05 is sampled by a macro step of 0.05 from the one at 1.0: x(1.05) within 1 tol
// of RK4 references (0.43 tol, as with matchstep). The linear interpolant of the samples at 1.0 and
// 1.1, before, ended 6.8 tol off, silently.
void NineSlow(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[1] + std::sin(9 * t);
  f[1] = 0;
}

TEST(VSHMMAdapt, AFinalTimeInsideAMacroStepIsSampled)
{
  const double ref = ConvergedReference({NineSlow, StepCountFast}, nullptr, {1.0, 0.0}, 1.05, 1e-5, 2e-5, 1e-9);
  SplitProblem p;
  AdaptRun     interp, match;
  p.terms = {NineSlow, StepCountFast};
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3 -ts_exact_final_time interpolate", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, 1.05, &interp), 0);
  EXPECT_LE(std::abs(interp.x[0] - ref), 1e-3 * (1 + std::abs(ref))) << "x(1.05) = " << interp.x[0] << ", reference " << ref;
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3 -ts_exact_final_time matchstep", p, {1.0, 0.0}, {"slow", "fast"}, 0.1, 1.05, &match), 0);
  EXPECT_LE(std::abs(match.x[0] - ref), 1e-3 * (1 + std::abs(ref))) << "x(1.05) = " << match.x[0] << ", reference " << ref;
}

// A second solve from the start (an ensemble member: TSSetTime(), TSSetStepNumber() and the initial
// state again, then TSSolve()): a new run, checked and started as at set-up, the same answer, work
// and estimate as the first. Before, the accuracy control kept the first run's state: the second
// solve of x' = -y + sin 3t, y' = -(y - cos(t) sin x) / 1e-3 at 1e-3 ended elsewhere (x(1) 3.1e-4
// from the first), and its error estimate was the sum of both runs.
TEST(VSHMMAdapt, ASecondSolveFromTheStartIsANewRun)
{
  SplitProblem           p;
  TS                     ts;
  Vec                    x;
  Guard                  guard("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3");
  std::vector<PetscReal> first, second;
  TSVSHMMStatistics      s1, s2;
  p.terms = {StepCountSlow, StepCountFast};
  p.n     = 2;
  ASSERT_EQ(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Component, {1.0, 0.0}, {"slow", "fast"}, &ts, &x), 0);
  ASSERT_EQ(TSSetTimeStep(ts, 0.1), 0);
  ASSERT_EQ(TSSetMaxTime(ts, 1), 0);
  ASSERT_EQ(TSVSHMMSetObservables(ts, 1, X0Observable, &p), 0);
  ASSERT_EQ(TSSetFromOptions(ts), 0);
  ASSERT_EQ(TSSolve(ts, x), 0);
  ASSERT_EQ(GatherState(&p, x, first), 0);
  ASSERT_EQ(TSVSHMMGetStatistics(ts, &s1), 0);
  const PetscInt64 work1  = std::accumulate(s1.rhs_evaluations, s1.rhs_evaluations + s1.nsplits, (PetscInt64)0) + s1.adapt_evaluations;
  const PetscReal  total1 = s1.error_estimate_total;
  ASSERT_EQ(TSSetTime(ts, 0), 0);
  ASSERT_EQ(TSSetStepNumber(ts, 0), 0);
  ASSERT_EQ(TSSetTimeStep(ts, 0.1), 0);
  {
    PetscInt     lo, hi;
    PetscScalar *a;
    ASSERT_EQ(VecGetOwnershipRange(x, &lo, &hi), 0);
    ASSERT_EQ(VecGetArray(x, &a), 0);
    for (PetscInt i = lo; i < hi; ++i) a[i - lo] = i == 0 ? 1.0 : 0.0;
    ASSERT_EQ(VecRestoreArray(x, &a), 0);
  }
  ASSERT_EQ(TSSolve(ts, x), 0);
  ASSERT_EQ(GatherState(&p, x, second), 0);
  ASSERT_EQ(TSVSHMMGetStatistics(ts, &s2), 0);
  const PetscInt64 work2 = std::accumulate(s2.rhs_evaluations, s2.rhs_evaluations + s2.nsplits, (PetscInt64)0) + s2.adapt_evaluations;
  EXPECT_EQ(first, second);
  EXPECT_EQ(work2, 2 * work1); /* the statistics count both solves, the second as much as the first */
  EXPECT_EQ(s2.error_estimate_total, total1);
  ASSERT_EQ(DestroySplitTS(&p, &ts, &x), 0);
}

// A vector atol (TSSetTolerances()) weighs the slow components per component beside the
// observables, which take the scalars: atol 1e-1 for the observable x, 1e-3 on the slow
// components, rtol 1e-3. Before, the slow components took the scalar atol too (x(4) then within
// the loose one only).
TEST(VSHMMAdapt, AVectorAtolWeighsTheSlowComponents)
{
  const double ref = SlowOscillatorReference(1e-5);
  PetscReal    x0, loose;
  PetscBool    slow;
  std::string  view;
  ASSERT_EQ(SolveSlowOscillator("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-1 -ts_vshmm_warnings_viewer none", &loose, &slow, &view), 0);
  gSlowVectorAtol = 1e-3;
  ASSERT_EQ(SolveSlowOscillator("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-1 -ts_vshmm_warnings_viewer none", &x0, &slow, &view), 0);
  gSlowVectorAtol = 0;
  EXPECT_LE(std::abs(x0 - ref), 2e-3 * (1 + std::abs(ref))) << "x(4) = " << x0 << ", reference " << ref << " (scalar atol: " << loose << ")";
  EXPECT_GT(std::abs(loose - ref), 5 * std::abs(x0 - ref)) << "x(4) = " << x0 << ", with the scalar atol " << loose << ", reference " << ref;
  EXPECT_NE(view.find("atol per component (a vector) on the slow components"), std::string::npos) << view;
}

// Without adapt nothing changes: no estimate, no extra work.
TEST(VSHMMAdapt, OffByDefault)
{
  AdaptRun run;
  ASSERT_EQ(SolveDissipativeAdapt("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10", 0.5, &run), 0);
  EXPECT_EQ(run.stats.error_estimate_total, 0.0);
  EXPECT_EQ(run.stats.adapt_evaluations, 0);
  EXPECT_EQ(run.stats.adapt_calibrations, 0);
}

TEST(VSHMMSeparation, UnseparatedScalesAreAnErrorOnRequest)
{
  std::vector<PetscReal> x, savings;
  const CapturedError    e = CaptureError([&] { return SolveWeak("-ts_vshmm_check_separation error", &x, &savings); });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("not separated"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("levels 0/1: 2"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("-ts_type rk"), std::string::npos) << e.message;
}

// Separations the application sets replace the spectral radii's: the paper's problem told that its
// scales are only 3 apart is taken at its word (and told 1e3, 1e3, passes).
TEST(VSHMMSeparation, SetSeparationsAreChecked)
{
  AdaptRun      run;
  CapturedError e = CaptureError([&] { return SolveDissipativeAdapt("-ts_vshmm_check_separation error -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10 -ts_vshmm_scale_separations 3,3", 0.2, &run); });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("not separated (separation of consecutive levels, at least 10"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("levels 0/1: 3 (set with -ts_vshmm_scale_separations); levels 1/2: 3 (set"), std::string::npos) << e.message;
  EXPECT_EQ(SolveDissipativeAdapt("-ts_vshmm_check_separation error -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10 -ts_vshmm_scale_separations 1e3,1e3", 0.2, &run), 0);
  PetscInt         n;
  const PetscReal *S;
  TS               ts;
  ASSERT_EQ(TSCreate(PETSC_COMM_WORLD, &ts), 0);
  ASSERT_EQ(TSSetType(ts, TSVSHMM), 0);
  const PetscReal set[] = {12, 340};
  ASSERT_EQ(TSVSHMMSetScaleSeparations(ts, 2, set), 0);
  ASSERT_EQ(TSVSHMMGetScaleSeparations(ts, &n, &S), 0);
  ASSERT_EQ(n, 2);
  EXPECT_EQ(S[0], 12);
  EXPECT_EQ(S[1], 340);
  ASSERT_EQ(TSDestroy(&ts), 0);
}

// The paper's problem is separated: the same setting raises nothing.
TEST(VSHMMSeparation, PaperProblemPasses)
{
  AdaptRun run;
  EXPECT_EQ(SolveDissipativeAdapt("-ts_vshmm_check_separation error -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10", 0.2, &run), 0);
}

// With adapt, unseparated scales get no savings (every level steps with the micro step) and the
// answer is the single-rate one: x(1) of x' = -x + y, y' = x - 2y from (1, 0).
TEST(VSHMMSeparation, AdaptTakesNoSavingsWithoutSeparation)
{
  std::vector<PetscReal> x, savings;
  ASSERT_EQ(SolveWeak("-ts_vshmm_adapt -ts_rtol 1e-4 -ts_atol 1e-4 -ts_vshmm_check_separation off", &x, &savings), 0);
  ASSERT_EQ(savings.size(), 1u);
  EXPECT_EQ(savings[0], 0.0);
  // exact: eigenvalues (-3 +- sqrt 5)/2
  const double l1 = (-3 + std::sqrt(5.0)) / 2, l2 = (-3 - std::sqrt(5.0)) / 2;
  const double v1 = 1 + l1, v2 = 1 + l2;                  // y/x of each eigenvector: x' = -x + y -> y = (l + 1) x
  const double c1 = -v2 / (v1 - v2), c2 = v1 / (v1 - v2); // c1 + c2 = 1, c1 v1 + c2 v2 = 0
  const double exact = c1 * std::exp(l1) + c2 * std::exp(l2);
  EXPECT_NEAR(x[0], exact, 2e-4 * (1 + std::abs(exact)));
}

// An unstable slow equation (a saddle) driven by a slaved fast variable: x' = a (x - 1) + z / 2
// (slow), z' = -(z - cos x) / 1e-3 (fast), from x = 0.59 next to the equilibrium x* = 0.582 of the
// slow manifold (a = 1: errors grow as e^(0.72 t)) to t = 4, x observed. Each macro step's estimate
// kept within its share, the early errors grew ~14 times by t = 4: 3.1 and 6.7 tol at 5e-4 and
// 1e-4, silently (docs/accuracy.md section 35). The growth probe measures the rate (0.72: the
// probe's smallest growth, within 15%) and shrinks the later shares: x(4) within 2 tol at both
// tolerances (and with additive splits at 5e-4), and the statistics name the rate. With a = 2 (errors grow e^(1.7 t) near x* = 0.811;
// from 0.81 x runs away to -32.45) the first macro steps' errors, made before the rate was known,
// grow beyond the tolerance (5.6 tol at 1e-3): said at the end of the solve.
void SaddleSlow(const void *params, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = *(const double *)params * (x[0] - 1) + 0.5 * x[1];
  f[1] = 0;
}
void SaddleFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - std::cos(x[0])) / 1e-3;
}

TEST(VSHMMAdapt, AnUnstableSlowEquationShrinksTheLaterShares)
{
  const double              a   = 1;
  const std::vector<double> x0  = {0.59, std::cos(0.59)};
  const double              ref = ConvergedReference({SaddleSlow, SaddleFast}, &a, x0, 4, 1e-5, 5e-6, 1e-9);
  for (const char *tol : {"5e-4", "1e-4", "5e-4 additive"}) {
    SplitProblem      p;
    AdaptRun          run;
    const std::string options  = std::string("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol ") + std::string(tol).substr(0, 4) + " -ts_atol " + std::string(tol).substr(0, 4);
    const bool        additive = std::string(tol).find("additive") != std::string::npos; /* every split writes both components: the first probed step settles the perturbation */
    p.terms                    = {SaddleSlow, SaddleFast};
    p.params                   = &a;
    ASSERT_EQ(SolveObservingX0(options.c_str(), p, x0, {"slow", "fast"}, 0.1, 4, &run, additive ? SplitKind::Additive : SplitKind::Component), 0);
    const double t = std::atof(tol);
    EXPECT_LE(std::abs(run.x[0] - ref), 2 * t * (1 + std::abs(ref))) << tol << ": x(4) = " << run.x[0] << ", reference " << ref;
    EXPECT_GE(run.stats.adapt_growth_probes, 1) << tol;
    EXPECT_NEAR(run.stats.adapt_growth_rate, 0.72, 0.11) << tol;
  }
}

// A switch in the fast level inside a steady step: z' = -1000 (z - cos y - 3 H(t - 2.47)), y' = -y + z
// from (1, 0.5), DeltaT = 0.1. The steps before it sit at their bounds far below their shares, so
// the step [2.4, 2.5] was left uncompared (the model's prediction stood in): the savings slowed the
// fast variable's jump to its new equilibrium, the lag went into y unmeasured, and y(2.5) ended 2.9
// tol off at 1e-2, silently. The field at a steady step's end may not jump by more than 4x from the
// last step's end (here 25x): the step is compared and refined (docs/accuracy.md section 37).
void JumpFast(const void *, PetscReal t, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -1000 * (x[1] - std::cos(x[0]) - (t >= 2.47 ? 3.0 : 0.0));
}

TEST(VSHMMAdapt, ASwitchInsideASteadyStepIsCompared)
{
  const double tol = 1e-2, T = 2.5;
  const double ref = ConvergedReference({RelaxSlow, JumpFast}, nullptr, {1.0, 0.5}, T, 5e-6, 2.5e-6, 1e-5); /* first order at the jump: 1.2e-6 apart */
  SplitProblem p;
  AdaptRun     run;
  p.terms = {RelaxSlow, JumpFast};
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-2 -ts_atol 1e-2", p, {1.0, 0.5}, {"slow", "fast"}, 0.1, T, &run), 0);
  EXPECT_GE(run.stats.adapt_uncompared, 1); /* steady steps before the switch */
  EXPECT_LE(std::abs(run.x[0] - ref), tol * (1 + std::abs(ref))) << "y(2.5) = " << run.x[0] << ", reference " << ref;
}

// Where a probe has found the slow dynamics growing an error, a steady step's comparison is left
// out only after two estimates far below their shares (a tenth), not below half of them as
// elsewhere: each step's error grows with the solution. With half the saddle at 1e-3 ended at
// 1.80 tol, 27 of its 40 steps uncompared (1.09 tol now; docs/accuracy.md section 37).
TEST(VSHMMAdapt, AGrowingSlowEquationComparesItsSteps)
{
  const double              a = 1, tol = 1e-3;
  const std::vector<double> x0  = {0.59, std::cos(0.59)};
  const double              ref = ConvergedReference({SaddleSlow, SaddleFast}, &a, x0, 4, 1e-5, 5e-6, 1e-9);
  SplitProblem              p;
  AdaptRun                  run;
  p.terms  = {SaddleSlow, SaddleFast};
  p.params = &a;
  ASSERT_EQ(SolveObservingX0("-ts_vshmm_adapt -ts_vshmm_warnings_viewer none -ts_rtol 1e-3 -ts_atol 1e-3", p, x0, {"slow", "fast"}, 0.1, 4, &run), 0);
  EXPECT_GT(run.stats.adapt_growth_rate, 0);
  EXPECT_EQ(run.stats.adapt_uncompared, 2); /* [0.2, 0.3] before the first probe ended, [0.3, 0.4] after two estimates below 1% of their shares */
  EXPECT_LE(std::abs(run.x[0] - ref), 1.5 * tol * (1 + std::abs(ref))) << "x(4) = " << run.x[0] << ", reference " << ref;
}

TEST(VSHMMAdapt, ErrorsGrownBeforeTheGrowthWasMeasuredAreSaid)
{
  const double              a  = 2;
  const std::vector<double> x0 = {0.81, std::cos(0.81)};
  SplitProblem              p;
  AdaptRun                  run;
  std::string               said;
  p.terms  = {SaddleSlow, SaddleFast};
  p.params = &a;
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", p, x0, 0.1, 4, &run, &said), 0);
  EXPECT_NE(said.find("the slow dynamics grew the errors of the sampled values"), std::string::npos) << said;
  EXPECT_NE(said.find("the tolerance is not met"), std::string::npos) << said;
  EXPECT_GE(run.stats.adapt_growth_probes, 2) << said;                                          /* the growth found at the start, and probed again (x runs away: the error's relative growth stops later) */
  const double ref = ConvergedReference({SaddleSlow, SaddleFast}, &a, x0, 4, 1e-5, 5e-6, 1e-7); /* x runs away to -32.45: the warning is right */
  EXPECT_GT(std::abs(run.x[0] - ref), 2e-3 * (1 + std::abs(ref))) << "x(4) = " << run.x[0] << ", reference " << ref;
}

// A growth that the slowest split's own Jacobian (-1) does not show, made by the coupling: x' = -x +
// 2 z (slow), z' = -(z - x - 0.01) / 1e-3 (fast), from (0, 0.01): on the slow manifold x' = x +
// 0.02, errors grow as e^t, x(4) = 1.063. The savings' lag changes the growth rate itself (x' (1 +
// 2 eps r) = x + 0.02 on the sampled manifold), a bias of every step that the growth amplifies:
// 5.9 and 13 tol at 1e-2 and 1e-3, silently before the probe (3.6 and 12 now). The motion over a macro
// step doubles by t = 0.8: probed there (growth 1.05-1.08 per step), and the steps' estimates,
// each grown by the growth measured after it, add up to 1.5 and 4.8 tolerances: said, not met
// (docs/accuracy.md section 35).
void CoupledSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + 2 * x[1];
  f[1] = 0;
}
void CoupledFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -(x[1] - x[0] - 0.01) / 1e-3;
}

TEST(VSHMMAdapt, AGrowthTheSlowJacobianDoesNotShowIsProbed)
{
  const std::vector<double> x0  = {0.0, 0.01};
  const double              ref = ConvergedReference({CoupledSlow, CoupledFast}, nullptr, x0, 4, 1e-5, 5e-6, 1e-9);
  for (const char *tol : {"1e-2", "1e-3"}) {
    SplitProblem p;
    AdaptRun     run;
    std::string  said;
    p.terms = {CoupledSlow, CoupledFast};
    ASSERT_EQ(SolveObservingX0Saying(std::string("-ts_vshmm_adapt -ts_rtol ") + tol + " -ts_atol " + tol, p, x0, 0.1, 4, &run, &said), 0);
    EXPECT_GE(run.stats.adapt_growth_probes, 1) << tol;
    const double t = std::atof(tol), error = std::abs(run.x[0] - ref) / (t * (1 + std::abs(ref)));
    EXPECT_GT(error, 2) << tol; /* not met: the savings' lag changes the growth rate itself (by 2 eps (r - 1)), an error every step makes */
    EXPECT_NE(said.find("the slow dynamics grew the errors of the sampled values"), std::string::npos) << tol << ": " << error << " tol, " << said;
  }
}

// Kapitza's pendulum: a pivot vibrating fast, A cos(w t) with A = 0.002, w = 1000, the vibration an
// oscillator of the fast split (q' = -w p, p' = w q); the slow split theta' = v, v' = -(1 - A w^2 q)
// sin(theta). The inverted position is stable ((A w)^2 > 2): from theta = pi - 0.3 the pendulum turns
// about it (period about 6), theta observed. An error turned by that oscillation grows for a part of
// its turn (v carries the fast phase, and its weight differs from theta's) and shrinks later: a
// probe's factors 1.53, 2.27, 1.15 were taken as a rate e^(1.4 t), which shrank the later shares a
// hundredfold, and the steps' estimates, grown by it, were said to miss the tolerance at 0.15 tol.
// A rate is now taken from a steady growth only (the saddles above: within 3%); the uneven one is
// propagated until it is damped (factor 0.98) and is no growth (docs/accuracy.md section 36).
void KapitzaSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = x[1];
  f[1] = -(1 - 0.002 * 1e6 * x[2]) * std::sin(x[0]);
  f[2] = f[3] = 0;
}
void KapitzaFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = f[1] = 0;
  f[2]        = -1000 * x[3];
  f[3]        = 1000 * x[2];
}

TEST(VSHMMAdapt, AnOscillationThatTurnsAnErrorIsNoGrowth)
{
  const std::vector<double> x0  = {PETSC_PI - 0.3, 0, 1, 0};
  const double              ref = ConvergedReference({KapitzaSlow, KapitzaFast}, nullptr, x0, 4, 1e-5, 5e-6, 1e-7); /* 3.3714763 */
  SplitProblem              p;
  AdaptRun                  run;
  std::string               said;
  p.terms      = {KapitzaSlow, KapitzaFast};
  p.components = {{0, 1}, {2, 3}};
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", p, x0, 0.1, 4, &run, &said), 0);
  EXPECT_GE(run.stats.adapt_growth_probes, 1);
  EXPECT_EQ(run.stats.adapt_growth_rate, 0);
  EXPECT_EQ(said.find("the slow dynamics grew the errors"), std::string::npos) << said;
  EXPECT_LE(std::abs(run.x[0] - ref), 1e-3 * (1 + std::abs(ref))) << "theta(4) = " << run.x[0] << ", reference " << ref;
  /* to t = 1.3 the probe of t = 0.4 is the run's only one: its uneven growth (taken as e^(1.4 t) where
     any three growing steps gave a rate) is no rate */
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3", p, x0, 0.1, 1.3, &run, &said), 0);
  EXPECT_EQ(run.stats.adapt_growth_probes, 1);
  EXPECT_EQ(run.stats.adapt_growth_rate, 0);
}

// The same pendulum with savings set by the user: the vibration forces v 13.5 times as hard as the
// slow dynamics move it, and the swing it gives theta, in phase with the force, drifts the slow
// dynamics (Kapitza's effect: 0.56 of their size per unit time). Savings slow the vibration by r
// and multiply the drift by r^2: with savings factor 1 theta(4) = 3.00 (3.37 converged), with 10
// it spun round to -177, silently. Said at set-up now (an error on request); a fast force whose
// Jacobian does not turn with it (x' = -x + 5 q^2: forced 10 times as hard, no drift) is not.
void SquareForcedSlow(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = -x[0] + 5 * x[1] * x[1];
  f[1] = f[2] = 0;
}
void SquareForcedFast(const void *, PetscReal, const PetscScalar *x, PetscScalar *f)
{
  f[0] = 0;
  f[1] = -1000 * x[2];
  f[2] = 1000 * x[1];
}

TEST(VSHMMSeparation, AFastForceOnSlowComponentsIsSaid)
{
  const std::vector<double> x0 = {PETSC_PI - 0.3, 0, 1, 0};
  for (const char *savings : {"1", "0.2"}) {
    SplitProblem p;
    AdaptRun     run;
    std::string  said;
    p.terms      = {KapitzaSlow, KapitzaFast};
    p.components = {{0, 1}, {2, 3}};
    ASSERT_EQ(SolveObservingX0Saying(std::string("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors ") + savings, p, x0, 0.1, 1, &run, &said), 0);
    EXPECT_NE(said.find("forces level 0's components 13.5 times as hard as their own dynamics"), std::string::npos) << savings << ": " << said;
    EXPECT_NE(said.find("drifts them by 0.565 of their size per unit time"), std::string::npos) << savings << ": " << said;
  }
  SplitProblem  p;
  AdaptRun      run;
  CapturedError e;
  p.terms      = {KapitzaSlow, KapitzaFast};
  p.components = {{0, 1}, {2, 3}};
  e            = CaptureError([&] { return SolveObservingX0("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 10 -ts_vshmm_check_separation error", p, x0, {"slow", "fast"}, 0.1, 1, &run); });
  EXPECT_EQ(e.code, PETSC_ERR_ARG_INCOMP);
  EXPECT_NE(e.message.find("multiplies that drift by 121"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("-ts_type rk"), std::string::npos) << e.message;
  SplitProblem q;
  std::string  said;
  q.terms      = {SquareForcedSlow, SquareForcedFast};
  q.components = {{0}, {1, 2}};
  ASSERT_EQ(SolveObservingX0Saying("-ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100", q, {1, 1, 0}, 0.1, 1, &run, &said), 0);
  EXPECT_EQ(said.find("forces level 0's components"), std::string::npos) << said;
}
