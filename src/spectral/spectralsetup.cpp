/*
  VSHMMSpectralSetUp(): the coefficient fields on the grid, the clusters (explicit, or detected by
  soft thresholding of snapshots), the layout of the state, the FFTW plans and the dense operator.
*/
#include "spectralimpl.hpp"

#include <algorithm>
#include <cmath>

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
    if (t == "diffusion") PetscCall(VSHMMSpectralSampleField_Private(sp, "diffusion_coefficient", s->diff, D));
    else if (t == "advection") {
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

static PetscErrorCode DetectRHS(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  spc::SpectralOperator *op = (spc::SpectralOperator *)ctx;
  const PetscScalar     *u;
  PetscScalar           *f;

  PetscFunctionBeginUser;
  (void)ts;
  (void)t;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  op->apply(u, f);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

/* Snapshots |c_k| (k = 0..N/2) of a short direct simulation on every rank (PETSC_COMM_SELF), TS
   options prefix <prefix>spectral_cluster_detect_. */
static PetscErrorCode DetectionDNS(VSHMMSpectral sp, const std::vector<double> &D, const std::vector<double> &A, const std::vector<double> &u0, std::vector<std::vector<double>> &mags)
{
  VSHMMSpectral_Data *s    = sp->data;
  spc::Layout         full = spc::Layout::full((int)s->N);
  spc::ExtraTerms     extra;
  Vec                 U;
  TS                  ts;
  PetscScalar        *u;
  PetscReal           dt = s->detect_dt;

  PetscFunctionBegin;
  PetscCheck(!s->detect_times.empty(), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_cluster_detect dns needs -%sspectral_cluster_detect_times t1,t2,...: the snapshot times of the short direct simulation", VSHMMSpectralPrefix(sp), VSHMMSpectralPrefix(sp));
  PetscCall(VSHMMSpectralBuildExtraTerms_Private(sp, extra));
  spc::SpectralOperator op(full, D, A, extra, spc::Planner::Estimate);
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, full.size(), &U));
  PetscCall(VecGetArray(U, &u));
  op.analyze(u0.data(), u);
  if (!(dt > 0)) { /* the operator's stable RK3 step (spectralstable.cpp) */
    std::vector<std::complex<double>> ritz;
    PetscCall(VSHMMSpectralRitzValues_Private(PETSC_COMM_SELF, op, std::vector<double>(u, u + full.size()), ritz));
    PetscCall(VSHMMSpectralStableStepOf_Private(PETSC_COMM_SELF, ritz, TSRK3, &dt));
  }
  PetscCall(VecRestoreArray(U, &u));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetOptionsPrefix(ts, ((PetscObject)sp)->prefix));
  PetscCall(TSAppendOptionsPrefix(ts, "spectral_cluster_detect_"));
  PetscCall(TSSetRHSFunction(ts, NULL, DetectRHS, &op));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRKSetType(ts, TSRK3));
  PetscCall(TSSetTimeStep(ts, dt));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetFromOptions(ts));
  s->detection.dt    = dt;
  s->detection.times = s->detect_times;
  for (PetscReal t : s->detect_times) {
    if (t > 0) {
      PetscCall(TSSetMaxTime(ts, t));
      PetscCall(TSSetTimeStep(ts, dt));
      PetscCall(TSSolve(ts, U));
    }
    const PetscScalar  *c;
    std::vector<double> m(full.modeCount());
    PetscCall(VecGetArrayRead(U, &c));
    for (int i = 0; i < full.modeCount(); ++i) {
      const int k = full.mode(i), o = full.offset(i);
      m[k] = spc::isRealOnly((int)s->N, k) ? std::fabs(c[o]) : std::hypot(c[o], c[o + 1]);
    }
    PetscCall(VecRestoreArrayRead(U, &c));
    mags.push_back(m);
  }
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
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
  if (s->detect == VSHMMSPECTRAL_DETECT_INITIAL) mags.push_back(spc::coefficientMagnitudes(u));
  else PetscCall(DetectionDNS(sp, D, A, u, mags));
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
  s->detection = VSHMMSpectralDetection();
  PetscCheck(!(explicit_clusters && s->detect != VSHMMSPECTRAL_DETECT_NONE), comm, PETSC_ERR_ARG_INCOMP, "Give either -%sspectral_clusters (explicit) or -%sspectral_cluster_detect %s, not both", pre, pre, VSHMMSpectralDetects[s->detect]);
  PetscCheck(explicit_clusters || s->detect != VSHMMSPECTRAL_DETECT_NONE, comm, PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_mode sparse needs clusters: give -%sspectral_clusters lo:hi,lo:hi,... (e.g. 0:3,62:66,192:193,255:257) or -%sspectral_cluster_detect initial|dns|file", pre, pre, pre);
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

    PetscCall(DetectionSnapshots(sp, D, A, mags));
    try {
      support = spc::thresholdSupport(mags, (int)s->N, s->lambda, s->norm);
    } catch (const std::exception &e) {
      SETERRQ(comm, PETSC_ERR_ARG_WRONG, "cluster detection: %s", e.what());
    }
    if (support.empty()) {
      double big  = 0;
      int    kbig = 0;
      for (const auto &m : mags)
        for (size_t k = 0; k < m.size(); ++k)
          if (m[k] > big) big = m[k], kbig = (int)k;
      SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "Soft thresholding with -%sspectral_cluster_lambda %g leaves no mode: the largest %s-normalised coefficient is %g (k = %d); lower -%sspectral_cluster_lambda", pre, (double)s->lambda, spc::normalizationName(s->norm),
              big * spc::normalizationFactor(s->norm, (int)s->N), kbig, pre);
    }
    try {
      s->clusters          = spc::mergeIntoClusters(support, (int)s->N, (int)s->gap);
      s->detection.support = (PetscInt)support.size();
      s->detection.merged  = (PetscInt)s->clusters.size();
      s->clusters          = spc::addBuffers(s->clusters, buffers);
    } catch (const std::exception &e) {
      SETERRQ(comm, PETSC_ERR_ARG_WRONG, "cluster detection (-%sspectral_cluster_buffers): %s", pre, e.what());
    }
    PetscCall(PetscInfo(sp, "cluster detection: %" PetscInt_FMT " wavenumbers above lambda %g in %" PetscInt_FMT " clusters\n", s->detection.support, (double)s->lambda, s->detection.merged));
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
  PetscValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
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
  s->out.assign(s->layout->size(), 0.0);
  PetscCall(CalibrateProjection(sp));
  s->cache_valid    = PETSC_FALSE;
  s->stats          = VSHMMSpectralStatistics();
  s->weights        = spc::parsevalWeights(*s->layout); /* spectralstable.cpp */
  s->ritz_done      = PETSC_FALSE;
  s->growth_started = PETSC_FALSE;
  sp->setupcalled   = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(VSHMMSPECTRAL_SetUp, sp, 0, 0, 0));
  PetscFunctionReturn(0);
}
