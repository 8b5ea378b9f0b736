/*
  VSHMMSpectral: the package (class id, log events), creation and destruction, the options
  prefix, the default scenes and the accessors.
*/
#include "spectralimpl.hpp"

#include <petscvshmm.h>

#include <fstream>
#include <sstream>

PetscClassId VSHMMSPECTRAL_CLASSID = 0;
PetscLogEvent VSHMMSPECTRAL_SetUp, VSHMMSPECTRAL_RHS, VSHMMSPECTRAL_Split, VSHMMSPECTRAL_Physical, VSHMMSPECTRAL_ForwardFFT, VSHMMSPECTRAL_ProjDirect, VSHMMSPECTRAL_MatVec, VSHMMSPECTRAL_Eigen, VSHMMSPECTRAL_Growth, VSHMMSPECTRAL_Truncation, VSHMMSPECTRAL_Detect;

const char *const VSHMMSpectralModes[]            = {"dns", "sparse", "VSHMMSpectralMode", "VSHMMSPECTRAL_MODE_", nullptr};
const char *const VSHMMSpectralDetects[]          = {"none", "initial", "dns", "file", "auto", "VSHMMSpectralDetect", "VSHMMSPECTRAL_DETECT_", nullptr};
const char *const VSHMMSpectralProjections[]      = {"auto", "fft", "direct", "VSHMMSpectralProjection", "VSHMMSPECTRAL_PROJECTION_", nullptr};
const char *const VSHMMSpectralEvaluations[]      = {"fft", "matrix", "VSHMMSpectralEvaluation", "VSHMMSPECTRAL_EVALUATION_", nullptr};
const char *const VSHMMSpectralPlanners[]         = {"estimate", "measure", "patient", "VSHMMSpectralPlanner", "VSHMMSPECTRAL_PLANNER_", nullptr};
const char *const VSHMMSpectralTruncationChecks[] = {"none", "warn", "error", "widen", "VSHMMSpectralTruncationCheck", "VSHMMSPECTRAL_TRUNCATION_", nullptr};
const char *const VSHMMSpectralNormalizations[]   = {"unitary", "series", "dft", "relative", "Normalization", "", nullptr};

static PetscBool VSHMMSpectralPackageInitialized = PETSC_FALSE;

