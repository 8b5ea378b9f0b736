// Tests of src/core/spectral/stable.{hpp,cpp}: the Parseval weights, the Arnoldi estimate of the
// operator's eigenvalues (against the exact ones of constant coefficients and the norm bound),
// the grid derivative and the growth model of each term.
#include <gtest/gtest.h>

#include "stable.hpp"
#include "truncation.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

using namespace vshmm::spectral;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<double> gridOf(int N, double (*f)(double))
{
  std::vector<double> v(N);
  for (int j = 0; j < N; ++j) v[j] = f(gridPoint(N, j));
  return v;
}

// The largest |entry| of the Hessenberg matrix (at most its norm).
double maxAbsColumnEntry(const ArnoldiResult &r)
{
  double m = 0;
  for (double h : r.H) m = std::max(m, std::fabs(h));
  return m;
}

} // namespace

TEST(SpectralStable, ParsevalWeightsGiveTheGridMeanSquare)
{
  const int                 N    = 16;
  const Layout              full = Layout::full(N);
  const std::vector<double> w    = parsevalWeights(full);
  std::vector<double>       coef(full.size()), u(N);
  for (int i = 0; i < full.size(); ++i) coef[i] = std::sin(0.7 * i + 0.2);
  SpectralOperator op(full, std::vector<double>(N, 1.0), {}, Planner::Estimate);
  op.synthesize(coef.data(), u.data());
  double ms = 0, grid = 0;
  for (int i = 0; i < full.size(); ++i) ms += w[i] * coef[i] * coef[i];
  for (double v : u) grid += v * v / N;
  EXPECT_NEAR(ms, grid, 1e-12 * grid);
  EXPECT_EQ(w[0], 1.0);        // k = 0
  EXPECT_EQ(w.back(), 1.0);    // k = N/2
  EXPECT_EQ(w[1], 2.0);        // Re c_1 stands for +-1
  EXPECT_EQ((int)w.size(), N); // every mode: N reals
}

// Constant d: the eigenvalues are -d k^2, k = 0..N/2 - 1 (the Nyquist mode's derivative is zero):
// 32 distinct values, fewer than the 40 Arnoldi steps, so the extreme Ritz value is exact: d (N/2-1)^2.
TEST(SpectralStable, ArnoldiFindsTheDiffusionSpectrum)
{
  const int        N    = 64;
  const double     d    = 0.7;
  const Layout     full = Layout::full(N);
  SpectralOperator op(full, std::vector<double>(N, d), {}, Planner::Estimate);
  const auto       w = parsevalWeights(full);
  ArnoldiResult    r = arnoldi([&](const double *v, double *out) { op.apply(v, out); }, w, 40);
  ASSERT_TRUE(r.finite);
  ASSERT_GT(r.k, 0);
  // In the Parseval inner product the operator is symmetric: H is symmetric (tridiagonal).
  for (int j = 0; j < r.k; ++j)
    for (int i = 0; i < r.k; ++i) EXPECT_NEAR(r.H[i + j * r.k], r.H[j + i * r.k], 1e-9 * d * 31 * 31);
  // Its largest |entry| is at most the spectral radius d 31^2, which is at most the bound d 32^2.
  EXPECT_LE(maxAbsColumnEntry(r), d * 31 * 31 * (1 + 1e-12));
  EXPECT_NEAR(spectralRadiusBound(std::vector<double>(N, d), {}, 32), d * 32 * 32, 1e-12);
  // The power of H: the Rayleigh quotient of H^p e converges to the largest eigenvalue -d 31^2.
  std::vector<double> x(r.k, 1.0), y(r.k);
  double              lambda = 0;
  for (int it = 0; it < 3000; ++it) {
    for (int i = 0; i < r.k; ++i) {
      y[i] = 0;
      for (int j = 0; j < r.k; ++j) y[i] += r.H[i + j * r.k] * x[j];
    }
    double xy = 0, xx = 0, yy = 0;
    for (int i = 0; i < r.k; ++i) xy += x[i] * y[i], xx += x[i] * x[i], yy += y[i] * y[i];
    lambda = xy / xx;
    for (int i = 0; i < r.k; ++i) x[i] = y[i] / std::sqrt(yy);
  }
  EXPECT_NEAR(lambda, -d * 31 * 31, 1e-6 * d * 31 * 31);
}

