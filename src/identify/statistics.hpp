// identify/statistics.hpp: what a least-squares fit (solver.hpp) says about its parameters: the
// linearised covariance s^2 (J^T J)^-1 with the condition number and correlations of the
// column-scaled Jacobian, and the 95 % intervals from the profile of the objective.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "identify/solver.hpp"

namespace oscidrum::detail {

/// The two-sided 95 % quantile of Student's t with `dof` degrees of freedom (at least 1).
double t_quantile(double dof);

/// Linearised uncertainties of a fit.
struct LinearisedUncertainty {
  Eigen::VectorXd se;           ///< standard uncertainties (internal coordinates; NaN: no effect)
  double condition = 0.0;       ///< of the column-scaled Jacobian [-]
  Eigen::MatrixXd correlation;  ///< of the estimates [-]
  std::vector<std::string> warnings;  ///< no effect, near-singular, cannot be told apart
};

/// se_j = sqrt(s2 [(J^T J)^-1]_jj), with the Jacobian's columns scaled to unit norm for the
/// condition number and the (pseudo-)inverse. `names` name the columns in the warnings: a
/// column of zeros ("has no effect on the fit"), a condition number above max_condition, a
/// |correlation| above max_correlation ("cannot be told apart").
LinearisedUncertainty linearised_uncertainty(const Eigen::MatrixXd& J, double s2,
                                             const std::vector<std::string>& names,
                                             double max_condition, double max_correlation);

/// One side of a profile interval.
struct ProfileLimit {
  double at;  ///< the limit (internal coordinate; NaN: none found)
  /// The profile stayed below the level up to the parameter's bound, or never rose within the
  /// steps taken: no limit within the range (a flat profile).
  bool open = false;
  /// The model failed before the profile reached the level: no limit; `last_good` is the last
  /// value that fitted and `failure` the model's reason.
  bool model_fails = false;
  double last_good = 0.0;
  std::string failure;
};

/// The limit on side `side` (-1 lower, +1 upper) of parameter j where the profile
/// S_profile(p_j) = min over the other free parameters of S reaches fit.S + s2 c^2 (c from
/// t_quantile), by secant (regula falsi) steps on sqrt((S_profile - S) / s2), starting at
/// c se_j (or 0.05 without se_j), at most 7 evaluations, each an inner fit of at most 5
/// iterations from the previous one.
ProfileLimit profile_limit(LeastSquares& problem, const Fit& fit, std::size_t j, int side,
                           double se_j, double c, double s2);

}  // namespace oscidrum::detail
