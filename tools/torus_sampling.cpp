// torus_sampling - the torus picture of Lee & Engquist (section "Variable Step Size
// Heterogeneous Multiscale Methods", the two figures "60 sampling points of constant / variable
// time steps in several copies of a torus, beta = sqrt(1.01)"): how well the phases of two
// periodic fast variables are sampled by one VSHMM run with constant and with variable
// mesoscopic steps.
//
// The model (the paper's): the fastest variable zeta and the intermediate one eta are periodic,
// both with period 1 (time measured in periods). One micro cycle advances zeta by the micro
// step dt and eta by the mesoscopic step h_2. With constant steps h_2 = beta dt, so the cycle
// end points (eta_k, zeta_k) lie on a straight line of slope 1/beta in the plane; the phases
// (eta_k mod 1, zeta_k mod 1) are the points at which the effective force is sampled on the
// torus. With variable steps h_2(t) = beta dt K(Theta^{-1}(u)) (the library's schedule,
// vshmm::MesoscopicSchedule with two scales and savings factor beta, whose kernel period P, one
// macro step, is chosen so that it holds exactly the N cycles), the line bends into a curve and
// its phases spread over the torus. (For constant steps P does not matter.)
//
// How evenly a point set covers the torus is measured by its star discrepancy
//   D*_N = sup over a, b in [0,1] of | #{points in [0,a) x [0,b)} / N - a b |,
// computed exactly (O(N^3): the supremum is attained at boxes whose corners are point
// coordinates or 1, counted open and closed). For comparison: N random points have
// D* ~ 1/sqrt(N) on average (0.1 to 0.2 for N = 60), a good lattice ~ log(N)/N.
//
// Usage: torus_sampling [--n 60] [--beta 1.00498756...] [--dt 0.14142...] [--kernel cosine]
//                       [--order q] [--table]
//   Prints a header with both discrepancies, then the two point sets as gnuplot data blocks
//   (index 0: constant steps, index 1: variable steps) with columns
//   k  eta  zeta  eta_mod_1  zeta_mod_1 (eta, zeta: unwrapped, in periods).
//   --table prints instead D* for constant and variable steps over a range of dt and N.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "kernel.hpp"
#include "schedule.hpp"

namespace {

struct Point {
  double eta, zeta; // unwrapped, in periods
};

double frac(double x)
{
  return x - std::floor(x);
}

// Exact star discrepancy of points in [0,1)^2.
double starDiscrepancy(const std::vector<Point> &pts)
{
  const std::size_t   n = pts.size();
  std::vector<double> xs, ys;
  for (const Point &p : pts) {
    xs.push_back(frac(p.eta));
    ys.push_back(frac(p.zeta));
  }
  std::vector<double> ax(xs), by(ys);
  ax.push_back(1.0);
  by.push_back(1.0);
  std::sort(ax.begin(), ax.end());
  std::sort(by.begin(), by.end());
  ax.erase(std::unique(ax.begin(), ax.end()), ax.end());
  by.erase(std::unique(by.begin(), by.end()), by.end());
  double d = 0.0;
  for (double a : ax)
    for (double b : by) {
      std::size_t open = 0, closed = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (xs[i] < a && ys[i] < b) ++open;
        if (xs[i] <= a && ys[i] <= b) ++closed;
      }
      d = std::max(d, std::max(a * b - (double)open / n, (double)closed / n - a * b));
    }
  return d;
}

// The cycles of one macro step (kernel period) P: zeta advances by dt, eta by h_2(tau); the
// cycle end points (the first is the start (0,0)) until tau reaches P.
std::vector<Point> cyclePoints(const vshmm::MesoscopicSchedule &schedule, double period, int maxPoints)
{
  std::vector<Point> pts;
  double             tau = 0.0, eta = 0.0, zeta = 0.0;
  const double       dt = schedule.microStep();
  while (tau < period && (int)pts.size() < maxPoints) {
    pts.push_back({eta, zeta});
    zeta += dt; // micro step (level 1)
    tau += dt;
    const double h = schedule.levelStep(0, tau, period); // mesoscopic step h_2 (level 0)
    eta += h;
    tau += h;
  }
  return pts;
}

// N sampling points: the cycles of one macro step whose kernel period P holds exactly N cycles
// (P found by bisection: the number of cycles grows with P).
std::vector<Point> samplePoints(int n, double beta, double dt, const vshmm::Kernel &kernel)
{
  const vshmm::MesoscopicSchedule schedule(kernel, dt, {beta}, {1});
  double                          lo = n * dt, hi = 4.0 * n * dt * (1.0 + beta);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((int)cyclePoints(schedule, mid, n + 1).size() < n) lo = mid;
    else hi = mid;
  }
  std::vector<Point> pts = cyclePoints(schedule, hi, n);
  if ((int)pts.size() != n) { // cannot happen for a positive kernel; be safe
    std::fprintf(stderr, "torus_sampling: could not fit %d cycles into one kernel period\n", n);
    std::exit(1);
  }
  return pts;
}

