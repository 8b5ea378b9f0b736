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

namespace {

double productOfRatios(const AdaptParameters &p)
{
  double R = 1.0;
  for (double r : p.ratios) R *= r;
  return R;
}

// dt^order / prod r_l: the micro-step term per unit coefficient (the fast scale's error per
// micro step, dt^(order+1), times the number of cycles, DeltaT / (dt prod r_l)).
double microUnit(const AdaptParameters &p, int order)
{
  return std::pow(p.microStep, order) / productOfRatios(p);
}

} // namespace

AdaptParameters coarsened(const AdaptParameters &p, int which, double factor)
{
  AdaptParameters q = p;
  if (which == 0) q.microStep *= factor;
  else q.ratios[which - 1] = 1.0 + factor * (q.ratios[which - 1] - 1.0);
  return q;
}

AdaptParameters termsScaled(const AdaptParameters &p, double factor, int order)
{
  AdaptParameters q = p;
  for (double &r : q.ratios) r = 1.0 + factor * (r - 1.0);
  q.microStep *= std::pow(factor * productOfRatios(q) / productOfRatios(p), 1.0 / order);
  return q;
}

double errorFromTwoComparisons(double d1, double f1, double d2, double f2, double *kappa, double kappaMin, double kappaMax)
{
  // (f2^k - 1) / (f1^k - 1) grows with k (from ln f2 / ln f1 at k = 0): bisection on log k
  const auto   ratio  = [&](double k) { return std::expm1(k * std::log(f2)) / std::expm1(k * std::log(f1)); };
  const double target = d2 / d1;
  double       k;
  if (target <= ratio(kappaMin)) k = kappaMin;
  else if (target >= ratio(kappaMax)) k = kappaMax;
  else {
    double lo = std::log(kappaMin), hi = std::log(kappaMax);
    for (int it = 0; it < 80; ++it) {
      const double mid                          = 0.5 * (lo + hi);
      (ratio(std::exp(mid)) < target ? lo : hi) = mid;
    }
    k = std::exp(0.5 * (lo + hi));
  }
  if (kappa) *kappa = k;
  return d2 / std::expm1(k * std::log(f2));
}

void limitWorkChange(AdaptParameters &next, const AdaptParameters &now, double maxCheaper, double maxDearer)
{
  // log changes of the cycle length's factors: > 0 coarsens (cheaper), < 0 refines
  const int           K = (int)now.ratios.size();
  std::vector<double> c(K + 1);
  c[0] = std::log(next.microStep / now.microStep);
  for (int l = 0; l < K; ++l) c[1 + l] = std::log(next.ratios[l] / now.ratios[l]);
  double coarser = 0.0, finer = 0.0;
  for (double x : c) (x > 0 ? coarser : finer) += x;
  // too cheap: shorten the coarsening changes only; too dear: the refining ones only
  double fc = 1.0, ff = 1.0;
  if (coarser + finer > std::log(maxCheaper) && coarser > 0) fc = std::max(0.0, (std::log(maxCheaper) - finer) / coarser);
  if (coarser + finer < -std::log(maxDearer) && finer < 0) ff = std::max(0.0, (-std::log(maxDearer) - coarser) / finer);
  if (fc >= 1.0 && ff >= 1.0) return;
  auto f         = [&](double x) { return x > 0 ? std::min(fc, 1.0) * x : std::min(ff, 1.0) * x; };
  next.microStep = now.microStep * std::exp(f(c[0]));
  for (int l = 0; l < K; ++l) next.ratios[l] = now.ratios[l] * std::exp(f(c[1 + l]));
}

double pairUnit(double x, double s)
{
  return (s > 0 && std::isfinite(s)) ? x / (1.0 + x / s) : x;
}

double pairUnitInverse(double u, double s)
{
  if (!(s > 0 && std::isfinite(s))) return u;
  return u < s ? u / (1.0 - u / s) : std::numeric_limits<double>::infinity();
}

std::vector<double> layerSaturations(const AdaptParameters &p, double macroStep, const std::vector<double> &rate)
{
  const int           K = (int)p.ratios.size();
  std::vector<double> s(K, 0.0);
  double              slowed = 1.0; // r_0 ... r_{l-1}
  for (int l = 0; l < K; ++l) {
    const double r = l + 1 < (int)rate.size() ? rate[l + 1] : 0.0;
    if (r > 0 && std::isfinite(r)) s[l] = macroStep * r / slowed;
    slowed *= p.ratios[l];
  }
  return s;
}

double ErrorModel::unit(const AdaptParameters &p, int l) const
{
  return pairUnit(p.ratios[l] - 1.0, l < (int)saturation.size() ? saturation[l] : 0.0);
}

ErrorModel ErrorModel::fromDifferences(const AdaptParameters &p, const std::vector<AdaptParameters> &coarse, const std::vector<double> &d, int order, const std::vector<double> &saturation)
{
  ErrorModel m;
  m.order      = order;
  m.saturation = saturation;
  // a parameter coarsened by less than 10% is taken as not measurable (its coefficient 0)
  const double u = microUnit(coarse[0], order) - microUnit(p, order);
  // a finer micro step (the coarser one unstable) measures the term from the other side
  m.cMicro = coarse[0].microStep > 1.1 * p.microStep ? d[0] / u : coarse[0].microStep < p.microStep / 1.1 ? d[0] / -u : 0.0;
  m.c.resize(p.ratios.size());
  for (size_t l = 0; l < p.ratios.size(); ++l) {
    const double x = coarse[1 + l].ratios[l] - p.ratios[l], v = m.unit(coarse[1 + l], (int)l) - m.unit(p, (int)l);
    m.c[l] = x > 0 && x > 0.1 * (p.ratios[l] - 1.0) && v > 0 ? d[1 + l] / v : 0.0;
  }
  return m;
}

