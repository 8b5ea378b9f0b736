// The numerical core of the sparse spectral component (no PETSc): periodic 1-D Fourier
// pseudo-spectral problems on FFTW.
//
//   Grid:      N points x_j = 2 pi j / N, j = 0..N-1, on [0, 2 pi).
//   Modes:     nonnegative wavenumbers k = 0..N/2 (u is real: u_{-k} = conj(u_k)).
//   State:     Fourier series coefficients c_k = (1/N) sum_j u_j exp(-i k x_j), so that
//              u(x_j) = sum_k c_k exp(i k x_j) over k = -N/2+1..N/2 (independent of N).
//   Layout:    the retained coefficients as reals, cluster by cluster (slowest first), each
//              cluster in ascending k: Re c_k, Im c_k; k = 0 and k = N/2 (N even) store Re only.
//   Operator:  F(u) = d/dx( D(x) du/dx ) + A(x) du/dx  (D: sum of diffusion coefficients,
//              A = minus the sum of advection velocities), evaluated pseudo-spectrally:
//              u_x by a c2r transform of (i k c_k), products on the grid, r2c transforms,
//              and i k for the flux form. The derivative of the Nyquist mode is zero.
//              Optional further terms (ExtraTerms): -(B(x) u^2/2)_x (Burgers),
//              R(x) (r0 + r1 u + r2 u^2 + r3 u^3) (reaction), S(x) (source). The first two are
//              evaluated without aliasing on a padded grid of M > N points (see ExtraTerms).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vshmm {
namespace spectral {

// Wavenumbers of N points: 0..N/2. k is stored as one real if k = 0 or k = N/2 (N even).
inline int maxWavenumber(int N)
{
  return N / 2;
}
inline bool isRealOnly(int N, int k)
{
  return k == 0 || (N % 2 == 0 && k == N / 2);
}
inline int realsOf(int N, int k)
{
  return isRealOnly(N, k) ? 1 : 2;
}
// x_j = 2 pi j / N
double gridPoint(int N, int j);

// ---------------------------------------------------------------------------------------------
// Clusters: disjoint sets of nonnegative wavenumbers (each cluster stands for +-k).
struct ClusterSet {
  int                           N = 0;
  std::vector<std::vector<int>> clusters; // each sorted ascending, distinct

  // Parses "0:3,62:66,192:193,255:257": clusters separated by ',', a cluster is one or more
  // ranges joined by '+', a range is "k" or "lo:hi" (inclusive). Throws std::invalid_argument
  // with a message that names the bad item: an empty item (also a ',' or '+' at an end), a
  // wavenumber above N/2 (checked before a range is expanded), overlaps.
  static ClusterSet parse(const std::string &spec, int N);
  // Throws unless there is at least one cluster, none is empty, every k is in 0..N/2 and no
  // wavenumber is in two clusters.
  void validate() const;
  // Sorts the clusters by their lowest wavenumber (slowest first). Returns true if it changed the order.
  bool        sortByLowest();
  size_t      size() const { return clusters.size(); }
  std::string format() const; // "K0 = {0..3}, K1 = {62,63,65,66}"
};

// "0..3" for runs of 3 or more, "62,63,65,66" otherwise: a compact list of sorted wavenumbers.
std::string formatModes(const std::vector<int> &modes);

// ---------------------------------------------------------------------------------------------
// The real layout of the retained coefficients.
class Layout {
public:
  // The retained modes are the clusters' modes, cluster by cluster.
  Layout(const ClusterSet &clusters);
  // Every mode 0..N/2 as one cluster (the direct simulation): size() = N.
  static Layout full(int N);

