// Accuracy control of VSHMM: the parameters in the form the error model uses (micro step and
// time ratios), the error model, and the choice of parameters for a tolerance. No PETSc here.
//
// Time ratios. In one micro cycle scale k acts for A_k = dt (1 + alpha_{k+1} + ... + alpha_K)
// (A_K = dt: the fastest scale acts during the micro step only; A_0 is the length of the cycle).
// The time ratio of the level pair (l, l+1) is r_l = A_l / A_{l+1} >= 1. The method slows scale
// l+1 relative to scale l by r_l: where the problem separates the two by S_l (ratio of their
// rates), the method keeps an effective separation sigma_l = S_l / r_l. r_l = 1 (alpha_{l+1} = 0)
// merges level l into level l+1: no savings there.
//
// Error model (measured in docs/user-guide.md "Accuracy on request"): the error of the slow
// quantities over a macro step is a sum of one term per parameter,
//   e_dt = c_dt dt^p / prod r_l (the micro step: the fast scale's error per micro step, dt^(p+1),
//                                times the number of cycles in the macro step, DeltaT / A_0)
//   e_l  = c_l g_l(r_l - 1)     (level pair l: averaging error ~ 1/sigma_l, none when merged),
// g_l(x) = x / (1 + x / s_l): linear while the effective separation sigma_l stays above 1, and
// saturating where the method slows level l+1 below level l's time scale (r_l beyond the pair's
// separation s_l, when that is known: TSVSHMMSetScaleSeparations()), or where level l+1's
// transient, slowed by r_l, outlasts the macro step (layerSaturations(): an initial layer);
// s_l = inf otherwise.
// The c's are measured by comparing the macro step with one whose parameter is coarsened
// (dt -> 2 dt, r_l - 1 -> 2 (r_l - 1)). Work per macro step is proportional to
// 1 / A_0 = 1 / (dt prod r_l), so the cheapest parameters for a total error E give each free ratio
// (about) the same share w of E and the micro step the share w / (p + 1).
#pragma once

#include <vector>

namespace vshmm {

// r_l = A_l / A_{l+1} for l = 0..K-1 from alpha_1..alpha_K (alpha_j >= 0).
std::vector<double> timeRatiosFromSavings(const std::vector<double> &savings);
// alpha_{l+1} = prod_{j>=l} r_j - prod_{j>l} r_j: the inverse of timeRatiosFromSavings.
std::vector<double> savingsFromTimeRatios(const std::vector<double> &ratios);

struct AdaptParameters {
  double              microStep = 0.0;
  std::vector<double> ratios; // r_0 .. r_{K-1}, each >= 1
};

// Cycle length A_0 = dt prod r_l.
double cycleLength(const AdaptParameters &p);

// The coarsened parameters whose comparison measures one error term: which = 0 multiplies the
// micro step by `factor`, which = 1 + l multiplies r_l - 1 (and so the term e_l; a merged pair,
// r_l = 1, stays merged).
AdaptParameters coarsened(const AdaptParameters &p, int which, double factor = 2.0);

// The parameters whose every error term is `factor` times that of p: each r_l - 1 times factor,
// and dt so that dt^order / prod r_l is too. Under the model the difference of the two macro
// steps is (factor - 1) times the error of p, whatever the coefficients; with factor 2 the
// comparison costs about 1/7 of the step (K = 2, RK4).
AdaptParameters termsScaled(const AdaptParameters &p, double factor, int order);

// Moves `next` back towards `now` so that the work per macro step (1 / cycle length) falls by at
// most maxCheaper and rises by at most maxDearer: the parameters that coarsen (or, when too dear,
// those that refine) are moved back geometrically by one fraction; the others keep their change
// (a choice that moves the error from one term to another is not undone).
void limitWorkChange(AdaptParameters &next, const AdaptParameters &now, double maxCheaper, double maxDearer);

// The shape of a level pair's error term: g(x) = x / (1 + x / s) for x = r - 1 (s = inf or
// s <= 0: g(x) = x), and its inverse (infinite where u >= s: any ratio stays below u).
double pairUnit(double x, double s);
double pairUnitInverse(double u, double s);

// Where each pair's term saturates by the time the faster level has (an initial layer): level
// l+1, slowed by r_l relative to level l, relaxes (or turns) over r_l / rate[l+1] of level l's
// time, rate[l+1] > 0 its slowest own rate; level l acts for macroStep / (r_0 ... r_{l-1}) of its
// own time in a macro step. Beyond s_l = macroStep rate[l+1] / (r_0 ... r_{l-1}) the slowed
// transient outlasts the macro step and a larger r_l changes the slow values no further. rate has
// K + 1 entries (rate[0] is not used); a rate that is not positive and finite gives s_l = 0
// (none: linear).
std::vector<double> layerSaturations(const AdaptParameters &p, double macroStep, const std::vector<double> &rate);

// The error of p from two comparisons with every error term scaled by f1 and by f2 > f1 > 1
// (termsScaled()), their differences d1 and d2 from p, where the error grows as a power of the
// scaling, e(f) = e(1) f^kappa, whatever the model says (an initial layer: faster than linearly,
// the fastest level slowed by the product of the ratios; or slower, saturated): d2 / d1 =
// (f2^kappa - 1) / (f1^kappa - 1) gives kappa, clamped to [kappaMin, kappaMax], and the error is
// d2 / (f2^kappa - 1). *kappa (if not null) receives the exponent. d1, d2 must be positive.
double errorFromTwoComparisons(double d1, double f1, double d2, double f2, double *kappa = nullptr, double kappaMin = 0.02, double kappaMax = 6.0);

// The error model: e_dt = cMicro dt^order / prod r_l, e_l = c[l] g(r_l - 1, saturation[l]).
struct ErrorModel {
  double              cMicro = 0.0;
  std::vector<double> c;
  std::vector<double> saturation; // s_l per level pair (empty or inf: linear)
  int                 order = 1;

