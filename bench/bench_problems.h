/*
   bench_problems.h - the right-hand sides of the ODE benchmark problems in plain C (no PETSc, no
   SUNDIALS), for the benchmark's own drivers (bench_imex.c, bench_sundials.c). They are the same
   fields as examples/ode/oscillatory.c, examples/ode/dissipative.c and examples/stress/chain.c
   (the benchmark checks that the drivers reproduce the examples' converged references).

   A problem is dx/dt = f_0(x) + f_1(x)/eps_1 + ... + f_K(x)/eps_K with K+1 terms ("scales",
   slowest first); BenchTerm() returns one term (with its 1/eps factor) as a full-size vector,
   BenchTermJacobian() the dense Jacobian of a range of terms.
*/
#ifndef BENCH_PROBLEMS_H
#define BENCH_PROBLEMS_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BENCH_MAX_N 6

typedef enum {
  BENCH_OSCILLATORS,
  BENCH_DISSIPATIVE,
  BENCH_CHAIN
} BenchKind;

typedef struct {
  BenchKind kind;
  int       n;      /* unknowns */
  int       nterms; /* K+1 */
  double    eps;    /* oscillators, dissipative: eps; chain: e (e_k = e^k) */
  double    ek[BENCH_MAX_N];
  double    x0[BENCH_MAX_N];
} BenchProblem;

/* Set up a problem by name: "oscillators" (eps), "dissipative" (eps), "chain" (e, nscales); 0 on success */
static int BenchProblemSetUp(BenchProblem *p, const char *name, double eps, int nscales)
{
  int k;

  memset(p, 0, sizeof(*p));
  p->eps = eps;
  if (!strcmp(name, "oscillators")) {
    p->kind   = BENCH_OSCILLATORS;
    p->n      = 4;
    p->nterms = 3;
    p->x0[0]  = 1.0; /* x1, x2, y1, y2 */
    p->x0[1]  = 0.5;
    p->x0[2]  = 0.0;
    p->x0[3]  = 0.5;
  } else if (!strcmp(name, "dissipative")) {
    p->kind   = BENCH_DISSIPATIVE;
    p->n      = 3;
    p->nterms = 3;
    p->x0[0]  = 5.0; /* xi, eta, zeta */
    p->x0[1]  = -10.0;
    p->x0[2]  = 5.0;
  } else if (!strcmp(name, "chain")) {
    if (nscales < 2 || nscales > BENCH_MAX_N) return 1;
    p->kind   = BENCH_CHAIN;
    p->n      = nscales;
    p->nterms = nscales;
    p->x0[0]  = 1.0;
    p->ek[0]  = 1.0;
    for (k = 1; k < nscales; k++) p->ek[k] = p->ek[k - 1] * eps;
  } else return 1;
  return 0;
}

/* Term k of the field at x (with its 1/eps_k factor), written to f (all n components) */
static void BenchTerm(const BenchProblem *p, int k, const double *x, double *f)
{
  int i;

  for (i = 0; i < p->n; i++) f[i] = 0.0;
  switch (p->kind) {
  case BENCH_OSCILLATORS: { /* x = (x1, x2, y1, y2) */
    const double x1 = x[0], x2 = x[1], y1 = x[2], y2 = x[3], e = p->eps;
    if (k == 0) {
      f[0] = -3.0 * x1 * x2 * x2;
      f[1] = -x2;
      f[2] = 0.5 * y1;
      f[3] = -y2 + 2.0 * x1 * x1 * y2;
    } else if (k == 1) {
      f[0] = y2 * y2 / e;
      f[1] = -y2 / e;
      f[3] = x2 / e;
    } else {
      f[0] = -y1 / (e * e);
      f[1] = -y2 / (e * e);
      f[2] = x1 / (e * e);
      f[3] = x2 / (e * e);
    }
  } break;
  case BENCH_DISSIPATIVE: { /* x = (xi, eta, zeta); term k has component k only */
    const double xi = x[0], eta = x[1], zeta = x[2], s = xi + eta + zeta, e = p->eps;
    if (k == 0) f[0] = sin(s) - s * s / 20.0;
    else if (k == 1) f[1] = (3.0 * xi * xi - eta * eta + zeta * zeta) / e;
    else f[2] = (xi - eta - zeta) / (e * e);
  } break;
  case BENCH_CHAIN: /* term k has component k only */
    if (k == 0) f[0] = sin(x[1]) - 0.5 * x[0];
    else f[k] = (x[k - 1] - x[k]) / p->ek[k];
    break;
  }
}

