#include "stability.hpp"

#include <cmath>
#include <algorithm>
#include <limits>

namespace vshmm {

StabilityFunction::StabilityFunction(const Tableau &tableau) : a_(tableau.a), b_(tableau.b), s_(tableau.stages)
{
  // R(z) = sum_k gamma_k z^k with gamma_0 = 1, gamma_k = b^T A^(k-1) 1 (A strictly lower: k <= s).
  std::vector<double> v(s_, 1.0), w(s_);
  gamma_.assign(s_ + 1, 0.0);
  gamma_[0] = 1.0;
  for (int k = 1; k <= s_; ++k) {
    for (int i = 0; i < s_; ++i) gamma_[k] += b_[i] * v[i];
    for (int i = 0; i < s_; ++i) {
      w[i] = 0;
      for (int j = 0; j < i; ++j) w[i] += a_[i * s_ + j] * v[j];
    }
    v.swap(w);
  }
}

std::complex<double> StabilityFunction::operator()(std::complex<double> z) const
{
  // Stage values for y' = y with step z: Y_i = 1 + z sum_{j<i} a_ij Y_j; R = 1 + z sum b_i Y_i.
  std::complex<double> Y[Tableau::kMaxStages], R = 1.0;
  for (int i = 0; i < s_; ++i) {
    std::complex<double> sum = 0.0;
    for (int j = 0; j < i; ++j) sum += a_[i * s_ + j] * Y[j];
    Y[i] = 1.0 + z * sum;
    R += z * b_[i] * Y[i];
  }
  return R;
}

std::complex<double> StabilityFunction::relativeDefect(std::complex<double> z) const
{
  if (std::abs(z) > 0.5) return 1.0 - (*this)(z)*std::exp(-z);
  /* exp(z) - R(z) = sum_k (1/k! - gamma_k) z^k + sum_{k > s} z^k / k!: a coefficient within
     roundoff of 1/k! is the order condition met exactly; |z| <= 1/2, so 30 more terms are exact
     to double precision */
  std::complex<double> D = 0.0, zk = 1.0;
  double               factorial = 1.0;
  for (int k = 0; k <= s_ + 30; ++k) {
    if (k > 0) {
      zk *= z;
      factorial *= k;
    }
    const double c    = 1.0 / factorial;
    const double diff = k <= s_ ? c - gamma_[k] : c;
    if (std::fabs(diff) > 64 * std::numeric_limits<double>::epsilon() * c) D += diff * zk;
  }
  return D * std::exp(-z);
}

double StabilityFunction::rayLimit(std::complex<double> direction) const
{
  const std::complex<double> d   = direction / std::abs(direction);
  const double               tol = 1e-12;
  // A step is stable for the mode when it grows the mode no more than the exact flow does:
  // |R(z)| <= max(1, |exp(z)|). For Re z <= 0 that is the usual |R(z)| <= 1; a growing mode
  // (Re z > 0, e.g. a slightly unstable oscillation) may grow by its own exp(Re z).
  auto stable = [&](double x) { return std::abs((*this)(x * d)) <= (d.real() > 0 ? std::max(1.0, std::exp(x * d.real())) : 1.0) * (1.0 + tol); };
  // Scan outwards in steps small against the size of any stability region of an explicit method,
  // then bisect the first crossing. |R(x d)|^2 = sum_n c_n x^n is a polynomial in x: where it is
  // below the bound (at least its value at x, the bound does not decrease) by a margin m, it cannot
  // reach it within m / L, L = sum_n n |c_n| (x + c)^(n-1) bounding its derivative on [x, x + c];
  // such a step is taken at once, so only the approach to the crossing costs fine steps.
  std::vector<double> c(2 * gamma_.size() - 1, 0.0);
  {
    std::vector<std::complex<double>> a(gamma_.size());
    std::complex<double>              dk = 1.0;
    for (size_t k = 0; k < gamma_.size(); ++k, dk *= d) a[k] = gamma_[k] * dk;
    for (size_t j = 0; j < a.size(); ++j)
      for (size_t k = 0; k < a.size(); ++k) c[j + k] += (a[j] * std::conj(a[k])).real();
  }
  auto square = [&](double x) { // |R(x d)|^2 - 1 by Horner, c_0 = 1 left out
    double p = 0;
    for (size_t n = c.size() - 1; n >= 1; --n) p = (p + c[n]) * x;
    return p;
  };
  // The polynomial's Taylor coefficients at x, a_k = P^(k)(x) / k! (k >= 1): P(x + t) <= P(x) +
  // sum_k |a_k| t^k for t >= 0, so below the bound by a margin m it stays below it for t up to
  // m / S(cap), S(cap) = sum_k |a_k| cap^(k-1), if that is at most cap. Near the crossing the
  // first term leads and a cap of a little more than m / |a_1| gives a leap close to Newton's
  // from the safe side (the bound of the coefficients at the ray's far end, before, leapt a
  // fixed fraction of the distance: about 600 evaluations per ray for RK4 on the real axis).
  std::vector<double> a(c.size());
  auto                taylor = [&](double x0) {
    for (size_t k = 1; k < c.size(); ++k) { // a_k = sum_{n >= k} binom(n, k) c_n x0^(n - k)
      double sum = 0, pw = 1, binom = 1;
      for (size_t n = k; n < c.size(); ++n, pw *= x0) {
        sum += binom * c[n] * pw;
        binom = binom * double(n + 1) / double(n + 1 - k);
      }
      a[k] = sum;
    }
  };
  auto slope = [&](double cap) {
    double S = 0, q = 1;
    for (size_t k = 1; k < a.size(); ++k, q *= cap) S += std::fabs(a[k]) * q;
    return S;
  };
  const double dx = 1e-3;
  double       x  = 0.0;
  while (x < kMaxRadius) {
    const double margin = (d.real() > 0 ? std::exp(2 * x * d.real()) : 1.0) - 1.0 - square(x);
    double       leap   = 0;
    if (margin > 0) {
      taylor(x);
      const double newton = a[1] > 0 ? 1.5 * margin / a[1] : 0.0;
      for (double cap : {newton, 0.25 * x + dx, x + dx, 1.0})
        if (cap > 0) leap = std::max(leap, std::min(cap, margin / slope(cap)));
    }
    if (leap > dx) {
      x = std::min(x + leap, kMaxRadius);
      continue;
    }
    if (!stable(x + dx)) break;
    x += dx;
  }
  if (x >= kMaxRadius) return kMaxRadius;
  double lo = x, hi = x + dx;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break; /* the bracket is two neighbouring doubles */
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

double StabilityFunction::largestStableStep(std::complex<double> lambda) const
{
  const double r = std::abs(lambda);
  if (r == 0.0) return std::numeric_limits<double>::infinity();
  return rayLimit(lambda) / r;
}

LevelAmplification levelAmplification(const StabilityFunction &R, const MesoscopicSchedule &schedule, double macroStep, int level, std::complex<double> lambda)
{
  LevelAmplification a;
  runMacroStep(schedule, macroStep, [&](int l, double, double h) {
    if (l == level) {
      a.logAmplification += std::log(std::abs(R(h * lambda))) - h * std::max(lambda.real(), 0.0);
      a.largestGrowth = std::max(a.largestGrowth, a.logAmplification);
      a.steps++;
      a.largestStep = std::max(a.largestStep, h);
    }
    return 0;
  });
  return a;
}

namespace {
// Calls f(|lambda|, |Re lambda|, oscillates, Re lambda) for every mode above 1e-8 of the largest
// |lambda| (the others are zero modes and not counted).
template <class F>
void forEachCountedMode(const std::vector<std::complex<double>> &modes, F f)
{
  double largest = 0;
  for (const std::complex<double> &lambda : modes) largest = std::max(largest, std::abs(lambda));
  for (const std::complex<double> &lambda : modes)
    if (std::abs(lambda) > 1e-8 * largest) f(std::abs(lambda), std::fabs(lambda.real()), oscillates(lambda), lambda.real());
}
} // namespace

double fastestGrowthRate(const std::vector<std::complex<double>> &modes, double noise)
{
  double fastest = 0;
  forEachCountedMode(modes, [&](double size, double, bool, double re) {
    if (re > noise * size) fastest = std::max(fastest, re);
  });
  return fastest;
}

double slowestAmplitudeRate(const std::vector<std::complex<double>> &modes, double noise)
{
  double slowest = std::numeric_limits<double>::infinity();
  forEachCountedMode(modes, [&](double size, double re, bool osc, double) {
    if (osc && re > noise * size) slowest = std::min(slowest, re);
  });
  return std::isfinite(slowest) ? slowest : 0.0;
}

AmplitudeRateNoise amplitudeRateNoise(double blockNorm, double largest, double stateNorm)
{
  AmplitudeRateNoise noise;
  if (!(largest > 0) || !std::isfinite(blockNorm) || !std::isfinite(stateNorm)) return noise;
  const double eps = std::numeric_limits<double>::epsilon(), scale = std::max(1.0, blockNorm / largest) * stateNorm / (1 + stateNorm);
  noise.forward = std::max(noise.forward, std::sqrt(eps) * scale);
  noise.central = std::max(noise.central, std::pow(eps, 2.0 / 3.0) * scale);
  return noise;
}

bool ambiguousAmplitudeRate(const std::vector<std::complex<double>> &modes, const AmplitudeRateNoise &noise)
{
  bool ambiguous = false;
  forEachCountedMode(modes, [&](double size, double re, bool osc, double) { ambiguous = ambiguous || (osc && re > noise.central * size && re <= noise.forward * size); });
  return ambiguous;
}

double slowestRate(const std::vector<std::complex<double>> &modes, double noise)
{
  double slowest = std::numeric_limits<double>::infinity();
  forEachCountedMode(modes, [&](double size, double re, bool osc, double) { slowest = std::min(slowest, (osc && re > noise * size) ? re : size); });
  return std::isfinite(slowest) ? slowest : 0.0;
}

double amplitudeError(const StabilityFunction &R, std::complex<double> lambda, double h)
{
  const std::complex<double> z = h * lambda;
  if (std::abs(z) <= 0.5) { /* log |R exp(-z)| = log |1 - u| = log1p(|1 - u|^2 - 1) / 2, accurate for small u */
    const std::complex<double> u = R.relativeDefect(z);
    return std::fabs(0.5 * std::log1p(std::norm(u) - 2 * u.real()));
  }
  const double a = std::abs(R(z));
  if (!(a > 0)) return std::numeric_limits<double>::infinity();
  return std::fabs(std::log(a) - z.real());
}

double phaseError(const StabilityFunction &R, std::complex<double> lambda, double h)
{
  const std::complex<double> z = h * lambda;
  if (std::abs(z) <= 0.5) { /* arg (R exp(-z)) = arg (1 - u), accurate for small u */
    const std::complex<double> u = R.relativeDefect(z);
    return std::fabs(std::atan2(-u.imag(), 1.0 - u.real()));
  }
  const std::complex<double> r = R(z);
  if (!(std::abs(r) > 0)) return std::numeric_limits<double>::infinity();
  const double d = std::remainder(std::arg(r) - h * lambda.imag(), 2 * 3.14159265358979323846); /* in [-pi, pi] */
  return std::fabs(d);
}

double largestAccurateStep(const StabilityFunction &R, const std::vector<std::complex<double>> &modes, double hMax, double stepsPerUnitStep, double allowed, double phaseWeight, double amplitudeStepsPerUnitStep)
{
  const double amplitudeSteps = amplitudeStepsPerUnitStep > 0 ? std::min(amplitudeStepsPerUnitStep, stepsPerUnitStep) : stepsPerUnitStep;
  auto         error          = [&](double h) {
    double e = 0;
    for (const std::complex<double> &lambda : modes) e = std::max(e, amplitudeError(R, lambda, h) * amplitudeSteps + (phaseWeight > 0 ? phaseWeight * phaseError(R, lambda, h) * stepsPerUnitStep : 0.0));
    return e / h;
  };
  if (!(hMax > 0) || modes.empty() || error(hMax) <= allowed) return hMax;
  double lo = hMax, hi = hMax;
  while (lo > hMax * 1e-12 && error(lo) > allowed) lo *= 0.5;
  if (error(lo) > allowed) return lo;
  while (hi / lo > 1.001) {
    const double mid                  = std::sqrt(lo * hi);
    (error(mid) <= allowed ? lo : hi) = mid;
  }
  return lo;
}

double largestStableSavingsFactor(const StabilityFunction &R, const Kernel &kernel, double microStep, std::vector<double> savings, const std::vector<int> &subintervals, double macroStep, int j, std::complex<double> lambda, double dampingTarget, double maxGrowth)
{
  double lo = 0, hi = savings.at(j - 1);
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    savings[j - 1]   = mid;
    const MesoscopicSchedule schedule(kernel, microStep, savings, subintervals);
    const LevelAmplification a                                                                          = levelAmplification(R, schedule, macroStep, j - 1, lambda);
    (a.logAmplification <= std::log(dampingTarget) && a.largestGrowth <= std::log(maxGrowth) ? lo : hi) = mid;
  }
  return lo;
}

double forcedResponse(const std::vector<double> &H, int n, int ld, double tau)
{
  const int           m = n + 1;
  std::vector<double> A(m * m, 0.0), T(m * m), P(m * m), W(m * m);
  auto                at       = [m](std::vector<double> &M, int i, int j) -> double                      &{ return M[i + j * m]; };
  auto                multiply = [m](const std::vector<double> &X, const std::vector<double> &Y, std::vector<double> &Z) {
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        double sum = 0;
        for (int l = 0; l < m; ++l) sum += X[i + l * m] * Y[l + j * m];
        Z[i + j * m] = sum;
      }
  };

