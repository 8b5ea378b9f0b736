/*
  VSHMMSpectral: the PETSc glue of the sparse spectral component (include/petscvshmmspectral.h).

  A scene (terms, coefficient fields, initial data, grid, clusters) read from the options
  database; the state Vec of the retained Fourier coefficients; the full right-hand side and
  one additive TSRHSSplit per cluster; cluster detection; the output contract.

  Cost of a VSHMM level (splits 0..l called one after another with the same state Vec):
    fft evaluation: the first split called with a new state (Vec id, object state, t) computes
    u_x on the grid (one c2r of size N) and the products with the coefficient fields (O(N));
    the following splits of the same state reuse them. Each split then needs the transform of
    the products on its own cluster only: by direct sums over the grid (n_j N flops for n_j
    modes) while the modes projected so for this state stay below the cost of one r2c, else by
    one r2c (size N, once per state, shared). So level l costs one c2r plus
    min(r2c, sum_{j<=l} n_j N), and the full field one c2r plus one r2c (per term kind).
    matrix evaluation (linear terms only): split j multiplies the rows of cluster j of the dense
    operator on the retained modes, (rows of cluster j) x (retained reals) flops: level l pays
    for its own clusters' rows only.
*/
#include <petscvshmmspectral.h>
#include <petscvshmm.h>
#include <petsc/private/petscimpl.h> /* PetscObjectStateGet(), PetscValidPointer() */

#include "detect.hpp"
#include "spectral.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace vs = vshmm::spectral;

typedef enum {
  MODE_DNS,
  MODE_SPARSE
} SpectralMode;
static const char *const ModeNames[] = {"dns", "sparse", "SpectralMode", "MODE_", nullptr};

typedef enum {
  DETECT_NONE,
  DETECT_INITIAL,
  DETECT_DNS,
  DETECT_FILE
} DetectKind;
static const char *const DetectNames[] = {"none", "initial", "dns", "file", "DetectKind", "DETECT_", nullptr};

typedef enum {
  PROJ_AUTO,
  PROJ_FFT,
  PROJ_DIRECT
} ProjectionKind;
static const char *const ProjectionNames[] = {"auto", "fft", "direct", "ProjectionKind", "PROJ_", nullptr};

typedef enum {
  EVAL_FFT,
  EVAL_MATRIX
} EvaluationKind;
static const char *const EvaluationNames[] = {"fft", "matrix", "EvaluationKind", "EVAL_", nullptr};

typedef enum {
  PLAN_ESTIMATE,
  PLAN_MEASURE,
  PLAN_PATIENT
} PlannerKind;
static const char *const PlannerNames[] = {"estimate", "measure", "patient", "PlannerKind", "PLAN_", nullptr};

static const char *const KnownTerms = "diffusion (d/dx(d(x) du/dx), coefficient -diffusion_coefficient) and advection (-a(x) du/dx, velocity -velocity)";

struct SplitCtx {
  VSHMMSpectral sp;
  PetscInt      j;
};

struct _n_VSHMMSpectral {
  MPI_Comm    comm;
  PetscMPIInt size = 1, rank = 0;

  /* the scene */
  std::string              scene = "diffusion";
  PetscInt                 N     = 2048;
  std::vector<std::string> terms;
  vs::Field                diff, vel, u0;
  SpectralMode             mode = MODE_DNS;
  std::string              cluster_spec;
  DetectKind               detect = DETECT_NONE;
  PetscReal                lambda = 3.1622776601683794e-3; /* 10^-2.5 */
  PetscInt                 gap    = 1;
  std::vector<int>         buffers;
  vs::Normalization        norm = vs::Normalization::Unitary;
  std::vector<PetscReal>   detect_times;
  std::string              detect_file;
  PetscReal                detect_dt = 0;
  ProjectionKind           projection = PROJ_AUTO;
  EvaluationKind           evaluation = EVAL_FFT;
  PlannerKind              planner    = PLAN_MEASURE;
  std::vector<PetscReal>   output_times;
  std::string              grid_prefix, spectrum_file, compare_prefix;
  PetscReal                spectrum_interval = 0.01, next_spectrum = 0, compare_tol = 0;
  FILE                    *spectrum_fp = nullptr;
  PetscBool                timing = PETSC_TRUE, setfromoptions_called = PETSC_FALSE, setup = PETSC_FALSE;

  /* set-up */
  vs::ClusterSet                        clusters;
  std::unique_ptr<vs::Layout>           layout;
  std::unique_ptr<vs::SpectralOperator> op;
  std::unique_ptr<vs::DenseOperator>    dense;
  std::vector<std::vector<PetscInt>>    cluster_modes; /* for VSHMMSpectralGetCluster() */
  std::vector<SplitCtx>                 split_ctx;
  VecScatter                            gather = nullptr;
  Vec                                   Useq   = nullptr;
  std::vector<double>                   out;

  /* the physical-space field of the last state seen */
  PetscBool        cache_valid = PETSC_FALSE, fft_done = PETSC_FALSE;
  PetscObjectId    cache_id    = 0;
  PetscObjectState cache_state = 0;
  PetscReal        cache_t     = 0;
  double           direct_spent = 0;

  VSHMMSpectralStatistics stats = {};
};

/* ------------------------------------------------------------------------------------------ */
/* Log events                                                                                   */

static PetscBool     SpecEventsRegistered = PETSC_FALSE;
static PetscLogEvent EV_RHS, EV_SPLIT, EV_PHYSICAL, EV_FORWARD, EV_DIRECT, EV_MATVEC, EV_OUTPUT;

