// Tests of the VSHMMSpectral object (src/spectral): bad options give a PETSc error that names the
// option (with the object's prefix), lists take every value given, a field form given only some
// of its parameters takes the stated defaults for the others. Each test reads its options from
// its own PetscOptions database.
#include <gtest/gtest.h>
#include <petscvshmmspectral.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

// PETSc for this file's tests (GoogleTest's main runs them).
class PetscEnvironment : public ::testing::Environment {
public:
  void SetUp() override { ASSERT_EQ(PetscInitializeNoArguments(), 0); }
  void TearDown() override { ASSERT_EQ(PetscFinalize(), 0); }
};
::testing::Environment *const petsc_environment = ::testing::AddGlobalTestEnvironment(new PetscEnvironment);

// A VSHMMSpectral with its own options database.
struct Scene {
  VSHMMSpectral sp   = nullptr;
  PetscOptions  opts = nullptr;

  explicit Scene(const std::string &options, const char *prefix = nullptr)
  {
    EXPECT_EQ(PetscOptionsCreate(&opts), 0);
    EXPECT_EQ(PetscOptionsInsertString(opts, options.c_str()), 0);
    EXPECT_EQ(VSHMMSpectralCreate(PETSC_COMM_WORLD, &sp), 0);
    EXPECT_EQ(PetscObjectSetOptions((PetscObject)sp, opts), 0);
    if (prefix) EXPECT_EQ(VSHMMSpectralSetOptionsPrefix(sp, prefix), 0);
  }
  ~Scene()
  {
    VSHMMSpectralDestroy(&sp);
    PetscOptionsDestroy(&opts);
  }
  // The first message of the error of SetFromOptions + SetUp ("" without an error).
  std::string error()
  {
    std::string message;
    PetscPushErrorHandler(
      [](MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx) -> PetscErrorCode {
        std::string *m = (std::string *)ctx;
        if (p == PETSC_ERROR_INITIAL && m->empty() && mess) *m = mess;
        return n;
      },
      &message);
    PetscErrorCode ierr = VSHMMSpectralSetFromOptions(sp);
    if (!ierr) ierr = VSHMMSpectralSetUp(sp);
    PetscPopErrorHandler();
    EXPECT_EQ(ierr != 0, !message.empty());
    return message;
  }
  // VSHMMSpectralView() as a string.
  std::string view()
  {
    char        buf[4096] = "";
    PetscViewer v;
    EXPECT_EQ(PetscViewerStringOpen(PETSC_COMM_WORLD, buf, sizeof(buf), &v), 0);
    EXPECT_EQ(VSHMMSpectralView(sp, v), 0);
    EXPECT_EQ(PetscViewerDestroy(&v), 0);
    return buf;
  }
};

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

} // namespace

TEST(VSHMMSpectralOptions, GoodSceneHasNoError)
{
  Scene s("-spectral_grid_points 64 -spectral_mode sparse -spectral_clusters 0:3,10:12");
  EXPECT_EQ(s.error(), "");
  PetscInt N, ncoef, nclusters;
  EXPECT_EQ(VSHMMSpectralGetSizes(s.sp, &N, &ncoef, &nclusters), 0);
  EXPECT_EQ(N, 64);
  EXPECT_EQ(ncoef, 7 + 6);
  EXPECT_EQ(nclusters, 2);
}

// Options and a part of the error message they must give.
struct BadOptions {
  const char *options, *message;
};

