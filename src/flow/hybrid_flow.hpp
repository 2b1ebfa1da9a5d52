// Internal: the hybrid flow of any roller type R (oscidrum/flow.hpp's BasicFlow<R>), Dormand-
// Prince 8(5,3) with its continuous extension of order 7 (flow/dop853.hpp), through the roller's
// events (the paper used MATLAB's ode45, Dormand-Prince 5(4): at the same tolerances the 8th-order
// pair takes steps about four times as long). Included by the one file that instantiates the engine
// for each roller (src/roller/engine.cpp).
//
// The state is the roller's vector (Dynamics<R>::Vector) in every phase; the right-hand side,
// the event functions and what an event does are the roller's (src/roller/dynamics.hpp). Events
// are located by TOMS 748 root finding on the dense output of the step that contains them, never
// by shrinking steps; the integrator restarts at each event with the state of the new phase. A
// step that straddles the end of an advance() interval is kept whole: its dense output serves the
// rest of it in the next call, so a trajectory does not depend on how it is cut into intervals.
#pragma once

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <string>

#include "flow/dop853.hpp"
#include "oscidrum/flow.hpp"
#include "roller/dynamics.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace detail {

// Event functions are sampled at this many points inside each step (evenly, the last at the
// step's end) before root finding, so that a function dipping below zero and back within one
// step is not missed. 8: the density of two samples per step of Dormand-Prince 5(4) (about four
// times shorter steps); with two samples per step of 8(5,3), short slip phases were missed often
// enough that orbits of long period never settled.
inline constexpr int kEventSubsamples = 8;

// A function positive at every sample of a step can still dip through zero and back between
// them: near a grazing, the slip+ phase of the paper's roller at MMd = 6885 N m lasts 0.4 % of
// the period, and the stick phase carried |T| > mu N through it (mu_required 0.50013) when it
// fell inside a step of Dormand-Prince 5(4) sampled twice. Where the parabola through the lowest
// sample and its neighbours has its minimum between them
// and below kDipFraction times the lowest sample, the function is evaluated there, and at the
// minimum of the parabola through the lowest value and its neighbours up to kDipEvaluations
// times in all; a value at or below zero brackets the event's root with the sample before it.
inline constexpr double kDipFraction = 0.5;
inline constexpr int kDipEvaluations = 4;

// The normal force's minimum inside a step, for min_N: where the parabola through N at its lowest
// sample and that sample's neighbours has its minimum between them, N is evaluated there on the
// dense output, and at the minimum of the parabola through the lowest value and its neighbours,
// up to this many times in all (successive parabolic interpolation). The parabola alone misses
// N's minimum by an error that grows with the fourth power of the sample spacing: with three
// samples per step of Dormand-Prince 8(5,3) it kept a continuation from locating where the
// paper's roller lifts off at 65.7 Hz.
inline constexpr int kMinNEvaluations = 3;

// The minimum of the parabola through (t[0], f[0]), (t[1], f[1]), (t[2], f[2]) (t increasing):
// false when the parabola is not convex or its minimum is not strictly between t[0] and t[2].
inline bool parabola_minimum(const double* t, const double* f, double& t_min, double& f_min) {
  const double d1 = (f[1] - f[0]) / (t[1] - t[0]);
  const double d2 = (f[2] - f[1]) / (t[2] - t[1]);
  const double a = (d2 - d1) / (t[2] - t[0]);
  if (!(a > 0.0)) return false;
  t_min = 0.5 * (t[0] + t[1]) - d1 / (2.0 * a);
  if (!(t_min > t[0] && t_min < t[2])) return false;
  f_min = f[0] + d1 * (t_min - t[0]) + a * (t_min - t[0]) * (t_min - t[1]);
  return true;
}

// Event functions are scaled to O(1): a value below -kWrongSide is not the round-off of a
// function that a switch left at zero, but a phase that does not hold where it starts.
inline constexpr double kWrongSide = 1e-6;

