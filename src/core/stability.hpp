// Linear stability of explicit Runge-Kutta steps: the stability function R(z) of a tableau, its
// stability limits along rays of the complex plane, and the amplification of a level's
// variable steps over one macro step. No PETSc here.
#pragma once

#include <complex>
#include <functional>
#include <vector>

#include "rk.hpp"
#include "schedule.hpp"

namespace vshmm {

// R(z) = 1 + z b^T (I - z A)^{-1} 1: one step of the method applied to y' = lambda y, z = h lambda.
class StabilityFunction {
public:
  explicit StabilityFunction(const Tableau &tableau);

  std::complex<double> operator()(std::complex<double> z) const;

  // 1 - R(z) exp(-z): what one step takes from the exact flow, relative. Near z = 0 from the
  // Taylor coefficients where R and exp differ (the terms above the method's order), without the
  // cancellation of R(z) - exp(z) in floating point (about 1e-16 per step, which a sum over many
  // steps of a fine micro step would take for an error of the method).
  std::complex<double> relativeDefect(std::complex<double> z) const;

  // The largest r with |R(x d)| <= max(1, |exp(x d)|) for every x in [0, r], d = direction / |direction|
  // (a step may grow a growing mode by as much as the exact flow, no more):
  // along the negative real axis (d = -1) it is 2 for forward Euler and 2.785 for RK4, along the
  // imaginary axis 0 and 2.828. Bounded by kMaxRadius.
  double rayLimit(std::complex<double> direction) const;
  double realLimit() const { return rayLimit(-1.0); }
  double imaginaryLimit() const { return rayLimit(std::complex<double>(0.0, 1.0)); }

  // The largest step h with |R(x h lambda)| <= 1 for every x in [0, 1] (infinity for lambda = 0).
  double largestStableStep(std::complex<double> lambda) const;

