/*
  VSHMMSpectralSetFromOptions(): the scene read from the options database with PETSc's readers,
  every option named -[prefix]spectral_<name>. Values are checked after reading; lists take as
  many values as the user gives.
*/
#include "spectralimpl.hpp"

#include <cmath>
#include <cstring>
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

/* PETSc's readers take an option given without a value for one not given, and drop empty list
   items ("1,,2", "1,2,"); both are refused here, from the option's value in the database. */
static PetscErrorCode CheckValue(VSHMMSpectral sp, const char opt[], bool list)
{
  const char *value;
  PetscBool   found;

  PetscFunctionBegin;
  PetscCall(PetscOptionsFindPair(((PetscObject)sp)->options, ((PetscObject)sp)->prefix, opt, &value, &found));
  if (!found) PetscFunctionReturn(0);
  PetscCheck(value && value[0], PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONG, "-%s%s is given without a value", VSHMMSpectralPrefix(sp), opt + 1);
  if (list) {
    const size_t n = std::strlen(value);
    PetscCheck(value[0] != ',' && value[n - 1] != ',' && !std::strstr(value, ",,"), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONG, "-%s%s %s has an empty item (two commas in a row, or a comma at an end)", VSHMMSpectralPrefix(sp), opt + 1, value);
  }
  PetscFunctionReturn(0);
}

/* A real or integer list of any length (PETSc's integer ranges a-b included): sized with get
   (PetscOptionsGetRealArray/IntArray), then read with read (PetscOptionsRealArray/IntArray) for
   -help. v holds the default on entry and the values given on return. */
