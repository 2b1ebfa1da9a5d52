// identify/solver.hpp: bounded nonlinear least squares by Levenberg-Marquardt, with a mask of
// fixed parameters (the profile intervals hold one parameter fixed and refit the others). The
// problem is anything that gives weighted residuals r(p) on a box of p, or says that it fails
// there (the model has no steady state at p): the solver steps back from such points.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace oscidrum::detail {

/// The box of one parameter (internal coordinates).
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
};

/// Weighted residuals r(p): the objective is S(p) = |r(p)|^2.
class LeastSquares {
 public:
  virtual ~LeastSquares() = default;
  virtual int rows() const = 0;
  virtual const std::vector<Bounds>& bounds() const = 0;
  /// r at p; false when there is none (the model fails at p).
  virtual bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) = 0;
  /// Why residual(p) failed, in words ("" if it did not or the problem cannot say).
  virtual std::string failure(const Eigen::VectorXd& /*p*/) { return {}; }
};

/// The result of a fit.
struct Fit {
  Eigen::VectorXd p, r;
  Eigen::MatrixXd J;       ///< the last Jacobian, at a point at most last_step from p
  double last_step = 1.0;  ///< size of the last accepted step (internal coordinates)
  double S = std::numeric_limits<double>::infinity();  ///< |r|^2 (infinite: no fit)
  int iterations = 0;
  bool converged = false;
  std::string message;  ///< why it stopped
};

/// Forward-difference step of the internal coordinates.
inline constexpr double kJacobianStep = 1e-3;
/// A step of the internal coordinates below this ends a fit as converged: 1e-4 in ln G is
/// 0.01 % of G, far below any uncertainty the data allow.
inline constexpr double kStepConverged = 1e-4;

/// The Jacobian dr/dp at p (r = r(p)) by forward differences of kJacobianStep (inwards at an
/// upper bound, the other side where the problem fails); columns of fixed parameters are 0.
/// False when the problem fails on both sides of some parameter.
bool jacobian(LeastSquares& problem, const Eigen::VectorXd& p, const Eigen::VectorXd& r,
              const std::vector<bool>& free, Eigen::MatrixXd& J);

/// Levenberg-Marquardt from p over the free parameters, steps clamped to the bounds and limited
/// to 0.7 in any internal coordinate (a factor 2 in a parameter on a log scale). Converged when
/// no step lowers S, a step is below kStepConverged or the decrease below 1e-8 S (also the
/// decrease the linearised problem predicts: such a step is not tried); after a rejected step
/// below kStepConverged no shorter one is tried. S is infinite (and
/// `message` says why) when the problem fails at the start or next to it. `first_jacobian`
/// (optional; its fixed parameters' columns are ignored) stands in for the finite differences of
/// the first iteration: a Jacobian known near p (a fit's, for the fits of its profile) saves one
/// model run per free parameter.
Fit levenberg_marquardt(LeastSquares& problem, const Eigen::VectorXd& p,
                        const std::vector<bool>& free, int max_iterations,
                        const Eigen::MatrixXd* first_jacobian = nullptr);

/// The same data fitted another way (`other`, a problem of the same rows and unknowns: identify's
/// and calibrate's model sampled at an in-step record's times) from `fit`'s estimate: where that
/// fits better (a lower S), it replaces `fit` and `other` is kept; else `other` is dropped and
/// its model runs are returned (to be counted with the rest), else 0.
template <class Problem>
int keep_the_better(std::optional<Problem>& other, Fit& fit, const std::vector<bool>& free,
                    int max_iterations) {
  Fit alternative = levenberg_marquardt(*other, fit.p, free, max_iterations);
  if (std::isfinite(alternative.S) && alternative.S < fit.S) {
    fit = std::move(alternative);
    return 0;
  }
  const int runs = other->simulations();
  other.reset();
  return runs;
}

/// The local minimum of S over the grid points 0 ... n-1 found walking downhill from the two
/// middle ones (n/2 - 1 and n/2; one point: that one): towards the lower of the two, one point at a
/// time, until S rises or is not finite (a point where the model fails: S = +inf). When both middle
/// points fail, every point is tried. The grid's minimum wherever S has one minimum on it,
/// without evaluating the points beyond it. Returns the index of the lowest S evaluated (ties:
/// the first evaluated) and its S, or {n, +inf} when S is nowhere finite; `S(k)` is called once
/// per point at most.
struct GridMinimum {
  std::size_t k;
  double S;
};
GridMinimum downhill_on_grid(std::size_t n, const std::function<double(std::size_t)>& S);

}  // namespace oscidrum::detail
