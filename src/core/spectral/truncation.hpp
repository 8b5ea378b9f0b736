// The truncation check of a sparse run (no PETSc): how far the dynamics drive the wavenumbers
// that the clusters leave out.
//
//   A sparse run keeps only the clusters' modes; the full operator F at its state has
//   components f_k on the left-out wavenumbers k too, which the run drops. Each left-out mode is
//   modelled as a forced, damped mode, a_k' = -lambda_k a_k + |f_k| (lambda_k >= 0 its own
//   decay rate: mean(d) k^2 for diffusion, the mean linear decay of a reaction; 0 where neither
//   damps it), so a_k bounds its amplitude while its feedback on the retained modes and the
//   coupling of the left-out modes among themselves are negligible. Between two looks at times
//   t0 < t1 the forcing is the mean of the two looks' |f_k|; the model starts from the left-out
//   part of the initial data. The modelled norm of the left-out part, sqrt(sum_k w_k a_k^2)
//   (w_k the Parseval weights: 2, or 1 for k = 0, N/2), against the norm of the solution is the
//   share of ||u|| the clusters miss: where it exceeds the clusters' tolerance, the clusters are
//   too narrow for the run (docs/spectral.md, "The truncation check").
#pragma once

#include <string>
#include <vector>

namespace vshmm {
namespace spectral {

class TruncationModel {
public:
  TruncationModel() = default;
  // The left-out wavenumbers, their decay rates (negative is taken as 0) and weights, the time
  // and the left-out amplitudes |c_k| of the initial data (empty: 0).
  TruncationModel(std::vector<int> modes, std::vector<double> rates, std::vector<double> weights, double t0, const std::vector<double> &a0);
  // Advance to t with the forcing magnitudes |f_k| at t (one per left-out mode); the first call
  // only records the forcing when t is the start time.
  void   advance(double t, const std::vector<double> &forcing);
  double time() const { return t_; }
  double startTime() const { return t0_; }
  double norm() const; // sqrt(sum_k w_k a_k^2)
  // The wavenumbers that hold all but `rest` of the modelled norm (largest first, then sorted).
  std::vector<int>           largest(double rest) const;
  const std::vector<int>    &modes() const { return modes_; }
  const std::vector<double> &amplitudes() const { return a_; }
  bool                       empty() const { return modes_.empty(); }

private:
  std::vector<int>    modes_;
  std::vector<double> rates_, weights_, a_, f_;
  double              t0_ = 0, t_ = 0;
  bool                forced_ = false; // f_ holds a look's forcing
};

} // namespace spectral
} // namespace vshmm
