// The VSHMM step schedule: the mesoscopic step formula, the micro cycles of one macro step and
// the measured mean steps of the method note.
#include "schedule.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using vshmm::Kernel;
using vshmm::KernelType;
using vshmm::MacroStepCounts;
using vshmm::MesoscopicSchedule;
using vshmm::runMacroStep;
using vshmm::stepToEnd;

const long double kPiL = 3.141592653589793238462643383279502884L;

struct Step {
  int    level;
  double tau, h;
};

// Runs one macro step, recording every step taken.
std::vector<Step> record(const MesoscopicSchedule &schedule, double macroStep, MacroStepCounts *counts = nullptr)
{
  std::vector<Step> steps;
  const int         error = runMacroStep(
            schedule, macroStep,
            [&](int level, double tau, double h) {
      steps.push_back({level, tau, h});
      return 0;
    },
            counts);
  EXPECT_EQ(error, 0);
  return steps;
}

// The method note's formula h_j = alpha_j dt K(Theta^{-1}(u)) for the cosine kernel, written
// independently of the library: K(s) = 1 - cos(2 pi s), Theta^{-1} by bisection, in long double.
long double cosineTheta(long double s)
{
  return s - std::sin(2 * kPiL * s) / (2 * kPiL);
}

long double cosineThetaInverse(long double u)
{
  long double lo = 0, hi = 1;
  for (int i = 0; i < 100; ++i) {
    const long double middle            = 0.5L * (lo + hi);
    (cosineTheta(middle) < u ? lo : hi) = middle;
  }
  return 0.5L * (lo + hi);
}

double referenceCosineStep(double dt, const std::vector<double> &alpha, const std::vector<int> &m, int level, double tau, double macroStep)
{
  const int top = static_cast<int>(alpha.size());
  if (level == top) return dt;
  const long double period = (long double)macroStep / m[level], u = std::fmod((long double)tau, period) / period;
  return (double)(alpha[level] * dt * (1 - std::cos(2 * kPiL * cosineThetaInverse(u))));
}

// Total time on a level over its number of steps, in units of alpha dt: the note's "mean step".
double meanStepRatio(const std::vector<Step> &steps, int level, double alphaDt)
{
  double time  = 0;
  int    count = 0;
  for (const Step &step : steps)
    if (step.level == level) {
      time += step.h;
      ++count;
    }
  return time / count / alphaDt;
}

double kahanSum(const std::vector<Step> &steps)
{
  double sum = 0, compensation = 0;
  for (const Step &step : steps) {
    const double y = step.h - compensation, t = sum + y;
    compensation = (t - sum) - y;
    sum          = t;
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Construction

TEST(MesoscopicSchedule, Accessors)
{
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 3});
  EXPECT_EQ(schedule.numScales(), 3);
  EXPECT_EQ(schedule.microStep(), 1e-4);
  EXPECT_EQ(schedule.savingsFactor(1), 100);
  EXPECT_EQ(schedule.savingsFactor(2), 10);
  EXPECT_EQ(schedule.subintervals(1), 1);
  EXPECT_EQ(schedule.subintervals(2), 3);
}

