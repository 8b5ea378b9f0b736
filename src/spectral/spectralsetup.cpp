/*
  VSHMMSpectralSetUp(): the coefficient fields on the grid, the clusters (explicit, or detected by
  soft thresholding of snapshots), the layout of the state, the FFTW plans and the dense operator.
*/
#include "spectralimpl.hpp"

#include "rkc.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

static constexpr double kNegativeDiffusionTolerance = 1e-12; /* d below -this times max |d| is negative (rounding of a field that touches 0 is not) */

static spc::Planner CorePlanner(VSHMMSpectralPlanner p)
{
  return p == VSHMMSPECTRAL_PLANNER_ESTIMATE ? spc::Planner::Estimate : p == VSHMMSPECTRAL_PLANNER_PATIENT ? spc::Planner::Patient : spc::Planner::Measure;
}

PetscErrorCode VSHMMSpectralBuildCoefficients_Private(VSHMMSpectral sp, std::vector<double> &D, std::vector<double> &A)
{
  VSHMMSpectral_Data *s = sp->data;

  PetscFunctionBegin;
  D.clear();
  A.clear();
  for (const std::string &t : s->terms) {
    if (t == "diffusion") {
      PetscCall(VSHMMSpectralSampleField_Private(sp, "diffusion_coefficient", s->diff, D));
      /* d < 0 somewhere is backward diffusion there: an ill-posed problem whose modes grow the
         faster the higher they are (no time step resolves them; the stable-step estimate found no
         limit and the solve took one step over the whole interval, silently) */
      double dmax = 0;
      size_t at   = 0;
      for (size_t i = 0; i < D.size(); ++i) {
        dmax = std::max(dmax, std::fabs(D[i]));
        if (D[i] < D[at]) at = i;
      }
      PetscCheck(D.empty() || D[at] >= -kNegativeDiffusionTolerance * dmax, PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_diffusion_coefficient: the diffusion coefficient is negative: d = %g at x = %g (its smallest value on the grid); the term u_t += (d u_x)_x needs d >= 0 everywhere (a negative d is backward diffusion, an ill-posed problem)", VSHMMSpectralPrefix(sp), D[at],
                 2 * PETSC_PI * (double)at / (double)D.size());
    } else if (t == "advection") {
      PetscCall(VSHMMSpectralSampleField_Private(sp, "velocity", s->vel, A));
      for (double &a : A) a = -a;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode VSHMMSpectralBuildExtraTerms_Private(VSHMMSpectral sp, spc::ExtraTerms &x)
{
  VSHMMSpectral_Data *s = sp->data;

  PetscFunctionBegin;
  x = spc::ExtraTerms();
  for (const std::string &t : s->terms) {
    if (t == "burgers") PetscCall(VSHMMSpectralSampleField_Private(sp, "burgers_coefficient", s->burgers, x.burgers));
    else if (t == "reaction") {
      PetscCall(VSHMMSpectralSampleField_Private(sp, "reaction_rate", s->rate, x.rate));
      for (size_t i = 0; i < 4; ++i) x.reaction[i] = i < s->reaction.size() ? s->reaction[i] : 0.0;
    } else if (t == "source") PetscCall(VSHMMSpectralSampleField_Private(sp, "source", s->source, x.source));
  }
  PetscFunctionReturn(0);
}

static constexpr double kDecayingBand     = 0.5; /* -spectral_cluster_min_band_share leaves out only a band whose decay share (spc::bandAction()) is at least this */
static constexpr double kMaxBandInfluence = 1.0; /* and whose influence on the other retained bands is below this */
static constexpr int    kRKCStepsPerLook  = 8;   /* RKC steps of the detection DNS between consecutive looks */
static constexpr size_t kAutoWidening     = 3;   /* -spectral_cluster_detect auto: F(u0) widening u0's bands by more wavenumbers than this (and half of u0's) needs the DNS */
static constexpr double kRKCSafety        = 0.9; /* the RKC step's margin on the Ritz values (as RK3's) */

/* The detection DNS's right-hand side, with its work counted. */
struct DetectCtx {
  spc::SpectralOperator *op;
  PetscInt               evaluations = 0, steps = 0;
  const spc::Layout     *full = nullptr; /* set: keep the largest |c_k| over every step in peak */
  std::vector<double>    peak;
  std::vector<double>    meansq;      /* sum over the states seen of weight x (|c_k| / ||u||)^2 */
  double                 samples = 0; /* the weights summed in meansq */
  /* a state seen: its |c_k| (full layout); weight: the time it stands for, in RK3 steps (1 for
     each RK3 step, h / dt for an RKC step of h: the mean stays a mean over time) */
  void keep(const std::vector<double> &m, double weight = 1)
  {
    double n2 = 0;
    for (size_t k = 0; k < m.size(); ++k) n2 += (spc::isRealOnly(full->N(), (int)k) ? 1.0 : 2.0) * m[k] * m[k];
    if (peak.empty()) peak.assign(m.size(), 0.0), meansq.assign(m.size(), 0.0);
    for (size_t k = 0; k < m.size(); ++k) {
      peak[k] = std::max(peak[k], m[k]);
      if (n2 > 0) meansq[k] += weight * m[k] * m[k] / n2;
    }
    samples += weight;
  }
  /* the root mean square over the states seen of |c_k| / ||u|| (relative norm 1) */
  std::vector<double> mean() const
  {
    std::vector<double> r(meansq.size());
    for (size_t k = 0; k < r.size(); ++k) r[k] = std::sqrt(meansq[k] / std::max(samples, 1.0));
    return r;
  }
};

static PetscErrorCode DetectRHS(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  DetectCtx         *d = (DetectCtx *)ctx;
  const PetscScalar *u;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  (void)ts;
  (void)t;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  d->op->apply(u, f);
  d->evaluations++;
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

static PetscErrorCode DetectPostStep(TS ts)
{
  DetectCtx *d;

  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &d));
  d->steps++;
  if (d->full) {
    Vec                U;
    const PetscScalar *c;
    PetscCall(TSGetSolution(ts, &U));
    PetscCall(VecGetArrayRead(U, &c));
    d->keep(VSHMMSpectralFullMagnitudes(*d->full, c) /* full layout: N reals */);
    PetscCall(VecRestoreArrayRead(U, &c));
  }
  PetscFunctionReturn(0);
}

/* The snapshots thresholded and grouped into clusters (before buffers) in *cs; support gets the
   wavenumbers above the threshold (empty: no cluster). Bad grouping parameters are a PETSc error. */
static PetscErrorCode ClustersOf(VSHMMSpectral sp, const std::vector<std::vector<double>> &mags, spc::Normalization norm, double lambda, std::vector<int> &support, spc::ClusterSet *cs)
{
  const VSHMMSpectral_Data *s = sp->data;

  PetscFunctionBegin;
  *cs = spc::ClusterSet();
  try {
    support = spc::thresholdSupport(mags, (int)s->N, lambda, norm);
    if (support.empty()) PetscFunctionReturn(0);
    *cs = s->gap >= 0 ? spc::mergeIntoClusters(support, (int)s->N, (int)s->gap) : spc::groupIntoClusters(support, (int)s->N, s->gap_ratio);
    if (s->fill_holes) *cs = spc::fillHoles(*cs);
  } catch (const std::exception &e) {
    SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONG, "cluster detection: %s", e.what());
  }
  PetscFunctionReturn(0);
}

/* The time scale of each band: max|d| k^2 + max|a| k at its highest wavenumber k. */
static std::vector<double> BandRates(const spc::ClusterSet &bands, const std::vector<double> &D, const std::vector<double> &A)
{
  double              md = 0, ma = 0;
  std::vector<double> r;
  for (double d : D) md = std::max(md, std::fabs(d));
  for (double a : A) ma = std::max(ma, std::fabs(a));
  for (const auto &c : bands.clusters) r.push_back(md * c.back() * (double)c.back() + ma * c.back());
  return r;
}

/* The time-scale separation of consecutive clusters from the linear terms: the rate of the slowest
   wavenumber k > 0 of cluster j+1, mean|d| k^2 + mean|a| k (a mode of variable coefficients decays
   or turns at about the mean rate), over the rate of the fastest of cluster j, max|d| k^2 +
   max|a| k (its spectral radius bound). Empty where a cluster has no such rate (no linear terms). */
std::vector<PetscReal> VSHMMSpectralClusterSeparations_Private(const std::vector<std::vector<PetscInt>> &clusters, const std::vector<double> &D, const std::vector<double> &A)
{
  double md = 0, ma = 0, ad = 0, aa = 0;
  for (double d : D) md = std::max(md, std::fabs(d)), ad += std::fabs(d) / D.size();
  for (double a : A) ma = std::max(ma, std::fabs(a)), aa += std::fabs(a) / A.size();
  std::vector<PetscReal> S;
  for (size_t j = 0; j + 1 < clusters.size(); ++j) {
    double fastest = 0, slowest = PETSC_INFINITY;
    for (PetscInt k : clusters[j]) fastest = std::max(fastest, md * k * (double)k + ma * k);
    for (PetscInt k : clusters[j + 1])
      if (k > 0) slowest = std::min(slowest, ad * k * (double)k + aa * k);
    if (!(fastest > 0) || !(slowest > 0) || !(slowest < PETSC_INFINITY)) return {}; /* PETSC_INFINITY is finite: no k > 0 in the faster cluster */
    S.push_back(slowest / fastest);
  }
  return S;
}

/* -spectral_cluster_min_band_share: the detection's top bands (here each band is a cluster of its
   own), the stiffest modes, which set the micro step, are left out from the top down while each
   holds less than min_band_share x cluster_tol of ||u|| (mean: RMS over the steps), decays (an
   oscillating one, under advection or Burgers terms, carries what the transport moves through it)
   and does less to the other retained modes than they do in all (a thin band can still shift the
   bands it feeds, and through them the slow modes): spc::bandAction() at the last state U. The
   bands left out are zeroed in peak and cs is thresholded again. */
static PetscErrorCode LeaveOutThinBands(VSHMMSpectral sp, DetectCtx *dctx, Vec U, const std::vector<double> &mean, std::vector<int> &support, spc::ClusterSet &cs, std::vector<double> &peak)
{
  VSHMMSpectral_Data               *s = sp->data;
  std::ostringstream                dropped;
  const std::vector<spc::BandShare> bands = spc::bandShares(cs, mean);
  const PetscScalar                *c;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(U, &c));
  for (size_t i = bands.size(); i-- > 0;) {
    const spc::BandShare &b = bands[i];
    if (i == 0 || !(b.share < s->min_band_share * s->cluster_tol)) break; /* the slowest band stays */
    spc::BandAction act;
    try {
      act = spc::bandAction(*dctx->op, c, cs, b.lo, b.hi);
    } catch (const std::exception &e) {
      SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_PLIB, "cluster detection: %s", e.what());
    }
    dctx->evaluations += 2;
    PetscCall(PetscInfo(sp, "cluster detection DNS: band %d..%d holds %g of ||u||; decay share of its rate %g, influence on the other bands %g\n", b.lo, b.hi, b.share, act.decay, act.influence));
    if (act.decay < kDecayingBand || !(act.influence < kMaxBandInfluence)) {
      std::ostringstream why;
      why << b.lo << ".." << b.hi << " (share " << b.share << ") is kept with every band below it: " << (act.decay < kDecayingBand ? "it oscillates (decay share " : "it moves the other bands (influence ")
          << (act.decay < kDecayingBand ? act.decay : act.influence) << ")";
      s->detection.kept_band = why.str();
      break;
    }
    for (size_t j = 0; j < cs.clusters.size(); ++j) /* the bands below are judged against what remains */
      cs.clusters[j].erase(std::remove_if(cs.clusters[j].begin(), cs.clusters[j].end(), [&](int k) { return k >= b.lo && k <= b.hi; }), cs.clusters[j].end());
    for (int k = b.lo; k <= b.hi; ++k) peak[k] = 0; /* the later thresholding no longer sees it */
    dropped << (dropped.tellp() > 0 ? ", " : "") << b.lo << ".." << b.hi << " (" << b.share << ")";
  }
  PetscCall(VecRestoreArrayRead(U, &c));
  s->detection.dropped = dropped.str();
  if (!s->detection.dropped.empty()) PetscCall(ClustersOf(sp, {peak}, s->norm, VSHMMSpectralLambda(s), support, &cs));
  PetscFunctionReturn(0);
}

