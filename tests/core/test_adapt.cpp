// The accuracy-control core: time ratios, the error model and the choice of parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adapt.hpp"
#include "kernel.hpp"
#include "rk.hpp"
#include "schedule.hpp"
#include "stability.hpp"

using namespace vshmm;

TEST(Adapt, TimeRatiosAndSavingsFactorsAreInverse)
{
  // alpha = (100, 10): A_2 = dt, A_1 = 11 dt, A_0 = 111 dt
  const std::vector<double> r = timeRatiosFromSavings({100, 10});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0], 111.0 / 11.0);
  EXPECT_DOUBLE_EQ(r[1], 11.0);
  const std::vector<double> a = savingsFromTimeRatios(r);
  EXPECT_NEAR(a[0], 100, 1e-12);
  EXPECT_NEAR(a[1], 10, 1e-12);
  EXPECT_DOUBLE_EQ(cycleLength({1e-4, r}), 111e-4);
  // r = 1 is no savings: alpha = 0
  EXPECT_EQ(savingsFromTimeRatios({1.0, 1.0}), (std::vector<double>{0.0, 0.0}));
}

// The micro step's term measured from the finer side (its coarser run unstable): a run at 3/4 of
// the micro step differs by the term times 1 - 0.75^4, and the model reads the term itself.
TEST(Adapt, TheMicroStepsTermFromTheFinerSide)
{
  const AdaptParameters        now{1e-6, {50, 20}};
  const double                 cdt   = 1e23;
  auto                         error = [&](const AdaptParameters &p) { return cdt * std::pow(p.microStep, 4) / (p.ratios[0] * p.ratios[1]); };
  std::vector<AdaptParameters> coarse{coarsened(now, 0, 0.75), now, now};
  std::vector<double>          d{error(now) - error(coarse[0]), 0.0, 0.0};
  EXPECT_DOUBLE_EQ(coarse[0].microStep, 0.75e-6);
  const ErrorModel model = ErrorModel::fromDifferences(now, coarse, d, 4);
  EXPECT_NEAR(model.cMicro, cdt, 1e-9 * cdt);
  EXPECT_NEAR(model.term(now, 0), d[0] / (1 - std::pow(0.75, 4)), 1e-12 * error(now));
  // a micro step changed by less than 10% either way measures nothing
  coarse[0] = coarsened(now, 0, 0.95);
  EXPECT_EQ(ErrorModel::fromDifferences(now, coarse, d, 4).cMicro, 0.0);
}

// A synthetic macro step whose error is exactly the model's: the choice meets the target with
// the shares the least-work rule gives, and refines the term that dominates.
TEST(Adapt, ChoiceMeetsTheTargetWithEqualShares)
{
  const AdaptParameters        now{1e-6, {50, 20}};
  const double                 cdt = 1e23, c0 = 1e-3, c1 = 1e-4; // e_dt = 1e-4, e_0 = 4.9e-2, e_1 = 1.9e-3
  auto                         error = [&](const AdaptParameters &p, int i) { return i == 0 ? cdt * std::pow(p.microStep, 4) / (p.ratios[0] * p.ratios[1]) : (i == 1 ? c0 : c1) * (p.ratios[i - 1] - 1); };
  std::vector<AdaptParameters> coarse;
  std::vector<double>          d;
  for (int i = 0; i < 3; ++i) {
    coarse.push_back(coarsened(now, i, i ? 4.0 : 2.0));
    d.push_back(error(coarse.back(), i) - error(now, i));
  }
  EXPECT_DOUBLE_EQ(coarse[1].ratios[0], 1 + 4 * 49.0); // r - 1 times the factor
  EXPECT_DOUBLE_EQ(coarse[0].microStep, 2e-6);
  const ErrorModel model = ErrorModel::fromDifferences(now, coarse, d, 4);
  EXPECT_NEAR(model.cMicro, cdt, 1e-9 * cdt);
  EXPECT_NEAR(model.c[0], c0, 1e-15);
  EXPECT_NEAR(model.c[1], c1, 1e-15);
  EXPECT_NEAR(model.total(now), error(now, 0) + error(now, 1) + error(now, 2), 1e-15);

  AdaptBounds bounds;
  bounds.maxMicroStep = 1e-5;
  bounds.maxRefine = bounds.maxGrowth = 100;
  const double          target        = 1e-2;
  const AdaptParameters next          = chooseParameters(now, model, target, bounds);
  EXPECT_NEAR(model.total(next), target, 1e-9);
  // the two ratios get equal shares w, the micro step w / (order + 1)
  const double w = target / (2 + 0.2);
  EXPECT_NEAR(model.term(next, 1), w, 1e-9);
  EXPECT_NEAR(model.term(next, 2), w, 1e-9);
  EXPECT_NEAR(model.term(next, 0), w / 5, 1e-9);
  EXPECT_LT(next.ratios[0], now.ratios[0]); // the dominant term is refined
  EXPECT_GT(next.ratios[1], now.ratios[1]); // the small ones are coarsened
  EXPECT_GT(next.microStep, now.microStep);
}

