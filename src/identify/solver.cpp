// Levenberg-Marquardt with a mask of fixed parameters (solver.hpp).
#include "identify/solver.hpp"

#include <algorithm>
#include <cmath>

namespace oscidrum::detail {

bool jacobian(LeastSquares& problem, const Eigen::VectorXd& p, const Eigen::VectorXd& r,
              const std::vector<bool>& free, Eigen::MatrixXd& J) {
  J.setZero(problem.rows(), p.size());
  for (Eigen::Index j = 0; j < p.size(); ++j) {
    if (!free[static_cast<std::size_t>(j)]) continue;
    const Bounds& b = problem.bounds()[static_cast<std::size_t>(j)];
    Eigen::VectorXd q = p;
    double h = kJacobianStep;
    if (q[j] + h > b.hi) h = -h;  // step inwards at the upper bound
    q[j] += h;
    Eigen::VectorXd rq;
    if (!problem.residual(q, rq)) {
      q[j] = p[j] - h;  // the other side
      if (!problem.residual(q, rq)) return false;
      h = -h;
    }
    J.col(j) = (rq - r) / h;
  }
  return true;
}

Fit levenberg_marquardt(LeastSquares& problem, const Eigen::VectorXd& p,
                        const std::vector<bool>& free, int max_iterations,
                        const Eigen::MatrixXd* first_jacobian) {
  Fit fit;
  fit.p = p;
  if (!problem.residual(p, fit.r)) {
    fit.message = "the model fails at the start";
    return fit;
  }
  fit.S = fit.r.squaredNorm();
  double lambda = 1e-3;
  Eigen::MatrixXd J;
  for (int it = 0; it < max_iterations; ++it) {
    fit.iterations = it + 1;
    const bool given = it == 0 && first_jacobian != nullptr &&
                       first_jacobian->rows() == fit.r.size() && first_jacobian->cols() == p.size();
    if (given) {
      J = *first_jacobian;
      for (Eigen::Index j = 0; j < p.size(); ++j)
        if (!free[static_cast<std::size_t>(j)]) J.col(j).setZero();
    } else if (!jacobian(problem, fit.p, fit.r, free, J)) {
      fit.message = "the model fails next to the estimate";
      return fit;
    }
    fit.J = J;
    fit.last_step = 1.0;
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * fit.r;
    bool accepted = false, predicted_nothing = false, rejected_small = false;
    double step_norm = 0, gain = 0;
    while (lambda < 1e12) {
      Eigen::MatrixXd M = A;
      for (Eigen::Index j = 0; j < A.rows(); ++j)
        M(j, j) = free[static_cast<std::size_t>(j)] ? A(j, j) * (1 + lambda) + 1e-12 : 1.0;
      Eigen::VectorXd dp = -M.ldlt().solve(g);
      for (Eigen::Index j = 0; j < dp.size(); ++j)
        if (!free[static_cast<std::size_t>(j)]) dp[j] = 0;
      // Trust region: internal coordinates move at most 0.7 (a factor 2 in G) per step.
      const double big = dp.cwiseAbs().maxCoeff();
      if (big > 0.7) dp *= 0.7 / big;
      if (big < 1e-7) break;  // the steps have shrunk to nothing: at the minimum
      Eigen::VectorXd q = fit.p + dp;
      for (Eigen::Index j = 0; j < q.size(); ++j) {
        const Bounds& b = problem.bounds()[static_cast<std::size_t>(j)];
        q[j] = std::clamp(q[j], b.lo, b.hi);
      }
      // The decrease the linearised problem predicts for this step, |r|^2 - |r + J d|^2: below
      // the convergence test's 1e-8 S no step of this iteration can count (a fit started at its
      // minimum, as a profile's inner fits are, would otherwise try steps with ever larger lambda
      // until they shrink to nothing, a model run each).
      const Eigen::VectorXd d = q - fit.p;
      if (-(2.0 * g.dot(d) + d.dot(A * d)) < 1e-8 * fit.S) {
        predicted_nothing = true;
        break;
      }
      Eigen::VectorXd rq;
      const double size = d.cwiseAbs().maxCoeff();
      if (problem.residual(q, rq) && rq.squaredNorm() < fit.S) {
        gain = fit.S - rq.squaredNorm();
        step_norm = (q - fit.p).cwiseAbs().maxCoeff();
        fit.p = q;
        fit.r = rq;
        fit.S = rq.squaredNorm();
        fit.last_step = step_norm;
        lambda = std::max(lambda / 5, 1e-9);
        accepted = true;
        break;
      }
      lambda *= 8;
      // A rejected step already below the convergence test's size: the larger lambda's steps are
      // shorter still, and the first of them accepted would end the fit as converged, having moved
      // p by less than kStepConverged. Not tried (near a minimum of a model whose residual carries
      // its integration tolerance, each was a model run that the noise rejected, seen 4-5 times
      // in a row at the end of fits with mu and MMd).
      if (size < kStepConverged) {
        rejected_small = true;
        break;
      }
    }
    if (!accepted) {
      fit.converged = true;  // no step lowers the objective: a minimum (to the FD precision)
      fit.message = predicted_nothing ? "converged (no step predicts a decrease of 1e-8 S)"
                    : rejected_small
                        ? "converged (no step lowers the objective; the last tried was below 1e-4)"
                        : "no step lowers the objective";
      return fit;
    }
    if (step_norm < kStepConverged || gain < 1e-8 * fit.S) {
      fit.converged = true;
      fit.message = "converged";
      return fit;
    }
  }
  fit.message = "iteration limit reached";
  return fit;
}

GridMinimum downhill_on_grid(std::size_t n, const std::function<double(std::size_t)>& S) {
  std::vector<double> v(n, std::numeric_limits<double>::quiet_NaN());
  std::size_t best = n;
  const auto found = [&]() -> GridMinimum {
    return {best, best < n ? v[best] : std::numeric_limits<double>::infinity()};
  };
  const auto at = [&](std::size_t k) {
    v[k] = S(k);
    if (std::isfinite(v[k]) && (best == n || v[k] < v[best])) best = k;
    return v[k];
  };
  if (n < 2) {
    if (n == 1) at(0);
    return found();
  }
  const std::size_t lo = n / 2 - 1, hi = n / 2;
  const double s_lo = at(lo), s_hi = at(hi);
  if (std::isfinite(s_lo) || std::isfinite(s_hi)) {
    if (s_hi < s_lo) {
      for (std::size_t k = hi + 1; k < n && at(k) < v[k - 1];) ++k;
    } else {
      for (std::size_t k = lo; k-- > 0 && at(k) < v[k + 1];) {
      }
    }
  } else {
    for (std::size_t k = 0; k < n; ++k)
      if (k != lo && k != hi) at(k);
  }
  return found();
}

}  // namespace oscidrum::detail