// Chattering in a vanishing time: this many switches within kChatterWindow excitation periods.
inline constexpr std::size_t kChatterSwitches = 20;
inline constexpr double kChatterWindow = 1e-6;

// After a switch the integration restarts with this fraction of the step the controller proposed
// before it. The proposal comes from the old phase: the first step of the new one failed its
// error test at almost every switch of the paper's stick-slip case (errors 5 to 20 times the
// tolerance, 39 rejected steps of 209, each 12 wasted evaluations of the right-hand side). With
// 0.7 that case from rest (MMd = 0.05 M0) evaluates the right-hand side 11 % less often (0.8: 2 %,
// 0.6: 11 %); over the 56 cases of examples/table2_sweep.toml the work (evaluations plus five
// per Jacobian) is 0.7 % less (0.8: 0.8 %, 0.6: 0.5 %; 0.5: 1 % more). bench/README.md, "Issue
// 26: the first step after a switch".
inline constexpr double kRestartStep = 0.7;

}  // namespace detail

template <class R>
struct BasicFlow<R>::Impl : BasicStepView<R> {
  using Dyn = detail::Dynamics<R>;
  using Vec = typename Dyn::Vector;
  using EventValues = typename Dyn::EventValues;
  using DenseStepper = detail::Dop853<Vec>;
  using Observer = BasicFlowObserver<R>;
  using StateT = typename R::State;

  // The right-hand side of the current phase as a first-order system, for the stepper.
  struct Rhs {
    const Dyn* dynamics;
    Phase phase;
    long* evaluations;
    void operator()(const Vec& x, Vec& dxdt, double t) const {
      ++*evaluations;
      dynamics->rhs(phase, t, x, dxdt);
    }
  };

  Impl(const Model& m, const FlowOptions& o)
      : model(m),
        options(o),
        period(m.period()),
        dynamics(m, o.baumgarte),
        stepper(o.atol, o.rtol, o.max_step) {
    counters.min_N = std::numeric_limits<double>::infinity();
  }

  // --- StepView: the piece [piece_t0, piece_t1] of the current step ---------------------------
  double t0() const override { return piece_t0; }
  double t1() const override { return piece_t1; }
  Phase phase() const override { return phase_; }
  bool ends_step() const override { return piece_ends_step; }
  StateT state(double t) const override { return StateT::from_array(vector_at(t)); }
  void states(const double* t, int n, StateT* out) const override {
    constexpr int kBlock = 16;
    std::array<Vec, kBlock> x;
    for (int i0 = 0; i0 < n; i0 += kBlock) {
      const int m = std::min(kBlock, n - i0);
      stepper.calc_states(t + i0, m, x.data());
      for (int j = 0; j < m; ++j)  // as vector_at: the integrator's own state at the step's end
        out[i0 + j] = StateT::from_array(t[i0 + j] == step_t1 ? stepper.current_state() : x[j]);
    }
  }
  Vec vector_at(double t) const {
    // At the step's end the integrator's own state, elsewhere the continuous extension.
    if (t == step_t1) return stepper.current_state();
    Vec x;
    stepper.calc_state(t, x);
    return x;
  }

  struct Crossing {
    bool found = false;
    double t = 0.0;
    int which = -1;  // index into EventValues
  };

  EventValues values(const Vec& x, double* N = nullptr) const {
    return dynamics.events(phase_, x, N);
  }
  Crossing find_event(double ta, double tb);
  void find_dip(int i, double ta, double tm, double tb, const std::array<double, 3>& f,
                Crossing& best);
  double root(int i, double a, double fa, double b, double fb);
  void restart(double t, const Vec& x);
  void track_min_N();
  FlowStop apply_event(const Crossing& c, Observer* observer);
  bool report(double a, double b, bool ends, Observer* observer);
  FlowStop stop(FlowStop s, double t, const Vec& x, std::string why) {
    t_now = t;
    x_now = x;
    message = std::move(why);
    return s;
  }
  FlowStop advance(double t_end, Observer* observer);