static const BadOptions kBadValues[] = {
  {"-spectral_grid_points 2", "-spectral_grid_points 2 is too small"},
  {"-spectral_terms diffusion,convection", "Unknown term 'convection' in -spectral_terms"},
  {"-spectral_terms diffusion,diffusion", "appears twice in -spectral_terms"},
  {"-spectral_mode fast", "Unknown option fast for -spectral_mode. Available options: dns sparse"},
  {"-spectral_u0 wavelet", "-spectral_u0"},
  {"-spectral_cluster_gap_ratio -1", "-spectral_cluster_gap_ratio must be finite and nonnegative"},
  {"-spectral_cluster_scale_separation -2", "-spectral_cluster_scale_separation must be finite and nonnegative"},
  {"-spectral_cluster_detect_max_steps 0", "-spectral_cluster_detect_max_steps must be positive"},
  {"-spectral_cluster_buffers 1,-2", "-spectral_cluster_buffers"},
  {"-spectral_cluster_detect_times 0.2,0.1", "-spectral_cluster_detect_times must be finite, nonnegative and increasing; item 2"},
  {"-spectral_cluster_detect_dt -1", "-spectral_cluster_detect_dt"},
  {"-spectral_u0 samples", "-spectral_u0 samples needs -spectral_u0_file"},
  {"-spectral_mode sparse -spectral_cluster_detect dns", "needs -spectral_cluster_detect_times"},
  {"-spectral_diffusion_coefficient_weights 1", "-spectral_diffusion_coefficient: expsin: 1 weights but 2 wavenumbers"},
  // PETSc's readers take a value-less option for an absent one and drop empty list items
  {"-spectral_grid_points 64 -spectral_cluster_lambda", "-spectral_cluster_lambda is given without a value"},
  {"-spectral_terms", "-spectral_terms is given without a value"},
  {"-spectral_mode", "-spectral_mode is given without a value"},
  {"-spectral_u0 gaussian -spectral_u0_width", "-spectral_u0_width is given without a value"},
  {"-spectral_terms diffusion,,advection", "-spectral_terms diffusion,,advection has an empty item"},
  {"-spectral_cluster_detect_times 0.1,0.2,", "-spectral_cluster_detect_times 0.1,0.2, has an empty item"},
  {"-spectral_diffusion_coefficient_weights ,1,1", "-spectral_diffusion_coefficient_weights ,1,1 has an empty item"},
  // the terms burgers, reaction, source and fields as sums of forms
  {"-spectral_terms reaction", "The term reaction needs -spectral_reaction_coefficients c0,c1,c2,c3"},
  {"-spectral_terms reaction -spectral_reaction_coefficients 1,2,3,4,5", "-spectral_reaction_coefficients takes at most 4 values c0,c1,c2,c3 (a cubic), got 5"},
  {"-spectral_terms reaction -spectral_reaction_coefficients 1,,2", "-spectral_reaction_coefficients 1,,2 has an empty item"},
  {"-spectral_terms reaction -spectral_reaction_coefficients", "-spectral_reaction_coefficients is given without a value"},
  {"-spectral_terms burgers -spectral_burgers_coefficient wavelet", "Unknown option wavelet for -spectral_burgers_coefficient. Available options: constant gaussian expsin"},
  {"-spectral_terms reaction -spectral_reaction_coefficients 1 -spectral_reaction_rate gaussian -spectral_reaction_rate_width 0", "-spectral_reaction_rate: gaussian: the width must be positive"},
  {"-spectral_diffusion_coefficient fourier+wavelet", "Unknown form 'wavelet' in summand 1 of -spectral_diffusion_coefficient fourier+wavelet: the forms are constant gaussian expsin fourier exp_ratio samples"},
  {"-spectral_diffusion_coefficient fourier+", "-spectral_diffusion_coefficient fourier+ has an empty summand"},
  {"-spectral_diffusion_coefficient fourier++expsin", "has an empty summand"},
  {"-spectral_diffusion_coefficient fourier+expsin -spectral_diffusion_coefficient_offset 1",
   "-spectral_diffusion_coefficient_offset: -spectral_diffusion_coefficient is a sum of forms (fourier+expsin), whose parameters are numbered by summand from 0: -spectral_diffusion_coefficient_0_offset"},
  {"-spectral_diffusion_coefficient fourier+expsin -spectral_diffusion_coefficient_1_weights 1", "-spectral_diffusion_coefficient: summand 1 (expsin): expsin: 1 weights but 0 wavenumbers"},
  {"-spectral_terms source -spectral_source constant+samples", "-spectral_source_1 samples needs -spectral_source_1_file"},
  {"-spectral_terms diffusion,burgers -spectral_evaluation matrix", "-spectral_evaluation matrix is for linear (and affine) scenes: the term burgers is nonlinear; use -spectral_evaluation fft"},
  {"-spectral_terms reaction -spectral_reaction_coefficients 0,1,0,-1 -spectral_evaluation matrix", "the term reaction (of degree 2 or 3) is nonlinear"},
  {"-spectral_terms diffusion,burgers -spectral_projection direct", "-spectral_projection direct is not available with the terms burgers and reaction"},
};

TEST(VSHMMSpectralOptions, BadValuesNameTheOption)
{
  for (const BadOptions &bad : kBadValues) EXPECT_CONTAINS(Scene(bad.options).error(), bad.message);
}

TEST(VSHMMSpectralOptions, ErrorsCarryThePrefix)
{
  EXPECT_CONTAINS(Scene("-a_spectral_grid_points 3", "a_").error(), "-a_spectral_grid_points 3 is too small");
  EXPECT_CONTAINS(Scene("-a_spectral_mode sparse -a_spectral_clusters 0:3,", "a_").error(), "-a_spectral_clusters 0:3,");
  EXPECT_CONTAINS(Scene("-a_spectral_terms reaction", "a_").error(), "The term reaction needs -a_spectral_reaction_coefficients");
  EXPECT_CONTAINS(Scene("-a_spectral_velocity constant+fourier -a_spectral_velocity_sin 1", "a_").error(), "-a_spectral_velocity_sin: -a_spectral_velocity is a sum of forms");
  // without the prefix the option is not the object's
  EXPECT_EQ(Scene("-spectral_grid_points 3", "a_").error(), "");
}

