// oscillatory_reference - reference solutions of the resonant-oscillator example
// (examples/ode/oscillatory.c) by classical RK4 with a constant step, written as a plain loop
// (no PETSc): about 50x faster than TSRK on this 4-component system, so that the long
// references (t = 8 with steps down to 3.125e-9, i.e. 2.6e9 steps) take minutes, not hours.
// Same scheme as `oscillatory -ts_type rk -ts_rk_type 4`; the state update is summed with
// Kahan compensation (or in long double with --long-double) so that round-off stays far below
// the discretisation error even after 1e9 steps.
//
//   dx1/dt = -y1/eps^2 + y2^2/eps - 3 x1 x2^2
//   dx2/dt = -(1/eps^2 + 1/eps) y2 - x2
//   dy1/dt = x1/eps^2 + y1/2
//   dy2/dt = (1/eps^2 + 1/eps) x2 - y2 + 2 x1^2 y2,      state (x1, x2, y1, y2)
//
// Usage: oscillatory_reference [--dt 2.5e-8] [--tmax 0.8] [--print 0.8] [--eps 1e-3]
//                              [--x0 1,0.5,0,0.5] [--csv FILE] [--csv-every 0.01] [--long-double]
// Prints "t T I1 ... I2 ..." at the multiples of --print (each must be a whole number of steps)
// and "final t ... I1 ... I2 ...", "steps N", "wall_time S". --csv writes t,I1,I2 at the
// multiples of --csv-every.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

struct Options {
  double      dt = 2.5e-8, tmax = 0.8, print = 0.8, eps = 1e-3, csvEvery = 0.01;
  double      x0[4] = {1.0, 0.5, 0.0, 0.5};
  std::string csv;
  bool        longDouble = false;
};

[[noreturn]] void usage(const char *msg)
{
  std::fprintf(stderr,
               "oscillatory_reference: %s\n"
               "usage: oscillatory_reference [--dt DT] [--tmax T] [--print P] [--eps E] [--x0 a,b,c,d]\n"
               "                             [--csv FILE] [--csv-every C] [--long-double]\n",
               msg);
  std::exit(2);
}

double number(const char *s)
{
  char  *end = nullptr;
  double v   = std::strtod(s, &end);
  if (end == s || *end != '\0' || !std::isfinite(v)) usage((std::string("not a number: ") + s).c_str());
  return v;
}

// The number of steps of length dt in the interval T; it must be a whole number (to 1e-9).
long long wholeSteps(double T, double dt, const char *what)
{
  double    n = T / dt;
  long long k = std::llround(n);
  if (k <= 0 || std::fabs(n - (double)k) > 1e-9 * n) usage((std::string(what) + " is not a whole number of steps dt").c_str());
  return k;
}

template <class Real>
struct System {
  Real e2, e1, w2; // 1/eps^2, 1/eps, 1/eps^2 + 1/eps
  explicit System(double eps) : e2(Real(1) / (Real(eps) * Real(eps))), e1(Real(1) / Real(eps)), w2(e2 + e1) {}
  void f(const Real *x, Real *d) const
  {
    const Real x1 = x[0], x2 = x[1], y1 = x[2], y2 = x[3];
    d[0] = -y1 * e2 + y2 * y2 * e1 - 3 * x1 * x2 * x2;
    d[1] = -w2 * y2 - x2;
    d[2] = x1 * e2 + y1 / 2;
    d[3] = w2 * x2 - y2 + 2 * x1 * x1 * y2;
  }
};

template <class Real>
int run(const Options &o)
{
  const System<Real> sys(o.eps);
  const long long    nsteps = wholeSteps(o.tmax, o.dt, "--tmax");
  const long long    nprint = wholeSteps(o.print, o.dt, "--print");
  const long long    ncsv   = o.csv.empty() ? 0 : wholeSteps(o.csvEvery, o.dt, "--csv-every");
  const Real         h      = Real(o.dt);
  Real               x[4], c[4] = {0, 0, 0, 0}, k1[4], k2[4], k3[4], k4[4], y[4];
  FILE              *csv = nullptr;

  for (int i = 0; i < 4; ++i) x[i] = Real(o.x0[i]);
  if (!o.csv.empty()) {
    csv = std::fopen(o.csv.c_str(), "w");
    if (!csv) usage(("cannot write " + o.csv).c_str());
    std::fprintf(csv, "t,I1,I2\n");
  }
  auto report = [&](long long n) {
    const double t  = (double)n * o.dt;
    const double I1 = (double)(x[0] * x[0] + x[2] * x[2]), I2 = (double)(x[1] * x[1] + x[3] * x[3]);
    if (n % nprint == 0 || n == nsteps) std::printf("t %.4f I1 %.12e I2 %.12e\n", t, I1, I2);
    if (csv && (n % ncsv == 0 || n == nsteps)) std::fprintf(csv, "%.10g,%.16e,%.16e\n", t, I1, I2);
  };

  const auto start = std::chrono::steady_clock::now();
  report(0);
  for (long long n = 1; n <= nsteps; ++n) {
    sys.f(x, k1);
    for (int i = 0; i < 4; ++i) y[i] = x[i] + h / 2 * k1[i];
    sys.f(y, k2);
    for (int i = 0; i < 4; ++i) y[i] = x[i] + h / 2 * k2[i];
    sys.f(y, k3);
    for (int i = 0; i < 4; ++i) y[i] = x[i] + h * k3[i];
    sys.f(y, k4);
    for (int i = 0; i < 4; ++i) { // x += h/6 (k1 + 2 k2 + 2 k3 + k4), Kahan-compensated
      const Real inc = h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]) - c[i];
      const Real s   = x[i] + inc;
      c[i]           = (s - x[i]) - inc;
      x[i]           = s;
    }
    if (n % nprint == 0 || n == nsteps || (ncsv && n % ncsv == 0)) report(n);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (csv) std::fclose(csv);
  std::printf("final t %.4f I1 %.12e I2 %.12e\n", (double)nsteps * o.dt, (double)(x[0] * x[0] + x[2] * x[2]), (double)(x[1] * x[1] + x[3] * x[3]));
  std::printf("steps %lld\nrhs_evaluations %lld\nwall_time %.6e\n", nsteps, 4 * nsteps, wall);
  return 0;
}

} // namespace

int main(int argc, char **argv)
{
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a     = argv[i];
    auto              value = [&]() -> const char              *{
      if (i + 1 >= argc) usage(("missing value after " + a).c_str());
      return argv[++i];
    };
    if (a == "--dt") o.dt = number(value());
    else if (a == "--tmax") o.tmax = number(value());
    else if (a == "--print") o.print = number(value());
    else if (a == "--eps") o.eps = number(value());
    else if (a == "--csv") o.csv = value();
    else if (a == "--csv-every") o.csvEvery = number(value());
    else if (a == "--long-double") o.longDouble = true;
    else if (a == "--x0") {
      std::string s = value() + std::string(",");
      int         n = 0;
      for (size_t p = 0, q; (q = s.find(',', p)) != std::string::npos; p = q + 1) {
        if (n == 4) usage("--x0 needs 4 values x1,x2,y1,y2");
        o.x0[n++] = number(s.substr(p, q - p).c_str());
      }
      if (n != 4) usage("--x0 needs 4 values x1,x2,y1,y2");
    } else usage(("unknown argument " + a).c_str());
  }
  if (!(o.dt > 0) || !(o.tmax > 0) || !(o.print > 0) || !(o.eps > 0) || !(o.csvEvery > 0)) usage("--dt, --tmax, --print, --eps, --csv-every must be positive");
  return o.longDouble ? run<long double>(o) : run<double>(o);
}
