// Stability functions of explicit Runge-Kutta tableaus against their known polynomials and
// stability limits, and the amplification of a level's steps over a macro step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "stability.hpp"

namespace {

using vshmm::Tableau;
using cd = std::complex<double>;

Tableau Euler()
{
  return Tableau("1fe", 1, 1, {0}, {1}, {0});
}
Tableau Heun()
{
  return Tableau("2a", 2, 2, {0, 0, 1, 0}, {0.5, 0.5}, {0, 1});
}
Tableau Kutta3()
{
  return Tableau("3", 3, 3, {0, 0, 0, 0.5, 0, 0, -1, 2, 0}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {0, 0.5, 1});
}
Tableau RK4()
{
  return Tableau("4", 4, 4, {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0}, {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, {0, 0.5, 0.5, 1});
}

TEST(StabilityFunction, IsTheTruncatedExponentialForMethodsWithOrderEqualToStages)
{
  const Tableau tabs[] = {Euler(), Heun(), Kutta3(), RK4()};
  for (const Tableau &t : tabs) {
    vshmm::StabilityFunction R(t);
    for (cd z : {cd(-1.3, 0.4), cd(0.2, -2.0), cd(-2.5, 0)}) {
      cd taylor = 1, term = 1;
      for (int k = 1; k <= t.stages; ++k) taylor += (term *= z / double(k));
      EXPECT_NEAR(std::abs(R(z) - taylor), 0.0, 1e-14) << t.name;
    }
  }
}

TEST(StabilityFunction, KnownRealAndImaginaryLimits)
{
  EXPECT_NEAR(vshmm::StabilityFunction(Euler()).realLimit(), 2.0, 1e-9);
  EXPECT_NEAR(vshmm::StabilityFunction(Heun()).realLimit(), 2.0, 1e-9);
  EXPECT_NEAR(vshmm::StabilityFunction(Kutta3()).realLimit(), 2.5127453266, 1e-8);
  EXPECT_NEAR(vshmm::StabilityFunction(RK4()).realLimit(), 2.7852935634, 1e-8);
  EXPECT_NEAR(vshmm::StabilityFunction(Kutta3()).imaginaryLimit(), std::sqrt(3.0), 1e-8);
  EXPECT_NEAR(vshmm::StabilityFunction(RK4()).imaginaryLimit(), 2 * std::sqrt(2.0), 1e-8);
  // Euler and Heun amplify every purely imaginary mode: (almost) no interval.
  EXPECT_LT(vshmm::StabilityFunction(Euler()).imaginaryLimit(), 1e-5);
  EXPECT_LT(vshmm::StabilityFunction(Heun()).imaginaryLimit(), 3e-3);
}

// rayLimit() leaps over the part of a ray where the polynomial |R(x d)|^2 stays below its bound by
// a margin its Taylor coefficients cannot close within the leap, and scans in steps of 1e-3 only
// near the crossing. Its limits are those of the plain scan in steps of 1e-3 (then bisected) on
// rays all around the left half plane (finer near the imaginary axis), for methods with short and long stability intervals: no
// leap passes a crossing the scan finds (a leap of the whole cap, not bounded by the margin, ends
// on the far side of the boundary).
TEST(StabilityFunction, RayLimitsAreThoseOfAFineScan)
{
  // a 12-stage first-order method with a long real interval (each stage a damped Euler step)
  std::vector<double> a(144, 0.0), b(12, 0.0), c(12, 0.0);
  for (int i = 1; i < 12; ++i) a[i * 12 + i - 1] = 0.9 / (13 - i);
  b[11]                = 1;
  const Tableau tabs[] = {Heun(), Kutta3(), RK4(), Tableau("chain12", 1, 12, a, b, c)};
  for (const Tableau &t : tabs) {
    const vshmm::StabilityFunction R(t);
    std::vector<double>            angles; // every 3 degrees, and every 0.01 within 0.1 of the imaginary axis (where a stability region's boundary bends most)
    for (int k = 0; k <= 60; ++k) angles.push_back(M_PI / 2 + M_PI * k / 60.0);
    for (int k = 1; k <= 10; ++k) angles.insert(angles.end(), {M_PI / 2 + 0.01 * k, 1.5 * M_PI - 0.01 * k});
    for (const double angle : angles) {
      const cd d      = std::polar(1.0, angle);
      auto     stable = [&](double x) { return std::abs(R(x * d)) <= 1.0 + 1e-12; };
      double   x      = 0;
      while (x < 100 && stable(x + 1e-3)) x += 1e-3;
      double lo = x, hi = x + 1e-3;
      for (int it = 0; it < 60; ++it) (stable(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
      EXPECT_NEAR(R.rayLimit(d), lo, 1e-9 * (1 + lo)) << t.name << " direction " << d;
    }
  }
}

TEST(StabilityFunction, LargestStableStepScalesWithTheEigenvalue)
{
  vshmm::StabilityFunction R(RK4());
  EXPECT_NEAR(R.largestStableStep(-1000.0), 2.7852935634e-3, 1e-11);
  EXPECT_NEAR(R.largestStableStep(cd(0, 500)), 2 * std::sqrt(2.0) / 500, 1e-11);
  EXPECT_TRUE(std::isinf(R.largestStableStep(0.0)));
  // Along a ray inside the left half plane the limit lies between the axes' limits and is a
  // boundary point: |R| = 1 there.
  const cd     lambda = std::polar(1.0, 0.75 * M_PI);
  const double h      = R.largestStableStep(lambda);
  EXPECT_NEAR(std::abs(R(h * lambda)), 1.0, 1e-9);
  EXPECT_GT(std::abs(R(1.01 * h * lambda)), 1.0);
}

TEST(StabilityFunction, SlightlyGrowingOscillationsAreJudgedAgainstTheirOwnGrowth)
{
  // An oscillation that grows slowly (Re lambda = 0.11, Im lambda = 1e6) is stable for RK4 up to
  // about the imaginary-axis limit, not for no step at all.
  vshmm::StabilityFunction R(RK4());
  const cd                 lambda(0.11, 1e6);
  EXPECT_NEAR(R.largestStableStep(lambda), 2 * std::sqrt(2.0) / 1e6, 1e-9);
  // A real growing mode is never limited for RK4: R(z) < exp(z) for z > 0.
  EXPECT_EQ(R.largestStableStep(2000.0), vshmm::StabilityFunction::kMaxRadius / 2000.0);
  // Forward Euler grows y' = i y: for an oscillation with no growth of its own it has no stable step.
  EXPECT_LT(vshmm::StabilityFunction(Euler()).largestStableStep(cd(0, 1)), 1e-5);
}

TEST(LevelAmplification, ConstantKernelGivesThePowerOfOneStep)
{
  auto                      kernel = vshmm::Kernel::create(vshmm::KernelType::Constant);
  vshmm::MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 1});
  vshmm::StabilityFunction  R(RK4());
  const double              lambda = -1500.0;
  // Level 1 takes steps of exactly 1e-3 (but the shortened last one).
  const vshmm::LevelAmplification a = vshmm::levelAmplification(R, schedule, 0.1, 1, lambda);
  ASSERT_GT(a.steps, 5);
  EXPECT_DOUBLE_EQ(a.largestStep, 1e-3);
  // Every full step damps by |R(-1.5)|; the shortened last one by a factor between that and 1
  // (|R(-x)| decreases on [0, 1.5] for RK4).
  const double per_step = std::log(std::abs(R(1e-3 * lambda)));
  ASSERT_LT(per_step, 0.0);
  EXPECT_GE(a.logAmplification, a.steps * per_step - 1e-9);
  EXPECT_LE(a.logAmplification, (a.steps - 1) * per_step + 1e-9);
}

TEST(LevelAmplification, AGrowingModeIsMeasuredAgainstItsOwnGrowth)
{
  // The amplification of a mode with Re lambda > 0 is taken relative to the exact flow's growth:
  // sum over the level's steps of log|R(h lambda)| - h Re lambda. Constant kernel: steps of 1e-3
  // (but the shortened last one), so the sum lies between (steps - 1) and steps times one full
  // step's term (the term decreases from 0 along both rays below).
  auto                      kernel = vshmm::Kernel::create(vshmm::KernelType::Constant);
  vshmm::MesoscopicSchedule schedule(*kernel, 1e-4, {100, 10}, {1, 1});
  vshmm::StabilityFunction  R(RK4());
  // A real growing mode, z = 0.05: RK4 follows exp(z) to -z^5/120 per step (about -2.6e-9).
  // An oscillation growing slowly, z = 1.1e-4 + 1.5i: |R(1.5i)| = 0.9414 damps, growth 1.1e-4.
  for (const cd lambda : {cd(50.0, 0.0), cd(0.11, 1500.0)}) {
    const vshmm::LevelAmplification a = vshmm::levelAmplification(R, schedule, 0.1, 1, lambda);
    ASSERT_GT(a.steps, 5);
    const double per_step = std::log(std::abs(R(1e-3 * lambda))) - 1e-3 * lambda.real();
    ASSERT_LT(per_step, 0.0);
    EXPECT_GE(a.logAmplification, a.steps * per_step - 1e-12 * a.steps) << lambda;
    EXPECT_LE(a.logAmplification, (a.steps - 1) * per_step + 1e-12 * a.steps) << lambda;
  }
}

TEST(LevelAmplification, VariableStepsBeyondThePeakLimitCanStillDampOverAPeriod)
{
  // The paper's dissipative parameters: level 1 (alpha_2 = 10, dt = 1e-4, cosine kernel) peaks at
  // h_2 = 2e-3. For lambda = -1500 the peak step is outside RK4's interval (z = -3 < -2.785),
  // yet the period as a whole damps; for lambda = -3000 it does not.
  auto                            kernel = vshmm::Kernel::create(vshmm::KernelType::Cosine);
  vshmm::MesoscopicSchedule       schedule(*kernel, 1e-4, {100, 10}, {1, 1});
  vshmm::StabilityFunction        R(RK4());
  const vshmm::LevelAmplification mild = vshmm::levelAmplification(R, schedule, 0.1, 1, -1500.0);
  EXPECT_GT(mild.largestStep * 1500.0, R.realLimit());
  EXPECT_LT(mild.logAmplification, 0.0);
  const vshmm::LevelAmplification hard = vshmm::levelAmplification(R, schedule, 0.1, 1, -3000.0);
  EXPECT_GT(hard.logAmplification, 0.0);
  // The micro steps of the top level are all dt.
  const vshmm::LevelAmplification top = vshmm::levelAmplification(R, schedule, 0.1, 2, -1e4);
  EXPECT_DOUBLE_EQ(top.largestStep, 1e-4);
  EXPECT_NEAR(top.logAmplification, top.steps * std::log(std::abs(R(-1.0))), 1e-9 * top.steps);
}

TEST(LargestStableSavingsFactor, IsTheEdgeOfTheCriterion)
{
  // The paper's dissipative parameters with lambda = -3000 at level 1: alpha_2 = 10 does not
  // damp the mode over a macro step (above). The factor found passes the criterion, a slightly
  // larger one fails, and the parameters passed in are left as they were.
  auto                      kernel = vshmm::Kernel::create(vshmm::KernelType::Cosine);
  vshmm::StabilityFunction  R(RK4());
  const std::vector<double> savings      = {100, 10};
  const std::vector<int>    subintervals = {1, 1};
  const double              target = 0.5, growth = 100, lambda = -3000;
  const double              alpha = vshmm::largestStableSavingsFactor(R, *kernel, 1e-4, savings, subintervals, 0.1, 2, lambda, target, growth);
  EXPECT_EQ(savings, (std::vector<double>{100, 10}));
  ASSERT_GT(alpha, 1.0);
  ASSERT_LT(alpha, 10.0);
  auto passes = [&](double a) {
    const vshmm::MesoscopicSchedule schedule(*kernel, 1e-4, {100, a}, subintervals);
    const vshmm::LevelAmplification amp = vshmm::levelAmplification(R, schedule, 0.1, 1, lambda);
    return amp.logAmplification <= std::log(target) && amp.largestGrowth <= std::log(growth);
  };
  EXPECT_TRUE(passes(alpha));
  EXPECT_FALSE(passes(alpha * (1 + 1e-6)));
  // Where even tiny steps do not damp enough (a growing mode), no positive factor passes.
  EXPECT_EQ(vshmm::largestStableSavingsFactor(R, *kernel, 1e-4, savings, subintervals, 0.1, 2, 10.0, target, growth), 0.0);
}

TEST(FastestGrowthRate, CountsGrowingModesAboveTheNoise)
{
  using C = std::complex<double>;
  // a rotation at 1e3 growing at 250 beside a decaying mode: 250
  EXPECT_DOUBLE_EQ(vshmm::fastestGrowthRate({C(250, 1e3), C(250, -1e3), C(-50, 0)}), 250.0);
  // only decaying modes, a growth at the noise (5e-7 of |lambda|), and a growing zero mode: none
  EXPECT_EQ(vshmm::fastestGrowthRate({C(-1, 10), C(5e-7, 1e3), C(1e-9, 0)}), 0.0);
  EXPECT_EQ(vshmm::fastestGrowthRate({}), 0.0);
  // the largest of two growing modes; central differences' noise admits a smaller real part
  EXPECT_DOUBLE_EQ(vshmm::fastestGrowthRate({C(3, 0), C(40, 100)}), 40.0);
  EXPECT_EQ(vshmm::fastestGrowthRate({C(5e-4, 1e3)}), 0.0);
  EXPECT_DOUBLE_EQ(vshmm::fastestGrowthRate({C(5e-4, 1e3)}, vshmm::kAmplitudeRateCentralNoise), 5e-4);
}

TEST(SlowestRate, AnOscillationsAmplitudeRateCounts)
{
  using C = std::complex<double>;
  // a relaxation at 100 and a rotation at 1e4 damped at 0.1: the damping is the slow process
  EXPECT_DOUBLE_EQ(vshmm::slowestRate({C(-100, 0), C(-0.1, 1e4), C(-0.1, -1e4)}), 0.1);
  // an undamped rotation (a real part at the estimate's noise) changes on its own time scale
  EXPECT_DOUBLE_EQ(vshmm::slowestRate({C(5e-7, 1e3), C(5e-7, -1e3)}), std::abs(C(5e-7, 1e3)));
  // a decaying mode: its modulus; zero modes are left out; nothing left: 0
  EXPECT_DOUBLE_EQ(vshmm::slowestRate({C(-30, 10), C(1e-12, 0), C(-1000, 0)}), std::abs(C(-30, 10)));
  EXPECT_EQ(vshmm::slowestRate({}), 0.0);
  // a real part of 1e-7 of the frequency: noise for forward differences' Ritz values, a rate for
  // central differences' (noise 1e-8); it lies in between, where a second estimate is needed
  const std::vector<C> damped = {C(-1e-4, 1e3), C(-1e-4, -1e3)};
  EXPECT_DOUBLE_EQ(vshmm::slowestRate(damped), std::abs(damped[0]));
  EXPECT_DOUBLE_EQ(vshmm::slowestRate(damped, vshmm::kAmplitudeRateCentralNoise), 1e-4);
  EXPECT_TRUE(vshmm::ambiguousAmplitudeRate(damped));
  EXPECT_FALSE(vshmm::ambiguousAmplitudeRate({C(5e-10 * 1e3, 1e3)}));                    // below both levels: noise
  EXPECT_FALSE(vshmm::ambiguousAmplitudeRate({C(-0.1, 1e4)}));                           // above both: a rate either way
  EXPECT_FALSE(vshmm::ambiguousAmplitudeRate({C(-1e-4, 0), C(-1e3, 0)}));                // no oscillation
  EXPECT_FALSE(vshmm::ambiguousAmplitudeRate({C(-1e-13, 1e-6), C(-1e3, 0), C(0, 1e3)})); // a zero mode left out
}

// The noise levels of the real parts scale with the block's entries over its eigenvalues: a
// rotation's entries are its eigenvalues' size (the fixed levels), a position-velocity block
// [[0, 1], [-w^2, 0]]'s are w times larger (a stiff bond at w = 1195, ||X|| = 1.5: forward
// differences' rounding sqrt(eps) w ||X|| / (1 + ||X||) = 1.1e-5 of w, central ones' eps^(2/3) times
// the same, 2.6e-8); its forward estimate of 1.6e-6 of w is noise, no longer a slow damping.
TEST(SlowestRate, TheNoiseLevelsScaleWithTheBlocksEntries)
{
  using C                                = std::complex<double>;
  const vshmm::AmplitudeRateNoise rotate = vshmm::amplitudeRateNoise(1e3, 1e3, 1.5);
  EXPECT_EQ(rotate.forward, vshmm::kAmplitudeRateNoise);
  EXPECT_EQ(rotate.central, vshmm::kAmplitudeRateCentralNoise);
  const double                    w = 1195, eps = std::numeric_limits<double>::epsilon();
  const vshmm::AmplitudeRateNoise bond = vshmm::amplitudeRateNoise(w * w, w, 1.5);
  EXPECT_NEAR(bond.forward, std::sqrt(eps) * w * 0.6, 1e-12);
  EXPECT_NEAR(bond.central, std::pow(eps, 2.0 / 3.0) * w * 0.6, 1e-15);
  const std::vector<C> read = {C(1.6e-6 * w, w), C(1.6e-6 * w, -w)};
  EXPECT_DOUBLE_EQ(vshmm::slowestRate(read), 1.6e-6 * w);                      /* with the fixed level it was a slow process, */
  EXPECT_FALSE(vshmm::ambiguousAmplitudeRate(read));                           /* and not estimated again; */
  EXPECT_DOUBLE_EQ(vshmm::slowestRate(read, bond.forward), std::abs(read[0])); /* now it is noise for forward differences, */
  EXPECT_TRUE(vshmm::ambiguousAmplitudeRate(read, bond));                      /* estimated again by central ones, */
  const std::vector<C> central = {C(2e-9 * w, w), C(2e-9 * w, -w)};            /* which read 2e-9 of w: noise, the bond's frequency */
  EXPECT_DOUBLE_EQ(vshmm::slowestRate(central, bond.central), std::abs(central[0]));
  const std::vector<C> damped = {C(-1e-6 * w, w), C(-1e-6 * w, -w)}; /* a true damping at 1e-6 of w: central differences still tell it */
  EXPECT_DOUBLE_EQ(vshmm::slowestRate(damped, bond.central), 1e-6 * w);
  const vshmm::AmplitudeRateNoise none = vshmm::amplitudeRateNoise(1.0, 0.0, 1.0); /* no eigenvalue: the fixed levels */
  EXPECT_EQ(none.forward, vshmm::kAmplitudeRateNoise);
}

TEST(LargestAccurateStep, KeepsTheAmplitudeOverTheSpan)
{
  vshmm::StabilityFunction   R(RK4());
  const std::complex<double> omega(0, 1e3);
  // RK4 on a rotation: 1 - |R(iy)| = y^6 / 144 + O(y^8)
  EXPECT_NEAR(vshmm::amplitudeError(R, omega, 1e-4), std::pow(0.1, 6) / 144, 1e-2 * std::pow(0.1, 6) / 144);
  EXPECT_NEAR(vshmm::amplitudeError(R, std::complex<double>(-50, 0), 1e-3), std::fabs(std::log(std::abs(R(-0.05))) + 0.05), 1e-6 * std::pow(0.05, 5) / 120);
  // 2 / h steps (span 2, cycle = h) with at most 1e-2 of amplitude lost in all
  const double h = vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2);
  EXPECT_LT(h, 2.5e-3);
  EXPECT_LE(vshmm::amplitudeError(R, omega, h) * 2.0 / h, 1e-2);
  EXPECT_GT(vshmm::amplitudeError(R, omega, 1.01 * h) * 2.0 / (1.01 * h), 1e-2);
  // a bound that already holds is kept; no mode: no bound
  EXPECT_EQ(vshmm::largestAccurateStep(R, {omega}, 1e-5, 2.0, 1e-2), 1e-5);
  EXPECT_EQ(vshmm::largestAccurateStep(R, {}, 2.5e-3, 2.0, 1e-2), 2.5e-3);
}

// RK4's phase lag on a rotation, y^5 / 120 + O(y^7) per step (y = h |lambda|), and the step that
// keeps the amplitude error plus a weighted phase error within a bound: the phase (about 6 / (5 y)
// times the amplitude error) then sets it.
TEST(LargestAccurateStep, CountsThePhaseWhereTheValuesHoldTheMode)
{
  vshmm::StabilityFunction   R(RK4());
  const std::complex<double> omega(0, 1e3);
  EXPECT_NEAR(vshmm::phaseError(R, omega, 1e-4), std::pow(0.1, 5) / 120, 1e-2 * std::pow(0.1, 5) / 120);
  EXPECT_NEAR(vshmm::phaseError(R, std::conj(omega), 1e-4), std::pow(0.1, 5) / 120, 1e-2 * std::pow(0.1, 5) / 120);
  EXPECT_EQ(vshmm::phaseError(R, std::complex<double>(-50, 0), 1e-3), 0.0); /* a real decay keeps its sign */
  /* the difference is taken modulo 2 pi: at y = 2.5 the step is stable and lags by less than pi */
  EXPECT_LT(vshmm::phaseError(R, omega, 2.5e-3), 3.14159);
  const double amplitudeOnly = vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2);
  const double withPhase     = vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2, 0.5);
  EXPECT_LT(withPhase, 0.8 * amplitudeOnly);
  const auto error = [&](double h) { return (vshmm::amplitudeError(R, omega, h) + 0.5 * vshmm::phaseError(R, omega, h)) * 2.0 / h; };
  EXPECT_LE(error(withPhase), 1e-2);
  EXPECT_GT(error(1.01 * withPhase), 1e-2);
  EXPECT_EQ(vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2, 0.0), amplitudeOnly);
}

