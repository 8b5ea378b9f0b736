/* outside_problems - the problems of docs/accuracy.md sections 13-23 that are not examples of their
   own ("outside the suite"): small ODEs with a slow and one or two faster levels, component splits
   (or -additive: every split writes every component, its own terms only), observables the first
   component (and a second one for some), run with any TS. Serial.

       outside_problems -prob P [-eps E] [-eps2 E2] [-a A] [-b B] [-d D] [-x0 v,...] [-additive]
                        [-ts_max_time T] [-ts_dt DeltaT] (-ts_type vshmm -ts_vshmm_adapt ... | -ts_type rk ...)

   Prints "T t S0=... S1=... q0 [q1]" at every step (the states and the observables) and a final
   "WORK rhs rhs+adapt est_total e" line for TSVSHMM ("WORK steps n" otherwise).
   tools/adapt_outside.py runs them at three tolerances against RK4 references. The problem
   numbers are those of the sessions that found them; each case says what it is. */
#include <petscts.h>
#include <petscvshmm.h>
#include <string.h>
#include <stdio.h>
#include <vector>

typedef struct {
  PetscInt  prob, n, nobs;
  PetscReal eps, eps2, a, d, b;
  PetscInt  nsplit;
  PetscBool additive;
  PetscInt  comp[4][12], ncomp[4]; /* components written by each split (slowest first) */
} Ctx;