/* f = sum of the terms k0..k1 at x */
static void BenchTerms(const BenchProblem *p, int k0, int k1, const double *x, double *f)
{
  double g[BENCH_MAX_N];
  int    i, k;

  for (i = 0; i < p->n; i++) f[i] = 0.0;
  for (k = k0; k <= k1; k++) {
    BenchTerm(p, k, x, g);
    for (i = 0; i < p->n; i++) f[i] += g[i];
  }
}

/* J (row-major n x n) += the Jacobian of term k at x */
static void BenchTermJacobianAdd(const BenchProblem *p, int k, const double *x, double *J)
{
  const int n = p->n;

  switch (p->kind) {
  case BENCH_OSCILLATORS: {
    const double x1 = x[0], x2 = x[1], y2 = x[3], e = p->eps, e2 = 1.0 / (e * e);
    if (k == 0) {
      J[0 * n + 0] += -3.0 * x2 * x2;
      J[0 * n + 1] += -6.0 * x1 * x2;
      J[1 * n + 1] += -1.0;
      J[2 * n + 2] += 0.5;
      J[3 * n + 0] += 4.0 * x1 * y2;
      J[3 * n + 3] += -1.0 + 2.0 * x1 * x1;
    } else if (k == 1) {
      J[0 * n + 3] += 2.0 * y2 / e;
      J[1 * n + 3] += -1.0 / e;
      J[3 * n + 1] += 1.0 / e;
    } else {
      J[0 * n + 2] += -e2;
      J[1 * n + 3] += -e2;
      J[2 * n + 0] += e2;
      J[3 * n + 1] += e2;
    }
  } break;
  case BENCH_DISSIPATIVE: {
    const double xi = x[0], eta = x[1], zeta = x[2], s = xi + eta + zeta, e = p->eps;
    if (k == 0) {
      const double d = cos(s) - s / 10.0;
      J[0] += d;
      J[1] += d;
      J[2] += d;
    } else if (k == 1) {
      J[n + 0] += 6.0 * xi / e;
      J[n + 1] += -2.0 * eta / e;
      J[n + 2] += 2.0 * zeta / e;
    } else {
      J[2 * n + 0] += 1.0 / (e * e);
      J[2 * n + 1] += -1.0 / (e * e);
      J[2 * n + 2] += -1.0 / (e * e);
    }
  } break;
  case BENCH_CHAIN:
    if (k == 0) {
      J[0] += -0.5;
      J[1] += cos(x[1]);
    } else {
      J[k * n + k - 1] += 1.0 / p->ek[k];
      J[k * n + k] += -1.0 / p->ek[k];
    }
    break;
  }
}

/* The slow observables the benchmark measures: oscillators I1, I2; dissipative xi; chain x0. Returns their number. */
static int BenchObservables(const BenchProblem *p, const double *x, double *q)
{
  if (p->kind == BENCH_OSCILLATORS) {
    q[0] = x[0] * x[0] + x[2] * x[2];
    q[1] = x[1] * x[1] + x[3] * x[3];
    return 2;
  }
  q[0] = x[0];
  return 1;
}

/* Parse a comma-separated list of up to nmax doubles; returns the count */
static int BenchParseList(const char *s, double *v, int nmax)
{
  int   n = 0;
  char *end;

  while (*s && n < nmax) {
    v[n++] = strtod(s, &end);
    if (end == s) return n - 1;
    s = end;
    if (*s == ',') s++;
  }
  return n;
}

#endif
