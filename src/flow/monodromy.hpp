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

#include "flow/magnus.hpp"
#include "oscidrum/flow.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail {

// Steps of the variational equations: at most T / kMonodromyStepsPerPeriod of the excitation
// period T (fewer where the flow's steps or phases are shorter). Every driver that integrates a
// monodromy (shooting, continuation, the motion's Lyapunov exponent) uses it.
inline constexpr double kMonodromyStepsPerPeriod = 10.0;

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
      const Matrix J1 = jacobian(lo, step.state(lo), phase),
                   J2 = jacobian(mid, step.state(mid), phase),
                   J3 = jacobian(hi, step.state(hi), phase);
      if (!balanced_) balance_.setOnes();
      phi_ = product(magnus_exponential(h, J1, J2, J3, balance_, balanced_ ? 0 : 3), phi_);
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
