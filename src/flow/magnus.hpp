// Internal: the Magnus integrator of the variational equations (used by src/flow/monodromy.hpp):
// one step's exponent from three Jacobians, and its exponential on the balanced matrix. Pure
// linear algebra on fixed-size Eigen matrices; the passes over the entries are plain loops, so
// that the wide kernels (src/flow/wide_kernels.cpp) compile the same code for AVX2 or AVX-512 and
// round every entry as this header does (tests/flow/test_magnus.cpp compares them to the bit).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "flow/matrix_product.hpp"

namespace oscidrum::detail {

// The infinity norm of D^-1 |J| D with D = diag(d), an induced norm of a matrix similar to |J|
// (an upper bound of the spectral radius rho(|J|) >= rho(J) for any positive d). The state's
// components have different units, so J's plain norm is no bound worth having: `sweeps` sweeps of
// Osborne's balancing first bring D^-1 |J| D closer to rows and columns of equal sums off the
// diagonal, updating d (a d balanced on a nearby J needs one sweep where one from d = 1 needs
// three).
template <class Matrix>
double balanced_norm(const Matrix& J, Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1>& d,
                     int sweeps) {
  constexpr int n = static_cast<int>(Matrix::RowsAtCompileTime);
  const Eigen::Matrix<double, n, 1> inv = d.cwiseInverse();
  Matrix B;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) B(i, j) = std::abs(J(i, j)) * (d[j] * inv[i]);
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int i = 0; i < n; ++i) {
      const double c = B.col(i).sum() - B(i, i), r = B.row(i).sum() - B(i, i);
      if (!(c > 0.0) || !(r > 0.0)) continue;
      const double f = std::sqrt(r / c);
      B.row(i) *= 1.0 / f;
      B.col(i) *= f;
      d[i] *= f;
    }
  return B.rowwise().sum().maxCoeff();
}

// exp(Omega) by scaling and squaring (Moler & Van Loan, "Nineteen dubious ways to compute the
// exponential of a matrix, twenty-five years later", SIAM Review 45, 2003, method 3) of the
// balanced B = D^-1 Omega D, D = diag(d) (balanced_norm, `sweeps` sweeps from the given d, which
// it updates): B / 2^s with s the first that brings its infinity norm below 1/2, the Taylor
// polynomial of degree 10 of that (evaluated as Paterson and Stockmeyer's nested products in
// B^3: 5 matrix products; the series' remainder is below 1.3e-11), squared s times, and
// exp(Omega) = D exp(B) D^-1. Without the balancing, the mixed units of the state would make
// Omega's norm, and with it s, many orders too large. A non-finite Omega gives NaN.
// (Always inlined: the wide kernels compile it inside their own functions.)
template <class Matrix>
[[gnu::always_inline]] inline Matrix balanced_exponential(
    const Matrix& omega, Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1>& d, int sweeps) {
  constexpr int n = static_cast<int>(Matrix::RowsAtCompileTime), size = n * n;
  if (sweeps > 0) balanced_norm(omega, d, sweeps);
  const Eigen::Matrix<double, n, 1> inverse = d.cwiseInverse();
  const double *dd = d.data(), *inv = inverse.data();
  Matrix B;
  double* b = B.data();
  // B(i, j) = Omega(i, j) (d_j / d_i), column by column.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) b[j * n + i] = omega.data()[j * n + i] * (inv[i] * dd[j]);
  const double norm = B.cwiseAbs().rowwise().sum().maxCoeff();
  if (!std::isfinite(norm)) return Matrix::Constant(std::numeric_limits<double>::quiet_NaN());
  const int s = norm > 0.5 ? std::max(0, std::ilogb(norm / 0.5) + 1) : 0;
  if (s > 0) {
    const double scale = std::ldexp(1.0, -s);
    for (int k = 0; k < size; ++k) b[k] *= scale;
  }
  constexpr double c2 = 1.0 / 2.0, c3 = c2 / 3.0, c4 = c3 / 4.0, c5 = c4 / 5.0, c6 = c5 / 6.0,
                   c7 = c6 / 7.0, c8 = c7 / 8.0, c9 = c8 / 9.0, c10 = c9 / 10.0;
  const Matrix B2 = product(B, B), B3 = product(B2, B);
  const double* b2 = B2.data();
  // sum c_k B^k = ((c10 B + c9) B^3 + c8 B^2 + c7 B + c6) B^6 ... nested in B^3
  Matrix P;
  double* p = P.data();
  for (int k = 0; k < size; ++k) p[k] = c10 * b[k];
  for (int i = 0; i < n; ++i) p[i * n + i] += c9;
  // P = P B^3 + c_hi B^2 + c_lo B + c_0 I
  const auto nest = [&](double c_hi, double c_lo, double c_0) {
    const Matrix PB3 = product(P, B3);
    const double* q = PB3.data();
    for (int k = 0; k < size; ++k) p[k] = q[k] + c_hi * b2[k] + c_lo * b[k];
    for (int i = 0; i < n; ++i) p[i * n + i] += c_0;
  };
  nest(c8, c7, c6);
  nest(c5, c4, c3);
  nest(c2, 1.0, 1.0);
  for (int k = 0; k < s; ++k) P = product(P, P);
  // exp(Omega) = D exp(B) D^-1: entry (i, j) times d_i / d_j.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) p[j * n + i] *= dd[i] * inv[j];
  return P;
}