// A level pair whose averaging error saturates beyond its separation s (the slowest modes of the
// faster level slowed below the slower level): e = c x / (1 + x / s), x = r - 1. The model with
// that s recovers c from one coarsened run, and the estimate of the comparison (every term doubled)
// stays true where a linear model would take the small difference for the whole error.
TEST(Adapt, SaturatingPairTermIsMeasuredAndInverted)
{
  EXPECT_DOUBLE_EQ(pairUnit(4.0, 0.0), 4.0); // no separation known: linear
  EXPECT_DOUBLE_EQ(pairUnit(4.0, 4.0), 2.0);
  EXPECT_DOUBLE_EQ(pairUnitInverse(pairUnit(30.0, 10.0), 10.0), 30.0);
  EXPECT_TRUE(std::isinf(pairUnitInverse(10.0, 10.0))); // at or above the saturated value: any ratio

  const double                 s = 70, c = 1e-3, cdt = 1e16; // e_dt = 8.7e-6
  const std::vector<double>    sat{s};
  const AdaptParameters        now{2.5e-5, {451}};
  auto                         error = [&](const AdaptParameters &p) { return cdt * std::pow(p.microStep, 4) / p.ratios[0] + c * (p.ratios[0] - 1) / (1 + (p.ratios[0] - 1) / s); };
  std::vector<AdaptParameters> coarse{coarsened(now, 0, 2.0), coarsened(now, 1, 4.0)};
  std::vector<double>          d{error(coarse[0]) - error(now), 0.0};
  d[1]                    = c * (pairUnit(coarse[1].ratios[0] - 1, s) - pairUnit(450, s));
  const ErrorModel model  = ErrorModel::fromDifferences(now, coarse, d, 4, sat);
  const ErrorModel linear = ErrorModel::fromDifferences(now, coarse, d, 4);
  EXPECT_NEAR(model.c[0], c, 1e-12);
  EXPECT_NEAR(model.total(now), error(now), 1e-12 * error(now));
  const AdaptParameters q  = termsScaled(now, 2.0, 4);
  const double          dq = error(q) - error(now); // what the comparison measures
  // the estimate d * total(p) / (total(q) - total(p)) of each model, against the true error
  const double est = dq * model.total(now) / (model.total(q) - model.total(now));
  const double lin = dq * linear.total(now) / (linear.total(q) - linear.total(now));
  EXPECT_NEAR(est, error(now), 1e-9 * error(now));
  EXPECT_LT(lin, 0.25 * error(now)); // the blind estimate of the saturated term

  // the choice: a target below the saturated value c s is met with the inverse of g; above it any
  // ratio meets it and the ratio goes to its bound
  AdaptBounds bounds;
  bounds.fixedMicroStep = true;
  bounds.maxRefine = bounds.maxGrowth = 1e3;
  const double          target        = 0.5 * c * s;
  const AdaptParameters next          = chooseParameters(now, model, target, bounds);
  // (the fixed micro step's term is taken at the ratio of the pass before: within 0.2%)
  EXPECT_NEAR(model.total(next), target, 2e-3 * target);
  EXPECT_NEAR(next.ratios[0] - 1, pairUnitInverse((target - model.term(next, 0)) / c, s), 0.5);
  EXPECT_NEAR(next.ratios[0] - 1, s, 0.1); // half the saturated error: at the knee, x = s
  const AdaptParameters any = chooseParameters(now, model, 2 * c * s, bounds);
  EXPECT_DOUBLE_EQ(any.ratios[0], 451.0 * 1e3);
}

