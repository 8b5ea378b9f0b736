// Tests of the VSHMMSpectral object (src/spectral): bad options give a PETSc error that names the
// option (with the object's prefix), lists take every value given, a field form given only some
// of its parameters takes the stated defaults for the others. Each test reads its options from
// its own PetscOptions database.
#include <gtest/gtest.h>
#include <petscvshmmspectral.h>

#include <chrono>
#include <string>

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
  {"-spectral_terms diffusion,reaction", "Unknown term 'reaction' in -spectral_terms"},
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
};

TEST(VSHMMSpectralOptions, BadValuesNameTheOption)
{
  for (const BadOptions &bad : kBadValues) EXPECT_CONTAINS(Scene(bad.options).error(), bad.message);
}

TEST(VSHMMSpectralOptions, ErrorsCarryThePrefix)
{
  EXPECT_CONTAINS(Scene("-a_spectral_grid_points 3", "a_").error(), "-a_spectral_grid_points 3 is too small");
  EXPECT_CONTAINS(Scene("-a_spectral_mode sparse -a_spectral_clusters 0:3,", "a_").error(), "-a_spectral_clusters 0:3,");
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