std::string constructionError(double dt, std::vector<double> alpha, std::vector<int> m)
{
  const auto kernel = Kernel::create(KernelType::Cosine);
  try {
    MesoscopicSchedule schedule(*kernel, dt, alpha, m);
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "no exception";
}

TEST(MesoscopicSchedule, ConstructorRejectsBadParameters)
{
  EXPECT_EQ(constructionError(0, {10}, {1}), "micro step dt is 0: must be positive and finite");
  EXPECT_EQ(constructionError(-1e-3, {10}, {1}), "micro step dt is -0.001: must be positive and finite");
  EXPECT_EQ(constructionError(NAN, {10}, {1}), "micro step dt is nan: must be positive and finite");
  EXPECT_EQ(constructionError(INFINITY, {10}, {1}), "micro step dt is inf: must be positive and finite");
  EXPECT_EQ(constructionError(1e-4, {100, -1}, {1, 1}), "savings factor 2 is -1: must be non-negative and finite");
  EXPECT_EQ(constructionError(1e-4, {0}, {1}), "no exception"); // alpha = 0: the level is merged into the next
  EXPECT_EQ(constructionError(1e-4, {INFINITY}, {1}), "savings factor 1 is inf: must be non-negative and finite");
  EXPECT_EQ(constructionError(1e-4, {NAN}, {1}), "savings factor 1 is nan: must be non-negative and finite");
  EXPECT_EQ(constructionError(1e-4, {100, 10}, {1, 0}), "subinterval count 2 is 0: must be at least 1");
  EXPECT_EQ(constructionError(1e-4, {100, 10}, {1}), "got 2 savings factors and 1 subinterval counts: need one of each per scale above scale 0");
  EXPECT_EQ(constructionError(1e-4, {}, {}), "no exception"); // a single scale: micro steps only
}

// ---------------------------------------------------------------------------------------------
// The mesoscopic step formula

TEST(MesoscopicSchedule, StepsFollowTheMethodFormula)
{
  const auto                kernel = Kernel::create(KernelType::Cosine);
  const double              dt     = 1e-4;
  const std::vector<double> alpha{100, 10};
  const std::vector<int>    m{1, 1};
  const MesoscopicSchedule  schedule(*kernel, dt, alpha, m);
  for (double macroStep : {0.1, 1.0}) {
    const std::vector<Step> steps = record(schedule, macroStep);
    ASSERT_GT(steps.size(), 20u);
    for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
      const Step  &step     = steps[i];
      const double expected = referenceCosineStep(dt, alpha, m, step.level, step.tau, macroStep);
      ASSERT_NEAR(step.h, expected, 1e-12 * expected) << "step " << i << " level " << step.level << " tau " << step.tau;
      EXPECT_EQ(steps[i + 1].tau, step.tau + step.h); // steps follow each other without gaps
    }
    const Step &last = steps.back();
    EXPECT_LE(last.h, referenceCosineStep(dt, alpha, m, last.level, last.tau, macroStep) * (1 + 1e-12));
    EXPECT_EQ(last.tau + last.h, macroStep);
  }
}

TEST(MesoscopicSchedule, LevelStepIsMicroStepOnTopLevel)
{
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 1});
  EXPECT_EQ(schedule.levelStep(2, 0.03, 0.1), 1e-4);
  EXPECT_EQ(schedule.levelStep(1, 0.03, 0.1), schedule.mesoscopicStep(2, 0.03, 0.1));
  EXPECT_EQ(schedule.levelStep(0, 0.03, 0.1), schedule.mesoscopicStep(1, 0.03, 0.1));
  // Mid-period the cosine kernel is at its maximum 2: h_j = 2 alpha_j dt.
  EXPECT_NEAR(schedule.mesoscopicStep(1, 0.05, 0.1), 2 * 100 * 1e-4, 1e-15);
  EXPECT_NEAR(schedule.mesoscopicStep(2, 0.05, 0.1), 2 * 10 * 1e-4, 1e-15);
  // At the start of a period K = 0.
  EXPECT_EQ(schedule.mesoscopicStep(1, 0.0, 0.1), 0.0);
}

TEST(MesoscopicSchedule, ConstantKernelStepsAreExactlyAlphaDt)
{
  const auto               kernel = Kernel::create(KernelType::Constant);
  const MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 2});
  const double             expected[] = {100 * 1e-4, 10 * 1e-4, 1e-4};
  const std::vector<Step>  steps      = record(schedule, 0.1);
  ASSERT_GT(steps.size(), 20u);
  for (std::size_t i = 0; i + 1 < steps.size(); ++i) ASSERT_EQ(steps[i].h, expected[steps[i].level]) << "step " << i;
  EXPECT_LE(steps.back().h, expected[steps.back().level]);
}