/* Snapshots |c_k| (k = 0..N/2) of a short direct simulation on every rank (PETSC_COMM_SELF), TS
   options prefix <prefix>spectral_cluster_detect_: at -spectral_cluster_detect_times, or (none
   given) the largest |c_k| over every step, looked at after 64, 128, 256, ... steps
   (-spectral_cluster_detect_first_steps, then doubled) until its
   clusters agree three times in a row (two doublings of the time bring nothing new;
   -spectral_cluster_detect_agreeing_looks) or
   -spectral_cluster_detect_max_steps is reached. Looks agree when their clusters are the same,
   or when the bands of the first of them only widened at their edges by wavenumbers that hold at
   most -spectral_cluster_tolerance of ||u|| (root mean square over the steps so far); the last
   look's (widest) bands are then kept. If bands of one look merge at the next and the
   wavenumbers outside the earlier bands hold at most -spectral_cluster_tolerance of ||u|| (root
   mean square over the steps so far), the earlier look's bands are kept: the merging modes carry
   less than the tolerance can see. */
static PetscErrorCode DetectionDNS(VSHMMSpectral sp, DetectCtx *dctx, const std::vector<double> &u0, std::vector<std::vector<double>> &mags, bool *rkc_failed)
{
  VSHMMSpectral_Data *s    = sp->data;
  spc::Layout         full = spc::Layout::full((int)s->N);
  Vec                 U;
  TS                  ts;
  PetscScalar        *u;
  PetscReal           dt = s->detect_dt;

  PetscFunctionBegin;
  PetscCheck(s->detect == VSHMMSPECTRAL_DETECT_AUTO || !s->detect_times.empty(), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_cluster_detect dns needs -%sspectral_cluster_detect_times t1,t2,...: the snapshot times of the short direct simulation (or use -%sspectral_cluster_detect auto)", VSHMMSpectralPrefix(sp), VSHMMSpectralPrefix(sp), VSHMMSpectralPrefix(sp));
  const bool automatic = s->detect_times.empty();
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, full.size(), &U));
  PetscCall(VecGetArray(U, &u));
  dctx->op->analyze(u0.data(), u);
  std::vector<std::complex<double>> ritz;
  if (!(dt > 0) || (automatic && s->detect_rkc)) { /* the operator's extreme eigenvalues (spectralstable.cpp), counted */
    PetscInt n;
    PetscCall(VSHMMSpectralRitzValues_Private(PETSC_COMM_SELF, *dctx->op, std::vector<double>(u, u + full.size()), ritz, &n));
    dctx->evaluations += n;
  }
  if (!(dt > 0)) PetscCall(VSHMMSpectralStableStepOf_Private(PETSC_COMM_SELF, ritz, TSRK3, &dt)); /* the stable RK3 step */
  PetscCall(VecRestoreArray(U, &u));
  /* RKC (-spectral_cluster_detect_rkc): the first look's steps are RK3's (the initial transient:
     the stiff modes' forcing by faster-changing ones changes within an RKC step, and RKC's peaks
     there were off at the threshold: a spurious top band, a missing single wavenumber); after it
     kRKCStepsPerLook steps between consecutive looks, each with the fewest stages for which every
     Ritz value (the step 1/0.9 longer, RK3's margin) lies in the stability region; used if the
     second look's steps need fewer evaluations than RK3's three per step dt */
  bool use_rkc = false;
  if (automatic && s->detect_rkc && std::isfinite(dt)) {
    const PetscReal h      = (PetscReal)s->detect_first_steps * dt / kRKCStepsPerLook;
    const int       stages = vshmm::ChebyshevRK2::stagesFor(h / kRKCSafety, ritz);
    use_rkc                = stages > 0 && stages * dt < 3 * h;
    PetscCall(PetscInfo(sp, "cluster detection DNS: an RKC step %g needs %d stages (0: none is stable), RK3 steps of %g 3 per step: %s\n", (double)h, stages, (double)dt, use_rkc ? "RKC" : "RK3"));
  }
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetOptionsPrefix(ts, ((PetscObject)sp)->prefix));
  PetscCall(TSAppendOptionsPrefix(ts, "spectral_cluster_detect_"));
  PetscCall(TSSetRHSFunction(ts, NULL, DetectRHS, dctx));
  PetscCall(TSSetApplicationContext(ts, dctx));
  PetscCall(TSSetPostStep(ts, DetectPostStep));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRKSetType(ts, TSRK3));
  PetscCall(TSSetTimeStep(ts, dt));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetFromOptions(ts));
  s->detection.dt = dt;
  std::vector<double> y, work; /* the RKC path's state (from the first look on) */
  PetscReal           t_rkc = 0;
  const auto          F     = [dctx](const double *v, double *f) {
    dctx->op->apply(v, f);
    dctx->evaluations++;
  };
  if (automatic) {
    const PetscScalar *c;
    dctx->full = &full;
    PetscCall(VecGetArrayRead(U, &c));
    dctx->keep(VSHMMSpectralFullMagnitudes(full, c));
    PetscCall(VecRestoreArrayRead(U, &c));
  }
  spc::ClusterSet     last, anchor;
  PetscInt            same     = 0;
  PetscReal           anchor_t = 0, widened = -1; /* the share of ||u|| the agreeing looks added */
  std::vector<double> last_peak;                  /* the largest |c_k| at the previous look */
  PetscReal           last_t = 0;
  for (size_t i = 0;; ++i) {
    PetscReal t;
    if (!automatic) {
      if (i == s->detect_times.size()) break;
      t = s->detect_times[i];
    } else t = PetscMin((double)s->detect_first_steps * std::ldexp(1.0, (int)PetscMin(i, (size_t)60)), (double)s->detect_max_steps) * dt;
    if (t > 0 && use_rkc && i > 0) { /* kRKCStepsPerLook RKC steps to t */
      const PetscReal h      = (t - t_rkc) / kRKCStepsPerLook;
      const int       stages = vshmm::ChebyshevRK2::stagesFor(h / kRKCSafety, ritz);
      if (!stages) { /* none up to 1000 stages (a far complex Ritz value): RK3 instead */
        *rkc_failed = true;
        break;
      }
      const vshmm::ChebyshevRK2 rkc(stages);
      s->detection.rkc_stages = PetscMax(s->detection.rkc_stages, (PetscInt)stages);
      s->detection.rkc_step   = PetscMax(s->detection.rkc_step, h);
      for (int j = 0; j < kRKCStepsPerLook; ++j) {
        rkc.step(F, h, y, work);
        dctx->steps++;
        for (double v : y)
          if (!std::isfinite(v)) *rkc_failed = true; /* the caller runs the detection again with RK3 */
        if (*rkc_failed) break;
        dctx->keep(VSHMMSpectralFullMagnitudes(full, y.data()), h / dt);
      }
      if (*rkc_failed) break;
      t_rkc = t;
      PetscCall(VecGetArray(U, &u));
      std::copy(y.begin(), y.end(), u);
      PetscCall(VecRestoreArray(U, &u));
    } else if (t > 0) {
      PetscCall(TSSetMaxTime(ts, t));
      PetscCall(TSSetTimeStep(ts, dt));
      PetscCall(TSSolve(ts, U));
      if (use_rkc) {
        const PetscScalar *c;
        PetscCall(VecGetArrayRead(U, &c));
        y.assign(c, c + full.size());
        PetscCall(VecRestoreArrayRead(U, &c));
        t_rkc = t;
      }
    }
    if (automatic) mags.assign(1, dctx->peak); /* the largest |c_k| over every step so far */
    else {
      const PetscScalar *c;
      PetscCall(VecGetArrayRead(U, &c));
      mags.push_back(VSHMMSpectralFullMagnitudes(full, c));
      PetscCall(VecRestoreArrayRead(U, &c));
    }
    s->detection.times.push_back(t);
    if (automatic) {
      std::vector<int> support;
      spc::ClusterSet  cs;
      PetscCall(ClustersOf(sp, mags, s->norm, VSHMMSpectralLambda(s), support, &cs));
      PetscCall(PetscInfo(sp, "cluster detection DNS: t = %g (%" PetscInt_FMT " steps): %d clusters %s\n", (double)t, dctx->steps, (int)cs.size(), cs.format().c_str()));
      if (i > 0 && spc::bandsMerged(last, cs)) {
        const double out = spc::shareOutside(last, dctx->mean());
        PetscCall(PetscInfo(sp, "cluster detection DNS: bands of t = %g merged at t = %g; the wavenumbers outside them hold %g of ||u|| (-spectral_cluster_tolerance %g)\n", (double)last_t, (double)t, out, (double)s->cluster_tol));
        if (out <= s->cluster_tol) { /* keep the bands before the merge */
          s->detection.merged_at = t;
          s->detection.kept      = last_t;
          mags.assign(1, last_peak);
          break;
        }
      }
      /* agreement with the first look of the current run of agreeing looks: the same bands, or
         (tolerance > 0) the same bands widened at their edges by wavenumbers that hold at most the
         tolerance of ||u|| in all (they sit at the threshold, as diffadv's slow band, which gains
         one wavenumber every few doublings) */
      bool agree = i > 0 && cs.clusters == anchor.clusters;
      if (i > 0 && !agree && s->cluster_tol > 0 && spc::bandsWidened(anchor, cs)) {
        const double added = spc::shareAdded(anchor, cs, dctx->mean());
        PetscCall(PetscInfo(sp, "cluster detection DNS: bands of t = %g widened at t = %g by wavenumbers holding %g of ||u|| (-spectral_cluster_tolerance %g)\n", (double)anchor_t, (double)t, added, (double)s->cluster_tol));
        if (added <= s->cluster_tol) agree = true, widened = PetscMax(widened, added);
      }
      if (agree) same++;
      else same = 0, anchor = cs, anchor_t = t, widened = -1;
      last      = cs;
      last_peak = mags[0];
      last_t    = t;
      if (same >= s->detect_agreeing - 1) {
        s->detection.widened = widened;
        break;
      }
      if (dctx->steps >= s->detect_max_steps || t >= s->detect_max_steps * dt * (1 - 1e-12)) {
        s->detection.converged = false;
        PetscCall(PetscInfo(sp, "cluster detection DNS: the clusters still changed at the step limit -spectral_cluster_detect_max_steps %" PetscInt_FMT "\n", s->detect_max_steps));
        break;
      }
    }
  }
  if (automatic && !*rkc_failed) { /* the share of ||u|| the bands leave out, RMS over every step */
    std::vector<int> support;
    spc::ClusterSet  cs;
    PetscCall(ClustersOf(sp, mags, s->norm, VSHMMSpectralLambda(s), support, &cs));
    const std::vector<double> mean = dctx->mean();
    if (s->min_band_share > 0) PetscCall(LeaveOutThinBands(sp, dctx, U, mean, support, cs, mags[0]));
    s->detection.left_out = spc::shareOutside(cs, mean);
  }
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
  PetscFunctionReturn(0);
}