// At steps far below the accuracy bound the errors (y^6 / 144 and y^5 / 120 per step, y = h |lambda|)
// are far below the roundoff of R(z) - exp(z) in floating point (about 1e-16 per step); summed over
// many steps that roundoff read as an error that grows as the step falls, and a tolerance of 1e-9
// took the step from 5e-10 down to 1e-12 of it (the oscillators at -ts_rtol 1e-9: 4.7e-22, a run
// without end). The errors come from the Taylor terms above the method's order.
TEST(LargestAccurateStep, StepsFarBelowTheLimitKeepTheirErrorsAboveRoundoff)
{
  vshmm::StabilityFunction   R(RK4());
  const std::complex<double> omega(0, 1e6);
  for (double h : {1e-9, 1e-11, 1e-13}) {
    const double y = h * 1e6;
    EXPECT_NEAR(vshmm::amplitudeError(R, omega, h), std::pow(y, 6) / 144, 1e-2 * std::pow(y, 6) / 144) << h;
    EXPECT_NEAR(vshmm::phaseError(R, omega, h), std::pow(y, 5) / 120, 1e-2 * std::pow(y, 5) / 120) << h;
  }
  /* a decay: exp(-y) - R(-y) = y^5 / 120 - ... of exp(-y) */
  EXPECT_NEAR(vshmm::amplitudeError(R, std::complex<double>(-1e6, 0), 1e-9), std::pow(1e-3, 5) / 120, 1e-2 * std::pow(1e-3, 5) / 120);
  /* the step for 1e-9 of amplitude and phase over 7.3e-3 of time: y^5 (1/144 y + 1/120) 7.3e-3 / h = 1e-9,
     h about 1.1e-9, a step where the roundoff alone would read 1e-16 x 7e6 steps = 7e-10 */
  const double h = vshmm::largestAccurateStep(R, {omega}, 5e-7, 7.3e-3, 1e-9, 1.0);
  EXPECT_GT(h, 5e-10);
  EXPECT_LT(h, 5e-9);
  const auto error = [&](double k) { return (vshmm::amplitudeError(R, omega, k) + vshmm::phaseError(R, omega, k)) * 7.3e-3 / k; };
  EXPECT_LE(error(h), 1e-9);
  EXPECT_GT(error(1.01 * h), 1e-9);
  /* the same step from either side of |z| = 1/2 (the accurate sum and the direct formula agree there) */
  EXPECT_NEAR(vshmm::amplitudeError(R, omega, 0.4999e-6), vshmm::amplitudeError(R, omega, 0.5001e-6), 5e-3 * vshmm::amplitudeError(R, omega, 0.5e-6)); /* y^6 changes by 2.4e-3 between them */
  EXPECT_NEAR(vshmm::phaseError(R, omega, 0.4999e-6), vshmm::phaseError(R, omega, 0.5001e-6), 5e-3 * vshmm::phaseError(R, omega, 0.5e-6));
}

