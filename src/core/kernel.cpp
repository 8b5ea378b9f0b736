#include "kernel.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace vshmm {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Numerical tools

// Gauss-Legendre rule on [-1, 1], computed in long double by Newton's method on P_n.
struct GaussLegendreRule {
  std::vector<long double> nodes, weights;
};

GaussLegendreRule gaussLegendre(int n)
{
  const long double pi = 3.141592653589793238462643383279502884L;
  GaussLegendreRule rule;
  for (int i = 0; i < n; ++i) {
    long double x = std::cos(pi * (i + 0.75L) / (n + 0.5L)), derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      long double previous = 1, legendre = x;
      for (int k = 2; k <= n; ++k) {
        const long double next = ((2 * k - 1) * x * legendre - (k - 1) * previous) / k;
        previous               = legendre;
        legendre               = next;
      }
      derivative           = n * (x * legendre - previous) / (x * x - 1);
      const long double dx = legendre / derivative;
      x -= dx;
      if (std::fabs(dx) <= 2 * LDBL_EPSILON) break;
    }
    rule.nodes.push_back(x);
    rule.weights.push_back(2 / ((1 - x * x) * derivative * derivative));
  }
  return rule;
}

// The root of f on [lo, hi], f increasing with f(lo) <= 0 <= f(hi), by Newton's method from x,
// falling back to bisection whenever a Newton step leaves the bracket. residual(x, slope)
// returns f(x) and sets slope = f'(x).
template <class Residual>
double safeguardedNewton(Residual residual, double x, double lo, double hi)
{
  // After a Newton step d the error is about |f''/2f'| d^2, so once |d| <= 1e-9 |x| it is
  // below an ulp of x wherever |x f''/f'| <= 200: for the polynomial and cosine kernels
  // |x f''/f'| <= 2(q+1); the exponential kernel solves in w = 1/s, where |x f''/f'| ~ w, but
  // there the table starts are within 1e-13 for w > 100.
  constexpr double kSmallStep = 1e-9;
  for (int iteration = 0; iteration < 200; ++iteration) {
    double       slope = 0;
    const double r     = residual(x, slope);
    if (r == 0) return x;
    if (r < 0) lo = x;
    else hi = x;
    const double step = r / slope;
    double       next = x - step;
    if (std::fabs(step) <= kSmallStep * std::fabs(x) && next >= lo && next <= hi) return next;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 2 * DBL_EPSILON * std::fabs(hi)) return next;
    x = next;
  }
  return x;
}

// x^k for k >= 0 by repeated squaring.
double integerPower(double x, int k)
{
  double result = 1;
  for (; k > 0; k >>= 1, x *= x)
    if (k & 1) result *= x;
  return result;
}

// Cubic Hermite interpolation on [x0, x0 + h] at x0 + t h from values f and slopes m.
double hermite(double t, double h, double f0, double m0, double f1, double m1)
{
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * f0 + (t3 - 2 * t2 + t) * h * m0 + (3 * t2 - 2 * t3) * f1 + (t3 - t2) * h * m1;
}

// ---------------------------------------------------------------------------------------------
// Theta^{-1} on [0, 1/2] for kernels with Theta(s) ~ c s^n as s -> 0 (n = q + 2): tabulated
// against y = v^{1/n}, in which s(y) is smooth down to y = 0, so that cubic Hermite
// interpolation gives a Newton start accurate to 1e-10 relative or better (n <= 18), and one
// Newton step reaches machine precision. The callable thetaAndValue(s, k) returns Theta(s) and
// sets k = K(s), for 0 <= s <= 1/2.
class RootTable {
public:
  template <class ThetaAndValue>
  RootTable(int n, double c, ThetaAndValue thetaAndValue);

  // Theta^{-1}(v) for 0 < v < 1/2.
  template <class ThetaAndValue>
  double invert(double v, ThetaAndValue thetaAndValue) const;

private:
  static constexpr int kCells = 1024;

  double              root(double v) const;
  int                 n_;
  double              yStep_;
  std::vector<double> s_, slope_; // s(y_i) and ds/dy(y_i)
};

