/*
  VSHMMSpectralSetFromOptions(): the scene read from the options database with PETSc's readers,
  every option named -[prefix]spectral_<name>. Values are checked after reading; lists take as
  many values as the user gives.
*/
#include "spectralimpl.hpp"

#include "vshmmoptions.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <functional>

static const char *const FieldForms[] = {"constant", "gaussian", "expsin", "fourier", "exp_ratio", "samples", "VSHMMSpectralFieldForm", "", nullptr};
static const char *const KnownTerms = "diffusion (d/dx(d(x) du/dx), field -spectral_diffusion_coefficient), advection (-a(x) du/dx, field -spectral_velocity), burgers (-d/dx(c(x) u^2/2), field -spectral_burgers_coefficient), reaction (r(x) (c0 + c1 "
                                      "u + c2 u^2 + c3 u^3), field -spectral_reaction_rate, -spectral_reaction_coefficients c0,c1,c2,c3) and source (s(x), field -spectral_source)";
static const char *const Terms[]    = {"diffusion", "advection", "burgers", "reaction", "source"};
/* every parameter name of the field forms, to refuse un-numbered parameters beside a sum of forms */
static const char *const FieldParameters[] = {"value", "offset", "amplitude", "center", "width", "periodic", "weights", "wavenumbers", "amplitudes", "phases", "cos", "sin", "scale", "numerator_offset", "numerator_wavenumbers", "numerator_cos", "numerator_sin", "denominator_offset", "denominator_wavenumbers", "denominator_cos", "denominator_sin", "file"};

/* PETSc's readers with the checks of src/common/vshmmoptions.hpp, for this object. */
static const char *const Man = "VSHMMSpectralSetFromOptions";

static PetscErrorCode OptionsRealList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<PetscReal> &v, PetscBool *set)
{
  return VSHMMOptionsRealList(PetscOptionsObject, (PetscObject)sp, opt, text, Man, v, set);
}

static PetscErrorCode OptionsIntList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<PetscInt> &v, PetscBool *set)
{
  return VSHMMOptionsIntList(PetscOptionsObject, (PetscObject)sp, opt, text, Man, v, set);
}

static PetscErrorCode OptionsStringList(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], std::vector<std::string> &v, PetscBool *set)
{
  return VSHMMOptionsStringList(PetscOptionsObject, (PetscObject)sp, opt, text, Man, v, set);
}

/* The option name -spectral_<field>_<parameter> (without the object's prefix). */
static std::string Opt(const char field[], const char parameter[])
{
  std::string o = std::string("-spectral_") + field;
  if (parameter && parameter[0]) o += std::string("_") + parameter;
  return o;
}

static PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const std::string &opt, const char text[], PetscReal *value)
{
  return VSHMMOptionsReal(PetscOptionsObject, (PetscObject)sp, opt.c_str(), text, Man, value, nullptr);
}

static PetscErrorCode OptionsInt(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], PetscInt *value)
{
  return VSHMMOptionsInt(PetscOptionsObject, (PetscObject)sp, opt, text, Man, value, nullptr);
}

template <typename E>
static PetscErrorCode OptionsEnum(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], const char *const names[], E *value, PetscBool *set)
{
  return VSHMMOptionsEnum(PetscOptionsObject, (PetscObject)sp, opt, text, Man, names, value, set);
}

static PetscErrorCode OptionsString(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char opt[], const char text[], const char takes[], std::string &value, PetscBool *set)
{
  return VSHMMOptionsString(PetscOptionsObject, (PetscObject)sp, opt, text, Man, takes, value, set);
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

/* The parameters -spectral_<field>_<parameter> of the form of f. */
static PetscErrorCode OptionsFieldParameters(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char field[], spc::Field &f)
{
  PetscBool set;

  PetscFunctionBegin;
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
    PetscCall(VSHMMOptionsBool(PetscOptionsObject, (PetscObject)sp, Opt(field, "periodic").c_str(), "gaussian: periodic distance to the center", Man, &periodic, nullptr));
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
    PetscCall(OptionsString(PetscOptionsObject, sp, Opt(field, "file").c_str(), "samples: grid file of N lines 'x value' or 'value'", "a file name", file, &set));
    PetscCheck(set && !file.empty(), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_WRONGSTATE, "-%sspectral_%s samples needs -%sspectral_%s_file <grid file>", VSHMMSpectralPrefix(sp), field, VSHMMSpectralPrefix(sp), field);
    PetscCall(VSHMMSpectralReadGridFile_Private(PetscObjectComm((PetscObject)sp), file.c_str(), f.samples));
  } break;
  }
  PetscFunctionReturn(0);
}

