/*
   petscvshmmspectral.h - sparse spectral multiscale PDEs for TSVSHMM (part of petsc-vshmm).

   A VSHMMSpectral object holds one periodic 1-D problem on [0, 2 pi) ("a scene"):

       u_t = F(u) = sum over the scene's terms of
                    diffusion:  d/dx( d(x) du/dx )
                    advection:  - a(x) du/dx
                    burgers:    - d/dx( c(x) u^2 / 2 )
                    reaction:   r(x) (c0 + c1 u + c2 u^2 + c3 u^3)
                    source:     s(x)

   discretised by the Fourier pseudo-spectral method on N points with FFTW, either on every
   mode (mode "dns") or on a sparse set of retained wavenumbers grouped in clusters (mode
   "sparse"), each cluster one TSRHSSplit, slowest (lowest wavenumbers) first, so that
   -ts_type vshmm integrates the clusters as the scales of the Lee-Engquist method.

   The state Vec holds the Fourier series coefficients c_k (u(x) = sum_k c_k exp(i k x)) of the
   retained wavenumbers k >= 0, as reals, cluster by cluster, each cluster in ascending k:
   Re c_k, Im c_k, except k = 0 and k = N/2 (N even), which store Re c_k only. In mode "dns"
   every k = 0..N/2 is retained and the Vec has N entries.

   A VSHMMSpectral is a PetscObject (class id VSHMMSPECTRAL_CLASSID) whose options are named
   -[prefix]spectral_<name>: -spectral_grid_points, -spectral_terms, -spectral_diffusion_coefficient,
   -spectral_velocity, -spectral_u0, -spectral_mode, -spectral_clusters, -spectral_cluster_detect, ...
   (see VSHMMSpectralSetFromOptions() and docs/spectral.md). The library writes nothing itself:
   VSHMMSpectralView() shows the scene; the examples in examples/spectral write the solutions.

   VSHMMSpectralGetStableTimeStep() estimates a stable explicit Runge-Kutta step from the
   operator's eigenvalues; VSHMMSpectralSetUpTS() also sets a TS monitor that stops a solve whose
   solution grows beyond what the scene's terms allow (-spectral_growth_bound).
*/
#ifndef PETSCVSHMMSPECTRAL_H
#define PETSCVSHMMSPECTRAL_H

#include <petscts.h>

/*S
   VSHMMSpectral - a periodic 1-D Fourier pseudo-spectral problem (a "scene") whose retained
   wavenumbers are grouped in clusters, one TSRHSSplit per cluster

   Level: beginner

.seealso: `VSHMMSpectralCreate()`, `VSHMMSpectralSetFromOptions()`, `VSHMMSpectralSetUpTS()`, `VSHMMSpectralView()`
S*/
typedef struct _p_VSHMMSpectral *VSHMMSpectral;

PETSC_EXTERN PetscClassId VSHMMSPECTRAL_CLASSID;

/*S
   VSHMMSpectralStatistics - work counted by a VSHMMSpectral since its set-up

   Fields:
+  rhs_calls        - calls of the full right-hand side (TSSetRHSFunction())
.  split_calls      - calls of the cluster splits (all clusters)
.  field_evaluations - evaluations of a right-hand-side field: rhs_calls plus the calls of the
                       slowest split (each VSHMM level evaluation calls it first)
.  inverse_ffts     - c2r transforms (one per state seen, shared by the splits of a level)
.  forward_ffts     - r2c transforms
.  direct_modes     - modes projected by direct sums over the grid instead of a transform
.  cache_hits       - split calls that reused the physical-space field of the same state
.  detection_steps  - time steps of the cluster detection's direct simulation (set-up work, not in the counts above)
.  detection_evaluations - operator evaluations of the cluster detection (its direct simulation and the auto rule's F(u0)), each on every mode
.  detection_time   - wall time of the cluster detection, seconds
.  truncation_share - the truncation check's largest model of the share of ||u|| that the clusters leave out (sparse mode; 0 before a solve or with -spectral_truncation_check none)
.  truncation_time  - where it was largest
.  widenings        - clusters widened by `VSHMMSpectralWidenClusters()` (-spectral_truncation_check widen), counted over the object's life
-  widening_evaluations - field evaluations of the runs stopped for those widenings (work spent, not in field_evaluations)

   Level: intermediate

.seealso: `VSHMMSpectralGetStatistics()`
S*/
typedef struct {
  PetscInt64     rhs_calls;
  PetscInt64     split_calls;
  PetscInt64     field_evaluations;
  PetscInt64     inverse_ffts;
  PetscInt64     forward_ffts;
  PetscInt64     direct_modes;
  PetscInt64     cache_hits;
  PetscInt64     detection_steps;
  PetscInt64     detection_evaluations;
  PetscLogDouble detection_time;
  PetscReal      truncation_share;
  PetscReal      truncation_time;
  PetscInt       widenings;
  PetscInt64     widening_evaluations;
} VSHMMSpectralStatistics;