static PetscErrorCode SpecEventsReset(void)
{
  PetscFunctionBegin;
  SpecEventsRegistered = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode SpecRegisterEvents(void)
{
  PetscFunctionBegin;
  if (SpecEventsRegistered) PetscFunctionReturn(0);
  SpecEventsRegistered = PETSC_TRUE;
  PetscCall(TSInitializePackage());
  PetscCall(PetscLogEventRegister("SpecRHS", TS_CLASSID, &EV_RHS));
  PetscCall(PetscLogEventRegister("SpecSplit", TS_CLASSID, &EV_SPLIT));
  PetscCall(PetscLogEventRegister("SpecPhysical", TS_CLASSID, &EV_PHYSICAL));
  PetscCall(PetscLogEventRegister("SpecForwardFFT", TS_CLASSID, &EV_FORWARD));
  PetscCall(PetscLogEventRegister("SpecProjDirect", TS_CLASSID, &EV_DIRECT));
  PetscCall(PetscLogEventRegister("SpecMatVec", TS_CLASSID, &EV_MATVEC));
  PetscCall(PetscLogEventRegister("SpecOutput", TS_CLASSID, &EV_OUTPUT));
  PetscCall(PetscRegisterFinalize(SpecEventsReset));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Creation, options                                                                            */

/* The paper's fields: d = (exp(sin 64x) + exp(sin 256x))/4, a = exp((0.6 + 0.2 cos 3x)/(1 + 0.35 sin 64x + 0.35 sin 256x))/4, u0 = exp(-(x - pi)^2). */
static void PaperDefaults(VSHMMSpectral sp)
{
  sp->diff             = vs::Field();
  sp->diff.form        = vs::Field::Form::ExpSin;
  sp->diff.weights     = {0.25, 0.25};
  sp->diff.wavenumbers = {64, 256};

  sp->vel                         = vs::Field();
  sp->vel.form                    = vs::Field::Form::ExpRatio;
  sp->vel.scale                   = 0.25;
  sp->vel.numerator.offset        = 0.6;
  sp->vel.numerator.wavenumbers   = {3};
  sp->vel.numerator.cosines       = {0.2};
  sp->vel.denominator.offset      = 1.0;
  sp->vel.denominator.wavenumbers = {64, 256};
  sp->vel.denominator.sines       = {0.35, 0.35};

  sp->u0        = vs::Field();
  sp->u0.form   = vs::Field::Form::Gaussian;
  sp->u0.center = PETSC_PI;
  sp->u0.width  = 1.0;
}

/*@C
   VSHMMSpectralCreate - Creates a sparse spectral problem (a scene) with the defaults of the
   paper's diffusion example

   Collective

   Input Parameter:
.  comm - the communicator of the state Vec and the TS (the transforms are done redundantly on every rank)

   Output Parameter:
.  sp - the new object

   Level: beginner

.seealso: `VSHMMSpectralSetDefaultScene()`, `VSHMMSpectralSetFromOptions()`, `VSHMMSpectralDestroy()`
@*/
PetscErrorCode VSHMMSpectralCreate(MPI_Comm comm, VSHMMSpectral *sp)
{
  PetscFunctionBegin;
  PetscValidPointer(sp, 2);
  PetscCall(SpecRegisterEvents());
  *sp         = new _n_VSHMMSpectral();
  (*sp)->comm = comm;
  PetscCallMPI(MPI_Comm_size(comm, &(*sp)->size));
  PetscCallMPI(MPI_Comm_rank(comm, &(*sp)->rank));
  PaperDefaults(*sp);
  PetscCall(VSHMMSpectralSetDefaultScene(*sp, "diffusion"));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetDefaultScene - Sets the defaults of one of the paper's experiments; options
   read later by `VSHMMSpectralSetFromOptions()` override them

   Logically Collective

   Input Parameters:
+  sp    - the object
-  scene - "diffusion" (u_t = (d u_x)_x, N = 2048) or "advection" (u_t + a u_x = 0, N = 1024)

   Notes:
   Both use u0 = exp(-(x - pi)^2) and mode dns. Only the terms and N differ: the coefficient
   fields default to the paper's d and a whichever scene is chosen.

   Level: intermediate

.seealso: `VSHMMSpectralCreate()`, `VSHMMSpectralSetFromOptions()`
@*/
PetscErrorCode VSHMMSpectralSetDefaultScene(VSHMMSpectral sp, const char scene[])
{
  PetscFunctionBegin;
  const std::string s = scene ? scene : "";
  if (s == "diffusion") {
    sp->terms = {"diffusion"};
    sp->N     = 2048;
  } else if (s == "advection") {
    sp->terms = {"advection"};
    sp->N     = 1024;
  } else SETERRQ(sp->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown default scene '%s': use diffusion or advection", s.c_str());
  sp->scene = s;
  PetscFunctionReturn(0);
}

#define MAX_LIST 256

static PetscErrorCode FieldError(MPI_Comm comm, const char *name, const std::exception &e)
{
  SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "-%s: %s", name, e.what());
}

static PetscErrorCode ReadRealList(PetscOptionItems *PetscOptionsObject, const std::string &opt, const char *text, std::vector<double> &v)
{
  PetscReal vals[MAX_LIST];
  PetscInt  n = MAX_LIST;
  PetscBool set;

  PetscFunctionBegin;
  for (size_t i = 0; i < v.size() && i < MAX_LIST; ++i) vals[i] = v[i];
  PetscCall(PetscOptionsRealArray(opt.c_str(), text, "VSHMMSpectralSetFromOptions", vals, &n, &set));
  if (set) v.assign(vals, vals + n);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadSeries(PetscOptionItems *PetscOptionsObject, const std::string &p, vs::Series &s)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsReal((p + "_offset").c_str(), "constant term of the series", "VSHMMSpectralSetFromOptions", s.offset, &s.offset, NULL));
  PetscCall(ReadRealList(PetscOptionsObject, p + "_wavenumbers", "wavenumbers of the series", s.wavenumbers));
  PetscCall(ReadRealList(PetscOptionsObject, p + "_cos", "cosine coefficients, one per wavenumber", s.cosines));
  PetscCall(ReadRealList(PetscOptionsObject, p + "_sin", "sine coefficients, one per wavenumber", s.sines));
  PetscFunctionReturn(0);
}

/* Reads grid values "x u" (or "u") per line: the format written by -grid_solution_file. */
static PetscErrorCode ReadGridFile(MPI_Comm comm, const std::string &path, std::vector<double> &u)
{
  PetscFunctionBegin;
  std::ifstream in(path);
  PetscCheck(in, comm, PETSC_ERR_FILE_OPEN, "Cannot open the grid file '%s'", path.c_str());
  std::string line;
  u.clear();
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<double> vals;
    double              v;
    while (ls >> v) vals.push_back(v);
    if (vals.empty()) continue;
    PetscCheck(vals.size() <= 2, comm, PETSC_ERR_FILE_UNEXPECTED, "Grid file '%s': a line has %d numbers; expected 'x u' or 'u'", path.c_str(), (int)vals.size());
    u.push_back(vals.back());
  }
  PetscCheck(!u.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "Grid file '%s' has no values", path.c_str());
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadField(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const std::string &p, const char *what, vs::Field &f)
{
  char      form[64];
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(form, vs::Field::formName(f.form), sizeof(form)));
  PetscCall(PetscOptionsString(("-" + p).c_str(), what, "VSHMMSpectralSetFromOptions", form, form, sizeof(form), &set));
  try {
    f.form = vs::Field::formFromName(form);
  } catch (const std::exception &e) {
    PetscCall(FieldError(sp->comm, p.c_str(), e));
  }
  const std::string o = "-" + p;
  PetscCall(PetscOptionsReal((o + "_value").c_str(), "constant: the value", "", f.value, &f.value, NULL));
  PetscCall(PetscOptionsReal((o + "_offset").c_str(), "gaussian, expsin, fourier: constant added", "", f.offset, &f.offset, NULL));
  PetscCall(PetscOptionsReal((o + "_amplitude").c_str(), "gaussian: amplitude", "", f.amplitude, &f.amplitude, NULL));
  PetscCall(PetscOptionsReal((o + "_center").c_str(), "gaussian: center", "", f.center, &f.center, NULL));
  PetscCall(PetscOptionsReal((o + "_width").c_str(), "gaussian: width w in exp(-((x-c)/w)^2)", "", f.width, &f.width, NULL));
  PetscBool periodic = f.periodic ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscOptionsBool((o + "_periodic").c_str(), "gaussian: periodic distance to the center", "", periodic, &periodic, NULL));
  f.periodic = periodic;
  PetscCall(ReadRealList(PetscOptionsObject, o + "_weights", "expsin: weights w_i", f.weights));
  PetscCall(ReadRealList(PetscOptionsObject, o + "_wavenumbers", "expsin, fourier: wavenumbers k_i", f.form == vs::Field::Form::Fourier ? f.numerator.wavenumbers : f.wavenumbers));
  PetscCall(ReadRealList(PetscOptionsObject, o + "_amplitudes", "expsin: amplitudes s_i in exp(s_i sin(k_i x + p_i))", f.amplitudes));
  PetscCall(ReadRealList(PetscOptionsObject, o + "_phases", "expsin: phases p_i", f.phases));
  PetscCall(ReadRealList(PetscOptionsObject, o + "_cos", "fourier: cosine coefficients", f.numerator.cosines));
  PetscCall(ReadRealList(PetscOptionsObject, o + "_sin", "fourier: sine coefficients", f.numerator.sines));
  if (f.form == vs::Field::Form::Fourier) f.numerator.offset = f.offset;
  PetscCall(PetscOptionsReal((o + "_scale").c_str(), "exp_ratio: the factor s in s exp(num/den)", "", f.scale, &f.scale, NULL));
  PetscCall(ReadSeries(PetscOptionsObject, o + "_numerator", f.numerator));
  PetscCall(ReadSeries(PetscOptionsObject, o + "_denominator", f.denominator));
  char file[PETSC_MAX_PATH_LEN] = "";
  PetscCall(PetscOptionsString((o + "_file").c_str(), "samples: grid file of 'x value' lines (N lines)", "", file, file, sizeof(file), &set));
  if (f.form == vs::Field::Form::Samples) {
    PetscCheck(set && file[0], sp->comm, PETSC_ERR_ARG_WRONGSTATE, "-%s samples needs -%s_file <grid file>", p.c_str(), p.c_str());
    PetscCall(ReadGridFile(sp->comm, file, f.samples));
  }
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetFromOptions - Reads the scene and the run's options from the options database

   Collective

   Input Parameter:
.  sp - the object

   Options Database Keys (see docs/spectral.md for the field forms):
+  -N <n> - grid points (any n >= 4; FFTW is fastest for powers of two); -grid_points <n> is a synonym
.  -terms <diffusion,advection> - the terms of F(u); an unknown name is an error
.  -diffusion_coefficient <form> - d(x): constant, gaussian, expsin, fourier, exp_ratio, samples (+ -diffusion_coefficient_* parameters)
.  -velocity <form> - a(x), same forms (+ -velocity_* parameters)
.  -u0 <form> - the initial data, same forms (+ -u0_* parameters)
.  -mode <dns,sparse> - every mode, or the clusters' modes only
.  -clusters <0:3,62:66,...> - explicit clusters: ranges lo:hi or single k, joined by + within a cluster ("none": no explicit clusters)
.  -cluster_detect <none,initial,dns,file> - find the clusters by soft thresholding
.  -cluster_lambda <l> - shrinkage value (default 10^-2.5)
.  -cluster_normalization <unitary,series,dft> - scaling of the coefficients before thresholding
.  -cluster_gap <g> - at most g missing wavenumbers inside a cluster
.  -cluster_buffers <b0,b1,...> - buffer widths added around the clusters (one value or one per cluster)
.  -cluster_detect_times <t1,...> - snapshot times of the short DNS (-cluster_detect dns)
.  -cluster_detect_file <file> - grid file to threshold (-cluster_detect file)
.  -spectral_evaluation <fft,matrix> - pseudo-spectral with FFTW, or the dense operator on the retained modes
.  -spectral_projection <auto,fft,direct> - how a split gets its cluster's coefficients
.  -fftw_planner <estimate,measure,patient> - FFTW planning
.  -output_times <t1,t2,...> - times at which to stop, print the work and write the grid solution
.  -grid_solution_file <prefix> - write prefix_<t>.txt (N lines "x u(x)") at every output time
.  -compare_grid_solution <prefix> - print the relative L2 and max errors against prefix_<t>.txt at every output time
.  -compare_tolerance <tol> - and stop with an error if a relative L2 error exceeds tol
.  -spectrum_file <file> - write "t k |c_k|" blocks every -spectrum_interval
-  -no_timing - omit wall times from the output

   Level: beginner

.seealso: `VSHMMSpectralSetUp()`, `VSHMMSpectralSolve()`
@*/
PetscErrorCode VSHMMSpectralSetFromOptions(VSHMMSpectral sp)
{
  char      buf[PETSC_MAX_PATH_LEN];
  PetscBool set;
  PetscInt  e;

  PetscFunctionBegin;
  PetscOptionsBegin(sp->comm, NULL, "Sparse spectral scene (VSHMMSpectral)", "TS");
  PetscCall(PetscOptionsInt("-N", "grid points", "VSHMMSpectralSetFromOptions", sp->N, &sp->N, NULL));
  PetscCall(PetscOptionsInt("-grid_points", "grid points (synonym of -N)", "VSHMMSpectralSetFromOptions", sp->N, &sp->N, NULL));
  {
    char     *names[MAX_LIST];
    PetscInt  n = MAX_LIST;
    PetscCall(PetscOptionsStringArray("-terms", "terms of F(u): diffusion, advection", "VSHMMSpectralSetFromOptions", names, &n, &set));
    if (set) {
      sp->terms.clear();
      for (PetscInt i = 0; i < n; ++i) {
        sp->terms.push_back(names[i]);
        PetscCall(PetscFree(names[i]));
      }
    }
  }
  PetscCall(ReadField(PetscOptionsObject, sp, "diffusion_coefficient", "diffusion coefficient d(x) (form)", sp->diff));
  PetscCall(ReadField(PetscOptionsObject, sp, "velocity", "advection velocity a(x) (form)", sp->vel));
  PetscCall(ReadField(PetscOptionsObject, sp, "u0", "initial data u0(x) (form)", sp->u0));
  e = sp->mode;
  PetscCall(PetscOptionsEList("-mode", "dns: every mode; sparse: the clusters' modes", "VSHMMSpectralSetFromOptions", ModeNames, 2, ModeNames[e], &e, NULL));
  sp->mode = (SpectralMode)e;
  PetscCall(PetscStrncpy(buf, sp->cluster_spec.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString("-clusters", "explicit clusters, e.g. 0:3,62:66,192:193,255:257", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) {
    PetscCheck(buf[0], sp->comm, PETSC_ERR_ARG_WRONG, "-clusters is empty: give clusters as lo:hi ranges separated by commas, e.g. -clusters 0:3,62:66 (or -clusters none to drop explicit clusters)");
    sp->cluster_spec = std::string(buf) == "none" ? std::string() : std::string(buf);
  }
  e = sp->detect;
  PetscCall(PetscOptionsEList("-cluster_detect", "find the clusters by soft thresholding", "VSHMMSpectralSetFromOptions", DetectNames, 4, DetectNames[e], &e, NULL));
  sp->detect = (DetectKind)e;
  PetscCall(PetscOptionsReal("-cluster_lambda", "shrinkage value of the soft thresholding", "VSHMMSpectralSetFromOptions", sp->lambda, &sp->lambda, NULL));
  PetscCall(PetscStrncpy(buf, vs::normalizationName(sp->norm), sizeof(buf)));
  PetscCall(PetscOptionsString("-cluster_normalization", "unitary, series or dft", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), NULL));
  try {
    sp->norm = vs::normalizationFromName(buf);
  } catch (const std::exception &ex) {
    SETERRQ(sp->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-cluster_normalization: %s", ex.what());
  }
  PetscCall(PetscOptionsInt("-cluster_gap", "at most this many missing wavenumbers inside a cluster", "VSHMMSpectralSetFromOptions", sp->gap, &sp->gap, NULL));
  {
    PetscInt b[MAX_LIST], n = MAX_LIST;
    PetscCall(PetscOptionsIntArray("-cluster_buffers", "buffer widths around the clusters", "VSHMMSpectralSetFromOptions", b, &n, &set));
    if (set) sp->buffers.assign(b, b + n);
  }
  {
    std::vector<double> t(sp->detect_times.begin(), sp->detect_times.end());
    PetscCall(ReadRealList(PetscOptionsObject, "-cluster_detect_times", "snapshot times of the detection DNS", t));
    sp->detect_times.assign(t.begin(), t.end());
  }
  PetscCall(PetscOptionsReal("-cluster_detect_dt", "time step of the detection DNS (0: estimate)", "VSHMMSpectralSetFromOptions", sp->detect_dt, &sp->detect_dt, NULL));
  buf[0] = 0;
  PetscCall(PetscOptionsString("-cluster_detect_file", "grid file to threshold", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) sp->detect_file = buf;
  e = sp->evaluation;
  PetscCall(PetscOptionsEList("-spectral_evaluation", "fft or matrix", "VSHMMSpectralSetFromOptions", EvaluationNames, 2, EvaluationNames[e], &e, NULL));
  sp->evaluation = (EvaluationKind)e;
  e = sp->projection;
  PetscCall(PetscOptionsEList("-spectral_projection", "auto, fft or direct", "VSHMMSpectralSetFromOptions", ProjectionNames, 3, ProjectionNames[e], &e, NULL));
  sp->projection = (ProjectionKind)e;
  e = sp->planner;
  PetscCall(PetscOptionsEList("-fftw_planner", "FFTW planning rigour", "VSHMMSpectralSetFromOptions", PlannerNames, 3, PlannerNames[e], &e, NULL));
  sp->planner = (PlannerKind)e;
  {
    std::vector<double> t(sp->output_times.begin(), sp->output_times.end());
    PetscCall(ReadRealList(PetscOptionsObject, "-output_times", "times at which to print the work and write the grid solution", t));
    sp->output_times.assign(t.begin(), t.end());
  }
  buf[0] = 0;
  PetscCall(PetscOptionsString("-grid_solution_file", "prefix of the grid solution files PREFIX_<t>.txt", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) sp->grid_prefix = buf;
  buf[0] = 0;
  PetscCall(PetscOptionsString("-compare_grid_solution", "prefix of reference grid solutions PREFIX_<t>.txt to compare with", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) sp->compare_prefix = buf;
  PetscCall(PetscOptionsReal("-compare_tolerance", "stop with an error if the relative L2 error exceeds this (0: no check)", "VSHMMSpectralSetFromOptions", sp->compare_tol, &sp->compare_tol, NULL));
  buf[0] = 0;
  PetscCall(PetscOptionsString("-spectrum_file", "write t k |c_k| blocks to this file", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) sp->spectrum_file = buf;
  PetscCall(PetscOptionsReal("-spectrum_interval", "time between two spectra in -spectrum_file", "VSHMMSpectralSetFromOptions", sp->spectrum_interval, &sp->spectrum_interval, NULL));
  {
    PetscBool no_timing = sp->timing ? PETSC_FALSE : PETSC_TRUE;
    PetscCall(PetscOptionsBool("-no_timing", "omit wall times", "VSHMMSpectralSetFromOptions", no_timing, &no_timing, NULL));
    sp->timing = no_timing ? PETSC_FALSE : PETSC_TRUE;
  }
  PetscOptionsEnd();
  sp->setfromoptions_called = PETSC_TRUE;
  sp->setup                 = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Set-up                                                                                       */

static vs::Planner CorePlanner(PlannerKind p)
{
  return p == PLAN_ESTIMATE ? vs::Planner::Estimate : p == PLAN_PATIENT ? vs::Planner::Patient : vs::Planner::Measure;
}

/* The fields D = sum of diffusion coefficients, A = - sum of velocities, on the grid. */
static PetscErrorCode BuildCoefficients(VSHMMSpectral sp, std::vector<double> &D, std::vector<double> &A)
{
  PetscFunctionBegin;
  D.clear();
  A.clear();
  PetscCheck(!sp->terms.empty(), sp->comm, PETSC_ERR_ARG_WRONG, "-terms is empty: the scene needs at least one term, %s", KnownTerms);
  for (size_t i = 0; i < sp->terms.size(); ++i) {
    const std::string &t = sp->terms[i];
    for (size_t j = 0; j < i; ++j) PetscCheck(sp->terms[j] != t, sp->comm, PETSC_ERR_ARG_WRONG, "Term '%s' appears twice in -terms", t.c_str());
    if (t == "diffusion") {
      try {
        D = sp->diff.sample((int)sp->N);
      } catch (const std::exception &e) {
        PetscCall(FieldError(sp->comm, "diffusion_coefficient", e));
      }
    } else if (t == "advection") {
      try {
        A = sp->vel.sample((int)sp->N);
      } catch (const std::exception &e) {
        PetscCall(FieldError(sp->comm, "velocity", e));
      }
      for (double &a : A) a = -a;
    } else SETERRQ(sp->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown term '%s' in -terms: the known terms are %s", t.c_str(), KnownTerms);
  }
  PetscFunctionReturn(0);
}

struct DetectCtx {
  vs::SpectralOperator *op;
};

static PetscErrorCode DetectRHS(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  DetectCtx         *dc = (DetectCtx *)ctx;
  const PetscScalar *u;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  (void)ts;
  (void)t;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  dc->op->apply(u, f);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

static double NiceStep(double dt)
{
  const double p = std::pow(10.0, std::floor(std::log10(dt)));
  const double m = dt / p;
  return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
}

/* A stable explicit step for 3-stage Runge-Kutta: 1 / (max|d| kmax^2 + max|a| kmax), rounded down to 1, 2 or 5 times a power of ten. */
static double EstimateStep(const std::vector<double> &D, const std::vector<double> &A, int kmax)
{
  double md = 0, ma = 0;
  for (double d : D) md = std::max(md, std::fabs(d));
  for (double a : A) ma = std::max(ma, std::fabs(a));
  const double rho = md * kmax * (double)kmax + ma * kmax;
  return rho > 0 ? NiceStep(1.0 / rho) : 1e-2;
}

/* Snapshots |c_k| (k = 0..N/2) for the cluster detection. */
static PetscErrorCode DetectionSnapshots(VSHMMSpectral sp, const std::vector<double> &D, const std::vector<double> &A, std::vector<std::vector<double>> &mags)
{
  std::vector<double> u0;

  PetscFunctionBegin;
  mags.clear();
  if (sp->detect == DETECT_FILE) {
    std::vector<double> u;
    PetscCheck(!sp->detect_file.empty(), sp->comm, PETSC_ERR_ARG_WRONGSTATE, "-cluster_detect file needs -cluster_detect_file <grid file of N lines 'x u'>");
    PetscCall(ReadGridFile(sp->comm, sp->detect_file, u));
    PetscCheck((PetscInt)u.size() == sp->N, sp->comm, PETSC_ERR_ARG_SIZ, "-cluster_detect_file '%s' has %d values but N = %" PetscInt_FMT, sp->detect_file.c_str(), (int)u.size(), sp->N);
    mags.push_back(vs::coefficientMagnitudes(u));
    PetscFunctionReturn(0);
  }
  try {
    u0 = sp->u0.sample((int)sp->N);
  } catch (const std::exception &e) {
    PetscCall(FieldError(sp->comm, "u0", e));
  }
  if (sp->detect == DETECT_INITIAL) {
    mags.push_back(vs::coefficientMagnitudes(u0));
    PetscFunctionReturn(0);
  }
  /* a short direct simulation on every rank (PETSC_COMM_SELF), TS options prefix cluster_detect_ */
  std::vector<PetscReal> times = sp->detect_times;
  PetscCheck(!times.empty(), sp->comm, PETSC_ERR_ARG_WRONGSTATE, "-cluster_detect dns needs -cluster_detect_times t1,t2,...: the snapshot times of the short direct simulation");
  for (size_t i = 0; i < times.size(); ++i) PetscCheck(times[i] >= 0 && (i == 0 || times[i] > times[i - 1]), sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cluster_detect_times must be nonnegative and increasing");
  vs::Layout           full = vs::Layout::full((int)sp->N);
  vs::SpectralOperator op(full, D, A, vs::Planner::Estimate);
  DetectCtx            dc = {&op};
  Vec                  U;
  TS                   ts;
  PetscScalar         *u;
  const double         dt = sp->detect_dt > 0 ? sp->detect_dt : EstimateStep(D, A, vs::maxWavenumber((int)sp->N));

  PetscCall(VecCreateSeq(PETSC_COMM_SELF, full.size(), &U));
  PetscCall(VecGetArray(U, &u));
  op.analyze(u0.data(), u);
  PetscCall(VecRestoreArray(U, &u));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetOptionsPrefix(ts, "cluster_detect_"));
  PetscCall(TSSetRHSFunction(ts, NULL, DetectRHS, &dc));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRKSetType(ts, TSRK3));
  PetscCall(TSSetTimeStep(ts, dt));
  PetscCall(TSSetMaxSteps(ts, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(PetscPrintf(sp->comm, "cluster detection: direct simulation with %" PetscInt_FMT " modes, RK3 dt = %g, snapshots at", sp->N, dt));
  for (PetscReal t : times) PetscCall(PetscPrintf(sp->comm, " %g", (double)t));
  PetscCall(PetscPrintf(sp->comm, "\n"));
  for (PetscReal t : times) {
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
      m[k]        = vs::isRealOnly((int)sp->N, k) ? std::fabs(c[o]) : std::hypot(c[o], c[o + 1]);
    }
    PetscCall(VecRestoreArrayRead(U, &c));
    mags.push_back(m);
  }
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
  PetscFunctionReturn(0);
}

static PetscErrorCode FindClusters(VSHMMSpectral sp, const std::vector<double> &D, const std::vector<double> &A)
{
  PetscFunctionBegin;
  const bool explicit_clusters = !sp->cluster_spec.empty();
  PetscCheck(!(explicit_clusters && sp->detect != DETECT_NONE), sp->comm, PETSC_ERR_ARG_INCOMP, "Give either -clusters (explicit) or -cluster_detect %s, not both", DetectNames[sp->detect]);
  PetscCheck(explicit_clusters || sp->detect != DETECT_NONE, sp->comm, PETSC_ERR_ARG_WRONGSTATE,
             "-mode sparse needs clusters: give -clusters lo:hi,lo:hi,... (e.g. 0:3,62:66,192:193,255:257) or -cluster_detect initial|dns|file");
  if (explicit_clusters) {
    try {
      sp->clusters = vs::ClusterSet::parse(sp->cluster_spec, (int)sp->N);
      sp->clusters = vs::addBuffers(sp->clusters, sp->buffers);
    } catch (const std::exception &e) {
      SETERRQ(sp->comm, PETSC_ERR_ARG_WRONG, "-clusters %s: %s", sp->cluster_spec.c_str(), e.what());
    }
  } else {
    std::vector<std::vector<double>> mags;
    std::vector<int>                 support;
    PetscCheck(std::isfinite(sp->lambda) && sp->lambda >= 0, sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cluster_lambda must be finite and nonnegative, got %g", (double)sp->lambda);
    PetscCheck(sp->gap >= 0, sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cluster_gap must be nonnegative, got %" PetscInt_FMT, sp->gap);
    PetscCall(DetectionSnapshots(sp, D, A, mags));
    try {
      support = vs::thresholdSupport(mags, (int)sp->N, sp->lambda, sp->norm);
    } catch (const std::exception &e) {
      SETERRQ(sp->comm, PETSC_ERR_ARG_WRONG, "cluster detection: %s", e.what());
    }
    if (support.empty()) {
      double big = 0;
      int    kbig = 0;
      for (const auto &m : mags)
        for (size_t k = 0; k < m.size(); ++k)
          if (m[k] > big) big = m[k], kbig = (int)k;
      SETERRQ(sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "Soft thresholding with -cluster_lambda %g leaves no mode: the largest %s-normalised coefficient is %g (k = %d); lower -cluster_lambda", (double)sp->lambda, vs::normalizationName(sp->norm),
              big * vs::normalizationFactor(sp->norm, (int)sp->N), kbig);
    }
    try {
      sp->clusters = vs::mergeIntoClusters(support, (int)sp->N, (int)sp->gap);
      PetscCall(PetscPrintf(sp->comm, "cluster detection: lambda %g (%s normalisation), gap %" PetscInt_FMT ": %d wavenumbers retained in %d clusters\n", (double)sp->lambda, vs::normalizationName(sp->norm), sp->gap, (int)support.size(), (int)sp->clusters.size()));
      sp->clusters = vs::addBuffers(sp->clusters, sp->buffers);
    } catch (const std::exception &e) {
      SETERRQ(sp->comm, PETSC_ERR_ARG_WRONG, "cluster detection: %s", e.what());
    }
  }
  if (sp->clusters.sortByLowest()) PetscCall(PetscPrintf(sp->comm, "note: clusters reordered by their lowest wavenumber (slowest first)\n"));
  PetscFunctionReturn(0);
}

/* -spectral_projection auto: measures how many modes a direct projection handles in the time of
   one r2c transform on this machine (the same value on every rank: the smallest). */
static PetscErrorCode CalibrateProjection(VSHMMSpectral sp)
{
  PetscFunctionBegin;
  if (sp->mode != MODE_SPARSE || sp->dense || sp->projection != PROJ_AUTO) PetscFunctionReturn(0);
  std::vector<double> zero(sp->layout->size(), 0.0), out(sp->layout->size());
  const int           R = 16;
  double              best_f = PETSC_MAX_REAL, best_d = PETSC_MAX_REAL;
  PetscLogDouble      t0, t1;

  sp->op->computePhysical(zero.data());
  sp->op->projectDirect(0, 1, out.data()); /* builds the mode's table */
  for (int trial = 0; trial < 3; ++trial) {
    PetscCall(PetscTime(&t0));
    for (int r = 0; r < R; ++r) sp->op->computeForward();
    PetscCall(PetscTime(&t1));
    best_f = PetscMin(best_f, (t1 - t0) / R);
    PetscCall(PetscTime(&t0));
    for (int r = 0; r < R; ++r) sp->op->projectDirect(0, 1, out.data());
    PetscCall(PetscTime(&t1));
    best_d = PetscMin(best_d, (t1 - t0) / R);
  }
  double ratio = best_d > 0 ? best_f / best_d : sp->op->directModesPerForward();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ratio, 1, MPI_DOUBLE, MPI_MIN, sp->comm));
  sp->op->setDirectModesPerForward(ratio);
  sp->op->counters() = vs::SpectralOperator::Counters();
  PetscCall(PetscInfo(NULL, "VSHMMSpectral: one r2c of N = %d takes %g s, a direct projection of one mode %g s: direct projections for up to %g modes per state\n", (int)sp->N, best_f, best_d, ratio));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetUp - Samples the fields, finds the clusters (explicit or detected), builds the
   layout of the state and the FFTW plans

   Collective

   Input Parameter:
.  sp - the object

   Notes:
   Prints the clusters. Errors name the option at fault: unknown term, empty or overlapping
   cluster lists, wavenumbers above N/2, thresholds that leave no mode, bad field parameters.

   Level: beginner

.seealso: `VSHMMSpectralSetFromOptions()`, `VSHMMSpectralSetUpTS()`
@*/
PetscErrorCode VSHMMSpectralSetUp(VSHMMSpectral sp)
{
  std::vector<double> D, A;

  PetscFunctionBegin;
  if (sp->setup) PetscFunctionReturn(0);
  PetscCheck(sp->N >= 4, sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-N %" PetscInt_FMT " is too small: the grid needs at least 4 points", sp->N);
  PetscCheck(sp->N <= (1 << 26), sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-N %" PetscInt_FMT " is too large", sp->N);
  PetscCall(BuildCoefficients(sp, D, A));
  try {
    (void)sp->u0.sample((int)sp->N);
  } catch (const std::exception &e) {
    PetscCall(FieldError(sp->comm, "u0", e));
  }
  if (sp->mode == MODE_SPARSE) {
    PetscCall(FindClusters(sp, D, A));
    sp->layout = std::make_unique<vs::Layout>(sp->clusters);
  } else {
    if (!sp->cluster_spec.empty() || sp->detect != DETECT_NONE) PetscCall(PetscPrintf(sp->comm, "note: -mode dns uses every wavenumber; -clusters and -cluster_detect are not used\n"));
    sp->layout   = std::make_unique<vs::Layout>(vs::Layout::full((int)sp->N));
    sp->clusters = vs::ClusterSet();
  }
  try {
    sp->op = std::make_unique<vs::SpectralOperator>(*sp->layout, D, A, CorePlanner(sp->planner));
  } catch (const std::exception &e) {
    SETERRQ(sp->comm, PETSC_ERR_LIB, "Spectral operator: %s", e.what());
  }
  sp->dense.reset();
  if (sp->evaluation == EVAL_MATRIX) {
    PetscCheck(sp->layout->size() <= 8192, sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-spectral_evaluation matrix: %d retained coefficients are too many for a dense operator (at most 8192)", sp->layout->size());
    sp->dense = std::make_unique<vs::DenseOperator>(*sp->op);
  }
  sp->cluster_modes.clear();
  for (int j = 0; j < sp->layout->clusterCount(); ++j) {
    std::vector<PetscInt> m;
    for (int i = sp->layout->clusterModeBegin(j); i < sp->layout->clusterModeEnd(j); ++i) m.push_back(sp->layout->mode(i));
    sp->cluster_modes.push_back(m);
  }
  sp->out.assign(sp->layout->size(), 0.0);
  PetscCall(CalibrateProjection(sp));
  sp->cache_valid = PETSC_FALSE;
  sp->stats       = VSHMMSpectralStatistics();
  sp->setup       = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralView - Prints the scene: grid, terms and fields, initial data, mode, clusters, evaluation

   Collective

   Input Parameters:
+  sp     - the object (set up)
-  viewer - an ASCII viewer (NULL: stdout of the object's communicator)

   Level: beginner

.seealso: `VSHMMSpectralSetUp()`
@*/
PetscErrorCode VSHMMSpectralView(VSHMMSpectral sp, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(sp->comm);
  PetscCall(PetscViewerASCIIPrintf(viewer, "scene: N = %" PetscInt_FMT " grid points on [0, 2 pi), wavenumbers 0..%d\n", sp->N, vs::maxWavenumber((int)sp->N)));
  for (const std::string &t : sp->terms) {
    if (t == "diffusion") PetscCall(PetscViewerASCIIPrintf(viewer, "  term diffusion: u_t += (d u_x)_x, d = %s\n", sp->diff.describe().c_str()));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "  term advection: u_t += -a u_x, a = %s\n", sp->vel.describe().c_str()));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "  u0 = %s\n", sp->u0.describe().c_str()));
  if (sp->mode == MODE_DNS) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "mode dns: every wavenumber, %d coefficients\n", sp->layout->size()));
  } else {
    PetscCall(PetscViewerASCIIPrintf(viewer, "mode sparse: %d wavenumbers (%d coefficients) in %d clusters, one RHS split each (slowest first)\n", sp->layout->modeCount(), sp->layout->size(), sp->layout->clusterCount()));
    for (int j = 0; j < sp->layout->clusterCount(); ++j) {
      std::vector<int> m(sp->cluster_modes[j].begin(), sp->cluster_modes[j].end());
      PetscCall(PetscViewerASCIIPrintf(viewer, "  K%d = {%s}: %d wavenumbers, coefficients %d..%d\n", j, vs::formatModes(m).c_str(), (int)m.size(), sp->layout->clusterOffsetBegin(j), sp->layout->clusterOffsetEnd(j) - 1));
    }
  }
  if (sp->evaluation == EVAL_MATRIX) PetscCall(PetscViewerASCIIPrintf(viewer, "evaluation: dense operator on the retained modes (%d x %d)\n", sp->layout->size(), sp->layout->size()));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "evaluation: pseudo-spectral with FFTW (%s planner), cluster projection %s\n", PlannerNames[sp->planner], ProjectionNames[sp->projection]));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetSizes - Grid points, retained coefficients (the Vec size) and clusters

   Not Collective

   Input Parameter:
.  sp - the object (set up)

   Output Parameters:
+  N         - grid points
.  ncoef     - reals in the state Vec
-  nclusters - clusters (0 in mode dns)

   Level: intermediate

.seealso: `VSHMMSpectralGetCluster()`
@*/
PetscErrorCode VSHMMSpectralGetSizes(VSHMMSpectral sp, PetscInt *N, PetscInt *ncoef, PetscInt *nclusters)
{
  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  if (N) *N = sp->N;
  if (ncoef) *ncoef = sp->layout->size();
  if (nclusters) *nclusters = sp->mode == MODE_SPARSE ? sp->layout->clusterCount() : 0;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetCluster - The wavenumbers of cluster j and its range in the state Vec

   Not Collective

   Input Parameters:
+  sp - the object (set up, mode sparse)
-  j  - the cluster, 0 (slowest) .. nclusters-1

   Output Parameters:
+  nmodes - number of wavenumbers
.  modes  - the wavenumbers (ascending; owned by sp)
.  begin  - first entry of the cluster in the state Vec
-  end    - one past its last entry

   Level: intermediate

.seealso: `VSHMMSpectralGetSizes()`
@*/
PetscErrorCode VSHMMSpectralGetCluster(VSHMMSpectral sp, PetscInt j, PetscInt *nmodes, const PetscInt *modes[], PetscInt *begin, PetscInt *end)
{
  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCheck(j >= 0 && j < (PetscInt)sp->cluster_modes.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Cluster %" PetscInt_FMT " does not exist", j);
  if (nmodes) *nmodes = (PetscInt)sp->cluster_modes[j].size();
  if (modes) *modes = sp->cluster_modes[j].data();
  if (begin) *begin = sp->layout->clusterOffsetBegin((int)j);
  if (end) *end = sp->layout->clusterOffsetEnd((int)j);
  PetscFunctionReturn(0);
}

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
  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(VecCreate(sp->comm, U));
  PetscCall(VecSetSizes(*U, PETSC_DECIDE, sp->layout->size()));
  PetscCall(VecSetFromOptions(*U));
  if (sp->size > 1 && !sp->gather) PetscCall(VecScatterCreateToAll(*U, &sp->gather, &sp->Useq));
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
  PetscCall(VSHMMSpectralSetUp(sp));
  try {
    u = sp->u0.sample((int)sp->N);
  } catch (const std::exception &e) {
    PetscCall(FieldError(sp->comm, "u0", e));
  }
  c.resize(sp->layout->size());
  sp->op->analyze(u.data(), c.data());
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  PetscCall(VecGetArray(U, &x));
  for (PetscInt i = lo; i < hi; ++i) x[i - lo] = c[i];
  PetscCall(VecRestoreArray(U, &x));
  PetscFunctionReturn(0);
}

/* The whole state on every rank: the Vec's own array on one rank, a gathered copy otherwise. */
static PetscErrorCode GetCoefficients(VSHMMSpectral sp, Vec U, const PetscScalar **c)
{
  PetscFunctionBegin;
  if (sp->size == 1) PetscCall(VecGetArrayRead(U, c));
  else {
    if (!sp->gather) PetscCall(VecScatterCreateToAll(U, &sp->gather, &sp->Useq));
    PetscCall(VecScatterBegin(sp->gather, U, sp->Useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sp->gather, U, sp->Useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(sp->Useq, c));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreCoefficients(VSHMMSpectral sp, Vec U, const PetscScalar **c)
{
  PetscFunctionBegin;
  if (sp->size == 1) PetscCall(VecRestoreArrayRead(U, c));
  else PetscCall(VecRestoreArrayRead(sp->Useq, c));
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

.seealso: `VSHMMSpectralSolve()`
@*/
PetscErrorCode VSHMMSpectralGetGridValues(VSHMMSpectral sp, Vec U, PetscReal u[])
{
  const PetscScalar *c;

  PetscFunctionBegin;
  PetscCall(GetCoefficients(sp, U, &c));
  sp->op->synthesize(c, u);
  PetscCall(RestoreCoefficients(sp, U, &c));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Right-hand sides                                                                             */

/* u_x and its products with the fields for the state (U, t), unless they are those of the last call. */
static PetscErrorCode EnsurePhysical(VSHMMSpectral sp, Vec U, PetscReal t)
{
  PetscObjectId      id;
  PetscObjectState   state;
  const PetscScalar *c;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetId((PetscObject)U, &id));
  PetscCall(PetscObjectStateGet((PetscObject)U, &state));
  if (sp->cache_valid && id == sp->cache_id && state == sp->cache_state && t == sp->cache_t) {
    sp->stats.cache_hits++;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(EV_PHYSICAL, 0, 0, 0, 0));
  PetscCall(GetCoefficients(sp, U, &c));
  sp->op->computePhysical(c);
  PetscCall(RestoreCoefficients(sp, U, &c));
  PetscCall(PetscLogFlops(2.5 * sp->N * std::log2((double)sp->N) + 2.0 * sp->N));
  PetscCall(PetscLogEventEnd(EV_PHYSICAL, 0, 0, 0, 0));
  sp->stats.inverse_ffts++;
  sp->cache_valid  = PETSC_TRUE;
  sp->cache_id     = id;
  sp->cache_state  = state;
  sp->cache_t      = t;
  sp->fft_done     = PETSC_FALSE;
  sp->direct_spent = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode EnsureForward(VSHMMSpectral sp)
{
  PetscFunctionBegin;
  if (sp->fft_done) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(EV_FORWARD, 0, 0, 0, 0));
  sp->op->computeForward();
  const int kinds = (sp->op->hasDiffusion() ? 1 : 0) + (sp->op->hasAdvection() ? 1 : 0);
  PetscCall(PetscLogFlops(kinds * 2.5 * sp->N * std::log2((double)sp->N)));
  PetscCall(PetscLogEventEnd(EV_FORWARD, 0, 0, 0, 0));
  sp->stats.forward_ffts += kinds;
  sp->fft_done = PETSC_TRUE;
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
  VSHMMSpectral sp = (VSHMMSpectral)ctx;
  const int     n  = sp->layout->size();

  PetscFunctionBegin;
  (void)ts;
  PetscCall(PetscLogEventBegin(EV_RHS, 0, 0, 0, 0));
  sp->stats.rhs_calls++;
  sp->stats.field_evaluations++;
  if (sp->dense) {
    const PetscScalar *c;
    PetscCall(PetscLogEventBegin(EV_MATVEC, 0, 0, 0, 0));
    PetscCall(GetCoefficients(sp, U, &c));
    sp->dense->applyRows(0, n, c, sp->out.data());
    PetscCall(RestoreCoefficients(sp, U, &c));
    PetscCall(PetscLogFlops(2.0 * n * n));
    PetscCall(PetscLogEventEnd(EV_MATVEC, 0, 0, 0, 0));
  } else {
    PetscCall(EnsurePhysical(sp, U, t));
    PetscCall(EnsureForward(sp));
    sp->op->extractForward(0, sp->layout->modeCount(), sp->out.data());
  }
  PetscCall(WriteRange(F, 0, n, sp->out.data(), false));
  PetscCall(PetscLogEventEnd(EV_RHS, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Split j: P_j F (the right-hand side projected on cluster j) in every entry, zeros outside cluster j. */
static PetscErrorCode SplitRHS(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  SplitCtx     *sc = (SplitCtx *)ctx;
  VSHMMSpectral sp = sc->sp;
  const int     j = (int)sc->j, mb = sp->layout->clusterModeBegin(j), me = sp->layout->clusterModeEnd(j);
  const int     ob = sp->layout->clusterOffsetBegin(j), oe = sp->layout->clusterOffsetEnd(j);

  PetscFunctionBegin;
  (void)ts;
  PetscCall(PetscLogEventBegin(EV_SPLIT, 0, 0, 0, 0));
  sp->stats.split_calls++;
  if (j == 0) sp->stats.field_evaluations++;
  if (sp->dense) {
    const PetscScalar *c;
    PetscCall(PetscLogEventBegin(EV_MATVEC, 0, 0, 0, 0));
    PetscCall(GetCoefficients(sp, U, &c));
    sp->dense->applyRows(ob, oe, c, sp->out.data());
    PetscCall(RestoreCoefficients(sp, U, &c));
    PetscCall(PetscLogFlops(2.0 * (oe - ob) * sp->layout->size()));
    PetscCall(PetscLogEventEnd(EV_MATVEC, 0, 0, 0, 0));
  } else {
    PetscCall(EnsurePhysical(sp, U, t));
    bool direct = false;
    if (!sp->fft_done) {
      if (sp->projection == PROJ_DIRECT) direct = true;
      else if (sp->projection == PROJ_AUTO) direct = sp->direct_spent + (me - mb) <= sp->op->directModesPerForward();
    }
    if (direct) {
      PetscCall(PetscLogEventBegin(EV_DIRECT, 0, 0, 0, 0));
      sp->op->projectDirect(mb, me, sp->out.data(), ob);
      const int kinds = (sp->op->hasDiffusion() ? 1 : 0) + (sp->op->hasAdvection() ? 1 : 0);
      PetscCall(PetscLogFlops(4.0 * kinds * (me - mb) * sp->N));
      PetscCall(PetscLogEventEnd(EV_DIRECT, 0, 0, 0, 0));
      sp->direct_spent += me - mb;
      sp->stats.direct_modes += me - mb;
    } else {
      PetscCall(EnsureForward(sp));
      sp->op->extractForward(mb, me, sp->out.data(), ob);
    }
  }
  PetscCall(WriteRange(F, ob, oe, sp->out.data(), true));
  PetscCall(PetscLogEventEnd(EV_SPLIT, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetUpTS - Gives the TS the full right-hand side and, in mode sparse, one additive
   RHS split per cluster ("K0" slowest, "K1", ...)

   Collective

   Input Parameters:
+  sp - the object
-  ts - the TS

   Notes:
   Split j returns P_j F, the right-hand side projected on cluster j, in every entry of a
   full-size vector (zeros outside cluster j): the splits add up to the full right-hand side.
   The physical-space field of a state is computed once and shared by the splits called with
   that state (same Vec, object state and time), as TSVSHMM does on each level.

   Level: beginner

.seealso: `VSHMMSpectralSolve()`, `TSRHSSplitSetIS()`
@*/
PetscErrorCode VSHMMSpectralSetUpTS(VSHMMSpectral sp, TS ts)
{
  Vec      U;
  PetscInt lo, hi;

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(TSSetRHSFunction(ts, NULL, VSHMMSpectralRHSFunction, sp));
  if (sp->mode != MODE_SPARSE) PetscFunctionReturn(0);
  PetscCall(TSGetSolution(ts, &U));
  PetscCheck(U, sp->comm, PETSC_ERR_ARG_WRONGSTATE, "VSHMMSpectralSetUpTS(): call TSSetSolution() first");
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  sp->split_ctx.assign(sp->layout->clusterCount(), SplitCtx{sp, 0});
  for (int j = 0; j < sp->layout->clusterCount(); ++j) {
    IS   is;
    char name[32];
    sp->split_ctx[j].j = j;
    PetscCall(PetscSNPrintf(name, sizeof(name), "K%d", j));
    PetscCall(ISCreateStride(sp->comm, hi - lo, lo, 1, &is));
    PetscCall(TSRHSSplitSetIS(ts, name, is));
    PetscCall(TSRHSSplitSetRHSFunction(ts, name, NULL, SplitRHS, &sp->split_ctx[j]));
    PetscCall(ISDestroy(&is));
  }
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralEstimateTimeStep - A stable step of a 3-stage explicit Runge-Kutta method for the
   retained modes: 1 / (max|d| kmax^2 + max|a| kmax), rounded down to 1, 2 or 5 times a power of 10

   Not Collective

   Input Parameter:
.  sp - the object

   Output Parameter:
.  dt - the step

   Level: intermediate

.seealso: `VSHMMSpectralSetUp()`
@*/
PetscErrorCode VSHMMSpectralEstimateTimeStep(VSHMMSpectral sp, PetscReal *dt)
{
  std::vector<double> D, A;

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(BuildCoefficients(sp, D, A));
  *dt = EstimateStep(D, A, sp->layout->modes().back());
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Solve with the output contract                                                               */

static PetscErrorCode SpectrumMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  VSHMMSpectral      sp = (VSHMMSpectral)ctx;
  const PetscScalar *c;

  PetscFunctionBeginUser;
  (void)ts;
  (void)step;
  if (t < sp->next_spectrum - 1e-9 * sp->spectrum_interval) PetscFunctionReturn(0);
  while (sp->next_spectrum <= t + 1e-9 * sp->spectrum_interval) sp->next_spectrum += sp->spectrum_interval;
  PetscCall(GetCoefficients(sp, U, &c));
  if (sp->rank == 0) {
    for (int i = 0; i < sp->layout->modeCount(); ++i) {
      const int k = sp->layout->mode(i), o = sp->layout->offset(i);
      const double m = vs::isRealOnly((int)sp->N, k) ? std::fabs(c[o]) : std::hypot(c[o], c[o + 1]);
      std::fprintf(sp->spectrum_fp, "%.10g %d %.6e\n", (double)t, k, m);
    }
    std::fprintf(sp->spectrum_fp, "\n");
  }
  PetscCall(RestoreCoefficients(sp, U, &c));
  PetscFunctionReturn(0);
}

static PetscErrorCode PrintWork(VSHMMSpectral sp, const char *what, PetscReal t, double wall, const char *file)
{
  char line[PETSC_MAX_PATH_LEN + 512];
  int  len;

  PetscFunctionBegin;
  /* C's %g (PetscPrintf would print 1 as "1.") */
  len = std::snprintf(line, sizeof(line), "%s t %g rhs_evaluations %lld split_evaluations %lld inverse_ffts %lld forward_ffts %lld direct_modes %lld", what, (double)t, (long long)sp->stats.field_evaluations, (long long)sp->stats.split_calls,
                      (long long)sp->stats.inverse_ffts, (long long)sp->stats.forward_ffts, (long long)sp->stats.direct_modes);
  if (sp->timing && len > 0 && len < (int)sizeof(line)) len += std::snprintf(line + len, sizeof(line) - len, " wall_time %.4e", wall);
  if (file && len > 0 && len < (int)sizeof(line)) len += std::snprintf(line + len, sizeof(line) - len, " file %s", file);
  PetscCall(PetscPrintf(sp->comm, "%s\n", line));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSolve - Runs the TS to each output time, printing the work done so far and writing
   the grid solution there

   Collective

   Input Parameters:
+  sp - the object
.  ts - the TS (set up with `VSHMMSpectralSetUpTS()` and `TSSetFromOptions()`)
-  U  - the state, initial condition on entry

   Notes:
   With -output_times t1,t2,... the TS stops on each t_i (TS_EXACTFINALTIME_MATCHSTEP: the last
   step, or TSVSHMM's last macro step, is shortened) and the run prints one line per time:
$    output t <t> rhs_evaluations <n> split_evaluations <n> inverse_ffts <n> forward_ffts <n> direct_modes <n> wall_time <s> [file <name>]
   counted from the start of the solve. With -grid_solution_file PREFIX it writes PREFIX_<t>.txt
   (<t> printed with %g): N lines "x_j u(x_j)", x_j = 2 pi j/N. Without -output_times it runs to
   the TS's final time and treats that as the only output time. The TS's time step is restored
   before each segment.

   Level: beginner

.seealso: `VSHMMSpectralSetUpTS()`
@*/
PetscErrorCode VSHMMSpectralSolve(VSHMMSpectral sp, TS ts, Vec U)
{
  std::vector<PetscReal> times = sp->output_times;
  PetscReal              t0, dt0, tf;
  PetscLogDouble         w0, w1;

  PetscFunctionBegin;
  PetscCall(VSHMMSpectralSetUp(sp));
  PetscCall(TSGetTime(ts, &t0));
  PetscCall(TSGetTimeStep(ts, &dt0));
  if (times.empty()) {
    PetscCall(TSGetMaxTime(ts, &tf));
    times.push_back(tf);
  }
  for (size_t i = 0; i < times.size(); ++i)
    PetscCheck(std::isfinite(times[i]) && times[i] > t0 && (i == 0 || times[i] > times[i - 1]), sp->comm, PETSC_ERR_ARG_OUTOFRANGE, "-output_times must be increasing and after the initial time %g; item %d is %g", (double)t0, (int)i + 1, (double)times[i]);
  if (!sp->spectrum_file.empty()) {
    if (sp->rank == 0) {
      sp->spectrum_fp = std::fopen(sp->spectrum_file.c_str(), "w");
      PetscCheck(sp->spectrum_fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot open -spectrum_file %s", sp->spectrum_file.c_str());
      std::fprintf(sp->spectrum_fp, "# t k |c_k| (Fourier series coefficients; unitary DFT magnitude = sqrt(N) |c_k|, N = %d)\n", (int)sp->N);
    }
    sp->next_spectrum = t0;
    PetscCall(SpectrumMonitor(ts, 0, t0, U, sp));
    PetscCall(TSMonitorSet(ts, SpectrumMonitor, sp, NULL));
  }
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  std::vector<PetscReal> u((size_t)sp->N);
  PetscCall(PetscTime(&w0));
  for (PetscReal ti : times) {
    PetscReal          t;
    TSConvergedReason  reason;
    char               file[PETSC_MAX_PATH_LEN] = "";

    PetscCall(TSSetMaxTime(ts, ti));
    PetscCall(TSSetTimeStep(ts, dt0));
    PetscCall(TSSolve(ts, U));
    PetscCall(TSGetSolveTime(ts, &t));
    PetscCall(TSGetConvergedReason(ts, &reason));
    PetscCheck(reason >= 0, sp->comm, PETSC_ERR_NOT_CONVERGED, "The TS diverged (%s) at t = %g before the output time %g", TSConvergedReasons[reason], (double)t, (double)ti);
    PetscCheck(std::fabs(t - ti) <= 1e-9 * PetscMax(1.0, std::fabs(ti)), sp->comm, PETSC_ERR_NOT_CONVERGED, "The TS stopped at t = %.12g, not at the output time %g (%s; raise -ts_max_steps?)", (double)t, (double)ti, TSConvergedReasons[reason]);
    PetscCall(PetscTime(&w1));
    {
      PetscReal norm;
      PetscCall(VecNorm(U, NORM_2, &norm));
      PetscCheck(std::isfinite(norm), sp->comm, PETSC_ERR_FP, "The solution at t = %g is not finite (Inf or NaN): the time step is probably too large for the fastest retained mode (see VSHMMSpectralEstimateTimeStep(); -ts_dt, -ts_vshmm_micro_dt, -ts_vshmm_savings_factors)", (double)ti);
    }
    PetscCall(PetscLogEventBegin(EV_OUTPUT, 0, 0, 0, 0));
    if (!sp->grid_prefix.empty()) {
      PetscCall(VSHMMSpectralGetGridValues(sp, U, u.data()));
      std::snprintf(file, sizeof(file), "%s_%g.txt", sp->grid_prefix.c_str(), (double)ti); /* C's %g, not PETSc's */
      if (sp->rank == 0) {
        FILE *fp = std::fopen(file, "w");
        PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot open the grid solution file %s", file);
        for (PetscInt j = 0; j < sp->N; ++j) std::fprintf(fp, "%.17g %.17g\n", vs::gridPoint((int)sp->N, (int)j), (double)u[j]);
        PetscCheck(std::fclose(fp) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write the grid solution file %s", file);
      }
    }
    PetscCall(PetscLogEventEnd(EV_OUTPUT, 0, 0, 0, 0));
    PetscCall(PrintWork(sp, "output", ti, w1 - w0, file[0] ? file : NULL));
    if (!sp->compare_prefix.empty()) {
      std::vector<double> ref;
      char                name[PETSC_MAX_PATH_LEN], line[256];
      double              e2 = 0, r2 = 0, emax = 0;

      PetscCall(VSHMMSpectralGetGridValues(sp, U, u.data()));
      std::snprintf(name, sizeof(name), "%s_%g.txt", sp->compare_prefix.c_str(), (double)ti);
      PetscCall(ReadGridFile(sp->comm, name, ref));
      PetscCheck((PetscInt)ref.size() == sp->N, sp->comm, PETSC_ERR_ARG_SIZ, "-compare_grid_solution: %s has %d values, the grid has N = %" PetscInt_FMT, name, (int)ref.size(), sp->N);
      for (PetscInt j = 0; j < sp->N; ++j) {
        const double d = u[j] - ref[j];
        e2 += d * d;
        r2 += ref[j] * ref[j];
        if (!(std::fabs(d) <= emax)) emax = std::fabs(d); /* keeps a NaN */
      }
      std::snprintf(line, sizeof(line), "compare t %g relative_l2_error %.3e max_error %.3e", (double)ti, std::sqrt(e2 / (r2 > 0 ? r2 : 1.0)), emax);
      PetscCall(PetscPrintf(sp->comm, "%s\n", line));
      PetscCheck(sp->compare_tol <= 0 || std::sqrt(e2 / (r2 > 0 ? r2 : 1.0)) <= sp->compare_tol, /* false for NaN */ sp->comm, PETSC_ERR_NOT_CONVERGED, "The relative L2 error %.3e against %s exceeds -compare_tolerance %g", std::sqrt(e2 / (r2 > 0 ? r2 : 1.0)), name, (double)sp->compare_tol);
    }
  }
  if (sp->spectrum_fp) {
    std::fclose(sp->spectrum_fp);
    sp->spectrum_fp = nullptr;
  }
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetStatistics - The work counted since set-up

   Not Collective

   Input Parameter:
.  sp - the object

   Output Parameter:
.  stats - the counts

   Level: intermediate

.seealso: `VSHMMSpectralStatistics`
@*/
PetscErrorCode VSHMMSpectralGetStatistics(VSHMMSpectral sp, VSHMMSpectralStatistics *stats)
{
  PetscFunctionBegin;
  *stats = sp->stats;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralDestroy - Destroys the object

   Collective

   Input Parameter:
.  sp - the object

   Level: beginner

.seealso: `VSHMMSpectralCreate()`
@*/
PetscErrorCode VSHMMSpectralDestroy(VSHMMSpectral *sp)
{
  PetscFunctionBegin;
  if (!sp || !*sp) PetscFunctionReturn(0);
  PetscCall(VecScatterDestroy(&(*sp)->gather));
  PetscCall(VecDestroy(&(*sp)->Useq));
  if ((*sp)->spectrum_fp) std::fclose((*sp)->spectrum_fp);
  delete *sp;
  *sp = nullptr;
  PetscFunctionReturn(0);
}