[[noreturn]] void usage(const char *msg)
{
  std::fprintf(stderr, "torus_sampling: %s\nusage: torus_sampling [--n N] [--beta B] [--dt DT] [--kernel cosine|polynomial|exponential] [--order q] [--table]\n", msg);
  std::exit(2);
}

double number(const char *s)
{
  char  *end = nullptr;
  double v   = std::strtod(s, &end);
  if (end == s || *end != '\0' || !std::isfinite(v)) usage((std::string("not a number: ") + s).c_str());
  return v;
}

} // namespace

int main(int argc, char **argv)
{
  int               n = 60, order = 1;
  double            beta = std::sqrt(1.01), dt = 0.1 * std::sqrt(2.0);
  bool              table = false;
  vshmm::KernelType type  = vshmm::KernelType::Cosine;
  for (int i = 1; i < argc; ++i) {
    const std::string a     = argv[i];
    auto              value = [&]() -> const char              *{
      if (i + 1 >= argc) usage(("missing value after " + a).c_str());
      return argv[++i];
    };
    if (a == "--n") n = (int)number(value());
    else if (a == "--beta") beta = number(value());
    else if (a == "--dt") dt = number(value());
    else if (a == "--order") order = (int)number(value());
    else if (a == "--table") table = true;
    else if (a == "--kernel") {
      const std::string k = value();
      if (k == "cosine") type = vshmm::KernelType::Cosine;
      else if (k == "polynomial") type = vshmm::KernelType::Polynomial;
      else if (k == "exponential") type = vshmm::KernelType::Exponential;
      else usage("--kernel must be cosine, polynomial or exponential");
    } else usage(("unknown argument " + a).c_str());
  }
  if (n < 1 || !(beta > 0) || !(dt > 0)) usage("--n, --beta and --dt must be positive");

  const auto constant = vshmm::Kernel::create(vshmm::KernelType::Constant);
  const auto variable = vshmm::Kernel::create(type, order);

  if (table) {
    const double dts[] = {0.01, 0.03, 0.05, 0.1, 0.1 * std::sqrt(2.0), 0.2, 0.3, 0.5, 0.7};
    const int    ns[]  = {60, 120, 240};
    std::printf("# star discrepancy D* of the torus sampling, beta = %.8f, kernel %s\n", beta, variable->name().c_str());
    std::printf("# %-10s", "dt");
    for (int N : ns) std::printf("  const N=%-4d  var N=%-4d ", N, N);
    std::printf("\n");
    for (double d : dts) {
      std::printf("  %-10.6f", d);
      for (int N : ns) std::printf("  %-11.4f  %-11.4f", starDiscrepancy(samplePoints(N, beta, d, *constant)), starDiscrepancy(samplePoints(N, beta, d, *variable)));
      std::printf("\n");
    }
    // A finer scan: dt = 0.01 + 0.48 i / 199, i = 0..199 (almost all of them irrational
    // fractions of the period in floating point terms); how often variable steps cover better.
    for (int N : ns) {
      std::vector<double> c, v;
      int                 better = 0;
      for (int i = 0; i < 200; ++i) {
        const double d  = 0.01 + 0.48 * i / 199.0;
        const double dc = starDiscrepancy(samplePoints(N, beta, d, *constant)), dv = starDiscrepancy(samplePoints(N, beta, d, *variable));
        c.push_back(dc);
        v.push_back(dv);
        better += dv < dc;
      }
      std::sort(c.begin(), c.end());
      std::sort(v.begin(), v.end());
      std::printf("# N = %d, 200 values of dt in [0.01, 0.49]: variable below constant in %d; median D* constant %.4f variable %.4f\n", N, better, (c[99] + c[100]) / 2, (v[99] + v[100]) / 2);
    }
    return 0;
  }

  const std::vector<Point> pc = samplePoints(n, beta, dt, *constant), pv = samplePoints(n, beta, dt, *variable);
  const double             dc = starDiscrepancy(pc), dv = starDiscrepancy(pv);
  std::printf("# torus_sampling: N = %d cycles in one kernel period, beta = h_2/dt = %.10f, micro step dt = %g periods\n", n, beta, dt);
  std::printf("# star discrepancy constant %.6f variable %.6f (kernel %s)\n", dc, dv, variable->name().c_str());
  const char               *names[2] = {"constant steps", "variable steps"};
  const std::vector<Point> *sets[2]  = {&pc, &pv};
  for (int s = 0; s < 2; ++s) {
    std::printf("%s# %s: star discrepancy %.6f\n# k eta zeta eta_mod_1 zeta_mod_1\n", s ? "\n\n" : "", names[s], s ? dv : dc);
    for (std::size_t k = 0; k < sets[s]->size(); ++k) {
      const Point &p = (*sets[s])[k];
      std::printf("%zu %.10f %.10f %.10f %.10f\n", k, p.eta, p.zeta, frac(p.eta), frac(p.zeta));
    }
  }
  return 0;
}