// An oscillation that restores its amplitude (a limit cycle) keeps an amplitude error only over the
// time it takes to restore it: the amplitude summed over 2e-3 of the span (a rate 1,000 restoring
// the amplitude of a rotation at 1,000 on a span of 2), the phase still over the whole span.
TEST(LargestAccurateStep, AnAmplitudeRestoredIsCountedOverItsRestoringTime)
{
  vshmm::StabilityFunction   R(RK4());
  const std::complex<double> omega(0, 1e3);
  const double               restored = vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2, 0.0, 1e-3);
  EXPECT_EQ(restored, vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 1e-3, 1e-2));      /* the amplitude alone: as over a span of 1e-3 */
  EXPECT_GT(restored, 2.5 * vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2)); /* (2000)^(1/5): 4.6x */
  const double withPhase = vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2, 0.5, 1e-3);
  const auto   error     = [&](double h) { return (vshmm::amplitudeError(R, omega, h) * 1e-3 + 0.5 * vshmm::phaseError(R, omega, h) * 2.0) / h; };
  EXPECT_LE(error(withPhase), 1e-2);
  EXPECT_GT(error(1.01 * withPhase), 1e-2);
  EXPECT_LT(withPhase, restored);
  /* not positive, or not shorter than the span: the amplitude over the whole span */
  EXPECT_EQ(vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2, 0.0, -1.0), vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2));
  EXPECT_EQ(vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2, 0.0, 5.0), vshmm::largestAccurateStep(R, {omega}, 2.5e-3, 2.0, 1e-2));
}

} // namespace

