// Kernels K(s) of the variable mesoscopic steps, their antiderivative Theta and its inverse,
// checked against independent long-double quadrature and finite differences.
#include "kernel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace {

using vshmm::Kernel;
using vshmm::KernelType;

const long double kPiL = 3.141592653589793238462643383279502884L;

// 5-point Gauss-Legendre on [a, b] (nodes and weights from tables, not from the library).
long double gaussLegendre5(const std::function<long double(long double)> &f, long double a, long double b)
{
  static const long double x[5]   = {0.0L, -0.538469310105683091036314420700208805L, 0.538469310105683091036314420700208805L, -0.906179845938663992797626878299392965L, 0.906179845938663992797626878299392965L};
  static const long double w[5]   = {0.568888888888888888888888888888888889L, 0.478628670499366468041291514835638192L, 0.478628670499366468041291514835638192L, 0.236926885056189087514264040719917363L, 0.236926885056189087514264040719917363L};
  const long double        middle = 0.5L * (a + b), half = 0.5L * (b - a);
  long double              sum = 0;
  for (int i = 0; i < 5; ++i) sum += w[i] * f(middle + half * x[i]);
  return half * sum;
}

long double compositeGaussLegendre(const std::function<long double(long double)> &f, long double a, long double b, int panels)
{
  long double sum = 0;
  for (int i = 0; i < panels; ++i) sum += gaussLegendre5(f, a + (b - a) * i / panels, a + (b - a) * (i + 1) / panels);
  return sum;
}

// exp(-1/(r(1-r))) integrated from 0 to s on panels shrinking like r^2 toward 0 (the scale of
// the integrand there), down to where it is below 1e-26 of its value at s.
long double exponentialIntegral(long double s)
{
  const auto        f   = [](long double r) { return std::exp(-1 / (r * (1 - r))); };
  long double       sum = 0, b = s;
  const long double stop = s / (1 + 60 * s);
  while (b > stop) {
    const long double a = std::max(b - 2e-3L * b * b, stop);
    sum += gaussLegendre5(f, a, b);
    b = a;
  }
  return sum;
}

// Independent formulas for K, and Theta(s) for s <= 1/2 by quadrature, in long double.
struct Reference {
  KernelType type;
  int        order;

  long double value(long double r) const
  {
    switch (type) {
    case KernelType::Cosine: {
      const long double sine = std::sin(kPiL * r);
      return 2 * sine * sine;
    }
    case KernelType::Constant:
      return 1;
    case KernelType::Polynomial: {
      const int         n    = order + 2;
      const long double beta = std::tgamma((long double)n) * std::tgamma((long double)n) / std::tgamma((long double)(2 * n));
      return std::pow(r * (1 - r), (long double)(n - 1)) / beta;
    }
    case KernelType::Exponential:
      return std::exp(-1 / (r * (1 - r))) / normalization();
    }
    return 0;
  }

  long double lowerTheta(long double s) const
  {
    if (type == KernelType::Exponential) return exponentialIntegral(s) / normalization();
    return compositeGaussLegendre([this](long double r) { return value(r); }, 0, s, 256);
  }

  static long double normalization()
  {
    static const long double Z = 2 * exponentialIntegral(0.5L);
    return Z;
  }
};

struct KernelCase {
  KernelType type;
  int        order; // polynomial order q (ignored by the other kernels)
};

std::string caseName(const testing::TestParamInfo<KernelCase> &info)
{
  const std::string name = Kernel::create(info.param.type, info.param.order)->name();
  return info.param.type == KernelType::Polynomial ? name + std::to_string(info.param.order) : name;
}

class KernelTest : public testing::TestWithParam<KernelCase> {
protected:
  void SetUp() override { kernel = Kernel::create(GetParam().type, GetParam().order); }

  bool      isExponential() const { return GetParam().type == KernelType::Exponential; }
  bool      isConstant() const { return GetParam().type == KernelType::Constant; }
  Reference reference() const { return Reference{GetParam().type, GetParam().order}; }