TEST(SpectralStable, ArnoldiStopsOnNonFiniteMaps)
{
  const std::vector<double> w(8, 1.0);
  ArnoldiResult             r = arnoldi([](const double *, double *out) { std::fill(out, out + 8, std::nan("")); }, w, 5);
  EXPECT_FALSE(r.finite);
}

TEST(SpectralStable, GridDerivativeOfATrigonometricPolynomial)
{
  const int                 N  = 32;
  const std::vector<double> f  = gridOf(N, [](double x) { return std::sin(3 * x) + 0.5 * std::cos(7 * x); });
  const std::vector<double> df = gridDerivative(f);
  for (int j = 0; j < N; ++j) {
    const double x = gridPoint(N, j);
    EXPECT_NEAR(df[j], 3 * std::cos(3 * x) - 3.5 * std::sin(7 * x), 1e-12);
  }
}

TEST(SpectralStable, GrowthModelOfEachTerm)
{
  const int   N = 64;
  GrowthModel diffusion;
  diffusion.addDiffusion(gridOf(N, [](double x) { return 1 + 0.5 * std::cos(x); }), 20);
  EXPECT_EQ(diffusion.rate0, 0.0); // d >= 0: the norm does not grow
  EXPECT_TRUE(diffusion.maxPrinciple);
  GrowthModel antidiffusion;
  antidiffusion.addDiffusion(gridOf(N, [](double x) { return 0.1 + 0.3 * std::cos(x); }), 10);
  EXPECT_NEAR(antidiffusion.rate0, 0.2 * 100, 1e-12); // max(-d) kmax^2
  EXPECT_FALSE(antidiffusion.maxPrinciple);

  GrowthModel advection; // a = 1 + 0.4 sin 2x: a' = 0.8 cos 2x, rate max(a')/2 = 0.4
  advection.addAdvection(gridOf(N, [](double x) { return 1 + 0.4 * std::sin(2 * x); }));
  EXPECT_NEAR(advection.rate0, 0.4, 1e-12);
  EXPECT_TRUE(advection.maxPrinciple);

  GrowthModel burgers; // c = 2 + sin x: max|c'| = 1, rate M / 6
  burgers.addBurgers(gridOf(N, [](double x) { return 2 + std::sin(x); }));
  EXPECT_NEAR(burgers.rate1, 1.0 / 6, 1e-12);
  EXPECT_FALSE(burgers.maxPrinciple);
  GrowthModel burgersConstant;
  burgersConstant.addBurgers(std::vector<double>(N, 1.5));
  EXPECT_NEAR(burgersConstant.rate1, 0.0, 1e-12);
  EXPECT_TRUE(burgersConstant.maxPrinciple);

  GrowthModel  reaction; // r = 2 (constant), c = (0.5, -1, 3, -2)
  const double c[4] = {0.5, -1, 3, -2};
  reaction.addReaction(std::vector<double>(N, 2.0), c);
  EXPECT_EQ(reaction.rate0, 0.0);          // r c1 = -2 < 0
  EXPECT_NEAR(reaction.rate1, 6.0, 1e-12); // |r c2|
  EXPECT_EQ(reaction.rate2, 0.0);          // r c3 = -4 < 0
  EXPECT_NEAR(reaction.source, 1.0, 1e-12);
  EXPECT_TRUE(reaction.needsMax());

  GrowthModel source; // s = 3 sin x: RMS 3/sqrt 2, max 3
  source.addSource(gridOf(N, [](double x) { return 3 * std::sin(x); }));
  EXPECT_NEAR(source.source, 3 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(source.supSource, 3.0, 1e-9);
}

TEST(SpectralStable, GrowthBoundAlongARun)
{
  GrowthModel diffusion; // nothing grows: the bound stays the initial norm
  GrowthBound b(diffusion, 0.0, 0.4, 1.0);
  b.advance(5.0, 0.0);
  EXPECT_EQ(b.bound(), 0.4);

  GrowthModel m; // rate 0.5, source 0.1, no maximum principle: E' = 0.5 E + 0.1 bounded stepwise
  m.rate0        = 0.5;
  m.source       = 0.1;
  m.maxPrinciple = false;
  GrowthBound g(m, 1.0, 2.0, 3.0);
  double      exact = 2.0;
  for (int i = 1; i <= 10; ++i) {
    g.advance(1.0 + 0.1 * i, 0.0);
    exact = (exact + 0.1 * 0.1) * std::exp(0.05);
  }
  EXPECT_NEAR(g.bound(), exact, 1e-12);
  EXPECT_GE(g.bound(), (2.0 + 0.1 / 0.5) * std::exp(0.5) - 0.1 / 0.5); // above the ODE's solution

  GrowthModel adv; // advection: the maximum principle caps the exponential bound
  adv.rate0 = 10;
  GrowthBound a(adv, 0.0, 0.45, 1.0);
  a.advance(3.0, 0.0);
  EXPECT_EQ(a.bound(), 1.0);
  a.advance(2.0, 0.0); // time going back is ignored
  EXPECT_EQ(a.time(), 3.0);
}

TEST(SpectralTruncation, AForcedDampedMode)
{
  // a' = -2 a + 3 from a(0) = 0.5, looked at every 0.1: exact for a constant forcing
  TruncationModel m({7}, {2.0}, {2.0}, 0.0, {-0.5});
  EXPECT_EQ(m.amplitudes()[0], 0.5); // |c_k| of the initial data
  for (int i = 0; i <= 10; ++i) m.advance(0.1 * i, {-3.0});
  const double a = 0.5 * std::exp(-2.0) + 3.0 * (1 - std::exp(-2.0)) / 2.0;
  EXPECT_NEAR(m.amplitudes()[0], a, 1e-12);
  EXPECT_NEAR(m.norm(), std::sqrt(2.0) * a, 1e-12); // weight 2: the mode stands for +-k
  EXPECT_EQ(m.time(), 1.0);
  EXPECT_EQ(m.startTime(), 0.0);

  // a forcing that grows like t: the trapezoid of the looks' forcings, O(dt^2) of
  // int_0^t e^{-lambda (t - s)} s ds = t / lambda - (1 - e^{-lambda t}) / lambda^2
  TruncationModel g({3}, {2.0}, {1.0}, 0.0, {});
  for (int i = 0; i <= 1000; ++i) g.advance(1e-3 * i, {1e-3 * i});
  EXPECT_NEAR(g.amplitudes()[0], 0.5 - (1 - std::exp(-2.0)) / 4.0, 1e-6);

  // undamped (rate 0) and growing (a negative rate is taken as 0) modes integrate their forcing
  TruncationModel u({1, 2}, {0.0, -5.0}, {2.0, 2.0}, 1.0, {});
  u.advance(1.0, {0.2, 0.2});
  u.advance(1.5, {0.4, 0.4});
  EXPECT_NEAR(u.amplitudes()[0], 0.15, 1e-15);
  EXPECT_NEAR(u.amplitudes()[1], 0.15, 1e-15);
  u.advance(1.2, {9.0, 9.0}); // an earlier time adds nothing
  EXPECT_NEAR(u.amplitudes()[0], 0.15, 1e-15);
  EXPECT_EQ(u.time(), 1.5);
}

TEST(SpectralTruncation, TheLargestModes)
{
  TruncationModel m({4, 9, 13, 40}, {0, 0, 0, 0}, {2, 2, 2, 1}, 0.0, {0.3, 0.01, 0.2, 0.05});
  EXPECT_NEAR(m.norm(), std::sqrt(2 * (0.09 + 1e-4 + 0.04) + 0.0025), 1e-15);
  EXPECT_EQ(m.largest(0.1), (std::vector<int>{4, 13})); // what is left: sqrt(2e-4 + 0.0025) = 0.052
  EXPECT_EQ(m.largest(0.03), (std::vector<int>{4, 13, 40}));
  EXPECT_EQ(m.largest(1.0), std::vector<int>());
  EXPECT_THROW(TruncationModel({1, 2}, {0}, {2, 2}, 0.0, {}), std::invalid_argument);
  EXPECT_THROW(m.advance(1.0, {1.0}), std::invalid_argument);
}
