// The VSHMM step schedule: variable mesoscopic steps h_j(t) from a kernel, and the sequence
// of micro cycles that fills one macro step (sampling interval) DeltaT. No PETSc here.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "kernel.hpp"

namespace vshmm {

// Scales are numbered 0 (slowest) .. K (fastest); level l integrates the field of scales 0..l.
// Level K takes the micro step dt; level l < K takes the mesoscopic step h_{l+1}(t).
// savings[j-1] = alpha_j and subintervals[j-1] = m_j for j = 1..K (slowest level first).
class MesoscopicSchedule {
public:
  // Throws std::invalid_argument unless dt > 0 and finite, savings.size() == subintervals.size(),
  // every alpha_j >= 0 and finite (alpha_j = 0: level j-1 takes no steps of its own), every m_j >= 1.
  MesoscopicSchedule(const Kernel &kernel, double microStep, std::vector<double> savings, std::vector<int> subintervals);

  int    numScales() const; // K + 1
  double microStep() const;
  double savingsFactor(int j) const; // alpha_j, j = 1..K
  int    subintervals(int j) const;  // m_j, j = 1..K

  // The method note's formula, with tau = t - t_n the time since the start of the macro step
  // (equal to (t - t_0) mod P_j because t_n - t_0 is a multiple of DeltaT):
  //   P_j = DeltaT / m_j,  u = (tau mod P_j) / P_j,
  //   h_j = alpha_j * dt * K(Theta^{-1}(u)).
  double mesoscopicStep(int j, double tau, double macroStep) const;

  // The step level `level` takes when it starts at tau: dt for level K, h_{level+1}(tau) otherwise.
  double levelStep(int level, double tau, double macroStep) const;

private:
  const Kernel       &kernel_;
  double              dt_;
  std::vector<double> alpha_;
  std::vector<int>    m_;
};

// What one macro step did.
struct MacroStepCounts {
  std::int64_t              cycles = 0; // micro cycles started
  std::vector<std::int64_t> levelSteps; // steps per level (index = level)
};

// The smallest step h from tau with fl(tau + h) >= end: it ends exactly on end whenever some
// double does, in particular whenever tau >= end / 2 (then end - tau is exact). end - tau alone
// can miss by an ulp when tau < end / 2; a few such (tau, end) admit no exact h at all.
inline double stepToEnd(double tau, double end)
{
  double h = end - tau;
  while (tau + h > end) h = std::nextafter(h, 0.0);
  while (tau + h < end) h = std::nextafter(h, end);
  return h;
}

// Runs one macro step of length macroStep: micro cycles of
//   level K with dt, then levels K-1, ..., 0 with h_K, ..., h_1,
// each step starting at tau (time since the macro step began) with the length given by the
// schedule, except that a step that would pass macroStep is shortened to end exactly on it,
// and the macro step ends there. A step of length 0 (K = 0 at the start of a period) is not
// taken. advance(level, tau, h) performs one step and returns 0 or a nonzero error code,
// which stops the macro step and is returned. The final tau + h is exactly macroStep whenever
// the last step starts at or after macroStep / 2 (see stepToEnd): the caller should still set
// its time to t_n + macroStep itself.
template <class Advance>
int runMacroStep(const MesoscopicSchedule &schedule, double macroStep, Advance &&advance, MacroStepCounts *counts = nullptr)
{
  const int top = schedule.numScales() - 1;
  if (counts) *counts = MacroStepCounts{std::int64_t{0}, std::vector<std::int64_t>(top + 1, 0)};
  double tau = 0.0;
  while (tau < macroStep) {
    if (counts) counts->cycles++;
    for (int level = top; level >= 0; --level) {
      double h    = schedule.levelStep(level, tau, macroStep);
      bool   last = false;
      if (!(tau + h < macroStep)) {
        if (tau + h != macroStep) h = stepToEnd(tau, macroStep);
        last = true;
      }
      if (h > 0.0) {
        if (int err = advance(level, tau, h)) return err;
        if (counts) counts->levelSteps[level]++;
      }
      if (last) return 0;
      tau += h;
    }
  }
  return 0;
}

} // namespace vshmm
