#include "stability.hpp"

#include <cmath>
#include <algorithm>
#include <limits>

namespace vshmm {

StabilityFunction::StabilityFunction(const Tableau &tableau) : a_(tableau.a), b_(tableau.b), s_(tableau.stages)
{
  // R(z) = 1 + sum_{k>=1} gamma_k z^k with gamma_k = b^T A^(k-1) 1 (A strictly lower: k <= s).
  std::vector<double> v(s_, 1.0), w(s_);
  lipschitz_.assign(s_ + 1, 0.0);
  for (int k = 1; k <= s_; ++k) {
    double gamma = 0;
    for (int i = 0; i < s_; ++i) gamma += b_[i] * v[i];
    lipschitz_[k] = k * std::fabs(gamma);
    for (int i = 0; i < s_; ++i) {
      w[i] = 0;
      for (int j = 0; j < i; ++j) w[i] += a_[i * s_ + j] * v[j];
    }
    v.swap(w);
  }
}

double StabilityFunction::derivativeBound(double r) const
{
  double L = 0, p = 1;
  for (size_t k = 1; k < lipschitz_.size(); ++k, p *= r) L += lipschitz_[k] * p;
  return L;
}

std::complex<double> StabilityFunction::operator()(std::complex<double> z) const
{
  // Stage values for y' = y with step z: Y_i = 1 + z sum_{j<i} a_ij Y_j; R = 1 + z sum b_i Y_i.
  std::complex<double> Y[Tableau::kMaxStages], R = 1.0;
  for (int i = 0; i < s_; ++i) {
    std::complex<double> sum = 0.0;
    for (int j = 0; j < i; ++j) sum += a_[i * s_ + j] * Y[j];
    Y[i] = 1.0 + z * sum;
    R += z * b_[i] * Y[i];
  }
  return R;
}

double StabilityFunction::rayLimit(std::complex<double> direction) const
{
  const std::complex<double> d   = direction / std::abs(direction);
  const double               tol = 1e-12;
  // A step is stable for the mode when it grows the mode no more than the exact flow does:
  // |R(z)| <= max(1, |exp(z)|). For Re z <= 0 that is the usual |R(z)| <= 1; a growing mode
  // (Re z > 0, e.g. a slightly unstable oscillation) may grow by its own exp(Re z).
  auto stable = [&](double x) { return std::abs((*this)(x * d)) <= (d.real() > 0 ? std::max(1.0, std::exp(x * d.real())) : 1.0) * (1.0 + tol); };
  // Scan outwards in steps small against the size of any stability region of an explicit method,
  // then bisect the first crossing. Where |R| is below the bound by a margin m, |R| cannot reach
  // it within m / L (L bounds |R'| on the next unit of the ray; the bound is at least 1):
  // such a step is taken at once, so only the approach to the crossing costs fine steps.
  const double dx = 1e-3;
  double       x  = 0.0;
  while (x < kMaxRadius) {
    const double margin = 1.0 - std::abs((*this)(x * d)); // the bound is at least 1
    const double leap   = margin > 0 ? std::min(1.0, margin / derivativeBound(x + 1.0)) : 0.0;
    if (leap > dx) {
      x = std::min(x + leap, kMaxRadius);
      continue;
    }
    if (!stable(x + dx)) break;
    x += dx;
  }
  if (x >= kMaxRadius) return kMaxRadius;
  double lo = x, hi = x + dx;
  for (int it = 0; it < 60; ++it) {
    const double mid        = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

double StabilityFunction::largestStableStep(std::complex<double> lambda) const
{
  const double r = std::abs(lambda);
  if (r == 0.0) return std::numeric_limits<double>::infinity();
  return rayLimit(lambda) / r;
}

LevelAmplification levelAmplification(const StabilityFunction &R, const MesoscopicSchedule &schedule, double macroStep, int level, std::complex<double> lambda)
{
  LevelAmplification a;
  runMacroStep(schedule, macroStep, [&](int l, double, double h) {
    if (l == level) {
      a.logAmplification += std::log(std::abs(R(h * lambda))) - h * std::max(lambda.real(), 0.0);
      a.largestGrowth = std::max(a.largestGrowth, a.logAmplification);
      a.steps++;
      a.largestStep = std::max(a.largestStep, h);
    }
    return 0;
  });
  return a;
}

double largestStableSavingsFactor(const StabilityFunction &R, const Kernel &kernel, double microStep, std::vector<double> savings, const std::vector<int> &subintervals, double macroStep, int j, std::complex<double> lambda, double dampingTarget, double maxGrowth)
{
  double lo = 0, hi = savings.at(j - 1);
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    savings[j - 1]   = mid;
    const MesoscopicSchedule schedule(kernel, microStep, savings, subintervals);
    const LevelAmplification a                                                                          = levelAmplification(R, schedule, macroStep, j - 1, lambda);
    (a.logAmplification <= std::log(dampingTarget) && a.largestGrowth <= std::log(maxGrowth) ? lo : hi) = mid;
  }
  return lo;
}

} // namespace vshmm