  if (n <= 0 || !(tau > 0)) return 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) at(A, i, j) = tau * H[i + j * ld];
  at(A, 0, n) = tau;
  double norm = 0; /* the 1-norm */
  for (int j = 0; j < m; ++j) {
    double col = 0;
    for (int i = 0; i < m; ++i) col += std::abs(at(A, i, j));
    norm = std::max(norm, col);
  }
  if (!std::isfinite(norm)) return std::numeric_limits<double>::infinity();
  int squarings = 0;
  while (norm > 0.25 && squarings < 200) {
    norm /= 2;
    ++squarings;
  }
  for (double &a : A) a = std::ldexp(a, -squarings);
  /* exp(A) by its Taylor series to order 12 (||A|| <= 1/4: remainder below 1e-16) */
  std::fill(T.begin(), T.end(), 0.0);
  for (int i = 0; i < m; ++i) at(T, i, i) = 1.0;
  P = T;
  for (int k = 1; k <= 12; ++k) {
    multiply(P, A, W);
    for (int i = 0; i < m * m; ++i) {
      P[i] = W[i] / k;
      T[i] += P[i];
    }
  }
  for (int s = 0; s < squarings; ++s) {
    multiply(T, T, W);
    T.swap(W);
  }
  double response = 0;
  for (int i = 0; i < n; ++i) response += at(T, i, n) * at(T, i, n);
  return std::isfinite(response) ? std::sqrt(response) : std::numeric_limits<double>::infinity();
}