  // Coefficients from the differences d_i between the macro step with p and with coarse[i], which
  // differs from p in parameter i only (dt, or r_{i-1}): d_i = term_i(coarse[i]) - term_i(p).
  // A parameter that could not be coarsened (coarse[i] equal to p) gets coefficient 0.
  static ErrorModel fromDifferences(const AdaptParameters &p, const std::vector<AdaptParameters> &coarse, const std::vector<double> &differences, int order, const std::vector<double> &saturation = {});
  // Equal shares at p (the least-work split, as if p were the best parameters for its error):
  // every level pair with r_l > 1 has the term `total` / (n + 1 / (order + 1)), the micro step
  // 1 / (order + 1) of that, for n such pairs. The model before anything is measured.
  static ErrorModel equalShares(const AdaptParameters &p, int order, double total, const std::vector<double> &saturation = {});
  double            unit(const AdaptParameters &p, int l) const;     // g(r_l - 1, s_l)
  double            term(const AdaptParameters &p, int which) const; // e_dt (which = 0) or e_l (which = 1 + l)
  double            total(const AdaptParameters &p) const;
  void              scale(double f); // every coefficient times f (a new measurement of the total)
  // Every term at least `fraction` of the total at p (a term measured as about zero could
  // otherwise grow without limit on one noisy measurement); the total is kept.
  void floorShares(const AdaptParameters &p, double fraction);
};

// What the choice must respect.
struct AdaptBounds {
  bool                fixedMicroStep = false; // set by the user: kept
  bool                fixedRatios    = false; // savings set by the user: kept
  double              maxMicroStep   = 0.0;   // stability (and accuracy) bound on dt (> 0)
  double              maxCycle       = 0.0;   // bound on A_0 (enough cycles per macro step); 0: none
  std::vector<double> maxRatio;               // per level pair, from stability and separation (>= 1)
  double              maxGrowth = 2.0;        // largest coarsening factor of dt, r_l or r_l - 1 per choice
  double              maxRefine = 8.0;        // largest refining factor
};

// The parameters that meet the total error `target` with the least work under the model,
// starting from `now` (fixed parameters are kept and use their share of the target).
AdaptParameters chooseParameters(const AdaptParameters &now, const ErrorModel &model, double target, const AdaptBounds &bounds);

// Split evaluations per unit of time with p: the cost of a micro cycle over its length A_0. A micro
// cycle takes one step of the fastest level (levelCost[K] split evaluations per stage) and one of
// every level l with r_l > 1 (levelCost[l]); a level with r_l = 1 takes none (alpha_{l+1} = 0: its
// splits are evaluated in the faster levels' steps). So savings whose product of ratios is below
// the cycle's cost over levelCost[K] cost more work than a single-rate step with the same micro
// step. levelCost has K + 1 entries.
double workRate(const AdaptParameters &p, const std::vector<double> &levelCost);

// Shrinks every r_l - 1 by one factor (and then dt, if fixedRatios or still needed) so that the
// cycle length A_0 is at most maxCycle.
void fitCycle(AdaptParameters &p, double maxCycle, bool fixedRatios, bool fixedMicroStep);

// Keeps every step stable: the micro step at most maxLevelStep[K], and level l's peak step
// alpha_{l+1} dt kernelPeak (alpha_{l+1} = (r_l - 1) prod_{j>l} r_j) at most maxLevelStep[l],
// by lowering dt, then r_{K-1}, ..., r_0 (an infinite bound does not limit).
void limitToStableSteps(AdaptParameters &p, double kernelPeak, const std::vector<double> &maxLevelStep);

// What a faster level moves of the sampled quantities on its own time scale: an observable that
// carries the level's phase, which VSHMM does not compute (it samples the level statistically, and
// with savings its value at a sampled time is one phase of it, not the solution's). For quantities
// with derivatives levelRate[i] along the level's own field, totalRate[i] along the whole field,
// and weights weight[i] (atol + rtol |q_i|: |rate| / weight[i] tolerances per unit time), quantity
// i turns with the level where both relative rates |rate| tol / weight[i] (tol the larger of rtol
// and atol: about |dq/dt| / (1 + |q|)) exceed minRate (a multiple of the slower level's spectral
// radius: a quantity slaved to the slow ones moves at their rates; and one that the level's splits
// move fast but the other splits move back, an invariant of the whole oscillation written across
// splits, does not turn), and then swings by at least |totalRate[i]| / (weight[i] fastestRadius)
// tolerances (no frequency exceeds the fastest level's spectral radius). Returns the sum of the
// squares of those swings (0: none), for the weighted norm's RMS.
double fastSwingSquares(const std::vector<double> &levelRate, const std::vector<double> &totalRate, const std::vector<double> &weight, double tol, double minRate, double fastestRadius);

} // namespace vshmm