TEST(VSHMMSpectralOptions, ClusterListsCheckedBeforeAnythingIsBuilt)
{
  const auto start = std::chrono::steady_clock::now();
  EXPECT_CONTAINS(Scene("-spectral_grid_points 64 -spectral_mode sparse -spectral_clusters 0:999999999").error(), "-spectral_clusters 0:999999999: cluster item '0:999999999' has wavenumber 999999999, outside 0..32");
  EXPECT_CONTAINS(Scene("-spectral_grid_points 64 -spectral_mode sparse -spectral_clusters 0:99999999").error(), "outside 0..32");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_CONTAINS(Scene("-spectral_mode sparse -spectral_clusters 0:3,").error(), "-spectral_clusters 0:3,: the cluster list '0:3,' has an empty cluster");
  EXPECT_CONTAINS(Scene("-spectral_mode sparse -spectral_clusters 0:3+").error(), "-spectral_clusters 0:3+: cluster item '0:3+' has an empty range");
  EXPECT_CONTAINS(Scene("-spectral_mode sparse -spectral_clusters 0:3++5").error(), "has an empty range");
  EXPECT_CONTAINS(Scene("-spectral_mode sparse -spectral_clusters ,0:3").error(), "empty cluster");
}

TEST(VSHMMSpectralOptions, ListsTakeEveryValue)
{
  // 300 wavenumbers and 299 sines: the lists are read whole (PETSc's readers alone stop at the
  // caller's capacity without a word), so the mismatch is seen
  std::string k, sines;
  for (int i = 1; i <= 300; ++i) {
    k += (i > 1 ? "," : "") + std::to_string(i);
    if (i < 300) sines += (i > 1 ? "," : "") + std::string("0.001");
  }
  EXPECT_CONTAINS(Scene("-spectral_terms advection -spectral_velocity fourier -spectral_velocity_offset 1 -spectral_velocity_wavenumbers " + k + " -spectral_velocity_sin " + sines).error(),
                  "-spectral_velocity: fourier: 300 wavenumbers but 0 cosine and 299 sine coefficients");
  EXPECT_EQ(Scene("-spectral_terms advection -spectral_velocity fourier -spectral_velocity_offset 1 -spectral_velocity_wavenumbers " + k + " -spectral_velocity_sin " + sines + ",0.001").error(), "");
}

// The view of a scene that must set up without an error.
static std::string ViewOf(const std::string &options)
{
  Scene s(options);
  EXPECT_EQ(s.error(), "") << options;
  return s.view();
}

TEST(VSHMMSpectralOptions, FieldFormStartsFromItsStatedDefaults)
{
  const std::string adv = "-spectral_grid_points 64 -spectral_terms advection ";
  // issue 9: this ran a = 1 + 0.2 cos 24x + 0.6 sin 24x (parameters inherited from the paper's a)
  EXPECT_CONTAINS(ViewOf(adv + "-spectral_velocity fourier -spectral_velocity_wavenumbers 24 -spectral_velocity_sin 0.6"), "a = fourier 0 + 0.6 sin(24x)\n");
  // parameters without the form change the scene's default field (the paper's a)
  EXPECT_CONTAINS(ViewOf(adv + "-spectral_velocity_scale 0.5"), "a = exp_ratio 0.5 exp((0.6 + 0.2 cos(3x)) / (1 + 0.35 sin(64x) + 0.35 sin(256x)))");
  EXPECT_CONTAINS(ViewOf(adv + "-spectral_velocity exp_ratio -spectral_velocity_numerator_wavenumbers 2 -spectral_velocity_numerator_cos 0.5"), "a = exp_ratio 1 exp((0 + 0.5 cos(2x)) / (1))");
  EXPECT_CONTAINS(ViewOf("-spectral_u0 gaussian -spectral_u0_width 0.5"), "u0 = gaussian 0 + 1 exp(-((x - 3.14159)/0.5)^2)");
  EXPECT_CONTAINS(ViewOf("-spectral_diffusion_coefficient constant"), "d = constant 0\n");
}

TEST(VSHMMSpectralOptions, NewTermsAndFieldSums)
{
  const std::string v = ViewOf("-spectral_grid_points 64 -spectral_terms diffusion,burgers,reaction,source -spectral_diffusion_coefficient constant+fourier -spectral_diffusion_coefficient_0_value 1 "
                               "-spectral_diffusion_coefficient_1_wavenumbers 8 -spectral_diffusion_coefficient_1_cos 0.25 -spectral_burgers_coefficient_value 0.5 -spectral_reaction_coefficients 0,1");
  EXPECT_CONTAINS(v, "d = [constant 1] + [fourier 0 + 0.25 cos(8x)]\n");
  EXPECT_CONTAINS(v, "term burgers: u_t += -(c u^2/2)_x, c = constant 0.5\n");
  // fewer reaction coefficients than four: the rest are 0
  EXPECT_CONTAINS(v, "term reaction: u_t += r (c0 + c1 u + c2 u^2 + c3 u^3), c = 0,1,0,0, r = constant 1\n");
  EXPECT_CONTAINS(v, "term source: u_t += s, s = constant 0\n");
  // M > p ku + kf + kout = 2 * 32 + 0 + 32 (Burgers), the smallest 2^a 3^b 5^c above: 100
  EXPECT_CONTAINS(v, "padded grid of M = 100 points");
  // affine terms (source, linear reaction) are allowed with the matrix evaluation
  EXPECT_CONTAINS(ViewOf("-spectral_grid_points 64 -spectral_terms diffusion,reaction,source -spectral_reaction_coefficients 0.5,-1 -spectral_evaluation matrix -spectral_mode sparse -spectral_clusters 0:3"), "evaluation: dense operator");
}