namespace {

// The response to a constant forcing along e1 of y' = H y + e1, against closed forms.
TEST(ForcedResponse, ClosedForms)
{
  EXPECT_NEAR(vshmm::forcedResponse({0.0}, 1, 1, 3.0), 3.0, 1e-12);                       // no dynamics: tau
  EXPECT_NEAR(vshmm::forcedResponse({-2.0}, 1, 1, 3.0), (1 - std::exp(-6.0)) / 2, 1e-12); // relaxation: (1 - e^{-r tau}) / r
  EXPECT_NEAR(vshmm::forcedResponse({-1e4}, 1, 1, 4.0), 1e-4, 1e-12);                     // a stiff relaxation forgets: 1 / r
  for (double tau : {0.3, 4.0}) {                                                         // a rotation at omega: sqrt(2 - 2 cos(omega tau)) / omega
    const double omega = 1e3;
    EXPECT_NEAR(vshmm::forcedResponse({0, omega, -omega, 0}, 2, 2, tau), std::sqrt(2 - 2 * std::cos(omega * tau)) / omega, 1e-8 / omega);
  }
  EXPECT_EQ(vshmm::forcedResponse({-1.0}, 1, 1, 0.0), 0.0);
}

// A slow variable the forcing moves, read through a leading dimension larger than n: y1' = -y1 + 1,
// y2' = y1 - 100 y2 (the Hessenberg matrices of an Arnoldi run are stored so).
TEST(ForcedResponse, LeadingDimension)
{
  const double        tau = 2.0;
  std::vector<double> H   = {-1, 1, 99, 0, -100, 99}; // ld 3, the third row is not read
  const double        y1  = 1 - std::exp(-tau);
  const double        y2  = (1 - std::exp(-100 * tau)) / 100 - (std::exp(-tau) - std::exp(-100 * tau)) / 99; // int_0^tau e^{-100 (tau - s)} y1(s) ds
  EXPECT_NEAR(vshmm::forcedResponse(H, 2, 3, tau), std::hypot(y1, y2), 1e-10);
}

} // namespace