  const Model& model;
  const FlowOptions options;
  const double period;
  const Dyn dynamics;
  mutable DenseStepper stepper;
  Phase phase_ = Phase::stick;
  FlowCounters counters;
  std::string message;

  // Event function values at the start of the current step, and which of them started at zero
  // by construction (the function that just caused a switch): those must move positive.
  EventValues e_prev{};
  // Set by reset when the state given lies on the wrong side of one of its phase's switching
  // surfaces (FlowStop::inconsistent_state): the next advance stops with this message.
  std::string inconsistent;
  std::array<bool, Dyn::kEvents> e_fresh{};
  // The event functions at the end of the current step and the normal force there, as
  // find_event evaluated them (the start of the next step when no event cuts it).
  EventValues e_end{};
  double N_end = 0.0;
  // The normal force at the start of the current step [N] and at its samples (the last is
  // N_end): where N's minimum inside the step is sought (track_min_N).
  double N_start = 0.0;
  std::array<double, detail::kEventSubsamples> N_samples{};

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

template <class R>
typename BasicFlow<R>::Impl::Crossing BasicFlow<R>::Impl::find_event(double ta, double tb) {
  Crossing best;
  constexpr int kSub = detail::kEventSubsamples;
  // The samples: ts[0] = ta with e_prev, ts[kSub] = tb.
  std::array<double, kSub + 1> ts{};
  std::array<EventValues, kSub + 1> es{};
  ts[0] = ta;
  es[0] = e_prev;
  Vec x;
  // A contact that pulls where its phase starts (N well below zero after a landing, which then
  // "lifts off again at once"): the switch is taken at once. Left to the samples it was missed
  // where N rose through zero before the step's middle (a landing of a unilateral pure-rolling
  // drum stayed in stick with N down to -307 N for 0.4 % of the period). Other functions may
  // start below zero and recover (a slip ending outside the cone: inconsistent_slip_ends).
  if constexpr (Dyn::kContactEvent >= 0) {
    constexpr int kContact = Dyn::kContactEvent;
    if (e_fresh[kContact] && e_prev[kContact] < -detail::kWrongSide) {
      const double a = ta + 1e-9 * (tb - ta);
      Vec xa;
      stepper.calc_state(a, xa);
      if (values(xa)[kContact] <= 0.0) return {true, a, kContact};
    }
  }
  // The samples' states and event functions, all at once where the roller evaluates them in
  // lanes (events_many: their chains of operations overlap), else one by one up to the first
  // sample past an event.
  constexpr bool kMany = requires(const Vec* xs, EventValues* e, double* N) {
    dynamics.events_many(phase_, xs, kSub, e, N);
  };
  for (int k = 1; k <= kSub; ++k) ts[k] = (k == kSub) ? tb : ta + (tb - ta) * k / kSub;
  if constexpr (kMany) {
    std::array<Vec, kSub> xs;
    stepper.calc_states(&ts[1], kSub - 1, xs.data());
    xs[kSub - 1] = stepper.current_state();
    dynamics.events_many(phase_, xs.data(), kSub, &es[1], N_samples.data());
  }
  for (int k = 1; k <= kSub && !best.found; ++k) {
    const double tk = ts[k];
    if constexpr (!kMany) {
      if (k == kSub) {
        x = stepper.current_state();
      } else {
        stepper.calc_state(tk, x);
      }
      es[k] = values(x, &N_samples[k - 1]);
    }
    const EventValues& e = es[k];
    const EventValues& prev = es[k - 1];
    const double tp = ts[k - 1];
    for (int i = 0; i < Dyn::kEvents; ++i) {
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
      const double te = root(i, a, fa, tk, e[i]);
      if (!best.found || te < best.t) best = {true, te, i};
    }
  }
  if (best.found) return best;
  e_end = es[kSub];
  N_end = N_samples[kSub - 1];
  // No function fell through zero at a sample: one may have dipped through it between them,
  // near its lowest sample (between that sample's neighbours).
  for (int i = 0; i < Dyn::kEvents; ++i) {
    if (e_fresh[i]) continue;
    int low = 0;
    for (int k = 0; k <= kSub; ++k) {
      if (!(es[k][i] > 0.0)) low = -1;
      if (low < 0) break;
      if (es[k][i] < es[low][i]) low = k;
    }
    if (low < 0) continue;
    const int m = std::clamp(low, 1, kSub - 1);
    find_dip(i, ts[m - 1], ts[m], ts[m + 1], {es[m - 1][i], es[m][i], es[m + 1][i]}, best);
  }
  return best;
}

template <class R>
double BasicFlow<R>::Impl::root(int i, double a, double fa, double b, double fb) {
  // TOMS 748 on the dense output, in (a, b] where f(a) > 0 >= f(b).
  auto f = [&](double t) {
    Vec xt;
    stepper.calc_state(t, xt);
    return values(xt)[i];
  };
  const double t_tol =
      std::max(1e-13 * period, 4.0 * std::numeric_limits<double>::epsilon() * std::abs(b));
  auto tol = [t_tol](double lo, double hi) { return std::abs(hi - lo) <= t_tol; };
  std::uintmax_t iterations = 100;
  const auto bracket = boost::math::tools::toms748_solve(f, a, b, fa, fb, tol, iterations);
  // Take the end where the event has happened (function <= 0), so that the new phase starts
  // consistently.
  return bracket.second;
}

template <class R>
void BasicFlow<R>::Impl::find_dip(int i, double ta, double tm, double tb,
                                  const std::array<double, 3>& f, Crossing& best) {
  // The samples in time order (kDipFraction, kDipEvaluations).
  std::array<double, 3 + detail::kDipEvaluations> ts{ta, tm, tb}, fs{f[0], f[1], f[2]};
  std::size_t n = 3;
  for (int evaluation = 0; evaluation < detail::kDipEvaluations; ++evaluation) {
    const std::size_t low =
        static_cast<std::size_t>(std::min_element(fs.begin(), fs.begin() + n) - fs.begin());
    const std::size_t first = std::clamp<std::size_t>(low, 1, n - 2) - 1;
    double t_min = 0.0, f_min = 0.0;
    if (!detail::parabola_minimum(&ts[first], &fs[first], t_min, f_min)) return;
    if (!(f_min < detail::kDipFraction * fs[low])) return;
    const std::size_t at =
        static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.begin() + n, t_min) - ts.begin());
    if (at == 0 || at == n || t_min <= ts[at - 1]) return;  // no time between the samples left
    Vec x;
    stepper.calc_state(t_min, x);
    const double value = values(x)[i];
    if (!(value > 0.0)) {
      const double te = root(i, ts[at - 1], fs[at - 1], t_min, value);
      if (!best.found || te < best.t) best = {true, te, static_cast<int>(i)};
      return;
    }
    std::copy_backward(ts.begin() + at, ts.begin() + n, ts.begin() + n + 1);
    std::copy_backward(fs.begin() + at, fs.begin() + n, fs.begin() + n + 1);
    ts[at] = t_min;
    fs[at] = value;
    ++n;
  }
}