namespace {
// The frequencies of the oscillating modes (|Im| > |Re|, Im > 0) above fastAbove in |lambda|, ascending.
std::vector<double> fastFrequencies(const std::vector<std::complex<double>> &modes, double fastAbove)
{
  std::vector<double> omega;
  for (const std::complex<double> &lambda : modes)
    if (oscillates(lambda) && std::abs(lambda) > fastAbove && lambda.imag() > 0) omega.push_back(lambda.imag());
  std::sort(omega.begin(), omega.end());
  return omega;
}

// Ascending in frequency, one of those within kDistinctBeats of each other (the slowest).
template <class T>
std::vector<T> slowestDistinct(std::vector<T> found)
{
  std::vector<T> distinct;
  std::sort(found.begin(), found.end(), [](const T &a, const T &b) { return a.frequency < b.frequency; });
  for (const T &f : found)
    if (distinct.empty() || f.frequency > distinct.back().frequency * (1 + kDistinctBeats)) distinct.push_back(f);
  return distinct;
}
} // namespace

std::vector<Beat> beatFrequencies(const std::vector<std::complex<double>> &modes, double fastAbove, double separation)
{
  const std::vector<double> omega = fastFrequencies(modes, fastAbove);
  std::vector<Beat>         beats;
  for (size_t i = 0; i < omega.size(); ++i)
    for (size_t j = i + 1; j < omega.size(); ++j) {
      const double g = omega[j] - omega[i];
      if (g > kDistinctFrequencies * omega[j] && g * separation < omega[i]) beats.push_back({g, omega[i], omega[j]});
    }
  return slowestDistinct(beats);
}

