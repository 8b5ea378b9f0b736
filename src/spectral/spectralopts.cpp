/*
  VSHMMSpectralSetFromOptions(): the scene read from the options database with PETSc's readers,
  every option named -[prefix]spectral_<name>. Values are checked after reading; lists take as
  many values as the user gives.
*/
#include "spectralimpl.hpp"

#include <cmath>
#include <functional>

static const char *const FieldForms[] = {"constant", "gaussian", "expsin", "fourier", "exp_ratio", "samples", "VSHMMSpectralFieldForm", "", nullptr};
static const char *const KnownTerms   = "diffusion (d/dx(d(x) du/dx), field -spectral_diffusion_coefficient) and advection (-a(x) du/dx, field -spectral_velocity)";

/* The number of values given for a list option (0 if it is absent). PETSc's array readers stop
   silently at the capacity they are given, so the capacity is doubled until the list fits. */
static PetscErrorCode ListLength(const std::function<PetscErrorCode(PetscInt, PetscInt *, PetscBool *)> &get, PetscInt *length)
{
  PetscFunctionBegin;
  for (PetscInt capacity = 16;; capacity *= 2) {
    PetscInt  n = capacity;
    PetscBool set;

    PetscCall(get(capacity, &n, &set));
    *length = set ? n : 0;
    if (!set || n < capacity) break;
  }
  PetscFunctionReturn(0);
}

/* A real or integer list of any length (PETSc's integer ranges a-b included): sized with get
   (PetscOptionsGetRealArray/IntArray), then read with read (PetscOptionsRealArray/IntArray) for
   -help. v holds the default on entry and the values given on return. */
template <typename T>
static PetscErrorCode OptionsList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<T> &v, PetscBool *set, PetscErrorCode (*get)(PetscOptions, const char[], const char[], T[], PetscInt *, PetscBool *),
                                  PetscErrorCode (*read)(PetscOptionItems *, const char[], const char[], const char[], T[], PetscInt *, PetscBool *))
{
  PetscInt       length, n;
  std::vector<T> buf;

  PetscFunctionBegin;
  PetscCall(ListLength(
    [&](PetscInt capacity, PetscInt *m, PetscBool *flg) {
      buf.resize(capacity);
      return get(((PetscObject)sp)->options, ((PetscObject)sp)->prefix, opt, buf.data(), m, flg);
    },
    &length));
  buf = v;
  buf.resize(PetscMax(1, PetscMax(length, (PetscInt)v.size())));
  n = (PetscInt)buf.size();
  PetscCall(read(PetscOptionsObject, opt, text, "VSHMMSpectralSetFromOptions", buf.data(), &n, set));
  if (*set) v.assign(buf.begin(), buf.begin() + n);
  PetscFunctionReturn(0);
}

static PetscErrorCode OptionsRealList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<PetscReal> &v, PetscBool *set)
{
  return OptionsList<PetscReal>(PetscOptionsObject, sp, opt, text, v, set, PetscOptionsGetRealArray, PetscOptionsRealArray_Private);
}

static PetscErrorCode OptionsIntList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<PetscInt> &v, PetscBool *set)
{
  return OptionsList<PetscInt>(PetscOptionsObject, sp, opt, text, v, set, PetscOptionsGetIntArray, PetscOptionsIntArray_Private);
}

/* A list of names of any length. */
static PetscErrorCode OptionsStringList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<std::string> &v, PetscBool *set)
{
  PetscInt           length, n;
  std::vector<char *> buf;

  PetscFunctionBegin;
  PetscCall(ListLength(
    [&](PetscInt capacity, PetscInt *m, PetscBool *flg) {
      buf.assign(capacity, nullptr);
      PetscCall(PetscOptionsGetStringArray(((PetscObject)sp)->options, ((PetscObject)sp)->prefix, opt, buf.data(), m, flg));
      for (PetscInt i = 0; i < *m; ++i) PetscCall(PetscFree(buf[i]));
      return PetscErrorCode(0);
    },
    &length));
  buf.assign(PetscMax(1, length), nullptr);
  n = (PetscInt)buf.size();
  PetscCall(PetscOptionsStringArray(opt, text, "VSHMMSpectralSetFromOptions", buf.data(), &n, set));
  if (*set) v.assign(buf.begin(), buf.begin() + n);
  for (PetscInt i = 0; *set && i < n; ++i) PetscCall(PetscFree(buf[i]));
  PetscFunctionReturn(0);
}

/* The option name -spectral_<field>_<parameter> (without the object's prefix). */
static std::string Opt(const char field[], const char parameter[])
{
  std::string o = std::string("-spectral_") + field;
  if (parameter && parameter[0]) o += std::string("_") + parameter;
  return o;
}

static PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, const char field[], const char parameter[], const char text[], PetscReal *value)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsReal(Opt(field, parameter).c_str(), text, "VSHMMSpectralSetFromOptions", *value, value, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode OptionsSeries(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char field[], const char series[], spc::Series &s)
{
  const std::string p = std::string(series) + (series[0] ? "_" : "");
  PetscBool         set;

  PetscFunctionBegin;
  PetscCall(OptionsReal(PetscOptionsObject, field, (p + "offset").c_str(), "constant term of the series (default 0)", &s.offset));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, (p + "wavenumbers").c_str()).c_str(), "wavenumbers k_i of the series", s.wavenumbers, &set));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, (p + "cos").c_str()).c_str(), "cosine coefficients, one per wavenumber (left out: all 0)", s.cosines, &set));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, (p + "sin").c_str()).c_str(), "sine coefficients, one per wavenumber (left out: all 0)", s.sines, &set));
  PetscFunctionReturn(0);
}

/* A field -spectral_<field> <form> and the parameters of its form. Naming the form starts from
   that form's defaults (spc::Field::ofForm(): every parameter 0 except those stated in -help);
   without it the parameters given change the scene's default field. */
static PetscErrorCode OptionsField(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char field[], const char text[], spc::Field &f)
{
  PetscEnum form = (PetscEnum)f.form;
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsEnum(Opt(field, "").c_str(), text, "VSHMMSpectralSetFromOptions", FieldForms, form, &form, &set));
  if (set) f = spc::Field::ofForm((spc::Field::Form)form);
  switch (f.form) {
  case spc::Field::Form::Constant:
    PetscCall(OptionsReal(PetscOptionsObject, field, "value", "constant: the value (default 0)", &f.value));
    break;
  case spc::Field::Form::Gaussian: {
    PetscBool periodic = f.periodic ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(OptionsReal(PetscOptionsObject, field, "offset", "gaussian: constant added (default 0)", &f.offset));
    PetscCall(OptionsReal(PetscOptionsObject, field, "amplitude", "gaussian: amplitude (default 1)", &f.amplitude));
    PetscCall(OptionsReal(PetscOptionsObject, field, "center", "gaussian: center (default pi)", &f.center));
    PetscCall(OptionsReal(PetscOptionsObject, field, "width", "gaussian: width w in exp(-((x-c)/w)^2) (default 1)", &f.width));
    PetscCall(PetscOptionsBool(Opt(field, "periodic").c_str(), "gaussian: periodic distance to the center", "VSHMMSpectralSetFromOptions", periodic, &periodic, NULL));
    f.periodic = periodic;
  } break;
  case spc::Field::Form::ExpSin:
    PetscCall(OptionsReal(PetscOptionsObject, field, "offset", "expsin: constant added (default 0)", &f.offset));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "weights").c_str(), "expsin: weights w_i", f.weights, &set));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "wavenumbers").c_str(), "expsin: wavenumbers k_i, one per weight", f.wavenumbers, &set));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "amplitudes").c_str(), "expsin: amplitudes s_i in exp(s_i sin(k_i x + p_i)) (left out: all 1)", f.amplitudes, &set));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "phases").c_str(), "expsin: phases p_i (left out: all 0)", f.phases, &set));
    break;
  case spc::Field::Form::Fourier:
    PetscCall(OptionsSeries(PetscOptionsObject, sp, field, "", f.numerator));
    break;
  case spc::Field::Form::ExpRatio:
    PetscCall(OptionsReal(PetscOptionsObject, field, "scale", "exp_ratio: the factor s in s exp(num/den) (default 1)", &f.scale));
    PetscCall(OptionsSeries(PetscOptionsObject, sp, field, "numerator", f.numerator));
    PetscCall(OptionsSeries(PetscOptionsObject, sp, field, "denominator", f.denominator));
    break;
  case spc::Field::Form::Samples: {
    char file[PETSC_MAX_PATH_LEN] = "";
    PetscCall(PetscOptionsString(Opt(field, "file").c_str(), "samples: grid file of N lines 'x value' or 'value'", "VSHMMSpectralSetFromOptions", file, file, sizeof(file), &set));
    PetscCheck(set && file[0], PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_%s samples needs -%sspectral_%s_file <grid file>", VSHMMSpectralPrefix(sp), field, VSHMMSpectralPrefix(sp), field);
    PetscCall(VSHMMSpectralReadGridFile_Private(PetscObjectComm((PetscObject)sp), file, f.samples));
  } break;
  }
  PetscFunctionReturn(0);
}