  std::unique_ptr<Kernel> kernel;
};

// log K(h1) / K(h2) over log h1 / h2: the power p in K(h) ~ c h^p.
double logSlope(const std::function<double(double)> &k, double h1, double h2)
{
  return std::log(k(h1) / k(h2)) / std::log(h1 / h2);
}

TEST_P(KernelTest, IntegralOverUnitIntervalIsOne)
{
  const auto        k        = [this](long double s) { return (long double)kernel->value((double)s); };
  const long double integral = compositeGaussLegendre(k, 0, 1, 2000);
  EXPECT_NEAR((double)integral, 1.0, 1e-13);
}

TEST_P(KernelTest, ValueMatchesIndependentFormula)
{
  const Reference ref = reference();
  for (int i = 1; i < 1000; ++i) {
    const double s = i / 1000.0, expected = (double)ref.value(s);
    EXPECT_NEAR(kernel->value(s), expected, 1e-13 * expected) << "s = " << s;
  }
}

TEST_P(KernelTest, IsSymmetric)
{
  for (int i = 0; i <= 1024; ++i) {
    const double s = i / 1024.0; // 1 - s is exact
    EXPECT_EQ(kernel->value(s), kernel->value(1 - s)) << "s = " << s;
  }
  for (int i = 1; i < 1000; ++i) {
    const double t = 1 - (0.0005 * i + 1e-7); // then 1 - t is exact
    EXPECT_EQ(kernel->value(t), kernel->value(1 - t)) << "t = " << t;
  }
}

TEST_P(KernelTest, VanishesAtBothEndsExceptConstant)
{
  const double expected = isConstant() ? 1.0 : 0.0;
  EXPECT_EQ(kernel->value(0.0), expected);
  EXPECT_EQ(kernel->value(1.0), expected);
  EXPECT_EQ(kernel->value(-0.5), 0.0);
  EXPECT_EQ(kernel->value(1.5), 0.0);
}

// K(h) ~ c h^{q+1} at both ends: derivatives 0..q vanish there and derivative q+1 does not.
// The kernels of finite order (the exponential one is flatter than any power: see
// ExponentialKernelIsFlatterThanAnyPower).
class FiniteOrderKernelTest : public KernelTest {};

TEST_P(FiniteOrderKernelTest, DerivativesUpToOrderVanishAtEnds)
{
  const int  q     = kernel->order();
  const auto left  = [this](double h) { return kernel->value(h); };
  const auto right = [this](double h) { return kernel->value(1 - h); };
  EXPECT_NEAR(logSlope(left, 1e-4, 1e-5), q + 1, 2e-3);
  EXPECT_NEAR(logSlope(right, 1e-4, 1e-5), q + 1, 2e-3);
}

TEST(ExponentialKernel, IsFlatterThanAnyPower)
{
  const auto kernel = Kernel::create(KernelType::Exponential);
  EXPECT_EQ(kernel->order(), Kernel::kInfiniteOrder);
  const auto   k      = [&](double h) { return kernel->value(h); };
  const double coarse = logSlope(k, 0.02, 0.01), fine = logSlope(k, 0.01, 0.005);
  EXPECT_GT(coarse, 50);         // K(h) = o(h^50)
  EXPECT_GT(fine, 1.5 * coarse); // and the apparent power keeps growing
  const auto k1 = [&](double h) { return kernel->value(1 - h); };
  EXPECT_GT(logSlope(k1, 0.02, 0.01), 50);
}

TEST_P(KernelTest, ThetaAtEndsAndMiddle)
{
  EXPECT_EQ(kernel->theta(0.0), 0.0);
  EXPECT_EQ(kernel->theta(1.0), 1.0);
  EXPECT_NEAR(kernel->theta(0.5), 0.5, 1e-16);
  EXPECT_EQ(kernel->theta(-1.0), 0.0);
  EXPECT_EQ(kernel->theta(2.0), 1.0);
}

