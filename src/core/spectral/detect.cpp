// Cluster detection: soft thresholding, merging, buffers.
#include "detect.hpp"

#include <climits>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace vshmm {
namespace spectral {

double normalizationFactor(Normalization n, int N, const std::vector<double> &mags)
{
  switch (n) {
  case Normalization::Series:
    return 1.0;
  case Normalization::DFT:
    return (double)N;
  case Normalization::Relative: {
    double s = 0;
    for (size_t k = 0; k < mags.size(); ++k) s += (isRealOnly(N, (int)k) ? 1.0 : 2.0) * mags[k] * mags[k];
    return s > 0 ? 1.0 / std::sqrt(s) : 0.0;
  }
  default:
    return std::sqrt((double)N);
  }
}

double defaultLambda(Normalization n)
{
  return n == Normalization::Relative ? 1e-4 : 3.1622776601683794e-3; /* 10^-2.5 */
}

const char *normalizationName(Normalization n)
{
  switch (n) {
  case Normalization::Series:
    return "series";
  case Normalization::DFT:
    return "dft";
  case Normalization::Relative:
    return "relative";
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
  std::vector<char> keep(maxWavenumber(N) + 1, 0);
  for (const auto &m : mags) {
    if ((int)m.size() != maxWavenumber(N) + 1) throw std::invalid_argument("a snapshot has the wrong number of wavenumbers");
    const double f = normalizationFactor(norm, N, m);
    for (int k = 0; k <= maxWavenumber(N); ++k)
      if (softThreshold(f * m[k], lambda) > 0.0) keep[k] = 1;
  }
  std::vector<int> modes;
  for (int k = 0; k <= maxWavenumber(N); ++k)
    if (keep[k]) modes.push_back(k);
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

ClusterSet groupIntoClusters(const std::vector<int> &modes, int N, double ratio)
{
  if (!(ratio >= 0) || !std::isfinite(ratio)) throw std::invalid_argument("the gap ratio must be finite and nonnegative");
  ClusterSet cs = mergeIntoClusters(modes, N, 2);
  auto      &g  = cs.clusters;
  for (;;) {
    size_t best = 0;
    double f    = ratio;
    for (size_t j = 0; j + 1 < g.size(); ++j) {
      const double gap = g[j + 1].front() - g[j].back() - 1;
      const double d   = 0.5 * (g[j + 1].front() + g[j + 1].back()) - 0.5 * (g[j].front() + g[j].back());
      if (gap / d <= f) f = gap / d, best = j + 1;
    }
    if (!best) break;
    g[best - 1].insert(g[best - 1].end(), g[best].begin(), g[best].end());
    g.erase(g.begin() + best);
  }
  return cs;
}

ClusterSet fillHoles(const ClusterSet &clusters)
{
  ClusterSet out;
  out.N = clusters.N;
  for (const auto &c : clusters.clusters) {
    std::vector<int> f;
    if (!c.empty())
      for (int k = c.front(); k <= c.back(); ++k) f.push_back(k);
    out.clusters.push_back(f);
  }
  out.validate();
  return out;
}

ClusterSet groupIntoScales(const ClusterSet &bands, const std::vector<double> &rates, double separation)
{
  if (rates.size() != bands.size()) throw std::invalid_argument("one rate per band is needed");
  if (!std::isfinite(separation)) throw std::invalid_argument("the scale separation must be finite");
  std::vector<size_t> starts; // first band of each scale
  double              fastest = 0;
  for (size_t j = 0; j < bands.size(); ++j) {
    if (j == 0 || !(rates[j] < separation * fastest)) starts.push_back(j);
    fastest = rates[j];
  }
  if (starts.size() == 1 && bands.size() >= 2) {
    size_t best = 1;
    for (size_t j = 2; j < bands.size(); ++j)
      if (rates[j] * rates[best - 1] > rates[best] * rates[j - 1]) best = j;
    starts.push_back(best);
  }
  ClusterSet out;
  out.N = bands.N;
  for (size_t i = 0; i < starts.size(); ++i) {
    std::vector<int> c;
    for (size_t j = starts[i]; j < (i + 1 < starts.size() ? starts[i + 1] : bands.size()); ++j) c.insert(c.end(), bands.clusters[j].begin(), bands.clusters[j].end());
    out.clusters.push_back(c);
  }
  out.validate();
  return out;
}

bool bandsMerged(const ClusterSet &before, const ClusterSet &now)
{
  for (const auto &c : now.clusters) {
    if (c.empty()) continue;
    int n = 0;
    for (const auto &b : before.clusters)
      if (!b.empty() && b.front() >= c.front() && b.front() <= c.back()) n++;
    if (n >= 2) return true;
  }
  return false;
}

double shareOutside(const ClusterSet &clusters, const std::vector<double> &m)
{
  if ((int)m.size() != maxWavenumber(clusters.N) + 1) throw std::invalid_argument("the mean spectrum has the wrong number of wavenumbers");
  std::vector<char> in(m.size(), 0);
  for (const auto &c : clusters.clusters)
    for (int k : c) in[k] = 1;
  double out = 0;
  for (size_t k = 0; k < m.size(); ++k)
    if (!in[k]) out += (isRealOnly(clusters.N, (int)k) ? 1.0 : 2.0) * m[k] * m[k];
  return std::sqrt(out);
}

std::vector<BandShare> bandShares(const ClusterSet &clusters, const std::vector<double> &m)
{
  if ((int)m.size() != maxWavenumber(clusters.N) + 1) throw std::invalid_argument("the mean spectrum has the wrong number of wavenumbers");
  std::vector<BandShare> bands;
  for (size_t c = 0; c < clusters.clusters.size(); ++c) {
    const std::vector<int> &K = clusters.clusters[c];
    for (size_t i0 = 0, i = 1; i <= K.size(); ++i)
      if (i == K.size() || K[i] != K[i - 1] + 1) {
        double sum = 0;
        for (size_t j = i0; j < i; ++j) sum += (isRealOnly(clusters.N, K[j]) ? 1.0 : 2.0) * m[K[j]] * m[K[j]];
        bands.push_back({(int)c, K[i0], K[i - 1], std::sqrt(sum)});
        i0 = i;
      }
  }
  return bands;
}

BandAction bandAction(SpectralOperator &op, const double *c, const ClusterSet &kept, int lo, int hi)
{
  const Layout &L = op.layout();
  const int     N = L.N();
  if (lo < 0 || hi < lo || hi > maxWavenumber(N) || L.modeCount() != maxWavenumber(N) + 1) throw std::invalid_argument("bandAction: the band must lie in 0..N/2 of a full layout");
  std::vector<char> in(maxWavenumber(N) + 1, 0);
  for (const auto &cl : kept.clusters)
    for (int k : cl)
      if (k >= 0 && k <= maxWavenumber(N)) in[k] = 1;
  std::vector<double> f(L.size()), g(L.size()), w(c, c + L.size());
  for (int i = 0; i < L.modeCount(); ++i)
    if (L.mode(i) >= lo && L.mode(i) <= hi)
      for (int j = 0; j < (isRealOnly(N, L.mode(i)) ? 1 : 2); ++j) w[L.offset(i) + j] = 0;
  op.apply(c, f.data());
  op.apply(w.data(), g.data());
  double vG = 0, vv = 0, GG = 0, GK = 0, FK = 0;
  for (int i = 0; i < L.modeCount(); ++i) {
    const int    k    = L.mode(i);
    const bool   band = k >= lo && k <= hi;
    const double wt   = isRealOnly(N, k) ? 1.0 : 2.0;
    if (!band && !in[k]) continue;
    for (int j = 0; j < (isRealOnly(N, k) ? 1 : 2); ++j) {
      const int    o = L.offset(i) + j;
      const double G = f[o] - g[o];
      if (band) vG += wt * c[o] * G, vv += wt * c[o] * c[o], GG += wt * G * G;
      else GK += wt * G * G, FK += wt * f[o] * f[o];
    }
  }
  BandAction a;
  a.decay     = vv > 0 && GG > 0 ? -vG / std::sqrt(vv * GG) : 0.0;
  a.influence = GK > 0 ? (FK > 0 ? std::sqrt(GK / FK) : std::numeric_limits<double>::infinity()) : 0.0;
  return a;
}

bool bandsWidened(const ClusterSet &before, const ClusterSet &now)
{
  if (before.size() != now.size()) return false;
  for (size_t j = 0; j < now.size(); ++j) {
    const auto &b = before.clusters[j], &c = now.clusters[j];
    bool        shared = false;
    for (int k : c)
      if (std::binary_search(b.begin(), b.end(), k)) {
        shared = true;
        break;
      }
    if (!shared) return false;
  }
  return true;
}

double shareAdded(const ClusterSet &before, const ClusterSet &now, const std::vector<double> &m)
{
  if ((int)m.size() != maxWavenumber(now.N) + 1) throw std::invalid_argument("the mean spectrum has the wrong number of wavenumbers");
  std::vector<char> in(m.size(), 0), added(m.size(), 0);
  for (const auto &c : before.clusters)
    for (int k : c)
      if (k >= 0 && k < (int)m.size()) in[k] = 1;
  for (const auto &c : now.clusters)
    for (int k : c) added[k] = !in[k];
  double a = 0;
  for (size_t k = 0; k < m.size(); ++k)
    if (added[k]) a += (isRealOnly(now.N, (int)k) ? 1.0 : 2.0) * m[k] * m[k];
  return std::sqrt(a);
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

ClusterSet widenClusters(const ClusterSet &clusters, const std::vector<int> &buffers)
{
  if (buffers.size() != clusters.size()) throw std::invalid_argument("widenClusters: one buffer per cluster");
  const int        kmax = maxWavenumber(clusters.N);
  std::vector<int> owner(kmax + 1, -1), dist(kmax + 1, INT_MAX);
  for (size_t j = 0; j < clusters.size(); ++j)
    for (int k : clusters.clusters[j]) owner[k] = (int)j, dist[k] = 0;
  for (size_t j = 0; j < clusters.size(); ++j) {
    if (buffers[j] < 0) throw std::invalid_argument("buffer widths must be nonnegative");
    for (int k : clusters.clusters[j])
      for (int q = std::max(0, k - buffers[j]); q <= std::min(kmax, k + buffers[j]); ++q) {
        const int d = std::abs(q - k);
        if (d < dist[q] || (d == dist[q] && owner[q] > (int)j)) owner[q] = (int)j, dist[q] = d;
      }
  }
  ClusterSet out;
  out.N = clusters.N;
  out.clusters.assign(clusters.size(), {});
  for (int k = 0; k <= kmax; ++k)
    if (owner[k] >= 0) out.clusters[owner[k]].push_back(k);
  out.validate();
  return out;
}

} // namespace spectral
} // namespace vshmm