ErrorModel ErrorModel::equalShares(const AdaptParameters &p, int order, double total, const std::vector<double> &saturation)
{
  ErrorModel m;
  m.order      = order;
  m.saturation = saturation;
  m.c.assign(p.ratios.size(), 0.0);
  int n = 0;
  for (double r : p.ratios) n += r > 1.0 ? 1 : 0;
  const double w = total / (n + 1.0 / (order + 1));
  m.cMicro       = p.microStep > 0 ? w / (order + 1) / microUnit(p, order) : 0.0;
  for (size_t l = 0; l < p.ratios.size(); ++l)
    if (p.ratios[l] > 1.0) m.c[l] = w / m.unit(p, (int)l);
  return m;
}

void ErrorModel::floorShares(const AdaptParameters &p, double fraction)
{
  const double before = total(p);
  if (!(before > 0)) return;
  if (p.microStep > 0) cMicro = std::max(cMicro, fraction * before / microUnit(p, order));
  for (size_t l = 0; l < c.size(); ++l)
    if (p.ratios[l] > 1.0) c[l] = std::max(c[l], fraction * before / unit(p, (int)l));
  scale(before / total(p));
}

double ErrorModel::term(const AdaptParameters &p, int which) const
{
  if (which == 0) return cMicro * microUnit(p, order);
  return c[which - 1] * unit(p, which - 1);
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

double clampTo(double x, double lo, double hi)
{
  return std::min(std::max(x, lo), hi);
}

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

  // Equal shares w for the free ratios and w / (order + 1) for the micro step (the least-work
  // split when e_dt = c dt^order / prod r_l); a parameter that hits its range keeps its own error
  // and the others share the rest (a few passes settle it). The ratios first: the micro step's
  // term depends on them.
  std::vector<bool> pinned(K + 1, false);
  pinned[0] = bounds.fixedMicroStep;
  for (int l = 0; l < K; ++l) pinned[1 + l] = bounds.fixedRatios;
  for (int pass = 0; pass < K + 2; ++pass) {
    double used = 0.0, weights = 0.0;
    for (int i = 0; i <= K; ++i) {
      if (pinned[i]) used += model.term(next, i);
      else weights += i == 0 ? 1.0 / (model.order + 1) : 1.0;
    }
    if (weights == 0.0) break;
    const double budget = std::max(target - used, 0.05 * target);
    const double w      = budget / weights;
    bool         again  = false;
    for (int l = 0; l < K; ++l) {
      if (pinned[1 + l]) continue;
      double r = model.c[l] > 0 ? 1.0 + pairUnitInverse(w / model.c[l], l < (int)model.saturation.size() ? model.saturation[l] : 0.0) : rHi[l];
      if (r <= rLo[l] || r >= rHi[l]) {
        pinned[1 + l] = again = true;
        r                     = clampTo(r, rLo[l], rHi[l]);
      }
      next.ratios[l] = r;
    }
    if (!pinned[0]) {
      const double share = w / (model.order + 1);
      double       dt    = model.cMicro > 0 ? std::pow(share * productOfRatios(next) / model.cMicro, 1.0 / model.order) : dtHi;
      if (dt <= dtLo || dt >= dtHi) {
        pinned[0] = again = true;
        dt                = clampTo(dt, dtLo, dtHi);
      }
      next.microStep = dt;
    }
    if (!again) break;
  }

  if (bounds.maxCycle > 0) fitCycle(next, bounds.maxCycle, bounds.fixedRatios, bounds.fixedMicroStep);
  return next;
}

double workRate(const AdaptParameters &p, const std::vector<double> &levelCost)
{
  const std::size_t K = p.ratios.size();
  if (levelCost.size() != K + 1) return std::numeric_limits<double>::quiet_NaN();
  double cost = levelCost[K];
  for (std::size_t l = 0; l < K; ++l)
    if (p.ratios[l] > 1.0) cost += levelCost[l];
  return cost / cycleLength(p);
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

double fastSwingSquares(const std::vector<double> &levelRate, const std::vector<double> &totalRate, const std::vector<double> &weight, double tol, double minRate, double fastestRadius)
{
  double sum = 0.0;
  if (!(fastestRadius > 0) || !(tol > 0)) return 0.0;
  for (size_t i = 0; i < levelRate.size() && i < totalRate.size() && i < weight.size(); ++i) {
    if (!(weight[i] > 0) || !std::isfinite(levelRate[i]) || !std::isfinite(totalRate[i])) continue;
    const double own = std::fabs(levelRate[i]) / weight[i], total = std::fabs(totalRate[i]) / weight[i]; /* tolerances per unit time */
    if (!(own * tol > minRate) || !(total * tol > minRate)) continue;
    const double swing = total / fastestRadius;
    sum += swing * swing;
  }
  return sum;
}

} // namespace vshmm