  static constexpr double kMaxRadius = 1e3;

private:
  std::vector<double> a_, b_;
  int                 s_;
  std::vector<double> gamma_; // R(z) = sum_k gamma_k z^k
};

// What the steps of one level do to a linear mode y' = lambda y over one macro step of
// length macroStep, with the schedule's own step sequence (the shortened last step included):
// the product of |R(h lambda)| over the level's steps, as its logarithm, beyond the mode's own
// growth over those steps (sum of h max(Re lambda, 0)), and the step count.
struct LevelAmplification {
  double logAmplification = 0.0; // log prod |R(h lambda)| - sum h max(Re lambda, 0)
  double largestGrowth    = 0.0; // the largest running value of that logarithm within the macro step (>= 0)
  long   steps            = 0;
  double largestStep      = 0.0;
};
LevelAmplification levelAmplification(const StabilityFunction &R, const MesoscopicSchedule &schedule, double macroStep, int level, std::complex<double> lambda);

// Whether the mode y' = lambda y oscillates (|Im lambda| > |Re lambda|) rather than only decays or grows.
inline bool oscillates(std::complex<double> lambda)
{
  return std::abs(lambda.imag()) > std::abs(lambda.real());
}

// The slowest rate of a level's modes: |lambda| for each mode, except that an oscillation whose
// amplitude changes (|Im| > |Re| > noise |lambda|) changes on the time scale of its amplitude,
// |Re lambda|. Modes below 1e-8 of the largest |lambda| (zero modes) are not counted; 0 where none
// is left. `noise`: the fraction of |lambda| below which a real part is the estimate's noise.
double           slowestRate(const std::vector<std::complex<double>> &modes, double noise = 1e-6);
constexpr double kAmplitudeRateNoise        = 1e-6; // Ritz values from forward differences: below this fraction of |lambda| a real part is noise
constexpr double kAmplitudeRateCentralNoise = 1e-8; // from central differences (no first-order truncation error)
// The slowest amplitude rate |Re lambda| among the oscillations (|Im| > |Re| > noise |lambda|,
// |lambda| above 1e-8 of the largest); 0 where there is none. For additive splits only these count
// as a slow process of a level (its own terms' block has many zero and interior Ritz values).
double slowestAmplitudeRate(const std::vector<std::complex<double>> &modes, double noise = 1e-6);
// The fastest growth rate Re lambda among the modes that grow (Re lambda > noise |lambda|, |lambda|
// above 1e-8 of the largest); 0 where none grows.
double fastestGrowthRate(const std::vector<std::complex<double>> &modes, double noise = 1e-6);
// The noise levels of Ritz values from forward and central differences (fractions of |lambda|
// below which a real part is noise; differences at sqrt(eps) (1 + ||X||) and cbrt(eps) (1 + ||X||)).
// The rounding of X + delta V makes an error of about eps ||X|| ||J|| / delta in J V: relative to
// the eigenvalues, the fixed levels above where the block's entries are of their size (a rotation),
// but a block whose entries are far larger than its eigenvalues has more (a position-velocity
// block [[0, 1], [-w^2, 0]] has entries w^2, w times its eigenvalues +-iw: a stiff bond at w = 1195
// read amplitude rates of 1.6e-6 of w by forward differences, above kAmplitudeRateNoise, where its
// block is exactly conservative). blockNorm: the largest entry of the Hessenberg matrix; largest:
// the largest |lambda|; stateNorm: ||X||.
struct AmplitudeRateNoise {
  double forward = kAmplitudeRateNoise, central = kAmplitudeRateCentralNoise;
};
AmplitudeRateNoise amplitudeRateNoise(double blockNorm, double largest, double stateNorm);
// Whether an oscillation's amplitude rate lies between the two noise levels (|Re| / |lambda| in
// (central, forward]): forward differences cannot tell a slow damping from their truncation error
// and rounding there, and central differences can.
bool ambiguousAmplitudeRate(const std::vector<std::complex<double>> &modes, const AmplitudeRateNoise &noise = AmplitudeRateNoise());

// The amplitude error of one step of size h on the mode y' = lambda y: |log |R(h lambda)| - h Re lambda|
// (what the step takes from, or adds to, the mode's amplitude beyond the exact flow, relative).
double amplitudeError(const StabilityFunction &R, std::complex<double> lambda, double h);

// The phase error of one step of size h on the mode y' = lambda y: |arg R(h lambda) - h Im lambda|,
// the difference taken in (-pi, pi] (what the step advances the mode's phase by beyond the exact
// flow, in radians; RK4 on a rotation lags by y^5 / 120 + O(y^7), y = h |lambda|).
double phaseError(const StabilityFunction &R, std::complex<double> lambda, double h);

// The largest step h <= hMax for which the error of every mode in `modes`, summed over the
// stepsPerUnitStep / h steps of a span (a span of length T stepped with steps h c takes T / (h c)
// of them: stepsPerUnitStep = T / c), is at most `allowed`: the amplitude error, plus phaseWeight
// times the phase error (0: the amplitude alone). Where the amplitude of an oscillating mode is
// lost (or gained) by the steps, no comparison of two such runs sees it, the energy is gone from
// both; where the sampled values hold the mode itself, its phase error adds up step by step as
// well (a rotation keeps it: the errors add coherently). hMax where it already passes; bisection
// to 1e-3 relative otherwise. amplitudeStepsPerUnitStep (where positive and smaller) sums the
// amplitude error over fewer steps than the phase error: an oscillation that restores its own
// amplitude (a limit cycle) keeps an amplitude error only over the time it takes to restore it.
double largestAccurateStep(const StabilityFunction &R, const std::vector<std::complex<double>> &modes, double hMax, double stepsPerUnitStep, double allowed, double phaseWeight = 0.0, double amplitudeStepsPerUnitStep = -1.0);

// The largest savings factor alpha_j, 0 <= alpha_j <= savings[j-1] (j = 1..K), with which the
// steps of level j - 1 damp the mode lambda by at least dampingTarget over a macro step
// (logAmplification <= log dampingTarget) and grow it by at most maxGrowth on the way
// (largestGrowth <= log maxGrowth), the other parameters as given: the schedule of every trial
// value is made from kernel, microStep, savings and subintervals. Bisection to 2^-40 of
// savings[j-1]; 0 if no positive value passes. Throws std::invalid_argument where the schedule does.
double largestStableSavingsFactor(const StabilityFunction &R, const Kernel &kernel, double microStep, std::vector<double> savings, const std::vector<int> &subintervals, double macroStep, int j, std::complex<double> lambda, double dampingTarget, double maxGrowth);

// || tau phi1(tau H) e1 ||_2 = || integral_0^tau exp(s H) e1 ds ||_2 for the n x n matrix H
// (column-major, leading dimension ld): how far a constant unit forcing along e1 moves the linear
// system y' = H y + e1 from y(0) = 0 in the time tau. tau for H = 0, (1 - exp(-r tau)) / r for H =
// -r, at most 2 / omega for a rotation at rate omega. The exponential of the augmented matrix
// tau [[H, e1], [0, 0]], by scaling and squaring of its Taylor series. Infinity where it overflows.
double forcedResponse(const std::vector<double> &H, int n, int ld, double tau);

// Two oscillations whose frequencies differ by g make, in any product of them, a beat at
// frequency g: slower than either, a process on a slower scale where g is small. The beats among
// the oscillating modes (|Im| > |Re|, Im > 0) above fastAbove in |lambda|: every difference g of
// two distinct frequencies (g above kDistinctFrequencies of the larger; equal frequencies make no
// beat) that is at least `separation` times slower than the slower of the two (lower, upper);
// ascending in g, beats within kDistinctBeats of a slower one left out.
constexpr double kDistinctFrequencies = 1e-6;
constexpr double kDistinctBeats       = 0.01;
struct Beat {
  double frequency, lower, upper;
};
std::vector<Beat> beatFrequencies(const std::vector<std::complex<double>> &modes, double fastAbove, double separation);

// Oscillations of frequencies w_i combined with integer coefficients c_i, sum c_i w_i = +-g, make
// in a product of them (w_i taken |c_i| times) a slow combination at g that no pair of them need
// show as a beat: three modes (a triad: wa + wb - wc, or 2 wa - wc for a rotation and one at about
// twice its frequency) or four (a quartet: wa + wb - wc - wd, wa + wb + wc - wd, 2 wa - wb - wc,
// 2 wa + wb - wc, 3 wa - wb). The slow combinations of `order` (3 or 4: the sum of the |c_i|) among
// the oscillating modes (|Im| > |Re|, Im > 0) above fastAbove in |lambda|: the distinct frequencies
// w ascending, their coefficients c (the first positive, at least one +-1: no multiple of a beat), g
// above kDistinctFrequencies of the largest w and at least `separation` times slower than the
// slowest; ascending in g (combinations at one frequency all kept: they are different products).
struct Combination {
  double              frequency;
  std::vector<double> w;
  std::vector<int>    c;
};
std::vector<Combination> slowCombinations(const std::vector<std::complex<double>> &modes, double fastAbove, double separation, int order);

// e1 with every mode of an n x n real matrix turned in its own plane: with the eigenvalues lambda
// and right eigenvectors vr of the matrix (column-major, as LAPACK's geev gives them: a complex
// pair's real and imaginary parts in two columns, the one with Im > 0 first), e1 = sum_j c_j y_j,
// and each term of a mode with Im lambda_j != 0 is multiplied by exp(i s_j phi(|Im lambda_j|)), s_j
// the sign of Im lambda_j: phi(w) = theta for every w advances every oscillation by the same angle
// whatever its frequency (an average over theta is an average over each one's own phase), theta +
// (w > split ? delta : 0) those above `split` by delta more (a relative phase: a beat's probe).
// Real modes are left as they are. On a Krylov space of a Jacobian started at v, V times this is
// v / ||v|| so turned. Empty where the eigenvectors are singular or the result is not finite.
std::vector<double> modesTurned(const std::vector<double> &vr, const std::vector<std::complex<double>> &lambda, int n, const std::function<double(double)> &phi);

} // namespace vshmm
