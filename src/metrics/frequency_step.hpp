// frequency_step.hpp: the Gauss-Newton step of the record's frequency refinement (record.cpp,
// refine_frequency), internal; exposed for its finite-difference tests.
#pragma once

#include <limits>
#include <span>

namespace oscidrum::detail {

/// The residual of the least-squares harmonic fit (n = 0 ... n_max) of x_M'' and z_M'' at f,
/// each relative to the signal's variance about its mean, F(f) = |x - B c_x|^2 / var x +
/// |z - B c_z|^2 / var z (the quantity refine_frequency minimises), with its derivatives in f
/// with the coefficients eliminated (variable projection): with r the residual after the fit,
/// D = d(B c)/df at the fitted c and P the projection onto the basis, dF/df = -2 sum w <r, D>
/// exactly (r is orthogonal to the basis, so the coefficients' own change drops out), and the
/// Gauss-Newton curvature (Kaufman's approximation, which leaves out the term in r) 2 sum w
/// |(I - P) D|^2 = 2 sum w (|D|^2 - u^T (B^T B)^-1 u), u = B^T D; w = 1 / var.
struct FrequencyStep {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double residual = kNaN;   ///< F(f) [-]
  double slope = kNaN;      ///< dF/df [1/Hz]
  double curvature = kNaN;  ///< Gauss-Newton d^2F/df^2 [1/Hz^2]
  double step = kNaN;       ///< -slope / curvature [Hz]; NaN unless curvature > 0
};

/// F and its derivatives at f (the phase origin at t[0]); NaN members for fewer than
/// 2 n_max + 1 samples.
FrequencyStep frequency_step(std::span<const double> t, std::span<const double> x,
                             std::span<const double> z, double f, int n_max);

}  // namespace oscidrum::detail