// With m_j > 1, h_j has period DeltaT / m_j: small at the start of every period, 2 alpha_j dt mid-period.
TEST(MesoscopicSchedule, SubintervalsMakeStepsPeriodic)
{
  const auto                kernel = Kernel::create(KernelType::Cosine);
  const double              dt = 1e-4, macroStep = 0.4, period = macroStep / 4;
  const std::vector<double> alpha{100};
  const std::vector<int>    m{4};
  const MesoscopicSchedule  schedule(*kernel, dt, alpha, m);
  for (int i = 1; i < 100; ++i) {
    const double tau = period * (0.01 * i), h = schedule.mesoscopicStep(1, tau, macroStep);
    for (int k = 1; k < 4; ++k) EXPECT_NEAR(schedule.mesoscopicStep(1, tau + k * period, macroStep), h, 1e-10 * h) << "tau " << tau << " period " << k;
  }

  // In every period the steps start small and reach nearly 2 alpha dt mid-period; with m = 1
  // the same stretch of time, the second quarter of a single period, has no small step.
  const MesoscopicSchedule single(*kernel, dt, alpha, {1});
  const std::vector<Step>  steps = record(schedule, macroStep), singleSteps = record(single, macroStep);
  for (int k = 0; k < 4; ++k) {
    const auto inPeriod = [&](const Step &step) { return step.level == 0 && step.tau >= k * period && step.tau < (k + 1) * period; };
    double     smallest = INFINITY, largest = 0, singleSmallest = INFINITY;
    int        count = 0;
    for (std::size_t i = 0; i + 1 < steps.size(); ++i)
      if (inPeriod(steps[i])) {
        ++count;
        smallest = std::min(smallest, steps[i].h);
        largest  = std::max(largest, steps[i].h);
        ASSERT_NEAR(steps[i].h, referenceCosineStep(dt, alpha, m, 0, steps[i].tau, macroStep), 1e-12 * steps[i].h);
      }
    for (const Step &step : singleSteps)
      if (inPeriod(step)) singleSmallest = std::min(singleSmallest, step.h);
    ASSERT_GT(count, 5) << "period " << k;
    EXPECT_LT(smallest, 0.5 * alpha[0] * dt) << "period " << k;
    EXPECT_GT(largest, 1.9 * alpha[0] * dt) << "period " << k;
    if (k == 1) { EXPECT_GT(singleSmallest, 0.5 * alpha[0] * dt); }
  }
}

// ---------------------------------------------------------------------------------------------
// Mean steps: the method note's measured ratios of mean step to alpha_j dt.

TEST(MesoscopicSchedule, MeanStepsReproduceMeasuredRatios)
{
  const auto kernel = Kernel::create(KernelType::Cosine);
  {
    const MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 1});
    const double             ratio = meanStepRatio(record(schedule, 0.1), 0, 100 * 1e-4); // note: 1.002
    EXPECT_GE(ratio, 1.0);
    EXPECT_LE(ratio, 1.01);
    const std::vector<Step> steps = record(schedule, 1.0); // note: 1.07
    EXPECT_NEAR(meanStepRatio(steps, 0, 100 * 1e-4), 1.07, 0.01);
    EXPECT_NEAR(meanStepRatio(steps, 1, 10 * 1e-4), 1.07, 0.01);
  }
  {
    const MesoscopicSchedule schedule(*kernel, 1e-5, {1000}, {1});
    EXPECT_NEAR(meanStepRatio(record(schedule, 1.0), 0, 1000 * 1e-5), 1.03, 0.005); // note: 1.03
  }
}

// With many cycles per period, a cycle at s spends dt (1 + alpha K(s)) and advances Theta by that
// over the period, so cycles are spread with density K / (1 + alpha K) in s and the mean of K is
//   int K^2 / (1 + alpha K) ds / int K / (1 + alpha K) ds  ->  1  as alpha grows.
double continuumMeanRatio(double alpha)
{
  const int N        = 100000;
  double    weighted = 0, weight = 0;
  for (int i = 0; i < N; ++i) {
    const double k = (double)(1 - std::cos(2 * kPiL * (i + 0.5L) / N)), w = k / (1 + alpha * k);
    weighted += k * w;
    weight += w;
  }
  return weighted / weight;
}

