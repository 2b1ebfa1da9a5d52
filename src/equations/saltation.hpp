// Internal: the saltation matrix of a switch of a hybrid flow, for a state of any size N (the
// drum's 8 components, the unilateral drum's 10, a test's oscillator). The drum's switches
// (src/equations/jacobian.cpp) and every roller's Dynamics<R>::saltation use it.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace oscidrum::detail {

/// The saltation matrix of a switch, S = G + (f+ - G f-) dh^T / (dh . f- + dh/dt), which maps a
/// perturbation just before a switch to one just after it (f- at y-, f+ at g(y-), G the Jacobian
/// of the jump map g, dh the gradient of the event function). `grazing` is set when the
/// denominator is below grazing_tol |dh| |f-|: the flow meets the switching surface tangentially
/// and the linearisation does not exist.
template <int N>
struct SaltationMatrix {
  Eigen::Matrix<double, N, N> S = Eigen::Matrix<double, N, N>::Identity();
  bool grazing = false;
};

template <int N>
SaltationMatrix<N> saltation_matrix(const Eigen::Matrix<double, N, N>& G,
                                    const Eigen::Matrix<double, N, 1>& f_minus,
                                    const Eigen::Matrix<double, N, 1>& f_plus,
                                    const Eigen::Matrix<double, N, 1>& dh, double dh_dt = 0.0,
                                    double grazing_tol = 1e-9) {
  SaltationMatrix<N> out;
  const double denominator = dh.dot(f_minus) + dh_dt;
  const double scale = dh.norm() * f_minus.norm() + std::abs(dh_dt);
  if (!(std::abs(denominator) > grazing_tol * scale)) {
    out.grazing = true;
    out.S = G;
    return out;
  }
  out.S = G + (f_plus - G * f_minus) * dh.transpose() / denominator;
  return out;
}

}  // namespace oscidrum::detail
