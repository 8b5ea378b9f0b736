#include "adapt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vshmm {

std::vector<double> timeRatiosFromSavings(const std::vector<double> &savings)
{
  const int           K = (int)savings.size();
  std::vector<double> r(K);
  double              faster = 1.0; // A_{l+1} / dt = 1 + alpha_{l+2} + ... + alpha_K
  for (int l = K - 1; l >= 0; --l) {
    const double here = faster + savings[l]; // A_l / dt
    r[l]              = here / faster;
    faster            = here;
  }
  return r;
}

std::vector<double> savingsFromTimeRatios(const std::vector<double> &ratios)
{
  const int           K = (int)ratios.size();
  std::vector<double> alpha(K);
  double              faster = 1.0; // prod_{j>l} r_j
  for (int l = K - 1; l >= 0; --l) {
    alpha[l] = (ratios[l] - 1.0) * faster;
    faster *= ratios[l];
  }
  return alpha;
}

double cycleLength(const AdaptParameters &p)
{
  double a = p.microStep;
  for (double r : p.ratios) a *= r;
  return a;
}

AdaptParameters coarsened(const AdaptParameters &p, int which)
{
  AdaptParameters q = p;
  if (which == 0) q.microStep *= 2.0;
  else q.ratios[which - 1] *= 2.0;
  return q;
}

ErrorModel ErrorModel::fromDifferences(const AdaptParameters &p, const std::vector<AdaptParameters> &coarse, const std::vector<double> &d, int order)
{
  ErrorModel m;
  m.order        = order;
  // a parameter coarsened by less than 10% is taken as not measurable (its coefficient 0)
  const double u = std::pow(coarse[0].microStep, order) - std::pow(p.microStep, order);
  m.cMicro       = coarse[0].microStep > 1.1 * p.microStep ? d[0] / u : 0.0;
  m.c.resize(p.ratios.size());
  for (size_t l = 0; l < p.ratios.size(); ++l) {
    const double v = coarse[1 + l].ratios[l] - p.ratios[l];
    m.c[l]         = v > 0.1 * p.ratios[l] ? d[1 + l] / v : 0.0;
  }
  return m;
}

double ErrorModel::term(const AdaptParameters &p, int which) const
{
  if (which == 0) return cMicro * std::pow(p.microStep, order);
  return c[which - 1] * (p.ratios[which - 1] - 1.0);
}

double ErrorModel::total(const AdaptParameters &p) const
{
  double e = 0.0;
  for (int i = 0; i <= (int)c.size(); ++i) e += term(p, i);
  return e;
}

void ErrorModel::scale(double f)
{
  cMicro *= f;
  for (double &x : c) x *= f;
}

namespace {

double clampTo(double x, double lo, double hi) { return std::min(std::max(x, lo), hi); }

} // namespace

AdaptParameters chooseParameters(const AdaptParameters &now, const ErrorModel &model, double target, const AdaptBounds &bounds)
{
  const int       K    = (int)now.ratios.size();
  const double    G    = bounds.maxGrowth;
  const double    inf  = std::numeric_limits<double>::infinity();
  AdaptParameters next = now;

  // Ranges each free parameter may take in this choice.
  double dtLo = now.microStep, dtHi = now.microStep;
  if (!bounds.fixedMicroStep) {
    dtLo = now.microStep / bounds.maxRefine;
    dtHi = std::min(now.microStep * G, bounds.maxMicroStep > 0 ? bounds.maxMicroStep : inf);
    dtLo = std::min(dtLo, dtHi);
  }
  std::vector<double> rLo(K), rHi(K);
  for (int l = 0; l < K; ++l) {
    const double r = now.ratios[l];
    if (bounds.fixedRatios) {
      rLo[l] = rHi[l] = r;
      continue;
    }
    const double rmax = l < (int)bounds.maxRatio.size() ? std::max(1.0, bounds.maxRatio[l]) : inf;
    rLo[l]            = 1.0 + (r - 1.0) / bounds.maxRefine;
    rHi[l]            = std::min(std::max(r * G, 1.0 + G), rmax);
    rLo[l]            = std::min(rLo[l], rHi[l]);
  }

  // Equal shares w for the free ratios and w / order for the micro step; a parameter that hits
  // its range keeps its own error and the others share the rest (a few passes settle it).
  std::vector<bool> pinned(K + 1, false);
  pinned[0] = bounds.fixedMicroStep;
  for (int l = 0; l < K; ++l) pinned[1 + l] = bounds.fixedRatios;
  for (int pass = 0; pass < K + 2; ++pass) {
    double used = 0.0, weights = 0.0;
    for (int i = 0; i <= K; ++i) {
      if (pinned[i]) used += model.term(next, i);
      else weights += i == 0 ? 1.0 / model.order : 1.0;
    }
    if (weights == 0.0) break;
    const double budget = std::max(target - used, 0.05 * target);
    const double w      = budget / weights;
    bool         again  = false;
    if (!pinned[0]) {
      const double share = w / model.order;
      double       dt    = model.cMicro > 0 ? std::pow(share / model.cMicro, 1.0 / model.order) : dtHi;
      if (dt <= dtLo || dt >= dtHi) {
        pinned[0] = again = true;
        dt                = clampTo(dt, dtLo, dtHi);
      }
      next.microStep = dt;
    }
    for (int l = 0; l < K; ++l) {
      if (pinned[1 + l]) continue;
      double r = model.c[l] > 0 ? 1.0 + w / model.c[l] : rHi[l];
      if (r <= rLo[l] || r >= rHi[l]) {
        pinned[1 + l] = again = true;
        r                     = clampTo(r, rLo[l], rHi[l]);
      }
      next.ratios[l] = r;
    }
    if (!again) break;
  }

  if (bounds.maxCycle > 0) fitCycle(next, bounds.maxCycle, bounds.fixedRatios, bounds.fixedMicroStep);
  return next;
}

void fitCycle(AdaptParameters &p, double maxCycle, bool fixedRatios, bool fixedMicroStep)
{
  const int K = (int)p.ratios.size();
  if (cycleLength(p) > maxCycle && !fixedRatios) {
    const std::vector<double> r0 = p.ratios;
    double                    lo = 0.0, hi = 1.0;
    for (int it = 0; it < 60; ++it) {
      const double f = 0.5 * (lo + hi);
      for (int l = 0; l < K; ++l) p.ratios[l] = 1.0 + f * (r0[l] - 1.0);
      (cycleLength(p) <= maxCycle ? lo : hi) = f;
    }
    for (int l = 0; l < K; ++l) p.ratios[l] = 1.0 + lo * (r0[l] - 1.0);
  }
  if (cycleLength(p) > maxCycle && !fixedMicroStep) p.microStep *= maxCycle / cycleLength(p);
}

void limitToStableSteps(AdaptParameters &p, double kernelPeak, const std::vector<double> &maxLevelStep)
{
  const int K = (int)p.ratios.size();
  if ((int)maxLevelStep.size() > K && std::isfinite(maxLevelStep[K])) p.microStep = std::min(p.microStep, maxLevelStep[K]);
  double faster = 1.0; // prod_{j>l} r_j
  for (int l = K - 1; l >= 0; --l) {
    if (std::isfinite(maxLevelStep[l])) p.ratios[l] = std::max(1.0, std::min(p.ratios[l], 1.0 + maxLevelStep[l] / (p.microStep * kernelPeak * faster)));
    faster *= p.ratios[l];
  }
}

} // namespace vshmm
