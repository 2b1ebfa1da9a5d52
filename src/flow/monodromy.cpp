// The variational equations along the hybrid flow (src/flow/monodromy.hpp).
#include "flow/monodromy.hpp"

#include <algorithm>
#include <cmath>

namespace oscidrum::detail {

MonodromyObserver::MonodromyObserver(const Model& model, double baumgarte, double max_substep)
    : model_(model), baumgarte_(baumgarte), max_substep_(max_substep) {}

void MonodromyObserver::reset() {
  phi_.setIdentity();
  have_last_ = false;
  grazing_ = false;
  switches_.clear();
}

Mat8 MonodromyObserver::jacobian(double t, const State& q, Phase phase) {
  ++jacobian_evaluations_;
  return phase_jacobian(model_, t, q, phase, baumgarte_);
}

bool MonodromyObserver::on_step(const StepView& step) {
  const double a = step.t0(), b = step.t1();
  if (!(b > a)) return true;
  const int n = std::max(1, static_cast<int>(std::ceil((b - a) / max_substep_)));
  const double h = (b - a) / n;
  const Phase phase = step.phase();
  // Classical Runge-Kutta for the linear equation Phi' = J(t) Phi, J on the dense output.
  Mat8 J0 = (have_last_ && last_t_ == a && last_phase_ == phase)
                ? last_J_
                : jacobian(a, step.state(a), phase);
  for (int i = 0; i < n; ++i) {
    const double t = a + i * h, tm = t + 0.5 * h, t1 = (i + 1 == n) ? b : t + h;
    const Mat8 Jm = jacobian(tm, step.state(tm), phase);
    const Mat8 J1 = jacobian(t1, step.state(t1), phase);
    // jacobian_times: the structure of J (three unit rows) halves the work of the products.
    const Mat8 k1 = jacobian_times(J0, phi_);
    const Mat8 k2 = jacobian_times(Jm, phi_ + 0.5 * h * k1);
    const Mat8 k3 = jacobian_times(Jm, phi_ + 0.5 * h * k2);
    const Mat8 k4 = jacobian_times(J1, phi_ + h * k3);
    phi_ += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    J0 = J1;
  }
  have_last_ = true;
  last_t_ = b;
  last_phase_ = phase;
  last_J_ = J0;
  return true;
}

bool MonodromyObserver::on_event(const Event& event, const State& before, const State& after) {
  if (event.kind == EventKind::contact_lost) return true;  // terminal: the flow stops
  // The soil's velocities jumped (a reversal, or a slip start with mu_static > mu).
  const bool jumped =
      after.ddelta != before.ddelta || after.dx_A != before.dx_A || after.ds_A != before.ds_A;
  const Saltation s =
      switch_saltation(model_, event.t, before, event.from, event.to, baumgarte_, jumped);
  if (s.grazing) grazing_ = true;
  have_last_ = false;
  phi_ = s.S.lazyProduct(phi_).eval();
  switches_.push_back(event);
  return true;
}

bool same_switching_sequence(const std::vector<Event>& a, const std::vector<Event>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].kind != b[i].kind || a[i].from != b[i].from || a[i].to != b[i].to) return false;
  return true;
}

}  // namespace oscidrum::detail