namespace {

// Two rotations (frequencies 1000 and 1010, the block form x' = w y, y' = -w x in coordinates Q
// mixes, so that e1 holds both): each turned by theta in its own plane, the faster one (above the
// split 1005) by delta more, against the closed form Q R Q^T e1. A real mode stays; singular
// eigenvectors give nothing.
TEST(ModesTurned, EachOscillationByItsAngle)
{
  using C                     = std::complex<double>;
  const double        h       = 1 / std::sqrt(2.0);
  const double        Q[4][4] = {{h, 0, h, 0}, {0, h, 0, h}, {h, 0, -h, 0}, {0, h, 0, -h}}; // symmetric, orthogonal
  std::vector<double> vr(16);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) vr[i + j * 4] = Q[i][j] * h; // the block's eigenvectors (1, i) / sqrt 2 for +i w, mixed by Q
  const std::vector<C> lambda  = {C(0, 1000), C(0, -1000), C(0, 1010), C(0, -1010)};
  const auto           rotated = [](double theta, double delta, double split) { return [=](double w) { return theta + (w > split ? delta : 0.0); }; };
  for (double theta : {0.0, 0.7, 2.5})
    for (double delta : {0.0, 1.5707963267948966, 3.0}) {
      const std::vector<double> y = vshmm::modesTurned(vr, lambda, 4, rotated(theta, delta, 1005));
      ASSERT_EQ(y.size(), 4u);
      const double b[4] = {h * std::cos(theta), -h * std::sin(theta), h * std::cos(theta + delta), -h * std::sin(theta + delta)}; // Q^T e1 = (h, 0, h, 0) turned
      for (int i = 0; i < 4; ++i) {
        double expected = 0;
        for (int j = 0; j < 4; ++j) expected += Q[i][j] * b[j];
        EXPECT_NEAR(y[i], expected, 1e-14) << "theta " << theta << " delta " << delta << " component " << i;
      }
    }
  const std::vector<double> real = vshmm::modesTurned({1.0}, {C(-1, 0)}, 1, rotated(2.0, 1.0, 0.0));
  ASSERT_EQ(real.size(), 1u);
  EXPECT_EQ(real[0], 1.0);
  EXPECT_TRUE(vshmm::modesTurned(std::vector<double>(16, 0.0), lambda, 4, rotated(1.0, 0.0, 1005)).empty());
  EXPECT_TRUE(vshmm::modesTurned(vr, {C(0, 1)}, 4, rotated(1.0, 0.0, 0)).empty()); // eigenvalues and vectors do not match
}