/*@C
   VSHMMSpectralFinalizePackage - Resets the VSHMMSpectral package state; called from `PetscFinalize()`

   Level: developer

.seealso: `VSHMMSpectralInitializePackage()`
@*/
PetscErrorCode VSHMMSpectralFinalizePackage(void)
{
  PetscFunctionBegin;
  VSHMMSpectralPackageInitialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralInitializePackage - Registers the VSHMMSpectral class and its log events

   Not Collective

   Notes:
   Also registers the `TSVSHMM` type (`TSVSHMMInitializePackage()`). Reached from
   `VSHMMSpectralCreate()` and, for a program that loads the library at run time
   (-dll_append <prefix>/lib/libpetscvshmmspectral.so), from PETSc's dynamic-library hook;
   idempotent, and reset by `PetscFinalize()`. The log events
   (`-log_view`) are SpecSetUp, SpecRHS (the full right-hand side), SpecSplit (a cluster's split),
   SpecPhysical (c2r transform and products on the grid), SpecForwardFFT (r2c transforms),
   SpecProjDirect (direct projections on a cluster) and SpecMatVec (dense-operator evaluation).

   Level: developer

.seealso: `VSHMMSpectralCreate()`, `VSHMMSpectralFinalizePackage()`, `TSVSHMMInitializePackage()`
@*/
PetscErrorCode VSHMMSpectralInitializePackage(void)
{
  PetscFunctionBegin;
  if (VSHMMSpectralPackageInitialized) PetscFunctionReturn(0);
  VSHMMSpectralPackageInitialized = PETSC_TRUE;
  PetscCall(TSVSHMMInitializePackage());
  if (!VSHMMSPECTRAL_CLASSID) PetscCall(PetscClassIdRegister("VSHMMSpectral", &VSHMMSPECTRAL_CLASSID));
  PetscCall(PetscLogEventRegister("SpecSetUp", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_SetUp));
  PetscCall(PetscLogEventRegister("SpecRHS", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_RHS));
  PetscCall(PetscLogEventRegister("SpecSplit", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_Split));
  PetscCall(PetscLogEventRegister("SpecPhysical", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_Physical));
  PetscCall(PetscLogEventRegister("SpecForwardFFT", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_ForwardFFT));
  PetscCall(PetscLogEventRegister("SpecProjDirect", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_ProjDirect));
  PetscCall(PetscLogEventRegister("SpecMatVec", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_MatVec));
  PetscCall(PetscLogEventRegister("SpecEigen", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_Eigen));
  PetscCall(PetscLogEventRegister("SpecGrowth", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_Growth));
  PetscCall(PetscLogEventRegister("SpecTruncation", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_Truncation));
  PetscCall(PetscLogEventRegister("SpecDetect", VSHMMSPECTRAL_CLASSID, &VSHMMSPECTRAL_Detect));
  PetscCall(PetscRegisterFinalize(VSHMMSpectralFinalizePackage));
  PetscFunctionReturn(0);
}

/*
  PetscDLLibraryRegister_petscvshmmspectral - called by PETSc when the library is loaded with
  -dll_append (the name follows from the file name libpetscvshmmspectral.so)
*/
PETSC_EXTERN PetscErrorCode PetscDLLibraryRegister_petscvshmmspectral(void)
{
  PetscFunctionBegin;
  PetscCall(VSHMMSpectralInitializePackage());
  PetscFunctionReturn(0);
}

PetscErrorCode VSHMMSpectralOptionError_Private(VSHMMSpectral sp, const char option[], const std::exception &e)
{
  SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_OUTOFRANGE, "-%sspectral_%s: %s", VSHMMSpectralPrefix(sp), option, e.what());
}

PetscErrorCode VSHMMSpectralSampleField_Private(VSHMMSpectral sp, const char option[], const spc::Field &f, std::vector<double> &v)
{
  PetscFunctionBegin;
  try {
    v = f.sample((int)sp->data->N);
  } catch (const std::exception &e) {
    PetscCall(VSHMMSpectralOptionError_Private(sp, option, e));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode VSHMMSpectralReadGridFile_Private(MPI_Comm comm, const char path[], std::vector<double> &u)
{
  PetscFunctionBegin;
  std::ifstream in(path);
  PetscCheck(in, comm, PETSC_ERR_FILE_OPEN, "Cannot open the grid file '%s'", path);
  std::string line;
  u.clear();
  while (std::getline(in, line)) {
    std::istringstream  ls(line);
    std::vector<double> vals;
    double              v;
    while (ls >> v) vals.push_back(v);
    if (vals.empty()) continue;
    PetscCheck(vals.size() <= 2, comm, PETSC_ERR_FILE_UNEXPECTED, "Grid file '%s': a line has %d numbers; expected 'x u' or 'u'", path, (int)vals.size());
    u.push_back(vals.back());
  }
  PetscCheck(!u.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "Grid file '%s' has no values", path);
  PetscFunctionReturn(0);
}

/* The paper's fields: d = (exp(sin 64x) + exp(sin 256x))/4, a = exp((0.6 + 0.2 cos 3x)/(1 + 0.35 sin 64x + 0.35 sin 256x))/4, u0 = exp(-(x - pi)^2). */
static void PaperFields(VSHMMSpectral_Data *s)
{
  s->diff             = spc::Field::ofForm(spc::Field::Form::ExpSin);
  s->diff.weights     = {0.25, 0.25};
  s->diff.wavenumbers = {64, 256};

  s->vel                         = spc::Field::ofForm(spc::Field::Form::ExpRatio);
  s->vel.scale                   = 0.25;
  s->vel.numerator.offset        = 0.6;
  s->vel.numerator.wavenumbers   = {3};
  s->vel.numerator.cosines       = {0.2};
  s->vel.denominator.offset      = 1.0;
  s->vel.denominator.wavenumbers = {64, 256};
  s->vel.denominator.sines       = {0.35, 0.35};

  s->u0        = spc::Field::ofForm(spc::Field::Form::Gaussian);
  s->u0.center = PETSC_PI;
  s->u0.width  = 1.0;
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
  VSHMMSpectral s;

  PetscFunctionBegin;
  VSHMMValidPointer(sp, 2);
  *sp = nullptr;
  PetscCall(VSHMMSpectralInitializePackage());
  PetscCall(PetscHeaderCreate(s, VSHMMSPECTRAL_CLASSID, "VSHMMSpectral", "Sparse spectral scene", "TS", comm, VSHMMSpectralDestroy, VSHMMSpectralView));
  s->data = new VSHMMSpectral_Data();
  PaperFields(s->data);
  PetscCall(VSHMMSpectralSetDefaultScene(s, "diffusion"));
  *sp = s;
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
  if (!*sp) PetscFunctionReturn(0);
  VSHMMValidHeaderSpecific(*sp, VSHMMSPECTRAL_CLASSID, 1);
  if (--((PetscObject)(*sp))->refct > 0) {
    *sp = nullptr;
    PetscFunctionReturn(0);
  }
  PetscCall(VecScatterDestroy(&(*sp)->data->gather));
  PetscCall(VecDestroy(&(*sp)->data->Useq));
  delete (*sp)->data;
  PetscCall(PetscHeaderDestroy(sp));
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
  VSHMMSpectral_Data *s;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  s                      = sp->data;
  const std::string name = scene ? scene : "";
  if (name == "diffusion") {
    s->terms = {"diffusion"};
    s->N     = 2048;
  } else if (name == "advection") {
    s->terms = {"advection"};
    s->N     = 1024;
  } else SETERRQ(PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown default scene '%s': use diffusion or advection", name.c_str());
  s->scene        = name;
  sp->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralSetOptionsPrefix - Sets the prefix of the object's options: with prefix "a_" the
   grid size is read from -a_spectral_grid_points

   Logically Collective

   Input Parameters:
+  sp     - the object
-  prefix - the prefix (no leading hyphen)

   Notes:
   The short direct simulation of `-spectral_cluster_detect dns` is a TS with the prefix
   `<prefix>spectral_cluster_detect_`.

   Level: intermediate

.seealso: `VSHMMSpectralGetOptionsPrefix()`, `VSHMMSpectralSetFromOptions()`
@*/
PetscErrorCode VSHMMSpectralSetOptionsPrefix(VSHMMSpectral sp, const char prefix[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)sp, prefix));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetOptionsPrefix - Gets the prefix of the object's options

   Not Collective

   Input Parameter:
.  sp - the object

   Output Parameter:
.  prefix - the prefix (NULL if none)

   Level: intermediate

.seealso: `VSHMMSpectralSetOptionsPrefix()`
@*/
PetscErrorCode VSHMMSpectralGetOptionsPrefix(VSHMMSpectral sp, const char *prefix[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)sp, prefix));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetSizes - Grid points, retained coefficients (the Vec size) and clusters

   Collective (sets the object up if needed)

   Input Parameter:
.  sp - the object

   Output Parameters:
+  N         - grid points
.  ncoef     - reals in the state Vec
-  nclusters - clusters (0 in mode dns)

   Level: intermediate

.seealso: `VSHMMSpectralGetCluster()`, `VSHMMSpectralGetModes()`
@*/
PetscErrorCode VSHMMSpectralGetSizes(VSHMMSpectral sp, PetscInt *N, PetscInt *ncoef, PetscInt *nclusters)
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(VSHMMSpectralSetUp(sp));
  if (N) *N = sp->data->N;
  if (ncoef) *ncoef = sp->data->layout->size();
  if (nclusters) *nclusters = sp->data->mode == VSHMMSPECTRAL_MODE_SPARSE ? sp->data->layout->clusterCount() : 0;
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetCluster - The wavenumbers of cluster j and its range in the state Vec

   Collective (sets the object up if needed)

   Input Parameters:
+  sp - the object (mode sparse)
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
  VSHMMSpectral_Data *s;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(VSHMMSpectralSetUp(sp));
  s = sp->data;
  PetscCheck(j >= 0 && j < (PetscInt)s->cluster_modes.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Cluster %" PetscInt_FMT " does not exist", j);
  if (nmodes) *nmodes = (PetscInt)s->cluster_modes[j].size();
  if (modes) *modes = s->cluster_modes[j].data();
  if (begin) *begin = s->layout->clusterOffsetBegin((int)j);
  if (end) *end = s->layout->clusterOffsetEnd((int)j);
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetScaleSeparations - The time-scale separation of consecutive clusters, for `TSVSHMMSetScaleSeparations()`

   Collective (sets the object up if needed)

   Input Parameter:
.  sp - the object

   Output Parameters:
+  n - the number of separations: the number of clusters less one (0 in mode dns, with one
       cluster, or where the scene has no diffusion or advection to give a rate)
-  S - the separations, slowest pair first (owned by sp)

   Notes:
   S_j is the rate of the slowest wavenumber k > 0 of cluster j+1, mean|d| k^2 + mean|a| k, over
   the rate of the fastest wavenumber of cluster j, max|d| k^2 + max|a| k, with d the diffusion
   coefficient and a the velocity of the scene. A cluster spans a band of rates, and the averaging
   error of VSHMM is set by the slowest mode of the faster cluster, while TSVSHMM's own estimate
   (the ratio of the levels' spectral radii) sees their fastest modes. The nonlinear terms
   (burgers, reaction) are not counted.

   Level: intermediate

.seealso: `TSVSHMMSetScaleSeparations()`, `VSHMMSpectralGetCluster()`, `VSHMMSpectralSetUpTS()`
@*/
PetscErrorCode VSHMMSpectralGetScaleSeparations(VSHMMSpectral sp, PetscInt *n, const PetscReal *S[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(VSHMMSpectralSetUp(sp));
  if (n) *n = (PetscInt)sp->data->separations.size();
  if (S) *S = sp->data->separations.empty() ? nullptr : sp->data->separations.data();
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralGetModes - Every retained wavenumber, in the order of the state Vec (cluster by
   cluster, each ascending; 0..N/2 in mode dns)

   Collective (sets the object up if needed)

   Input Parameter:
.  sp - the object

   Output Parameters:
+  nmodes - number of retained wavenumbers
-  modes  - the wavenumbers (owned by sp)

   Level: intermediate

.seealso: `VSHMMSpectralGetModeMagnitudes()`, `VSHMMSpectralGetCluster()`
@*/
PetscErrorCode VSHMMSpectralGetModes(VSHMMSpectral sp, PetscInt *nmodes, const PetscInt *modes[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(VSHMMSpectralSetUp(sp));
  if (nmodes) *nmodes = (PetscInt)sp->data->modes.size();
  if (modes) *modes = sp->data->modes.data();
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralReadGridValues - Reads a grid file (N lines "x u" or "u", as the examples write
   with -grid_solution_file) of the object's grid

   Collective

   Input Parameters:
+  sp   - the object
-  file - the file name

   Output Parameter:
.  u - the N values (caller's array)

   Level: intermediate

.seealso: `VSHMMSpectralGetGridValues()`
@*/
PetscErrorCode VSHMMSpectralReadGridValues(VSHMMSpectral sp, const char file[], PetscReal u[])
{
  std::vector<double> v;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(VSHMMSpectralReadGridFile_Private(PetscObjectComm((PetscObject)sp), file, v));
  PetscCheck((PetscInt)v.size() == sp->data->N, PetscObjectComm((PetscObject)sp), PETSC_ERR_ARG_SIZ, "Grid file '%s' has %d values, the grid has N = %" PetscInt_FMT, file, (int)v.size(), sp->data->N);
  for (size_t j = 0; j < v.size(); ++j) u[j] = v[j];
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
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  VSHMMValidPointer(stats, 2);
  *stats = sp->data->stats;
  PetscFunctionReturn(0);
}