  int                     N() const { return N_; }
  int                     size() const { return size_; }                   // number of reals
  int                     modeCount() const { return (int)modes_.size(); } // retained nonnegative wavenumbers
  int                     mode(int i) const { return modes_[i]; }          // i-th retained wavenumber
  int                     offset(int i) const { return offsets_[i]; }      // where mode i starts in the reals
  const std::vector<int> &modes() const { return modes_; }
  int                     clusterCount() const { return (int)clusterModeBegin_.size() - 1; }
  int                     clusterModeBegin(int j) const { return clusterModeBegin_[j]; } // modes [begin, end) of cluster j
  int                     clusterModeEnd(int j) const { return clusterModeBegin_[j + 1]; }
  int                     clusterOffsetBegin(int j) const { return offsets_[clusterModeBegin_[j]]; } // reals [begin, end)
  int                     clusterOffsetEnd(int j) const { return clusterModeEnd(j) < modeCount() ? offsets_[clusterModeEnd(j)] : size_; }
  // Index of wavenumber k in the layout, or -1.
  int indexOf(int k) const { return k >= 0 && k < (int)where_.size() ? where_[k] : -1; }

private:
  Layout() = default;
  void             finish();
  int              N_ = 0, size_ = 0;
  std::vector<int> modes_, offsets_, clusterModeBegin_, where_;
};

// ---------------------------------------------------------------------------------------------
// Parametrised periodic fields on [0, 2 pi): coefficient fields and initial data.
struct Series { // offset + sum_i (cos_i cos(k_i x) + sin_i sin(k_i x))
  double              offset = 0.0;
  std::vector<double> wavenumbers, cosines, sines;
  double              eval(double x) const;
};

struct Field {
  enum class Form {
    Constant,
    Gaussian,
    ExpSin,
    Fourier,
    ExpRatio,
    Samples
  };
  Form form = Form::Constant;
  // constant: value
  double value = 0.0;
  // gaussian: offset + amplitude exp(-((x - center)/width)^2); periodic: x - center wrapped to [-pi, pi)
  double offset = 0.0, amplitude = 1.0, center = 3.14159265358979323846, width = 1.0;
  bool   periodic = false;
  // expsin: offset + sum_i weights_i exp(amplitudes_i sin(wavenumbers_i x + phases_i))
  std::vector<double> weights, wavenumbers, amplitudes, phases;
  // fourier: the series `numerator`
  // exp_ratio: scale exp(numerator(x) / denominator(x)), denominator > 0 on the grid
  Series numerator, denominator;
  double scale = 1.0;
  // samples: values on the grid (length N)
  std::vector<double> samples;
  // a sum of forms: when not empty the field is the sum of these (form and the parameters
  // above are then unused)
  std::vector<Field> summands;

  static const char *formName(Form f);
  // A field of form f with its defaults: every parameter 0 or empty (a series term left out is
  // 0), except gaussian amplitude 1, center pi, width 1; expsin amplitudes 1 (empty list);
  // exp_ratio scale 1 and denominator offset 1.
  static Field ofForm(Form f);
  // Values at x_j, j = 0..N-1. Throws std::invalid_argument for inconsistent parameters,
  // a non-positive exp_ratio denominator or non-finite values (for a sum: naming the summand,
  // "summand 1 (expsin): ...", counted from 0).
  std::vector<double> sample(int N) const;
  std::string         describe() const;
};

// ---------------------------------------------------------------------------------------------
// FFTW r2c / c2r transforms of size N: plans made once, buffers owned.
enum class Planner {
  Estimate,
  Measure,
  Patient
};

class RealFFT {
public:
  RealFFT(int N, Planner planner);
  ~RealFFT();
  RealFFT(const RealFFT &)            = delete;
  RealFFT &operator=(const RealFFT &) = delete;
  int      N() const { return N_; }
  double  *real() { return real_; }     // N reals
  double  *spectrum() { return spec_; } // N/2+1 complex numbers as (re, im) pairs
  void     forward();                   // spectrum = sum_j real_j exp(-i k x_j) (unnormalised)
  void     inverse();                   // real_j = sum_k spectrum_k exp(i k x_j) (Hermitian); destroys spectrum

private:
  int     N_;
  double *real_ = nullptr, *spec_ = nullptr;
  void   *fwd_ = nullptr, *inv_ = nullptr;
};

// |c_k| for k = 0..N/2 of grid values u (series normalisation: u = sum c_k exp(i k x)).
std::vector<double> coefficientMagnitudes(const std::vector<double> &u);

// ---------------------------------------------------------------------------------------------
// Terms beside the linear ones (each field: values on the grid, size N, or empty when absent):
//   burgers   -(B(x) u^2 / 2)_x
//   reaction  R(x) (r0 + r1 u + r2 u^2 + r3 u^3)
//   source    S(x)
// Dealiasing: B and R stand for their trigonometric interpolants on the N grid (bandwidth kB,
// kR: their highest wavenumber above 1e-14 of their largest coefficient), u for its retained
// modes (highest ku). Their products are formed on a padded grid of M points,
// M > p ku + kf + kout and M > 2 ku (p the degree in u, kout = ku the highest retained
// wavenumber; in sparse mode M may be below N), so that the
// retained coefficients of the products are exact (no aliasing): the operator returns the
// projection of the term onto the retained modes. The source is added as its N-grid
// coefficients.
struct ExtraTerms {
  std::vector<double> burgers, rate, source;
  double              reaction[4] = {0, 0, 0, 0}; // r0..r3 (used when rate is given)
  bool                empty() const { return burgers.empty() && rate.empty() && source.empty(); }
  // Burgers, or a reaction of degree 2 or 3: the operator is not affine
  bool nonlinear() const { return !burgers.empty() || (!rate.empty() && (reaction[2] != 0.0 || reaction[3] != 0.0)); }
};

// The smallest even M >= n whose only prime factors are 2, 3 and 5 (FFTW's fast sizes).
int smoothSize(int n);

// ---------------------------------------------------------------------------------------------
// The operator F(u) = (D u_x)_x + A u_x (+ ExtraTerms) on the retained coefficients of a Layout.
class SpectralOperator {
public:
  struct Counters {
    std::int64_t inverse     = 0; // c2r transforms (one per physical evaluation)
    std::int64_t forward     = 0; // r2c transforms
    std::int64_t directModes = 0; // modes projected by direct sums over the grid
  };
  // D, A: values on the grid (size N) or empty when the term is absent (at least one given).
  SpectralOperator(const Layout &layout, std::vector<double> D, std::vector<double> A, Planner planner);
  // With the extra terms (Burgers, reaction, source); D and A may both be empty then.
  SpectralOperator(const Layout &layout, std::vector<double> D, std::vector<double> A, const ExtraTerms &extra, Planner planner);
  const Layout &layout() const { return layout_; }