// Two fast rotations 10 apart beat at 10 (a slow process where the slower level's rate is 1); equal
// frequencies do not beat; a difference as fast as the rotations is no beat; real modes and slow
// oscillations (below fastAbove) are not counted; beats within 1% are one.
TEST(BeatFrequencies, DifferencesOfDistinctFastFrequencies)
{
  using C                            = std::complex<double>;
  const std::vector<vshmm::Beat> two = vshmm::beatFrequencies({C(-1, 0), C(0, 1000), C(0, -1000), C(0, 1010), C(0, -1010)}, 10, 10);
  ASSERT_EQ(two.size(), 1u);
  EXPECT_DOUBLE_EQ(two[0].frequency, 10.0);
  EXPECT_EQ(two[0].lower, 1000.0);
  EXPECT_EQ(two[0].upper, 1010.0);
  EXPECT_TRUE(vshmm::beatFrequencies({C(0, 1000), C(0, -1000), C(-1e-9, 1000 * (1 + 1e-8))}, 10, 10).empty()); // equal up to the estimate's noise
  EXPECT_TRUE(vshmm::beatFrequencies({C(0, 1000), C(0, 1500)}, 10, 10).empty());                               // 500: not 10 times slower than 1000
  EXPECT_TRUE(vshmm::beatFrequencies({C(-5000, 0), C(-5001, 0)}, 10, 10).empty());                             // no oscillation
  EXPECT_TRUE(vshmm::beatFrequencies({C(0, 5), C(0, 6), C(0, 1000)}, 10, 10).empty());                         // 5 and 6 below fastAbove
  const std::vector<vshmm::Beat> band = vshmm::beatFrequencies({C(0, 50), C(0, 50.0113), C(0, 50.08), C(0, 50.0805)}, 10, 10);
  ASSERT_EQ(band.size(), 4u); // 0.0005 (distinct: 1e-5 of 50), 0.0113, 0.0687 (0.0692 within 1% of it), 0.08 (0.0805 within 1%)
  EXPECT_NEAR(band[0].frequency, 0.0005, 1e-9);
  EXPECT_EQ(band[0].lower, 50.08);
  EXPECT_NEAR(band[1].frequency, 0.0113, 1e-9);
  EXPECT_NEAR(band[2].frequency, 0.0687, 1e-9);
  EXPECT_EQ(band[2].lower, 50.0113);
  EXPECT_NEAR(band[3].frequency, 0.08, 1e-9);
}

