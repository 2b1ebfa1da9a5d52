// Internal: the variational equations of the hybrid flow. An observer of the flow
// (oscidrum/flow.hpp) that carries the sensitivity matrix Phi = d y(t) / d y(t0) along the
// trajectory the flow reports: Phi' = J(t, y(t)) Phi inside each phase, with J the analytic
// Jacobian of that phase's right-hand side (src/equations/jacobian.hpp) evaluated on the flow's
// dense output, and Phi+ = S Phi- at every switch, with S the saltation matrix of the switch
// (and of the jump map of a slip end). Over one excitation period from a periodic orbit, Phi is
// the monodromy matrix whose eigenvalues are the Floquet multipliers (docs/periodic.md).
//
// The state is integrated once, by the flow; this observer only integrates the linear equation
// for Phi along it (classical Runge-Kutta on the flow's steps, subdivided to at most
// max_substep), so there is one flow and its events, chattering guard and budgets apply
// unchanged.
#pragma once

#include <vector>

#include "equations/jacobian.hpp"
#include "oscidrum/flow.hpp"

namespace oscidrum::detail {

class MonodromyObserver : public FlowObserver {
 public:
  /// `baumgarte` must be the flow's rate (FlowOptions::baumgarte); `max_substep` [s] bounds the
  /// Runge-Kutta substeps of Phi.
  MonodromyObserver(const Model& model, double baumgarte, double max_substep);

  /// Phi = I, no switches seen.
  void reset();

  bool on_step(const StepView& step) override;
  bool on_event(const Event& event, const State& before, const State& after) override;

  const Mat8& phi() const { return phi_; }
  /// A switch met the switching surface tangentially: the linearisation does not exist there.
  bool grazing() const { return grazing_; }
  /// The switches since reset(), in time order (their kinds and phases, not their times).
  const std::vector<Event>& switches() const { return switches_; }
  long jacobian_evaluations() const { return jacobian_evaluations_; }

 private:
  Mat8 jacobian(double t, const State& q, Phase phase);

  const Model& model_;
  double baumgarte_;
  double max_substep_;
  Mat8 phi_ = Mat8::Identity();
  // J at the end of the last piece, reused when the next piece continues it (same time, same
  // phase, no event between).
  bool have_last_ = false;
  double last_t_ = 0.0;
  Phase last_phase_ = Phase::stick;
  Mat8 last_J_ = Mat8::Zero();
  bool grazing_ = false;
  std::vector<Event> switches_;
  long jacobian_evaluations_ = 0;
};

/// True when two switch sequences have the same kinds and phases in the same order.
bool same_switching_sequence(const std::vector<Event>& a, const std::vector<Event>& b);

}  // namespace oscidrum::detail