  // Stage 1: u_x from the coefficients (one c2r), then W1 = D u_x and W0 = A u_x on the grid;
  // with Burgers or reaction terms also u on the padded grid (one c2r of size M) and the
  // products -B u^2/2, R (r0 + ... + r3 u^3) there.
  void computePhysical(const double *coef);
  // Stage 2, full: the r2c transform(s) of W1, W0 and of the padded products (one per present
  // term kind).
  void computeForward();
  // F on the modes [mb, me) of the layout from the forward transforms, into out at the modes'
  // offsets minus `base` (so a cluster may be written into its own array).
  void extractForward(int mb, int me, double *out, int base = 0) const;
  // F on the modes [mb, me) by direct sums over the grid (no forward transform): cost
  // (me - mb) N per present term kind. Not available with Burgers or reaction terms
  // (hasPadded()): throws std::logic_error.
  void projectDirect(int mb, int me, double *out, int base = 0);
  // F on every retained mode: computePhysical + computeForward + extractForward.
  void apply(const double *coef, double *out);

  // u on the grid from the retained coefficients, and the coefficients of u (restricted).
  void synthesize(const double *coef, double *u);
  void analyze(const double *u, double *coef);

  Counters &counters() { return counters_; }
  bool      hasDiffusion() const { return !D_.empty(); }
  bool      hasAdvection() const { return !A_.empty(); }
  bool      hasPadded() const { return padded_ > 0; } // Burgers or reaction terms
  bool      isNonlinear() const { return extra_.nonlinear(); }
  bool      hasSource() const { return !Sk_.empty(); }
  int       paddedSize() const { return padded_; } // M (0 without Burgers or reaction)
  // transforms per state: c2r in computePhysical(), r2c in computeForward()
  int inversePerState() const { return (inv_ ? 1 : 0) + (invM_ ? 1 : 0); }
  int forwardPerState() const { return (fw1_ ? 1 : 0) + (fw0_ ? 1 : 0) + (fwB_ ? 1 : 0) + (fwR_ ? 1 : 0); }
  // How many modes a direct projection can handle for the cost of one forward transform:
  // a flop-model estimate until setDirectModesPerForward() gives a measured value.
  double directModesPerForward() const { return directPerForward_; }
  void   setDirectModesPerForward(double r) { directPerForward_ = r; }

private:
  Layout                           layout_;
  int                              N_;
  std::vector<double>              D_, A_;
  std::unique_ptr<RealFFT>         inv_, fw1_, fw0_; // c2r; r2c of W1; r2c of W0
  ExtraTerms                       extra_;
  int                              padded_ = 0;       // M
  std::unique_ptr<RealFFT>         invM_, fwB_, fwR_; // size M: c2r of u; r2c of -B u^2/2; r2c of R p(u)
  std::vector<double>              Bm_, Rm_, Sk_;     // B, R on the padded grid; the source's coefficients per layout mode (re, im)
  std::vector<std::vector<double>> twiddle_;          // per layout mode, built on first use: cos, -sin interleaved by halves
  double                           directPerForward_ = 1.0;
  Counters                         counters_;
  const std::vector<double>       &twiddle(int i);
};

// A dense matrix of the (affine) operator restricted to the retained modes: rows and columns
// in the layout, F(c) = M c + b with b = F(0) (zero without source or reaction terms). Built by
// applying the pseudo-spectral operator to 0 and to unit vectors, so it gives the same numbers
// up to round-off; a cluster's rows cost (rows x layout size) flops. Throws
// std::invalid_argument for a nonlinear operator (Burgers, reaction of degree 2 or 3).
class DenseOperator {
public:
  explicit DenseOperator(SpectralOperator &op);
  // out[r - rb] = sum_c M[r][c] coef[c] (+ b[r]) for rows [rb, re)
  void applyRows(int rb, int re, const double *coef, double *out) const;
  int  size() const { return n_; }

private:
  int                 n_;
  bool                affine_ = false;
  std::vector<double> M_, b_; // row-major; b_ when affine_
};

} // namespace spectral
} // namespace vshmm
