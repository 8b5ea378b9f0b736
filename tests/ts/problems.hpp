// Test problems for the PETSc-level tests, each built as a TS with one RHS split per scale,
// on any communicator, with additive or component splits.
#pragma once

#include <petscvshmm.h>

#include <functional>
#include <string>
#include <vector>

// Mixed: even scales additive, odd scales component splits. Scattered: the same, but every IS lists
// its components in decreasing order, all on the last rank (unsorted, and on several ranks naming
// components that other ranks own): TSVSHMM adds such splits with a VecScatter.
enum class SplitKind {
  Additive,
  Component,
  Mixed,
  Scattered
};

// One call of a split function, as seen by the test hooks below.
struct SplitCall {
  int       split;    // the term (scale index of the problem)
  long      call;     // 1, 2, ...: the how-many-th call of this split
  int       level;    // the TSVSHMM level whose field is being evaluated (-1: the stability check)
  PetscReal t;        // the time the split is evaluated at
  PetscReal macro_t0; // the start of the macro step (TSGetTime() of the TS during the step)
};

// A small ODE dx/dt = sum_k f_k(x) whose split k writes the terms of scale k. The state lives on
// `comm` (spread over its ranks); split functions gather it to every rank.
struct SplitProblem {
  using Term                           = void (*)(const void *params, PetscReal t, const PetscScalar *x, PetscScalar *f); // f_k for all components
  PetscInt                           n = 0;
  std::vector<Term>                  terms;      // scale k's term, written for every component
  std::vector<Term>                  full_extra; // terms the TS's RHS function adds to the splits' sum (a program whose splits miss them)
  std::vector<std::vector<PetscInt>> components; // SplitKind::Component: scale k's components where set (default: component k, the last scale the rest)
  const void                        *params          = nullptr;
  long                               nan_after_calls = -1;             // test hook: the fastest split returns NaN after this many calls
  PetscReal                          nan_after_time  = PETSC_MAX_REAL; // test hook: ... or at times past this one
  long                               calls           = 0;
  // Test hooks that follow every split call (only when set): `trace` records each call; split
  // nan_split returns NaN in all its entries on its nan_call-th call. The level is found from the
  // TSVSHMM statistics of `ts` (set by CreateSplitTS): the level whose evaluation count moved.
  std::vector<SplitCall> *trace     = nullptr;
  int                     nan_split = -1;
  long                    nan_call  = -1;
  TS                      ts        = nullptr;
  std::vector<long>       split_calls;        // per split
  std::vector<PetscInt64> seen_evaluations;   // per level, at the last call
  PetscInt64              seen_stability = 0; // stability-check evaluations at the last call
  int                     level          = -1;

  // Internal
  VecScatter gather = nullptr;
  Vec        xall   = nullptr;
};

// Builds ts (type TSVSHMM unless `type` says otherwise) for `problem` with the initial state x0.
// The splits are created in the order `creation` (scale indices; empty: slowest first).
PetscErrorCode CreateSplitTS(MPI_Comm comm, SplitProblem *problem, SplitKind kind, const std::vector<PetscReal> &x0, const std::vector<std::string> &names, TS *ts, Vec *x, const std::vector<int> &creation = {});
PetscErrorCode DestroySplitTS(SplitProblem *problem, TS *ts, Vec *x);
// The full state on every rank.
PetscErrorCode GatherState(SplitProblem *problem, Vec x, std::vector<PetscReal> &out);

// The paper's dissipative example (xi, eta, zeta) with eps: three scales.
struct DissipativeParams {
  PetscReal eps = 1e-2;
};
void DissipativeProblem(SplitProblem *p, const DissipativeParams *params);
// The same with the slow term given as two splits of one half each (four splits, three scales).
void DissipativeProblemWithSlowHalves(SplitProblem *p, const DissipativeParams *params);

// A four-scale dissipative chain with a known averaged equation:
//   x0' = sin(x1) - x0/2,  x1' = (x0 - x1)/e1,  x2' = (x1 + x0 - x2)/e2,  x3' = (x2 - x3)/e3,
// whose fast variables relax to x1 = x0, x2 = 2 x0, x3 = 2 x0, so that X' = sin(X) - X/2.
struct ChainParams {
  PetscReal e1 = 1e-2, e2 = 1e-3, e3 = 1e-4;
};
void ChainProblem(SplitProblem *p, const ChainParams *params);

// Runs the TS's error path with errors captured: returns the error code and the first message.
struct CapturedError {
  PetscErrorCode code = 0;
  std::string    message;
};
CapturedError CaptureError(const std::function<PetscErrorCode()> &f);