template <class R>
void BasicFlow<R>::Impl::track_min_N() {
  // N at three times of the step in increasing order: the lowest sample and its neighbours, then
  // the lowest value with its neighbours once evaluations are in (kMinNEvaluations). No lower
  // than 0: where N fell through 0 inside the step, find_event took the event.
  constexpr int kSub = detail::kEventSubsamples;
  auto sample_t = [&](int k) {
    return k == kSub ? step_t1 : step_t0 + (step_t1 - step_t0) * k / kSub;
  };
  auto sample_N = [&](int k) { return k == 0 ? N_start : N_samples[k - 1]; };
  int low = 0;
  for (int k = 1; k <= kSub; ++k)
    if (sample_N(k) < sample_N(low)) low = k;
  const int m = std::clamp(low, 1, kSub - 1);
  std::array<double, 3> ts{sample_t(m - 1), sample_t(m), sample_t(m + 1)};
  std::array<double, 3> Ns{sample_N(m - 1), sample_N(m), sample_N(m + 1)};
  for (int k = 0; k < detail::kMinNEvaluations; ++k) {
    double t_min = 0.0, N_parabola = 0.0;
    if (!detail::parabola_minimum(ts.data(), Ns.data(), t_min, N_parabola)) return;
    if (t_min == ts[1]) return;  // converged to the resolution of t
    Vec x;
    stepper.calc_state(t_min, x);
    double N = 0.0;
    values(x, &N);
    counters.min_N = std::min(counters.min_N, std::max(N, 0.0));
    // Keep the lowest value with its neighbours on either side.
    if (t_min < ts[1]) {
      if (N <= Ns[1])
        ts = {ts[0], t_min, ts[1]}, Ns = {Ns[0], N, Ns[1]};
      else
        ts[0] = t_min, Ns[0] = N;
    } else {
      if (N <= Ns[1])
        ts = {ts[1], t_min, ts[2]}, Ns = {Ns[1], N, Ns[2]};
      else
        ts[2] = t_min, Ns[2] = N;
    }
  }
}