// The exponent of one step of Magnus's expansion of order 6 for Phi' = J(t) Phi over [t, t + h],
// from J at the three Gauss-Legendre nodes t + (1/2 - sqrt(15)/10, 1/2, 1/2 + sqrt(15)/10) h
// (Blanes, Casas, Oteo & Ros, "The Magnus expansion and some of its applications", Physics
// Reports 470, 2009, section 5: the sixth-order method with three commutators): Phi(t + h) =
// exp(Omega) Phi(t) up to O(h^7). Exact for a constant J, whatever h |lambda|: its error comes
// from J's change over the step, not from the stiffness of J, unlike an explicit Runge-Kutta
// method's.
inline constexpr double kMagnusNode = 0.3872983346207416885;  // sqrt(15) / 10
template <class Matrix>
[[gnu::always_inline]] inline Matrix magnus6_exponent(double h, const Matrix& J1, const Matrix& J2,
                                                      const Matrix& J3) {
  constexpr int size = static_cast<int>(Matrix::SizeAtCompileTime);
  const double *j1 = J1.data(), *j2 = J2.data(), *j3 = J3.data();
  const double h2 = h * 1.2909944487358056284;  // sqrt(15) / 3
  const double h3 = h * 10.0 / 3.0;
  Matrix a1, a2, a3;
  double *x1 = a1.data(), *x2 = a2.data(), *x3 = a3.data();
  for (int k = 0; k < size; ++k) {
    x1[k] = h * j2[k];
    x2[k] = h2 * (j3[k] - j1[k]);
    x3[k] = h3 * (j3[k] - 2.0 * j2[k] + j1[k]);
  }
  // C1 = [a1, a2], C2 = -[a1, 2 a3 + C1] / 60, Omega = a1 + a3 / 12 + [-20 a1 - a3 + C1, a2 + C2]
  // / 240: six products, each into its own matrix, and the passes around them.
  Matrix P = product(a1, a2), Q = product(a2, a1);
  Matrix W, X;
  {
    const double *p = P.data(), *q = Q.data();
    double *w = W.data(), *x = X.data();
    for (int k = 0; k < size; ++k) {
      w[k] = 2.0 * x3[k] + p[k] - q[k];            // 2 a3 + C1
      x[k] = -20.0 * x1[k] - x3[k] + p[k] - q[k];  // -20 a1 - a3 + C1
    }
  }
  P = product(a1, W);
  Q = product(W, a1);
  Matrix Y;
  {
    const double *p = P.data(), *q = Q.data();
    double* y = Y.data();
    for (int k = 0; k < size; ++k) y[k] = x2[k] - (p[k] - q[k]) / 60.0;  // a2 + C2
  }
  P = product(X, Y);
  Q = product(Y, X);
  Matrix omega;
  const double *p = P.data(), *q = Q.data();
  double* o = omega.data();
  for (int k = 0; k < size; ++k) o[k] = x1[k] + x3[k] / 12.0 + (p[k] - q[k]) / 240.0;
  return omega;
}

// The wide kernels' version of one Magnus step's exponential for 8 x 8 matrices,
// balanced_exponential(magnus6_exponent(h, J1, J2, J3), d, sweeps) compiled for AVX2 or AVX-512
// (src/flow/wide_kernels.cpp): false, with E and d untouched, where the processor has neither.
bool wide_magnus_exponential8(double h, const Eigen::Matrix<double, 8, 8>& J1,
                              const Eigen::Matrix<double, 8, 8>& J2,
                              const Eigen::Matrix<double, 8, 8>& J3, Eigen::Matrix<double, 8, 1>& d,
                              int sweeps, Eigen::Matrix<double, 8, 8>& E) noexcept;

/// The wide versions this processor can run, the widest first: for tests and benchmarks.
struct MagnusKernel {
  const char* name;  ///< "avx512" or "avx2"
  Eigen::Matrix<double, 8, 8> (*exponential)(double h, const Eigen::Matrix<double, 8, 8>& J1,
                                             const Eigen::Matrix<double, 8, 8>& J2,
                                             const Eigen::Matrix<double, 8, 8>& J3,
                                             Eigen::Matrix<double, 8, 1>& d, int sweeps);
};
std::vector<MagnusKernel> wide_magnus_kernels();

// exp(Omega) of one Magnus step: balanced_exponential(magnus6_exponent(h, J1, J2, J3), d,
// sweeps), by a wide kernel for 8 x 8 matrices where the processor has one (the same bits).
template <class Matrix>
Matrix magnus_exponential(double h, const Matrix& J1, const Matrix& J2, const Matrix& J3,
                          Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1>& d, int sweeps) {
  if constexpr (Matrix::RowsAtCompileTime == 8 && Matrix::ColsAtCompileTime == 8 &&
                !Matrix::IsRowMajor) {
    Matrix E;
    if (wide_magnus_exponential8(h, J1, J2, J3, d, sweeps, E)) return E;
  }
  return balanced_exponential(magnus6_exponent(h, J1, J2, J3), d, sweeps);
}

}  // namespace oscidrum::detail