// The chain's initial layer (docs/accuracy.md section 3): x1 relaxes at rate 1/e = 100, DeltaT =
// 0.1, and the error of x0 saturates at r_0 - 1 = 10 (measured: C (r_0 - 1) / (r_0 + 9)). A faster
// pair's transient has the slow level's share of the macro step only: rate 1e4 gives 1000 / r_0.
TEST(Adapt, LayerSaturations)
{
  AdaptParameters p;
  p.microStep                 = 1e-6;
  p.ratios                    = {5.0, 20.0, 3.0};
  const std::vector<double> s = layerSaturations(p, 0.1, {0.5, 100.0, 1e4, 1e6});
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[0], 10.0);
  EXPECT_DOUBLE_EQ(s[1], 1000.0 / 5.0);
  EXPECT_DOUBLE_EQ(s[2], 1e5 / (5.0 * 20.0));
  const std::vector<double> none = layerSaturations(p, 0.1, {0.5, 0.0, std::numeric_limits<double>::infinity(), 1e6});
  EXPECT_EQ(none[0], 0.0); // no rate known: linear
  EXPECT_EQ(none[1], 0.0);
  EXPECT_DOUBLE_EQ(none[2], 1e5 / (5.0 * 20.0));
}

// The comparison of the estimate scales every term by one factor whatever the coefficients; the
// equal-share model and the share floor keep totals.
TEST(Adapt, ScaledTermsAndEqualShares)
{
  const AdaptParameters p{2e-7, {40, 1, 8}}; // the middle pair merged
  ErrorModel            m;
  m.order  = 4;
  m.cMicro = 3e25;
  m.c      = {2e-4, 5.0, 1e-3};
  for (double f : {2.0, 3.0}) {
    const AdaptParameters q = termsScaled(p, f, 4);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.term(q, i), f * m.term(p, i), 1e-12 * (1 + m.term(p, i))) << "term " << i;
    EXPECT_DOUBLE_EQ(q.ratios[1], 1.0); // a merged pair stays merged
    EXPECT_GT(cycleLength(q), cycleLength(p));
  }
  const ErrorModel e = ErrorModel::equalShares(p, 4, 0.6);
  EXPECT_NEAR(e.total(p), 0.6, 1e-12);
  EXPECT_NEAR(e.term(p, 1), 0.6 / (2 + 0.2), 1e-12);
  EXPECT_NEAR(e.term(p, 3), 0.6 / (2 + 0.2), 1e-12);
  EXPECT_EQ(e.term(p, 2), 0.0);
  EXPECT_NEAR(e.term(p, 0), 0.6 / (2 + 0.2) / 5, 1e-12);
  ErrorModel f        = m;
  f.c[2]              = 0.0; // measured as nothing
  const double before = f.total(p);
  f.floorShares(p, 0.05);
  EXPECT_NEAR(f.total(p), before, 1e-12 * before);
  EXPECT_GT(f.term(p, 3) / f.total(p), 0.04); // 5% of the total before the other terms are scaled back
  EXPECT_LE(f.term(p, 3) / f.total(p), 0.05);
}

// Two comparisons (every term x 1.5 and x 2) recover an error that grows as a power of the
// scaling, faster than linearly (an initial layer), linearly, or saturated; beyond the exponent's
// range it is clamped.
TEST(Adapt, ErrorFromTwoComparisons)
{
  for (double kappa : {0.3, 1.0, 2.4, 4.0})
    for (double E : {1e-3, 0.7}) {
      const double d1 = E * (std::pow(1.5, kappa) - 1), d2 = E * (std::pow(2.0, kappa) - 1);
      double       k;
      EXPECT_NEAR(errorFromTwoComparisons(d1, 1.5, d2, 2.0, &k), E, 1e-9 * E) << "kappa " << kappa;
      EXPECT_NEAR(k, kappa, 1e-9) << "kappa " << kappa;
    }
  double k;
  // d2 / d1 below ln 2 / ln 1.5 (no exponent gives it: noise, or a term that shrinks): the smallest exponent
  EXPECT_NEAR(errorFromTwoComparisons(1.0, 1.5, 1.2, 2.0, &k), 1.2 / (std::pow(2.0, 0.02) - 1), 1e-9);
  EXPECT_DOUBLE_EQ(k, 0.02);
  // far above the ratio of exponent 6: the largest
  EXPECT_NEAR(errorFromTwoComparisons(1.0, 1.5, 100.0, 2.0, &k), 100.0 / 63.0, 1e-9);
  EXPECT_DOUBLE_EQ(k, 6.0);
  // the linear case, d2 = 2 d1: the comparison's own difference d2 is the error (what the model assumes)
  EXPECT_NEAR(errorFromTwoComparisons(0.5, 1.5, 1.0, 2.0), 1.0, 1e-9);
}