// Three fast rotations whose frequencies make w1 + w2 - w3 = 10 are a triad at 10, though no pair
// of them beats; a rotation and one at twice its frequency less 5 are a triad (2 w1 - w2) at 5; an
// exact resonance (g = 0) is no slow process, a combination as fast as the rotations is none, and
// real modes and slow oscillations are not counted.
TEST(SlowCombinations, TriadsOfThreeFastFrequencies)
{
  using C                                     = std::complex<double>;
  const std::vector<vshmm::Combination> three = vshmm::slowCombinations({C(0, 1000), C(0, -1000), C(0, 1500), C(0, -1500), C(0, 2490), C(0, -2490), C(-7, 0)}, 10, 10, 3);
  ASSERT_EQ(three.size(), 1u);
  EXPECT_NEAR(three[0].frequency, 10.0, 1e-9);
  EXPECT_EQ(three[0].w, (std::vector<double>{1000, 1500, 2490}));
  EXPECT_EQ(three[0].c, (std::vector<int>{1, 1, -1}));
  EXPECT_TRUE(vshmm::beatFrequencies({C(0, 1000), C(0, 1500), C(0, 2490)}, 10, 10).empty()); // no pair beats
  const std::vector<vshmm::Combination> middle = vshmm::slowCombinations({C(0, 1000), C(0, 2490), C(0, 1500)}, 10, 10, 3);
  ASSERT_EQ(middle.size(), 1u); // the same triad, whatever the order of the modes
  EXPECT_EQ(middle[0].w, (std::vector<double>{1000, 1500, 2490}));
  const std::vector<vshmm::Combination> sum = vshmm::slowCombinations({C(0, 1000), C(0, 2495), C(0, 1500)}, 10, 10, 3);
  ASSERT_EQ(sum.size(), 1u); // 1000 + 1500 - 2495 = 5
  EXPECT_NEAR(sum[0].frequency, 5.0, 1e-9);
  const std::vector<vshmm::Combination> twice = vshmm::slowCombinations({C(0, 1000), C(0, 1995)}, 10, 10, 3);
  ASSERT_EQ(twice.size(), 1u);
  EXPECT_NEAR(twice[0].frequency, 5.0, 1e-9);
  EXPECT_EQ(twice[0].w, (std::vector<double>{1000, 1995}));
  EXPECT_EQ(twice[0].c, (std::vector<int>{2, -1}));
  EXPECT_TRUE(vshmm::slowCombinations({C(0, 1000), C(0, 1500), C(0, 2500)}, 10, 10, 3).empty());    // exact resonance
  EXPECT_TRUE(vshmm::slowCombinations({C(0, 1000), C(0, 1500), C(0, 2400)}, 10, 10, 3).empty());    // 100: not 10 times slower than 1000
  EXPECT_TRUE(vshmm::slowCombinations({C(-1000, 0), C(-1500, 0), C(-2490, 0)}, 10, 10, 3).empty()); // no oscillation
  EXPECT_TRUE(vshmm::slowCombinations({C(0, 5), C(0, 6), C(0, 10.9)}, 10, 10, 3).empty());          // below fastAbove
}

