// The hybrid flow (oscidrum/flow.hpp): Dormand-Prince 5(4) with its dense output (Boost.Odeint),
// the scheme of MATLAB's ode45 that the paper used, through the stick/slip events.
//
// The state is the 8-vector of (54) in every phase; in stick phi follows delta by the rolling
// condition (12). Events are located by TOMS 748 root finding on the dense output of the step
// that contains them, never by shrinking steps; the integrator restarts at each event with the
// state of the new phase. A step that straddles the end of an advance() interval is kept whole:
// its dense output serves the rest of it in the next call, so a trajectory does not depend on
// how it is cut into intervals.
#include "oscidrum/flow.hpp"

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>

#include "equations/equations.hpp"
#include "equations/event_logic.hpp"
#include "flow/event_functions.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

namespace odeint = boost::numeric::odeint;
using Vec = std::array<double, 8>;
using Dopri5 = odeint::runge_kutta_dopri5<Vec>;
using DenseStepper = odeint::dense_output_runge_kutta<odeint::controlled_runge_kutta<Dopri5>>;

// Event functions are sampled at this many points inside each step before root finding, so that
// a function dipping below zero and back within one step is not missed.
constexpr int kEventSubsamples = 2;

// Chattering in a vanishing time: this many switches within kChatterWindow excitation periods.
constexpr std::size_t kChatterSwitches = 20;
constexpr double kChatterWindow = 1e-6;

// The right-hand side of (52) (stick) or (55) (slip) as a first-order system.
struct Rhs {
  const Model* model;
  Phase phase;
  double baumgarte;
  long* evaluations;

  void operator()(const Vec& x, Vec& dxdt, double t) const {
    ++*evaluations;
    const State q = State::from_array(x);
    const Kinematics k = kinematics(model->geometry(), q.delta);
    const Accelerations a =
        phase == Phase::stick
            ? detail::stick_accelerations(*model, t, q, k)
            : detail::slip_accelerations(*model, t, q, slip_sign(phase), baumgarte, k);
    dxdt[0] = x[4];
    dxdt[1] = x[5];
    dxdt[2] = x[6];
    // (12): in stick phi' = f5 delta' exactly, so phi cannot drift from the rolling condition.
    dxdt[3] = phase == Phase::stick ? k.f5 * x[4] : x[7];
    dxdt[4] = a.delta;
    dxdt[5] = a.x_A;
    dxdt[6] = a.s_A;
    dxdt[7] = a.phi;
  }
};

}  // namespace

const char* to_string(FlowStop stop) {
  switch (stop) {
    case FlowStop::reached:
      return "reached";
    case FlowStop::observer:
      return "observer";
    case FlowStop::contact_lost:
      return "contact_lost";
    case FlowStop::chattering:
      return "chattering";
    case FlowStop::non_finite:
      return "non_finite";
    case FlowStop::invalid_geometry:
      return "invalid_geometry";
    case FlowStop::budget_exceeded:
      return "budget_exceeded";
    case FlowStop::cancelled:
      return "cancelled";
  }
  return "?";
}

FlowOptions FlowOptions::from(const Model& model) {
  const Numerics& n = model.parameters().numerics;
  FlowOptions o;
  o.rtol = n.rtol;
  o.atol = n.atol;
  o.baumgarte = n.slip_constraint_rate > 0 ? n.slip_constraint_rate : 2.0 * model.nu();
  o.max_step = model.period() / 16.0;
  o.max_switches_per_period = n.max_switches_per_period;
  o.max_steps_per_period = n.max_steps_per_period;
  return o;
}

Phase initial_phase(const Model& model) { return initial_phase(model.friction()); }

struct Flow::Impl : StepView {
  Impl(const Model& m, const FlowOptions& o)
      : model(m),
        options(o),
        period(m.period()),
        stepper(odeint::make_dense_output(o.atol, o.rtol, o.max_step, Dopri5())) {
    counters.min_N = std::numeric_limits<double>::infinity();
  }

  // --- StepView: the piece [piece_t0, piece_t1] of the current step ---------------------------
  double t0() const override { return piece_t0; }
  double t1() const override { return piece_t1; }
  Phase phase() const override { return phase_; }
  bool ends_step() const override { return piece_ends_step; }
  State state(double t) const override {
    // At the step's end the integrator's own state, elsewhere the continuous extension.
    if (t == step_t1) return State::from_array(stepper.current_state());
    Vec x;
    stepper.calc_state(t, x);
    return State::from_array(x);
  }