TEST(MesoscopicSchedule, MeanStepApproachesAlphaDtAsAlphaGrows)
{
  const auto   kernel   = Kernel::create(KernelType::Cosine);
  const double dt       = 1e-5;
  double       previous = 2;
  for (double alpha : {10.0, 100.0, 1000.0, 10000.0}) {
    const MesoscopicSchedule schedule(*kernel, dt, {alpha}, {1});
    const double             ratio = meanStepRatio(record(schedule, 2000 * alpha * dt), 0, alpha * dt); // about 2000 cycles
    EXPECT_NEAR(ratio, continuumMeanRatio(alpha), 2e-3) << "alpha " << alpha;
    EXPECT_GT(ratio, 1.0) << "alpha " << alpha;
    EXPECT_LT(ratio, previous) << "alpha " << alpha;
    previous = ratio;
  }
  EXPECT_LT(previous, 1.01); // alpha = 10^4
}

// ---------------------------------------------------------------------------------------------
// The micro cycles of one macro step

// fl(tau + h) == end exactly, or no double h does it: h and its predecessor straddle end.
::testing::AssertionResult landsOnEndIfPossible(double tau, double h, double end)
{
  if (tau + h == end) return ::testing::AssertionSuccess();
  if (tau + h > end && tau + std::nextafter(h, 0.0) < end) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "tau " << tau << " + h " << h << " misses " << end << " though some h lands";
}

TEST(RunMacroStep, StepToEndLandsExactlyWhenPossible)
{
  unsigned   seed   = 777;
  const auto random = [&seed]() {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) / 16777216.0 + (seed & 255) / 4294967296.0;
  };
  int impossible = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const double end = std::ldexp(1 + random(), -10 + trial % 12), tau = end * random(), h = stepToEnd(tau, end);
    if (tau >= end / 2) {
      ASSERT_EQ(tau + h, end) << "tau " << tau << " end " << end; // Sterbenz: end - tau is exact
    }
    ASSERT_TRUE(landsOnEndIfPossible(tau, h, end));
    ASSERT_LE(tau + std::nextafter(h, 0.0), end); // the smallest such step
    if (tau + h != end) ++impossible;
  }
  EXPECT_LT(impossible, 1000); // rare: a tie that rounds away from end on both sides
}

TEST(RunMacroStep, LastStepLandsExactlyOnMacroStep)
{
  const auto kernel = Kernel::create(KernelType::Cosine);
  unsigned   seed   = 12345;
  const auto random = [&seed]() { // deterministic, in [0, 1)
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) / 16777216.0;
  };
  int lateStarts = 0, earlyStarts = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Macro steps from a fraction of a cycle (the last step may start before DeltaT/2) to many cycles.
    const double             dt = 1e-5 * (1 + random()), macroStep = std::pow(10.0, -4 + 3 * random()) * (1 + random());
    const MesoscopicSchedule schedule(*kernel, dt, {1000 * (1 + random()), 10}, {1, 1 + trial % 3});
    const std::vector<Step>  steps = record(schedule, macroStep);
    ASSERT_FALSE(steps.empty());
    const Step &last = steps.back();
    if (last.tau >= macroStep / 2) {
      ++lateStarts;
      ASSERT_EQ(last.tau + last.h, macroStep) << "trial " << trial;
    } else {
      ++earlyStarts;
      ASSERT_TRUE(landsOnEndIfPossible(last.tau, last.h, macroStep)) << "trial " << trial;
    }
    ASSERT_NEAR(kahanSum(steps), macroStep, 1e-14 * macroStep) << "trial " << trial;
    for (std::size_t i = 0; i + 1 < steps.size(); ++i) ASSERT_EQ(steps[i].h, schedule.levelStep(steps[i].level, steps[i].tau, macroStep)) << "trial " << trial;
    ASSERT_LE(last.h, schedule.levelStep(last.level, last.tau, macroStep)) << "trial " << trial;
  }
  EXPECT_GT(lateStarts, 100);
  EXPECT_GT(earlyStarts, 20);
}