/* Checks of values PETSc's readers accept but the scene cannot use. */
static PetscErrorCode CheckOptions(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s    = sp->data;
  MPI_Comm            comm = PetscObjectComm((PetscObject)sp);
  const char         *pre  = VSHMMSpectralPrefix(sp);

  PetscFunctionBegin;
  PetscCheck(s->N >= 4, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_grid_points %" PetscInt_FMT " is too small: the grid needs at least 4 points", pre, s->N);
  PetscCheck(s->N <= (1 << 26), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_grid_points %" PetscInt_FMT " is too large (at most 2^26)", pre, s->N);
  PetscCheck(!s->terms.empty(), comm, PETSC_ERR_ARG_WRONG, "-%sspectral_terms is empty: the scene needs at least one term, %s", pre, KnownTerms);
  for (size_t i = 0; i < s->terms.size(); ++i) {
    const std::string &t = s->terms[i];
    PetscCheck(t == "diffusion" || t == "advection", comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown term '%s' in -%sspectral_terms: the known terms are %s", t.c_str(), pre, KnownTerms);
    for (size_t j = 0; j < i; ++j) PetscCheck(s->terms[j] != t, comm, PETSC_ERR_ARG_WRONG, "Term '%s' appears twice in -%sspectral_terms", t.c_str(), pre);
  }
  PetscCheck(std::isfinite(s->lambda) && s->lambda >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_lambda must be finite and nonnegative, got %g", pre, (double)s->lambda);
  PetscCheck(s->gap >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_gap must be nonnegative, got %" PetscInt_FMT, pre, s->gap);
  for (PetscInt b : s->buffers) PetscCheck(b >= 0 && b <= s->N / 2, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_buffers: a buffer width must be in 0..N/2 = %" PetscInt_FMT ", got %" PetscInt_FMT, pre, s->N / 2, b);
  for (size_t i = 0; i < s->detect_times.size(); ++i)
    PetscCheck(std::isfinite(s->detect_times[i]) && s->detect_times[i] >= 0 && (i == 0 || s->detect_times[i] > s->detect_times[i - 1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_times must be finite, nonnegative and increasing; item %d is %g", pre, (int)i + 1, (double)s->detect_times[i]);
  PetscCheck(std::isfinite(s->detect_dt) && s->detect_dt >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_dt must be finite and nonnegative (0: estimate), got %g", pre, (double)s->detect_dt);
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetFromOptions - Reads the scene from the options database

   Collective

   Input Parameter:
.  sp - the object

   Options Database Keys (all with the object's prefix, see `VSHMMSpectralSetOptionsPrefix()`; docs/spectral.md has the field forms):
+  -spectral_grid_points <n> - grid points N (any n >= 4; FFTW is fastest for powers of two)
.  -spectral_terms <diffusion,advection> - the terms of F(u); an unknown name is an error
.  -spectral_diffusion_coefficient <form> - d(x): constant, gaussian, expsin, fourier, exp_ratio, samples (+ -spectral_diffusion_coefficient_* parameters)
.  -spectral_velocity <form> - a(x), same forms (+ -spectral_velocity_* parameters)
.  -spectral_u0 <form> - the initial data, same forms (+ -spectral_u0_* parameters)
.  -spectral_mode <dns,sparse> - every mode, or the clusters' modes only
.  -spectral_clusters <0:3,62:66,...> - explicit clusters: ranges lo:hi or single k, joined by + within a cluster ("none": no explicit clusters)
.  -spectral_cluster_detect <none,initial,dns,file> - find the clusters by soft thresholding
.  -spectral_cluster_lambda <l> - shrinkage value (default 10^-2.5)
.  -spectral_cluster_normalization <unitary,series,dft> - scaling of the coefficients before thresholding
.  -spectral_cluster_gap <g> - at most g missing wavenumbers inside a cluster
.  -spectral_cluster_buffers <b0,b1,...> - buffer widths added around the clusters (one value or one per cluster)
.  -spectral_cluster_detect_times <t1,...> - snapshot times of the short DNS (-spectral_cluster_detect dns)
.  -spectral_cluster_detect_dt <dt> - its time step (0: a stable estimate)
.  -spectral_cluster_detect_file <file> - grid file to threshold (-spectral_cluster_detect file)
.  -spectral_evaluation <fft,matrix> - pseudo-spectral with FFTW, or the dense operator on the retained modes
.  -spectral_projection <auto,fft,direct> - how a split gets its cluster's coefficients
-  -spectral_fftw_planner <estimate,measure,patient> - FFTW planning

   Notes:
   Naming a field's form starts the field from that form's defaults: every parameter left out is
   0, except those -help states (gaussian amplitude 1, center pi, width 1; expsin amplitudes 1;
   exp_ratio scale 1, denominator offset 1). Parameters given without the form change the scene's
   default field (the paper's d, a and u0).

   Level: beginner

.seealso: `VSHMMSpectralSetUp()`, `VSHMMSpectralSetOptionsPrefix()`
@*/
PetscErrorCode VSHMMSpectralSetFromOptions(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s;
  char                buf[PETSC_MAX_PATH_LEN];
  PetscBool           set;
  PetscEnum           e;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  s = sp->data;
  PetscObjectOptionsBegin((PetscObject)sp);
  PetscCall(PetscOptionsInt("-spectral_grid_points", "grid points N (at least 4)", "VSHMMSpectralSetFromOptions", s->N, &s->N, NULL));
  PetscCall(OptionsStringList(PetscOptionsObject, sp, "-spectral_terms", "terms of F(u): diffusion, advection", s->terms, &set));
  PetscCall(OptionsField(PetscOptionsObject, sp, "diffusion_coefficient", "diffusion coefficient d(x) (form)", s->diff));
  PetscCall(OptionsField(PetscOptionsObject, sp, "velocity", "advection velocity a(x) (form)", s->vel));
  PetscCall(OptionsField(PetscOptionsObject, sp, "u0", "initial data u0(x) (form)", s->u0));
  e = (PetscEnum)s->mode;
  PetscCall(PetscOptionsEnum("-spectral_mode", "dns: every mode; sparse: the clusters' modes", "VSHMMSpectralSetFromOptions", VSHMMSpectralModes, e, &e, NULL));
  s->mode = (VSHMMSpectralMode)e;
  PetscCall(PetscStrncpy(buf, s->cluster_spec.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString("-spectral_clusters", "explicit clusters, e.g. 0:3,62:66,192:193,255:257 (none: no explicit clusters)", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) {
    PetscCheck(buf[0], PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONG, "-%sspectral_clusters is empty: give clusters as lo:hi ranges separated by commas, e.g. 0:3,62:66 (or none to drop explicit clusters)", VSHMMSpectralPrefix(sp));
    s->cluster_spec = std::string(buf) == "none" ? std::string() : std::string(buf);
  }
  e = (PetscEnum)s->detect;
  PetscCall(PetscOptionsEnum("-spectral_cluster_detect", "find the clusters by soft thresholding", "VSHMMSpectralSetFromOptions", VSHMMSpectralDetects, e, &e, NULL));
  s->detect = (VSHMMSpectralDetect)e;
  PetscCall(PetscOptionsReal("-spectral_cluster_lambda", "shrinkage value of the soft thresholding", "VSHMMSpectralSetFromOptions", s->lambda, &s->lambda, NULL));
  e = (PetscEnum)s->norm;
  PetscCall(PetscOptionsEnum("-spectral_cluster_normalization", "scaling of the coefficients before thresholding", "VSHMMSpectralSetFromOptions", VSHMMSpectralNormalizations, e, &e, NULL));
  s->norm = (spc::Normalization)e;
  PetscCall(PetscOptionsInt("-spectral_cluster_gap", "at most this many missing wavenumbers inside a cluster", "VSHMMSpectralSetFromOptions", s->gap, &s->gap, NULL));
  PetscCall(OptionsIntList(PetscOptionsObject, sp, "-spectral_cluster_buffers", "buffer widths around the clusters (one, or one per cluster)", s->buffers, &set));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, "-spectral_cluster_detect_times", "snapshot times of the detection DNS", s->detect_times, &set));
  PetscCall(PetscOptionsReal("-spectral_cluster_detect_dt", "time step of the detection DNS (0: estimate)", "VSHMMSpectralSetFromOptions", s->detect_dt, &s->detect_dt, NULL));
  PetscCall(PetscStrncpy(buf, s->detect_file.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString("-spectral_cluster_detect_file", "grid file to threshold", "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), &set));
  if (set) s->detect_file = buf;
  e = (PetscEnum)s->evaluation;
  PetscCall(PetscOptionsEnum("-spectral_evaluation", "fft or matrix", "VSHMMSpectralSetFromOptions", VSHMMSpectralEvaluations, e, &e, NULL));
  s->evaluation = (VSHMMSpectralEvaluation)e;
  e             = (PetscEnum)s->projection;
  PetscCall(PetscOptionsEnum("-spectral_projection", "auto, fft or direct", "VSHMMSpectralSetFromOptions", VSHMMSpectralProjections, e, &e, NULL));
  s->projection = (VSHMMSpectralProjection)e;
  e             = (PetscEnum)s->planner;
  PetscCall(PetscOptionsEnum("-spectral_fftw_planner", "FFTW planning rigour", "VSHMMSpectralSetFromOptions", VSHMMSpectralPlanners, e, &e, NULL));
  s->planner = (VSHMMSpectralPlanner)e;
  PetscCall(PetscObjectProcessOptionsHandlers((PetscObject)sp, PetscOptionsObject));
  PetscOptionsEnd();
  PetscCall(CheckOptions(sp));
  sp->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}