// The work change of a choice is limited by moving back only the parameters that go the wrong way.
TEST(Adapt, WorkChangeIsLimitedByTheParametersThatCauseIt)
{
  const AdaptParameters now{1e-6, {10, 10}};
  AdaptParameters       next{8e-6, {5, 80}}; // 8 * 0.5 * 8 = 32x cheaper
  limitWorkChange(next, now, 4.0, 4.0);
  EXPECT_NEAR(cycleLength(next) / cycleLength(now), 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(next.ratios[0], 5.0);                                             // the refining change is kept
  EXPECT_NEAR(next.microStep / now.microStep, next.ratios[1] / now.ratios[1], 1e-9); // coarsening ones moved back alike
  AdaptParameters dear{1e-7, {2, 20}};                                               // 10 * 5 / 2 = 25x dearer
  limitWorkChange(dear, now, 4.0, 4.0);
  EXPECT_NEAR(cycleLength(now) / cycleLength(dear), 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(dear.ratios[1], 20.0);
  AdaptParameters within{2e-6, {10, 10}};
  limitWorkChange(within, now, 4.0, 4.0);
  EXPECT_DOUBLE_EQ(within.microStep, 2e-6);
}

TEST(Adapt, ChoiceKeepsFixedParametersAndBounds)
{
  const AdaptParameters now{1e-6, {50, 20}};
  ErrorModel            model;
  model.order  = 4;
  model.cMicro = 1e20;
  model.c      = {1e-3, 1e-4};
  AdaptBounds bounds;
  bounds.fixedMicroStep      = true;
  bounds.maxRatio            = {1e9, 25};
  bounds.maxCycle            = 1e-3;
  const AdaptParameters next = chooseParameters(now, model, 1.0, bounds); // a loose target: coarsen
  EXPECT_EQ(next.microStep, now.microStep);
  EXPECT_LE(next.ratios[1], 25.0);
  EXPECT_LE(next.ratios[0], now.ratios[0] * bounds.maxGrowth * (1 + 1e-12));
  EXPECT_LE(cycleLength(next), 1e-3 * (1 + 1e-12));
  bounds.fixedRatios         = true;
  const AdaptParameters same = chooseParameters(now, model, 1e-6, bounds);
  EXPECT_EQ(same.ratios, now.ratios);
}

TEST(Adapt, StableStepsLimitMicroStepAndPeakSteps)
{
  AdaptParameters p{1e-4, {100, 10}};
  limitToStableSteps(p, 2.0, {1e-2, 5e-3, 5e-5});
  EXPECT_EQ(p.microStep, 5e-5);
  // level 1 peak: alpha_2 dt Kmax = (r_1 - 1) dt 2 <= 5e-3 -> r_1 <= 51: unchanged at 10
  EXPECT_EQ(p.ratios[1], 10);
  // level 0 peak: (r_0 - 1) r_1 dt 2 <= 1e-2 -> r_0 <= 1 + 1e-2 / (10 * 5e-5 * 2) = 11
  EXPECT_NEAR(p.ratios[0], 11, 1e-12);
  const std::vector<double> a = savingsFromTimeRatios(p.ratios);
  EXPECT_NEAR(a[0] * p.microStep * 2, 1e-2, 1e-15);
}

// The work rate counts the level steps a micro cycle takes (a level with r_l = 1 takes none) at
// their costs, against the steps of runMacroStep() (up to the last cycle, cut at the macro
// step's end: at most one cycle's cost, 6); savings whose product of ratios is below the
// cycle's cost over the fastest level's cost are dearer than the single-rate step.
TEST(Adapt, WorkRateCountsTheLevelStepsOfACycle)
{
  const std::vector<double> cost   = {1, 2, 3}; // level l evaluates splits 0..l
  const auto                kernel = Kernel::create(KernelType::Constant);
  const double              DeltaT = 1.0;
  for (const std::vector<double> &ratios : std::vector<std::vector<double>>{{1.1, 1.2}, {1, 2}, {3, 1}, {1, 1}, {10, 10}}) {
    const AdaptParameters    p{1e-3, ratios};
    const MesoscopicSchedule schedule(*kernel, p.microStep, savingsFromTimeRatios(ratios), {1, 1});
    MacroStepCounts          counts;
    ASSERT_EQ(runMacroStep(
                schedule, DeltaT, [](int, double, double) { return 0; }, &counts),
              0);
    double evaluations = 0;
    for (int l = 0; l < 3; ++l) evaluations += cost[l] * counts.levelSteps[l];
    EXPECT_NEAR(workRate(p, cost) * DeltaT, evaluations, 6.0) << ratios[0] << ", " << ratios[1];
  }
  const AdaptParameters single{1e-3, {1, 1}};
  EXPECT_GT(workRate({1e-3, {1.1, 1.2}}, cost), workRate(single, cost)); // 6 / 1.32 against 3 per dt
  EXPECT_LT(workRate({1e-3, {1.5, 1.5}}, cost), workRate(single, cost)); // 6 / 2.25
  EXPECT_TRUE(std::isnan(workRate(single, {1, 2})));
}

// The running product: a mode amplified near the kernel's peak but damped over the macro step
// shows a largest running growth far above its net change.
TEST(Adapt, LevelAmplificationReportsGrowthWithinTheMacroStep)
{
  const Tableau            rk4("4", 4, 4, {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0}, {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, {0, 0.5, 0.5, 1});
  const StabilityFunction  R(rk4);
  const auto               kernel = Kernel::create(KernelType::Cosine);
  const MesoscopicSchedule schedule(*kernel, 1e-3, {4}, {1});
  // lambda = -900: RK4 is stable up to 2.785 / 900 = 3.1e-3; the mean step is 5e-3 and the peak 1e-2
  const LevelAmplification a = levelAmplification(R, schedule, 1.0, 0, -900.0);
  EXPECT_GT(a.largestStep * 900, R.realLimit());
  EXPECT_GT(a.largestGrowth, a.logAmplification);
  EXPECT_GT(a.largestGrowth, std::log(100.0));
  // a stable mode never grows
  const LevelAmplification b = levelAmplification(R, schedule, 1.0, 0, -10.0);
  EXPECT_EQ(b.largestGrowth, 0.0);
  EXPECT_LT(b.logAmplification, 0.0);
}

TEST(FastSwing, CountsQuantitiesThatTurnWithTheLevel)
{
  /* tol 1e-2, weights tol (1 + |q|) at q = 0: a rate of 1 is a relative rate of 1 (and 100
     tolerances per unit time) */
  const double tol = 1e-2, minRate = 10, rho = 1000;
  const auto   swings = [&](const std::vector<double> &rate, const std::vector<double> &weight) { return vshmm::fastSwingSquares(rate, rate, weight, tol, minRate, rho); };
  /* a quantity slaved to the slow ones (relative rate 1) and one turning with the level (1000) */
  EXPECT_EQ(swings({1.0, 1.0}, {1e-2, 1e-2}), 0.0);
  const double swing = (1000 / 1e-2) / rho; /* 100 tolerances */
  EXPECT_DOUBLE_EQ(swings({1.0, 1000.0}, {1e-2, 1e-2}), swing * swing);
  /* the sign, and a zero weight (nothing to weigh) */
  EXPECT_DOUBLE_EQ(swings({-1000.0, 1000.0}, {1e-2, 0.0}), swing * swing);
  /* the relative rate decides: just below and above minRate */
  EXPECT_EQ(swings({9.9}, {1e-2}), 0.0);
  EXPECT_DOUBLE_EQ(swings({10.1}, {1e-2}), (1010 / rho) * (1010 / rho));
  /* the weight is relative to the quantity: the same rate on a quantity of 99 is 100 times slower */
  EXPECT_EQ(swings({1000.0}, {1.0}), 0.0);
  /* moved fast by the level's splits and back by the others (an invariant of an oscillation
     written across splits): the whole field's rate is slow, nothing turns; the swing is the whole
     field's */
  EXPECT_EQ(vshmm::fastSwingSquares({1000.0}, {1.0}, {1e-2}, tol, minRate, rho), 0.0);
  EXPECT_EQ(vshmm::fastSwingSquares({1.0}, {1000.0}, {1e-2}, tol, minRate, rho), 0.0);
  EXPECT_DOUBLE_EQ(vshmm::fastSwingSquares({1000.0}, {500.0}, {1e-2}, tol, minRate, rho), (50000 / rho) * (50000 / rho));
  /* no radius or no tolerance: nothing */
  EXPECT_EQ(vshmm::fastSwingSquares({1000.0}, {1000.0}, {1e-2}, tol, minRate, 0.0), 0.0);
  EXPECT_EQ(vshmm::fastSwingSquares({1000.0}, {1000.0}, {1e-2}, 0.0, minRate, rho), 0.0);
}