TEST_P(KernelTest, ThetaIsMonotone)
{
  const int N        = 100000;
  double    previous = kernel->theta(0.0);
  for (int i = 1; i <= N; ++i) {
    const double s = double(i) / N, theta = kernel->theta(s);
    ASSERT_GE(theta, previous) << "s = " << s;
    // Strictly increasing where Theta is a normal number below 1/2 (above, steps can be below an ulp of 1).
    if (s <= 0.5 && previous >= DBL_MIN) { ASSERT_GT(theta, previous) << "s = " << s; }
    previous = theta;
  }
}

// Theta' = K by fourth-order central differences with steps scaled to the kernel's local scale.
// The rounding allowance is one ulp of Theta over h: relative to Theta for s <= 1/2, of 1 above
// (where Theta = 1 - Theta(1-s) is rounded near 1).
TEST_P(KernelTest, ThetaDerivativeIsKernel)
{
  for (int i = 1; i < 200; ++i) {
    const double s = 0.005 * i, t = std::min(s, 1 - s), h = 1e-3 * t * t;
    const double difference = (8 * (kernel->theta(s + h) - kernel->theta(s - h)) - (kernel->theta(s + 2 * h) - kernel->theta(s - 2 * h))) / (12 * h);
    const double k = kernel->value(s), rounding = (s <= 0.5 ? kernel->theta(s + 2 * h) : 1.0) * DBL_EPSILON / h;
    EXPECT_NEAR(difference, k, 1e-9 * k + rounding) << "s = " << s;
  }
}

// Theta for s <= 1/2 is accurate relative to its own (possibly tiny) size.
TEST_P(KernelTest, LowerThetaMatchesIndependentQuadratureRelatively)
{
  const Reference ref                 = reference();
  const double    smallest[]          = {1e-8, 1e-6, 1e-4, 1e-2, 0.1, 0.25, 0.4, 0.5};
  const double    exponentialPoints[] = {0.0015, 0.002, 0.005, 0.01, 0.05, 0.1, 0.3, 0.5}; // Theta normal for s > 1/690
  for (double s : isExponential() ? exponentialPoints : smallest) {
    const long double expected = ref.lowerTheta(s);
    EXPECT_NEAR(kernel->theta(s) / (double)expected, 1.0, 2e-15) << "s = " << s;
    EXPECT_NEAR(kernel->theta(1 - s), (double)(1 - expected), 2.3e-16) << "s = " << 1 - s;
  }
}

// thetaInverse(theta(s), theta(1-s)) = s relative to min(s, 1-s). For the exponential kernel only
// where Theta(s) (or 1 - Theta(s)) is a normal double, s in [1/690, 1 - 1/690]: below, Theta
// carries less than 53 bits and the inverse is only approximate.
TEST_P(KernelTest, ThetaInverseRoundTrip)
{
  const int N       = 100000;
  int       checked = 0;
  for (int i = 0; i <= N; ++i) {
    const double s = double(i) / N, u = kernel->theta(s), uc = kernel->theta(1 - s);
    if (isExponential() && std::min(u, uc) < DBL_MIN) {
      ASSERT_LE(std::min(s, 1 - s), 1.0 / 680) << "subnormal Theta inside [1/690, 1 - 1/690]";
      const double inverse = kernel->thetaInverse(u, uc);
      EXPECT_LE(std::min(inverse, 1 - inverse), 1.0 / 680) << "s = " << s;
      continue;
    }
    ++checked;
    const double inverse = kernel->thetaInverse(u, uc);
    ASSERT_NEAR(inverse, s, 1e-13 * std::min(s, 1 - s)) << "s = " << s;
  }
  EXPECT_GT(checked, 99000);
  for (double s = 0.1; s > 1e-16; s /= 10) {
    const double u = kernel->theta(s), uc = kernel->theta(1 - s);
    if (std::min(u, uc) < DBL_MIN) continue; // exponential kernel below s = 1/690
    EXPECT_NEAR(kernel->thetaInverse(u, uc), s, 1e-13 * s);
    EXPECT_NEAR(1 - kernel->thetaInverse(uc, u), s, 1e-15); // mirrored: s' = 1 - s
  }
}