template <class ThetaAndValue>
RootTable::RootTable(int n, double c, ThetaAndValue thetaAndValue) : n_(n), yStep_(std::pow(0.5, 1.0 / n) / kCells), s_(kCells + 1), slope_(kCells + 1)
{
  s_[0]     = 0;
  slope_[0] = std::pow(c, -1.0 / n);
  for (int i = 1; i <= kCells; ++i) {
    const double y = i * yStep_, v = i == kCells ? 0.5 : std::pow(y, n);
    const auto   residual = [&](double s, double &k) { return thetaAndValue(s, k) - v; };
    s_[i]                 = i == kCells ? 0.5 : safeguardedNewton(residual, std::min(s_[i - 1] + slope_[i - 1] * yStep_, 0.5), s_[i - 1], 0.5);
    double k;
    thetaAndValue(s_[i], k);
    slope_[i] = n * v / (y * k); // ds/dy = (dv/dy) / K
  }
}

double RootTable::root(double v) const
{
  if (n_ == 2) return std::sqrt(v);
  if (n_ == 3) return std::cbrt(v);
  return std::pow(v, 1.0 / n_);
}

template <class ThetaAndValue>
double RootTable::invert(double v, ThetaAndValue thetaAndValue) const
{
  const double y     = root(v);
  const int    cell  = std::min(static_cast<int>(y / yStep_), kCells - 1);
  const double t     = y / yStep_ - cell;
  const double start = hermite(t, yStep_, s_[cell], slope_[cell], s_[cell + 1], slope_[cell + 1]);
  const double lo = s_[std::max(cell - 1, 0)], hi = s_[std::min(cell + 2, kCells)];
  const auto   residual = [&](double s, double &k) { return thetaAndValue(s, k) - v; };
  return safeguardedNewton(residual, std::clamp(start, lo, hi), lo, hi);
}

// A kernel that computes Theta and K together (Derived::thetaAndValue) and inverts Theta from a
// RootTable (Derived::inverse_): the cosine and polynomial kernels.
template <class Derived>
class RootTabulatedKernel : public Kernel {
protected:
  double lowerTheta(double s) const final
  {
    double k;
    return s <= 0 ? 0.0 : self().thetaAndValue(s, k);
  }
  double lowerThetaInverse(double v) const final
  {
    if (!(v > 0)) return 0;
    if (v >= 0.5) return 0.5;
    return self().inverse_.invert(v, [this](double s, double &k) { return self().thetaAndValue(s, k); });
  }

private:
  const Derived &self() const { return static_cast<const Derived &>(*this); }
};

// ---------------------------------------------------------------------------------------------
// Cosine kernel K(s) = 1 - cos(2 pi s) = 2 sin^2(pi s), Theta(s) = (x - sin x) / (2 pi), x = 2 pi s.

class CosineKernel final : public RootTabulatedKernel<CosineKernel> {
public:
  CosineKernel() : inverse_(3, 2 * kPi * kPi / 3, thetaAndValue) {}
  std::string name() const override { return "cosine"; }
  int         order() const override { return 1; }
  double      value(double s) const override
  {
    if (s <= 0 || s >= 1) return 0;
    const double sine = std::sin(kPi * std::min(s, 1 - s));
    return 2 * sine * sine;
  }

private:
  friend class RootTabulatedKernel<CosineKernel>;
  static double thetaAndValue(double s, double &k);

  RootTable inverse_;
};

// (-1)^k / (2k + 3)!, k = 0..10: the Taylor coefficients of (x - sin x) / x^3.
constexpr std::array<double, 11> sineRemainderSeries()
{
  std::array<double, 11> coefficients{};
  double                 factorial = 6;
  for (int k = 0; k < 11; ++k) {
    coefficients[k] = (k % 2 ? -1 : 1) / factorial;
    factorial *= (2 * k + 4) * (2 * k + 5);
  }
  return coefficients;
}

double CosineKernel::thetaAndValue(double s, double &k)
{
  const double x = 2 * kPi * s;
  // Below this x, x - sin x and 1 - cos x cancel: Theta comes from the Taylor series of x - sin x
  // (11 terms reach machine precision: x^22 / 25! < 1e-19 x^3 / 6) and K = 2 sin^2(x/2).
  constexpr double kSeriesLimit = 1.5;
  if (x >= kSeriesLimit) {
    k = 1 - std::cos(x);
    return s - std::sin(x) / (2 * kPi);
  }
  const double sine                              = std::sin(kPi * s);
  k                                              = 2 * sine * sine;
  static constexpr std::array<double, 11> series = sineRemainderSeries();
  const double                            x2     = x * x;
  double                                  sum    = 0;
  for (int i = 10; i >= 0; --i) sum = sum * x2 + series[i];
  return s * x2 * sum; // x^3 / (2 pi) = s x^2
}