template <class R>
void BasicFlow<R>::Impl::restart(double t, const Vec& x) {
  const double dt = detail::kRestartStep * stepper.current_time_step();
  stepper.initialize(x, t, std::min(dt > 0 ? dt : period / 100.0, options.max_step));
  ++counters.restarts;
  e_prev = values(x, &N_start);
  // A function of the new phase that is already at or below zero after the switch (not one the
  // switch marked fresh) would never fire: it fires only when it falls through zero from above.
  // It counts as fresh, so that find_event takes the switch it makes at once. This happens where
  // two switching surfaces meet: a drum whose friction cone closes as N reaches 0 (T and N
  // vanishing together, the symmetric lift-off of a vertical exciter) switches from stick to
  // slip with N already at 0 in slip, and would otherwise slip on with N < 0, pulling the soil.
  for (int i = 0; i < Dyn::kEvents; ++i)
    if (e_prev[i] <= 0.0) e_fresh[i] = true;
  have_step = false;
  t_now = t;
  x_now = x;
}

template <class R>
FlowStop BasicFlow<R>::Impl::apply_event(const Crossing& c, Observer* observer) {
  // The state at the event by the integrator's own step to it (step_to): the next phase starts
  // from it, and the continuous extension's error (an order higher in the step) would enter the
  // trajectory at every switch (the slip coupling (39) held ten times worse, stroboscopic
  // points of a period-11 lift-off orbit repeated to 4e-6 instead of 1e-8).
  Vec x = stepper.step_to(c.t, Rhs{&dynamics, phase_, &counters.rhs_evaluations});
  ++counters.partial_steps;
  // The state at the event is one of the trajectory: N there counts in min_N (N has a corner
  // minimum at a stick-to-slip switch, 83 N below every step end of a case of mu 1.27).
  // (No lower than 0: a landing whose contact pulls at once lifts off, or loses contact, there.)
  double N_event = 0.0;
  values(x, &N_event);
  dynamics.track(phase_, x, std::max(N_event, 0.0), counters);
  ++counters.events;
  Event ev;
  ev.t = c.t;
  ev.from = phase_;
  e_fresh = {};
  const typename Dyn::Switch sw = dynamics.apply(phase_, c.which, c.t, x);
  ev.kind = sw.kind;
  ev.to = sw.to;
  ev.speed = sw.speed;
  // N reached 0 here (a lift-off, or the contact lost): the smallest normal force of the
  // trajectory is 0, not the smallest at the step ends before it (which read as a margin of
  // hundreds of newtons on a run that lost contact). Where the contact pulled from the start of
  // its phase (a landing with N < 0, switched at once), N there is the smallest; a root's
  // round-off (below 1e-6 of the weight) is 0.
  if (sw.kind == EventKind::contact_lost || sw.kind == EventKind::lift_off) {
    double N_here = 0.0;
    values(x, &N_here);
    counters.min_N =
        std::min(counters.min_N, N_here < -detail::kWrongSide * model.W() ? N_here : 0.0);
  }
  const StateT before = StateT::from_array(x);
  if (sw.terminal) {
    if (observer) observer->on_event(ev, before, before);
    return stop(sw.stop, c.t, x, sw.message);
  }
  phase_ = sw.to;
  e_fresh = sw.fresh;
  if (!sw.consistent) ++counters.inconsistent_slip_ends;
  if (sw.reversal) ++counters.reversals;
  x = sw.after;
  ++counters.switches;
  const bool go_on = observer ? observer->on_event(ev, before, StateT::from_array(x)) : true;

  // Chattering: many switches in a vanishing time, or too many in one excitation period.
  recent_switches.push_back(c.t);
  if (recent_switches.size() > detail::kChatterSwitches) recent_switches.pop_front();
  if (recent_switches.size() == detail::kChatterSwitches &&
      recent_switches.back() - recent_switches.front() < detail::kChatterWindow * period) {
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

template <class R>
bool BasicFlow<R>::Impl::report(double a, double b, bool ends, Observer* observer) {
  if (!observer || !(b > a)) return true;
  piece_t0 = a;
  piece_t1 = b;
  piece_ends_step = ends;
  return observer->on_step(*this);
}

template <class R>
FlowStop BasicFlow<R>::Impl::advance(double t_end, Observer* observer) {
  message.clear();
  if (!(t_end > t_now)) return FlowStop::reached;
  if (!inconsistent.empty()) return stop(FlowStop::inconsistent_state, t_now, x_now, inconsistent);
  while (true) {
    if (!have_step) {
      if (options.cancelled && options.cancelled())
        return stop(FlowStop::cancelled, t_now, x_now,
                    detail::format("cancelled at t = %.9g s", t_now));
      Rhs rhs{&dynamics, phase_, &counters.rhs_evaluations};
      const auto [a, b] = stepper.do_step(rhs);
      if (stepper.failed())
        return stop(FlowStop::budget_exceeded, t_now, x_now,
                    detail::format("the integration step fell below the round-off of t = %.9g s: "
                                   "the problem is too stiff for the explicit Dormand-Prince "
                                   "method at these parameters",
                                   t_now));
      ++counters.steps;
      const Vec& x1 = stepper.current_state();
      if (!std::all_of(x1.begin(), x1.end(), [](double v) { return std::isfinite(v); }))
        return stop(FlowStop::non_finite, b, x1,
                    detail::format("non-finite state at t = %.9g s (the integration diverged)", b));
      std::string why;
      FlowStop invalid = FlowStop::invalid_geometry;
      if (dynamics.invalid(phase_, x1, b, &why, &invalid)) return stop(invalid, b, x1, why);
      const long n = static_cast<long>(std::floor(a / period));
      if (n != step_period) {
        step_period = n;
        steps_in_period = 0;
      }
      if (options.max_steps_per_period > 0 && ++steps_in_period > options.max_steps_per_period)
        return stop(
            FlowStop::budget_exceeded, a, x_now,
            detail::format(
                "more than %.0f integration steps in the excitation period starting at t = "
                "%.9g s: the problem is too stiff or too fast for the explicit Dormand-Prince "
                "method at these parameters (see numerics.max_steps_per_period)",
                static_cast<double>(options.max_steps_per_period),
                static_cast<double>(n) * period));
      crossing = find_event(a, b);
      have_step = true;
      step_t0 = a;
      step_t1 = b;
      cursor = a;
    }
    const double seg_end = crossing.found ? crossing.t : step_t1;
    if (t_end < seg_end) {
      if (!report(cursor, t_end, false, observer)) {
        cursor = t_end;
        Vec x;
        stepper.calc_state(t_end, x);
        return stop(FlowStop::observer, t_end, x, "stopped by an observer");
      }
      cursor = t_end;
      t_now = t_end;
      // The state at the interval's end by the integrator's own step to it (step_to), not the
      // continuous extension: drivers compare these states period to period (the steady-state
      // search, the shooting residual), and the extension's error, an order higher, varies with
      // where the steps fall in each period (a noise floor above 1e-9 of the ranges).
      x_now = stepper.step_to(t_end, Rhs{&dynamics, phase_, &counters.rhs_evaluations});
      ++counters.partial_steps;
      return FlowStop::reached;
    }
    const bool go_on = report(cursor, seg_end, !crossing.found, observer);
    cursor = seg_end;
    if (crossing.found) {
      const FlowStop r = apply_event(crossing, observer);
      if (r != FlowStop::reached) return r;
    } else {
      // find_event evaluated the event functions at the step's end (x1) last.
      const Vec x1 = stepper.current_state();
      dynamics.track(phase_, x1, N_end, counters);
      track_min_N();
      N_start = N_end;
      e_prev = e_end;
      e_fresh = {};
      have_step = false;
      t_now = step_t1;
      x_now = x1;
    }
    if (!go_on) return stop(FlowStop::observer, t_now, x_now, "stopped by an observer");
    if (seg_end == t_end) return FlowStop::reached;
  }
}

template <class R>
BasicFlow<R>::BasicFlow(const Model& model, const FlowOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {}

template <class R>
BasicFlow<R>::~BasicFlow() = default;

template <class R>
void BasicFlow<R>::reset(double t, const State& q, Phase phase) {
  Impl& s = *impl_;
  const typename Impl::Vec x = q.to_array();
  s.phase_ = phase;
  s.e_fresh = {};
  s.recent_switches.clear();
  s.switch_period = s.step_period = -1;
  s.stepper.initialize(x, t, std::min(s.period / 100.0, s.options.max_step));
  ++s.counters.restarts;
  s.e_prev = s.values(x, &s.N_start);  // the first step's parabola of min_N starts here
  // An event fires when its function falls through zero from above: a function that starts below
  // zero never fires, and the flow would follow the phase's equations where they do not hold
  // (a shooting iterate in flight with the drum inside the trough closed into a spurious orbit
  // in flight throughout). Below -kWrongSide is not round-off at a switch.
  s.inconsistent.clear();
  for (int i = 0; i < Impl::Dyn::kEvents; ++i) {
    // On the surface itself (within round-off): the function counts as fresh, so that a switch
    // it makes at once (a landing from g = 0 with g' < 0) is taken at the start, where a function
    // that only touches zero from above would never fire.
    if (s.e_prev[i] <= 0.0 && s.e_prev[i] >= -detail::kWrongSide) s.e_fresh[i] = true;
    if (s.e_prev[i] < -detail::kWrongSide) {
      s.inconsistent = detail::format(
          "the state at t = %.9g s is not one of its phase: its event function %.0f is %.3g < 0 "
          "(on the wrong side of the switch it detects)",
          t, i, s.e_prev[i]);
      s.inconsistent += std::string(" in ") + to_string(phase);
      break;
    }
  }
  s.have_step = false;
  s.t_now = t;
  s.x_now = x;
  s.message.clear();
}

template <class R>
FlowStop BasicFlow<R>::advance(double t_end, Observer* observer) {
  return impl_->advance(t_end, observer);
}

template <class R>
double BasicFlow<R>::t() const {
  return impl_->t_now;
}
template <class R>
typename BasicFlow<R>::State BasicFlow<R>::state() const {
  return State::from_array(impl_->x_now);
}
template <class R>
Phase BasicFlow<R>::phase() const {
  return impl_->phase_;
}
template <class R>
const Model& BasicFlow<R>::model() const {
  return impl_->model;
}
template <class R>
const FlowOptions& BasicFlow<R>::options() const {
  return impl_->options;
}
template <class R>
const FlowCounters& BasicFlow<R>::counters() const {
  return impl_->counters;
}
template <class R>
void BasicFlow<R>::reset_extremes() {
  impl_->counters.min_N = std::numeric_limits<double>::infinity();
  impl_->counters.max_slip_residual = 0.0;
}
template <class R>
const std::string& BasicFlow<R>::message() const {
  return impl_->message;
}

}  // namespace oscidrum
