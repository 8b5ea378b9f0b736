/*
  Private header of VSHMMSpectral (include/petscvshmmspectral.h): the object, its log events and
  the functions shared by the files of src/spectral, split by concern as SLEPc splits
  src/eps/interface:

    spectralbasic.cpp  the package (class id, log events), creation, destruction, options prefix,
                       default scenes, sizes, clusters, statistics
    spectralopts.cpp   VSHMMSpectralSetFromOptions(): the scene read with PETSc's readers
    spectralsetup.cpp  VSHMMSpectralSetUp(): fields, clusters (explicit or detected), operator
    spectralrhs.cpp    the state Vec, the right-hand side, the splits and the physical-space cache
    spectralview.cpp   VSHMMSpectralView()

  The numerical core (no PETSc) is src/core/spectral.
*/
#pragma once

#include <petscvshmmspectral.h>
#include <petsc/private/petscimpl.h>
#include "vshmmvalid.hpp"

#include "detect.hpp"
#include "spectral.hpp"
#include "stable.hpp"
#include "truncation.hpp"

#include <cmath>
#include <complex>

#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace spc = vshmm::spectral;

typedef enum {
  VSHMMSPECTRAL_MODE_DNS,
  VSHMMSPECTRAL_MODE_SPARSE
} VSHMMSpectralMode;
PETSC_INTERN const char *const VSHMMSpectralModes[];

typedef enum {
  VSHMMSPECTRAL_DETECT_NONE,
  VSHMMSPECTRAL_DETECT_INITIAL,
  VSHMMSPECTRAL_DETECT_DNS,
  VSHMMSPECTRAL_DETECT_FILE,
  VSHMMSPECTRAL_DETECT_AUTO
} VSHMMSpectralDetect;
PETSC_INTERN const char *const VSHMMSpectralDetects[];

typedef enum {
  VSHMMSPECTRAL_PROJECTION_AUTO,
  VSHMMSPECTRAL_PROJECTION_FFT,
  VSHMMSPECTRAL_PROJECTION_DIRECT
} VSHMMSpectralProjection;
PETSC_INTERN const char *const VSHMMSpectralProjections[];

typedef enum {
  VSHMMSPECTRAL_EVALUATION_FFT,
  VSHMMSPECTRAL_EVALUATION_MATRIX
} VSHMMSpectralEvaluation;
PETSC_INTERN const char *const VSHMMSpectralEvaluations[];

typedef enum {
  VSHMMSPECTRAL_PLANNER_ESTIMATE,
  VSHMMSPECTRAL_PLANNER_MEASURE,
  VSHMMSPECTRAL_PLANNER_PATIENT
} VSHMMSpectralPlanner;
PETSC_INTERN const char *const VSHMMSpectralPlanners[];

PETSC_INTERN const char *const VSHMMSpectralNormalizations[];

/* The cluster detection's outcome, for VSHMMSpectralView() (the library prints nothing itself). */
struct VSHMMSpectralDetection {
  PetscReal              dt         = 0; /* RK3 time step of the detection DNS (0: no DNS); its looks are at multiples of it */
  PetscInt               rkc_stages = 0; /* > 0: the DNS took RKC steps of rkc_step with this many stages instead */
  PetscReal              rkc_step   = 0;
  std::vector<PetscReal> times;              /* its snapshot times */
  PetscInt               support     = 0;    /* wavenumbers above the threshold */
  PetscInt               merged      = 0;    /* bands (groups of wavenumbers) found */
  PetscInt               scales      = 0;    /* clusters (time scales) they were grouped into */
  PetscInt               steps       = 0;    /* time steps of the detection DNS */
  PetscInt               evaluations = 0;    /* operator evaluations of the detection (DNS and the auto rule's F(u0)) */
  PetscLogDouble         wall        = 0;    /* wall time of the detection */
  bool                   converged   = true; /* auto snapshots: the clusters stopped changing before the step limit */
  PetscReal              merged_at   = 0;    /* auto snapshots: the look at which bands merged and the previous look's were kept (0: none) */
  PetscReal              kept        = 0;    /* the time of that previous look */
  PetscReal              widened     = -1;   /* auto snapshots: the agreeing looks' bands widened by wavenumbers holding this share of ||u|| (-1: the looks were the same) */
  PetscReal              left_out    = -1;   /* auto snapshots: RMS over the steps of ||u outside the bands|| / ||u|| (-1: not known) */
  std::string            dropped;            /* auto snapshots: the bands left out by -spectral_cluster_min_band_share, with their shares */
  std::string            kept_band;          /* auto snapshots: the thin band min_band_share kept, and why (empty: none) */
  std::string            rule;               /* -spectral_cluster_detect auto: what it decided and why */
};