// ---------------------------------------------------------------------------------------------
// Polynomial kernel K(s) = s^{q+1} (1-s)^{q+1} / B(n, n), n = q + 2. Theta is the regularized
// incomplete beta function I_s(n, n) = sum_{j=n}^{2n-1} C(2n-1, j) s^j (1-s)^{2n-1-j}, a sum of
// positive terms, evaluated as s (s(1-s))^{n-1} sum_{i<n} C(2n-1, n+i) r^i with r = s/(1-s) <= 1.

class PolynomialKernel final : public RootTabulatedKernel<PolynomialKernel> {
public:
  explicit PolynomialKernel(int order);
  std::string name() const override { return "polynomial"; }
  int         order() const override { return n_ - 2; }
  double      value(double s) const override
  {
    if (s <= 0 || s >= 1) return 0;
    const double t = std::min(s, 1 - s);
    return integerPower(t * (1 - t), n_ - 1) * inverseBeta_;
  }

private:
  friend class RootTabulatedKernel<PolynomialKernel>;
  double                     thetaAndValue(double s, double &k) const;
  static std::vector<double> binomialTail(int n);

  int                 n_;
  std::vector<double> binomials_;   // C(2n-1, n+i), i = 0..n-1
  double              inverseBeta_; // 1 / B(n, n) = n C(2n-1, n)
  RootTable           inverse_;
};

std::vector<double> PolynomialKernel::binomialTail(int n)
{
  std::vector<double> tail;
  std::uint64_t       binomial = 1; // C(2n-1, j), exact in 64 bits for n <= 18
  for (int j = 0; j <= 2 * n - 1; ++j) {
    if (j >= n) tail.push_back(static_cast<double>(binomial));
    binomial = binomial * static_cast<std::uint64_t>(2 * n - 1 - j) / static_cast<std::uint64_t>(j + 1);
  }
  return tail;
}

PolynomialKernel::PolynomialKernel(int order) : n_(order + 2), binomials_(binomialTail(n_)), inverseBeta_(n_ * binomials_[0]), inverse_(n_, binomials_[0], [this](double s, double &k) { return thetaAndValue(s, k); }) {}

double PolynomialKernel::thetaAndValue(double s, double &k) const
{
  const double complement = 1 - s, r = s / complement, power = integerPower(s * complement, n_ - 1);
  double       sum = 0;
  for (int i = n_ - 1; i >= 0; --i) sum = sum * r + binomials_[i];
  k = power * inverseBeta_;
  return s * power * sum;
}

// ---------------------------------------------------------------------------------------------
// Constant kernel K = 1: Theta(s) = s.

class ConstantKernel final : public Kernel {
public:
  std::string name() const override { return "constant"; }
  int         order() const override { return -1; }
  double      value(double s) const override { return s < 0 || s > 1 ? 0.0 : 1.0; }

protected:
  double lowerTheta(double s) const override { return std::max(s, 0.0); }
  double lowerThetaInverse(double v) const override { return std::clamp(v, 0.0, 0.5); }
};

// ---------------------------------------------------------------------------------------------
// Exponential kernel K(s) = exp(-1/(s(1-s))) / Z. With w = 1/s, for s <= 1/2:
//   Theta(s) = int_{1/s}^inf g(w) dw,  g(w) = exp(-(w + 1 + 1/(w-1))) / (w^2 Z),
// an integrand that decays like exp(-w) with no fast scale, so a table in w with local
// Gauss-Legendre integrals is accurate relative to Theta down to the smallest normal double
// (s ~ 1/690). The table also gives the start for inverting Theta.

class ExponentialTable {
public:
  ExponentialTable();
  // exp(-a) / Z without overflow or premature underflow.
  double scaledExp(double a) const { return a < 700 ? std::exp(-a) * inverseZ_ : std::exp(-a - logZ_); }
  double g(double w) const { return scaledExp(w + 1 + 1 / (w - 1)) / (w * w); }
  // int_w^inf g for w >= 2, i.e. Theta(1/w).
  double upperIntegral(double w) const;
  // The w >= 2 with upperIntegral(w) = v, for 0 < v < 1/2.
  double solve(double v) const;

private:
  // Nodes: uniform in (w-1)^{-1/2} on [2, kGradedEnd], where the Hermite start of the inverse
  // needs cells of width about 0.012 (w-1)^{3/2} to be accurate to 1e-10, then uniform with
  // spacing kStep up to kEnd, beyond which the integral is below 1e-340.
  static constexpr double kGradedEnd   = 8;
  static constexpr int    kGradedCells = 96;
  static constexpr double kStep        = 0.25;
  static constexpr double kEnd         = 802;
  static constexpr int    kNodes       = kGradedCells + 1 + static_cast<int>((kEnd - kGradedEnd) / kStep);
  static constexpr int    kLocalPoints = 4; // Gauss-Legendre points over at most half a cell