/* -spectral_cluster_detect auto: does the initial data show every cluster? F(u0) is computed on
   every mode; if the wavenumbers of u0 and F(u0) (each above lambda relative to its own norm)
   form more bands than those of u0 alone, or widen them by more than kAutoWidening wavenumbers
   and half of u0's, the operator creates modes u0 does not show and a short direct simulation is
   needed. */
static PetscErrorCode AutoNeedsDNS(VSHMMSpectral sp, DetectCtx *dctx, const std::vector<double> &u0, bool *dns)
{
  VSHMMSpectral_Data *s    = sp->data;
  const int           N    = (int)s->N;
  spc::Layout         full = spc::Layout::full(N);
  std::vector<double> c(full.size()), f(full.size());
  std::vector<int>    s0, s1;
  spc::ClusterSet     c0, c1;
  const double        lambda = s->norm == spc::Normalization::Relative ? VSHMMSpectralLambda(s) : spc::defaultLambda(spc::Normalization::Relative);

  PetscFunctionBegin;
  dctx->op->analyze(u0.data(), c.data());
  dctx->op->apply(c.data(), f.data());
  dctx->evaluations++;
  const std::vector<double> m0 = VSHMMSpectralFullMagnitudes(full, c.data()), mf = VSHMMSpectralFullMagnitudes(full, f.data());
  PetscCall(ClustersOf(sp, {m0}, spc::Normalization::Relative, lambda, s0, &c0));
  PetscCall(ClustersOf(sp, {m0, mf}, spc::Normalization::Relative, lambda, s1, &c1));
  /* new bands, or bands widened by more than half the wavenumbers u0 shows (a coefficient's
     wavenumber close to u0's band joins them: d = 0.025 + 0.275 exp(sin 20x) + ... on a Gaussian
     u0 made its 0..5 and the fast modes one band, and the clusters of u0 alone missed them) */
  size_t added = 0;
  for (int k : s1) added += std::binary_search(s0.begin(), s0.end(), k) ? 0 : 1;
  *dns = c1.size() > c0.size() || added > std::max<size_t>(kAutoWidening, s0.size() / 2);
  std::ostringstream m;
  if (c1.size() > c0.size()) m << "auto: F(u0) reaches " << c1.size() << " clusters (" << c1.format() << "), u0 shows " << c0.size() << ": short direct simulation";
  else if (*dns) m << "auto: F(u0) widens the bands of u0 by " << added << " wavenumbers (" << c1.format() << ", u0 shows " << c0.format() << "): short direct simulation";
  else m << "auto: the initial data shows every cluster F(u0) reaches (" << c0.size() << "): initial data only";
  s->detection.rule = m.str();
  PetscFunctionReturn(0);
}

