// Stability of the coupled levels: the levels of VSHMM step one after another with different
// fields, so a mode can grow although every level alone is stable for it. A slow field that moves
// the fast variables (a stiff-spring chain whose slow split carries the kinematics q' = p) shears
// the fast oscillation at every mesoscopic step; composed with the fast rotation of the micro
// step, the cycle becomes hyperbolic and pumps energy into the fast modes. No eigenvalue of any
// single level shows it. No PETSc here.
//
// The analysis is linear, on small dense matrices: each level's Jacobian restricted (Galerkin) to
// a common n-dimensional subspace (in the TS glue: a Krylov space of the full field's Jacobian,
// exact when n is the state's size). One step of the inner Runge-Kutta method on y' = J y is the
// matrix R(h J); one micro cycle is the product of its levels' steps.
#pragma once

#include <vector>

#include "kernel.hpp"
#include "rk.hpp"
#include "schedule.hpp"

namespace vshmm {

// Column-major n x n matrices, one per level (0 = slowest .. K = the full field).
struct CoupledLevels {
  int                              n = 0;
  std::vector<std::vector<double>> jacobian;
};

// log of the spectral radius of the n x n matrix A (column-major), from repeated squaring with
// normalisation: log rho = lim log ||A^(2^p)|| / 2^p. -infinity for a nilpotent A.
double logSpectralRadius(std::vector<double> A, int n);

// R(h J) for the explicit tableau, by the stage recursion K_i = J (I + h sum_{j<i} a_ij K_j),
// R = I + h sum_i b_i K_i.
std::vector<double> stepMatrix(const Tableau &tableau, double h, const std::vector<double> &J, int n);

// What the coupling of the levels does over one macro step: the linearised macro step P, the
// product of every step's R(h J_level) in the schedule's order, against each level's own steps
// (a level's steps commute with each other): the growth from the coupling is
//   max(0, log rho(P) - sum_l max(0, log rho(product of level l's steps))),
// 0 where the levels commute (their own growth is the per-level check's business). The growth of
// the exact flow (an unstable slow manifold) is in P too; the caller allows for it. At most
// maxSteps steps are multiplied; a longer macro step's growth is extrapolated from them.
struct CouplingGrowth {
  double logGrowth    = 0.0;
  long   cycles       = 0;
  long   steps        = 0;
  bool   extrapolated = false;
};
CouplingGrowth couplingGrowth(const Tableau &tableau, const CoupledLevels &levels, const MesoscopicSchedule &schedule, double macroStep, long maxSteps = 2000);

// The largest s in [0, 1] such that the savings factors s alpha_j (all scaled together) keep the
// coupling growth over a macro step at most maxLogGrowth; bisection to 2^-30. 1 if the given
// factors pass; 0 if no s passes, or every s that passes needs more than maxSteps steps per macro
// step (smaller factors mean more steps). Throws std::invalid_argument where the schedule does.
double largestCouplingStableScaling(const Tableau &tableau, const CoupledLevels &levels, const Kernel &kernel, double microStep, const std::vector<double> &savings, const std::vector<int> &subintervals, double macroStep, double maxLogGrowth, long maxSteps = 5000);

} // namespace vshmm