TEST_P(KernelTest, ThetaInverseSpecialValues)
{
  EXPECT_EQ(kernel->thetaInverse(0.0, 1.0), 0.0);
  EXPECT_EQ(kernel->thetaInverse(1.0, 0.0), 1.0);
  EXPECT_EQ(kernel->thetaInverse(0.5, 0.5), 0.5);
  // The complement carries the information when u rounds to 1.
  const double tiny = 1e-20, lower = kernel->thetaInverse(tiny, 1.0);
  EXPECT_GT(lower, 0.0);
  EXPECT_NEAR(kernel->thetaInverse(1.0, tiny), 1 - lower, 1e-16);
}

TEST_P(KernelTest, ValueAtThetaInverseIsValueOfInverse)
{
  const int N = 10000;
  for (int i = 1; i < N; ++i) {
    const double u = (i - 0.3) / N, uc = (N - i + 0.3) / N, expected = kernel->value(kernel->thetaInverse(u, uc));
    EXPECT_NEAR(kernel->valueAtThetaInverse(u, uc), expected, 1e-13 * expected) << "u = " << u;
  }
}

INSTANTIATE_TEST_SUITE_P(AllKernels, KernelTest, testing::Values(KernelCase{KernelType::Cosine, 1}, KernelCase{KernelType::Constant, 1}, KernelCase{KernelType::Polynomial, 0}, KernelCase{KernelType::Polynomial, 1}, KernelCase{KernelType::Polynomial, 2}, KernelCase{KernelType::Polynomial, 5}, KernelCase{KernelType::Polynomial, 16}, KernelCase{KernelType::Exponential, 1}), caseName);
INSTANTIATE_TEST_SUITE_P(FiniteOrderKernels, FiniteOrderKernelTest, testing::Values(KernelCase{KernelType::Cosine, 1}, KernelCase{KernelType::Constant, 1}, KernelCase{KernelType::Polynomial, 0}, KernelCase{KernelType::Polynomial, 1}, KernelCase{KernelType::Polynomial, 2}, KernelCase{KernelType::Polynomial, 5}, KernelCase{KernelType::Polynomial, 16}), caseName);

TEST(KernelCreate, NamesAndOrders)
{
  EXPECT_EQ(Kernel::create(KernelType::Cosine)->name(), "cosine");
  EXPECT_EQ(Kernel::create(KernelType::Cosine)->order(), 1);
  EXPECT_EQ(Kernel::create(KernelType::Constant)->name(), "constant");
  EXPECT_EQ(Kernel::create(KernelType::Constant)->order(), -1);
  EXPECT_EQ(Kernel::create(KernelType::Polynomial, 7)->name(), "polynomial");
  EXPECT_EQ(Kernel::create(KernelType::Polynomial, 7)->order(), 7);
  EXPECT_EQ(Kernel::create(KernelType::Exponential)->name(), "exponential");
  // Fixed-order kernels ignore the order argument, even an out-of-range one.
  EXPECT_EQ(Kernel::create(KernelType::Cosine, 99)->order(), 1);
}

TEST(KernelCreate, PolynomialOrderOutOfRangeThrows)
{
  EXPECT_NO_THROW(Kernel::create(KernelType::Polynomial, 0));
  EXPECT_NO_THROW(Kernel::create(KernelType::Polynomial, Kernel::kMaxPolynomialOrder));
  EXPECT_THROW(Kernel::create(KernelType::Polynomial, -1), std::invalid_argument);
  try {
    Kernel::create(KernelType::Polynomial, Kernel::kMaxPolynomialOrder + 1);
    FAIL() << "no exception for order 17";
  } catch (const std::invalid_argument &e) {
    EXPECT_STREQ(e.what(), "polynomial kernel order 17 is out of range: must be 0..16");
  }
}

} // namespace