/* Snapshots |c_k| (k = 0..N/2) for the cluster detection. */
static PetscErrorCode DetectionSnapshots(VSHMMSpectral sp, const std::vector<double> &D, const std::vector<double> &A, std::vector<std::vector<double>> &mags)
{
  VSHMMSpectral_Data *s    = sp->data;
  MPI_Comm            comm = PetscObjectComm((PetscObject)sp);
  std::vector<double> u;

  PetscFunctionBegin;
  mags.clear();
  if (s->detect == VSHMMSPECTRAL_DETECT_FILE) {
    PetscCheck(!s->detect_file.empty(), comm, PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_cluster_detect file needs -%sspectral_cluster_detect_file <grid file of N lines 'x u'>", VSHMMSpectralPrefix(sp), VSHMMSpectralPrefix(sp));
    PetscCall(VSHMMSpectralReadGridFile_Private(comm, s->detect_file.c_str(), u));
    PetscCheck((PetscInt)u.size() == s->N, comm, PETSC_ERR_ARG_SIZ, "-%sspectral_cluster_detect_file '%s' has %d values but N = %" PetscInt_FMT, VSHMMSpectralPrefix(sp), s->detect_file.c_str(), (int)u.size(), s->N);
    mags.push_back(spc::coefficientMagnitudes(u));
    PetscFunctionReturn(0);
  }
  PetscCall(VSHMMSpectralSampleField_Private(sp, "u0", s->u0, u));
  if (s->detect == VSHMMSPECTRAL_DETECT_INITIAL) {
    mags.push_back(spc::coefficientMagnitudes(u));
    PetscFunctionReturn(0);
  }
  spc::ExtraTerms extra;
  PetscCall(VSHMMSpectralBuildExtraTerms_Private(sp, extra));
  spc::SpectralOperator op(spc::Layout::full((int)s->N), D, A, extra, spc::Planner::Estimate);
  DetectCtx             dctx;
  bool                  dns = true;

  dctx.op = &op;
  if (s->detect == VSHMMSPECTRAL_DETECT_AUTO) {
    PetscCall(AutoNeedsDNS(sp, &dctx, u, &dns));
    if (!dns) mags.push_back(spc::coefficientMagnitudes(u));
  }
  if (dns) {
    bool failed = false;
    PetscCall(DetectionDNS(sp, &dctx, u, mags, &failed));
    if (failed) { /* RKC met a mode outside its region (the Ritz values missed it): again with RK3, both counted */
      const PetscBool rkc = s->detect_rkc;
      PetscCall(PetscInfo(sp, "cluster detection DNS: the RKC steps gave Inf or NaN; again with RK3\n"));
      DetectCtx again;
      again.op          = &op;
      again.evaluations = dctx.evaluations;
      dctx              = again;
      mags.clear();
      s->detection.times.clear();
      s->detection.rkc_stages = 0;
      s->detection.rkc_step   = 0;
      s->detect_rkc           = PETSC_FALSE;
      PetscErrorCode ierr     = DetectionDNS(sp, &dctx, u, mags, &failed);
      s->detect_rkc           = rkc;
      PetscCall(ierr);
    }
  }
  s->detection.steps       = dctx.steps;
  s->detection.evaluations = dctx.evaluations;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetClusterTolerance - Sets the tolerance of the automatic cluster detection: when
   bands of the detection DNS merge (the modes between them rise above the threshold) and the
   wavenumbers outside the bands before the merge hold at most tol of ||u|| (root mean square over
   the DNS steps so far), the bands before the merge are kept

   Logically collective

   Input Parameters:
+  sp - the object
-  tol - the tolerance, nonnegative (0: merged bands stay merged); default 1e-2

   Options Database Key:
.  -spectral_cluster_tolerance <tol> - the tolerance

   Note:
   The examples pass `-ts_rtol` here (before `VSHMMSpectralSetFromOptions()`), so the detection
   and the time stepping share the scene's tolerance.

   Level: intermediate

.seealso: `VSHMMSpectralSetUp()`, `VSHMMSpectralView()`
@*/
PetscErrorCode VSHMMSpectralSetClusterTolerance(VSHMMSpectral sp, PetscReal tol)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCheck(std::isfinite(tol) && tol >= 0, PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "The cluster tolerance (-%sspectral_cluster_tolerance) must be finite and nonnegative, got %g", VSHMMSpectralPrefix(sp), (double)tol);
  sp->data->cluster_tol = tol;
  sp->setupcalled       = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetClusterThreshold - Sets the threshold lambda of the cluster detection: the
   wavenumbers whose coefficient magnitude (soft-thresholded, in the detection's normalisation)
   stays above lambda form the bands

   Logically collective

   Input Parameters:
+  sp - the object
-  lambda - the threshold, nonnegative (negative: the normalisation's default, 1e-4 relative to
            ||u||, 10^-2.5 for the others)

   Options Database Key:
.  -spectral_cluster_lambda <lambda> - the threshold

   Note:
   The modes the detection leaves out cost the sparse method (and VSHMM on its clusters) an error
   of about 10 times lambda (relative normalisation; measured on the diffusion scenes: 1e-4 gives
   relative L2 errors of 1e-3 to 5e-3). The examples set lambda = tol / 30 for tolerances
   `-ts_rtol` below 3e-3.

   Level: intermediate

.seealso: `VSHMMSpectralSetClusterTolerance()`, `VSHMMSpectralSetUp()`
@*/
PetscErrorCode VSHMMSpectralSetClusterThreshold(VSHMMSpectral sp, PetscReal lambda)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCheck(std::isfinite(lambda), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_lambda must be finite (negative: the normalisation's default), got %g", VSHMMSpectralPrefix(sp), (double)lambda);
  sp->data->lambda = lambda;
  sp->setupcalled  = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode FindClusters(VSHMMSpectral sp, const std::vector<double> &D, const std::vector<double> &A)
{
  VSHMMSpectral_Data *s                 = sp->data;
  MPI_Comm            comm              = PetscObjectComm((PetscObject)sp);
  const char         *pre               = VSHMMSpectralPrefix(sp);
  const bool          explicit_clusters = !s->cluster_spec.empty();
  std::vector<int>    buffers(s->buffers.begin(), s->buffers.end());

  PetscFunctionBegin;
  if (!s->widened.clusters.empty()) { /* VSHMMSpectralWidenClusters(): the clusters found before, widened; the detection's figures stay */
    s->clusters = s->widened;
    PetscFunctionReturn(0);
  }
  s->detection = VSHMMSpectralDetection();
  PetscCheck(!(explicit_clusters && s->detect != VSHMMSPECTRAL_DETECT_NONE), comm, PETSC_ERR_ARG_INCOMP, "Give either -%sspectral_clusters (explicit) or -%sspectral_cluster_detect %s, not both", pre, pre, VSHMMSpectralDetects[s->detect]);
  const VSHMMSpectralDetect given = s->detect;
  if (!explicit_clusters && s->detect == VSHMMSPECTRAL_DETECT_NONE) {
    s->detect = VSHMMSPECTRAL_DETECT_AUTO; /* sparse mode without clusters: find them (restored below) */
    PetscCall(PetscInfo(sp, "-%sspectral_mode sparse without -%sspectral_clusters: -%sspectral_cluster_detect auto\n", pre, pre, pre));
  }
  if (explicit_clusters) {
    try {
      s->clusters = spc::ClusterSet::parse(s->cluster_spec, (int)s->N);
      s->clusters = spc::addBuffers(s->clusters, buffers);
    } catch (const std::exception &e) {
      SETERRQ(comm, PETSC_ERR_ARG_WRONG, "-%sspectral_clusters %s: %s", pre, s->cluster_spec.c_str(), e.what());
    }
  } else {
    std::vector<std::vector<double>> mags;
    std::vector<int>                 support;
    spc::ClusterSet                  found;
    PetscLogDouble                   w0, w1;

    PetscCall(PetscTime(&w0));
    PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_Detect, sp, 0, 0, 0));
    PetscCall(DetectionSnapshots(sp, D, A, mags));
    PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_Detect, sp, 0, 0, 0));
    s->detect = given; /* the option as given: a later -spectral_clusters is not "both" */
    PetscCall(ClustersOf(sp, mags, s->norm, VSHMMSpectralLambda(s), support, &found));
    if (support.empty()) {
      double big  = 0;
      int    kbig = 0;
      for (const auto &m : mags)
        for (size_t k = 0; k < m.size(); ++k)
          if (m[k] * spc::normalizationFactor(s->norm, (int)s->N, m) > big) big = m[k] * spc::normalizationFactor(s->norm, (int)s->N, m), kbig = (int)k;
      PetscCheck(big > 0, comm, PETSC_ERR_ARG_WRONG, "The cluster detection sees no mode: every Fourier coefficient of its snapshots is 0 (an initial state u0 = 0 that the scene's terms leave at 0): there are no time scales to find. Give the clusters (-%sspectral_clusters) or run the DNS (-%sspectral_mode dns)", pre, pre);
      SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "Soft thresholding with -%sspectral_cluster_lambda %g leaves no mode: the largest %s-normalised coefficient is %g (k = %d); lower -%sspectral_cluster_lambda", pre, (double)VSHMMSpectralLambda(s), spc::normalizationName(s->norm), big, kbig, pre);
    }
    PetscCall(PetscTime(&w1));
    s->detection.wall = w1 - w0;
    try {
      s->detection.support = (PetscInt)support.size();
      s->detection.merged  = (PetscInt)found.size();
      s->clusters          = spc::groupIntoScales(found, BandRates(found, D, A), s->scale_separation);
      s->detection.scales  = (PetscInt)s->clusters.size();
      s->clusters          = spc::addBuffers(s->clusters, buffers);
    } catch (const std::exception &e) {
      SETERRQ(comm, PETSC_ERR_ARG_WRONG, "cluster detection (-%sspectral_cluster_buffers): %s", pre, e.what());
    }
    PetscCall(PetscInfo(sp, "cluster detection: %" PetscInt_FMT " wavenumbers above lambda %g in %" PetscInt_FMT " clusters\n", s->detection.support, (double)VSHMMSpectralLambda(s), s->detection.merged));
  }
  if (s->clusters.sortByLowest()) PetscCall(PetscInfo(sp, "clusters reordered by their lowest wavenumber (slowest first)\n"));
  PetscFunctionReturn(0);
}