/* Manufactured solution. Scene (DNS, N = 32): diffusion d = 1 + 0.3 cos x, Burgers c = 0.5 +
   0.2 sin 2x, reaction r = 1 + 0.1 cos 3x with c0..c3 = 0.1, -0.5, 0.3, -0.2, source s = 0.2 cos 2x
   + 0.1 exp(sin x) (a sum of forms). Exact solution u*(x, t) = 0.4 + 0.6 e^{-t/2} sin x +
   0.3 cos(2x - t); the forcing f = u*_t - F(u*) that makes it exact depends on t and is added by
   the test's right-hand side (the scene's source is time-independent). u* and every product are
   trigonometric polynomials of degree <= 9 < N/2 and the nonlinear terms are evaluated without
   aliasing, so the only error is the time stepping's. */
namespace {
struct Manufactured {
  VSHMMSpectral sp;
  PetscInt      N;
  Vec           forcing;
};

double ExactU(double x, double t)
{
  return 0.4 + 0.6 * std::exp(-t / 2) * std::sin(x) + 0.3 * std::cos(2 * x - t);
}

/* f(x, t) = u_t - (d u_x)_x + (c u^2/2)_x - r P(u) - s on the grid, as DNS coefficients. */
PetscErrorCode Forcing(Manufactured *m, double t)
{
  const int           N = (int)m->N;
  std::vector<double> f(N);
  for (int j = 0; j < N; ++j) {
    const double x = 2 * M_PI * j / N, e = std::exp(-t / 2);
    const double u = ExactU(x, t), ut = -0.3 * e * std::sin(x) + 0.3 * std::sin(2 * x - t);
    const double ux = 0.6 * e * std::cos(x) - 0.6 * std::sin(2 * x - t), uxx = -0.6 * e * std::sin(x) - 1.2 * std::cos(2 * x - t);
    const double d = 1 + 0.3 * std::cos(x), dx = -0.3 * std::sin(x), c = 0.5 + 0.2 * std::sin(2 * x), cx = 0.4 * std::cos(2 * x);
    const double r = 1 + 0.1 * std::cos(3 * x), P = 0.1 - 0.5 * u + 0.3 * u * u - 0.2 * u * u * u, s = 0.2 * std::cos(2 * x) + 0.1 * std::exp(std::sin(x));
    f[j] = ut - (dx * ux + d * uxx) + (cx * u * u / 2 + c * u * ux) - r * P - s;
  }
  /* the DNS layout: Re c_0, then Re c_k, Im c_k for k = 1..N/2-1, then Re c_{N/2} */
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(m->forcing, &a));
  for (int k = 0; k <= N / 2; ++k) {
    double re = 0, im = 0;
    for (int j = 0; j < N; ++j) {
      re += f[j] * std::cos(2 * M_PI * k * j / N) / N;
      im -= f[j] * std::sin(2 * M_PI * k * j / N) / N;
    }
    if (k == 0) a[0] = re;
    else if (k == N / 2) a[N - 1] = re;
    else {
      a[2 * k - 1] = re;
      a[2 * k]     = im;
    }
  }
  PetscCall(VecRestoreArray(m->forcing, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ForcedRHS(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  Manufactured *m = (Manufactured *)ctx;

  PetscFunctionBeginUser;
  PetscCall(VSHMMSpectralRHSFunction(ts, t, U, F, m->sp));
  PetscCall(Forcing(m, t));
  PetscCall(VecAXPY(F, 1.0, m->forcing));
  PetscFunctionReturn(0);
}

/* The max error against u* at t = 0.4 of TSRK type rk with step dt. */
double ManufacturedError(TSRKType rk, double dt)
{
  Scene s("-spectral_grid_points 32 -spectral_mode dns -spectral_terms diffusion,burgers,reaction,source -spectral_fftw_planner estimate "
          "-spectral_diffusion_coefficient fourier -spectral_diffusion_coefficient_offset 1 -spectral_diffusion_coefficient_wavenumbers 1 -spectral_diffusion_coefficient_cos 0.3 "
          "-spectral_burgers_coefficient fourier -spectral_burgers_coefficient_offset 0.5 -spectral_burgers_coefficient_wavenumbers 2 -spectral_burgers_coefficient_sin 0.2 "
          "-spectral_reaction_rate fourier -spectral_reaction_rate_offset 1 -spectral_reaction_rate_wavenumbers 3 -spectral_reaction_rate_cos 0.1 -spectral_reaction_coefficients 0.1,-0.5,0.3,-0.2 "
          "-spectral_source fourier+expsin -spectral_source_0_wavenumbers 2 -spectral_source_0_cos 0.2 -spectral_source_1_weights 0.1 -spectral_source_1_wavenumbers 1 "
          "-spectral_u0 fourier -spectral_u0_offset 0.4 -spectral_u0_wavenumbers 1,2 -spectral_u0_sin 0.6,0 -spectral_u0_cos 0,0.3");
  EXPECT_EQ(s.error(), "");
  Manufactured m = {s.sp, 32, nullptr};
  Vec          U;
  TS           ts;
  TSAdapt      adapt;
  const double T = 0.4;
  EXPECT_EQ(VSHMMSpectralCreateVec(s.sp, &U), 0);
  EXPECT_EQ(VecDuplicate(U, &m.forcing), 0);
  EXPECT_EQ(VSHMMSpectralSetInitialCondition(s.sp, U), 0);
  EXPECT_EQ(TSCreate(PETSC_COMM_WORLD, &ts), 0);
  EXPECT_EQ(TSSetSolution(ts, U), 0);
  EXPECT_EQ(VSHMMSpectralSetUpTS(s.sp, ts), 0);
  EXPECT_EQ(TSSetRHSFunction(ts, NULL, ForcedRHS, &m), 0);
  EXPECT_EQ(TSSetType(ts, TSRK), 0);
  EXPECT_EQ(TSRKSetType(ts, rk), 0);
  EXPECT_EQ(TSGetAdapt(ts, &adapt), 0);
  EXPECT_EQ(TSAdaptSetType(adapt, TSADAPTNONE), 0);
  EXPECT_EQ(TSSetTimeStep(ts, dt), 0);
  EXPECT_EQ(TSSetMaxTime(ts, T), 0);
  EXPECT_EQ(TSSetMaxSteps(ts, 1000000), 0);
  EXPECT_EQ(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP), 0);
  EXPECT_EQ(TSSolve(ts, U), 0);
  PetscReal t;
  EXPECT_EQ(TSGetSolveTime(ts, &t), 0);
  EXPECT_NEAR(t, T, 1e-12);
  std::vector<PetscReal> u(32);
  EXPECT_EQ(VSHMMSpectralGetGridValues(s.sp, U, u.data()), 0);
  double err = 0;
  for (int j = 0; j < 32; ++j) err = std::max(err, std::fabs(u[j] - ExactU(2 * M_PI * j / 32, T)));
  TSDestroy(&ts);
  VecDestroy(&m.forcing);
  VecDestroy(&U);
  return err;
}
} // namespace

TEST(VSHMMSpectralTerms, ManufacturedSolutionConvergesAtTheMethodsOrder)
{
  // RK3 (stable up to dt ~ 7e-3 here: max d k^2 = 1.3 * 256). Measured: 5.8e-9, 7.2e-10, 9.0e-11
  // (ratios 8.1, 8.0: order 3); RK4 4.1e-11, 2.5e-12 (ratio 16.2). An aliased evaluation or a
  // wrong term would leave an error that does not fall with dt.
  const double e1 = ManufacturedError(TSRK3, 4e-3), e2 = ManufacturedError(TSRK3, 2e-3), e3 = ManufacturedError(TSRK3, 1e-3);
  std::printf("manufactured solution, RK3: errors %.3e %.3e %.3e (dt = 4e-3, 2e-3, 1e-3)\n", e1, e2, e3);
  EXPECT_GT(e1 / e2, 6.0);
  EXPECT_GT(e2 / e3, 6.0);
  EXPECT_LT(e3, 2e-10);
  // RK4: order 4 (16)
  const double f1 = ManufacturedError(TSRK4, 4e-3), f2 = ManufacturedError(TSRK4, 2e-3);
  std::printf("manufactured solution, RK4: errors %.3e %.3e (dt = 4e-3, 2e-3)\n", f1, f2);
  EXPECT_GT(f1 / f2, 12.0);
}

TEST(VSHMMSpectralObject, IsAPetscObject)
{
  Scene       s("-spectral_grid_points 32");
  const char *name;
  EXPECT_EQ(s.error(), "");
  EXPECT_EQ(PetscObjectGetClassName((PetscObject)s.sp, &name), 0);
  EXPECT_STREQ(name, "VSHMMSpectral");
  PetscClassId id;
  EXPECT_EQ(PetscObjectGetClassId((PetscObject)s.sp, &id), 0);
  EXPECT_EQ(id, VSHMMSPECTRAL_CLASSID);
  EXPECT_CONTAINS(s.view(), "scene: N = 32 grid points");
}

// A NULL argument is an error (PETSC_ERR_ARG_NULL), not a segmentation fault, in an optimised
// PETSc too (src/common/vshmmvalid.hpp), and so is another object in the place of the scene.
TEST(VSHMMSpectralObject, NullArgumentsAreErrorsNotCrashes)
{
  Scene s("-spectral_grid_points 32");
  ASSERT_EQ(s.error(), "");
  Vec       v;
  PetscReal dt;
  ASSERT_EQ(VecCreateSeq(PETSC_COMM_SELF, 2, &v), 0);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_EQ(VSHMMSpectralGetStableTimeStep(s.sp, TSRK3, nullptr), PETSC_ERR_ARG_NULL);
  EXPECT_EQ(VSHMMSpectralGetStableTimeStep(nullptr, TSRK3, &dt), PETSC_ERR_ARG_NULL);
  EXPECT_EQ(VSHMMSpectralGetStableTimeStep((VSHMMSpectral)v, TSRK3, &dt), PETSC_ERR_ARG_WRONG);
  EXPECT_EQ(VSHMMSpectralCreateVec(s.sp, nullptr), PETSC_ERR_ARG_NULL);
  EXPECT_EQ(VSHMMSpectralGetStatistics(s.sp, nullptr), PETSC_ERR_ARG_NULL);
  EXPECT_EQ(VSHMMSpectralSetUpTS(s.sp, nullptr), PETSC_ERR_ARG_NULL);
  PetscPopErrorHandler();
  ASSERT_EQ(VecDestroy(&v), 0);
}

// The stable step at a given state: a linear scene's is the initial one at any state; with a
// cubic reaction -u^3 the Jacobian at a constant state a is -0.5 k^2 - 3 a^2 on mode k (d = 0.5,
// N = 64), so the spectral radius is 480.5 + 3 a^2: from u0 = 1 to the state 10 u0 the step falls
// from 0.9 * 2.5127453266 / 483.5 to 0.9 * 2.5127453266 / 780.5.
TEST(VSHMMSpectralStableStep, AtAStateFollowsTheJacobian)
{
  const std::string diffusion = "-spectral_grid_points 64 -spectral_diffusion_coefficient constant -spectral_diffusion_coefficient_value 0.5 -spectral_u0 constant -spectral_u0_value 1";
  for (const bool cubic : {false, true}) {
    Scene     s(diffusion + (cubic ? " -spectral_terms diffusion,reaction -spectral_reaction_coefficients 0,0,0,-1" : ""));
    Vec       U;
    PetscReal dt0 = 0, dt1 = 0, dt10 = 0;
    ASSERT_EQ(s.error(), "");
    ASSERT_EQ(VSHMMSpectralCreateVec(s.sp, &U), 0);
    ASSERT_EQ(VSHMMSpectralSetInitialCondition(s.sp, U), 0);
    ASSERT_EQ(VSHMMSpectralGetStableTimeStep(s.sp, TSRK3, &dt0), 0);
    ASSERT_EQ(VSHMMSpectralGetStableTimeStepAt(s.sp, U, TSRK3, &dt1), 0);
    ASSERT_EQ(VecScale(U, 10.0), 0);
    ASSERT_EQ(VSHMMSpectralGetStableTimeStepAt(s.sp, U, TSRK3, &dt10), 0);
    const double radius0 = cubic ? 483.5 : 480.5, radius10 = cubic ? 780.5 : 480.5;
    EXPECT_NEAR(dt0, 0.9 * 2.5127453266 / radius0, 1e-5 * dt0);
    EXPECT_NEAR(dt1, dt0, 1e-5 * dt0);
    EXPECT_NEAR(dt10, 0.9 * 2.5127453266 / radius10, 1e-5 * dt10);
    if (!cubic) EXPECT_EQ(dt10, dt0); // the initial estimate, no new work
    ASSERT_EQ(VecDestroy(&U), 0);
  }
}

// Constant d = 0.5 on every mode of N = 64: the eigenvalues are -0.5 k^2, k = 0..31 (the Nyquist
// mode's derivative is zero), so the spectral radius is 480.5 and the bound max|d| kmax^2 = 512;
// RK3's real-axis limit is 2.5127453266, RK4's 2.7852935634: the step is 0.9 of that / 480.5.
TEST(VSHMMSpectralStableStep, ConstantDiffusionHasItsExactStep)
{
  Scene     s("-spectral_grid_points 64 -spectral_diffusion_coefficient constant -spectral_diffusion_coefficient_value 0.5");
  PetscReal radius = 0, bound = 0, dt3 = 0, dt4 = 0, dtold = 0;
  ASSERT_EQ(s.error(), "");
  ASSERT_EQ(VSHMMSpectralGetSpectralRadius(s.sp, &radius, &bound), 0);
  EXPECT_NEAR(radius, 480.5, 1e-6 * 480.5);
  EXPECT_NEAR(bound, 512.0, 1e-12);
  ASSERT_EQ(VSHMMSpectralGetStableTimeStep(s.sp, TSRK3, &dt3), 0);
  ASSERT_EQ(VSHMMSpectralGetStableTimeStep(s.sp, TSRK4, &dt4), 0);
  ASSERT_EQ(VSHMMSpectralEstimateTimeStep(s.sp, &dtold), 0);
  EXPECT_NEAR(dt3, 0.9 * 2.5127453266 / 480.5, 1e-6 * dt3);
  EXPECT_NEAR(dt4, 0.9 * 2.7852935634 / 480.5, 1e-6 * dt4);
  EXPECT_EQ(dtold, dt3);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_EQ(VSHMMSpectralSetGrowthBound(s.sp, 0.5), PETSC_ERR_ARG_OUTOFRANGE); // 0 or >= 1
  PetscPopErrorHandler();
}

// The clusters' separations: constant d = 0.5 and clusters {0..3}, {20..24}, {60..64}: the slowest
// wavenumber of each faster cluster over the fastest of the slower one, (20/3)^2 and (60/24)^2;
// advection a = 2 adds 2 k to each rate. Mode dns has none.
TEST(VSHMMSpectralObject, ScaleSeparationsOfTheClusters)
{
  const std::string base = "-spectral_grid_points 256 -spectral_mode sparse -spectral_clusters 0:3,20:24,60:64 -spectral_diffusion_coefficient constant -spectral_diffusion_coefficient_value 0.5";
  for (const bool adv : {false, true}) {
    Scene            s(base + (adv ? " -spectral_terms diffusion,advection -spectral_velocity constant -spectral_velocity_value 2" : ""));
    PetscInt         n = -1;
    const PetscReal *S = nullptr;
    ASSERT_EQ(s.error(), "");
    ASSERT_EQ(VSHMMSpectralGetScaleSeparations(s.sp, &n, &S), 0);
    ASSERT_EQ(n, 2);
    const double a = adv ? 2 : 0;
    EXPECT_NEAR(S[0], (0.5 * 400 + a * 20) / (0.5 * 9 + a * 3), 1e-12);
    EXPECT_NEAR(S[1], (0.5 * 3600 + a * 60) / (0.5 * 576 + a * 24), 1e-12);
  }
  Scene            dns("-spectral_grid_points 64");
  PetscInt         n = -1;
  const PetscReal *S = nullptr;
  ASSERT_EQ(VSHMMSpectralGetScaleSeparations(dns.sp, &n, &S), 0);
  EXPECT_EQ(n, 0);
  EXPECT_EQ(S, nullptr);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_EQ(VSHMMSpectralSetClusterThreshold(dns.sp, NAN), PETSC_ERR_ARG_OUTOFRANGE);
  PetscPopErrorHandler();
  EXPECT_EQ(VSHMMSpectralSetClusterThreshold(dns.sp, 3e-5), 0);
}

namespace {
// A sparse run of u_t = (d u_x)_x, d = 1 + 0.5 cos 2x, u0 = cos x on the cluster {0, 1}: the retained
// mode decays as A = e^{-0.75 t} (F(cos x) = -0.75 cos x - 0.75 cos 3x) and forces the left-out
// wavenumber 3 by f_3 = 0.375 A (|c_3| of -0.75 A cos 3x); the truncation check's model of it is
// a_3' = -9 a_3 + 0.375 A (mean(d) 3^2), and its feedback on wavenumber 1 (F of c_3 = a_3, the
// function 2 a_3 cos 3x, on wavenumber 1: 0.75 a_3) e_1' = -e_1 + 0.75 a_3. Returns the statistics after TSSolve to T
// and TSSolve's error code.
const char *const kTruncationScene = "-spectral_grid_points 32 -spectral_mode sparse -spectral_clusters 0:1 -spectral_diffusion_coefficient fourier -spectral_diffusion_coefficient_offset 1 "
                                     "-spectral_diffusion_coefficient_wavenumbers 2 -spectral_diffusion_coefficient_cos 0.5 -spectral_u0 fourier -spectral_u0_wavenumbers 1 -spectral_u0_cos 1";

// Runs sp's scene with RK (fixed step 1e-3) from u0 to T; *size (if given) the state's size.
// Returns TSSolve's error code.
PetscErrorCode SolveSparse(VSHMMSpectral sp, PetscReal T, PetscInt *size = nullptr)
{
  Vec     U;
  TS      ts;
  TSAdapt adapt;
  EXPECT_EQ(VSHMMSpectralCreateVec(sp, &U), 0);
  if (size) EXPECT_EQ(VecGetSize(U, size), 0);
  EXPECT_EQ(VSHMMSpectralSetInitialCondition(sp, U), 0);
  EXPECT_EQ(TSCreate(PETSC_COMM_WORLD, &ts), 0);
  EXPECT_EQ(TSSetSolution(ts, U), 0);
  EXPECT_EQ(VSHMMSpectralSetUpTS(sp, ts), 0);
  EXPECT_EQ(TSSetType(ts, TSRK), 0);
  EXPECT_EQ(TSGetAdapt(ts, &adapt), 0);
  EXPECT_EQ(TSAdaptSetType(adapt, TSADAPTNONE), 0);
  EXPECT_EQ(TSSetTimeStep(ts, 1e-3), 0);
  EXPECT_EQ(TSSetMaxTime(ts, T), 0);
  EXPECT_EQ(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP), 0);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  PetscErrorCode ierr = TSSolve(ts, U);
  PetscPopErrorHandler();
  TSDestroy(&ts);
  VecDestroy(&U);
  return ierr;
}

PetscErrorCode TruncationRun(VSHMMSpectralTruncationCheck check, PetscReal T, VSHMMSpectralStatistics *stats)
{
  Scene s(kTruncationScene);
  EXPECT_EQ(s.error(), "");
  EXPECT_EQ(VSHMMSpectralSetTruncationCheck(s.sp, check), 0);
  PetscErrorCode ierr = SolveSparse(s.sp, T);
  EXPECT_EQ(VSHMMSpectralGetStatistics(s.sp, stats), 0);
  return ierr;
}
} // namespace

