// Cluster detection for the sparse spectral component (no PETSc): soft thresholding of Fourier
// coefficients over snapshots, grouping of the wavenumbers found into clusters, holes, buffers.
#pragma once

#include "spectral.hpp"

namespace vshmm {
namespace spectral {

// How the coefficients are scaled before thresholding. With series coefficients c_k
// (u = sum c_k exp(ikx)), the thresholded value is factor |c_k|:
//   relative factor 1/||u||  with ||u||^2 = sum over k = -N/2+1..N/2 of |c_k|^2, the mean square
//                            of u on the grid (Parseval): independent of N (the default)
//   unitary  factor sqrt(N)  (DFT with 1/sqrt(N), the paper's normalisation as we read it: the
//                            same lambda keeps sqrt(2) times smaller coefficients when N doubles)
//   series   factor 1        (Fourier series coefficients c_k)
//   dft      factor N        (unnormalised DFT, as FFTW and numpy.fft.fft return it)
enum class Normalization {
  Unitary,
  Series,
  DFT,
  Relative
};
// The factor for a snapshot mags (|c_k|, k = 0..N/2; only Relative reads it).
double      normalizationFactor(Normalization n, int N, const std::vector<double> &mags = {});
const char *normalizationName(Normalization n);
// The default shrinkage value of a normalisation: 1e-4 (relative), 10^-2.5 (the others).
double defaultLambda(Normalization n);

// Soft thresholding: v^s_k = max(|v_k| - lambda, 0) v_k / |v_k|. The support is the set of k
// with |v_k| > lambda.
double softThreshold(double magnitude, double lambda);

// Wavenumbers k in 0..N/2 whose scaled magnitude factor * mags[s][k] exceeds lambda in at
// least one snapshot s (each snapshot holds |c_k| for k = 0..N/2). Sorted.
std::vector<int> thresholdSupport(const std::vector<std::vector<double>> &mags, int N, double lambda, Normalization norm);

// Groups sorted wavenumbers into clusters: neighbours k < k' share a cluster when at most
// `gap` wavenumbers lie strictly between them (k' - k - 1 <= gap). Throws if modes is empty.
ClusterSet mergeIntoClusters(const std::vector<int> &modes, int N, int gap);

// Groups sorted wavenumbers into clusters without a fixed gap (the default of the detection):
//  1. neighbours with at most 2 missing wavenumbers between them share a group (the near-zero
//     centre of a cluster, k = 64 between 62,63 and 65,66, and the oscillating edges);
//  2. repeatedly, the two adjacent groups whose gap (missing wavenumbers between them) is the
//     smallest fraction of the distance between their centres ((lo + hi)/2) are merged while
//     that fraction is at most `ratio` (default 1/3): a fragment near a wide cluster joins it,
//     two clusters whose gap is comparable to their spacing stay apart.
// The outcome depends on the wavenumbers only, not on N. Throws if modes is empty or ratio < 0.
ClusterSet groupIntoClusters(const std::vector<int> &modes, int N, double ratio);

// Every wavenumber between the lowest and the highest of each cluster (no holes).
ClusterSet fillHoles(const ClusterSet &clusters);

// Groups adjacent clusters (bands, slowest first) into time scales: band j joins the current
// scale while rates[j] is less than `separation` times the rate of the scale's fastest band so
// far; otherwise it starts a new scale. rates[j] is the band's time scale (e.g. its spectral
// radius), increasing with j. If everything would end up in one scale but there are at least two
// bands, the scales split once, at the largest ratio of consecutive rates. separation <= 1 keeps
// every band a scale of its own. The result's clusters may have holes between their bands.
ClusterSet groupIntoScales(const ClusterSet &bands, const std::vector<double> &rates, double separation);

// Whether bands merged between two looks at a growing support: a band of `now` holds the lowest
// wavenumbers of two or more bands of `before`.
bool bandsMerged(const ClusterSet &before, const ClusterSet &now);

// The share of ||u|| outside the clusters: sqrt(sum over k = 0..N/2 outside them of w_k m_k^2),
// w_k = 1 for k = 0 and k = N/2 (N even), 2 otherwise, with m_k the root mean square over time of
// |c_k| / ||u|| (so that the sum over every k is 1). Throws if m does not have N/2 + 1 values.
double shareOutside(const ClusterSet &clusters, const std::vector<double> &m);

// The bands of the clusters (their runs of consecutive wavenumbers), slowest first, each with its
// share of ||u||: sqrt(sum over its k of w_k m_k^2), w_k and m as in shareOutside(). Throws if m
// does not have N/2 + 1 values.
struct BandShare {
  int    cluster = 0, lo = 0, hi = 0;
  double share = 0;
};
std::vector<BandShare> bandShares(const ClusterSet &clusters, const std::vector<double> &m);

// What a band does, from the state c (in `op`'s full layout): with v the band's part of c (its
// wavenumbers lo..hi) and G = F(c) - F(c - v) the operator's action on v (exact for linear terms, a
// secant for nonlinear ones), in the Parseval inner product,
//   decay     = -<v, G_b> / (||v|| ||G_b||), G_b the band's part of G: the cosine of the angle
//               between v and -G_b. Near 1 for a band that only decays (diffusion, G_b = -d k^2 v:
//               1 on one wavenumber, at least 2 sqrt(q) / (1 + q) on lo..hi with q = (hi / lo)^2),
//               about 0 for one that oscillates (advection and Burgers terms act on their own band
//               as i a k, skew in this product); 0 where v or G_b is zero;
//   influence = ||G_K|| / ||F(c)_K||, K the wavenumbers of `kept` outside lo..hi: what the band
//               does to the other retained modes against what they do in all (0 where G_K is
//               zero, infinite where only F(c)_K is).
// Costs two evaluations of `op`. Throws if lo..hi does not lie in 0..N/2 or the layout is not full.
struct BandAction {
  double decay = 0, influence = 0;
};
BandAction bandAction(SpectralOperator &op, const double *c, const ClusterSet &kept, int lo, int hi);

// Whether the bands only widened between two looks at a growing support: `now` has as many bands
// as `before` and band j of `now` shares a wavenumber with band j of `before` (no band appeared,
// vanished or merged).
bool bandsWidened(const ClusterSet &before, const ClusterSet &now);

// The share of ||u|| in the wavenumbers of `now` that `before` does not hold: sqrt(sum over
// those k of w_k m_k^2), w_k and m as in shareOutside(). Throws if m does not have N/2 + 1 values.
double shareAdded(const ClusterSet &before, const ClusterSet &now, const std::vector<double> &m);

// Adds every wavenumber within buffers[j] of a member of cluster j (clipped to 0..N/2). One
// value for all clusters or one per cluster. Throws if two clusters then overlap.
ClusterSet addBuffers(const ClusterSet &clusters, const std::vector<int> &buffers);

// The same widening (buffers[j] around every member of cluster j, one value per cluster), but
// the clusters never overlap: a wavenumber of one cluster stays its own, and one that the buffers
// of several clusters reach goes to the cluster nearest to it (the lower index on a tie).
ClusterSet widenClusters(const ClusterSet &clusters, const std::vector<int> &buffers);

} // namespace spectral
} // namespace vshmm