  struct Crossing {
    bool found = false;
    double t = 0.0;
    int which = -1;  // index into EventValues
  };

  EventValues values(const Vec& x, double* N = nullptr) const {
    return event_values(model, phase_, State::from_array(x), N);
  }
  Crossing find_event(double ta, double tb);
  void restart(double t, const Vec& x);
  FlowStop apply_event(const Crossing& c, FlowObserver* observer);
  void track_step_end(const Vec& x, double N);
  bool report(double a, double b, bool ends, FlowObserver* observer);
  FlowStop stop(FlowStop s, double t, const Vec& x, std::string why) {
    t_now = t;
    x_now = x;
    message = std::move(why);
    return s;
  }

  const Model& model;
  const FlowOptions options;
  const double period;
  mutable DenseStepper stepper;
  Phase phase_ = Phase::stick;
  FlowCounters counters;
  std::string message;

  // Event function values at the start of the current step, and which of them started at zero
  // by construction (the function that just caused a switch): those must move positive.
  EventValues e_prev{};
  std::array<bool, kEventCount> e_fresh{};
  // The event functions at the end of the current step and the normal force there, as
  // find_event evaluated them (the start of the next step when no event cuts it).
  EventValues e_end{};
  double N_end = 0.0;

  // The step taken but not yet wholly consumed.
  bool have_step = false;
  double step_t0 = 0.0, step_t1 = 0.0, cursor = 0.0;
  Crossing crossing;
  double piece_t0 = 0.0, piece_t1 = 0.0;
  bool piece_ends_step = false;

  double t_now = 0.0;
  Vec x_now{};

  // Budgets per excitation period (t in [nT, (n+1)T)).
  long switch_period = -1, switches_in_period = 0;
  long step_period = -1, steps_in_period = 0;
  std::deque<double> recent_switches;
};

Flow::Impl::Crossing Flow::Impl::find_event(double ta, double tb) {
  Crossing best;
  EventValues prev = e_prev;
  double tp = ta;
  Vec x;
  for (int k = 1; k <= kEventSubsamples && !best.found; ++k) {
    const double tk = (k == kEventSubsamples) ? tb : ta + (tb - ta) * k / kEventSubsamples;
    if (k == kEventSubsamples) {
      x = stepper.current_state();
    } else {
      stepper.calc_state(tk, x);
    }
    const EventValues e = k == kEventSubsamples ? values(x, &N_end) : values(x);
    if (k == kEventSubsamples) e_end = e;
    for (int i = 0; i < kEventCount; ++i) {
      // A fresh function is zero at ta by construction and counts as positive there.
      const bool was_positive = prev[i] > 0.0 || e_fresh[i];
      if (!(was_positive && e[i] <= 0.0)) continue;
      // Root in (tp, tk]: TOMS 748 on the dense output. For a fresh function the bracket's lower
      // end is moved off the switching instant, where it is zero.
      double a = tp, fa = prev[i];
      if (e_fresh[i] && tp == ta) {
        a = ta + 1e-9 * (tk - ta);
        Vec xa;
        stepper.calc_state(a, xa);
        fa = values(xa)[i];
        if (fa <= 0.0) {  // the new phase is inconsistent at once: switch back immediately
          if (!best.found || a < best.t) best = {true, a, i};
          continue;
        }
      }
      auto f = [&](double t) {
        Vec xt;
        stepper.calc_state(t, xt);
        return values(xt)[i];
      };
      const double t_tol =
          std::max(1e-13 * period, 4.0 * std::numeric_limits<double>::epsilon() * std::abs(tk));
      auto tol = [t_tol](double lo, double hi) { return std::abs(hi - lo) <= t_tol; };
      std::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(f, a, tk, fa, e[i], tol, iterations);
      // Take the end where the event has happened (function <= 0), so that the new phase starts
      // consistently.
      const double te = bracket.second;
      if (!best.found || te < best.t) best = {true, te, i};
    }
    prev = e;
    tp = tk;
  }
  return best;
}

void Flow::Impl::restart(double t, const Vec& x) {
  const double dt = stepper.current_time_step();
  stepper.initialize(x, t, std::min(dt > 0 ? dt : period / 100.0, options.max_step));
  ++counters.restarts;
  e_prev = values(x);
  have_step = false;
  t_now = t;
  x_now = x;
}

