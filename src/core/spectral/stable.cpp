// Stable time steps and growth bounds of the spectral operator (no PETSc): stable.hpp.
#include "stable.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vshmm {
namespace spectral {

std::vector<double> parsevalWeights(const Layout &layout)
{
  std::vector<double> w(layout.size());
  for (int i = 0; i < layout.modeCount(); ++i) {
    const int k = layout.mode(i), o = layout.offset(i);
    if (isRealOnly(layout.N(), k)) w[o] = 1.0;
    else w[o] = w[o + 1] = 2.0;
  }
  return w;
}

// Four partial sums: one running sum is bound by the latency of its additions (the compiler may
// not reorder them), and the 40-step Arnoldi's 1,700 products took most of the detection's
// set-up time on 2,048 modes.
static double weightedDot(const std::vector<double> &w, const double *x, const double *y)
{
  const size_t n = w.size(), n4 = n - n % 4;
  double       s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  for (size_t i = 0; i < n4; i += 4) {
    s0 += w[i] * x[i] * y[i];
    s1 += w[i + 1] * x[i + 1] * y[i + 1];
    s2 += w[i + 2] * x[i + 2] * y[i + 2];
    s3 += w[i + 3] * x[i + 3] * y[i + 3];
  }
  for (size_t i = n4; i < n; ++i) s0 += w[i] * x[i] * y[i];
  return (s0 + s1) + (s2 + s3);
}

ArnoldiResult arnoldi(const std::function<void(const double *, double *)> &apply, const std::vector<double> &weights, int m)
{
  const int                        n = (int)weights.size();
  ArnoldiResult                    r;
  std::vector<std::vector<double>> V;
  std::vector<double>              Hfull((size_t)(m + 1) * m, 0.0), w(n);

  m = std::min(m, n);
  if (m <= 0) return r;
  V.emplace_back(n);
  for (int i = 0; i < n; ++i) V[0][i] = 1.0 + 0.5 * std::sin(1.7 * i + 0.3); // every mode present
  double beta = std::sqrt(weightedDot(weights, V[0].data(), V[0].data()));
  for (double &v : V[0]) v /= beta;
  for (int j = 0; j < m; ++j) {
    apply(V[j].data(), w.data());
    for (int pass = 0; pass < 2; ++pass)
      for (int i = 0; i <= j; ++i) {
        const double h = weightedDot(weights, w.data(), V[i].data());
        Hfull[i + (size_t)j * (m + 1)] += h;
        for (int q = 0; q < n; ++q) w[q] -= h * V[i][q];
      }
    const double hnext = std::sqrt(weightedDot(weights, w.data(), w.data()));
    if (!std::isfinite(hnext)) {
      r.finite = false;
      break;
    }
    Hfull[j + 1 + (size_t)j * (m + 1)] = hnext;
    r.k                                = j + 1;
    double hnorm                       = 0;
    for (int i = 0; i <= j + 1; ++i) hnorm = std::max(hnorm, std::fabs(Hfull[i + (size_t)j * (m + 1)]));
    if (hnext <= 1e-12 * hnorm || j + 1 == m) break; // invariant subspace, or done
    V.emplace_back(w);
    for (double &v : V.back()) v /= hnext;
  }
  r.H.assign((size_t)r.k * r.k, 0.0);
  for (int j = 0; j < r.k; ++j)
    for (int i = 0; i < r.k; ++i) r.H[i + (size_t)j * r.k] = Hfull[i + (size_t)j * (m + 1)];
  return r;
}

static double maxAbs(const std::vector<double> &f)
{
  double m = 0;
  for (double v : f) m = std::max(m, std::fabs(v));
  return m;
}

double spectralRadiusBound(const std::vector<double> &D, const std::vector<double> &A, int kmax)
{
  return maxAbs(D) * kmax * (double)kmax + maxAbs(A) * kmax;
}

std::vector<double> gridDerivative(const std::vector<double> &f)
{
  const int N = (int)f.size();
  RealFFT   fft(N, Planner::Estimate);
  std::memcpy(fft.real(), f.data(), sizeof(double) * N);
  fft.forward();
  double *s = fft.spectrum();
  for (int k = 0; k <= N / 2; ++k) {
    const double kk = isRealOnly(N, k) ? 0.0 : (double)k, re = s[2 * k], im = s[2 * k + 1];
    s[2 * k]     = -kk * im / N; // i k (re + i im) / N
    s[2 * k + 1] = kk * re / N;
  }
  fft.inverse();
  return std::vector<double>(fft.real(), fft.real() + N);
}

static double rms(const std::vector<double> &f)
{
  double s = 0;
  for (double v : f) s += v * v;
  return f.empty() ? 0.0 : std::sqrt(s / (double)f.size());
}

void GrowthModel::addDiffusion(const std::vector<double> &d, int kmax)
{
  const double negative = -*std::min_element(d.begin(), d.end());
  if (negative > 0) {
    rate0 += negative * kmax * (double)kmax;
    maxPrinciple = false;
  }
}

void GrowthModel::addAdvection(const std::vector<double> &a)
{
  const std::vector<double> da = gridDerivative(a);
  rate0 += std::max(0.0, *std::max_element(da.begin(), da.end())) / 2.0;
}

void GrowthModel::addBurgers(const std::vector<double> &c)
{
  const double dc = maxAbs(gridDerivative(c));
  rate1 += dc / 6.0;
  if (dc > 1e-12 * std::max(1.0, maxAbs(c))) maxPrinciple = false;
}

void GrowthModel::addReaction(const std::vector<double> &r, const double c[4])
{
  double r1 = 0, r3 = 0, r2 = 0;
  for (double v : r) {
    r1 = std::max(r1, v * c[1]);
    r2 = std::max(r2, std::fabs(v * c[2]));
    r3 = std::max(r3, v * c[3]);
  }
  rate0 += r1;
  rate1 += r2;
  rate2 += r3;
  source += std::fabs(c[0]) * rms(r);
  maxPrinciple = false;
}

void GrowthModel::addSource(const std::vector<double> &s)
{
  source += rms(s);
  supSource += maxAbs(s);
}

GrowthBound::GrowthBound(const GrowthModel &model, double t0, double norm0, double max0) : model_(model), t0_(t0), t_(t0), norm0_(norm0), max0_(max0), energy_(norm0) {}

void GrowthBound::advance(double t, double maxU)
{
  const double dt = t - t_;
  if (!(dt > 0)) return;
  const double rate = model_.rate0 + model_.rate1 * maxU + model_.rate2 * maxU * maxU;
  // d E/dt <= rate E + source over [t_, t]: E(t) <= (E + source dt) exp(rate dt)
  energy_ = (energy_ + model_.source * dt) * std::exp(rate * dt);
  t_      = t;
}

double GrowthBound::bound() const
{
  if (!model_.maxPrinciple) return energy_;
  return std::min(energy_, max0_ + model_.supSource * (t_ - t0_)); // ||u|| <= max|u|
}

} // namespace spectral
} // namespace vshmm
