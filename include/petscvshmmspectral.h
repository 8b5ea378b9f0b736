/*
   petscvshmmspectral.h - sparse spectral multiscale PDEs for TSVSHMM (part of petsc-vshmm).

   A VSHMMSpectral object holds one periodic 1-D problem on [0, 2 pi) ("a scene"):

       u_t = F(u) = sum over the scene's terms of
                    diffusion:  d/dx( d(x) du/dx )
                    advection:  - a(x) du/dx

   discretised by the Fourier pseudo-spectral method on N points with FFTW, either on every
   mode (mode "dns") or on a sparse set of retained wavenumbers grouped in clusters (mode
   "sparse"), each cluster one TSRHSSplit, slowest (lowest wavenumbers) first, so that
   -ts_type vshmm integrates the clusters as the scales of the Lee-Engquist method.

   The state Vec holds the Fourier series coefficients c_k (u(x) = sum_k c_k exp(i k x)) of the
   retained wavenumbers k >= 0, as reals, cluster by cluster, each cluster in ascending k:
   Re c_k, Im c_k, except k = 0 and k = N/2 (N even), which store Re c_k only. In mode "dns"
   every k = 0..N/2 is retained and the Vec has N entries.

   See docs/spectral.md for the options (-terms, -diffusion_coefficient, -velocity, -u0,
   -clusters, -cluster_detect, -output_times, -grid_solution_file, ...).
*/
#ifndef PETSCVSHMMSPECTRAL_H
#define PETSCVSHMMSPECTRAL_H

#include <petscts.h>

/*S
   VSHMMSpectral - a periodic 1-D Fourier pseudo-spectral problem (a "scene") whose retained
   wavenumbers are grouped in clusters, one TSRHSSplit per cluster

   Level: beginner

.seealso: `VSHMMSpectralCreate()`, `VSHMMSpectralSetFromOptions()`, `VSHMMSpectralSetUpTS()`, `VSHMMSpectralSolve()`
S*/
typedef struct _n_VSHMMSpectral *VSHMMSpectral;

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
-  cache_hits       - split calls that reused the physical-space field of the same state

   Level: intermediate

.seealso: `VSHMMSpectralGetStatistics()`
S*/
typedef struct {
  PetscInt64 rhs_calls;
  PetscInt64 split_calls;
  PetscInt64 field_evaluations;
  PetscInt64 inverse_ffts;
  PetscInt64 forward_ffts;
  PetscInt64 direct_modes;
  PetscInt64 cache_hits;
} VSHMMSpectralStatistics;

PETSC_EXTERN PetscErrorCode VSHMMSpectralCreate(MPI_Comm, VSHMMSpectral *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralDestroy(VSHMMSpectral *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetDefaultScene(VSHMMSpectral, const char[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetFromOptions(VSHMMSpectral);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetUp(VSHMMSpectral);
PETSC_EXTERN PetscErrorCode VSHMMSpectralView(VSHMMSpectral, PetscViewer);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetSizes(VSHMMSpectral, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetCluster(VSHMMSpectral, PetscInt, PetscInt *, const PetscInt *[], PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralCreateVec(VSHMMSpectral, Vec *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetInitialCondition(VSHMMSpectral, Vec);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetGridValues(VSHMMSpectral, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode VSHMMSpectralRHSFunction(TS, PetscReal, Vec, Vec, void *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSetUpTS(VSHMMSpectral, TS);
PETSC_EXTERN PetscErrorCode VSHMMSpectralEstimateTimeStep(VSHMMSpectral, PetscReal *);
PETSC_EXTERN PetscErrorCode VSHMMSpectralSolve(VSHMMSpectral, TS, Vec);
PETSC_EXTERN PetscErrorCode VSHMMSpectralGetStatistics(VSHMMSpectral, VSHMMSpectralStatistics *);

#endif