FlowStop Flow::Impl::apply_event(const Crossing& c, FlowObserver* observer) {
  Vec x;
  stepper.calc_state(c.t, x);
  const State before = State::from_array(x);
  ++counters.events;
  Event ev;
  ev.t = c.t;
  ev.from = phase_;
  e_fresh = {};

  if (c.which == kEventContact) {  // N reached 0: lift-off is outside the model
    ev.kind = EventKind::contact_lost;
    ev.to = phase_;
    if (observer) observer->on_event(ev, before, before);
    return stop(
        FlowStop::contact_lost, c.t, x,
        detail::format("contact lost at t = %.9g s (N reached 0): the model assumes permanent "
                       "contact and does not cover lift-off",
                       c.t));
  }

  State q = before;
  if (phase_ == Phase::stick) {
    // The friction limit is reached: slip starts with s = -sign(T) (29). The negative-side
    // function (mu N - T) reaching zero means T > 0, hence slip-.
    const Phase to = (c.which == kEventConeNegative) ? Phase::slip_negative : Phase::slip_positive;
    ev.kind = EventKind::stick_to_slip;
    ev.to = to;
    phase_ = to;
    const SlipStart start = decide_slip_start(model, q, static_cast<int>(to));
    q = start.state;
    if (!start.consistent) ++counters.inconsistent_slip_ends;
    x = q.to_array();
    e_fresh[kEventSlipVelocity] = true;  // s v_rel starts at zero and must grow
  } else {
    // v_rel = 0: stick resumes if the stick solution stays inside the friction cone, else slip
    // reverses (docs/model.md section 6).
    const SlipEnd decision = decide_slip_end(model, c.t, q, static_cast<int>(phase_));
    q = decision.state;
    if (decision.stick) {
      ev.kind = EventKind::slip_to_stick;
      ev.to = Phase::stick;
      phase_ = Phase::stick;
      // The cone function on the side of the old slip starts at zero: slip+ ended with
      // T = -mu N (mu N + T = 0), slip- with T = +mu N (mu N - T = 0).
      e_fresh[ev.from == Phase::slip_positive ? kEventConePositive : kEventConeNegative] = true;
      if (!decision.consistent) ++counters.inconsistent_slip_ends;
    } else {
      ev.kind = EventKind::slip_reversal;
      ev.to = (ev.from == Phase::slip_positive) ? Phase::slip_negative : Phase::slip_positive;
      phase_ = ev.to;
      ++counters.reversals;
      e_fresh[kEventSlipVelocity] = true;
    }
    x = q.to_array();
  }
  ++counters.switches;
  const bool go_on = observer ? observer->on_event(ev, before, q) : true;

  // Chattering: many switches in a vanishing time, or too many in one excitation period.
  recent_switches.push_back(c.t);
  if (recent_switches.size() > kChatterSwitches) recent_switches.pop_front();
  if (recent_switches.size() == kChatterSwitches &&
      recent_switches.back() - recent_switches.front() < kChatterWindow * period) {
    return stop(
        FlowStop::chattering, c.t, x,
        detail::format("chattering: 20 stick/slip switches within %.3g s ending at t = %.9g s",
                       recent_switches.back() - recent_switches.front(), c.t));
  }
  const long n = static_cast<long>(std::floor(c.t / period));
  if (n != switch_period) {
    switch_period = n;
    switches_in_period = 0;
  }
  if (++switches_in_period > options.max_switches_per_period) {
    return stop(
        FlowStop::chattering, c.t, x,
        detail::format("chattering: more than %.0f stick/slip switches in the excitation period "
                       "starting at t = %.9g s",
                       static_cast<double>(options.max_switches_per_period),
                       static_cast<double>(n) * period));
  }
  restart(c.t, x);
  if (!go_on) return stop(FlowStop::observer, c.t, x, "stopped by an observer");
  return FlowStop::reached;
}

void Flow::Impl::track_step_end(const Vec& x, double N) {
  const State q = State::from_array(x);
  counters.min_N = std::min(counters.min_N, N);
  if (phase_ != Phase::stick && model.cone() > 0.0) {
    const double residual =
        std::abs(slip_constraint_residual(model, q, slip_sign(phase_))) / model.W();
    counters.max_slip_residual = std::max(counters.max_slip_residual, residual);
  }
}

bool Flow::Impl::report(double a, double b, bool ends, FlowObserver* observer) {
  if (!observer || !(b > a)) return true;
  piece_t0 = a;
  piece_t1 = b;
  piece_ends_step = ends;
  return observer->on_step(*this);
}

Flow::Flow(const Model& model, const FlowOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}

Flow::~Flow() = default;

