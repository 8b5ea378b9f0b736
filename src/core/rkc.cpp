#include "rkc.hpp"

#include <cmath>
#include <stdexcept>

namespace vshmm {

namespace {
constexpr double kDamping   = 2.0 / 13.0; // epsilon of RKC: |R| <= 1 - epsilon / 3 or so inside the interval
constexpr int    kRayPoints = 256;
constexpr double kGrowing   = 0.1; // stableFor's default
} // namespace

ChebyshevRK2::ChebyshevRK2(int stages) : s_(stages)
{
  if (stages < 2) throw std::invalid_argument("RKC needs at least 2 stages");
  const int s = stages;
  w0_         = 1.0 + kDamping / ((double)s * s);
  // T_j, T_j', T_j'' at w0 by the three-term recurrence
  std::vector<double> T(s + 1), dT(s + 1), ddT(s + 1);
  T[0] = 1, dT[0] = 0, ddT[0] = 0;
  T[1] = w0_, dT[1] = 1, ddT[1] = 0;
  for (int j = 2; j <= s; ++j) {
    T[j]   = 2 * w0_ * T[j - 1] - T[j - 2];
    dT[j]  = 2 * T[j - 1] + 2 * w0_ * dT[j - 1] - dT[j - 2];
    ddT[j] = 4 * dT[j - 1] + 2 * w0_ * ddT[j - 1] - ddT[j - 2];
  }
  w1_ = dT[s] / ddT[s];
  b_.assign(s + 1, 0.0);
  for (int j = 2; j <= s; ++j) b_[j] = ddT[j] / (dT[j] * dT[j]);
  b_[0] = b_[1] = b_[2];
  Tw_           = T;
}

std::complex<double> ChebyshevRK2::operator()(std::complex<double> z) const
{
  const std::complex<double> x  = w0_ + w1_ * z;
  std::complex<double>       t0 = 1.0, t1 = x;
  for (int j = 2; j <= s_; ++j) {
    const std::complex<double> t2 = 2.0 * x * t1 - t0;
    t0                            = t1;
    t1                            = t2;
  }
  const double as = 1.0 - b_[s_] * Tw_[s_];
  return as + b_[s_] * t1;
}

bool ChebyshevRK2::stableFor(double h, const std::vector<std::complex<double>> &lambdas, double growing) const
{
  for (const std::complex<double> &lambda : lambdas) {
    if (std::abs(lambda) == 0 || lambda.real() > growing * std::abs(lambda)) continue;
    for (int i = 1; i <= kRayPoints; ++i)
      if (!(std::abs((*this)(h * lambda * ((double)i / kRayPoints))) <= 1.0)) return false;
  }
  return true;
}

int ChebyshevRK2::stagesFor(double h, const std::vector<std::complex<double>> &lambdas, int maxStages)
{
  double rho = 0;
  for (const std::complex<double> &lambda : lambdas)
    if (!(lambda.real() > kGrowing * std::abs(lambda))) rho = std::max(rho, std::abs(lambda));
  // beta(s) is about 0.65 s^2: start the search a little below the real-axis estimate
  int s = std::max(2, (int)std::floor(std::sqrt(h * rho / 0.7)));
  for (; s <= maxStages; ++s)
    if (ChebyshevRK2(s).stableFor(h, lambdas, kGrowing)) return s;
  return 0;
}

void ChebyshevRK2::step(const std::function<void(const double *, double *)> &F, double h, std::vector<double> &y, std::vector<double> &work) const
{
  const size_t n = y.size();
  if (work.size() < 5 * n) work.resize(5 * n);
  double *y0 = work.data(), *f0 = y0 + n, *ym2 = f0 + n, *ym1 = ym2 + n, *f = ym1 + n;
  for (size_t i = 0; i < n; ++i) y0[i] = y[i];
  F(y0, f0);
  const double mt1 = b_[1] * w1_; // mu~_1
  for (size_t i = 0; i < n; ++i) ym2[i] = y0[i], ym1[i] = y0[i] + mt1 * h * f0[i];
  for (int j = 2; j <= s_; ++j) {
    F(ym1, f);
    const double mu = 2 * b_[j] * w0_ / b_[j - 1], nu = -b_[j] / b_[j - 2];
    const double mt = 2 * b_[j] * w1_ / b_[j - 1], gt = -(1.0 - b_[j - 1] * Tw_[j - 1]) * mt;
    for (size_t i = 0; i < n; ++i) {
      const double yj = (1 - mu - nu) * y0[i] + mu * ym1[i] + nu * ym2[i] + mt * h * f[i] + gt * h * f0[i];
      ym2[i]          = ym1[i];
      ym1[i]          = yj;
    }
  }
  for (size_t i = 0; i < n; ++i) y[i] = ym1[i];
}

} // namespace vshmm