  static double node(int i);
  static double fractionalIndex(double w);
  double        localIntegral(int k, double w) const;
  double        tail(double w) const;

  double              inverseZ_, logZ_;
  int                 last_;                             // the first node where Theta is subnormal
  std::vector<double> w_, g_, theta_, logTheta_, slope_; // nodes; g, Theta, log Theta and dw / dlog Theta there
  std::vector<double> localNodes_, localWeights_;
};

double ExponentialTable::node(int i)
{
  const double gradedStep = (1 - 1 / std::sqrt(kGradedEnd - 1)) / kGradedCells;
  if (i >= kGradedCells) return kGradedEnd + (i - kGradedCells) * kStep;
  const double u = 1 - i * gradedStep;
  return 1 + 1 / (u * u);
}

double ExponentialTable::fractionalIndex(double w)
{
  const double gradedStep = (1 - 1 / std::sqrt(kGradedEnd - 1)) / kGradedCells;
  if (w >= kGradedEnd) return kGradedCells + (w - kGradedEnd) / kStep;
  return (1 - 1 / std::sqrt(w - 1)) / gradedStep;
}

ExponentialTable::ExponentialTable()
{
  // Panel integrals and their cumulative sum from the right, in compensated long double.
  const GaussLegendreRule  rule = gaussLegendre(12);
  const auto               gl   = [](long double w) { return std::exp(-(w + 1 + 1 / (w - 1))) / (w * w); };
  std::vector<long double> upper(kNodes, 0.0L);
  long double              sum = 0, compensation = 0;
  for (int i = kNodes - 2; i >= 0; --i) {
    const long double a = node(i), half = 0.5L * (node(i + 1) - a);
    long double       panel = 0;
    for (std::size_t k = 0; k < rule.nodes.size(); ++k) panel += rule.weights[k] * gl(a + half * (1 + rule.nodes[k]));
    panel *= half;
    const long double t = sum + panel; // Neumaier summation
    compensation += std::fabs(sum) >= std::fabs(panel) ? (sum - t) + panel : (panel - t) + sum;
    sum      = t;
    upper[i] = sum + compensation;
  }
  const long double Z = 2 * upper[0];
  inverseZ_           = static_cast<double>(1 / Z);
  logZ_               = static_cast<double>(std::log(Z));
  // Up to the first node where Theta is subnormal: beyond it, Theta need not be accurate.
  for (int i = 0; i < kNodes && (i == 0 || upper[i - 1] / Z >= DBL_MIN); ++i) {
    w_.push_back(node(i));
    g_.push_back(static_cast<double>(gl(w_.back()) / Z));
    theta_.push_back(static_cast<double>(upper[i] / Z));
    logTheta_.push_back(std::log(theta_.back()));
    slope_.push_back(-theta_.back() / g(w_.back()));
  }
  last_ = static_cast<int>(theta_.size()) - 1;

  const GaussLegendreRule local = gaussLegendre(kLocalPoints);
  for (std::size_t k = 0; k < local.nodes.size(); ++k) {
    localNodes_.push_back(static_cast<double>(local.nodes[k]));
    localWeights_.push_back(static_cast<double>(local.weights[k]));
  }
}

// int_{w_k}^w g, with g relative to its value at the node, g(x) = g_k exp(-d) (w_k/x)^2 where
// d = (x - w_k)(1 - 1/((x-1)(w_k-1))), and x - w_k computed directly: g(x) itself, or x
// rounded near w ~ 700, would carry an error of up to 700 ulps in the exponent.
double ExponentialTable::localIntegral(int k, double w) const
{
  const double a = w_[k], inverseA = 1 / (a - 1), half = 0.5 * (w - a);
  double       sum = 0;
  for (int i = 0; i < kLocalPoints; ++i) {
    const double offset = half * (1 + localNodes_[i]), x = a + offset;
    const double inverse = 1 / (x * (x - 1)); // 1/(x-1) = inverse x, 1/x = inverse (x-1)
    const double d = offset * (1 - inverse * x * inverseA), ratio = a * (x - 1) * inverse;
    sum += localWeights_[i] * std::exp(-d) * ratio * ratio;
  }
  return half * g_[k] * sum;
}

