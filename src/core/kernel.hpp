// Kernels K(s) on [0,1] that shape the variable mesoscopic steps of VSHMM, with their
// antiderivative Theta(s) = int_0^s K and its inverse. No PETSc here.
#pragma once

#include <memory>
#include <string>

namespace vshmm {

enum class KernelType {
  Cosine,
  Constant,
  Polynomial,
  Exponential
};

// A kernel on [0,1]: integral 1, symmetric (K(s) = K(1-s)), positive inside (0,1).
// Derivatives of order 0..order() vanish at s = 0 and s = 1 (order() = -1: none vanish,
// kInfiniteOrder: all of them).
class Kernel {
public:
  static constexpr int kInfiniteOrder      = 1 << 30;
  static constexpr int kMaxPolynomialOrder = 16;

  // The polynomial kernel takes 0 <= order <= kMaxPolynomialOrder; the others have a fixed
  // order and ignore the argument. Throws std::invalid_argument on a bad order.
  static std::unique_ptr<Kernel> create(KernelType type, int polynomialOrder = 1);

  virtual ~Kernel()                 = default;
  virtual std::string name() const  = 0; // "cosine", "constant", "polynomial", "exponential"
  virtual int         order() const = 0; // q as above

  // K(s) for s in [0,1] (0 outside).
  virtual double value(double s) const = 0;
  // Theta(s) = int_0^s K(r) dr for s in [0,1], accurate to a few ulps relative to
  // min(Theta(s), 1 - Theta(s)) (computed as 1 - Theta(1-s) for s > 1/2).
  double theta(double s) const;
  // Theta^{-1}(u): the s in [0,1] with Theta(s) = u. The caller passes both u and its
  // complement uc = 1 - u, computed accurately (the schedule knows both from times), so
  // that s is accurate to near machine precision on both halves.
  double thetaInverse(double u, double uc) const;
  // K(Theta^{-1}(u)), using the symmetry of K: only min(u, uc) is inverted.
  double valueAtThetaInverse(double u, double uc) const;

protected:
  // Theta(s) for s in [0, 1/2], accurate relative to its own value.
  virtual double lowerTheta(double s) const = 0;
  // Theta^{-1}(v) for v in [0, 1/2], accurate relative to its own value.
  virtual double lowerThetaInverse(double v) const = 0;
};

} // namespace vshmm
