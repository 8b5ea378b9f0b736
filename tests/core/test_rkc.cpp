// The Runge-Kutta-Chebyshev method RKC: its stability polynomial against its steps, its order,
// its real stability interval (about 0.65 s^2) and the choice of the stage count.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "rkc.hpp"

namespace {

using vshmm::ChebyshevRK2;
using cd = std::complex<double>;

// One step on y' = lambda y (as two reals: y = (re, im)) is R(h lambda) y.
TEST(RKC, OneStepOnALinearModeIsTheStabilityPolynomial)
{
  for (int s : {2, 5, 20}) {
    const ChebyshevRK2 m(s);
    for (cd z : {cd(-0.3, 0), cd(-7, 0.5), cd(-0.5 * m.realLimit(), 0), cd(-1, 2)}) {
      std::vector<double> y      = {1.0, 0.0}, work;
      const double        h      = 0.1;
      const cd            lambda = z / h;
      m.step(
        [&](const double *v, double *f) {
          const cd w = lambda * cd(v[0], v[1]);
          f[0] = w.real(), f[1] = w.imag();
        },
        h, y, work);
      const cd R = m(z);
      EXPECT_NEAR(y[0], R.real(), 1e-12 * (1 + std::abs(R))) << "s = " << s << ", z = " << z;
      EXPECT_NEAR(y[1], R.imag(), 1e-12 * (1 + std::abs(R))) << "s = " << s << ", z = " << z;
    }
  }
}

// R(z) = exp(z) + O(z^3): halving z divides the error by about 8.
TEST(RKC, TheStabilityPolynomialIsOfSecondOrder)
{
  for (int s : {2, 3, 10, 40}) {
    const ChebyshevRK2 m(s);
    const double       e1 = std::abs(m(cd(-1e-2, 0)) - std::exp(cd(-1e-2, 0)));
    const double       e2 = std::abs(m(cd(-5e-3, 0)) - std::exp(cd(-5e-3, 0)));
    EXPECT_GT(e1, 0) << s;
    EXPECT_NEAR(e1 / e2, 8.0, 0.3) << "s = " << s;
  }
}

// The real stability interval grows like s^2 (0.653 s^2 for the damping 2/13, Verwer), |R| <= 1
// inside it and > 1 just beyond.
TEST(RKC, TheRealStabilityIntervalGrowsLikeTheSquareOfTheStages)
{
  for (int s : {2, 4, 10, 30, 100}) {
    const ChebyshevRK2 m(s);
    const double       beta = m.realLimit();
    if (s >= 10) {
      EXPECT_GT(beta, 0.64 * s * s) << s;
      EXPECT_LT(beta, 0.67 * s * s) << s;
    }
    for (int i = 1; i <= 2000; ++i) EXPECT_LE(std::abs(m(cd(-beta * i / 2000.0, 0))), 1.0 + 1e-12) << "s = " << s << ", x = " << -beta * i / 2000.0;
    EXPECT_GT(std::abs(m(cd(-1.02 * beta, 0))), 1.0) << s;
  }
}

// Second order on a nonlinear problem: y' = -y^2, y(0) = 1, y(1) = 1/2.
TEST(RKC, ConvergesWithSecondOrder)
{
  const ChebyshevRK2 m(6);
  double             err[2];
  for (int r = 0; r < 2; ++r) {
    const int           n = 10 << r;
    std::vector<double> y = {1.0}, work;
    for (int i = 0; i < n; ++i) m.step([](const double *v, double *f) { f[0] = -v[0] * v[0]; }, 1.0 / n, y, work);
    err[r] = std::fabs(y[0] - 0.5);
  }
  EXPECT_NEAR(err[0] / err[1], 4.0, 0.4);
  EXPECT_LT(err[1], 1e-3);
}

// The fewest stages whose step is stable: a diffusion-like spectrum needs about sqrt(h rho / 0.65),
// a far imaginary eigenvalue none.
TEST(RKC, StagesForTheSpectrum)
{
  const std::vector<cd> real = {cd(-1, 0), cd(-300, 0), cd(-1000, 0)};
  const int             s    = ChebyshevRK2::stagesFor(1.0, real);
  ASSERT_GT(s, 2);
  EXPECT_TRUE(ChebyshevRK2(s).stableFor(1.0, real));
  EXPECT_FALSE(ChebyshevRK2(s - 1).stableFor(1.0, real));
  EXPECT_GE(s, 39);
  EXPECT_LE(s, 40);
  EXPECT_EQ(ChebyshevRK2::stagesFor(1.0, {cd(-1, 0), cd(0, 100)}, 200), 0);
  // a growing mode is not a limit
  EXPECT_EQ(ChebyshevRK2::stagesFor(1.0, {cd(-1, 0), cd(50, 0)}), 2);
  EXPECT_THROW(ChebyshevRK2(1), std::invalid_argument);
}

} // namespace