/* full field (every component) */
static void Field(Ctx *c, PetscReal t, const PetscScalar *u, PetscScalar *f)
{
  PetscReal e = c->eps, e2 = c->eps2, a = c->a;
  switch (c->prob) {
  case 0: /* slow explicit time dependence: x' = -y + a sin(3 t) ; y' = -(y - cos(t) sin(x))/eps */
    f[0] = -u[1] + a * PetscSinReal(c->eps2 * 3e5 * t);
    f[1] = -(u[1] - PetscCosReal(c->b * t) * PetscSinReal(u[0])) / e;
    break;
  case 1: /* Duffing fast oscillator drives a slow relaxation: x' = -x + q^2 ; q' = p/eps, p' = -(q + a q^3)/eps; x drains energy weakly */
    f[0] = -u[0] + u[1] * u[1];
    f[1] = u[2] / e;
    f[2] = -(u[1] + a * u[1] * u[1] * u[1]) / e - c->d * u[0] * u[2];
    break;
  case 2: /* adiabatic oscillator: tau' = 1 ; q' = w(tau) p / eps, p' = -w(tau) q / eps, w = 1 + 0.5 sin(tau) ; plus slow y' = -y + q^2 */
  {
    PetscReal w = 1 + 0.5 * PetscSinReal(u[0]);
    f[0]        = 1;
    f[3]        = -u[3] + u[1] * u[1];
    f[1]        = w * u[2] / e;
    f[2]        = -w * u[1] / e;
  } break;
  case 3: /* 3 scales: slow x' = 1 - x z ; medium z' = -(z - E)/eps, E = (q^2+p^2)/2 ; fast rotation damped by x: q' = p/eps2 - 0.5 x q, p' = -q/eps2 - 0.5 x p + 1 */
    f[0] = 1 - u[0] * u[1];
    f[1] = -(u[1] - 0.5 * (u[2] * u[2] + u[3] * u[3])) / e;
    f[2] = u[3] / e2 - 0.5 * u[0] * u[2];
    f[3] = -u[2] / e2 - 0.5 * u[0] * u[3] + a;
    break;
  case 4: /* 2 slow coupled oscillators + fast decaying: x1' = y1, y1' = -x1 + z ; z' = -(z - x1^2)/eps ; slow harmonic driven by fast slaved nonlinearity */
    f[0] = u[1];
    f[1] = -u[0] + a * u[2];
    f[2] = -(u[2] - u[0] * u[0]) / e;
    break;
  case 5: /* fast decaying level with slowly varying rate: x' = -z + cos(t) ; z' = -(1 + 0.9 sin(x)) (z - x)/eps */
    f[0] = -u[1] + PetscCosReal(t);
    f[1] = -(1 + 0.9 * PetscSinReal(u[0])) * (u[1] - u[0]) / e;
    break;
  case 6: /* underdamped fast spiral slaved to slow: x' = -x + u ; u' = (-u + a v + x)/eps, v' = (-a u - v)/eps  (|Im|/|Re| = a) */
    f[0] = -u[0] + u[1] + PetscSinReal(t);
    f[1] = (-u[1] + a * u[2] + u[0]) / e;
    f[2] = (-a * u[1] - u[2]) / e;
    break;
  case 7: /* dynamic Hopf: x' = 0.5 ; y' = -y + (u^2+v^2) ; u' = (x u - v - u r2)/eps, v' = (u + x v - v r2)/eps */
  {
    PetscReal r2 = u[2] * u[2] + u[3] * u[3];
    f[0]         = 0.5;
    f[1]         = -u[1] + r2;
    f[2]         = (u[0] * u[2] - u[3] - u[2] * r2) / e;
    f[3]         = (u[2] + u[0] * u[3] - u[3] * r2) / e;
  } break;
  case 9: /* Hopf with mu = -0.5 + t/2 explicit: y' = -y + r2 ; (u,v) fast */
  {
    PetscReal r2 = u[1] * u[1] + u[2] * u[2], mu = -0.5 + 0.5 * t;
    f[0] = -u[0] + r2;
    f[1] = (mu * u[1] - u[2] - u[1] * r2) / e;
    f[2] = (u[1] + mu * u[2] - u[2] * r2) / e;
  } break;
  case 10: /* linear 2-scale, from rest at the equilibrium: x' = -x + z ; z' = -(z - x)/eps */
    f[0] = -u[0] + u[1];
    f[1] = -(u[1] - u[0]) / e;
    break;
  case 11: /* a slow load switched on inside a macro step: x' = -x + z + H(t - tj) ; z' = -(z - cos x)/eps */
    f[0] = -u[0] + u[1] + (t >= c->b ? 1.0 : 0.0);
    f[1] = -(u[1] - PetscCosReal(u[0])) / e;
    break;
  case 12: /* a fast level with a spread of rates: z1 rate 1/eps, z2 rate 1/(eps e2) */
    f[0] = -u[0] + u[1] + u[2];
    f[1] = -(u[1] - PetscCosReal(u[0])) / e;
    f[2] = -(u[2] - PetscSinReal(u[0])) / (e * e2);
    break;
  case 13: /* observing a fast phase: x' = -x + q^2 ; q' = p/eps, p' = -q/eps */
    f[0] = -u[0] + u[1] * u[1];
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    break;
  case 14: /* the 'slow' split stiffer than the 'fast' one: x' = -1e4 (x - z) ; z' = -(z - cos t)/eps */
    f[0] = -a * (u[0] - u[1]);
    f[1] = -(u[1] - PetscCosReal(t)) / e;
    break;
  case 15: /* three levels, the medium phase observed: x' = -x + u^2 ; (u, v) rotation at 1/eps ; w' = -(w - u)/eps2 (fast, decaying), u' += -0.1 (w - u) */
    f[0] = -u[0] + u[1] * u[1];
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    f[3] = -(u[3] - u[1]) / e2;
    break;
  case 8: /* slow time dependence inside the fast split: x' = -x + z ; z' = -(z - cos(a t) x)/eps */
    f[0] = -u[0] + u[1];
    f[1] = -(u[1] - PetscCosReal(a * t) * u[0]) / e;
    break;
  case 16: /* Michaelis-Menten: s' = -s + (s + K - L) c ; c' = (s - (s + K) c)/eps, K = 1, L = 0.5 */
    f[0] = -u[0] + (u[0] + 1 - 0.5) * u[1];
    f[1] = (u[0] - (u[0] + 1) * u[1]) / e;
    break;
  case 17: /* nested cascade: x' = 1 - x - z + sin(2t) ; y' = (x^2 - y)/eps ; z' = (y - z)/eps2 */
    f[0] = 1 - u[0] - u[2] + PetscSinReal(2 * t);
    f[1] = (u[0] * u[0] - u[1]) / e;
    f[2] = (u[1] - u[2]) / e2;
    break;
  case 18: /* slaved cubic: x' = a cos(t) - z ; z' = (x^3 - z)/eps */
    f[0] = a * PetscCosReal(t) - u[1];
    f[1] = (u[0] * u[0] * u[0] - u[1]) / e;
    break;
  case 20: /* degenerate (cubic) relaxation: x' = -x + z ; z' = -(z - x)^3/eps */
    f[0] = -u[0] + u[1];
    f[1] = -(u[1] - u[0]) * (u[1] - u[0]) * (u[1] - u[0]) / e;
    break;
  case 21: /* non-normal fast level: x' = -x + z1 ; z1' = (-z1 + a z2 + x)/eps ; z2' = -2 z2/eps */
    f[0] = -u[0] + u[1];
    f[1] = (-u[1] + a * u[2] + u[0]) / e;
    f[2] = -2 * u[2] / e;
    break;
  case 22: /* a steep switch of the fast equilibrium: x' = 1 - z ; z' = -(z - 1 - tanh(a (x - 1)))/eps */
    f[0] = 1 - u[1];
    f[1] = -(u[1] - 1 - PetscTanhReal(a * (u[0] - 1))) / e;
    break;
  case 23: /* slow rotation whose speed is a slaved fast variable: x1' = -x2 z, x2' = x1 z ; z' = -(z - 1 - 0.5 x1)/eps */
    f[0] = -u[1] * u[2];
    f[1] = u[0] * u[2];
    f[2] = -(u[2] - 1 - 0.5 * u[0]) / e;
    break;
  case 24: /* quadratic degenerate relaxation: x' = -x + z ; z' = -(z - x)|z - x|/eps */
    f[0] = -u[0] + u[1];
    f[1] = -(u[1] - u[0]) * PetscAbsReal(u[1] - u[0]) / e;
    break;
  case 25: /* three levels, the medium one degenerate: x' = -x + y + 0.5 sin(t) ; y' = -(y - x)^3/eps ; w' = -(w - y)/eps2, x' += 0 */
    f[0] = -u[0] + u[1] + 0.5 * PetscSinReal(t) + 0.1 * u[2];
    f[1] = -(u[1] - u[0]) * (u[1] - u[0]) * (u[1] - u[0]) / e;
    f[2] = -(u[2] - u[1]) / e2;
    break;
  case 26: /* Michaelis-Menten with a small constant K = a: s' = -s + (s + a/2) c ; c' = (s - (s + a) c)/eps */
    f[0] = -u[0] + (u[0] + 0.5 * a) * u[1];
    f[1] = (u[0] - (u[0] + a) * u[1]) / e;
    break;
  case 27: /* a fast rotation whose frequency falls with a slow variable: x' = -x ; q' = x p/eps, p' = -x q/eps (E/x adiabatic) */
    f[0] = -u[0];
    f[1] = u[0] * u[2] / e;
    f[2] = -u[0] * u[1] / e;
    break;
  case 28: /* the same rotation driving a slow y: x' = -x ; y' = -y + q^2 ; q' = x p/eps, p' = -x q/eps */
    f[0] = -u[0];
    f[1] = -u[1] + u[2] * u[2];
    f[2] = u[0] * u[3] / e;
    f[3] = -u[0] * u[2] / e;
    break;
  case 29: /* a fast limit cycle whose amplitude the slow variable sets (van der Pol with Hopf parameter x, amplitude about 2 sqrt(x)): x' = 1 - x q^2 ; q' = p/eps, p' = (-q + (x - q^2) p)/eps */
    f[0] = 1 - u[0] * u[1] * u[1];
    f[1] = u[2] / e;
    f[2] = (-u[1] + (u[0] - u[1] * u[1]) * u[2]) / e;
    break;
  case 30: /* two fast rotations a beat apart drive a slow variable: x' = -x + q1 q2 ; q1' = p1/eps, p1' = -q1/eps ; q2' = w p2/eps, p2' = -w q2/eps, w = 1 + a eps (q1 q2 holds cos(a t): a slow beat the averaging must keep) */
    f[0] = -u[0] + u[1] * u[3];
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    f[3] = (1 + a * e) * u[4] / e;
    f[4] = -(1 + a * e) * u[3] / e;
    break;
  case 31: /* three fast rotations in a triad resonance, w1 + w2 - w3 = a: x' = -x + 4 q1 q2 q3 ; (q_i, p_i)' = w_i (p_i, -q_i) / eps, w = (1, 1.5, 2.5 - a eps) (q1 q2 q3 holds cos(a t) / 4: a slow combination no pair of them shows) */
    f[0] = -u[0] + 4 * u[1] * u[3] * u[5];
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    f[3] = 1.5 * u[4] / e;
    f[4] = -1.5 * u[3] / e;
    f[5] = (2.5 - a * e) * u[6] / e;
    f[6] = -(2.5 - a * e) * u[5] / e;
    break;
  case 32: /* a beat in the medium level of three: x' = -x + u1 u2 ; (u1, v1)' = (v1, -u1) / eps, (u2, v2)' = w (v2, -u2) / eps, w = 1 + a eps ; fast w' = -(w - u1) / eps2 */
    f[0] = -u[0] + u[1] * u[3];
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    f[3] = (1 + a * e) * u[4] / e;
    f[4] = -(1 + a * e) * u[3] / e;
    f[5] = -(u[5] - u[1]) / e2;
    break;
  case 33: /* the beat of problem 30 through squares: x' = -x + 8 q1^2 q2^2 - 2 (the mean of 8 q1^2 q2^2 over the fast phases is 2 + cos(2 a t)) */
    f[0] = -u[0] + 8 * u[1] * u[1] * u[3] * u[3] - 2;
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    f[3] = (1 + a * e) * u[4] / e;
    f[4] = -(1 + a * e) * u[3] / e;
    break;
  case 34: /* a fast band: x' = -x + 2 m + sin t, m the mean of u_1..u_7 ; u_i' = (u_{i-1} - 2 u_i + u_{i+1})/eps + a (x - u_i) (a no-flux chain: rates a to a + 4/eps, the slowest, the mean's, a = 30 times the slow one) */
  {
    PetscReal m = 0;
    for (PetscInt i = 1; i <= 7; i++) m += u[i] / 7;
    f[0] = -u[0] + 2 * m + PetscSinReal(t);
    for (PetscInt i = 1; i <= 7; i++) f[i] = (u[i > 1 ? i - 1 : 1] - 2 * u[i] + u[i < 7 ? i + 1 : 7]) / e + a * (u[0] - u[i]);
  } break;
  case 35: /* a slow rotation at frequency a, turning within a few macro steps, driven by a slaved fast variable: x1' = a x2 + z, x2' = -a x1 ; z' = -(z - x1^2)/eps (x1 and x2 observed) */
    f[0] = a * u[1] + u[2];
    f[1] = -a * u[0];
    f[2] = -(u[2] - u[0] * u[0]) / e;
    break;
  case 36: /* four fast rotations in a quartet resonance, w1 - w2 - w3 + w4 = -a eps: x' = -x + 8 q1 q2 q3 q4 ; (q_i, p_i)' = w_i (p_i, -q_i) / eps, w = (1, 1.5, 2.35, 2.85 - a eps) (8 q1 q2 q3 q4 holds cos(a t): a slow combination no pair or triad of them shows) */
    f[0] = -u[0] + 8 * u[1] * u[3] * u[5] * u[7];
    f[1] = u[2] / e;
    f[2] = -u[1] / e;
    f[3] = 1.5 * u[4] / e;
    f[4] = -1.5 * u[3] / e;
    f[5] = 2.35 * u[6] / e;
    f[6] = -2.35 * u[5] / e;
    f[7] = (2.85 - a * e) * u[8] / e;
    f[8] = -(2.85 - a * e) * u[7] / e;
    break;
  case 37: /* a beat that slows down through the run: x' = -x + q1 q2 ; tau' = 1 ; q1' = p1/eps, p1' = -q1/eps ; q2' = w p2/eps, p2' = -w q2/eps, w = 1 + b (1 - tau / a) (the beat (w - 1) / eps falls from b / eps at t = 0 to 0 at t = a: a fast process that becomes a slow one) */
  {
    const PetscReal w = 1 + c->b * (1 - u[1] / a);
    f[0]              = -u[0] + u[2] * u[4];
    f[1]              = 1;
    f[2]              = u[3] / e;
    f[3]              = -u[2] / e;
    f[4]              = w * u[5] / e;
    f[5]              = -w * u[4] / e;
  } break;
  case 38: /* an unstable slow equation (a saddle) driven by a slaved fast variable: x' = a (x - 1) + z / 2 ; z' = -(z - cos x)/eps (on the slow manifold x' = a (x - 1) + cos(x) / 2, unstable at its equilibrium x* (0.582 for a = 1, 0.811 for a = 2) with rate a - sin(x*) / 2: an error made at t grows by e^(mu (T - t))) */
    f[0] = a * (u[0] - 1) + 0.5 * u[1];
    f[1] = -(u[1] - PetscCosReal(u[0])) / e;
    break;
  case 39: /* an instability the slow split's own Jacobian (-1) does not show, made by the coupling: x' = -x + 2 z ; z' = -(z - x - 0.01)/eps (on the slow manifold x' = x + 0.02: errors grow as e^t) */
    f[0] = -u[0] + 2 * u[1];
    f[1] = -(u[1] - u[0] - 0.01) / e;
    break;
  case 40: /* Kapitza's pendulum, the pivot vibrating as a fast oscillator (q, p) of frequency 1/eps and amplitude a: theta' = v, v' = -(1 - a q / eps^2) sin(theta) ; q' = -p/eps, p' = q/eps (the inverted position is stable where (a / eps)^2 > 2: an error turns with the slow oscillation about it, and grows for a part of its turn) */
    f[0] = u[1];
    f[1] = -(1 - a * u[2] / (e * e)) * PetscSinReal(u[0]);
    f[2] = -u[3] / e;
    f[3] = u[2] / e;
    break;
  case 41: /* a slow predator-prey cycle (a center: Lotka-Volterra) whose predator grows with a slaved fast variable: x' = x (2 - y), y' = y (z - 1) ; z' = -(z - x)/eps (on the slow manifold y' = y (x - 1): closed orbits about (1, 2), an error carried round them, neither growing nor damped on average) */
    f[0] = u[0] * (2 - u[1]);
    f[1] = u[1] * (u[2] - 1);
    f[2] = -(u[2] - u[0]) / e;
    break;
  case 42: /* a switch in the fast level: the slaved variable's equilibrium jumps by a at t = b: x' = -x + z ; z' = -(z - cos x - a H(t - b))/eps (the slow split sees the jump only through z) */
    f[0] = -u[0] + u[1];
    f[1] = -(u[1] - PetscCosReal(u[0]) - (t >= c->b ? a : 0.0)) / e;
    break;
  case 19: /* three-level chemistry: A' = -A + B ; B' = (A - 2 B + C)/eps ; C' = (B - C - C^3)/eps2 */
    f[0] = -u[0] + u[1];
    f[1] = (u[0] - 2 * u[1] + u[2]) / e;
    f[2] = (u[1] - u[2] - u[2] * u[2] * u[2]) / e2;
    break;
  }
}