namespace {
// Every choice of coefficients for the frequencies omega[first..] after `w`/`c` so far, the sum of
// the |c| reaching `left` more.
void addCombinations(const std::vector<double> &omega, size_t first, int left, std::vector<double> &w, std::vector<int> &c, double separation, std::vector<Combination> &found)
{
  if (left == 0) {
    /* a coefficient +-1 (the probe turns that mode by the combination's phase; up to order 4 it
       also leaves out the multiples of a beat, 2 w_a - 2 w_b) */
    if (c.size() < 2 || std::none_of(c.begin(), c.end(), [](int ci) { return std::abs(ci) == 1; })) return;
    double g = 0;
    for (size_t i = 0; i < w.size(); ++i) g += c[i] * w[i];
    g = std::fabs(g);
    if (g > kDistinctFrequencies * w.back() && g * separation < w.front()) found.push_back({g, w, c});
    return;
  }
  for (size_t i = first; i < omega.size(); ++i)
    for (int a = 1; a <= left; ++a)
      for (int sign : {1, -1}) {
        if (c.empty() && sign < 0) continue; /* the first coefficient positive: a combination and its negative are one */
        w.push_back(omega[i]);
        c.push_back(sign * a);
        addCombinations(omega, i + 1, left - a, w, c, separation, found);
        w.pop_back();
        c.pop_back();
      }
}
} // namespace

