// PETSc features that TSVSHMM does not support are refused at set-up with an error that names
// the feature, before any split function is called: an adaptive TSAdapt (once accepted and
// ignored), events, TSTrajectory and adjoint or forward sensitivities (once PETSc's generic
// "No method ..." in mid-run), forward cost integrals, pre-/post-stage functions, and an implicit
// function definition (as PETSc's explicit types refuse it).
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "problems.hpp"

namespace {

struct UnsupportedRun {
  CapturedError error;
  long          split_calls = -1; // split function calls before the error
};

// The dissipative example (paper's parameters) to t = 0.3, with `configure` applied to the TS
// and `options` inserted (and cleared afterwards) before TSSetFromOptions() and TSSolve().
UnsupportedRun SolveWith(const char *options, const std::function<PetscErrorCode(TS, Vec)> &configure)
{
  DissipativeParams params;
  SplitProblem      p;
  TS                ts      = nullptr;
  Vec               x       = nullptr;
  const PetscReal   alpha[] = {100, 10};
  UnsupportedRun    run;

  DissipativeProblem(&p, &params);
  EXPECT_EQ(CreateSplitTS(PETSC_COMM_WORLD, &p, SplitKind::Additive, {5, -10, 5}, {"slow", "medium", "fast"}, &ts, &x), 0);
  if (options) EXPECT_EQ(PetscOptionsInsertString(nullptr, options), 0);
  run.error = CaptureError([&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(TSSetTimeStep(ts, 0.1));
    PetscCall(TSSetMaxTime(ts, 0.3));
    PetscCall(TSVSHMMSetMicroStep(ts, 1e-4));
    PetscCall(TSVSHMMSetSavingsFactors(ts, 2, alpha));
    if (configure) PetscCall(configure(ts, x));
    PetscCall(TSSetFromOptions(ts));
    PetscCall(TSSolve(ts, x));
    PetscFunctionReturn(0);
  });
  if (options) EXPECT_EQ(PetscOptionsClear(nullptr), 0);
  run.split_calls = p.calls;
  EXPECT_EQ(DestroySplitTS(&p, &ts, &x), 0);
  return run;
}

void ExpectRefused(const UnsupportedRun &run, const char *what)
{
  EXPECT_EQ(run.error.code, PETSC_ERR_SUP) << run.error.message;
  EXPECT_NE(run.error.message.find(what), std::string::npos) << run.error.message;
  EXPECT_EQ(run.split_calls, 0) << "refused only after work was done";
}

PetscErrorCode EventFunction(TS, PetscReal t, Vec, PetscScalar *f, void *)
{
  f[0] = t - 0.15;
  return 0;
}

PetscErrorCode Hook(TS, PetscReal)
{
  return 0;
}

PetscErrorCode PostStageHook(TS, PetscReal, PetscInt, Vec *)
{
  return 0;
}

TEST(VSHMMUnsupported, AdaptiveTSAdaptIsRefusedAtSetUp)
{
  ExpectRefused(SolveWith("-ts_adapt_type basic", nullptr), "TSVSHMM does not support the time step adaptivity TSAdapt 'basic' (-ts_adapt_type)");
  ExpectRefused(SolveWith(nullptr,
                          [](TS ts, Vec) -> PetscErrorCode {
                            TSAdapt adapt;
                            PetscFunctionBeginUser;
                            PetscCall(TSGetAdapt(ts, &adapt));
                            PetscCall(TSAdaptSetType(adapt, TSADAPTDSP));
                            PetscFunctionReturn(0);
                          }),
                "TSAdapt 'dsp'");
  // none, the default, is accepted, also when asked for
  const UnsupportedRun none = SolveWith("-ts_adapt_type none", nullptr);
  EXPECT_EQ(none.error.code, 0) << none.error.message;
  EXPECT_GT(none.split_calls, 0);
}

TEST(VSHMMUnsupported, EventsAreRefusedAtSetUp)
{
  ExpectRefused(SolveWith(nullptr,
                          [](TS ts, Vec) -> PetscErrorCode {
                            PetscInt  direction = 0;
                            PetscBool terminate = PETSC_FALSE;
                            PetscFunctionBeginUser;
                            PetscCall(TSSetEventHandler(ts, 1, &direction, &terminate, EventFunction, nullptr, nullptr));
                            PetscFunctionReturn(0);
                          }),
                "TSVSHMM does not support events (TSSetEventHandler())");
}

TEST(VSHMMUnsupported, TrajectoryAndAdjointAreRefusedAtSetUp)
{
  ExpectRefused(SolveWith("-ts_save_trajectory", nullptr), "TSVSHMM does not support TSTrajectory (TSSetSaveTrajectory(), -ts_save_trajectory) or the adjoint solve");
  ExpectRefused(SolveWith(nullptr, [](TS ts, Vec) { return TSSetSaveTrajectory(ts); }), "does not support TSTrajectory");
  Vec lambda = nullptr;
  ExpectRefused(SolveWith(nullptr,
                          [&lambda](TS ts, Vec x) -> PetscErrorCode {
                            PetscFunctionBeginUser;
                            PetscCall(VecDuplicate(x, &lambda));
                            PetscCall(TSSetCostGradients(ts, 1, &lambda, nullptr));
                            PetscFunctionReturn(0);
                          }),
                "TSVSHMM does not support adjoint sensitivities (TSSetCostGradients(), TSAdjointSolve())");
  ASSERT_EQ(VecDestroy(&lambda), 0);
}

TEST(VSHMMUnsupported, ForwardSensitivitiesAreRefusedAtSetUp)
{
  Mat S = nullptr;
  ExpectRefused(SolveWith(nullptr,
                          [&S](TS ts, Vec x) -> PetscErrorCode {
                            PetscInt n, N;
                            PetscFunctionBeginUser;
                            PetscCall(VecGetLocalSize(x, &n));
                            PetscCall(VecGetSize(x, &N));
                            PetscCall(MatCreateDense(PetscObjectComm((PetscObject)x), n, PETSC_DECIDE, N, 1, nullptr, &S));
                            PetscCall(TSForwardSetSensitivities(ts, 1, S));
                            PetscFunctionReturn(0);
                          }),
                "TSVSHMM does not support forward sensitivities (TSForwardSetSensitivities())");
  ASSERT_EQ(MatDestroy(&S), 0);
}

TEST(VSHMMUnsupported, StageHooksAreRefusedAtSetUp)
{
  const char *what = "TSVSHMM does not call pre-stage or post-stage functions (TSSetPreStage(), TSSetPostStage())";
  ExpectRefused(SolveWith(nullptr, [](TS ts, Vec) { return TSSetPreStage(ts, Hook); }), what);
  ExpectRefused(SolveWith(nullptr, [](TS ts, Vec) { return TSSetPostStage(ts, PostStageHook); }), what);
}

// An implicit function definition (TSSetIFunction()), which TSVSHMM, explicit, steps past: it ran
// the splits and ignored it (a mass matrix, or a term only there, silently lost). Refused at set-up
// as PETSc's explicit types refuse it (PETSC_ERR_ARG_INCOMP), before any split call.
PetscErrorCode ImplicitFunction(TS, PetscReal, Vec, Vec Xdot, Vec F, void *)
{
  return VecCopy(Xdot, F);
}

TEST(VSHMMUnsupported, AnImplicitFunctionIsRefusedAtSetUp)
{
  const UnsupportedRun run = SolveWith(nullptr, [](TS ts, Vec) { return TSSetIFunction(ts, nullptr, ImplicitFunction, nullptr); });
  EXPECT_EQ(run.error.code, PETSC_ERR_ARG_INCOMP) << run.error.message;
  EXPECT_NE(run.error.message.find("TSVSHMM is an explicit integrator: it steps the RHS splits (TSRHSSplitSetRHSFunction()) and cannot use an implicit function definition (TSSetIFunction())"), std::string::npos) << run.error.message;
  EXPECT_EQ(run.split_calls, 0);
}

} // namespace