struct SplitCtx {
  VSHMMSpectral sp;
  PetscInt      j;
};

static inline spc::Field ConstantField(double v)
{
  spc::Field f = spc::Field::ofForm(spc::Field::Form::Constant);
  f.value      = v;
  return f;
}

/* The C++ state of a VSHMMSpectral: the scene, the set-up and the physical-space cache. */
struct VSHMMSpectral_Data {
  /* the scene */
  std::string              scene = "diffusion";
  PetscInt                 N     = 2048;
  std::vector<std::string> terms;
  spc::Field               diff, vel, u0;
  spc::Field               burgers = ConstantField(1.0); /* burgers: -(c u^2/2)_x */
  spc::Field               rate    = ConstantField(1.0); /* reaction: r(x) (c0 + c1 u + c2 u^2 + c3 u^3) */
  spc::Field               source  = ConstantField(0.0); /* source: s(x) */
  std::vector<PetscReal>   reaction;                     /* c0..c3 (fewer: the rest 0) */
  VSHMMSpectralMode        mode = VSHMMSPECTRAL_MODE_DNS;
  std::string              cluster_spec;
  VSHMMSpectralDetect      detect           = VSHMMSPECTRAL_DETECT_NONE; /* none in sparse mode without clusters: auto */
  PetscReal                lambda           = -1;                        /* negative: spc::defaultLambda(norm) */
  PetscInt                 gap              = -1;                        /* negative: spc::groupIntoClusters() with gap_ratio */
  PetscReal                gap_ratio        = 1.0 / 3.0;
  PetscBool                fill_holes       = PETSC_TRUE;
  PetscReal                scale_separation = 10; /* detected bands closer than this in time scale share a cluster */
  std::vector<PetscInt>    buffers;
  spc::Normalization       norm = spc::Normalization::Relative;
  std::vector<PetscReal>   detect_times;
  std::string              detect_file;
  PetscReal                detect_dt          = 0;
  PetscInt                 detect_max_steps   = 32768;
  PetscInt                 detect_first_steps = 64;         /* steps before the first automatic look (then doubled) */
  PetscInt                 detect_agreeing    = 3;          /* automatic looks in a row that agree end the detection */
  PetscBool                detect_rkc         = PETSC_TRUE; /* automatic looks: RKC steps where they need fewer evaluations than RK3 */
  PetscReal                min_band_share     = 0.05;       /* the detection's highest bands holding less than this times cluster_tol of ||u|| are left out */
  PetscReal                cluster_tol        = 1e-2;       /* merged bands are undone if what the merge adds holds at most this of ||u|| */
  VSHMMSpectralProjection  projection         = VSHMMSPECTRAL_PROJECTION_AUTO;
  VSHMMSpectralEvaluation  evaluation         = VSHMMSPECTRAL_EVALUATION_FFT;
  VSHMMSpectralPlanner     planner            = VSHMMSPECTRAL_PLANNER_ESTIMATE;
  PetscReal                growth_factor      = 10; /* -spectral_growth_bound (0: no check) */