static PetscErrorCode Split(TS ts, PetscReal t, Vec U, Vec F, void *ctx, PetscInt s)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *u;
  PetscScalar       *f, full[12];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  Field(c, t, u, full);
  if (c->additive) {
    for (PetscInt k = 0; k < c->n; k++) f[k] = 0;
    for (PetscInt k = 0; k < c->ncomp[s]; k++) f[c->comp[s][k]] = full[c->comp[s][k]];
  } else
    for (PetscInt k = 0; k < c->ncomp[s]; k++) f[k] = full[c->comp[s][k]]; /* component split: F holds the IS's components */
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}
static PetscErrorCode S0(TS ts, PetscReal t, Vec U, Vec F, void *c)
{
  return Split(ts, t, U, F, c, 0);
}
static PetscErrorCode S1(TS ts, PetscReal t, Vec U, Vec F, void *c)
{
  return Split(ts, t, U, F, c, 1);
}
static PetscErrorCode S2(TS ts, PetscReal t, Vec U, Vec F, void *c)
{
  return Split(ts, t, U, F, c, 2);
}
static PetscErrorCode Full(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *u;
  PetscScalar       *f;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(F, &f));
  Field(c, t, u, f);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

static void Obs(Ctx *c, PetscReal t, const PetscScalar *u, PetscReal *q)
{
  q[0] = u[0]; /* the slow variable, and a second observable where the problem has two (kSetups) */
  switch (c->prob) {
  case 1: /* and the Duffing oscillator's energy */
    q[1] = 0.5 * (u[2] * u[2] + u[1] * u[1] + 0.5 * c->a * PetscPowReal(u[1], 4));
    break;
  case 2: /* the adiabatic oscillator's energy scaled by its frequency, and y */
    q[0] = 0.5 * (u[1] * u[1] + u[2] * u[2]) * (1 + 0.5 * PetscSinReal(u[0]));
    q[1] = u[3];
    break;
  case 4:
  case 41:
  case 13:
  case 15:
  case 35:
    q[1] = u[1];
    break;
  case 7:
  case 28:
    q[0] = u[1];
    break;
  case 27: /* and the rotation's energy */
    q[1] = 0.5 * (u[1] * u[1] + u[2] * u[2]);
    break;
  }
}