TEST(VSHMMSpectralTruncation, ModelOfAForcedLeftOutMode)
{
  const PetscReal         T = 0.5;
  VSHMMSpectralStatistics st;
  EXPECT_EQ(TruncationRun(VSHMMSPECTRAL_TRUNCATION_WARN, T, &st), 0); // warns on stderr, carries on
  double a3 = 0, e1 = 0, h = 1e-5;                                    // the model's equations, finely
  for (double t = 0; t < T - h / 2; t += h) {
    auto rhs = [](double t, double a, double e, double *da, double *de) {
      *da = -9 * a + 0.375 * std::exp(-0.75 * t);
      *de = -e + 0.75 * a;
    };
    double k1a, k1e, k2a, k2e, k3a, k3e, k4a, k4e;
    rhs(t, a3, e1, &k1a, &k1e);
    rhs(t + h / 2, a3 + h / 2 * k1a, e1 + h / 2 * k1e, &k2a, &k2e);
    rhs(t + h / 2, a3 + h / 2 * k2a, e1 + h / 2 * k2e, &k3a, &k3e);
    rhs(t + h, a3 + h * k3a, e1 + h * k3e, &k4a, &k4e);
    a3 += h / 6 * (k1a + 2 * k2a + 2 * k3a + k4a);
    e1 += h / 6 * (k1e + 2 * k2e + 2 * k3e + k4e);
  }
  const double share = std::hypot(a3, e1) * std::sqrt(2.0) / (std::sqrt(2.0) * 0.5 * std::exp(-0.75 * T)); // ||u|| = sqrt(2) A / 2
  EXPECT_NEAR(st.truncation_share, share, 2e-3 * share);                                                   // the looks' trapezoid, 64 per solve
  EXPECT_NEAR(st.truncation_time, T, 1e-12);                                                               // the share grows: largest at the end
  EXPECT_GT(share, 0.05);
  EXPECT_EQ(TruncationRun(VSHMMSPECTRAL_TRUNCATION_ERROR, T, &st), PETSC_ERR_NOT_CONVERGED); // above the default tolerance 1e-2
  EXPECT_LT(st.truncation_time, 0.05);                                                       // stopped at its first look above it
  EXPECT_EQ(TruncationRun(VSHMMSPECTRAL_TRUNCATION_NONE, T, &st), 0);
  EXPECT_EQ(st.truncation_share, 0);
  Scene s("-spectral_grid_points 32");
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  EXPECT_EQ(VSHMMSpectralSetTruncationCheck(s.sp, (VSHMMSpectralTruncationCheck)4), PETSC_ERR_ARG_OUTOFRANGE);
  PetscPopErrorHandler();
}

