// The coupled-level stability analysis (core/coupling.hpp): spectral radii of small matrices, the
// Runge-Kutta step matrix, and the growth a composition of levels gives a linear oscillator whose
// slow level carries its kinematics, against plain vector stepping of the same schedule.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling.hpp"

namespace {

using vshmm::Tableau;

Tableau RK4()
{
  return Tableau("4", 4, 4, {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0}, {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, {0, 0.5, 0.5, 1});
}

TEST(Coupling, LogSpectralRadiusOfKnownMatrices)
{
  // 2 x rotation by 0.3: rho = 2
  const double c = std::cos(0.3), s = std::sin(0.3);
  EXPECT_NEAR(vshmm::logSpectralRadius({2 * c, 2 * s, -2 * s, 2 * c}, 2), std::log(2.0), 1e-10);
  // strongly non-normal, eigenvalues 1 and 0.5: rho = 1 though the norm is 100
  EXPECT_NEAR(vshmm::logSpectralRadius({1, 0, 100, 0.5}, 2), 0.0, 1e-9);
  // a rotation in unscaled oscillator variables (x, v) -> eigenvalues on the unit circle
  const double w = 50, th = 0.7;
  EXPECT_NEAR(vshmm::logSpectralRadius({std::cos(th), -w * std::sin(th), std::sin(th) / w, std::cos(th)}, 2), 0.0, 1e-9);
  // nilpotent
  EXPECT_TRUE(std::isinf(vshmm::logSpectralRadius({0, 0, 1, 0}, 2)));
}

TEST(Coupling, StepMatrixIsTheStabilityPolynomialOnDiagonals)
{
  const Tableau tab = RK4();
  const double  h = 0.1, l1 = -3, l2 = 2;
  auto          R = [&](double z) { return 1 + z + z * z / 2 + z * z * z / 6 + z * z * z * z / 24; };
  const auto    S = vshmm::stepMatrix(tab, h, {l1, 0, 0, l2}, 2);
  EXPECT_NEAR(S[0], R(h * l1), 1e-15);
  EXPECT_NEAR(S[3], R(h * l2), 1e-15);
  EXPECT_EQ(S[1], 0.0);
  EXPECT_EQ(S[2], 0.0);
  // a nilpotent J: exact, I + h J
  const auto N = vshmm::stepMatrix(tab, 0.3, {0, 0, 1, 0}, 2);
  EXPECT_NEAR(N[2], 0.3, 1e-15);
  EXPECT_NEAR(N[0], 1.0, 1e-15);
}

TEST(Coupling, CommutingLevelsGiveNoCouplingGrowth)
{
  auto                      kernel = vshmm::Kernel::create(vshmm::KernelType::Cosine);
  vshmm::CoupledLevels      levels{2, {{-1, 0, 0, -0.5}, {-40, 0, 0, -30}}};
  vshmm::MesoscopicSchedule schedule(*kernel, 0.01, {20}, {1});
  const auto                g = vshmm::couplingGrowth(RK4(), levels, schedule, 1.0);
  EXPECT_GT(g.cycles, 0);
  EXPECT_EQ(g.logGrowth, 0.0);
}

// x' = v, v' = -w^2 x; the slow level holds the kinematics (J0 = [[0,1],[0,0]]), the full field
// the oscillator. Vector stepping of the same schedule over many macro steps grows like the
// macro step's spectral radius, which the analysis gives (the levels' own steps do not grow: the
// nilpotent J0 exactly, RK4 on the rotation with |R(i w dt)| < 1).
TEST(Coupling, OscillatorWithKinematicsInTheSlowLevelAgainstVectorStepping)
{
  const double              w = 50, dt = 2e-3, DeltaT = 0.1;
  const Tableau             tab    = RK4();
  auto                      kernel = vshmm::Kernel::create(vshmm::KernelType::Cosine);
  const std::vector<double> J0 = {0, 0, 1, 0}, J1 = {0, -w * w, 1, 0};
  vshmm::CoupledLevels      levels{2, {J0, J1}};
  for (double alpha : {1.0, 3.0}) {
    vshmm::MesoscopicSchedule schedule(*kernel, dt, {alpha}, {1});
    const auto                g = vshmm::couplingGrowth(tab, levels, schedule, DeltaT);
    // vector stepping: y <- R(h J) y with the stage recursion on 2-vectors
    double    y[2] = {1 / w, 1}, logNorm = 0;
    const int macroSteps = 4000;
    for (int n = 0; n < macroSteps; ++n) {
      vshmm::runMacroStep(schedule, DeltaT, [&](int level, double, double h) {
        const std::vector<double> &J = level ? J1 : J0;
        double                     k[4][2], Y[2];
        for (int i = 0; i < 4; ++i) {
          for (int d = 0; d < 2; ++d) {
            Y[d] = y[d];
            for (int j = 0; j < i; ++j) Y[d] += h * tab.a[i * 4 + j] * k[j][d];
          }
          k[i][0] = J[0] * Y[0] + J[2] * Y[1];
          k[i][1] = J[1] * Y[0] + J[3] * Y[1];
        }
        for (int i = 0; i < 4; ++i)
          for (int d = 0; d < 2; ++d) y[d] += h * tab.b[i] * k[i][d];
        return 0;
      });
      const double nrm = std::hypot(w * y[0], y[1]);
      logNorm += std::log(nrm);
      y[0] /= nrm;
      y[1] /= nrm;
    }
    const double rate = logNorm / macroSteps; // -> log rho of the macro step
    if (alpha == 1.0) {
      EXPECT_GT(g.logGrowth, 0.1) << "alpha 1 resonates: the composed steps grow the oscillation";
      EXPECT_NEAR(g.logGrowth, rate, 0.01 * rate + 1e-3);
    } else {
      EXPECT_NEAR(g.logGrowth, 0.0, 1e-9);
      EXPECT_LT(rate, 1e-2);
    }
  }
}

// Two oscillators (omega 50 and 35) with a soft coupling, the kinematics in the slow level: a 4 x 4
// case where the order of the steps in the product matters (the 2 x 2 one above is symmetric under
// reversal). The analysis against plain vector stepping over 4,000 macro steps.
TEST(Coupling, TwoCoupledOscillatorsAgainstVectorStepping)
{
  const double        dt = 2e-3, DeltaT = 0.1;
  const Tableau       tab    = RK4();
  auto                kernel = vshmm::Kernel::create(vshmm::KernelType::Cosine);
  const int           n      = 4; // (x1, x2, v1, v2)
  std::vector<double> J0(n * n, 0.0), J1;
  J0[0 + 2 * n] = J0[1 + 3 * n] = 1.0;       // x' = v
  J0[2 + 0 * n] = -0.7, J0[2 + 1 * n] = 0.4; // soft forces on v1
  J0[3 + 0 * n] = 0.3, J0[3 + 1 * n] = -0.9; // and on v2 (not symmetric)
  J1 = J0;
  J1[2 + 0 * n] += -50.0 * 50.0;
  J1[3 + 1 * n] += -35.0 * 35.0;
  vshmm::CoupledLevels      levels{n, {J0, J1}};
  vshmm::MesoscopicSchedule schedule(*kernel, dt, {1.0}, {1});
  const auto                g    = vshmm::couplingGrowth(tab, levels, schedule, DeltaT);
  double                    y[4] = {0.02, -0.01, 1.0, 0.5}, logNorm = 0;
  const int                 macroSteps = 4000;
  for (int m = 0; m < macroSteps; ++m) {
    vshmm::runMacroStep(schedule, DeltaT, [&](int level, double, double h) {
      const std::vector<double> &J = level ? J1 : J0;
      double                     k[4][4], Y[4];
      for (int i = 0; i < 4; ++i) {
        for (int d = 0; d < n; ++d) {
          Y[d] = y[d];
          for (int j = 0; j < i; ++j) Y[d] += h * tab.a[i * 4 + j] * k[j][d];
        }
        for (int d = 0; d < n; ++d) {
          k[i][d] = 0;
          for (int e = 0; e < n; ++e) k[i][d] += J[d + e * n] * Y[e];
        }
      }
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < n; ++d) y[d] += h * tab.b[i] * k[i][d];
      return 0;
    });
    double nrm = 0;
    for (int d = 0; d < n; ++d) nrm += (d < 2 ? 2500.0 : 1.0) * y[d] * y[d];
    nrm = std::sqrt(nrm);
    logNorm += std::log(nrm);
    for (double &v : y) v /= nrm;
  }
  const double rate = logNorm / macroSteps;
  EXPECT_GT(g.logGrowth, 0.05);
  EXPECT_NEAR(g.logGrowth, rate, 0.01 * rate + 1e-3);
}

TEST(Coupling, LargestStableScalingPassesAndTheNextDoesNot)
{
  const double              w = 50, dt = 2e-3, DeltaT = 0.1;
  auto                      kernel = vshmm::Kernel::create(vshmm::KernelType::Cosine);
  vshmm::CoupledLevels      levels{2, {{0, 0, 1, 0}, {0, -w * w, 1, 0}}};
  const std::vector<double> savings = {1.0};
  const double              target  = std::log(1.001);
  const double              s       = vshmm::largestCouplingStableScaling(RK4(), levels, *kernel, dt, savings, {1}, DeltaT, target);
  ASSERT_GT(s, 0.0);
  ASSERT_LT(s, 1.0);
  auto growth = [&](double scale) { return vshmm::couplingGrowth(RK4(), levels, vshmm::MesoscopicSchedule(*kernel, dt, {scale}, {1}), DeltaT).logGrowth; };
  EXPECT_LE(growth(s), target);
  EXPECT_GT(growth(s * (1 + 1e-6) + 1e-9), target);
}

} // namespace
