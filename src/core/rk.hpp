// One step of an explicit Runge-Kutta method given by its Butcher tableau, written against
// an abstract vector space so that it runs on PETSc Vecs (the TS glue) and on plain arrays
// (the unit tests). No PETSc here.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace vshmm {

// Butcher tableau of an explicit method: a is stages x stages, row-major, strictly lower.
struct Tableau {
  static constexpr int kMaxStages = 32;

  std::string         name;
  int                 order  = 0;
  int                 stages = 0;
  std::vector<double> a, b, c;

  // Throws std::invalid_argument unless the sizes agree, 1 <= stages <= kMaxStages and a is
  // strictly lower triangular (an explicit method).
  Tableau(std::string name, int order, int stages, std::vector<double> a, std::vector<double> b, std::vector<double> c) : name(std::move(name)), order(order), stages(stages), a(std::move(a)), b(std::move(b)), c(std::move(c))
  {
    if (stages < 1 || stages > kMaxStages) throw std::invalid_argument("Runge-Kutta tableau " + this->name + ": stage count out of range");
    if ((int)this->a.size() != stages * stages || (int)this->b.size() != stages || (int)this->c.size() != stages) throw std::invalid_argument("Runge-Kutta tableau " + this->name + ": sizes do not match the stage count");
    for (int i = 0; i < stages; ++i)
      for (int j = i; j < stages; ++j)
        if (this->a[i * stages + j] != 0.0) throw std::invalid_argument("Runge-Kutta tableau " + this->name + " is not explicit");
  }
};

// Advances x by one step of length h from time t:
//   Y_i = x + sum_{j<i} h a_ij k_j,  k_i = f(t + c_i h, Y_i),  x <- x + sum_i h b_i k_i.
// Ops supplies the vector work and returns 0 or an error code, which stops the step:
//   int stage(int i, double ti, const double *w)   Y_i = x + sum_{j<i} w[j] k_j; k_i = f(ti, Y_i)
//   int update(int s, const double *w)             x += sum_{j<s} w[j] k_j
template <class Ops>
int explicitRungeKuttaStep(const Tableau &tab, Ops &ops, double t, double h)
{
  double    w[Tableau::kMaxStages];
  const int s = tab.stages;
  for (int i = 0; i < s; ++i) {
    for (int j = 0; j < i; ++j) w[j] = h * tab.a[i * s + j];
    if (int err = ops.stage(i, t + tab.c[i] * h, w)) return err;
  }
  for (int j = 0; j < s; ++j) w[j] = h * tab.b[j];
  return ops.update(s, w);
}

} // namespace vshmm
