// The numerical core of the sparse spectral component: clusters, layout, fields, FFTW
// transforms and the pseudo-spectral operator (no PETSc).
#include "spectral.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace vshmm {
namespace spectral {

static constexpr double kPi = 3.14159265358979323846;

double gridPoint(int N, int j)
{
  return 2.0 * kPi * (double)j / (double)N;
}

// ---------------------------------------------------------------------------------------------
// Clusters

static std::string trim(const std::string &s)
{
  size_t b = s.find_first_not_of(" \t\n\r"), e = s.find_last_not_of(" \t\n\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

static int parseWavenumber(const std::string &text, const std::string &item)
{
  const std::string t   = trim(text);
  size_t            pos = 0;
  long              v   = 0;
  bool              ok  = !t.empty();
  if (ok) {
    try {
      v  = std::stol(t, &pos, 10);
      ok = pos == t.size();
    } catch (const std::exception &) {
      ok = false;
    }
  }
  if (!ok) throw std::invalid_argument("cluster item '" + item + "': '" + t + "' is not a wavenumber (an integer)");
  if (v < 0) throw std::invalid_argument("cluster item '" + item + "': wavenumbers are nonnegative (a cluster stands for +-k)");
  if (v > 1000000000L) throw std::invalid_argument("cluster item '" + item + "': wavenumber too large");
  return (int)v;
}

// The parts of text between separators, empty ones included ("a," gives "a" and "").
static std::vector<std::string> splitAt(const std::string &text, char sep)
{
  std::vector<std::string> parts;
  size_t                   begin = 0;
  for (size_t end; (end = text.find(sep, begin)) != std::string::npos; begin = end + 1) parts.push_back(text.substr(begin, end - begin));
  parts.push_back(text.substr(begin));
  return parts;
}

ClusterSet ClusterSet::parse(const std::string &spec, int N)
{
  ClusterSet cs;
  cs.N = N;
  if (N < 2) throw std::invalid_argument("the grid needs at least 2 points, got N = " + std::to_string(N));
  if (trim(spec).empty()) throw std::invalid_argument("the cluster list is empty: give clusters as lo:hi ranges separated by commas, e.g. 0:3,62:66");
  const int kmax = maxWavenumber(N);
  for (const std::string &item : splitAt(spec, ',')) {
    if (trim(item).empty()) throw std::invalid_argument("the cluster list '" + spec + "' has an empty cluster (two commas in a row, or a comma at an end)");
    std::vector<int> c;
    for (const std::string &range : splitAt(item, '+')) {
      if (trim(range).empty()) throw std::invalid_argument("cluster item '" + trim(item) + "' has an empty range ('+' at an end, or two in a row)");
      const size_t colon = range.find(':');
      int          lo, hi;
      if (colon == std::string::npos) lo = hi = parseWavenumber(range, trim(item));
      else {
        lo = parseWavenumber(range.substr(0, colon), trim(item));
        hi = parseWavenumber(range.substr(colon + 1), trim(item));
      }
      if (hi < lo) throw std::invalid_argument("cluster item '" + trim(item) + "': the range " + std::to_string(lo) + ":" + std::to_string(hi) + " is empty (lo > hi)");
      // checked before the range is expanded: 0:999999999 must not allocate
      if (hi > kmax) {
        std::ostringstream m;
        m << "cluster item '" << trim(item) << "' has wavenumber " << hi << ", outside 0.." << kmax << " (N = " << N << " grid points resolve |k| <= N/2)";
        throw std::invalid_argument(m.str());
      }
      for (int k = lo; k <= hi; ++k) c.push_back(k);
    }
    std::sort(c.begin(), c.end());
    if (std::adjacent_find(c.begin(), c.end()) != c.end()) throw std::invalid_argument("cluster item '" + trim(item) + "' names a wavenumber twice");
    cs.clusters.push_back(c);
  }
  cs.validate();
  return cs;
}

void ClusterSet::validate() const
{
  if (N < 2) throw std::invalid_argument("the grid needs at least 2 points, got N = " + std::to_string(N));
  if (clusters.empty()) throw std::invalid_argument("the cluster list is empty: a sparse run needs at least one cluster");
  const int        kmax = maxWavenumber(N);
  std::vector<int> owner(kmax + 1, -1);
  for (size_t j = 0; j < clusters.size(); ++j) {
    if (clusters[j].empty()) throw std::invalid_argument("cluster K" + std::to_string(j) + " is empty");
    for (size_t i = 0; i < clusters[j].size(); ++i) {
      const int k = clusters[j][i];
      if (k < 0 || k > kmax) {
        std::ostringstream s;
        s << "cluster K" << j << " has wavenumber " << k << ", outside 0.." << kmax << " (N = " << N << " grid points resolve |k| <= N/2)";
        throw std::invalid_argument(s.str());
      }
      if (i > 0 && k <= clusters[j][i - 1]) throw std::invalid_argument("cluster K" + std::to_string(j) + " is not sorted or repeats a wavenumber");
      if (owner[k] >= 0) {
        std::ostringstream s;
        s << "clusters K" << owner[k] << " and K" << j << " overlap: both contain wavenumber " << k;
        throw std::invalid_argument(s.str());
      }
      owner[k] = (int)j;
    }
  }
}

bool ClusterSet::sortByLowest()
{
  auto lowest  = [](const std::vector<int> &a, const std::vector<int> &b) { return a.front() < b.front(); };
  bool changed = !std::is_sorted(clusters.begin(), clusters.end(), lowest);
  std::stable_sort(clusters.begin(), clusters.end(), lowest);
  return changed;
}

std::string formatModes(const std::vector<int> &modes)
{
  std::ostringstream s;
  size_t             i     = 0;
  bool               first = true;
  while (i < modes.size()) {
    size_t j = i;
    while (j + 1 < modes.size() && modes[j + 1] == modes[j] + 1) ++j;
    if (!first) s << ",";
    first = false;
    if (j >= i + 2) {
      s << modes[i] << ".." << modes[j];
      i = j + 1;
    } else {
      s << modes[i];
      ++i;
    }
  }
  return s.str();
}

std::string ClusterSet::format() const
{
  std::ostringstream s;
  for (size_t j = 0; j < clusters.size(); ++j) s << (j ? ", " : "") << "K" << j << " = {" << formatModes(clusters[j]) << "}";
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Layout

Layout::Layout(const ClusterSet &clusters)
{
  clusters.validate();
  N_ = clusters.N;
  clusterModeBegin_.push_back(0);
  for (const auto &c : clusters.clusters) {
    modes_.insert(modes_.end(), c.begin(), c.end());
    clusterModeBegin_.push_back((int)modes_.size());
  }
  finish();
}

Layout Layout::full(int N)
{
  if (N < 2) throw std::invalid_argument("the grid needs at least 2 points, got N = " + std::to_string(N));
  Layout l;
  l.N_ = N;
  for (int k = 0; k <= maxWavenumber(N); ++k) l.modes_.push_back(k);
  l.clusterModeBegin_ = {0, (int)l.modes_.size()};
  l.finish();
  return l;
}

void Layout::finish()
{
  offsets_.resize(modes_.size());
  where_.assign(maxWavenumber(N_) + 1, -1);
  size_ = 0;
  for (size_t i = 0; i < modes_.size(); ++i) {
    offsets_[i]       = size_;
    where_[modes_[i]] = (int)i;
    size_ += realsOf(N_, modes_[i]);
  }
}

// ---------------------------------------------------------------------------------------------
// Fields

double Series::eval(double x) const
{
  double v = offset;
  for (size_t i = 0; i < wavenumbers.size(); ++i) {
    if (!cosines.empty()) v += cosines[i] * std::cos(wavenumbers[i] * x);
    if (!sines.empty()) v += sines[i] * std::sin(wavenumbers[i] * x);
  }
  return v;
}

static void checkSeries(const Series &s, const char *what)
{
  const size_t n = s.wavenumbers.size();
  if ((!s.cosines.empty() && s.cosines.size() != n) || (!s.sines.empty() && s.sines.size() != n)) {
    std::ostringstream m;
    m << what << ": " << n << " wavenumbers but " << s.cosines.size() << " cosine and " << s.sines.size() << " sine coefficients (give one per wavenumber, or none)";
    throw std::invalid_argument(m.str());
  }
}

static const char *const kFormNames[] = {"constant", "gaussian", "expsin", "fourier", "exp_ratio", "samples"};

const char *Field::formName(Form f)
{
  return kFormNames[(int)f];
}

Field Field::ofForm(Form f)
{
  Field field;
  field.form = f;
  if (f == Form::ExpRatio) field.denominator.offset = 1.0; // exp(num / 1): a denominator of 0 is never meant
  return field;
}

std::vector<double> Field::sample(int N) const
{
  std::vector<double> v(N);
  if (!summands.empty()) {
    std::fill(v.begin(), v.end(), 0.0);
    for (size_t i = 0; i < summands.size(); ++i) {
      std::vector<double> w;
      try {
        w = summands[i].sample(N);
      } catch (const std::invalid_argument &e) {
        throw std::invalid_argument("summand " + std::to_string(i) + " (" + formName(summands[i].form) + "): " + e.what());
      }
      for (int j = 0; j < N; ++j) v[j] += w[j];
    }
    return v;
  }
  switch (form) {
  case Form::Constant:
    std::fill(v.begin(), v.end(), value);
    break;
  case Form::Gaussian:
    if (!(width > 0.0)) throw std::invalid_argument("gaussian: the width must be positive");
    for (int j = 0; j < N; ++j) {
      double d = gridPoint(N, j) - center;
      if (periodic) d -= 2.0 * kPi * std::floor((d + kPi) / (2.0 * kPi));
      v[j] = offset + amplitude * std::exp(-(d / width) * (d / width));
    }
    break;
  case Form::ExpSin: {
    const size_t n = weights.size();
    if (n == 0) throw std::invalid_argument("expsin: give at least one weight");
    if (wavenumbers.size() != n || (!amplitudes.empty() && amplitudes.size() != n) || (!phases.empty() && phases.size() != n)) {
      std::ostringstream m;
      m << "expsin: " << n << " weights but " << wavenumbers.size() << " wavenumbers, " << amplitudes.size() << " amplitudes, " << phases.size() << " phases (wavenumbers: one per weight; amplitudes, phases: one per weight or none)";
      throw std::invalid_argument(m.str());
    }
    for (int j = 0; j < N; ++j) {
      const double x = gridPoint(N, j);
      double       s = offset;
      for (size_t i = 0; i < n; ++i) s += weights[i] * std::exp((amplitudes.empty() ? 1.0 : amplitudes[i]) * std::sin(wavenumbers[i] * x + (phases.empty() ? 0.0 : phases[i])));
      v[j] = s;
    }
  } break;
  case Form::Fourier:
    checkSeries(numerator, "fourier");
    for (int j = 0; j < N; ++j) v[j] = numerator.eval(gridPoint(N, j));
    break;
  case Form::ExpRatio:
    checkSeries(numerator, "exp_ratio numerator");
    checkSeries(denominator, "exp_ratio denominator");
    for (int j = 0; j < N; ++j) {
      const double x = gridPoint(N, j), den = denominator.eval(x);
      if (!(den > 0.0)) {
        std::ostringstream m;
        m << "exp_ratio: the denominator is " << den << " <= 0 at x = " << x << ": it must be positive on the whole grid";
        throw std::invalid_argument(m.str());
      }
      v[j] = scale * std::exp(numerator.eval(x) / den);
    }
    break;
  case Form::Samples:
    if ((int)samples.size() != N) throw std::invalid_argument("samples: " + std::to_string(samples.size()) + " values for a grid of N = " + std::to_string(N) + " points");
    v = samples;
    break;
  }
  for (int j = 0; j < N; ++j)
    if (!std::isfinite(v[j])) throw std::invalid_argument(std::string(formName(form)) + ": the field is not finite at x = " + std::to_string(gridPoint(N, j)));
  return v;
}

static std::string list(const std::vector<double> &v)
{
  std::ostringstream s;
  for (size_t i = 0; i < v.size(); ++i) s << (i ? "," : "") << v[i];
  return s.str();
}

static std::string describeSeries(const Series &s)
{
  std::ostringstream m;
  m << s.offset;
  for (size_t i = 0; i < s.wavenumbers.size(); ++i) {
    if (!s.cosines.empty() && s.cosines[i] != 0.0) m << " + " << s.cosines[i] << " cos(" << s.wavenumbers[i] << "x)";
    if (!s.sines.empty() && s.sines[i] != 0.0) m << " + " << s.sines[i] << " sin(" << s.wavenumbers[i] << "x)";
  }
  return m.str();
}

std::string Field::describe() const
{
  std::ostringstream s;
  if (!summands.empty()) {
    for (size_t i = 0; i < summands.size(); ++i) s << (i ? " + " : "") << "[" << summands[i].describe() << "]";
    return s.str();
  }
  switch (form) {
  case Form::Constant:
    s << "constant " << value;
    break;
  case Form::Gaussian:
    s << "gaussian " << offset << " + " << amplitude << " exp(-((x - " << center << ")/" << width << ")^2)" << (periodic ? " (periodic distance)" : "");
    break;
  case Form::ExpSin:
    s << "expsin offset " << offset << " weights " << list(weights) << " wavenumbers " << list(wavenumbers) << " amplitudes " << (amplitudes.empty() ? std::string("1") : list(amplitudes)) << " phases " << (phases.empty() ? std::string("0") : list(phases));
    break;
  case Form::Fourier:
    s << "fourier " << describeSeries(numerator);
    break;
  case Form::ExpRatio:
    s << "exp_ratio " << scale << " exp((" << describeSeries(numerator) << ") / (" << describeSeries(denominator) << "))";
    break;
  case Form::Samples:
    s << "samples (" << samples.size() << " grid values)";
    break;
  }
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// FFTW transforms

static unsigned plannerFlags(Planner p)
{
  switch (p) {
  case Planner::Estimate:
    return FFTW_ESTIMATE;
  case Planner::Patient:
    return FFTW_PATIENT;
  default:
    return FFTW_MEASURE;
  }
}

RealFFT::RealFFT(int N, Planner planner) : N_(N)
{
  if (N < 2) throw std::invalid_argument("the grid needs at least 2 points, got N = " + std::to_string(N));
  real_ = fftw_alloc_real((size_t)N);
  spec_ = (double *)fftw_alloc_complex((size_t)(N / 2 + 1));
  if (!real_ || !spec_) throw std::bad_alloc();
  const unsigned flags = plannerFlags(planner);
  fwd_                 = fftw_plan_dft_r2c_1d(N, real_, (fftw_complex *)spec_, flags);
  inv_                 = fftw_plan_dft_c2r_1d(N, (fftw_complex *)spec_, real_, flags);
  if (!fwd_ || !inv_) throw std::runtime_error("FFTW could not make the plans for N = " + std::to_string(N));
  std::memset(real_, 0, sizeof(double) * N);
  std::memset(spec_, 0, sizeof(double) * 2 * (N / 2 + 1));
}

RealFFT::~RealFFT()
{
  if (fwd_) fftw_destroy_plan((fftw_plan)fwd_);
  if (inv_) fftw_destroy_plan((fftw_plan)inv_);
  fftw_free(real_);
  fftw_free(spec_);
}

void RealFFT::forward()
{
  fftw_execute((fftw_plan)fwd_);
}
void RealFFT::inverse()
{
  fftw_execute((fftw_plan)inv_);
}

// ---------------------------------------------------------------------------------------------
// The operator

int smoothSize(int n)
{
  for (int m = std::max(n, 2) + (std::max(n, 2) % 2);; m += 2) {
    int r = m;
    for (int p : {2, 3, 5})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

// The highest wavenumber of grid values f whose coefficient exceeds 1e-14 of the largest.
static int bandwidth(const std::vector<double> &f)
{
  const std::vector<double> m   = coefficientMagnitudes(f);
  const double              big = *std::max_element(m.begin(), m.end());
  int                       k   = 0;
  for (int i = 0; i < (int)m.size(); ++i)
    if (m[i] > 1e-14 * big) k = i;
  return k;
}

// The trigonometric interpolant of grid values f (N points) at the M points 2 pi j / M (the
// Nyquist coefficient of an even N split evenly between +-N/2). Summed directly over the
// coefficients above 1e-14 of the largest (a coefficient field's few harmonics: e^{sin 64x} has
// about 15) with the angles k j mod M from a table of M; where that sum would cost more than
// kDirectInterpolation multiply-adds, synthesised by FFT on L > N points, L a multiple of M, and
// sampled every L/M points. The FFT path plans a transform of a size used nowhere else, 1-3 ms
// of FFTW's estimate planner (the nonlinear scene's set-up: 3.5-5.5 of its 9.7 ms).
static constexpr double kDirectInterpolation = 1 << 20;

static std::vector<double> interpolate(const std::vector<double> &f, int M)
{
  const int N = (int)f.size();
  RealFFT   a(N, Planner::Estimate);
  std::memcpy(a.real(), f.data(), sizeof(double) * N);
  a.forward();
  std::vector<double> re(N / 2 + 1), im(N / 2 + 1);
  double              big = 0;
  for (int k = 0; k <= N / 2; ++k) {
    const double w = (N % 2 == 0 && k == N / 2 && k > 0) ? 0.5 : 1.0;
    re[k]          = w * a.spectrum()[2 * k] / N;
    im[k]          = (N % 2 == 0 && k == N / 2) ? 0.0 : a.spectrum()[2 * k + 1] / N;
    big            = std::max(big, std::hypot(re[k], im[k]));
  }
  std::vector<int> used;
  for (int k = 1; k <= N / 2; ++k)
    if (std::hypot(re[k], im[k]) > 1e-14 * big) used.push_back(k);
  std::vector<double> v(M, re[0]);
  if ((double)used.size() * M <= kDirectInterpolation) {
    std::vector<double> c(M), sn(M);
    for (int m = 0; m < M; ++m) c[m] = std::cos(2 * kPi * m / M), sn[m] = std::sin(2 * kPi * m / M);
    for (int k : used)
      for (int j = 0; j < M; ++j) {
        const int m = (int)(((long long)k * j) % M);
        v[j] += 2 * (re[k] * c[m] - im[k] * sn[m]);
      }
    return v;
  }
  int L = M;
  while (L <= N) L += M;
  RealFFT b(L, Planner::Estimate);
  double *s = b.spectrum();
  std::memset(s, 0, sizeof(double) * 2 * (L / 2 + 1));
  for (int k = 0; k <= N / 2; ++k) s[2 * k] = re[k], s[2 * k + 1] = im[k];
  b.inverse();
  for (int j = 0; j < M; ++j) v[j] = b.real()[(size_t)j * (L / M)];
  return v;
}

SpectralOperator::SpectralOperator(const Layout &layout, std::vector<double> D, std::vector<double> A, Planner planner) : SpectralOperator(layout, std::move(D), std::move(A), ExtraTerms(), planner) {}

SpectralOperator::SpectralOperator(const Layout &layout, std::vector<double> D, std::vector<double> A, const ExtraTerms &extra, Planner planner) : layout_(layout), N_(layout.N()), D_(std::move(D)), A_(std::move(A)), extra_(extra)
{
  if (D_.empty() && A_.empty() && extra_.empty()) throw std::invalid_argument("the operator has no term: give a diffusion coefficient, a velocity, a Burgers coefficient, a reaction rate or a source");
  for (const std::vector<double> *f : {&D_, &A_, &extra_.burgers, &extra_.rate, &extra_.source})
    if (!f->empty() && (int)f->size() != N_) throw std::invalid_argument("coefficient fields must have N values");
  if (!D_.empty() || !A_.empty()) inv_ = std::make_unique<RealFFT>(N_, planner);
  if (!D_.empty()) fw1_ = std::make_unique<RealFFT>(N_, planner);
  if (!A_.empty()) fw0_ = std::make_unique<RealFFT>(N_, planner);
  if (!extra_.burgers.empty() || !extra_.rate.empty()) {
    // M > p ku + kf + kout: the retained coefficients of f u^p are free of aliasing (and
    // M > 2 ku: u's modes fit on the padded grid)
    const int ku   = layout_.modes().empty() ? 0 : *std::max_element(layout_.modes().begin(), layout_.modes().end());
    int       need = 2 * ku + 2;
    if (!extra_.burgers.empty()) need = std::max(need, 2 * ku + bandwidth(extra_.burgers) + ku + 1);
    if (!extra_.rate.empty()) {
      int p = 0;
      for (int d = 1; d <= 3; ++d)
        if (extra_.reaction[d] != 0.0) p = d;
      need = std::max(need, p * ku + bandwidth(extra_.rate) + ku + 1);
    }
    padded_ = smoothSize(need);
    invM_   = std::make_unique<RealFFT>(padded_, planner);
    if (!extra_.burgers.empty()) {
      fwB_ = std::make_unique<RealFFT>(padded_, planner);
      Bm_  = interpolate(extra_.burgers, padded_);
      for (double &b : Bm_) b *= -0.5;
    }
    if (!extra_.rate.empty()) {
      fwR_ = std::make_unique<RealFFT>(padded_, planner);
      Rm_  = interpolate(extra_.rate, padded_);
    }
  }
  if (!extra_.source.empty()) {
    RealFFT f(N_, Planner::Estimate);
    std::memcpy(f.real(), extra_.source.data(), sizeof(double) * N_);
    f.forward();
    Sk_.resize(2 * (size_t)layout_.modeCount());
    for (int i = 0; i < layout_.modeCount(); ++i) {
      const int k    = layout_.mode(i);
      Sk_[2 * i]     = f.spectrum()[2 * k] / N_;
      Sk_[2 * i + 1] = isRealOnly(N_, k) ? 0.0 : f.spectrum()[2 * k + 1] / N_;
    }
  }
  twiddle_.resize(layout_.modeCount());
  // Flop model: an r2c transform of N reals ~ 2.5 N log2 N flops, a direct projection of one
  // mode ~ 4 N flops. The PETSc glue replaces it by a measured ratio.
  directPerForward_ = 2.5 * std::log2((double)N_) / 4.0;
}

// cos(k x_j) in [0, N), -sin(k x_j) in [N, 2N), for the layout's mode i (exact angles from k j mod N)
const std::vector<double> &SpectralOperator::twiddle(int i)
{
  std::vector<double> &t = twiddle_[i];
  if (t.empty()) {
    const int k = layout_.mode(i);
    t.resize(2 * (size_t)N_);
    long idx = 0;
    for (int j = 0; j < N_; ++j) {
      t[j]      = std::cos(gridPoint(N_, (int)idx));
      t[N_ + j] = -std::sin(gridPoint(N_, (int)idx));
      idx       = (idx + k) % N_;
    }
  }
  return t;
}

void SpectralOperator::computePhysical(const double *coef)
{
  if (invM_) {
    // u on the padded grid: the retained modes as they are, the Nyquist mode of an even N
    // (c cos(N x / 2) on the N grid) as c/2 at +-N/2
    double *s = invM_->spectrum();
    std::memset(s, 0, sizeof(double) * 2 * (padded_ / 2 + 1));
    for (int i = 0; i < layout_.modeCount(); ++i) {
      const int k = layout_.mode(i);
      if (isRealOnly(N_, k)) s[2 * k] = k ? 0.5 * coef[layout_.offset(i)] : coef[layout_.offset(i)];
      else {
        s[2 * k]     = coef[layout_.offset(i)];
        s[2 * k + 1] = coef[layout_.offset(i) + 1];
      }
    }
    invM_->inverse();
    const double *u = invM_->real();
    if (fwB_) {
      double *w = fwB_->real();
      for (int j = 0; j < padded_; ++j) w[j] = Bm_[j] * u[j] * u[j];
    }
    if (fwR_) {
      const double *r = extra_.reaction;
      double       *w = fwR_->real();
      for (int j = 0; j < padded_; ++j) w[j] = Rm_[j] * (r[0] + u[j] * (r[1] + u[j] * (r[2] + u[j] * r[3])));
    }
    counters_.inverse++;
  }
  if (!inv_) return;
  double *s = inv_->spectrum();
  std::memset(s, 0, sizeof(double) * 2 * (N_ / 2 + 1));
  const int n = layout_.modeCount();
  for (int i = 0; i < n; ++i) {
    const int k = layout_.mode(i);
    if (isRealOnly(N_, k)) continue; // k = 0 and the Nyquist mode have no derivative
    const double a = coef[layout_.offset(i)], b = coef[layout_.offset(i) + 1];
    s[2 * k]     = -k * b; // i k (a + i b)
    s[2 * k + 1] = k * a;
  }
  inv_->inverse();
  const double *ux = inv_->real();
  if (fw1_) {
    double *w = fw1_->real();
    for (int j = 0; j < N_; ++j) w[j] = D_[j] * ux[j];
  }
  if (fw0_) {
    double *w = fw0_->real();
    for (int j = 0; j < N_; ++j) w[j] = A_[j] * ux[j];
  }
  counters_.inverse++;
}

void SpectralOperator::computeForward()
{
  if (fw1_) {
    fw1_->forward();
    counters_.forward++;
  }
  if (fw0_) {
    fw0_->forward();
    counters_.forward++;
  }
  for (RealFFT *f : {fwB_.get(), fwR_.get()})
    if (f) {
      f->forward();
      counters_.forward++;
    }
}

// F_k = i k S1_k + S0_k (S = transform / N); the derivative of the Nyquist mode is zero.
static inline void storeMode(int N, int k, double s1r, double s1i, double s0r, double s0i, double *o)
{
  const double kk = isRealOnly(N, k) ? 0.0 : (double)k;
  const double re = -kk * s1i + s0r, im = kk * s1r + s0i;
  o[0] = re;
  if (!isRealOnly(N, k)) o[1] = im;
}

void SpectralOperator::extractForward(int mb, int me, double *out, int base) const
{
  const double  invN = 1.0 / N_;
  const double *s1 = fw1_ ? fw1_->spectrum() : nullptr, *s0 = fw0_ ? fw0_->spectrum() : nullptr;
  if (!padded_ && Sk_.empty()) { // the linear terms alone
    for (int i = mb; i < me; ++i) {
      const int k = layout_.mode(i);
      storeMode(N_, k, s1 ? s1[2 * k] * invN : 0.0, s1 ? s1[2 * k + 1] * invN : 0.0, s0 ? s0[2 * k] * invN : 0.0, s0 ? s0[2 * k + 1] * invN : 0.0, out + layout_.offset(i) - base);
    }
    return;
  }
  const double  invM = padded_ ? 1.0 / padded_ : 0.0;
  const double *sB = fwB_ ? fwB_->spectrum() : nullptr, *sR = fwR_ ? fwR_->spectrum() : nullptr;
  for (int i = mb; i < me; ++i) {
    const int k = layout_.mode(i);
    // flux terms (times i k) and direct terms; the Nyquist mode of an even N holds the
    // coefficients of +-N/2 together: twice the real part of the padded coefficient
    double fr = s1 ? s1[2 * k] * invN : 0.0, fi = s1 ? s1[2 * k + 1] * invN : 0.0;
    double dr = s0 ? s0[2 * k] * invN : 0.0, di = s0 ? s0[2 * k + 1] * invN : 0.0;
    if (sB) fr += sB[2 * k] * invM, fi += sB[2 * k + 1] * invM;
    if (sR) {
      const double w = (isRealOnly(N_, k) && k > 0) ? 2.0 : 1.0;
      dr += w * sR[2 * k] * invM, di += sR[2 * k + 1] * invM;
    }
    if (!Sk_.empty()) dr += Sk_[2 * i], di += Sk_[2 * i + 1];
    storeMode(N_, k, fr, fi, dr, di, out + layout_.offset(i) - base);
  }
}

// re = sum w c, im = sum w s, with four partial sums (instruction-level parallelism).
static inline void dot2(const double *w, const double *c, const double *s, int n, double &re, double &im)
{
  double r[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0};
  int    j = 0;
  for (; j + 4 <= n; j += 4)
    for (int u = 0; u < 4; ++u) {
      r[u] += w[j + u] * c[j + u];
      q[u] += w[j + u] * s[j + u];
    }
  for (; j < n; ++j) {
    r[0] += w[j] * c[j];
    q[0] += w[j] * s[j];
  }
  re = (r[0] + r[1]) + (r[2] + r[3]);
  im = (q[0] + q[1]) + (q[2] + q[3]);
}

void SpectralOperator::projectDirect(int mb, int me, double *out, int base)
{
  if (padded_) throw std::logic_error("direct projections are not available with Burgers or reaction terms: project by FFT");
  const double  invN = 1.0 / N_;
  const double *w1 = fw1_ ? fw1_->real() : nullptr, *w0 = fw0_ ? fw0_->real() : nullptr;
  for (int i = mb; i < me; ++i) {
    const int                  k  = layout_.mode(i);
    const std::vector<double> &tw = twiddle(i);
    const double              *c = tw.data(), *s = tw.data() + N_;
    double                     r1 = 0, i1 = 0, r0 = 0, i0 = 0;
    if (w1) dot2(w1, c, s, N_, r1, i1);
    if (w0) dot2(w0, c, s, N_, r0, i0);
    if (Sk_.empty()) storeMode(N_, k, r1 * invN, i1 * invN, r0 * invN, i0 * invN, out + layout_.offset(i) - base);
    else storeMode(N_, k, r1 * invN, i1 * invN, r0 * invN + Sk_[2 * i], i0 * invN + Sk_[2 * i + 1], out + layout_.offset(i) - base);
  }
  counters_.directModes += me - mb;
}

void SpectralOperator::apply(const double *coef, double *out)
{
  computePhysical(coef);
  computeForward();
  extractForward(0, layout_.modeCount(), out);
}

void SpectralOperator::synthesize(const double *coef, double *u)
{
  RealFFT fft(N_, Planner::Estimate);
  double *s = fft.spectrum();
  for (int i = 0; i < layout_.modeCount(); ++i) {
    const int k  = layout_.mode(i);
    s[2 * k]     = coef[layout_.offset(i)];
    s[2 * k + 1] = isRealOnly(N_, k) ? 0.0 : coef[layout_.offset(i) + 1];
  }
  fft.inverse();
  std::memcpy(u, fft.real(), sizeof(double) * N_);
}

void SpectralOperator::analyze(const double *u, double *coef)
{
  RealFFT fft(N_, Planner::Estimate);
  std::memcpy(fft.real(), u, sizeof(double) * N_);
  fft.forward();
  const double *s = fft.spectrum();
  for (int i = 0; i < layout_.modeCount(); ++i) {
    const int k             = layout_.mode(i);
    coef[layout_.offset(i)] = s[2 * k] / N_;
    if (!isRealOnly(N_, k)) coef[layout_.offset(i) + 1] = s[2 * k + 1] / N_;
  }
}

std::vector<double> coefficientMagnitudes(const std::vector<double> &u)
{
  const int N_ = (int)u.size();
  RealFFT   fft(N_, Planner::Estimate);
  std::memcpy(fft.real(), u.data(), sizeof(double) * N_);
  fft.forward();
  const double       *s = fft.spectrum();
  std::vector<double> m(N_ / 2 + 1);
  for (int k = 0; k <= N_ / 2; ++k) m[k] = std::hypot(s[2 * k], s[2 * k + 1]) / N_;
  return m;
}

// ---------------------------------------------------------------------------------------------

DenseOperator::DenseOperator(SpectralOperator &op) : n_(op.layout().size()), M_((size_t)n_ * n_)
{
  if (op.isNonlinear()) throw std::invalid_argument("the operator is nonlinear (Burgers, or a reaction of degree 2 or 3): a matrix holds linear and affine operators only");
  std::vector<double> e(n_, 0.0), col(n_);
  affine_ = op.hasPadded() || op.hasSource();
  if (affine_) {
    b_.resize(n_);
    op.apply(e.data(), b_.data());
  }
  for (int c = 0; c < n_; ++c) {
    e[c] = 1.0;
    op.apply(e.data(), col.data());
    e[c] = 0.0;
    for (int r = 0; r < n_; ++r) M_[(size_t)r * n_ + c] = affine_ ? col[r] - b_[r] : col[r];
  }
}

void DenseOperator::applyRows(int rb, int re, const double *coef, double *out) const
{
  for (int r = rb; r < re; ++r) {
    const double *m = &M_[(size_t)r * n_];
    double        s = 0.0;
    for (int c = 0; c < n_; ++c) s += m[c] * coef[c];
    out[r - rb] = affine_ ? s + b_[r] : s;
  }
}

} // namespace spectral
} // namespace vshmm
