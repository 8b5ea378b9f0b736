#include "coupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vshmm {

namespace {

std::vector<double> multiply(const std::vector<double> &A, const std::vector<double> &B, int n)
{
  std::vector<double> C((size_t)n * n, 0.0);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      const double b = B[k + (size_t)j * n];
      if (b == 0.0) continue;
      for (int i = 0; i < n; ++i) C[i + (size_t)j * n] += A[i + (size_t)k * n] * b;
    }
  return C;
}

double frobenius(const std::vector<double> &A)
{
  double s = 0.0;
  for (double a : A) s += a * a;
  return std::sqrt(s);
}

} // namespace

double logSpectralRadius(std::vector<double> A, int n)
{
  // ||A^(2^p)||^(1/2^p) -> rho(A); a non-normal A (an oscillation in unscaled variables) has
  // ||A^k|| <= C rho^k with C up to the condition number of its eigenvectors, whose share
  // log C / 2^p is negligible after 40 squarings.
  double nrm = frobenius(A);
  if (!(nrm > 0.0)) return -std::numeric_limits<double>::infinity();
  if (!std::isfinite(nrm)) return std::numeric_limits<double>::infinity();
  for (double &a : A) a /= nrm;
  double    L = std::log(nrm), scale = 1.0;
  const int squarings = 40;
  for (int p = 0; p < squarings; ++p) {
    A   = multiply(A, A, n);
    nrm = frobenius(A);
    if (!(nrm > 0.0)) return -std::numeric_limits<double>::infinity();
    for (double &a : A) a /= nrm;
    scale *= 0.5;
    L += scale * std::log(nrm); // log ||A^(2^(p+1))|| / 2^(p+1), accumulated
  }
  return L;
}

std::vector<double> stepMatrix(const Tableau &tableau, double h, const std::vector<double> &J, int n)
{
  const int                        s = tableau.stages;
  std::vector<std::vector<double>> K(s);
  std::vector<double>              R((size_t)n * n, 0.0), Y;
  for (int i = 0; i < n; ++i) R[i + (size_t)i * n] = 1.0;
  for (int i = 0; i < s; ++i) {
    Y.assign((size_t)n * n, 0.0);
    for (int d = 0; d < n; ++d) Y[d + (size_t)d * n] = 1.0;
    for (int j = 0; j < i; ++j) {
      const double w = h * tableau.a[i * s + j];
      if (w != 0.0)
        for (size_t e = 0; e < Y.size(); ++e) Y[e] += w * K[j][e];
    }
    K[i]           = multiply(J, Y, n);
    const double w = h * tableau.b[i];
    for (size_t e = 0; e < R.size(); ++e) R[e] += w * K[i][e];
  }
  return R;
}

CouplingGrowth couplingGrowth(const Tableau &tableau, const CoupledLevels &levels, const MesoscopicSchedule &schedule, double macroStep, long maxSteps)
{
  const int      top = schedule.numScales() - 1, n = levels.n;
  CouplingGrowth g;
  if (n == 0 || top == 0) return g;
  // The linearised macro step: the product of every step's R(h J_level) in order, renormalised
  // as it goes (its log norm kept apart), and each level's own product (its steps commute).
  auto identity = [n]() {
    std::vector<double> I((size_t)n * n, 0.0);
    for (int i = 0; i < n; ++i) I[i + (size_t)i * n] = 1.0;
    return I;
  };
  std::vector<double>              P = identity();
  std::vector<std::vector<double>> own(top + 1, identity());
  std::vector<double>              ownLog(top + 1, 0.0);
  double                           logP  = 0.0;
  long                             taken = 0;
  MacroStepCounts                  counts;
  runMacroStep(
    schedule, macroStep,
    [&](int level, double, double h) {
      if (taken >= maxSteps) return 0; // the rest is only counted
      taken++;
      const std::vector<double> S = stepMatrix(tableau, h, levels.jacobian[level], n);
      P                           = multiply(S, P, n);
      own[level]                  = multiply(S, own[level], n);
      for (auto *M : {&P, &own[level]}) {
        const double nrm = frobenius(*M);
        if (nrm > 1e100 || (nrm > 0.0 && nrm < 1e-100)) {
          for (double &x : *M) x /= nrm;
          (M == &P ? logP : ownLog[level]) += std::log(nrm);
        }
      }
      return 0;
    },
    &counts);
  g.cycles = (long)counts.cycles;
  for (auto c : counts.levelSteps) g.steps += (long)c;
  g.extrapolated   = taken < g.steps;
  double ownGrowth = 0.0;
  for (int l = 0; l <= top; ++l) ownGrowth += std::max(0.0, ownLog[l] + logSpectralRadius(own[l], n));
  g.logGrowth = std::max(0.0, logP + logSpectralRadius(P, n) - ownGrowth);
  if (g.extrapolated && taken > 0) g.logGrowth *= (double)g.steps / (double)taken;
  return g;
}

double largestCouplingStableScaling(const Tableau &tableau, const CoupledLevels &levels, const Kernel &kernel, double microStep, const std::vector<double> &savings, const std::vector<int> &subintervals, double macroStep, double maxLogGrowth, long maxSteps)
{
  // Smaller factors mean more steps per macro step; a value whose macro step needs more than
  // maxSteps steps is not tried (it counts as failing), so that the search stays cheap.
  auto passes = [&](double s) {
    std::vector<double> scaled(savings);
    for (double &a : scaled) a *= s;
    const MesoscopicSchedule schedule(kernel, microStep, scaled, subintervals);
    const CouplingGrowth     g = couplingGrowth(tableau, levels, schedule, macroStep, maxSteps);
    return !g.extrapolated && g.logGrowth <= maxLogGrowth;
  };
  if (passes(1.0)) return 1.0;
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 30; ++it) {
    const double mid        = 0.5 * (lo + hi);
    (passes(mid) ? lo : hi) = mid;
  }
  return lo;
}

} // namespace vshmm