/* -spectral_projection auto: measures how many modes a direct projection handles in the time of
   one r2c transform on this machine (the same value on every rank: the smallest). */
static PetscErrorCode CalibrateProjection(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s = sp->data;

  PetscFunctionBegin;
  if (s->mode != VSHMMSPECTRAL_MODE_SPARSE || s->dense || s->projection != VSHMMSPECTRAL_PROJECTION_AUTO || s->op->hasPadded()) PetscFunctionReturn(0);
  std::vector<double> zero(s->layout->size(), 0.0), out(s->layout->size());
  const int           R      = 16;
  double              best_f = PETSC_MAX_REAL, best_d = PETSC_MAX_REAL;
  PetscLogDouble      t0, t1;

  s->op->computePhysical(zero.data());
  s->op->projectDirect(0, 1, out.data()); /* builds the mode's table */
  for (int trial = 0; trial < 3; ++trial) {
    PetscCall(PetscTime(&t0));
    for (int r = 0; r < R; ++r) s->op->computeForward();
    PetscCall(PetscTime(&t1));
    best_f = PetscMin(best_f, (t1 - t0) / R);
    PetscCall(PetscTime(&t0));
    for (int r = 0; r < R; ++r) s->op->projectDirect(0, 1, out.data());
    PetscCall(PetscTime(&t1));
    best_d = PetscMin(best_d, (t1 - t0) / R);
  }
  double ratio = best_d > 0 ? best_f / best_d : s->op->directModesPerForward();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ratio, 1, MPI_DOUBLE, MPI_MIN, PetscObjectComm((PetscObject)sp)));
  s->op->setDirectModesPerForward(ratio);
  s->op->counters() = spc::SpectralOperator::Counters();
  PetscCall(PetscInfo(sp, "one r2c of N = %d takes %g s, a direct projection of one mode %g s: direct projections for up to %g modes per state\n", (int)s->N, best_f, best_d, ratio));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetUp - Samples the fields, finds the clusters (explicit or detected), builds the
   layout of the state and the FFTW plans

   Collective

   Input Parameter:
.  sp - the object

   Notes:
   Errors name the option at fault: unknown term, empty or overlapping cluster lists, wavenumbers
   above N/2, thresholds that leave no mode, bad field parameters. `VSHMMSpectralView()` shows the
   clusters found.

   Level: beginner

.seealso: `VSHMMSpectralSetFromOptions()`, `VSHMMSpectralSetUpTS()`, `VSHMMSpectralView()`
@*/
PetscErrorCode VSHMMSpectralSetUp(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s;
  MPI_Comm            comm;
  std::vector<double> D, A, u0;
  spc::ExtraTerms     extra;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  if (sp->setupcalled) PetscFunctionReturn(0);
  s    = sp->data;
  comm = PetscObjectComm((PetscObject)sp);
  PetscCall(PetscLogEventBegin(VSHMMSPECTRAL_SetUp, sp, 0, 0, 0));
  PetscCall(VSHMMSpectralBuildCoefficients_Private(sp, D, A));
  PetscCall(VSHMMSpectralBuildExtraTerms_Private(sp, extra));
  if (s->evaluation == VSHMMSPECTRAL_EVALUATION_MATRIX) {
    const char *nl = !extra.burgers.empty() ? "burgers" : extra.nonlinear() ? "reaction (of degree 2 or 3)" : nullptr;
    PetscCheck(!nl, comm, PETSC_ERR_SUP, "-%sspectral_evaluation matrix is for linear (and affine) scenes: the term %s is nonlinear; use -%sspectral_evaluation fft", VSHMMSpectralPrefix(sp), nl, VSHMMSpectralPrefix(sp));
  }
  PetscCheck(!(s->projection == VSHMMSPECTRAL_PROJECTION_DIRECT && (!extra.burgers.empty() || !extra.rate.empty())), comm, PETSC_ERR_SUP, "-%sspectral_projection direct is not available with the terms burgers and reaction (their products are formed on a padded grid and projected by FFT); use -%sspectral_projection auto or fft", VSHMMSpectralPrefix(sp), VSHMMSpectralPrefix(sp));
  PetscCall(VSHMMSpectralSampleField_Private(sp, "u0", s->u0, u0));
  if (s->mode == VSHMMSPECTRAL_MODE_SPARSE) {
    PetscCall(FindClusters(sp, D, A));
    s->layout = std::make_unique<spc::Layout>(s->clusters);
  } else {
    if (!s->cluster_spec.empty() || s->detect != VSHMMSPECTRAL_DETECT_NONE) PetscCall(PetscInfo(sp, "mode dns uses every wavenumber; the clusters and their detection are not used\n"));
    s->layout    = std::make_unique<spc::Layout>(spc::Layout::full((int)s->N));
    s->clusters  = spc::ClusterSet();
    s->detection = VSHMMSpectralDetection();
  }
  try {
    s->op = std::make_unique<spc::SpectralOperator>(*s->layout, D, A, extra, CorePlanner(s->planner));
  } catch (const std::exception &e) {
    SETERRQ(comm, PETSC_ERR_LIB, "Spectral operator: %s", e.what());
  }
  s->dense.reset();
  if (s->evaluation == VSHMMSPECTRAL_EVALUATION_MATRIX) {
    PetscCheck(s->layout->size() <= 8192, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_evaluation matrix: %d retained coefficients are too many for a dense operator (at most 8192)", VSHMMSpectralPrefix(sp), s->layout->size());
    s->dense = std::make_unique<spc::DenseOperator>(*s->op);
  }
  s->cluster_modes.clear();
  for (int j = 0; j < s->layout->clusterCount(); ++j) {
    std::vector<PetscInt> m;
    for (int i = s->layout->clusterModeBegin(j); i < s->layout->clusterModeEnd(j); ++i) m.push_back(s->layout->mode(i));
    s->cluster_modes.push_back(m);
  }
  s->modes.assign(s->layout->modes().begin(), s->layout->modes().end());
  s->separations = s->mode == VSHMMSPECTRAL_MODE_SPARSE ? VSHMMSpectralClusterSeparations_Private(s->cluster_modes, D, A) : std::vector<PetscReal>();
  s->out.assign(s->layout->size(), 0.0);
  PetscCall(CalibrateProjection(sp));
  s->cache_valid                 = PETSC_FALSE;
  s->stats                       = VSHMMSpectralStatistics();
  s->stats.detection_steps       = s->detection.steps;
  s->stats.detection_evaluations = s->detection.evaluations;
  s->stats.detection_time        = s->detection.wall;
  s->stats.widenings             = s->widenings;
  s->stats.widening_evaluations  = s->widening_evaluations;
  s->weights                     = spc::parsevalWeights(*s->layout); /* spectralstable.cpp */
  s->ritz_done                   = PETSC_FALSE;
  s->dns_ritz_done               = PETSC_FALSE;
  s->growth_started              = PETSC_FALSE;
  s->truncation_started          = PETSC_FALSE;
  PetscCall(VecScatterDestroy(&s->gather)); /* for the layout before (VSHMMSpectralWidenClusters()) */
  PetscCall(VecDestroy(&s->Useq));
  s->full_op.reset(); /* the truncation check's operator on every wavenumber, made at its first look */
  s->full_layout.reset();
  sp->setupcalled = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_SetUp, sp, 0, 0, 0));
  PetscFunctionReturn(0);
}
