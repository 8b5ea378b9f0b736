// Stable time steps and growth bounds of the spectral operator (no PETSc):
//
//   Norm:      the mean square of u, ||u||^2 = (1/2 pi) int u^2 dx = sum_k |c_k|^2 over
//              k = -N/2+1..N/2 (Parseval; on the grid, the mean of u(x_j)^2). In the real layout
//              a mode k > 0 stands for +-k: weight 2, the real-only modes (k = 0, N/2) weight 1.
//   Arnoldi:   a few Arnoldi steps on a linear map of the layout's reals in that inner product
//              (in which the diffusion operator is symmetric: real Ritz values); the eigenvalues
//              of the Hessenberg matrix (the Ritz values) approximate the extreme eigenvalues.
//   Bound:     ||F|| <= max|D| kmax^2 + max|A| kmax for F(u) = (D u_x)_x + A u_x on modes up to
//              kmax, in that norm: a bound on every eigenvalue (and on every Ritz value).
//   Growth:    an a-priori bound on ||u(t)|| from the scene's terms (GrowthModel, GrowthBound).
#pragma once

#include "spectral.hpp"

#include <functional>
#include <vector>

namespace vshmm {
namespace spectral {

// The weights of the layout's reals in the mean square: 1 (k = 0, N/2) or 2.
std::vector<double> parsevalWeights(const Layout &layout);

// The Hessenberg matrix of k Arnoldi steps, column-major with leading dimension k: H[i + j k].
struct ArnoldiResult {
  int                 k = 0;
  std::vector<double> H;
  bool                finite = true; // false if the map gave Inf or NaN
};

// Up to m Arnoldi steps on apply (w = A v, n reals) in the weighted inner product
// sum_i weights_i v_i w_i, from a fixed start vector (independent of the caller); stops early on
// an invariant subspace. Gram-Schmidt twice.
ArnoldiResult arnoldi(const std::function<void(const double *, double *)> &apply, const std::vector<double> &weights, int m);

// max|D| kmax^2 + max|A| kmax: a bound on the operator's norm, so on its spectral radius.
double spectralRadiusBound(const std::vector<double> &D, const std::vector<double> &A, int kmax);

// The derivative of the trigonometric interpolant of grid values f (N values), on the grid.
std::vector<double> gridDerivative(const std::vector<double> &f);

// An a-priori bound on the growth of ||u|| along a solution of u_t = sum of the terms:
//   d||u||/dt <= (rate0 + rate1 M + rate2 M^2) ||u|| + source,  M = max|u| on the grid,
// and, when every term keeps a maximum principle, max|u(t)| <= max|u(0)| + t supSource, so
// ||u(t)|| <= that too. Each add* states its term's contribution (docs/spectral.md).
struct GrowthModel {
  double rate0 = 0, rate1 = 0, rate2 = 0; // growth rate of ||u||, as a polynomial in M
  double source       = 0;                // rate of growth independent of u (RMS of the forcing)
  double supSource    = 0;                // max|forcing| (for the maximum principle)
  bool   maxPrinciple = true;

  // u_t += (d u_x)_x: ||u|| does not grow where d >= 0 (maximum principle too); else rate
  // max(-d) kmax^2 and no maximum principle.
  void addDiffusion(const std::vector<double> &d, int kmax);
  // u_t += -a u_x: d||u||^2/dt = mean(a' u^2) <= max(a') ||u||^2: rate max(a', 0)/2;
  // the maximum principle holds (u is transported).
  void addAdvection(const std::vector<double> &a);
  // u_t += -(c u^2/2)_x: d||u||^2/dt = -mean(c' u^3)/3: rate max|c'| M / 6; maximum principle
  // only for constant c.
  void addBurgers(const std::vector<double> &c);
  // u_t += r (c0 + c1 u + c2 u^2 + c3 u^3): rate max(r c1, 0) + max|r c2| M + max(r c3, 0) M^2,
  // source RMS(r c0); no maximum principle.
  void addReaction(const std::vector<double> &r, const double c[4]);
  // u_t += s: source RMS(s), supSource max|s|.
  void addSource(const std::vector<double> &s);
  bool needsMax() const { return rate1 != 0 || rate2 != 0; }
};

// The bound along a run: start at (t0, ||u0||, max|u0|), then advance() to each checked time
// with the largest max|u| seen over the interval (only used when the model needs it).
class GrowthBound {
public:
  GrowthBound() = default;
  GrowthBound(const GrowthModel &model, double t0, double norm0, double max0);
  void   advance(double t, double maxU);
  double bound() const; // the bound on ||u|| at the last time advanced to
  double time() const { return t_; }
  double initialNorm() const { return norm0_; }

private:
  GrowthModel model_;
  double      t0_ = 0, t_ = 0, norm0_ = 0, max0_ = 0, energy_ = 0;
};

} // namespace spectral
} // namespace vshmm