std::vector<Combination> slowCombinations(const std::vector<std::complex<double>> &modes, double fastAbove, double separation, int order)
{
  std::vector<double>      omega = fastFrequencies(modes, fastAbove);
  std::vector<Combination> found;
  std::vector<double>      w;
  std::vector<int>         c;
  omega.erase(std::unique(omega.begin(), omega.end(), [](double x, double y) { return std::fabs(y - x) <= kDistinctFrequencies * y; }), omega.end());
  addCombinations(omega, 0, order, w, c, separation, found);
  /* ascending in g, all kept: two combinations at one frequency are different products of the
     modes (1000, 1700, 2300, 2990: 3 w1 - w4 and w1 - w2 - w3 + w4 both at 10) */
  std::stable_sort(found.begin(), found.end(), [](const Combination &a, const Combination &b) { return a.frequency < b.frequency; });
  return found;
}

std::vector<double> modesTurned(const std::vector<double> &vr, const std::vector<std::complex<double>> &lambda, int n, const std::function<double(double)> &angle)
{
  using C = std::complex<double>;
  if (n <= 0 || (int)lambda.size() != n || (int)vr.size() < n * n) return {};
  /* the eigenvectors, complex (LAPACK's geev: a pair's real and imaginary parts in two columns) */
  std::vector<C> Y(n * n), A(n * n), c(n, 0.0);
  for (int j = 0; j < n; ++j) {
    if (lambda[j].imag() > 0 && j + 1 < n) {
      for (int i = 0; i < n; ++i) {
        Y[i + j * n]       = C(vr[i + j * n], vr[i + (j + 1) * n]);
        Y[i + (j + 1) * n] = std::conj(Y[i + j * n]);
      }
      ++j;
    } else
      for (int i = 0; i < n; ++i) Y[i + j * n] = vr[i + j * n];
  }
  /* Y c = e1 by Gaussian elimination with partial pivoting */
  A    = Y;
  c[0] = 1.0;
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(A[i + k * n]) > std::abs(A[p + k * n])) p = i;
    if (!(std::abs(A[p + k * n]) > 0)) return {};
    if (p != k) {
      for (int j = 0; j < n; ++j) std::swap(A[k + j * n], A[p + j * n]);
      std::swap(c[k], c[p]);
    }
    for (int i = k + 1; i < n; ++i) {
      const C m = A[i + k * n] / A[k + k * n];
      for (int j = k; j < n; ++j) A[i + j * n] -= m * A[k + j * n];
      c[i] -= m * c[k];
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    for (int j = k + 1; j < n; ++j) c[k] -= A[k + j * n] * c[j];
    c[k] /= A[k + k * n];
  }
  std::vector<double> y(n, 0.0);
  for (int j = 0; j < n; ++j) {
    const double omega = lambda[j].imag();
    const double phi   = omega == 0 ? 0.0 : (omega > 0 ? 1.0 : -1.0) * angle(std::abs(omega));
    const C      w     = c[j] * std::polar(1.0, phi);
    for (int i = 0; i < n; ++i) y[i] += (w * Y[i + j * n]).real();
  }
  for (double v : y)
    if (!std::isfinite(v)) return {};
  return y;
}

} // namespace vshmm