  /* set-up */
  spc::ClusterSet                        clusters;
  VSHMMSpectralDetection                 detection;
  std::unique_ptr<spc::Layout>           layout;
  std::unique_ptr<spc::SpectralOperator> op;
  std::unique_ptr<spc::DenseOperator>    dense;
  std::vector<std::vector<PetscInt>>     cluster_modes; /* for VSHMMSpectralGetCluster() */
  std::vector<PetscInt>                  modes;         /* every retained wavenumber, in the layout */
  std::vector<PetscReal>                 separations;   /* of consecutive clusters, from the linear terms (VSHMMSpectralGetScaleSeparations()) */
  std::vector<SplitCtx>                  split_ctx;
  VecScatter                             gather = nullptr;
  Vec                                    Useq   = nullptr;
  std::vector<double>                    out;

  /* the physical-space field of the last state seen */
  PetscBool        cache_valid = PETSC_FALSE, fft_done = PETSC_FALSE;
  PetscObjectId    cache_id     = 0;
  PetscObjectState cache_state  = 0;
  PetscReal        cache_t      = 0;
  double           direct_spent = 0;

  VSHMMSpectralStatistics stats = {};

  /* stable steps and the growth check (spectralstable.cpp) */
  PetscBool                         ritz_done = PETSC_FALSE;     /* ritz holds the estimate of this set-up */
  std::vector<std::complex<double>> ritz;                        /* Ritz values of the operator's Jacobian at u0 */
  PetscBool                         dns_ritz_done = PETSC_FALSE; /* dns_ritz holds those of the operator on every wavenumber */
  std::vector<std::complex<double>> dns_ritz;
  PetscReal                         radius_bound = 0; /* max|D| kmax^2 + max|A| kmax */
  std::vector<double>               weights;          /* Parseval weights of the layout's reals */
  PetscBool                         growth_started = PETSC_FALSE, growth_needs_max = PETSC_FALSE;
  spc::GrowthBound                  growth;
  PetscReal                         growth_max = 0; /* max|u| on the grid at the last check */

  /* the truncation check (spectralstable.cpp): the left-out wavenumbers of a sparse run */
  VSHMMSpectralTruncationCheck           truncation_check = VSHMMSPECTRAL_TRUNCATION_WARN; /* -spectral_truncation_check */
  std::unique_ptr<spc::Layout>           full_layout;                                      /* every wavenumber, and the operator on it */
  std::unique_ptr<spc::SpectralOperator> full_op;
  spc::TruncationModel                   truncation;                                                        /* the left-out wavenumbers */
  spc::TruncationModel                   feedback;                                                          /* what they change in the retained ones */
  PetscBool                              truncation_started = PETSC_FALSE, truncation_warned = PETSC_FALSE; /* its share and time: stats */
  PetscReal                              truncation_warned_share = 0;                                       /* the share of the run's last warning (it warns again at kWarnAgain times it) */
  /* -spectral_truncation_check widen: the buffers per cluster the check asks for (pending), and
     the clusters of the widenings applied (used by the set-up instead of the detection's) */
  std::vector<char> truncation_detuned; /* per left-out wavenumber of `truncation`: its rate is mostly advection's detuning (not widened) */
  std::vector<int>  widen_buffers;
  PetscReal         widen_time = 0;
  PetscInt          widen_step = 0;           /* the step of the request: a program that restarts stops the solve after the next step */
  PetscBool         widen_all  = PETSC_FALSE; /* the request is every wavenumber (a direct simulation) */
  spc::ClusterSet   widened;
  PetscInt          widenings            = 0;
  PetscInt64        widening_evaluations = 0;
};

typedef struct _VSHMMSpectralOps *VSHMMSpectralOps;
struct _VSHMMSpectralOps {
  PetscErrorCode (*view)(VSHMMSpectral, PetscViewer);
};

struct _p_VSHMMSpectral {
  PETSCHEADER(struct _VSHMMSpectralOps);
  VSHMMSpectral_Data *data;
  PetscBool           setupcalled;
};