// Four fast rotations with w1 - w2 - w3 + w4 = -10 (1000, 1700, 2300, 2990) are a quartet at 10,
// though no pair beats and no three of them combine slowly (3 w1 - w4 at 10 and 2 w3 - w2 - w4 at
// 90 are others, all kept); so are w1 + w2 + w3 - w4, 2 w1 - w2 -
// w3, 2 w1 + w2 - w3 and 3 w1 - w2 (a mode taken twice or three times); 2 w1 - 2 w2 is twice a
// beat (no coefficient +-1), and a quartet as fast as the rotations is none.
TEST(SlowCombinations, QuartetsOfFourFastFrequencies)
{
  using C                                    = std::complex<double>;
  const std::vector<std::complex<double>> q4 = {C(0, 1000), C(0, 1700), C(0, 2300), C(0, 2990)};
  EXPECT_TRUE(vshmm::beatFrequencies(q4, 10, 10).empty());
  EXPECT_TRUE(vshmm::slowCombinations(q4, 10, 10, 3).empty());
  const std::vector<vshmm::Combination> four = vshmm::slowCombinations(q4, 10, 10, 4);
  ASSERT_EQ(four.size(), 3u); // and 3 w1 - w4 at 10 too, 2 w3 - w2 - w4 at 90: each its own product of the modes
  EXPECT_NEAR(four[0].frequency, 10.0, 1e-9);
  EXPECT_NEAR(four[1].frequency, 10.0, 1e-9);
  EXPECT_NEAR(four[2].frequency, 90.0, 1e-9);
  const vshmm::Combination &q = four[0].w.size() == 4 ? four[0] : four[1];
  EXPECT_EQ(q.w, (std::vector<double>{1000, 1700, 2300, 2990}));
  EXPECT_EQ(q.c, (std::vector<int>{1, -1, -1, 1}));
  EXPECT_EQ(four[2].c, (std::vector<int>{1, -2, 1}));
  const std::vector<vshmm::Combination> three = vshmm::slowCombinations({C(0, 1000), C(0, 1300), C(0, 1450), C(0, 3757)}, 10, 10, 4);
  ASSERT_EQ(three.size(), 1u); // 1000 + 1300 + 1450 - 3757 = -7
  EXPECT_NEAR(three[0].frequency, 7.0, 1e-9);
  EXPECT_EQ(three[0].c, (std::vector<int>{1, 1, 1, -1}));
  const struct {
    std::vector<std::complex<double>> modes;
    double                            g;
    std::vector<int>                  size; /* the |c| of the combination, ascending */
  } repeated[] = {
    {{C(0, 1000), C(0, 1200), C(0, 803)}, 3, {1, 1, 2}},  // 2 w - w' - w'': 2000 - 1200 - 803
    {{C(0, 1000), C(0, 1200), C(0, 3196)}, 4, {1, 1, 2}}, // 2 w + w' - w'': 2000 + 1200 - 3196
    {{C(0, 1000), C(0, 2996)}, 4, {1, 3}},                // 3 w - w': 3000 - 2996
  };
  for (const auto &r : repeated) {
    const std::vector<vshmm::Combination> found = vshmm::slowCombinations(r.modes, 10, 10, 4);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NEAR(found[0].frequency, r.g, 1e-9);
    std::vector<int> size;
    double           sum = 0;
    for (size_t n = 0; n < found[0].c.size(); ++n) {
      size.push_back(std::abs(found[0].c[n]));
      sum += found[0].c[n] * found[0].w[n];
    }
    std::sort(size.begin(), size.end());
    EXPECT_EQ(size, r.size);
    EXPECT_NEAR(std::fabs(sum), r.g, 1e-9);
  }
  EXPECT_TRUE(vshmm::slowCombinations({C(0, 1000), C(0, 1002)}, 1, 10, 4).empty());                          // 2 w1 - 2 w2: twice the beat at 2
  EXPECT_TRUE(vshmm::slowCombinations({C(0, 1000), C(0, 1600), C(0, 2300), C(0, 3000)}, 10, 10, 4).empty()); // 100: not 10 times slower than 1000
  EXPECT_TRUE(vshmm::slowCombinations({C(0, 1000), C(0, 1500), C(0, 2350), C(0, 2850)}, 10, 10, 4).empty()); // exact resonance
}

} // namespace
