#include "schedule.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace vshmm {
namespace {

std::string show(double x)
{
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

void checkMicroStep(double dt)
{
  if (!(dt > 0 && std::isfinite(dt))) throw std::invalid_argument("micro step dt is " + show(dt) + ": must be positive and finite");
}

void checkSavingsFactors(const std::vector<double> &savings)
{
  for (std::size_t j = 1; j <= savings.size(); ++j) {
    const double alpha = savings[j - 1];
    if (!(alpha >= 0 && std::isfinite(alpha))) throw std::invalid_argument("savings factor " + std::to_string(j) + " is " + show(alpha) + ": must be non-negative and finite");
  }
}

void checkSubintervals(const std::vector<int> &subintervals)
{
  for (std::size_t j = 1; j <= subintervals.size(); ++j) {
    const int m = subintervals[j - 1];
    if (m < 1) throw std::invalid_argument("subinterval count " + std::to_string(j) + " is " + std::to_string(m) + ": must be at least 1");
  }
}

} // namespace

MesoscopicSchedule::MesoscopicSchedule(const Kernel &kernel, double microStep, std::vector<double> savings, std::vector<int> subintervals) : kernel_(kernel), dt_(microStep), alpha_(std::move(savings)), m_(std::move(subintervals))
{
  checkMicroStep(dt_);
  if (alpha_.size() != m_.size()) throw std::invalid_argument("got " + std::to_string(alpha_.size()) + " savings factors and " + std::to_string(m_.size()) + " subinterval counts: need one of each per scale above scale 0");
  checkSavingsFactors(alpha_);
  checkSubintervals(m_);
}

int MesoscopicSchedule::numScales() const
{
  return static_cast<int>(alpha_.size()) + 1;
}

double MesoscopicSchedule::microStep() const
{
  return dt_;
}

double MesoscopicSchedule::savingsFactor(int j) const
{
  return alpha_.at(j - 1);
}

int MesoscopicSchedule::subintervals(int j) const
{
  return m_.at(j - 1);
}

double MesoscopicSchedule::mesoscopicStep(int j, double tau, double macroStep) const
{
  const double period = macroStep / m_[j - 1];
  const double phase  = std::fmod(tau, period);
  return alpha_[j - 1] * dt_ * kernel_.valueAtThetaInverse(phase / period, (period - phase) / period);
}

double MesoscopicSchedule::levelStep(int level, double tau, double macroStep) const
{
  return level == numScales() - 1 ? dt_ : mesoscopicStep(level + 1, tau, macroStep);
}

} // namespace vshmm