// -spectral_truncation_check widen on the same run: the check asks for the buffer that holds
// wavenumber 3 (and, as the cluster {0, 1} is a band of 2, at least 1: 2), a program that does not
// restart is warned at the end of the solve, VSHMMSpectralWidenClusters() widens {0, 1} to
// {0..3} and sets up again: the state's size, the statistics' widening, no pending request
TEST(VSHMMSpectralTruncation, WidenTheClusters)
{
  Scene s(std::string(kTruncationScene) + " -spectral_truncation_check widen");
  EXPECT_EQ(s.error(), "");
  PetscBool pending = PETSC_TRUE, widened = PETSC_TRUE;
  PetscReal tw = -1;
  PetscInt  n  = 0;
  Vec       U;
  EXPECT_EQ(VSHMMSpectralWidenClusters(s.sp, &widened), 0); // nothing asked for
  EXPECT_FALSE(widened);
  testing::internal::CaptureStderr();
  EXPECT_EQ(SolveSparse(s.sp, 0.5, &n), 0);
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_EQ(n, 3);
  EXPECT_NE(said.find("truncation check at t = 0.5: "), std::string::npos) << said;
  EXPECT_NE(said.find("widening it asked for at t = 0.016 was not applied by VSHMMSpectralWidenClusters()"), std::string::npos) << said;
  EXPECT_EQ(VSHMMSpectralGetTruncationWidening(s.sp, &pending, &tw), 0);
  EXPECT_TRUE(pending);
  EXPECT_LT(tw, 0.05); // the first look above the default tolerance 1e-2 (not applied: the warning at the solve's end, stderr)
  EXPECT_EQ(VSHMMSpectralWidenClusters(s.sp, &widened), 0);
  EXPECT_TRUE(widened);
  EXPECT_EQ(VSHMMSpectralGetTruncationWidening(s.sp, &pending, nullptr), 0);
  EXPECT_FALSE(pending);
  PetscInt        nm;
  const PetscInt *modes;
  EXPECT_EQ(VSHMMSpectralGetModes(s.sp, &nm, &modes), 0);
  EXPECT_EQ(std::vector<PetscInt>(modes, modes + nm), (std::vector<PetscInt>{0, 1, 2, 3}));
  EXPECT_EQ(VSHMMSpectralCreateVec(s.sp, &U), 0);
  EXPECT_EQ(VecGetSize(U, &n), 0);
  EXPECT_EQ(n, 7);
  VecDestroy(&U);
  VSHMMSpectralStatistics st;
  EXPECT_EQ(VSHMMSpectralGetStatistics(s.sp, &st), 0);
  EXPECT_EQ(st.widenings, 1);
  EXPECT_GT(st.widening_evaluations, 1000); // the stopped runs' 600 RK steps
  EXPECT_EQ(st.field_evaluations, 0);
}
