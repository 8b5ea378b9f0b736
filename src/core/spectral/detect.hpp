// Cluster detection for the sparse spectral component (no PETSc): soft thresholding of Fourier
// coefficients over snapshots, merging of adjacent wavenumbers, buffers.
#pragma once

#include "spectral.hpp"

namespace vshmm {
namespace spectral {

// How the coefficients are scaled before thresholding. With series coefficients c_k
// (u = sum c_k exp(ikx)), the thresholded value is factor |c_k|:
//   unitary  factor sqrt(N)  (DFT with 1/sqrt(N): the default; gives the paper's clusters)
//   series   factor 1        (Fourier series coefficients c_k)
//   dft      factor N        (unnormalised DFT, as FFTW and numpy.fft.fft return it)
enum class Normalization {
  Unitary,
  Series,
  DFT
};
double      normalizationFactor(Normalization n, int N);
const char *normalizationName(Normalization n);

// Soft thresholding: v^s_k = max(|v_k| - lambda, 0) v_k / |v_k|. The support is the set of k
// with |v_k| > lambda.
double softThreshold(double magnitude, double lambda);

// Wavenumbers k in 0..N/2 whose scaled magnitude factor * mags[s][k] exceeds lambda in at
// least one snapshot s (each snapshot holds |c_k| for k = 0..N/2). Sorted.
std::vector<int> thresholdSupport(const std::vector<std::vector<double>> &mags, int N, double lambda, Normalization norm);

// Groups sorted wavenumbers into clusters: neighbours k < k' share a cluster when at most
// `gap` wavenumbers lie strictly between them (k' - k - 1 <= gap). Throws if modes is empty.
ClusterSet mergeIntoClusters(const std::vector<int> &modes, int N, int gap);

// Adds every wavenumber within buffers[j] of a member of cluster j (clipped to 0..N/2). One
// value for all clusters or one per cluster. Throws if two clusters then overlap.
ClusterSet addBuffers(const ClusterSet &clusters, const std::vector<int> &buffers);

} // namespace spectral
} // namespace vshmm
