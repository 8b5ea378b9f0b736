// The second-order Runge-Kutta-Chebyshev method RKC (Sommeijer, Shampine and Verwer, "RKC: an
// explicit solver for parabolic PDEs", J. Comput. Appl. Math. 88, 1997), with damping
// epsilon = 2/13. An s-stage step is stable on the negative real axis up to beta(s), about
// 0.65 s^2: where the spectrum lies near that axis (diffusion), a step of length h costs about
// sqrt(h rho / 0.65) evaluations against h rho / 2.5 x 3 for RK3, rho the spectral radius.
// Used by the sparse spectral component's cluster detection (a short direct simulation on
// every mode, where the stiffest wavenumbers set RK3's step). No PETSc here.
#pragma once

#include <complex>
#include <functional>
#include <vector>

namespace vshmm {

class ChebyshevRK2 {
public:
  // An s-stage method, s >= 2 (std::invalid_argument otherwise).
  explicit ChebyshevRK2(int stages);

  int stages() const { return s_; }

  // R(z) = a_s + b_s T_s(w0 + w1 z): one step applied to y' = lambda y, z = h lambda.
  std::complex<double> operator()(std::complex<double> z) const;

  // beta(s) = (1 + w0) / w1: |R(x)| <= 1 for every x in [-beta(s), 0].
  double realLimit() const { return (1.0 + w0_) / w1_; }

  // Whether |R(x h lambda)| <= 1 for every x in [0, 1] and every lambda given (checked at 256
  // points of each ray); lambda with Re lambda > growing |lambda| are growing modes, not checked.
  bool stableFor(double h, const std::vector<std::complex<double>> &lambdas, double growing = 0.1) const;

  // The fewest stages (2 .. maxStages) whose step h is stable for every lambda (stableFor), or 0
  // if none is.
  static int stagesFor(double h, const std::vector<std::complex<double>> &lambdas, int maxStages = 1000);

  // One step of length h of y' = F(y) (autonomous; F(y, f) writes f = F(y), n reals) from y in
  // place; work holds at least 5 n reals (resized if not). Exactly s evaluations of F.
  void step(const std::function<void(const double *, double *)> &F, double h, std::vector<double> &y, std::vector<double> &work) const;

private:
  int                 s_;
  double              w0_, w1_;
  std::vector<double> b_;  // b_j, j = 0..s
  std::vector<double> Tw_; // T_j(w0), j = 0..s
};

} // namespace vshmm