PETSC_EXTERN PetscErrorCode VSHMMSpectralInitializePackage(void);
PETSC_EXTERN PetscErrorCode VSHMMSpectralFinalizePackage(void);
PETSC_EXTERN PetscErrorCode VSHMMSpectralCreate(MPI_Comm, VSHMMSpectral *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralDestroy(VSHMMSpectral *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetDefaultScene(VSHMMSpectral, const char[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetOptionsPrefix(VSHMMSpectral, const char[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetOptionsPrefix(VSHMMSpectral, const char *[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetFromOptions(VSHMMSpectral);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetUp(VSHMMSpectral);
PETSC_EXTERN PetscErrorCode VSHMMSpectralView(VSHMMSpectral, PetscViewer);
PETSC_EXTERN PetscErrorCode VSHMMSpectralViewFromOptions(VSHMMSpectral, PetscObject, const char[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetSizes(VSHMMSpectral, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetCluster(VSHMMSpectral, PetscInt, PetscInt *, const PetscInt *[], PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetModes(VSHMMSpectral, PetscInt *, const PetscInt *[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetScaleSeparations(VSHMMSpectral, PetscInt *, const PetscReal *[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralCreateVec(VSHMMSpectral, Vec *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetInitialCondition(VSHMMSpectral, Vec);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetGridValues(VSHMMSpectral, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetModeMagnitudes(VSHMMSpectral, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralReadGridValues(VSHMMSpectral, const char[], PetscReal[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralRHSFunction(TS, PetscReal, Vec, Vec, void *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetUpTS(VSHMMSpectral, TS);
PETSC_EXTERN PetscErrorCode VSHMMSpectralEstimateTimeStep(VSHMMSpectral, PetscReal *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetStableTimeStep(VSHMMSpectral, TSRKType, PetscReal *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetStableTimeStepAt(VSHMMSpectral, Vec, TSRKType, PetscReal *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetDNSStableTimeStep(VSHMMSpectral, TSRKType, PetscReal *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetSpectralRadius(VSHMMSpectral, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetGrowthBound(VSHMMSpectral, PetscReal);

/*E
   VSHMMSpectralTruncationCheck - what the truncation check of a sparse run does when the
   wavenumbers its clusters leave out exceed the clusters' tolerance (`VSHMMSpectralTruncationMonitor()`)

$  VSHMMSPECTRAL_TRUNCATION_NONE - no check
$  VSHMMSPECTRAL_TRUNCATION_WARN - a warning on the standard error, once per solve (the default)
$  VSHMMSPECTRAL_TRUNCATION_ERROR - the solve stops with PETSC_ERR_NOT_CONVERGED
$  VSHMMSPECTRAL_TRUNCATION_WIDEN - the check records the buffers that would hold the left-out
$    wavenumbers, for a program that stops its solve (`VSHMMSpectralGetTruncationWidening()`),
$    widens the clusters (`VSHMMSpectralWidenClusters()`) and runs again from its initial state;
$    where the widened clusters would not be separated it asks for every wavenumber (a direct
$    simulation) if the figure passes the tolerance in the TS's measure, and warns otherwise;
$    after six widenings, where advection's detuning sets the model, or at the end of a solve
$    whose widening was not applied, it warns

   Level: intermediate

.seealso: `VSHMMSpectralSetTruncationCheck()`
E*/
typedef enum {
  VSHMMSPECTRAL_TRUNCATION_NONE,
  VSHMMSPECTRAL_TRUNCATION_WARN,
  VSHMMSPECTRAL_TRUNCATION_ERROR,
  VSHMMSPECTRAL_TRUNCATION_WIDEN
} VSHMMSpectralTruncationCheck;
PETSC_EXTERN const char *const VSHMMSpectralTruncationChecks[];
PETSC_EXTERN PetscErrorCode    VSHMMSpectralSetTruncationCheck(VSHMMSpectral, VSHMMSpectralTruncationCheck);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralGetTruncationWidening(VSHMMSpectral, PetscBool *, PetscReal *);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralWidenClusters(VSHMMSpectral, PetscBool *);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralSetClusterTolerance(VSHMMSpectral, PetscReal);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralSetClusterThreshold(VSHMMSpectral, PetscReal);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralGrowthMonitor(TS, PetscInt, PetscReal, Vec, void *);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralTruncationMonitor(TS, PetscInt, PetscReal, Vec, void *);
PETSC_EXTERN PetscErrorCode    VSHMMSpectralGetStatistics(VSHMMSpectral, VSHMMSpectralStatistics *);

#endif