// Laplace's approximation g / psi' with psi = w + 1 + 1/(w-1) + 2 log w, used only where Theta
// is subnormal (its relative error ~ 2/w^2 < 1e-5 there).
double ExponentialTable::tail(double w) const
{
  return g(w) / (1 - 1 / ((w - 1) * (w - 1)) + 2 / w);
}

double ExponentialTable::upperIntegral(double w) const
{
  if (w > w_[last_] + 0.5 * kStep) return tail(w);
  const int nearest = std::min(static_cast<int>(fractionalIndex(w) + 0.5), last_);
  return theta_[nearest] - localIntegral(nearest, w);
}

double ExponentialTable::solve(double v) const
{
  if (v < theta_[last_]) return w_[last_] + std::log(theta_[last_] / v); // rough, for subnormal v
  // theta_ decreases: find the cell [i, i+1] with theta_[i] >= v > theta_[i+1].
  const auto   first = std::partition_point(theta_.begin(), theta_.end(), [v](double t) { return t >= v; });
  const int    cell  = std::min(static_cast<int>(first - theta_.begin()) - 1, last_ - 1);
  const double dL    = logTheta_[cell + 1] - logTheta_[cell];
  const double t     = (std::log(v) - logTheta_[cell]) / dL;
  const double start = hermite(t, dL, w_[cell], slope_[cell], w_[cell + 1], slope_[cell + 1]);
  const double lo = w_[std::max(cell - 1, 0)], hi = w_[std::min(cell + 2, last_)];
  const auto   residual = [&](double w, double &slope) {
    slope = g(w);
    return v - upperIntegral(w);
  };
  return safeguardedNewton(residual, std::clamp(start, lo, hi), lo, hi);
}

const ExponentialTable &exponentialTable()
{
  static const ExponentialTable table;
  return table;
}

class ExponentialKernel final : public Kernel {
public:
  ExponentialKernel() : table_(exponentialTable()) {}
  std::string name() const override { return "exponential"; }
  int         order() const override { return kInfiniteOrder; }
  double      value(double s) const override
  {
    if (s <= 0 || s >= 1) return 0;
    const double t = std::min(s, 1 - s);
    return table_.scaledExp(1 / (t * (1 - t)));
  }

protected:
  double lowerTheta(double s) const override;
  double lowerThetaInverse(double v) const override
  {
    if (!(v > 0)) return 0;
    if (v >= 0.5) return 0.5;
    return 1 / table_.solve(v);
  }

private:
  const ExponentialTable &table_;
};

double ExponentialKernel::lowerTheta(double s) const
{
  if (s <= 0) return 0;
  // 1/s = w + error exactly; without the correction the rounding of w would cost w ulps.
  const double w = 1 / s, error = std::fma(-w, s, 1.0) / s;
  return table_.upperIntegral(w) - table_.g(w) * error;
}

} // namespace

// ---------------------------------------------------------------------------------------------

std::unique_ptr<Kernel> Kernel::create(KernelType type, int polynomialOrder)
{
  switch (type) {
  case KernelType::Cosine:
    return std::make_unique<CosineKernel>();
  case KernelType::Constant:
    return std::make_unique<ConstantKernel>();
  case KernelType::Exponential:
    return std::make_unique<ExponentialKernel>();
  case KernelType::Polynomial:
    if (polynomialOrder < 0 || polynomialOrder > kMaxPolynomialOrder) throw std::invalid_argument("polynomial kernel order " + std::to_string(polynomialOrder) + " is out of range: must be 0.." + std::to_string(kMaxPolynomialOrder));
    return std::make_unique<PolynomialKernel>(polynomialOrder);
  }
  throw std::invalid_argument("unknown kernel type " + std::to_string(static_cast<int>(type)));
}

double Kernel::theta(double s) const
{
  if (s <= 0) return 0;
  if (s >= 1) return 1;
  return s <= 0.5 ? lowerTheta(s) : 1 - lowerTheta(1 - s);
}

double Kernel::thetaInverse(double u, double uc) const
{
  return u <= uc ? lowerThetaInverse(u) : 1 - lowerThetaInverse(uc);
}

double Kernel::valueAtThetaInverse(double u, double uc) const
{
  return value(lowerThetaInverse(std::min(u, uc)));
}

} // namespace vshmm
