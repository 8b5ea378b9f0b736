#include "truncation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace vshmm {
namespace spectral {

TruncationModel::TruncationModel(std::vector<int> modes, std::vector<double> rates, std::vector<double> weights, double t0, const std::vector<double> &a0)
    : modes_(std::move(modes)), rates_(std::move(rates)), weights_(std::move(weights)), t0_(t0), t_(t0)
{
  if (rates_.size() != modes_.size() || weights_.size() != modes_.size() || (!a0.empty() && a0.size() != modes_.size())) throw std::invalid_argument("TruncationModel: one rate, weight (and initial amplitude) per left-out mode");
  for (double &r : rates_) r = std::max(r, 0.0);
  a_ = a0.empty() ? std::vector<double>(modes_.size(), 0.0) : a0;
  for (double &a : a_) a = std::abs(a);
  f_.assign(modes_.size(), 0.0);
}

void TruncationModel::advance(double t, const std::vector<double> &forcing)
{
  if (forcing.size() != modes_.size()) throw std::invalid_argument("TruncationModel::advance: one forcing per left-out mode");
  const double dt = t - t_;
  if (dt > 0 && forced_) {
    for (size_t i = 0; i < modes_.size(); ++i) {
      const double f = 0.5 * (f_[i] + std::abs(forcing[i])), x = rates_[i] * dt;
      const double decay = std::exp(-x), gain = x > 1e-8 ? -std::expm1(-x) / rates_[i] : dt; /* int_0^dt e^{-lambda s} ds */
      a_[i] = a_[i] * decay + f * gain;
    }
  }
  for (size_t i = 0; i < modes_.size(); ++i) f_[i] = std::abs(forcing[i]);
  forced_ = true;
  t_      = std::max(t_, t);
}

double TruncationModel::norm() const
{
  double s = 0;
  for (size_t i = 0; i < a_.size(); ++i) s += weights_[i] * a_[i] * a_[i];
  return std::sqrt(s);
}

std::vector<int> TruncationModel::largest(double rest) const
{
  std::vector<size_t> idx(modes_.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](size_t i, size_t j) { return weights_[i] * a_[i] * a_[i] > weights_[j] * a_[j] * a_[j]; });
  double left = 0;
  for (size_t i : idx) left += weights_[i] * a_[i] * a_[i];
  std::vector<int> out;
  for (size_t i : idx) {
    if (std::sqrt(std::max(left, 0.0)) <= rest) break;
    out.push_back(modes_[i]);
    left -= weights_[i] * a_[i] * a_[i];
  }
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace spectral
} // namespace vshmm