/* A sum of forms "fourier+expsin" given for -spectral_<field>: summand i's parameters are
   -spectral_<field>_<i>_<parameter> (i from 0); un-numbered parameters are refused. */
static PetscErrorCode OptionsFieldSum(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char field[], const char text[], const std::string &sum, spc::Field &f)
{
  const char *pre  = VSHMMSpectralPrefix(sp);
  MPI_Comm    comm = PetscObjectComm((PetscObject)sp);
  std::string forms;
  char        buf[PETSC_MAX_PATH_LEN];
  spc::Field  total;

  PetscFunctionBegin;
  for (int i = 0; i < 6; ++i) forms += std::string(i ? " " : "") + FieldForms[i];
  PetscCall(PetscStrncpy(buf, sum.c_str(), sizeof(buf)));
  PetscCall(PetscOptionsString(Opt(field, "").c_str(), text, "VSHMMSpectralSetFromOptions", buf, buf, sizeof(buf), NULL)); /* for -help */
  size_t begin = 0;
  for (int i = 0;; ++i) {
    const size_t end  = sum.find('+', begin);
    std::string  name = sum.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    PetscCheck(!name.empty(), comm, PETSC_ERR_ARG_WRONG, "-%sspectral_%s %s has an empty summand ('+' at an end, or two in a row)", pre, field, sum.c_str());
    int form = -1;
    for (int k = 0; k < 6; ++k)
      if (name == FieldForms[k]) form = k;
    PetscCheck(form >= 0, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown form '%s' in summand %d of -%sspectral_%s %s: the forms are %s", name.c_str(), i, pre, field, sum.c_str(), forms.c_str());
    total.summands.push_back(spc::Field::ofForm((spc::Field::Form)form));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  for (const char *p : FieldParameters) {
    PetscBool has;
    PetscCall(PetscOptionsHasName(((PetscObject)sp)->options, ((PetscObject)sp)->prefix, Opt(field, p).c_str(), &has));
    PetscCheck(!has, comm, PETSC_ERR_ARG_WRONG, "-%sspectral_%s_%s: -%sspectral_%s is a sum of forms (%s), whose parameters are numbered by summand from 0: -%sspectral_%s_0_%s, -%sspectral_%s_1_..., ...", pre, field, p, pre, field, sum.c_str(), pre, field, p, pre, field);
  }
  for (size_t i = 0; i < total.summands.size(); ++i) PetscCall(OptionsFieldParameters(PetscOptionsObject, sp, (std::string(field) + "_" + std::to_string(i)).c_str(), total.summands[i]));
  f = total;
  PetscFunctionReturn(0);
}

/* A field -spectral_<field> <form> (or a sum of forms, form+form+...) and the parameters of its
   form(s). Naming the form starts from that form's defaults (spc::Field::ofForm(): every
   parameter 0 except those stated in -help); without it the parameters given change the
   scene's default field. */
static PetscErrorCode OptionsField(PetscOptionItems *PetscOptionsObject, VSHMMSpectral sp, const char field[], const char text[], spc::Field &f)
{
  spc::Field::Form form = f.form;
  PetscBool        set, found;
  char             value[PETSC_MAX_PATH_LEN];

  PetscFunctionBegin;
  PetscCall(VSHMMOptionCheckValue((PetscObject)sp, Opt(field, "").c_str(), "a field form, or a sum of forms form+form+...", false, false));
  PetscCall(PetscOptionsGetString(((PetscObject)sp)->options, ((PetscObject)sp)->prefix, Opt(field, "").c_str(), value, sizeof(value), &found));
  if (found && std::strchr(value, '+')) {
    PetscCall(OptionsFieldSum(PetscOptionsObject, sp, field, text, value, f));
    PetscFunctionReturn(0);
  }
  PetscCall(OptionsEnum(PetscOptionsObject, sp, Opt(field, "").c_str(), text, FieldForms, &form, &set));
  if (set) f = spc::Field::ofForm(form);
  if (f.summands.empty()) PetscCall(OptionsFieldParameters(PetscOptionsObject, sp, field, f));
  else
    for (size_t i = 0; i < f.summands.size(); ++i) PetscCall(OptionsFieldParameters(PetscOptionsObject, sp, (std::string(field) + "_" + std::to_string(i)).c_str(), f.summands[i]));
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
    PetscCheck(std::find(std::begin(Terms), std::end(Terms), t) != std::end(Terms), comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown term '%s' in -%sspectral_terms: the known terms are %s", t.c_str(), pre, KnownTerms);
    for (size_t j = 0; j < i; ++j) PetscCheck(s->terms[j] != t, comm, PETSC_ERR_ARG_WRONG, "Term '%s' appears twice in -%sspectral_terms", t.c_str(), pre);
  }
  if (std::find(s->terms.begin(), s->terms.end(), "reaction") != s->terms.end()) {
    PetscCheck(!s->reaction.empty(), comm, PETSC_ERR_ARG_WRONG, "The term reaction needs -%sspectral_reaction_coefficients c0,c1,c2,c3: r(x) (c0 + c1 u + c2 u^2 + c3 u^3) (fewer values: the rest are 0)", pre);
    PetscCheck(s->reaction.size() <= 4, comm, PETSC_ERR_ARG_SIZ, "-%sspectral_reaction_coefficients takes at most 4 values c0,c1,c2,c3 (a cubic), got %d", pre, (int)s->reaction.size());
    for (PetscReal c : s->reaction) PetscCheck(std::isfinite(c), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_reaction_coefficients must be finite", pre);
  }
  PetscCheck(std::isfinite(s->lambda), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_lambda must be finite (negative: the normalisation's default), got %g", pre, (double)s->lambda);
  PetscCheck(std::isfinite(s->gap_ratio) && s->gap_ratio >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_gap_ratio must be finite and nonnegative, got %g", pre, (double)s->gap_ratio);
  PetscCheck(std::isfinite(s->scale_separation) && s->scale_separation >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_scale_separation must be finite and nonnegative, got %g", pre, (double)s->scale_separation);
  PetscCheck(std::isfinite(s->cluster_tol) && s->cluster_tol >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_tolerance must be finite and nonnegative (0: merged bands are kept merged), got %g", pre, (double)s->cluster_tol);
  PetscCheck(s->detect_max_steps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_max_steps must be positive, got %" PetscInt_FMT, pre, s->detect_max_steps);
  PetscCheck(std::isfinite(s->min_band_share) && s->min_band_share >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_min_band_share must be finite and nonnegative (a fraction of -spectral_cluster_tolerance; 0: every band is kept), got %g", pre,
             (double)s->min_band_share);
  PetscCheck(s->detect_agreeing >= 2, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_agreeing_looks must be at least 2 (looks in a row whose clusters agree), got %" PetscInt_FMT, pre, s->detect_agreeing);
  PetscCheck(s->detect_first_steps >= 1 && s->detect_first_steps <= s->detect_max_steps, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_cluster_detect_first_steps must be in 1..-%sspectral_cluster_detect_max_steps (%" PetscInt_FMT "), got %" PetscInt_FMT, pre, pre, s->detect_max_steps, s->detect_first_steps);
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
.  -spectral_terms <diffusion,advection,burgers,reaction,source> - the terms of F(u); an unknown name is an error
.  -spectral_diffusion_coefficient <form> - d(x): constant, gaussian, expsin, fourier, exp_ratio, samples (+ -spectral_diffusion_coefficient_* parameters), or a sum form+form+... (+ -spectral_diffusion_coefficient_<i>_* parameters of summand i = 0, 1, ...)
.  -spectral_velocity <form> - a(x), same forms (+ -spectral_velocity_* parameters)
.  -spectral_burgers_coefficient <form> - c(x) of the term burgers -(c u^2/2)_x, same forms (default constant 1)
.  -spectral_reaction_rate <form> - r(x) of the term reaction r(x) (c0 + c1 u + c2 u^2 + c3 u^3), same forms (default constant 1)
.  -spectral_reaction_coefficients <c0,c1,c2,c3> - its polynomial (needed with the term; fewer values: the rest 0)
.  -spectral_source <form> - s(x) of the term source, same forms (default constant 0)
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
.  -spectral_cluster_detect_first_steps <n> - steps of the detection DNS before its first look, then doubled (default 64; 16 cuts the detection 4x where the clusters show early)
.  -spectral_cluster_min_band_share <f> - the automatic detection DNS leaves out its highest bands (the stiffest: they set the micro step), from the top down, while each holds less than f times -spectral_cluster_tolerance of ||u||, decays, and acts on the other retained bands less than their own tendency (a band that oscillates, under advection or Burgers terms, or that moves the others is kept with every band below it) (default 0.05; 0: every band is kept)
.  -spectral_cluster_detect_agreeing_looks <n> - the detection ends when this many looks in a row agree (default 3: two doublings of the time bring nothing new; 2 halves the detection, at the risk of narrower clusters)
.  -spectral_cluster_detect_rkc <bool> - the automatic detection DNS takes Runge-Kutta-Chebyshev (RKC) steps where the operator's spectrum lies near the negative real axis and they need fewer evaluations than RK3 (default true; false: RK3 by a TS with prefix spectral_cluster_detect_)
.  -spectral_cluster_tolerance <tol> - when the detection DNS's bands merge and the wavenumbers that merged them hold at most tol of ||u||, keep the bands before the merge (default 1e-2; the examples pass -ts_rtol)
.  -spectral_cluster_buffers <b0,b1,...> - buffer widths added around the clusters (one value or one per cluster)
.  -spectral_cluster_detect_times <t1,...> - snapshot times of the short DNS (-spectral_cluster_detect dns)
.  -spectral_cluster_detect_dt <dt> - its time step (0: a stable estimate)
.  -spectral_cluster_detect_file <file> - grid file to threshold (-spectral_cluster_detect file)
.  -spectral_evaluation <fft,matrix> - pseudo-spectral with FFTW, or the dense operator on the retained modes
.  -spectral_projection <auto,fft,direct> - how a split gets its cluster's coefficients
.  -spectral_fftw_planner <estimate,measure,patient> - FFTW planning (default estimate)
.  -spectral_growth_bound <factor> - stop a solve whose solution grows beyond factor times what the scene's terms allow (default 10; 0: no check)
-  -spectral_truncation_check <none,warn,error,widen> - what a sparse run does when the dynamics drive the wavenumbers its clusters leave out beyond -spectral_cluster_tolerance of ||u|| (default warn; widen: asks a program that restarts for wider clusters, `VSHMMSpectralWidenClusters()`; `VSHMMSpectralTruncationMonitor()`)

   Notes:
   Naming a field's form starts the field from that form's defaults: every parameter left out is
   0, except those -help states (gaussian amplitude 1, center pi, width 1; expsin amplitudes 1;
   exp_ratio scale 1, denominator offset 1). Parameters given without the form change the scene's
   default field (the paper's d, a and u0). A field given as a sum of forms, e.g.
   -spectral_diffusion_coefficient fourier+expsin, is the sum of the summands, each with its own
   parameters numbered from 0: -spectral_diffusion_coefficient_0_offset 1,
   -spectral_diffusion_coefficient_1_weights 0.1, ...

   The terms burgers and reaction are nonlinear: their products are formed without aliasing on a
   padded grid and projected by FFT (docs/spectral.md); -spectral_evaluation matrix refuses them.

   Level: beginner

.seealso: `VSHMMSpectralSetUp()`, `VSHMMSpectralSetOptionsPrefix()`
@*/
PetscErrorCode VSHMMSpectralSetFromOptions(VSHMMSpectral sp)
{
  VSHMMSpectral_Data *s;
  std::string         clusters;
  PetscBool           set;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  s = sp->data;
  PetscObjectOptionsBegin((PetscObject)sp);
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_grid_points", "grid points N (at least 4)", &s->N));
  PetscCall(OptionsStringList(PetscOptionsObject, sp, "-spectral_terms", "terms of F(u): diffusion, advection, burgers, reaction, source", s->terms, &set));
  PetscCall(OptionsField(PetscOptionsObject, sp, "diffusion_coefficient", "diffusion coefficient d(x) (a form, or a sum form+form+... whose parameters are numbered by summand: _0_, _1_, ...)", s->diff));
  PetscCall(OptionsField(PetscOptionsObject, sp, "velocity", "advection velocity a(x) (a form, or a sum form+form+... whose parameters are numbered by summand: _0_, _1_, ...)", s->vel));
  PetscCall(OptionsField(PetscOptionsObject, sp, "burgers_coefficient", "Burgers coefficient c(x) in -(c u^2/2)_x (a form or a sum form+form+...; default constant 1)", s->burgers));
  PetscCall(OptionsField(PetscOptionsObject, sp, "reaction_rate", "reaction rate r(x) (a form or a sum form+form+...; default constant 1)", s->rate));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, "-spectral_reaction_coefficients", "c0,c1,c2,c3 of the reaction r(x) (c0 + c1 u + c2 u^2 + c3 u^3) (fewer values: the rest 0)", s->reaction, &set));
  PetscCall(OptionsField(PetscOptionsObject, sp, "source", "source s(x) (a form or a sum form+form+...; default constant 0)", s->source));
  PetscCall(OptionsField(PetscOptionsObject, sp, "u0", "initial data u0(x) (a form, or a sum form+form+... whose parameters are numbered by summand: _0_, _1_, ...)", s->u0));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_mode", "dns: every mode; sparse: the clusters' modes", VSHMMSpectralModes, &s->mode, &set));
  PetscCall(OptionsString(PetscOptionsObject, sp, "-spectral_clusters", "explicit clusters, e.g. 0:3,62:66,192:193,255:257 (none: no explicit clusters)", "clusters lo:hi or k, joined by + within a cluster and by commas between clusters, or none", clusters, &set));
  if (set) s->cluster_spec = clusters == "none" ? std::string() : clusters;
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_cluster_detect", "find the clusters by soft thresholding", VSHMMSpectralDetects, &s->detect, &set));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_lambda", "shrinkage value of the soft thresholding (negative: 1e-4 relative, 10^-2.5 otherwise)", &s->lambda));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_cluster_normalization", "scaling of the coefficients before thresholding", VSHMMSpectralNormalizations, &s->norm, &set));
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_cluster_gap", "at most this many missing wavenumbers inside a cluster (negative: by -spectral_cluster_gap_ratio)", &s->gap));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_gap_ratio", "adjacent groups merge while gap <= ratio * distance of their centres", &s->gap_ratio));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_scale_separation", "detected bands whose time scales are less than this apart share a cluster (1: one cluster per band)", &s->scale_separation));
  PetscCall(PetscOptionsBool("-spectral_cluster_fill_holes", "a detected cluster holds every wavenumber between its ends", "VSHMMSpectralSetFromOptions", s->fill_holes, &s->fill_holes, NULL));
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_cluster_detect_max_steps", "step limit of the detection DNS with automatic snapshots", &s->detect_max_steps));
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_cluster_detect_first_steps", "steps of the detection DNS before its first automatic look (then doubled)", &s->detect_first_steps));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_min_band_share", "automatic detection DNS: its highest bands are left out, from the top down, while each holds less than this times -spectral_cluster_tolerance of ||u||, decays and moves the other bands less than their own tendency (0: none)", &s->min_band_share));
  PetscCall(OptionsInt(PetscOptionsObject, sp, "-spectral_cluster_detect_agreeing_looks", "the detection DNS ends when this many automatic looks in a row agree", &s->detect_agreeing));
  PetscCall(PetscOptionsBool("-spectral_cluster_detect_rkc", "automatic detection DNS: Runge-Kutta-Chebyshev steps (RKC) where the operator's spectrum allows them with fewer evaluations than RK3", "VSHMMSpectralSetFromOptions", s->detect_rkc, &s->detect_rkc, NULL));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_tolerance", "automatic detection DNS: when bands merge and the wavenumbers that merged them hold at most this share of ||u||, the bands before the merge are kept (VSHMMSpectralSetClusterTolerance())", &s->cluster_tol));
  PetscCall(OptionsIntList(PetscOptionsObject, sp, "-spectral_cluster_buffers", "buffer widths around the clusters (one, or one per cluster)", s->buffers, &set));
  PetscCall(OptionsRealList(PetscOptionsObject, sp, "-spectral_cluster_detect_times", "snapshot times of the detection DNS", s->detect_times, &set));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_cluster_detect_dt", "time step of the detection DNS (0: estimate)", &s->detect_dt));
  PetscCall(OptionsString(PetscOptionsObject, sp, "-spectral_cluster_detect_file", "grid file to threshold", "a file name", s->detect_file, &set));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_evaluation", "fft or matrix", VSHMMSpectralEvaluations, &s->evaluation, &set));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_projection", "auto, fft or direct", VSHMMSpectralProjections, &s->projection, &set));
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_fftw_planner", "FFTW planning rigour", VSHMMSpectralPlanners, &s->planner, &set));
  PetscCall(OptionsReal(PetscOptionsObject, sp, "-spectral_growth_bound", "stop a solve whose solution norm exceeds this factor times the bound of the scene's terms (0: no check)", &s->growth_factor));
  PetscCheck(std::isfinite(s->growth_factor) && (s->growth_factor == 0 || s->growth_factor >= 1), PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_growth_bound must be 0 (no check) or a finite factor >= 1, got %g", VSHMMSpectralPrefix(sp),
             (double)s->growth_factor);
  PetscCall(OptionsEnum(PetscOptionsObject, sp, "-spectral_truncation_check", "sparse runs: what a check that the left-out wavenumbers stay below -spectral_cluster_tolerance of ||u|| does when they do not (widen: wider clusters for a program that restarts)", VSHMMSpectralTruncationChecks, &s->truncation_check, &set));
  PetscCall(PetscObjectProcessOptionsHandlers((PetscObject)sp, PetscOptionsObject));
  PetscOptionsEnd();
  PetscCall(CheckOptions(sp));
  sp->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}
