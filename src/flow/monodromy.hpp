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
// for Phi along it (classical Runge-Kutta on the flow's steps, subdivided to at most
// max_substep), so there is one flow and its events, chattering guard and budgets apply
// unchanged.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "oscidrum/flow.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail {

// Runge-Kutta substeps of the variational equations: at most T / kMonodromySubstepsPerPeriod of
// the excitation period T (fewer where the flow's steps or phases are shorter). Butcher's
// seven-stage scheme of order 6: its error falls with the 6th power of the substep. Every driver
// that integrates a monodromy (shooting, continuation, the motion's Lyapunov exponent) uses it.
inline constexpr double kMonodromySubstepsPerPeriod = 20.0;

// ... and enough substeps that h rho(J) stays below this (the scheme is stable to 2.86 on the
// negative real axis), rho(J) bounded by a norm of J (monodromy_rate): where a stiff phase (the
// regularised friction law's steep slope near v_rel = 0) bounds the flow's steps, Dormand-Prince
// 8(5,3) takes them up to |h lambda| = 6.39.
inline constexpr double kMonodromyStability = 1.0;

// An upper bound of the spectral radius of J [1/s]: the infinity norm of D^-1 |J| D with D =
// diag(d), an induced norm of a matrix similar to |J|, which bounds rho(|J|) >= rho(J) for any
// positive d. The state's components have different units, so J's plain norm is no bound worth
// having: `sweeps` sweeps of Osborne's balancing first bring D^-1 |J| D closer to rows and
// columns of equal sums off the diagonal, updating d (a d balanced on a nearby J needs one sweep
// where one from d = 1 needs three).
template <class Matrix>
double monodromy_rate(const Matrix& J, Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1>& d,
                      int sweeps) {
  constexpr int n = static_cast<int>(Matrix::RowsAtCompileTime);
  Matrix B = J.cwiseAbs();
  for (int i = 0; i < n; ++i) {
    const double inv = 1.0 / d[i];
    for (int j = 0; j < n; ++j) B(i, j) *= d[j] * inv;
  }
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (int i = 0; i < n; ++i) {
      const double c = B.col(i).sum() - B(i, i), r = B.row(i).sum() - B(i, i);
      if (!(c > 0.0) || !(r > 0.0)) continue;
      const double f = std::sqrt(r / c);
      B.row(i) /= f;
      B.col(i) *= f;
      d[i] *= f;
    }
  return B.rowwise().sum().maxCoeff();
}

template <class R>
class MonodromyObserver : public BasicFlowObserver<R> {
 public:
  using Dyn = Dynamics<R>;
  using Matrix = typename Dyn::Matrix;
  using StateT = typename R::State;

  /// `baumgarte` must be the flow's rate (FlowOptions::baumgarte); `max_substep` [s] bounds the
  /// Runge-Kutta substeps of Phi.
  MonodromyObserver(const Model& model, double baumgarte, double max_substep)
      : dynamics_(model, baumgarte), max_substep_(max_substep) {}

  /// Phi = I, no switches seen.
  void reset() {
    phi_.setIdentity();
    have_last_ = false;
    balanced_ = false;
    grazing_ = false;
    switches_.clear();
  }

  bool on_step(const BasicStepView<R>& step) override {
    const double a = step.t0(), b = step.t1();
    if (!(b > a)) return true;
    const Phase phase = step.phase();
    Matrix J0 = (have_last_ && last_t_ == a && last_phase_ == phase)
                    ? last_J_
                    : jacobian(a, step.state(a), phase);
    if (!balanced_) balance_.setOnes();
    const double rate = monodromy_rate(J0, balance_, balanced_ ? 1 : 3);
    balanced_ = true;
    const double stable = kMonodromyStability / std::max(rate, 1e-300);
    const int n =
        std::max(1, static_cast<int>(std::ceil((b - a) / std::min(max_substep_, stable))));
    const double h = (b - a) / n;
    // A seven-stage Runge-Kutta method of order 6 of Butcher's ("On Runge-Kutta processes of high
    // order", J. Austral. Math. Soc. 4, 1964) for the linear equation Phi' = J(t) Phi, J on the
    // dense output at the nodes 0, 1/3, 2/3, 1/2, 1 of each substep.
    for (int i = 0; i < n; ++i) {
      const double t = a + i * h, t1 = (i + 1 == n) ? b : t + h;
      const Matrix J13 = jacobian(t + h / 3.0, step.state(t + h / 3.0), phase);
      const Matrix J23 = jacobian(t + 2.0 * h / 3.0, step.state(t + 2.0 * h / 3.0), phase);
      const Matrix J12 = jacobian(t + 0.5 * h, step.state(t + 0.5 * h), phase);
      const Matrix J1 = jacobian(t1, step.state(t1), phase);
      // jacobian_times: the roller's structure of J (unit rows) saves work in the products.
      const Matrix k1 = Dyn::jacobian_times(J0, phi_);
      const Matrix k2 = Dyn::jacobian_times(J13, phi_ + (h / 3.0) * k1);
      const Matrix k3 = Dyn::jacobian_times(J23, phi_ + (2.0 * h / 3.0) * k2);
      const Matrix k4 = Dyn::jacobian_times(J13, phi_ + h * (k1 / 12.0 + k2 / 3.0 - k3 / 12.0));
      const Matrix k5 = Dyn::jacobian_times(
          J12, phi_ + h * (-k1 / 16.0 + 9.0 / 8.0 * k2 - 3.0 / 16.0 * k3 - 3.0 / 8.0 * k4));
      const Matrix k6 = Dyn::jacobian_times(
          J12, phi_ + h * (9.0 / 8.0 * k2 - 3.0 / 8.0 * k3 - 3.0 / 4.0 * k4 + 0.5 * k5));
      const Matrix k7 =
          Dyn::jacobian_times(J1, phi_ + h * (9.0 / 44.0 * k1 - 9.0 / 11.0 * k2 + 63.0 / 44.0 * k3 +
                                              18.0 / 11.0 * k4 - 16.0 / 11.0 * k6));
      phi_ += h * (11.0 / 120.0 * (k1 + k7) + 27.0 / 40.0 * (k3 + k4) - 4.0 / 15.0 * (k5 + k6));
      J0 = J1;
    }
    have_last_ = true;
    last_t_ = b;
    last_phase_ = phase;
    last_J_ = J0;
    return true;
  }

  bool on_event(const Event& event, const StateT& before, const StateT& after) override {
    if (event.kind == EventKind::contact_lost) return true;  // terminal: the flow stops
    const auto s = dynamics_.saltation(event, before.to_array(), after.to_array());
    if (s.grazing) grazing_ = true;
    have_last_ = false;
    balanced_ = false;
    phi_ = s.S.lazyProduct(phi_).eval();
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
  double max_substep_;
  Matrix phi_ = Matrix::Identity();
  // J at the end of the last piece, reused when the next piece continues it (same time, same
  // phase, no event between).
  bool have_last_ = false;
  double last_t_ = 0.0;
  Phase last_phase_ = Phase::stick;
  Matrix last_J_ = Matrix::Zero();
  bool grazing_ = false;
  // d of monodromy_rate, balanced from 1 at the first Jacobian since reset() or the last switch
  // and carried on (one sweep per step) while the phase lasts: a third of the sweeps for the same
  // bound.
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