static PetscErrorCode ObsFn(TS ts, PetscReal t, Vec X, PetscReal q[], void *ctx)
{
  const PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &u));
  Obs((Ctx *)ctx, t, u, q);
  PetscCall(VecRestoreArrayRead(X, &u));
  PetscFunctionReturn(0);
}
static PetscErrorCode Mon(TS ts, PetscInt step, PetscReal t, Vec X, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *u;
  PetscReal          q[12];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &u));
  Obs(c, t, u, q);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "T %.10g", (double)t));
  if (step >= 0) {
    for (PetscInt i = 0; i < c->n; i++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, " S%d=%.17g", (int)i, (double)u[i]));
  }
  for (PetscInt i = 0; i < c->nobs; i++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, " %.15e", (double)q[i]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "\n"));
  PetscCall(VecRestoreArrayRead(X, &u));
  PetscFunctionReturn(0);
}

/* "LABEL steps steps+estimates est_total E single_rate S" for a TSVSHMM run (S: single-rate TSRK steps at its micro steps) (tools/adapt_outside.py reads it) */
static PetscErrorCode PrintWork(TS ts, const char *label)
{
  TSVSHMMStatistics st;
  PetscInt64        tot = 0;
  PetscFunctionBeginUser;
  PetscCall(TSVSHMMGetStatistics(ts, &st));
  for (PetscInt i = 0; i < st.nsplits; i++) tot += st.rhs_evaluations[i];
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %lld %lld est_total %g single_rate %lld\n", label, (long long)tot, (long long)(tot + st.adapt_evaluations), (double)st.error_estimate_total, (long long)st.single_rate_evaluations));
  PetscFunctionReturn(0);
}

