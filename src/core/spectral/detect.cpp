// Cluster detection: soft thresholding, merging, buffers.
#include "detect.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vshmm {
namespace spectral {

double normalizationFactor(Normalization n, int N)
{
  switch (n) {
  case Normalization::Series:
    return 1.0;
  case Normalization::DFT:
    return (double)N;
  default:
    return std::sqrt((double)N);
  }
}

const char *normalizationName(Normalization n)
{
  switch (n) {
  case Normalization::Series:
    return "series";
  case Normalization::DFT:
    return "dft";
  default:
    return "unitary";
  }
}

double softThreshold(double magnitude, double lambda)
{
  return std::max(magnitude - lambda, 0.0);
}

std::vector<int> thresholdSupport(const std::vector<std::vector<double>> &mags, int N, double lambda, Normalization norm)
{
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) throw std::invalid_argument("the shrinkage value lambda must be finite and nonnegative");
  if (mags.empty()) throw std::invalid_argument("cluster detection needs at least one snapshot");
  const double     f = normalizationFactor(norm, N);
  std::vector<int> modes;
  for (int k = 0; k <= maxWavenumber(N); ++k) {
    bool keep = false;
    for (const auto &m : mags) {
      if ((int)m.size() != maxWavenumber(N) + 1) throw std::invalid_argument("a snapshot has the wrong number of wavenumbers");
      if (softThreshold(f * m[k], lambda) > 0.0) keep = true;
    }
    if (keep) modes.push_back(k);
  }
  return modes;
}

ClusterSet mergeIntoClusters(const std::vector<int> &modes, int N, int gap)
{
  if (gap < 0) throw std::invalid_argument("the cluster gap must be nonnegative");
  if (modes.empty()) throw std::invalid_argument("no wavenumber to group into clusters");
  ClusterSet cs;
  cs.N = N;
  for (size_t i = 0; i < modes.size(); ++i) {
    if (i > 0 && modes[i] <= modes[i - 1]) throw std::invalid_argument("wavenumbers to merge must be sorted and distinct");
    if (i == 0 || modes[i] - modes[i - 1] - 1 > gap) cs.clusters.emplace_back();
    cs.clusters.back().push_back(modes[i]);
  }
  cs.validate();
  return cs;
}

ClusterSet addBuffers(const ClusterSet &clusters, const std::vector<int> &buffers)
{
  if (buffers.empty()) return clusters;
  if (buffers.size() != 1 && buffers.size() != clusters.size()) {
    std::ostringstream s;
    s << "buffer widths: give one value for all clusters or one per cluster (" << clusters.size() << "), not " << buffers.size();
    throw std::invalid_argument(s.str());
  }
  ClusterSet out;
  out.N          = clusters.N;
  const int kmax = maxWavenumber(clusters.N);
  for (size_t j = 0; j < clusters.size(); ++j) {
    const int b = buffers.size() == 1 ? buffers[0] : buffers[j];
    if (b < 0) throw std::invalid_argument("buffer widths must be nonnegative");
    std::vector<char> in(kmax + 1, 0);
    for (int k : clusters.clusters[j])
      for (int q = std::max(0, k - b); q <= std::min(kmax, k + b); ++q) in[q] = 1;
    std::vector<int> c;
    for (int k = 0; k <= kmax; ++k)
      if (in[k]) c.push_back(k);
    out.clusters.push_back(c);
  }
  try {
    out.validate();
  } catch (const std::invalid_argument &e) {
    throw std::invalid_argument(std::string("after adding the buffers: ") + e.what());
  }
  return out;
}

} // namespace spectral
} // namespace vshmm
