// Internal: the variational equations of the hybrid flow of a roller type R. An observer of the
// flow (oscidrum/flow.hpp) that carries the sensitivity matrix Phi = d y(t) / d y(t0) along the
// trajectory the flow reports: Phi' = J(t, y(t)) Phi inside each phase, with J the Jacobian of
// that phase's right-hand side (Dynamics<R>::jacobian, analytic or by dual numbers) evaluated on
// the flow's dense output, and Phi+ = S Phi- at every switch, with S the saltation matrix of the
// switch (and of its jump map, Dynamics<R>::saltation). Over one excitation period from a
// periodic orbit, Phi is the monodromy matrix whose eigenvalues are the Floquet multipliers
// (docs/periodic.md).
//
// The state is integrated once, by the flow; this observer only integrates the linear equation
// for Phi along it (a Magnus integrator of order 6 on the flow's steps, subdivided to at most
// max_step), so there is one flow and its events, chattering guard and budgets apply
// unchanged.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "flow/matrix_product.hpp"
#include "oscidrum/flow.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail {

// Steps of the variational equations: at most T / kMonodromyStepsPerPeriod of the excitation
// period T (fewer where the flow's steps or phases are shorter). Every driver that integrates a
// monodromy (shooting, continuation, the motion's Lyapunov exponent) uses it.
inline constexpr double kMonodromyStepsPerPeriod = 10.0;

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
template <class Matrix>
Matrix balanced_exponential(const Matrix& omega,
                            Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1>& d, int sweeps) {
  constexpr int n = static_cast<int>(Matrix::RowsAtCompileTime);
  if (sweeps > 0) balanced_norm(omega, d, sweeps);
  const Eigen::Matrix<double, n, 1> inv = d.cwiseInverse();
  // B(i, j) = Omega(i, j) (d_j / d_i), by whole columns.
  Matrix B = omega.cwiseProduct(inv * d.transpose());
  const double norm = B.cwiseAbs().rowwise().sum().maxCoeff();
  if (!std::isfinite(norm)) return Matrix::Constant(std::numeric_limits<double>::quiet_NaN());
  const int s = norm > 0.5 ? std::max(0, std::ilogb(norm / 0.5) + 1) : 0;
  if (s > 0) B *= std::ldexp(1.0, -s);
  constexpr double c2 = 1.0 / 2.0, c3 = c2 / 3.0, c4 = c3 / 4.0, c5 = c4 / 5.0, c6 = c5 / 6.0,
                   c7 = c6 / 7.0, c8 = c7 / 8.0, c9 = c8 / 9.0, c10 = c9 / 10.0;
  const Matrix B2 = product(B, B), B3 = product(B2, B);
  // sum c_k B^k = ((c10 B + c9) B^3 + c8 B^2 + c7 B + c6) B^6 ... nested in B^3
  Matrix P = c10 * B;
  P.diagonal().array() += c9;
  Matrix PB3 = product(P, B3);
  P = PB3 + c8 * B2 + c7 * B;
  P.diagonal().array() += c6;
  PB3 = product(P, B3);
  P = PB3 + c5 * B2 + c4 * B;
  P.diagonal().array() += c3;
  PB3 = product(P, B3);
  P = PB3 + c2 * B2 + B;
  P.diagonal().array() += 1.0;
  for (int k = 0; k < s; ++k) P = product(P, P);
  return P.cwiseProduct(d * inv.transpose());
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
Matrix magnus6_exponent(double h, const Matrix& J1, const Matrix& J2, const Matrix& J3) {
  const Matrix a1 = h * J2;
  const Matrix a2 = (h * 1.2909944487358056284) * (J3 - J1);  // sqrt(15) / 3
  const Matrix a3 = (h * 10.0 / 3.0) * (J3 - 2.0 * J2 + J1);
  // C1 = [a1, a2], C2 = -[a1, 2 a3 + C1] / 60, Omega = a1 + a3 / 12 + [-20 a1 - a3 + C1, a2 + C2]
  // / 240. Each product into its own matrix (a coefficient-based product inside a larger
  // expression is evaluated a third slower), the sums around them in as few passes as they allow.
  Matrix P = product(a1, a2), Q = product(a2, a1);
  const Matrix W = 2.0 * a3 + P - Q;         // 2 a3 + C1
  const Matrix X = -20.0 * a1 - a3 + P - Q;  // -20 a1 - a3 + C1
  P = product(a1, W);
  Q = product(W, a1);
  const Matrix Y = a2 - (P - Q) / 60.0;  // a2 + C2
  P = product(X, Y);
  Q = product(Y, X);
  return a1 + a3 / 12.0 + (P - Q) / 240.0;
}

template <class R>
class MonodromyObserver : public BasicFlowObserver<R> {
 public:
  using Dyn = Dynamics<R>;
  using Matrix = typename Dyn::Matrix;
  using StateT = typename R::State;

  /// `baumgarte` must be the flow's rate (FlowOptions::baumgarte); `max_step` [s] bounds the
  /// Magnus steps of Phi.
  MonodromyObserver(const Model& model, double baumgarte, double max_step)
      : dynamics_(model, baumgarte), max_step_(max_step) {}

  /// Phi = I, no switches seen.
  void reset() {
    phi_.setIdentity();
    balanced_ = false;
    grazing_ = false;
    switches_.clear();
  }

  bool on_step(const BasicStepView<R>& step) override {
    const double a = step.t0(), b = step.t1();
    if (!(b > a)) return true;
    const Phase phase = step.phase();
    const int n = std::max(1, static_cast<int>(std::ceil((b - a) / max_step_)));
    const double h = (b - a) / n;
    for (int i = 0; i < n; ++i) {
      const double t = a + i * h, lo = t + (0.5 - kMagnusNode) * h, mid = t + 0.5 * h,
                   hi = t + (0.5 + kMagnusNode) * h;
      const Matrix omega = magnus6_exponent(h, jacobian(lo, step.state(lo), phase),
                                            jacobian(mid, step.state(mid), phase),
                                            jacobian(hi, step.state(hi), phase));
      if (!balanced_) balance_.setOnes();
      phi_ = product(balanced_exponential(omega, balance_, balanced_ ? 0 : 3), phi_);
      balanced_ = true;
    }
    return true;
  }

  bool on_event(const Event& event, const StateT& before, const StateT& after) override {
    if (event.kind == EventKind::contact_lost) return true;  // terminal: the flow stops
    const auto s = dynamics_.saltation(event, before.to_array(), after.to_array());
    if (s.grazing) grazing_ = true;
    balanced_ = false;
    phi_ = product(s.S, phi_);
    switches_.push_back(event);
    return true;
  }

  const Matrix& phi() const { return phi_; }
  /// A switch met the switching surface tangentially: the linearisation does not exist there.
  bool grazing() const { return grazing_; }
  /// The switches since reset(), in time order (their kinds and phases, not their times).
  const std::vector<Event>& switches() const { return switches_; }
  long jacobian_evaluations() const { return jacobian_evaluations_; }

 private:
  Matrix jacobian(double t, const StateT& q, Phase phase) {
    ++jacobian_evaluations_;
    return dynamics_.jacobian(phase, t, q.to_array());
  }

  const Dyn dynamics_;
  double max_step_;
  Matrix phi_ = Matrix::Identity();
  bool grazing_ = false;
  // d of balanced_exponential: three sweeps from 1 at the first step since reset() or the last
  // switch, then kept while the phase lasts (a sweep per step, tried, cost about as much as four
  // matrix products and more than it saved in squarings: bench_monodromy).
  bool balanced_ = false;
  Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1> balance_;
  std::vector<Event> switches_;
  long jacobian_evaluations_ = 0;
};

/// True when two switch sequences have the same kinds and phases in the same order.
inline bool same_switching_sequence(const std::vector<Event>& a, const std::vector<Event>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].kind != b[i].kind || a[i].from != b[i].from || a[i].to != b[i].to) return false;
  return true;
}

}  // namespace oscidrum::detail