/* Each problem's observables' count, the components each split writes (slowest first) and its
   initial state (-x0 replaces it); its number of components is the state's length. */
struct Setup {
  PetscInt                           prob, nobs;
  std::vector<std::vector<PetscInt>> splits;
  std::vector<PetscReal>             u0;
};
static const Setup kSetups[] = {
  {0, 1, {{0}, {1}}, {1, 0}},
  {1, 2, {{0}, {1, 2}}, {0, 1, 0}},
  {2, 2, {{0, 3}, {1, 2}}, {0, 1, 0, 0}},
  {3, 1, {{0}, {1}, {2, 3}}, {0.5, 0.5, 1, 0}},
  {4, 2, {{0, 1}, {2}}, {0.5, 0, 0}},
  {5, 1, {{0}, {1}}, {1, 1}},
  {6, 1, {{0}, {1, 2}}, {1, 0, 0}},
  {7, 1, {{0, 1}, {2, 3}}, {-0.5, 0, 0.5, 0}},
  {8, 1, {{0}, {1}}, {1, 0}},
  {9, 1, {{0}, {1, 2}}, {0, 0.5, 0}},
  {10, 1, {{0}, {1}}, {0, 0}},
  {11, 1, {{0}, {1}}, {1, 0.5}},
  {12, 1, {{0}, {1, 2}}, {1, 0, 0}},
  {13, 2, {{0}, {1, 2}}, {0, 1, 0}},
  {14, 1, {{0}, {1}}, {1, 0}},
  {15, 2, {{0}, {1, 2}, {3}}, {0, 1, 0, 1}},
  {16, 1, {{0}, {1}}, {1, 0}},
  {17, 1, {{0}, {1}, {2}}, {2, 0, 0}},
  {18, 1, {{0}, {1}}, {0.5, 0.125}},
  {19, 1, {{0}, {1}, {2}}, {2, 0, 0}},
  {20, 1, {{0}, {1}}, {1, 0}},
  {21, 1, {{0}, {1, 2}}, {1, 0, 1}},
  {22, 1, {{0}, {1}}, {0, 0}},
  {23, 1, {{0, 1}, {2}}, {1, 0, 1.5}},
  {24, 1, {{0}, {1}}, {1, 0}},
  {25, 1, {{0}, {1}, {2}}, {1, 0, 0}},
  {26, 1, {{0}, {1}}, {1, 0}},
  {27, 2, {{0}, {1, 2}}, {1, 1, 0}},
  {28, 1, {{0, 1}, {2, 3}}, {1, 0, 1, 0}},
  {29, 1, {{0}, {1, 2}}, {0.2, 0.5, 0}},
  {30, 1, {{0}, {1, 2, 3, 4}}, {0, 1, 0, 1, 0}},
  {31, 1, {{0}, {1, 2, 3, 4, 5, 6}}, {0, 1, 0, 1, 0, 1, 0}},
  {32, 1, {{0}, {1, 2, 3, 4}, {5}}, {0, 1, 0, 1, 0, 0}},
  {33, 1, {{0}, {1, 2, 3, 4}}, {0, 1, 0, 1, 0}},
  {34, 1, {{0}, {1, 2, 3, 4, 5, 6, 7}}, {1, 0.97, 0.78, 0.43, 0, -0.43, -0.78, -0.97}},
  {35, 2, {{0, 1}, {2}}, {1, 0, 0}},
  {36, 1, {{0}, {1, 2, 3, 4, 5, 6, 7, 8}}, {0, 1, 0, 1, 0, 1, 0, 1, 0}},
  {37, 1, {{0, 1}, {2, 3, 4, 5}}, {0, 0, 1, 0, 1, 0}},
  {38, 1, {{0}, {1}}, {0.59, 0.8309406791}},
  {39, 1, {{0}, {1}}, {0, 0.01}},
  {40, 1, {{0, 1}, {2, 3}}, {2.8415926535897931, 0, 1, 0}},
  {41, 2, {{0, 1}, {2}}, {2, 2, 2}},
  {42, 1, {{0}, {1}}, {1, 0.5}},
};

