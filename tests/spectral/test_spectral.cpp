// Unit tests of the sparse spectral core (src/spectral): transforms and projections against
// direct sums, the sparse right-hand side against the full one, clusters, detection, fields.
#include <gtest/gtest.h>

#include "detect.hpp"
#include "spectral.hpp"

#include <cmath>
#include <complex>
#include <limits>
#include <random>

using namespace vshmm::spectral;
using cplx = std::complex<double>;

static constexpr double kPi = 3.14159265358979323846;

static std::vector<double> randomVector(int n, unsigned seed)
{
  std::mt19937                           g(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<double>                    v(n);
  for (double &x : v) x = d(g);
  return v;
}

// Complex coefficients c_k (k = 0..N/2) of a real layout vector (zero for modes not retained).
static std::vector<cplx> toComplex(const Layout &l, const std::vector<double> &v)
{
  std::vector<cplx> c(l.N() / 2 + 1, 0.0);
  for (int i = 0; i < l.modeCount(); ++i) {
    const int k = l.mode(i);
    c[k]        = cplx(v[l.offset(i)], isRealOnly(l.N(), k) ? 0.0 : v[l.offset(i) + 1]);
  }
  return c;
}

// The pseudo-spectral operator by direct sums (O(N^2)):
//   ux_j = sum_{k=-N/2+1}^{N/2} (i k c_k) e^{i k x_j} (Nyquist derivative zero),
//   F_k = i k DFT(D ux)_k / N + DFT(A ux)_k / N.
static std::vector<cplx> directOperator(int N, const std::vector<cplx> &c, const std::vector<double> &D, const std::vector<double> &A)
{
  std::vector<double> ux(N, 0.0);
  for (int j = 0; j < N; ++j) {
    const double x = gridPoint(N, j);
    double       s = 0;
    for (int k = 1; k <= N / 2; ++k) {
      if (isRealOnly(N, k)) continue;
      s += 2.0 * std::real(cplx(0, k) * c[k] * std::exp(cplx(0, k * x)));
    }
    ux[j] = s;
  }
  std::vector<cplx> F(N / 2 + 1, 0.0);
  for (int k = 0; k <= N / 2; ++k) {
    cplx s1 = 0, s0 = 0;
    for (int j = 0; j < N; ++j) {
      const cplx e = std::exp(cplx(0, -2.0 * kPi * (double)k * j / N));
      if (!D.empty()) s1 += D[j] * ux[j] * e;
      if (!A.empty()) s0 += A[j] * ux[j] * e;
    }
    const double kk = isRealOnly(N, k) ? 0.0 : (double)k;
    F[k]            = cplx(0, kk) * s1 / (double)N + s0 / (double)N;
    if (isRealOnly(N, k)) F[k] = cplx(F[k].real(), 0.0);
  }
  return F;
}

// ---------------------------------------------------------------------------------------------

TEST(Layout, RealLayout)
{
  for (int N : {16, 15}) {
    Layout full = Layout::full(N);
    EXPECT_EQ(full.size(), N); // N reals: k = 0 (and k = N/2 for even N) store Re only
    EXPECT_EQ(full.modeCount(), N / 2 + 1);
    EXPECT_EQ(full.offset(0), 0);
    EXPECT_EQ(full.offset(1), 1);
    EXPECT_EQ(full.offset(2), 3);
  }
  ClusterSet cs = ClusterSet::parse("0:2,5+7,8", 16);
  Layout     l(cs);
  EXPECT_EQ(l.clusterCount(), 3);
  EXPECT_EQ(l.modeCount(), 6);
  EXPECT_EQ(l.size(), 1 + 2 + 2 + 2 + 2 + 1); // k = 8 = N/2 is real only
  EXPECT_EQ(l.clusterOffsetBegin(0), 0);
  EXPECT_EQ(l.clusterOffsetEnd(0), 5);
  EXPECT_EQ(l.clusterOffsetBegin(1), 5);
  EXPECT_EQ(l.clusterOffsetEnd(1), 9);
  EXPECT_EQ(l.clusterOffsetBegin(2), 9);
  EXPECT_EQ(l.clusterOffsetEnd(2), 10);
  EXPECT_EQ(l.indexOf(7), 4);
  EXPECT_EQ(l.indexOf(6), -1);
}

TEST(Transforms, AgainstDirectSums)
{
  for (int N : {16, 15, 64}) {
    RealFFT             fft(N, Planner::Estimate);
    std::vector<double> u = randomVector(N, 7 + N);
    std::copy(u.begin(), u.end(), fft.real());
    fft.forward();
    for (int k = 0; k <= N / 2; ++k) {
      cplx s = 0;
      for (int j = 0; j < N; ++j) s += u[j] * std::exp(cplx(0, -2.0 * kPi * (double)k * j / N));
      EXPECT_NEAR(fft.spectrum()[2 * k], s.real(), 1e-12 * N);
      EXPECT_NEAR(fft.spectrum()[2 * k + 1], s.imag(), 1e-12 * N);
    }
    fft.inverse(); // unnormalised: N u
    for (int j = 0; j < N; ++j) EXPECT_NEAR(fft.real()[j], N * u[j], 1e-11 * N);
  }
}

TEST(Transforms, SynthesizeAnalyzeRoundTrip)
{
  const int           N    = 32;
  Layout              full = Layout::full(N);
  SpectralOperator    op(full, std::vector<double>(N, 1.0), {}, Planner::Estimate);
  std::vector<double> c = randomVector(full.size(), 3), u(N), back(full.size());
  op.synthesize(c.data(), u.data());
  // u(x_j) = sum_k c_k e^{ikx_j} over k = -N/2+1..N/2
  std::vector<cplx> cc = toComplex(full, c);
  for (int j = 0; j < N; ++j) {
    cplx s = cc[0];
    for (int k = 1; k < N / 2; ++k) s += 2.0 * std::real(cc[k] * std::exp(cplx(0, k * gridPoint(N, j))));
    s += cc[N / 2].real() * std::cos(N / 2 * gridPoint(N, j));
    EXPECT_NEAR(u[j], s.real(), 1e-12);
  }
  op.analyze(u.data(), back.data());
  for (int i = 0; i < full.size(); ++i) EXPECT_NEAR(back[i], c[i], 1e-13);
}

TEST(Operator, FullAgainstDirectSums)
{
  for (int N : {32, 31}) {
    Layout              full = Layout::full(N);
    std::vector<double> D = randomVector(N, 11), A = randomVector(N, 12);
    for (double &d : D) d += 2.0;
    for (int terms = 0; terms < 3; ++terms) {
      std::vector<double> Dt = terms == 1 ? std::vector<double>() : D, At = terms == 0 ? std::vector<double>() : A;
      SpectralOperator    op(full, Dt, At, Planner::Estimate);
      std::vector<double> c = randomVector(full.size(), 5), F(full.size());
      op.apply(c.data(), F.data());
      std::vector<cplx> ref = directOperator(N, toComplex(full, c), Dt, At), got = toComplex(full, F);
      for (int k = 0; k <= N / 2; ++k) {
        EXPECT_NEAR(got[k].real(), ref[k].real(), 1e-11 * N * N) << "N " << N << " k " << k;
        EXPECT_NEAR(got[k].imag(), ref[k].imag(), 1e-11 * N * N) << "N " << N << " k " << k;
      }
    }
  }
}

TEST(Operator, ConstantCoefficients)
{
  // d = 2: F_k = -2 k^2 c_k; a = 3 (A = -3): F_k = -3 i k c_k (Nyquist: derivative zero)
  const int           N    = 16;
  Layout              full = Layout::full(N);
  std::vector<double> c    = randomVector(full.size(), 9), F(full.size());
  SpectralOperator    dif(full, std::vector<double>(N, 2.0), {}, Planner::Estimate);
  dif.apply(c.data(), F.data());
  std::vector<cplx> cc = toComplex(full, c), ff = toComplex(full, F);
  for (int k = 0; k < N / 2; ++k) EXPECT_NEAR(std::abs(ff[k] - (-2.0 * k * k) * cc[k]), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(ff[N / 2]), 0.0, 1e-12);
  SpectralOperator adv(full, {}, std::vector<double>(N, -3.0), Planner::Estimate);
  adv.apply(c.data(), F.data());
  ff = toComplex(full, F);
  for (int k = 0; k < N / 2; ++k) EXPECT_NEAR(std::abs(ff[k] - cplx(0, -3.0 * k) * cc[k]), 0.0, 1e-12);
}

TEST(Operator, NyquistModeReadsOnlyItsOneReal)
{
  // The Nyquist mode k = N/2 (even N) is stored as one real and has no derivative. Wherever it
  // sits in the layout (first, with the clusters in the order given; last, as in the full layout
  // and in sorted clusters) the operator must not take a second real for it: that would be the
  // next mode's coefficient, or the value past the end of the vector (NaN here).
  const int           N = 16;
  std::vector<double> D = randomVector(N, 41), A = randomVector(N, 42);
  for (double &d : D) d += 2.0;
  for (const char *spec : {"8,1:3", "0:8"}) {
    Layout           l(ClusterSet::parse(spec, N));
    SpectralOperator op(l, D, A, Planner::Estimate);
    ASSERT_EQ(l.mode(spec[0] == '8' ? 0 : l.modeCount() - 1), N / 2) << spec;
    std::vector<double> c = randomVector(l.size() + 1, 43), F(l.size());
    c[l.size()]           = std::numeric_limits<double>::quiet_NaN();
    op.apply(c.data(), F.data());
    c.pop_back();
    std::vector<cplx> ref = directOperator(N, toComplex(l, c), D, A), got = toComplex(l, F);
    for (int i = 0; i < l.modeCount(); ++i) {
      const int k = l.mode(i);
      EXPECT_NEAR(got[k].real(), ref[k].real(), 1e-11 * N * N) << spec << ": k = " << k;
      EXPECT_NEAR(got[k].imag(), ref[k].imag(), 1e-11 * N * N) << spec << ": k = " << k;
    }
  }
}

TEST(Operator, ProjectionsDirectEqualFFT)
{
  const int           N  = 64;
  ClusterSet          cs = ClusterSet::parse("0:3,10:12+14,20,29:32", N);
  Layout              l(cs);
  std::vector<double> D = randomVector(N, 21), A = randomVector(N, 22);
  SpectralOperator    op(l, D, A, Planner::Estimate);
  std::vector<double> c = randomVector(l.size(), 23), viaFFT(l.size()), viaDirect(l.size());
  op.computePhysical(c.data());
  for (int j = 0; j < l.clusterCount(); ++j) {
    // a cluster written into its own array (base = its first offset)
    std::vector<double> own(l.clusterOffsetEnd(j) - l.clusterOffsetBegin(j));
    op.projectDirect(l.clusterModeBegin(j), l.clusterModeEnd(j), own.data(), l.clusterOffsetBegin(j));
    std::copy(own.begin(), own.end(), viaDirect.begin() + l.clusterOffsetBegin(j));
  }
  op.computeForward();
  op.extractForward(0, l.modeCount(), viaFFT.data());
  for (int i = 0; i < l.size(); ++i) EXPECT_NEAR(viaDirect[i], viaFFT[i], 1e-12);
  EXPECT_EQ(op.counters().inverse, 1);
  EXPECT_EQ(op.counters().forward, 2);
  EXPECT_EQ(op.counters().directModes, l.modeCount());
}

TEST(Operator, SparseEqualsFullRestricted)
{
  // The sparse right-hand side is the full one, evaluated on a state that is zero outside the
  // retained modes, restricted to the retained modes; the cluster projections add up to it.
  const int           N  = 128;
  ClusterSet          cs = ClusterSet::parse("0:3,14:18,48:49,63:64", N);
  Layout              l(cs), full = Layout::full(N);
  std::vector<double> D(N), A(N);
  for (int j = 0; j < N; ++j) {
    const double x = gridPoint(N, j);
    D[j]           = 0.25 * (std::exp(std::sin(16 * x)) + std::exp(std::sin(64 * x)));
    A[j]           = -0.25 * std::exp((0.6 + 0.2 * std::cos(3 * x)) / (1 + 0.35 * std::sin(16 * x) + 0.35 * std::sin(48 * x)));
  }
  SpectralOperator    sparse(l, D, A, Planner::Estimate), fullop(full, D, A, Planner::Estimate);
  std::vector<double> c = randomVector(l.size(), 31), cfull(full.size(), 0.0), F(l.size()), Ffull(full.size());
  for (int i = 0; i < l.modeCount(); ++i) {
    const int fi = full.indexOf(l.mode(i));
    for (int r = 0; r < realsOf(N, l.mode(i)); ++r) cfull[full.offset(fi) + r] = c[l.offset(i) + r];
  }
  sparse.apply(c.data(), F.data());
  fullop.apply(cfull.data(), Ffull.data());
  for (int i = 0; i < l.modeCount(); ++i) {
    const int fi = full.indexOf(l.mode(i));
    for (int r = 0; r < realsOf(N, l.mode(i)); ++r) EXPECT_NEAR(F[l.offset(i) + r], Ffull[full.offset(fi) + r], 1e-10) << "k = " << l.mode(i);
  }
  DenseOperator       M(sparse);
  std::vector<double> G(l.size());
  M.applyRows(0, l.size(), c.data(), G.data());
  for (int i = 0; i < l.size(); ++i) EXPECT_NEAR(G[i], F[i], 1e-10);
}

// ---------------------------------------------------------------------------------------------

TEST(Clusters, Parse)
{
  ClusterSet cs = ClusterSet::parse("0:3,62:66,192:193,255:257", 2048);
  ASSERT_EQ(cs.size(), 4u);
  EXPECT_EQ(cs.clusters[0], (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(cs.clusters[1], (std::vector<int>{62, 63, 64, 65, 66}));
  EXPECT_EQ(cs.clusters[3], (std::vector<int>{255, 256, 257}));
  ClusterSet holes = ClusterSet::parse("0:3, 62:63+65:66 ,192:193,255+257", 2048);
  EXPECT_EQ(holes.clusters[1], (std::vector<int>{62, 63, 65, 66}));
  EXPECT_EQ(holes.clusters[3], (std::vector<int>{255, 257}));
  EXPECT_EQ(holes.format(), "K0 = {0..3}, K1 = {62,63,65,66}, K2 = {192,193}, K3 = {255,257}");
}

static std::string parseError(const std::string &spec, int N)
{
  try {
    ClusterSet::parse(spec, N);
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

TEST(Clusters, BadInput)
{
  EXPECT_NE(parseError("", 64).find("empty"), std::string::npos);
  EXPECT_NE(parseError("0:3,,5", 64).find("empty cluster"), std::string::npos);
  EXPECT_NE(parseError("0:3,2:5", 64).find("overlap"), std::string::npos);
  EXPECT_NE(parseError("0:3,30:40", 64).find("outside 0..32"), std::string::npos);
  EXPECT_NE(parseError("0:x", 64).find("not a wavenumber"), std::string::npos);
  EXPECT_NE(parseError("5:3", 64).find("lo > hi"), std::string::npos);
  EXPECT_NE(parseError("-1:3", 64).find("nonnegative"), std::string::npos);
  EXPECT_NE(parseError("1+1", 64).find("twice"), std::string::npos);
  EXPECT_NE(parseError("0:3,", 64).find("empty cluster"), std::string::npos); // trailing ','
  EXPECT_NE(parseError("0:3,5+", 64).find("empty range"), std::string::npos); // trailing '+'
  EXPECT_NE(parseError("0:3,+5", 64).find("empty range"), std::string::npos);
  EXPECT_NE(parseError("0:999999999", 64).find("outside 0..32"), std::string::npos); // before expanding
}

TEST(Clusters, SortByLowest)
{
  ClusterSet cs = ClusterSet::parse("10:12,0:2", 64);
  EXPECT_TRUE(cs.sortByLowest());
  EXPECT_EQ(cs.clusters[0].front(), 0);
  EXPECT_FALSE(cs.sortByLowest());
}

// ---------------------------------------------------------------------------------------------

TEST(Detect, SoftThresholdAndMerge)
{
  EXPECT_DOUBLE_EQ(softThreshold(0.5, 0.2), 0.3);
  EXPECT_DOUBLE_EQ(softThreshold(0.1, 0.2), 0.0);
  // A synthetic spectrum of N = 512 (series coefficients): clusters near 0, 64 (with a hole
  // at 64) and 200, plus noise below the threshold.
  const int           N = 512;
  std::vector<double> m(N / 2 + 1, 1e-6);
  for (int k : {0, 1, 2, 3, 62, 63, 65, 66, 200, 201}) m[k] = 1e-2;
  const double lambda = std::pow(10.0, -2.5);
  // unitary: sqrt(512) * 1e-2 = 0.23 > lambda; sqrt(512) * 1e-6 = 2.3e-5 < lambda
  std::vector<int> support = thresholdSupport({m}, N, lambda, Normalization::Unitary);
  EXPECT_EQ(support, (std::vector<int>{0, 1, 2, 3, 62, 63, 65, 66, 200, 201}));
  ClusterSet cs = mergeIntoClusters(support, N, 1);
  EXPECT_EQ(cs.format(), "K0 = {0..3}, K1 = {62,63,65,66}, K2 = {200,201}");
  EXPECT_EQ(mergeIntoClusters(support, N, 0).size(), 4u);  // the hole at 64 splits K1
  EXPECT_EQ(mergeIntoClusters(support, N, 60).size(), 2u); // 3 -> 62 is 58 missing: merged
  // series normalisation: 1e-2 > lambda still, dft: noise N * 1e-6 = 5e-4 < lambda
  EXPECT_EQ(thresholdSupport({m}, N, lambda, Normalization::Series).size(), 10u);
  EXPECT_EQ(thresholdSupport({m}, N, 1e-3, Normalization::DFT).size(), 10u);
  EXPECT_EQ(thresholdSupport({m}, N, 1e-4, Normalization::DFT).size(), (size_t)N / 2 + 1);
  // union over snapshots
  std::vector<double> m2(N / 2 + 1, 0.0);
  m2[100] = 1.0;
  EXPECT_EQ(thresholdSupport({m, m2}, N, lambda, Normalization::Unitary).size(), 11u);
  // a threshold that leaves no mode
  EXPECT_TRUE(thresholdSupport({m}, N, 10.0, Normalization::Unitary).empty());
  EXPECT_THROW(mergeIntoClusters({}, N, 1), std::invalid_argument);
}

// One physical cluster whose thresholded support is fragmented (a near-zero centre, oscillating
// edges with gaps of 3 and 4) stays one cluster, without holes; a fixed gap of 1 fragments it.
TEST(Detect, NoFragmentation)
{
  const int        N = 1024;
  std::vector<int> modes{0, 1, 2, 3, 4, 5, 232, 236, 240, 241, 242, 243, 244, 245, 246, 247, 248, 249, 250, 251, 252, 253, 254, 258, 259, 260, 261, 262, 263, 264, 265, 266, 267, 268, 269, 270, 274, 279};
  EXPECT_GT(mergeIntoClusters(modes, N, 1).size(), 4u);
  ClusterSet cs = fillHoles(groupIntoClusters(modes, N, 1.0 / 3.0));
  EXPECT_EQ(cs.format(), "K0 = {0..5}, K1 = {232..279}");
}

// Separated clusters stay apart, also where a fixed gap large enough to join the fragments
// above would merge them: 0..5 and 11..21 (gap 5, centres 13.5 apart), 40..52 (gap 18).
TEST(Detect, NoMerging)
{
  const int        N = 256;
  std::vector<int> modes;
  for (int k = 0; k <= 5; ++k) modes.push_back(k);
  for (int k = 11; k <= 21; ++k) modes.push_back(k);
  for (int k = 40; k <= 52; ++k) modes.push_back(k);
  EXPECT_EQ(mergeIntoClusters(modes, N, 5).size(), 2u); // a fixed gap of 5 merges 0..5 with 11..21
  EXPECT_EQ(groupIntoClusters(modes, N, 1.0 / 3.0).format(), "K0 = {0..5}, K1 = {11..21}, K2 = {40..52}");
  // the paper's diffusion scene, detected from the dynamics: six bands
  std::vector<int> paper{0, 1, 2, 3, 4, 5, 60, 61, 62, 63, 65, 66, 67, 68, 126, 127, 129, 130, 189, 190, 191, 193, 194, 195, 253, 254, 255, 257, 258, 259, 318, 319, 321, 322};
  EXPECT_EQ(fillHoles(groupIntoClusters(paper, 2048, 1.0 / 3.0)).format(), "K0 = {0..5}, K1 = {60..68}, K2 = {126..130}, K3 = {189..195}, K4 = {253..259}, K5 = {318..322}");
  EXPECT_THROW(groupIntoClusters(paper, 2048, -1), std::invalid_argument);
}

// No holes: the near-zero centre k = 64 between 62,63 and 65,66 is kept.
TEST(Detect, NoHoles)
{
  ClusterSet cs = groupIntoClusters({0, 1, 2, 3, 62, 63, 65, 66}, 512, 1.0 / 3.0);
  EXPECT_EQ(cs.clusters[1], (std::vector<int>{62, 63, 65, 66}));
  EXPECT_EQ(fillHoles(cs).clusters[1], (std::vector<int>{62, 63, 64, 65, 66}));
}

// The relative threshold does not depend on N: the same function sampled on N = 256 and 2048
// keeps the same wavenumbers; the unitary one (sqrt(N) |c_k|) keeps more on the finer grid.
TEST(Detect, ThresholdIndependentOfN)
{
  auto sample = [](int N) {
    std::vector<double> u(N);
    for (int j = 0; j < N; ++j) {
      const double x = 2 * M_PI * j / N;
      u[j]           = 1 + 0.5 * std::cos(x) + 2e-4 * std::cos(20 * x) + 5e-5 * std::cos(40 * x) + 1e-3 * std::sin(60 * x);
    }
    return coefficientMagnitudes(u);
  };
  const std::vector<double> m256 = sample(256), m2048 = sample(2048);
  // ||u||^2 = 1 + 0.5^2/2 + ...: relative values 1e-4/1.06, 2.5e-5/1.06, 5e-4/1.06 for k = 20, 40, 60
  const std::vector<int> expect{0, 1, 60};
  EXPECT_EQ(thresholdSupport({m256}, 256, 2e-4, Normalization::Relative), expect);
  EXPECT_EQ(thresholdSupport({m2048}, 2048, 2e-4, Normalization::Relative), expect);
  EXPECT_EQ(thresholdSupport({m256}, 256, 2e-3, Normalization::Unitary).size(), 3u);
  EXPECT_EQ(thresholdSupport({m2048}, 2048, 2e-3, Normalization::Unitary).size(), 4u); // k = 20 as well
  EXPECT_DOUBLE_EQ(defaultLambda(Normalization::Relative), 1e-4);
}

// Bands grouped into time scales: rates 10, 2e3, 7e3, 1.5e4 with separation 10 give two scales.
TEST(Detect, Scales)
{
  ClusterSet bands = ClusterSet::parse("0:5,60:68,126:130,189:195", 1024);
  ClusterSet s     = groupIntoScales(bands, {10, 2e3, 7e3, 1.5e4}, 10);
  EXPECT_EQ(s.format(), "K0 = {0..5}, K1 = {60..68,126..130,189..195}");
  EXPECT_EQ(groupIntoScales(bands, {10, 2e3, 7e3, 1.5e4}, 1).size(), 4u); // separation 1: every band
  // nothing 10 apart: split once, at the largest ratio (7e3 / 2e3)
  EXPECT_EQ(groupIntoScales(bands, {1e3, 2e3, 7e3, 1.5e4}, 10).format(), "K0 = {0..5,60..68}, K1 = {126..130,189..195}");
  EXPECT_THROW(groupIntoScales(bands, {1, 2}, 10), std::invalid_argument);
}

// Bands merge when a band of the later look holds two of the earlier one; widening, a new band
// or a band split (which a growing support cannot give) is no merge.
TEST(Detect, BandsMerged)
{
  ClusterSet eight = ClusterSet::parse("0:14,47:87,117:154,187:196", 1024);
  EXPECT_TRUE(bandsMerged(eight, ClusterSet::parse("0:160,187:196", 1024)));
  EXPECT_TRUE(bandsMerged(eight, ClusterSet::parse("0:386", 1024)));
  EXPECT_FALSE(bandsMerged(eight, ClusterSet::parse("0:15,44:90,117:154,187:196,245:267", 1024)));
  EXPECT_FALSE(bandsMerged(eight, eight));
  EXPECT_FALSE(bandsMerged(ClusterSet::parse("0:5", 64), ClusterSet::parse("0:2,4:5", 64)));
}

// The share of ||u|| outside the clusters, with the weights of a real field (k = 0 and N/2 once).
TEST(Detect, ShareOutside)
{
  const int           N = 16;
  std::vector<double> m(N / 2 + 1, 0.0);
  m[0] = 0.6, m[1] = std::sqrt(0.5 * (1 - 0.36 - 0.01 - 2 * 0.0009)), m[5] = 0.03, m[8] = 0.1; // sum of w_k m_k^2 = 1
  EXPECT_NEAR(shareOutside(ClusterSet::parse("0:1", N), m), std::sqrt(2 * 0.0009 + 0.01), 1e-15);
  EXPECT_NEAR(shareOutside(ClusterSet::parse("0:1,8", N), m), 0.03 * std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(shareOutside(ClusterSet::parse("0:8", N), m), 0.0, 1e-15);
  EXPECT_THROW(shareOutside(ClusterSet::parse("0:1", N), std::vector<double>(5, 0.0)), std::invalid_argument);
}

// Each run of consecutive wavenumbers of the clusters is a band, with its share of ||u||.
TEST(Detect, BandShares)
{
  const int           N = 16;
  std::vector<double> m(N / 2 + 1, 0.0);
  m[0] = 0.6, m[1] = 0.1, m[2] = 0.2, m[5] = 0.03, m[6] = 0.04, m[8] = 0.1;
  const std::vector<BandShare> bands = bandShares(ClusterSet::parse("0:2,5:6+8", N), m);
  ASSERT_EQ(bands.size(), 3u);
  EXPECT_EQ(bands[0].cluster, 0);
  EXPECT_EQ(bands[0].lo, 0);
  EXPECT_EQ(bands[0].hi, 2);
  EXPECT_NEAR(bands[0].share, std::sqrt(0.36 + 2 * 0.01 + 2 * 0.04), 1e-15);
  EXPECT_EQ(bands[1].cluster, 1);
  EXPECT_EQ(bands[1].lo, 5);
  EXPECT_EQ(bands[1].hi, 6);
  EXPECT_NEAR(bands[1].share, std::sqrt(2 * 0.0009 + 2 * 0.0016), 1e-15);
  EXPECT_EQ(bands[2].cluster, 1);
  EXPECT_EQ(bands[2].lo, 8);
  EXPECT_NEAR(bands[2].share, 0.1, 1e-15); // k = N/2 once
  EXPECT_THROW(bandShares(ClusterSet::parse("0:1", N), std::vector<double>(5, 0.0)), std::invalid_argument);
}

// What a band does (what -spectral_cluster_min_band_share asks before it leaves a thin band out).
// Decay share: 1 for diffusion on one wavenumber, at least 2 sqrt(q) / (1 + q) on a band lo..hi
// (q = (hi / lo)^2, Kantorovich), 0 for advection, -1 for a growing band, d k^2 / |-d k^2 + i a k|
// for one wavenumber of both. Influence: 0 where nothing couples the band to the rest (constant coefficients); for
// u = cos x + b cos 5x under (d u_x)_x with d = 1 + cos(4x) / 2, the band {5} adds -5 b / 4 cos x to
// F at k = 1, where F is -(1 + 5 b / 4) cos x: influence 5 b / 4 / (1 + 5 b / 4).
TEST(Detect, BandAction)
{
  const int           N    = 32;
  const Layout        full = Layout::full(N);
  const ClusterSet    all  = ClusterSet::parse("0:16", N);
  std::vector<double> c    = randomVector(full.size(), 51);
  SpectralOperator    diff(full, std::vector<double>(N, 0.5), {}, Planner::Estimate);
  SpectralOperator    adv(full, {}, std::vector<double>(N, 3.0), Planner::Estimate);
  SpectralOperator    both(full, std::vector<double>(N, 1.0), std::vector<double>(N, 20.0), Planner::Estimate);
  EXPECT_NEAR(bandAction(diff, c.data(), all, 7, 7).decay, 1.0, 1e-12);
  const double q = 81.0 / 25.0, spread = bandAction(diff, c.data(), all, 5, 9).decay;
  EXPECT_GT(spread, 2 * std::sqrt(q) / (1 + q));
  EXPECT_LT(spread, 1.0 - 1e-3);
  EXPECT_NEAR(bandAction(adv, c.data(), all, 5, 9).decay, 0.0, 1e-12);
  SpectralOperator growth(full, std::vector<double>(N, -0.5), {}, Planner::Estimate); // a band that grows
  EXPECT_NEAR(bandAction(growth, c.data(), all, 7, 7).decay, -1.0, 1e-12);
  EXPECT_NEAR(bandAction(both, c.data(), all, 4, 4).decay, 16.0 / std::sqrt(16.0 * 16.0 + 80.0 * 80.0), 1e-12);
  EXPECT_EQ(bandAction(both, c.data(), all, 16, 16).decay, 0.0); // the Nyquist mode has no derivative: G_b = 0
  EXPECT_NEAR(bandAction(diff, c.data(), all, 5, 9).influence, 0.0, 1e-12);
  EXPECT_NEAR(bandAction(both, c.data(), all, 5, 9).influence, 0.0, 1e-12);
  EXPECT_EQ(bandAction(diff, std::vector<double>(full.size(), 0.0).data(), all, 5, 9).decay, 0.0);

  std::vector<double> D(N), u(N), cu(full.size());
  const double        b = 0.1;
  for (int j = 0; j < N; ++j) {
    const double x = 2 * M_PI * j / N;
    D[j] = 1 + 0.5 * std::cos(4 * x), u[j] = std::cos(x) + b * std::cos(5 * x);
  }
  SpectralOperator coupled(full, D, {}, Planner::Estimate);
  coupled.analyze(u.data(), cu.data());
  const BandAction a = bandAction(coupled, cu.data(), ClusterSet::parse("1,5", N), 5, 5);
  EXPECT_NEAR(a.influence, 1.25 * b / (1 + 1.25 * b), 1e-12);
  EXPECT_NEAR(a.decay, 1.0, 1e-12);
  // the rest of the state is not retained: nothing to compare with
  EXPECT_EQ(bandAction(coupled, cu.data(), ClusterSet::parse("5", N), 5, 5).influence, 0.0);
  EXPECT_THROW(bandAction(diff, c.data(), all, 9, 17), std::invalid_argument);
  Layout           part(ClusterSet::parse("0:3,8:9", N));
  SpectralOperator sparse(part, std::vector<double>(N, 0.5), {}, Planner::Estimate);
  EXPECT_THROW(bandAction(sparse, c.data(), all, 8, 9), std::invalid_argument);
}

// Bands that only widen (the diffadv scene's looks at 64 and 256 steps) against a new band, a
// vanished band, a merge; the share of the added wavenumbers (k = 0 and N/2 once).
TEST(Detect, BandsWidened)
{
  ClusterSet six = ClusterSet::parse("0:5,44:52,94:98,149:154,197:203,246:250", 1024);
  EXPECT_TRUE(bandsWidened(six, six));
  EXPECT_TRUE(bandsWidened(six, ClusterSet::parse("0:6,44:52,94:98,149:155,197:203,246:250", 1024)));
  EXPECT_TRUE(bandsWidened(six, ClusterSet::parse("0:8,43:53,94:98,149:155,197:203,246:250", 1024)));
  EXPECT_FALSE(bandsWidened(six, ClusterSet::parse("0:5,44:52,94:98,149:154,197:203,246:250,300:302", 1024))); // a new band
  EXPECT_FALSE(bandsWidened(six, ClusterSet::parse("0:52,94:98,149:154,197:203,246:250", 1024)));              // merged
  EXPECT_FALSE(bandsWidened(six, ClusterSet::parse("0:5,44:52,94:98,149:154,197:203,300:302", 1024)));         // one band replaced
}

TEST(Detect, ShareAdded)
{
  const int           N = 16;
  std::vector<double> m(N / 2 + 1, 0.0);
  m[0] = 0.5, m[2] = 0.01, m[3] = 0.02, m[8] = 0.03;
  const ClusterSet before = ClusterSet::parse("0:1", N);
  EXPECT_DOUBLE_EQ(shareAdded(before, before, m), 0.0);
  EXPECT_NEAR(shareAdded(before, ClusterSet::parse("0:2", N), m), 0.01 * std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(shareAdded(before, ClusterSet::parse("0:3,8", N), m), std::sqrt(2 * 1e-4 + 2 * 4e-4 + 9e-4), 1e-15);
  EXPECT_NEAR(shareAdded(ClusterSet::parse("0:2", N), ClusterSet::parse("1:3", N), m), 0.02 * std::sqrt(2.0), 1e-15); // k = 0 dropped: not added
  EXPECT_THROW(shareAdded(before, before, std::vector<double>(5, 0.0)), std::invalid_argument);
}

TEST(Detect, Buffers)
{
  ClusterSet cs = ClusterSet::parse("0,64,138,256", 1024);
  ClusterSet b  = addBuffers(cs, {24, 24, 24, 10});
  EXPECT_EQ(b.format(), "K0 = {0..24}, K1 = {40..88}, K2 = {114..162}, K3 = {246..266}");
  EXPECT_EQ(addBuffers(cs, {3}).clusters[1].size(), 7u);
  EXPECT_THROW(addBuffers(cs, {40}), std::invalid_argument); // 64+40 > 138-40: overlap
  EXPECT_THROW(addBuffers(cs, {1, 2}), std::invalid_argument);
  // holes are filled only within the buffer width
  ClusterSet h = ClusterSet::parse("62:63+65:66", 256);
  EXPECT_EQ(addBuffers(h, {1}).clusters[0], (std::vector<int>{61, 62, 63, 64, 65, 66, 67}));
}

TEST(Detect, WidenClusters)
{
  // the truncation check's widening: buffers that reach another cluster do not overlap it
  ClusterSet cs = ClusterSet::parse("0:3,9:11+20", 64);
  EXPECT_EQ(widenClusters(cs, {0, 0}).format(), cs.format());
  EXPECT_EQ(widenClusters(cs, {2, 1}).format(), "K0 = {0..5}, K1 = {8..12,19..21}");
  // 4..8 reached by both: 4, 5 nearer K0, 6 a tie (3 from 3 and from 9: the lower cluster), 7, 8 nearer K1
  EXPECT_EQ(widenClusters(cs, {6, 6}).format(), "K0 = {0..6}, K1 = {7..26}");
  EXPECT_EQ(widenClusters(cs, {0, 12}).format(), "K0 = {0..3}, K1 = {4..32}");             // K0's own stay its own
  EXPECT_EQ(widenClusters(ClusterSet::parse("30:32", 64), {5}).format(), "K0 = {25..32}"); // clipped at N/2
  EXPECT_THROW(widenClusters(cs, {1}), std::invalid_argument);
  EXPECT_THROW(widenClusters(cs, {1, -1}), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------

TEST(Fields, Forms)
{
  const int N = 64;
  Field     d;
  d.form                = Field::Form::ExpSin;
  d.weights             = {0.25, 0.25};
  d.wavenumbers         = {4, 16};
  std::vector<double> v = d.sample(N);
  for (int j = 0; j < N; ++j) {
    const double x = gridPoint(N, j);
    EXPECT_NEAR(v[j], 0.25 * (std::exp(std::sin(4 * x)) + std::exp(std::sin(16 * x))), 1e-14);
  }
  Field a;
  a.form                    = Field::Form::ExpRatio;
  a.scale                   = 0.25;
  a.numerator.offset        = 0.6;
  a.numerator.wavenumbers   = {3};
  a.numerator.cosines       = {0.2};
  a.denominator.offset      = 1.0;
  a.denominator.wavenumbers = {8, 32};
  a.denominator.sines       = {0.35, 0.35};
  v                         = a.sample(N);
  for (int j = 0; j < N; ++j) {
    const double x = gridPoint(N, j);
    EXPECT_NEAR(v[j], 0.25 * std::exp((0.6 + 0.2 * std::cos(3 * x)) / (1 + 0.35 * std::sin(8 * x) + 0.35 * std::sin(32 * x))), 1e-13);
  }
  a.denominator.wavenumbers = {1};
  a.denominator.sines       = {1.5}; // 1 + 1.5 sin(x) < 0 near x = 3 pi / 2
  EXPECT_THROW(a.sample(N), std::invalid_argument);
  Field g; // gaussian, default exp(-(x - pi)^2)
  g.form = Field::Form::Gaussian;
  v      = g.sample(N);
  EXPECT_NEAR(v[N / 2], 1.0, 1e-15);
  EXPECT_NEAR(v[0], std::exp(-kPi * kPi), 1e-15);
  g.center   = 0.5;
  g.periodic = true;
  v          = g.sample(N);
  EXPECT_NEAR(v[N - 1], std::exp(-std::pow(gridPoint(N, N - 1) - 2 * kPi - 0.5, 2)), 1e-15);
  Field f;
  f.form                  = Field::Form::Fourier;
  f.numerator.offset      = 1;
  f.numerator.wavenumbers = {2};
  f.numerator.sines       = {0.5, 0.1};
  EXPECT_THROW(f.sample(N), std::invalid_argument); // two sines for one wavenumber
  Field r = Field::ofForm(Field::Form::ExpRatio);   // exp(0 / 1) = 1
  EXPECT_EQ(r.sample(N)[3], 1.0);
  Field q                 = Field::ofForm(Field::Form::Fourier); // cos left out: 0
  q.numerator.wavenumbers = {24};
  q.numerator.sines       = {0.6};
  EXPECT_NEAR(q.sample(N)[1], 0.6 * std::sin(24 * gridPoint(N, 1)), 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Burgers, reaction and source terms

// The trigonometric interpolant of grid values f (N points) at y (the Nyquist coefficient of an
// even N as f_{N/2} cos(N y / 2)), from its coefficients by direct sums.
static std::vector<cplx> directCoefficients(const std::vector<double> &f)
{
  const int         N = (int)f.size();
  std::vector<cplx> c(N / 2 + 1, 0.0);
  for (int k = 0; k <= N / 2; ++k) {
    for (int j = 0; j < N; ++j) c[k] += f[j] * std::exp(cplx(0, -2.0 * kPi * (double)k * j / N));
    c[k] /= (double)N;
  }
  return c;
}

static double evalSeries(int N, const std::vector<cplx> &c, double y)
{
  double v = c[0].real();
  for (int k = 1; k <= N / 2; ++k) v += isRealOnly(N, k) ? c[k].real() * std::cos(k * y) : 2.0 * std::real(c[k] * std::exp(cplx(0, k * y)));
  return v;
}

// The extra terms by direct sums (O(N Mref)): u and the fields' interpolants at Mref points, the
// products there, their coefficients k = 0..N/2 (exact when Mref exceeds the products' bandwidth
// plus N/2), F_k = i k G^B_k + G^R_k + S_k with the Nyquist mode of an even N holding both +-N/2
// (2 Re G^R, no derivative).
static std::vector<cplx> directExtra(int N, const std::vector<cplx> &c, const ExtraTerms &x, int Mref)
{
  std::vector<cplx> B, R, S;
  if (!x.burgers.empty()) B = directCoefficients(x.burgers);
  if (!x.rate.empty()) R = directCoefficients(x.rate);
  if (!x.source.empty()) S = directCoefficients(x.source);
  std::vector<cplx> F(N / 2 + 1, 0.0), GB(N / 2 + 1, 0.0), GR(N / 2 + 1, 0.0);
  for (int m = 0; m < Mref; ++m) {
    const double y = 2.0 * kPi * m / Mref, u = evalSeries(N, c, y);
    const double gb = B.empty() ? 0.0 : -0.5 * evalSeries(N, B, y) * u * u;
    const double gr = R.empty() ? 0.0 : evalSeries(N, R, y) * (x.reaction[0] + x.reaction[1] * u + x.reaction[2] * u * u + x.reaction[3] * u * u * u);
    for (int k = 0; k <= N / 2; ++k) {
      const cplx e = std::exp(cplx(0, -k * y)) / (double)Mref;
      GB[k] += gb * e;
      GR[k] += gr * e;
    }
  }
  for (int k = 0; k <= N / 2; ++k) {
    if (isRealOnly(N, k)) F[k] = (k ? 2.0 : 1.0) * GR[k].real() + (S.empty() ? 0.0 : S[k].real());
    else F[k] = cplx(0, k) * GB[k] + GR[k] + (S.empty() ? 0.0 : S[k]);
  }
  return F;
}

static ExtraTerms randomExtra(int N, int which)
{
  ExtraTerms x;
  if (which & 1) x.burgers = randomVector(N, 51);
  if (which & 2) {
    x.rate            = randomVector(N, 52);
    const double r[4] = {0.3, -0.7, 0.5, -0.4};
    std::copy(r, r + 4, x.reaction);
  }
  if (which & 4) x.source = randomVector(N, 53);
  return x;
}

TEST(ExtraTerms, FullAgainstDirectSums)
{
  // every mode (up to the Nyquist mode), random fields and a random state: the padded
  // evaluation equals the exact projection of the products by direct sums (N = 1536: the fields'
  // interpolants on the padded grid by FFT, their 768 coefficients too many for the direct sum)
  for (int N : {32, 31, 1536}) {
    Layout full = Layout::full(N);
    for (int which = 1; which < 8; ++which) {
      if (N > 100 && which > 2) continue; /* Burgers, reaction: the two interpolated fields */
      const ExtraTerms    x = randomExtra(N, which);
      SpectralOperator    op(full, {}, {}, x, Planner::Estimate);
      std::vector<double> c = randomVector(full.size(), 55), F(full.size());
      for (double &v : c) v *= 0.5;
      op.apply(c.data(), F.data());
      const std::vector<cplx> ref = directExtra(N, toComplex(full, c), x, 6 * N), got = toComplex(full, F);
      for (int k = 0; k <= N / 2; ++k) {
        EXPECT_NEAR(got[k].real(), ref[k].real(), 1e-12 * N) << "N " << N << " terms " << which << " k " << k;
        EXPECT_NEAR(got[k].imag(), ref[k].imag(), 1e-12 * N) << "N " << N << " terms " << which << " k " << k;
      }
      if (which & 3) {
        EXPECT_GT(op.paddedSize(), N);
        // the same products formed on the N grid alone are aliased: the reference sees it
        const std::vector<cplx> aliased = directExtra(N, toComplex(full, c), x, N);
        double                  diff    = 0;
        for (int k = 0; k <= N / 2; ++k) diff = std::max(diff, std::abs(aliased[k] - ref[k]));
        EXPECT_GT(diff, 1e-3) << "N " << N << " terms " << which;
      }
    }
  }
}

TEST(ExtraTerms, WithLinearTermsAndConstantFields)
{
  // u = a cos x, c = 1: -(u^2/2)_x = a^2 sin(2x) / 2, i.e. F_2 = -i a^2 / 4 ... plus diffusion
  // d = 1 (F_1 = -a/2) and a source 0.25 (F_0 = 0.25), reaction 1 * (u^3): F_1 += 3 a^3 / 8,
  // F_3 = a^3 / 8 (coefficients of e^{ikx}, cos x = (e^{ix} + e^{-ix}) / 2)
  const int  N    = 16;
  Layout     full = Layout::full(N);
  ExtraTerms x;
  x.burgers.assign(N, 1.0);
  x.rate.assign(N, 1.0);
  x.reaction[3] = 1.0;
  x.source.assign(N, 0.25);
  SpectralOperator    op(full, std::vector<double>(N, 1.0), {}, x, Planner::Estimate);
  const double        a = 0.8;
  std::vector<double> c(full.size(), 0.0), F(full.size());
  c[full.offset(1)] = a / 2;
  op.apply(c.data(), F.data());
  const std::vector<cplx> f = toComplex(full, F);
  EXPECT_NEAR(std::abs(f[0] - 0.25), 0.0, 1e-14);
  EXPECT_NEAR(std::abs(f[1] - (-a / 2 + 3 * a * a * a / 8)), 0.0, 1e-14);
  EXPECT_NEAR(std::abs(f[2] - cplx(0, -a * a / 4)), 0.0, 1e-14);
  EXPECT_NEAR(std::abs(f[3] - a * a * a / 8), 0.0, 1e-14);
  for (int k = 4; k <= N / 2; ++k) EXPECT_NEAR(std::abs(f[k]), 0.0, 1e-14);
  EXPECT_EQ(op.inversePerState(), 2);
  EXPECT_EQ(op.forwardPerState(), 3);
}

TEST(ExtraTerms, SparseEqualsFullRestricted)
{
  // the sparse operator returns the projection onto the retained modes of the terms evaluated
  // on the sparse state: the full operator on the zero-extended state, restricted
  const int           N = 128;
  Layout              l(ClusterSet::parse("0:3,14:18,48:49,58:60", N)), full = Layout::full(N);
  std::vector<double> D(N);
  for (int j = 0; j < N; ++j) D[j] = 1.0 + 0.5 * std::sin(16 * gridPoint(N, j));
  const ExtraTerms    x = randomExtra(N, 7);
  SpectralOperator    sparse(l, D, {}, x, Planner::Estimate), fullop(full, D, {}, x, Planner::Estimate);
  std::vector<double> c = randomVector(l.size(), 61), cfull(full.size(), 0.0), F(l.size()), Ffull(full.size());
  for (double &v : c) v *= 0.3;
  for (int i = 0; i < l.modeCount(); ++i)
    for (int r = 0; r < realsOf(N, l.mode(i)); ++r) cfull[full.offset(full.indexOf(l.mode(i))) + r] = c[l.offset(i) + r];
  sparse.apply(c.data(), F.data());
  fullop.apply(cfull.data(), Ffull.data());
  for (int i = 0; i < l.modeCount(); ++i)
    for (int r = 0; r < realsOf(N, l.mode(i)); ++r) EXPECT_NEAR(F[l.offset(i) + r], Ffull[full.offset(full.indexOf(l.mode(i))) + r], 1e-12) << "k = " << l.mode(i);
  // the sparse state needs a smaller padded grid than the full one
  EXPECT_LT(sparse.paddedSize(), fullop.paddedSize());
  EXPECT_THROW(sparse.projectDirect(0, 1, F.data()), std::logic_error);
  EXPECT_THROW(DenseOperator{sparse}, std::invalid_argument); // nonlinear
}

TEST(ExtraTerms, SparsePaddedGridBelowN)
{
  // few low modes and fields of small bandwidth: the padded grid is coarser than the N grid
  // (the fields' interpolants sampled there), and the result is still the full one restricted
  const int  N = 128;
  Layout     l(ClusterSet::parse("0:3,10:12", N)), full = Layout::full(N);
  ExtraTerms x;
  x.burgers.resize(N);
  x.rate.resize(N);
  for (int j = 0; j < N; ++j) {
    x.burgers[j] = 0.5 + 0.3 * std::cos(5 * gridPoint(N, j));
    x.rate[j]    = 1.0 - 0.2 * std::sin(7 * gridPoint(N, j));
  }
  const double r[4] = {0.1, -1.0, 0.5, -0.3};
  std::copy(r, r + 4, x.reaction);
  SpectralOperator sparse(l, {}, {}, x, Planner::Estimate), fullop(full, {}, {}, x, Planner::Estimate);
  EXPECT_LT(sparse.paddedSize(), N); // M > 3 * 12 + 7 + 12 = 55: 60
  std::vector<double> c = randomVector(l.size(), 81), cfull(full.size(), 0.0), F(l.size()), Ffull(full.size());
  for (int i = 0; i < l.modeCount(); ++i)
    for (int q = 0; q < realsOf(N, l.mode(i)); ++q) cfull[full.offset(full.indexOf(l.mode(i))) + q] = c[l.offset(i) + q];
  sparse.apply(c.data(), F.data());
  fullop.apply(cfull.data(), Ffull.data());
  for (int i = 0; i < l.modeCount(); ++i)
    for (int q = 0; q < realsOf(N, l.mode(i)); ++q) EXPECT_NEAR(F[l.offset(i) + q], Ffull[full.offset(full.indexOf(l.mode(i))) + q], 1e-13) << "k = " << l.mode(i);
}

TEST(ExtraTerms, AffineDenseOperatorAndDirectProjectionWithSource)
{
  // a source and a linear reaction are affine: the dense operator holds them as M c + b
  const int           N = 64;
  Layout              l(ClusterSet::parse("0:3,10:12+14,29:32", N));
  ExtraTerms          x = randomExtra(N, 4); // source only
  std::vector<double> D = randomVector(N, 71);
  for (double &d : D) d += 2.0;
  SpectralOperator    op(l, D, {}, x, Planner::Estimate);
  std::vector<double> c = randomVector(l.size(), 72), F(l.size()), G(l.size()), H(l.size());
  op.apply(c.data(), F.data());
  DenseOperator M(op);
  M.applyRows(0, l.size(), c.data(), G.data());
  op.computePhysical(c.data());
  op.projectDirect(0, l.modeCount(), H.data());
  for (int i = 0; i < l.size(); ++i) {
    EXPECT_NEAR(G[i], F[i], 1e-10);
    EXPECT_NEAR(H[i], F[i], 1e-12);
  }
  x             = randomExtra(N, 2);
  x.reaction[2] = x.reaction[3] = 0.0; // r (c0 + c1 u)
  SpectralOperator lin(l, {}, {}, x, Planner::Estimate);
  EXPECT_FALSE(lin.isNonlinear());
  lin.apply(c.data(), F.data());
  DenseOperator L(lin);
  L.applyRows(0, l.size(), c.data(), G.data());
  for (int i = 0; i < l.size(); ++i) EXPECT_NEAR(G[i], F[i], 1e-12);
}

TEST(Fields, Sums)
{
  const int N = 64;
  Field     f, a = Field::ofForm(Field::Form::Fourier), b = Field::ofForm(Field::Form::ExpSin);
  a.numerator.offset          = 1.0;
  a.numerator.wavenumbers     = {3};
  a.numerator.cosines         = {0.5};
  b.weights                   = {0.1};
  b.wavenumbers               = {16};
  f.summands                  = {a, b};
  const std::vector<double> v = f.sample(N);
  for (int j = 0; j < N; ++j) {
    const double x = gridPoint(N, j);
    EXPECT_NEAR(v[j], 1.0 + 0.5 * std::cos(3 * x) + 0.1 * std::exp(std::sin(16 * x)), 1e-14);
  }
  EXPECT_EQ(f.describe(), "[fourier 1 + 0.5 cos(3x)] + [expsin offset 0 weights 0.1 wavenumbers 16 amplitudes 1 phases 0]");
  f.summands[1].wavenumbers.clear();
  try {
    f.sample(N);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument &e) {
    EXPECT_EQ(std::string(e.what()).rfind("summand 1 (expsin): expsin: 1 weights but 0 wavenumbers", 0), 0u) << e.what();
  }
}

TEST(ExtraTerms, SmoothSizes)
{
  EXPECT_EQ(smoothSize(97), 100);
  EXPECT_EQ(smoothSize(129), 144);
  EXPECT_EQ(smoothSize(7), 8);
  EXPECT_EQ(smoothSize(2049), 2160);
}
