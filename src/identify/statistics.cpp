// Uncertainties of a least-squares fit: linearised covariance and profile intervals
// (statistics.hpp).
#include "identify/statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>

#include "util/format.hpp"

namespace oscidrum::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
std::string num(double v) { return shortest(v); }

}  // namespace

double t_quantile(double dof) {
  const boost::math::students_t t(std::max(1.0, dof));
  return boost::math::quantile(t, 0.975);
}

LinearisedUncertainty linearised_uncertainty(const Eigen::MatrixXd& J, double s2,
                                             const std::vector<std::string>& names,
                                             double max_condition, double max_correlation) {
  LinearisedUncertainty u;
  const Eigen::Index q = J.cols();
  u.se = Eigen::VectorXd::Constant(q, kNaN);
  u.correlation = Eigen::MatrixXd::Constant(q, q, kNaN);
  const Eigen::VectorXd norms = J.colwise().norm();
  Eigen::MatrixXd Js = J;
  for (Eigen::Index j = 0; j < q; ++j)
    if (norms[j] > 0) Js.col(j) /= norms[j];
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js);
  const auto sv = svd.singularValues();
  u.condition =
      sv[sv.size() - 1] > 0 ? sv[0] / sv[sv.size() - 1] : std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j < q; ++j)
    if (!(norms[j] > 0))
      u.warnings.push_back(names[static_cast<std::size_t>(j)] +
                           " has no effect on the fit: it cannot be identified from these data");
  if (u.condition > max_condition)
    u.warnings.push_back("near-singular Jacobian (condition number " +
                         num(std::round(u.condition)) + "): the parameters cannot be told apart");
  const Eigen::MatrixXd Ai =
      (Js.transpose() * Js).completeOrthogonalDecomposition().pseudoInverse();
  for (Eigen::Index j = 0; j < q; ++j) {
    u.se[j] = norms[j] > 0 ? std::sqrt(s2 * Ai(j, j)) / norms[j] : kNaN;
    for (Eigen::Index k = 0; k < q; ++k)
      u.correlation(j, k) = Ai(j, k) / std::sqrt(Ai(j, j) * Ai(k, k));
    for (Eigen::Index k = j + 1; k < q; ++k) {
      const double c = u.correlation(j, k);
      if (std::abs(c) > max_correlation)
        u.warnings.push_back(
            names[static_cast<std::size_t>(j)] + " and " + names[static_cast<std::size_t>(k)] +
            " cannot be told apart (correlation " + num(std::round(c * 1000) / 1000) + ")");
    }
  }
  return u;
}

ProfileLimit profile_limit(LeastSquares& problem, const Fit& fit, std::size_t j, int side,
                           double se_j, double c, double s2) {
  const std::size_t q = static_cast<std::size_t>(fit.p.size());
  const Eigen::Index J_ = static_cast<Eigen::Index>(j);
  const Bounds& bounds = problem.bounds()[j];
  const double pj = fit.p[J_];
  const double bound = side < 0 ? bounds.lo : bounds.hi;
  std::vector<bool> others(q, true);
  others[j] = false;
  double step = std::isfinite(se_j) && se_j > 0 ? c * se_j : 0.05;
  step = std::min(step, std::abs(bound - pj));
  double lo_step = 0, lo_delta = 0, hi_step = kNaN, hi_delta = kNaN;
  // Where the others go as p_j moves by d, in the problem linearised at the fit: by d times the
  // least-squares solution of J_others slope = -J_j (the conditional minimiser). Each inner fit
  // starts there from the last one, with the fit's Jacobian for its first step, so that it
  // usually needs no finite differences of its own.
  const bool have_J = fit.J.rows() > 0 && fit.J.cols() == fit.p.size();
  Eigen::VectorXd slope = Eigen::VectorXd::Zero(fit.p.size());
  if (q > 1 && have_J) {
    Eigen::MatrixXd Jo(fit.J.rows(), static_cast<Eigen::Index>(q) - 1);
    for (Eigen::Index k = 0, col = 0; k < fit.p.size(); ++k)
      if (k != J_) Jo.col(col++) = fit.J.col(k);
    const Eigen::VectorXd so = Jo.colPivHouseholderQr().solve(-fit.J.col(J_));
    if (so.allFinite())
      for (Eigen::Index k = 0, col = 0; k < fit.p.size(); ++k)
        if (k != J_) slope[k] = so[col++];
  }
  Eigen::VectorXd warm = fit.p;
  bool found = false, open = false;
  std::string failure;  // why the model failed at hi_step (when hi_delta is infinite)
  for (int k = 0; k < 7 && step > 0; ++k) {
    Eigen::VectorXd p = warm + (pj + side * step - warm[J_]) * slope;
    p[J_] = pj + side * step;
    for (std::size_t i = 0; i < q; ++i) {
      const Bounds& b = problem.bounds()[i];
      const auto I = static_cast<Eigen::Index>(i);
      p[I] = std::clamp(p[I], b.lo, b.hi);
    }
    double S = kNaN;
    if (q > 1) {
      const Fit inner = levenberg_marquardt(problem, p, others, 5, have_J ? &fit.J : nullptr);
      if (std::isfinite(inner.S)) {
        S = inner.S;
        warm = inner.p;
      }
    } else {
      Eigen::VectorXd rr;
      if (problem.residual(p, rr)) S = rr.squaredNorm();
    }
    if (!std::isfinite(S)) {  // the model fails out there: stop at the last good point
      failure = problem.failure(p);
      hi_step = step;
      hi_delta = std::numeric_limits<double>::infinity();
      step = 0.5 * (lo_step + step);
      continue;
    }
    const double delta = std::sqrt(std::max(0.0, S - fit.S) / s2);
    if (std::abs(delta - c) < 0.03 * c) {
      found = true;
      lo_step = step;
      break;
    }
    if (delta < c) {
      lo_step = step;
      lo_delta = delta;
      if (std::abs(pj + side * step - bound) < 1e-12) {
        open = true;
        break;
      }
    } else {
      hi_step = step;
      hi_delta = delta;
    }
    if (std::isfinite(hi_step)) {  // regula falsi on delta, linear in the step
      step = std::isfinite(hi_delta)
                 ? lo_step + (c - lo_delta) * (hi_step - lo_step) / (hi_delta - lo_delta)
                 : 0.5 * (lo_step + hi_step);
    } else {
      step = lo_delta > 0.05 * c ? step * std::min(4.0, 1.1 * c / lo_delta) : step * 4;
      step = std::min(step, std::abs(bound - pj));
    }
  }
  ProfileLimit out;
  out.at = kNaN;
  if (found || open) {
    out.at = pj + side * lo_step;
  } else if (std::isfinite(hi_step) && !std::isfinite(hi_delta)) {
    // Where the model fails, the data have not excluded anything: that is no limit.
    out.model_fails = true;
    out.last_good = pj + side * lo_step;
    out.failure = failure;
  } else if (std::isfinite(hi_step)) {
    out.at = pj + side * 0.5 * (lo_step + hi_step);
  }
  out.open = open || (!found && !std::isfinite(hi_step));
  return out;
}

}  // namespace oscidrum::detail