int main(int argc, char **argv)
{
  Ctx          c;
  TS           ts;
  Vec          U;
  PetscBool    isv, noobs = PETSC_FALSE;
  PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TSVSHMMInitializePackage());
  memset(&c, 0, sizeof c);
  c.eps  = 1e-3;
  c.eps2 = 1e-5;
  c.a    = 1;
  c.d    = 0.5;
  c.b    = 1;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-b", &c.b, NULL));
  PetscBool obs1 = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-obs1", &obs1, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-d", &c.d, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-prob", &c.prob, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-eps", &c.eps, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-eps2", &c.eps2, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-a", &c.a, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-noobs", &noobs, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-additive", &c.additive, NULL));
  PetscReal    u0[12] = {0};
  const Setup *setup  = nullptr;
  for (const Setup &st : kSetups)
    if (st.prob == c.prob) setup = &st;
  PetscCheck(setup, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-prob %d: no such problem (0-42, the cases of Field())", (int)c.prob);
  c.n      = (PetscInt)setup->u0.size();
  c.nobs   = setup->nobs;
  c.nsplit = (PetscInt)setup->splits.size();
  for (PetscInt s = 0; s < c.nsplit; ++s) {
    c.ncomp[s] = (PetscInt)setup->splits[s].size();
    for (PetscInt k = 0; k < c.ncomp[s]; ++k) c.comp[s][k] = setup->splits[s][k];
  }
  for (PetscInt i = 0; i < c.n; ++i) u0[i] = setup->u0[i];
  if (obs1) c.nobs = 1;
  {
    PetscReal xs[12];
    PetscInt  nx = 12;
    PetscBool set;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-x0", xs, &nx, &set));
    if (set)
      for (PetscInt i = 0; i < nx; i++) u0[i] = xs[i];
  }
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c.n, &U));
  PetscCall(VecGetArray(U, &u));
  for (PetscInt i = 0; i < c.n; i++) u[i] = u0[i];
  PetscCall(VecRestoreArray(U, &u));
  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetProblemType(ts, TS_NONLINEAR));
  PetscCall(TSSetRHSFunction(ts, NULL, Full, &c));
  const char *names[3] = {"slow", "medium", "fast"};
  if (c.nsplit == 2) names[1] = "fast";
  PetscErrorCode (*fns[3])(TS, PetscReal, Vec, Vec, void *) = {S0, S1, S2};
  PetscBool reverse                                         = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-reverse", &reverse, NULL));
  for (PetscInt s0 = 0; s0 < c.nsplit; s0++) {
    PetscInt s = reverse ? c.nsplit - 1 - s0 : s0;
    IS       is;
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, c.ncomp[s], c.comp[s], PETSC_COPY_VALUES, &is));
    if (!c.additive) PetscCall(TSRHSSplitSetIS(ts, names[s], is));
    else {
      IS all;
      PetscCall(ISCreateStride(PETSC_COMM_SELF, c.n, 0, 1, &all));
      PetscCall(TSRHSSplitSetIS(ts, names[s], all));
      PetscCall(ISDestroy(&all));
    }
    PetscCall(TSRHSSplitSetRHSFunction(ts, names[s], NULL, fns[s], &c));
    PetscCall(ISDestroy(&is));
  }
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, 1));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSMonitorSet(ts, Mon, &c, NULL));
  {
    PetscReal t0 = 0;
    PetscBool set;
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-t0", &t0, &set));
    if (set) PetscCall(TSSetTime(ts, t0));
  }
  PetscCall(TSSetFromOptions(ts));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, "vshmm", &isv));
  if (isv && !noobs) PetscCall(TSVSHMMSetObservables(ts, obs1 ? 1 : c.nobs, ObsFn, &c));
  PetscInt nloop = 1;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-loop", &nloop, NULL));
  if (nloop > 1) {
    PetscReal tf;
    PetscCall(TSGetMaxTime(ts, &tf));
    for (PetscInt k = 1; k <= nloop; k++) {
      PetscCall(TSSetMaxTime(ts, tf * k / nloop));
      PetscCall(TSSolve(ts, U));
    }
  } else PetscCall(TSSolve(ts, U));
  PetscReal dt2 = 0;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-dt2", &dt2, NULL));
  if (dt2 > 0) { /* continue to twice the final time with another sampling interval */
    PetscReal tf;
    PetscCall(TSGetMaxTime(ts, &tf));
    PetscCall(TSSetTimeStep(ts, dt2));
    PetscCall(TSSetMaxTime(ts, 2 * tf));
    PetscCall(TSSolve(ts, U));
  }
  PetscBool restart = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-restart", &restart, NULL));
  if (restart) { /* a second solve from the start (an ensemble member): time, step number and state reset */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESTART\n"));
    if (isv) PetscCall(PrintWork(ts, "WORK1"));
    PetscCall(TSSetTime(ts, 0));
    PetscCall(TSSetStepNumber(ts, 0));
    PetscCall(TSSetTimeStep(ts, 0.1));
    PetscCall(VecGetArray(U, &u));
    for (PetscInt i = 0; i < c.n; i++) u[i] = u0[i];
    PetscCall(VecRestoreArray(U, &u));
    PetscCall(TSSolve(ts, U));
  }
  if (isv) PetscCall(PrintWork(ts, "WORK"));
  else {
    PetscInt st;
    PetscCall(TSGetStepNumber(ts, &st));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "WORK steps %d\n", (int)st));
  }
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFinalize());
  return 0;
}