// Each micro cycle takes one step per level (top first), so the work per cycle is the number of
// scales: linear in the number of scales.
TEST(RunMacroStep, StepsPerMicroCycleEqualNumberOfScales)
{
  const auto kernel = Kernel::create(KernelType::Cosine);
  for (int scales = 2; scales <= 6; ++scales) {
    std::vector<double> alpha;
    for (int j = 1; j < scales; ++j) alpha.push_back(std::pow(4.0, scales - j)); // slowest level: largest savings
    const MesoscopicSchedule schedule(*kernel, 1e-6, alpha, std::vector<int>(scales - 1, 1));
    MacroStepCounts          counts;
    const std::vector<Step>  steps = record(schedule, 0.1, &counts);
    const int                top   = scales - 1;
    ASSERT_GT(counts.cycles, 10) << scales << " scales";
    for (std::size_t i = 0; i < steps.size(); ++i) ASSERT_EQ(steps[i].level, top - static_cast<int>(i % scales)) << scales << " scales, step " << i;
    const std::int64_t total = static_cast<std::int64_t>(steps.size());
    EXPECT_GT(total, scales * (counts.cycles - 1));
    EXPECT_LE(total, scales * counts.cycles);
    ASSERT_EQ(counts.levelSteps.size(), static_cast<std::size_t>(scales));
    for (int level = 0; level <= top; ++level) {
      const std::int64_t onLevel = std::count_if(steps.begin(), steps.end(), [level](const Step &s) { return s.level == level; });
      EXPECT_EQ(counts.levelSteps[level], onLevel);
      EXPECT_GE(onLevel, counts.cycles - 1);
      EXPECT_LE(onLevel, counts.cycles);
    }
  }
}

TEST(RunMacroStep, SingleScaleTakesMicroStepsOnly)
{
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 0.03, {}, {});
  MacroStepCounts          counts;
  const std::vector<Step>  steps = record(schedule, 0.1, &counts);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(counts.cycles, 4);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(steps[i].h, 0.03);
  EXPECT_EQ(steps[3].tau + steps[3].h, 0.1);
}

// With m_1 = 4 and dt = DeltaT / 4, every mesoscopic step starts at a period boundary where
// K = 0: such steps of length 0 are not taken.
TEST(RunMacroStep, StepsOfLengthZeroAreNotTaken)
{
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 0.25, {10}, {4});
  MacroStepCounts          counts;
  const std::vector<Step>  steps = record(schedule, 1.0, &counts);
  EXPECT_EQ(counts.cycles, 4);
  EXPECT_EQ(counts.levelSteps[0], 0);
  EXPECT_EQ(counts.levelSteps[1], 4);
  for (const Step &step : steps) EXPECT_GT(step.h, 0.0);
}

TEST(RunMacroStep, AdvanceErrorStopsMacroStepAndIsReturned)
{
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 1});
  int                      calls = 0;
  MacroStepCounts          counts;
  const int                error = runMacroStep(
                   schedule, 0.1, [&](int, double, double) { return ++calls == 5 ? 7 : 0; }, &counts);
  EXPECT_EQ(error, 7);
  EXPECT_EQ(calls, 5);
  EXPECT_EQ(counts.cycles, 2);
  EXPECT_EQ(counts.levelSteps[0] + counts.levelSteps[1] + counts.levelSteps[2], 4); // the failed step is not counted
}

TEST(RunMacroStep, CountsDescribeOneMacroStep)
{
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 1});
  MacroStepCounts          first, second;
  record(schedule, 0.1, &first);
  second.cycles = 1000; // stale values are overwritten
  second.levelSteps.assign(7, 99);
  record(schedule, 0.1, &second);
  EXPECT_EQ(second.cycles, first.cycles);
  EXPECT_EQ(second.levelSteps, first.levelSteps);
  EXPECT_EQ(first.cycles, 9); // the method note: about 9 micro cycles per DeltaT = 0.1 here
}

} // namespace