void Flow::reset(double t, const State& q, Phase phase) {
  Impl& s = *impl_;
  const Vec x = q.to_array();
  s.phase_ = phase;
  s.e_fresh = {};
  s.recent_switches.clear();
  s.switch_period = s.step_period = -1;
  s.stepper.initialize(x, t, std::min(s.period / 100.0, s.options.max_step));
  ++s.counters.restarts;
  s.e_prev = s.values(x);
  s.have_step = false;
  s.t_now = t;
  s.x_now = x;
  s.message.clear();
}

FlowStop Flow::advance(double t_end, FlowObserver* observer) {
  Impl& s = *impl_;
  s.message.clear();
  if (!(t_end > s.t_now)) return FlowStop::reached;
  while (true) {
    if (!s.have_step) {
      if (s.options.cancelled && s.options.cancelled())
        return s.stop(FlowStop::cancelled, s.t_now, s.x_now,
                      detail::format("cancelled at t = %.9g s", s.t_now));
      Rhs rhs{&s.model, s.phase_, s.options.baumgarte, &s.counters.rhs_evaluations};
      const auto [a, b] = s.stepper.do_step(rhs);
      ++s.counters.steps;
      const Vec& x1 = s.stepper.current_state();
      if (!std::all_of(x1.begin(), x1.end(), [](double v) { return std::isfinite(v); }))
        return s.stop(
            FlowStop::non_finite, b, x1,
            detail::format("non-finite state at t = %.9g s (the integration diverged)", b));
      if (kinematics(s.model.geometry(), x1[0]).f5 <= 0.0)
        return s.stop(
            FlowStop::invalid_geometry, b, x1,
            detail::format("at t = %.9g s, delta = %.6g rad, the trough's curvature radius fell "
                           "to the drum radius (f5 <= 0): rolling is undefined there",
                           b, x1[0]));
      const long n = static_cast<long>(std::floor(a / s.period));
      if (n != s.step_period) {
        s.step_period = n;
        s.steps_in_period = 0;
      }
      if (s.options.max_steps_per_period > 0 &&
          ++s.steps_in_period > s.options.max_steps_per_period)
        return s.stop(
            FlowStop::budget_exceeded, a, s.x_now,
            detail::format(
                "more than %.0f integration steps in the excitation period starting at t = "
                "%.9g s: the problem is too stiff or too fast for the explicit Dormand-Prince "
                "method at these parameters (see numerics.max_steps_per_period)",
                static_cast<double>(s.options.max_steps_per_period),
                static_cast<double>(n) * s.period));
      s.crossing = s.find_event(a, b);
      s.have_step = true;
      s.step_t0 = a;
      s.step_t1 = b;
      s.cursor = a;
    }
    const double seg_end = s.crossing.found ? s.crossing.t : s.step_t1;
    if (t_end < seg_end) {
      if (!s.report(s.cursor, t_end, false, observer)) {
        s.cursor = t_end;
        Vec x;
        s.stepper.calc_state(t_end, x);
        return s.stop(FlowStop::observer, t_end, x, "stopped by an observer");
      }
      s.cursor = t_end;
      s.t_now = t_end;
      s.stepper.calc_state(t_end, s.x_now);
      return FlowStop::reached;
    }
    const bool go_on = s.report(s.cursor, seg_end, !s.crossing.found, observer);
    s.cursor = seg_end;
    if (s.crossing.found) {
      const FlowStop r = s.apply_event(s.crossing, observer);
      if (r != FlowStop::reached) return r;
    } else {
      // find_event evaluated the event functions at the step's end (x1) last.
      const Vec x1 = s.stepper.current_state();
      s.track_step_end(x1, s.N_end);
      s.e_prev = s.e_end;
      s.e_fresh = {};
      s.have_step = false;
      s.t_now = s.step_t1;
      s.x_now = x1;
    }
    if (!go_on) return s.stop(FlowStop::observer, s.t_now, s.x_now, "stopped by an observer");
    if (seg_end == t_end) return FlowStop::reached;
  }
}

double Flow::t() const { return impl_->t_now; }
State Flow::state() const { return State::from_array(impl_->x_now); }
Phase Flow::phase() const { return impl_->phase_; }
const Model& Flow::model() const { return impl_->model; }
const FlowOptions& Flow::options() const { return impl_->options; }
const FlowCounters& Flow::counters() const { return impl_->counters; }
void Flow::reset_extremes() {
  impl_->counters.min_N = std::numeric_limits<double>::infinity();
  impl_->counters.max_slip_residual = 0.0;
}
const std::string& Flow::message() const { return impl_->message; }

}  // namespace oscidrum