/* log events (registered by VSHMMSpectralInitializePackage()) */
PETSC_INTERN PetscLogEvent VSHMMSPECTRAL_SetUp, VSHMMSPECTRAL_RHS, VSHMMSPECTRAL_Split, VSHMMSPECTRAL_Physical, VSHMMSPECTRAL_ForwardFFT, VSHMMSPECTRAL_ProjDirect, VSHMMSPECTRAL_MatVec, VSHMMSPECTRAL_Eigen, VSHMMSPECTRAL_Growth, VSHMMSPECTRAL_Truncation, VSHMMSPECTRAL_Detect;

/* |c_k|, k = 0..N/2, of coefficients in the full layout (Layout::full()): the detection's and the
   truncation check's magnitudes. */
static inline std::vector<double> VSHMMSpectralFullMagnitudes(const spc::Layout &full, const double *c)
{
  std::vector<double> m(full.modeCount());
  for (int i = 0; i < full.modeCount(); ++i) {
    const int k = full.mode(i), o = full.offset(i);
    m[k] = spc::isRealOnly(full.N(), k) ? std::fabs(c[o]) : std::hypot(c[o], c[o + 1]);
  }
  return m;
}

/* The options prefix of sp ("" without one), for error messages that name an option. */
static inline const char *VSHMMSpectralPrefix(VSHMMSpectral sp)
{
  return ((PetscObject)sp)->prefix ? ((PetscObject)sp)->prefix : "";
}

/* The shrinkage value in use (-spectral_cluster_lambda or the normalisation's default). */
static inline PetscReal VSHMMSpectralLambda(const VSHMMSpectral_Data *s)
{
  return s->lambda >= 0 ? s->lambda : spc::defaultLambda(s->norm);
}

/* An error of the numerical core (a std::exception) as a PETSc error naming the option. */
PETSC_INTERN PetscErrorCode VSHMMSpectralOptionError_Private(VSHMMSpectral, const char[], const std::exception &);
/* u0, d or a on the grid; an error names the option of the field. */
PETSC_INTERN PetscErrorCode VSHMMSpectralSampleField_Private(VSHMMSpectral, const char[], const spc::Field &, std::vector<double> &);
/* Grid values "x u" (or "u") per line, the format of the examples' grid solution files. */
PETSC_INTERN PetscErrorCode VSHMMSpectralReadGridFile_Private(MPI_Comm, const char[], std::vector<double> &);
/* The fields D = sum of diffusion coefficients, A = - sum of velocities, on the grid. */
PETSC_INTERN PetscErrorCode VSHMMSpectralBuildCoefficients_Private(VSHMMSpectral, std::vector<double> &, std::vector<double> &);
/* The time-scale separation of consecutive clusters from the linear terms D, A (the slowest rate of
   cluster j+1 over the fastest of cluster j; empty without linear rates). */
PETSC_INTERN std::vector<PetscReal> VSHMMSpectralClusterSeparations_Private(const std::vector<std::vector<PetscInt>> &, const std::vector<double> &, const std::vector<double> &);
/* The terms burgers, reaction and source of the scene on the grid (empty fields for absent terms). */
PETSC_INTERN PetscErrorCode VSHMMSpectralBuildExtraTerms_Private(VSHMMSpectral, spc::ExtraTerms &);
/* spectralstable.cpp: the Ritz values of op's Jacobian at the coefficients c0 (Arnoldi), and the
   stable step of a TSRK type for them (0.9 times the largest; PETSC_INFINITY if none limits it). */
PETSC_INTERN PetscErrorCode VSHMMSpectralRitzValues_Private(MPI_Comm, spc::SpectralOperator &, const std::vector<double> &, std::vector<std::complex<double>> &, PetscInt *);
PETSC_INTERN PetscErrorCode VSHMMSpectralStableStepOf_Private(MPI_Comm, const std::vector<std::complex<double>> &, TSRKType, PetscReal *);
/* The whole state on every rank (the Vec's own array on one rank, a gathered copy otherwise). */
PETSC_INTERN PetscErrorCode VSHMMSpectralGetCoefficients_Private(VSHMMSpectral, Vec, const PetscScalar **);
PETSC_INTERN PetscErrorCode VSHMMSpectralRestoreCoefficients_Private(VSHMMSpectral, Vec, const PetscScalar **);