template <typename T>
static PetscErrorCode OptionsList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<T> &v, PetscBool *set, PetscErrorCode (*get)(PetscOptions, const char[], const char[], T[], PetscInt *, PetscBool *), PetscErrorCode (*read)(PetscOptionItems *, const char[], const char[], const char[], T[], PetscInt *, PetscBool *))
{
  PetscInt       length, n;
  std::vector<T> buf;

  PetscFunctionBegin;
  PetscCall(CheckValue(sp, opt, true));
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
  PetscInt            length, n;
  std::vector<char *> buf;

  PetscFunctionBegin;
  PetscCall(CheckValue(sp, opt, true));
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

/* PETSc's scalar readers, each followed by CheckValue(). */
static PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const std::string &opt, const char text[], PetscReal *value)
{
  PetscFunctionBegin;
  PetscCall(CheckValue(sp, opt.c_str(), false));
  PetscCall(PetscOptionsReal(opt.c_str(), text, "VSHMMSpectralSetFromOptions", *value, value, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode OptionsInt(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], PetscInt *value)
{
  PetscFunctionBegin;
  PetscCall(CheckValue(sp, opt, false));
  PetscCall(PetscOptionsInt(opt, text, "VSHMMSpectralSetFromOptions", *value, value, NULL));
  PetscFunctionReturn(0);
}

template <typename E>
static PetscErrorCode OptionsEnum(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], const char *const names[], E *value, PetscBool *set)
{
  PetscEnum e = (PetscEnum)*value;

  PetscFunctionBegin;
  PetscCall(CheckValue(sp, opt, false));
  PetscCall(PetscOptionsEnum(opt, text, "VSHMMSpectralSetFromOptions", names, e, &e, set));
  *value = (E)e;
  PetscFunctionReturn(0);
}

static PetscErrorCode OptionsString(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::string &value, PetscBool *set)
{
  char buf[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCall(CheckValue(sp, opt, false));
  PetscCall(PetscStrncpy(buf, value.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString(opt, text, "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), set));
  if (*set) value = buf;
  PetscFunctionReturn(0);
}

static PetscErrorCode OptionsSeries(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char field[], const char series[], spc::Series &s)
{
  const std::string p = std::string(series) + (series[0] ? "_" : "");
  PetscBool         set;

  PetscFunctionBegin;
  PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, (p + "offset").c_str()), "constant term of the series (default 0)", &s.offset));
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
  spc::Field::Form form = f.form;
  PetscBool        set;

  PetscFunctionBegin;
  PetscCall(OptionsEnum(PetscOptionsObject, sp, Opt(field, "").c_str(), text, FieldForms, &form, &set));
  if (set) f = spc::Field::ofForm(form);
  switch (f.form) {
  case spc::Field::Form::Constant:
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "value"), "constant: the value (default 0)", &f.value));
    break;
  case spc::Field::Form::Gaussian: {
    PetscBool periodic = f.periodic ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "offset"), "gaussian: constant added (default 0)", &f.offset));
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "amplitude"), "gaussian: amplitude (default 1)", &f.amplitude));
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "center"), "gaussian: center (default pi)", &f.center));
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "width"), "gaussian: width w in exp(-((x-c)/w)^2) (default 1)", &f.width));
    PetscCall(PetscOptionsBool(Opt(field, "periodic").c_str(), "gaussian: periodic distance to the center", "VSHMMSpectralSetFromOptions", periodic, &periodic, NULL));
    f.periodic = periodic;
  } break;
  case spc::Field::Form::ExpSin:
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "offset"), "expsin: constant added (default 0)", &f.offset));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "weights").c_str(), "expsin: weights w_i", f.weights, &set));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "wavenumbers").c_str(), "expsin: wavenumbers k_i, one per weight", f.wavenumbers, &set));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "amplitudes").c_str(), "expsin: amplitudes s_i in exp(s_i sin(k_i x + p_i)) (left out: all 1)", f.amplitudes, &set));
    PetscCall(OptionsRealList(PetscOptionsObject, sp, Opt(field, "phases").c_str(), "expsin: phases p_i (left out: all 0)", f.phases, &set));
    break;
  case spc::Field::Form::Fourier:
    PetscCall(OptionsSeries(PetscOptionsObject, sp, field, "", f.numerator));
    break;
  case spc::Field::Form::ExpRatio:
    PetscCall(OptionsReal(PetscOptionsObject, sp, Opt(field, "scale"), "exp_ratio: the factor s in s exp(num/den) (default 1)", &f.scale));
    PetscCall(OptionsSeries(PetscOptionsObject, sp, field, "numerator", f.numerator));
    PetscCall(OptionsSeries(PetscOptionsObject, sp, field, "denominator", f.denominator));
    break;
  case spc::Field::Form::Samples: {
    std::string file;
    PetscCall(OptionsString(PetscOptionsObject, sp, Opt(field, "file").c_str(), "samples: grid file of N lines 'x value' or 'value'", file, &set));
    PetscCheck(set && !file.empty(), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_%s samples needs -%sspectral_%s_file <grid file>", VSHMMSpectralPrefix(sp), field, VSHMMSpectralPrefix(sp), field);
    PetscCall(VSHMMSpectralReadGridFile_Private(PetscObjectComm((PetscObject)sp), file.c_str(), f.samples));
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
  PetscCheck(std::isfinite(s->lambda), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_lambda must be finite (negative: the normalisation's default), got %g", pre, (double)s->lambda);
  PetscCheck(std::isfinite(s->gap_ratio) && s->gap_ratio >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_gap_ratio must be finite and nonnegative, got %g", pre, (double)s->gap_ratio);
  PetscCheck(std::isfinite(s->scale_separation) && s->scale_separation >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_scale_separation must be finite and nonnegative, got %g", pre, (double)s->scale_separation);
  PetscCheck(s->detect_max_steps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_max_steps must be positive, got %" PetscInt_FMT, pre, s->detect_max_steps);
  for (PetscInt b : s->buffers) PetscCheck(b >= 0 && b <= s->N / 2, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_buffers: a buffer width must be in 0..N/2 = %" PetscInt_FMT ", got %" PetscInt_FMT, pre, s->N / 2, b);
  for (size_t i = 0; i < s->detect_times.size(); ++i)
    PetscCheck(std::isfinite(s->detect_times[i]) && s->detect_times[i] >= 0 && (i == 0 || s->detect_times[i] > s->detect_times[i - 1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_times must be finite, nonnegative and increasing; item %d is %g", pre, (int)i + 1,
               (double)s->detect_times[i]);
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
.  -spectral_cluster_detect <none,initial,dns,file,auto> - find the clusters by soft thresholding (sparse mode without -spectral_clusters: auto)
.  -spectral_cluster_lambda <l> - shrinkage value (default 1e-4 relative, 10^-2.5 for the other normalisations)
.  -spectral_cluster_normalization <unitary,series,dft,relative> - scaling of the coefficients before thresholding (default relative: |c_k| / ||u||, independent of N)
.  -spectral_cluster_gap <g> - at most g missing wavenumbers inside a cluster (default -1: grouping by -spectral_cluster_gap_ratio)
.  -spectral_cluster_gap_ratio <r> - adjacent groups merge while their gap is at most r times the distance of their centres (default 1/3)
.  -spectral_cluster_scale_separation <S> - detected bands whose time scales are less than S apart share a cluster (default 10; 1: one cluster per band)
.  -spectral_cluster_fill_holes <bool> - a detected cluster holds every wavenumber between its lowest and highest (default true)
.  -spectral_cluster_detect_max_steps <n> - step limit of the detection DNS with automatic snapshots (default 32768)
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
  std::string         clusters;
  PetscBool           set;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  s = sp->data;
  PetscObjectOptionsBegin((PetscObject)sp);
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_grid_points", "grid points N (at least 4)", &s->N));
  PetscCall(OptionsStringList(PetscOptionsObject, sp, "-spectral_terms", "terms of F(u): diffusion, advection", s->terms, &set));
  PetscCall(OptionsField(PetscOptionsObject, sp, "diffusion_coefficient", "diffusion coefficient d(x) (form)", s->diff));
  PetscCall(OptionsField(PetscOptionsObject, sp, "velocity", "advection velocity a(x) (form)", s->vel));
  PetscCall(OptionsField(PetscOptionsObject, sp, "u0", "initial data u0(x) (form)", s->u0));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_mode", "dns: every mode; sparse: the clusters' modes", VSHMMSpectralModes, &s->mode, &set));
  PetscCall(OptionsString(PetscOptionsObject, sp, "-spectral_clusters", "explicit clusters, e.g. 0:3,62:66,192:193,255:257 (none: no explicit clusters)", clusters, &set));
  if (set) s->cluster_spec = clusters == "none" ? std::string() : clusters;
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_cluster_detect", "find the clusters by soft thresholding", VSHMMSpectralDetects, &s->detect, &set));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_lambda", "shrinkage value of the soft thresholding (negative: 1e-4 relative, 10^-2.5 otherwise)", &s->lambda));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_cluster_normalization", "scaling of the coefficients before thresholding", VSHMMSpectralNormalizations, &s->norm, &set));
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_cluster_gap", "at most this many missing wavenumbers inside a cluster (negative: by -spectral_cluster_gap_ratio)", &s->gap));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_gap_ratio", "adjacent groups merge while gap <= ratio * distance of their centres", &s->gap_ratio));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_scale_separation", "detected bands whose time scales are less than this apart share a cluster (1: one cluster per band)", &s->scale_separation));
  PetscCall(PetscOptionsBool("-spectral_cluster_fill_holes", "a detected cluster holds every wavenumber between its ends", "VSHMMSpectralSetFromOptions", s->fill_holes, &s->fill_holes, NULL));
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_cluster_detect_max_steps", "step limit of the detection DNS with automatic snapshots", &s->detect_max_steps));
  PetscCall(OptionsIntList(PetscOptionsObject, sp, "-spectral_cluster_buffers", "buffer widths around the clusters (one, or one per cluster)", s->buffers, &set));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, "-spectral_cluster_detect_times", "snapshot times of the detection DNS", s->detect_times, &set));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_detect_dt", "time step of the detection DNS (0: estimate)", &s->detect_dt));
  PetscCall(OptionsString(PetscOptionsObject, sp, "-spectral_cluster_detect_file", "grid file to threshold", s->detect_file, &set));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_evaluation", "fft or matrix", VSHMMSpectralEvaluations, &s->evaluation, &set));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_projection", "auto, fft or direct", VSHMMSpectralProjections, &s->projection, &set));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_fftw_planner", "FFTW planning rigour", VSHMMSpectralPlanners, &s->planner, &set));
  PetscCall(PetscObjectProcessOptionsHandlers((PetscObject)sp, PetscOptionsObject));
  PetscOptionsEnd();
  PetscCall(CheckOptions(sp));
  sp->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}
