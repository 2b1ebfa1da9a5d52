// The hybrid (stick/slip) integration from rest to the steady state (MODEL.md sections 4-7).
//
// Integration: Dormand-Prince 5(4) with its dense output (Boost.Odeint), the scheme of MATLAB's
// ode45 that the paper used. The state is the 8-vector of (54) in every phase; in stick phi
// follows delta by the rolling condition (12). Events are located by TOMS 748 root finding on the
// dense output of the step that contains them, never by shrinking steps; the integrator is
// restarted at each event with the state of the new phase.
#include "oscidrum/simulate.hpp"

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <limits>
#include <string>

#include "equations/equations.hpp"
#include "equations/event_logic.hpp"
#include "oscidrum/error.hpp"

namespace oscidrum {
namespace {

namespace odeint = boost::numeric::odeint;
using Vec = std::array<double, 8>;
using Dopri5 = odeint::runge_kutta_dopri5<Vec>;
using DenseStepper = odeint::dense_output_runge_kutta<odeint::controlled_runge_kutta<Dopri5>>;

// Components compared between excitation periods: everything but phi, which may drift by the
// net slip per period (MODEL.md section 7); phi' is compared instead.
constexpr std::array<int, 7> kPeriodic = {0, 1, 2, 4, 5, 6, 7};

// Event functions are sampled at this many points inside each step before root finding, so that
// a function dipping below zero and back within one step is not missed.
constexpr int kEventSubsamples = 2;

// A steady state repeating only every p > 1 excitation periods is accepted only while every
// comparison over fewer periods differs by more than this (scaled) amount.
constexpr double kSubharmonicGap = 1e-4;

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
            : detail::slip_accelerations(*model, t, q, static_cast<int>(phase), baumgarte, k);
    dxdt[0] = x[4];
    dxdt[1] = x[5];
    dxdt[2] = x[6];
    if (phase == Phase::stick) {
      // (12): phi' = f5 delta' exactly, so phi cannot drift away from the rolling condition.
      dxdt[3] = k.f5 * x[4];
    } else {
      dxdt[3] = x[7];
    }
    dxdt[4] = a.delta;
    dxdt[5] = a.x_A;
    dxdt[6] = a.s_A;
    dxdt[7] = a.phi;
  }
};

std::string fmt(const char* format, double a, double b = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

class Engine {
 public:
  Engine(const Model& model, const ProgressCallback& progress)
      : model_(model),
        num_(model.parameters().numerics),
        period_(model.period()),
        progress_(progress),
        stepper_(odeint::make_dense_output(num_.atol, num_.rtol, model.period() / 16.0, Dopri5())) {
    baumgarte_ = num_.slip_constraint_rate > 0 ? num_.slip_constraint_rate : 2.0 * model.nu();
  }

  Result run();

 private:
  // --- event handling -------------------------------------------------------------------------
  struct Crossing {
    bool found = false;
    double t = 0.0;
    int which = -1;  // index into event_values()
  };
  std::array<double, 3> event_values(double t, const Vec& x) const;
  Crossing find_event(double t0, double t1);
  void apply_event(const Crossing& c);
  void restart(double t, const Vec& x);

  // --- periods, steady state and sampling ----------------------------------------------------
  void on_boundary(int n, const Vec& x);
  void sample(double t, const Vec& x);
  void account_phase_time(double ta, double tb);
  void track_step_end(const Vec& x);
  bool finish(Status s, const std::string& message);

  const Model& model_;
  const Numerics num_;
  const double period_;
  const ProgressCallback& progress_;
  DenseStepper stepper_;
  double baumgarte_ = 0.0;

  Phase phase_ = Phase::stick;
  Result result_;
  bool done_ = false;

  // Event function values at the start of the current step, and which of them started at zero
  // by construction (the function that just caused a switch): those must move positive.
  std::array<double, 3> e_prev_{};
  std::array<bool, 3> e_fresh_{};

  // Period bookkeeping.
  int next_boundary_ = 1;                      // the next t = n T to process
  std::deque<std::pair<Vec, Phase>> history_;  // states at the last boundaries, newest first
  Vec range_lo_{}, range_hi_{}, last_range_{};
  long switches_this_period_ = 0;
  std::deque<double> recent_switches_;

  // Output window.
  bool sampling_ = false;
  double window_start_ = 0.0, window_end_ = 0.0;
  int window_periods_ = 0;
  long next_sample_ = 0, total_samples_ = 0;
  long inconsistent_slip_ends_ = 0;
  std::array<int, 65> below_{};  // consecutive boundaries with change_p < steady_tol, per p
};

std::array<double, 3> Engine::event_values(double /*t*/, const Vec& x) const {
  // 0, 1: stick -> slip ((28): |T| <= mu N), or, in slip, s v_rel (the slip velocity returning
  // to zero); 2: contact (N > 0). Values are scaled to O(1).
  const State q = State::from_array(x);
  const ContactForces f = contact_forces(model_, q);
  const double W = model_.W();
  std::array<double, 3> e{1.0, 1.0, f.N / W};
  if (phase_ == Phase::stick) {
    if (!model_.pure_rolling()) {
      e[0] = (model_.mu() * f.N - f.T) / W;
      e[1] = (model_.mu() * f.N + f.T) / W;
    }
  } else if (model_.mu() > 0.0) {
    const double v_scale = model_.r() * model_.nu() * 1e-3;  // 1 mrad amplitude at nu
    e[0] = static_cast<int>(phase_) * slip_velocity(model_, q) / v_scale;
  }
  return e;
}

Engine::Crossing Engine::find_event(double t0, double t1) {
  Crossing best;
  std::array<double, 3> prev = e_prev_;
  double tp = t0;
  Vec x;
  for (int k = 1; k <= kEventSubsamples && !best.found; ++k) {
    const double tk = (k == kEventSubsamples) ? t1 : t0 + (t1 - t0) * k / kEventSubsamples;
    if (k == kEventSubsamples) {
      x = stepper_.current_state();
    } else {
      stepper_.calc_state(tk, x);
    }
    const std::array<double, 3> e = event_values(tk, x);
    for (int i = 0; i < 3; ++i) {
      // A fresh function is zero at t0 by construction and counts as positive there.
      const bool was_positive = prev[i] > 0.0 || e_fresh_[i];
      if (!(was_positive && e[i] <= 0.0)) continue;
      // Root in (tp, tk]: TOMS 748 on the dense output. For a fresh function the bracket's lower
      // end is moved off the switching instant, where it is zero.
      double a = tp, fa = prev[i];
      if (e_fresh_[i] && tp == t0) {
        a = t0 + 1e-9 * (tk - t0);
        Vec xa;
        stepper_.calc_state(a, xa);
        fa = event_values(a, xa)[i];
        if (fa <= 0.0) {  // the new phase is inconsistent at once: switch back immediately
          if (!best.found || a < best.t) best = {true, a, i};
          continue;
        }
      }
      auto f = [&](double t) {
        Vec xt;
        stepper_.calc_state(t, xt);
        return event_values(t, xt)[i];
      };
      const double t_tol =
          std::max(1e-13 * period_, 4.0 * std::numeric_limits<double>::epsilon() * std::abs(tk));
      auto tol = [t_tol](double lo, double hi) { return std::abs(hi - lo) <= t_tol; };
      std::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(f, a, tk, fa, e[i], tol, iterations);
      // Take the end where the event has happened (function <= 0), so the new phase starts
      // consistently.
      const double te = bracket.second;
      if (!best.found || te < best.t) best = {true, te, i};
    }
    prev = e;
    tp = tk;
  }
  return best;
}

void Engine::restart(double t, const Vec& x) {
  const double dt = stepper_.current_time_step();
  stepper_.initialize(x, t, std::min(dt > 0 ? dt : period_ / 100.0, period_ / 16.0));
  e_prev_ = event_values(t, x);
}

void Engine::apply_event(const Crossing& c) {
  Vec x;
  stepper_.calc_state(c.t, x);
  ++result_.diagnostics.events;
  Event ev;
  ev.t = c.t;
  ev.from = phase_;
  e_fresh_ = {false, false, false};

  if (c.which == 2) {  // N reached 0: lift-off is outside the model
    ev.kind = EventKind::contact_lost;
    ev.to = phase_;
    result_.events.push_back(ev);
    finish(Status::contact_lost,
           fmt("contact lost at t = %.9g s (N reached 0): the model assumes permanent contact "
               "and does not cover lift-off",
               c.t));
    return;
  }

  State q = State::from_array(x);
  if (phase_ == Phase::stick) {
    // |T| = mu N reached: slip starts with s = -sign(T) (29). e0 = mu N - T hit zero => T > 0.
    const Phase to = (c.which == 0) ? Phase::slip_negative : Phase::slip_positive;
    ev.kind = EventKind::stick_to_slip;
    ev.to = to;
    phase_ = to;
    e_fresh_[0] = true;  // s v_rel starts at zero and must grow
  } else {
    // v_rel = 0: stick resumes if the stick solution stays inside the friction cone, else slip
    // reverses (MODEL.md section 6).
    const SlipEnd decision = decide_slip_end(model_, c.t, q, static_cast<int>(phase_));
    q = decision.state;
    if (decision.stick) {
      ev.kind = EventKind::slip_to_stick;
      ev.to = Phase::stick;
      phase_ = Phase::stick;
      // |T| = mu N on the side of the old slip: that event function starts at zero.
      // slip+ ended with T = -mu N (e1 = mu N + T = 0), slip- with T = +mu N (e0 = 0).
      e_fresh_[ev.from == Phase::slip_positive ? 1 : 0] = true;
      if (!decision.consistent) ++inconsistent_slip_ends_;
    } else {
      ev.kind = EventKind::slip_reversal;
      ev.to = (ev.from == Phase::slip_positive) ? Phase::slip_negative : Phase::slip_positive;
      phase_ = ev.to;
      ++result_.diagnostics.reversals;
      e_fresh_[0] = true;
    }
    x = q.to_array();
  }
  result_.events.push_back(ev);
  ++switches_this_period_;

  // Chattering: many switches in a vanishing time, or too many in one period.
  recent_switches_.push_back(c.t);
  if (recent_switches_.size() > 20) recent_switches_.pop_front();
  if (recent_switches_.size() == 20 &&
      recent_switches_.back() - recent_switches_.front() < 1e-6 * period_) {
    finish(Status::chattering,
           fmt("chattering: 20 stick/slip switches within %.3g s ending at t = %.9g s",
               recent_switches_.back() - recent_switches_.front(), c.t));
    return;
  }
  if (switches_this_period_ > num_.max_switches_per_period) {
    finish(Status::chattering, fmt("chattering: more than %.0f stick/slip switches in the "
                                   "excitation period ending after t = %.9g s",
                                   num_.max_switches_per_period, c.t));
    return;
  }
  restart(c.t, x);
}

void Engine::track_step_end(const Vec& x) {
  for (int i : kPeriodic) {
    range_lo_[i] = std::min(range_lo_[i], x[i]);
    range_hi_[i] = std::max(range_hi_[i], x[i]);
  }
  const State q = State::from_array(x);
  const ContactForces f = contact_forces(model_, q);
  result_.diagnostics.min_N = std::min(result_.diagnostics.min_N, f.N);
  if (phase_ != Phase::stick && model_.mu() > 0.0) {
    const double residual =
        std::abs(slip_constraint_residual(model_, q, static_cast<int>(phase_))) / model_.W();
    result_.diagnostics.max_slip_residual =
        std::max(result_.diagnostics.max_slip_residual, residual);
  }
}

void Engine::on_boundary(int n, const Vec& x) {
  result_.diagnostics.periods_simulated = n;
  if (sampling_) return;
  // The scale of each compared component: its range over the last period, floored at a level
  // the integration tolerances can resolve (a component that hardly moves, like s_A around its
  // static value, must not demand more than the integrator delivers).
  for (int i : kPeriodic) {
    const double range = range_hi_[i] - range_lo_[i];
    const double floor =
        100.0 * (num_.atol + num_.rtol * std::max(std::abs(range_hi_[i]), std::abs(range_lo_[i])));
    last_range_[i] = std::max(range, floor);
    range_lo_[i] = range_hi_[i] = x[i];
  }
  switches_this_period_ = 0;

  history_.emplace_front(x, phase_);
  if (static_cast<int>(history_.size()) > num_.max_multiplicity + 1) history_.pop_back();

  // A p-periodic steady state must repeat at p consecutive boundaries (a whole cycle of the
  // subharmonic), and for p > 1 every shorter comparison must stay macroscopic (above
  // kSubharmonicGap): the slow, lightly damped pendulum mode of the drum in its trough can alias
  // to almost a whole number of cycles over p periods, making the p-period change of a decaying
  // transient smaller than the 1-period change although the motion tends to period 1.
  int found = 0;
  double change1 = std::numeric_limits<double>::infinity();
  double shorter_min = std::numeric_limits<double>::infinity();
  for (int p = 1; p < static_cast<int>(history_.size()); ++p) {
    const auto& [xp, phase_p] = history_[p];
    double change = 0.0;
    for (int i : kPeriodic) change = std::max(change, std::abs(x[i] - xp[i]) / last_range_[i]);
    if (phase_p != phase_) change = std::max(change, 1.0);
    if (p == 1) change1 = change;
    below_[p] = change < num_.steady_tol ? below_[p] + 1 : 0;
    if (found == 0 && below_[p] >= p && (p == 1 || shorter_min > kSubharmonicGap)) found = p;
    shorter_min = std::min(shorter_min, change);
  }
  result_.diagnostics.final_change = change1;
  if (progress_ && !progress_(n, change1)) {
    done_ = true;
    result_.status = Status::max_periods_reached;
    result_.message = fmt("cancelled after %.0f periods", n);
    return;
  }

  const bool give_up = (found == 0 && n >= num_.max_periods);
  if (found == 0 && !give_up) return;

  // Start sampling the steady state (or, when giving up, the periods that follow).
  const int p = found > 0 ? found : 1;
  result_.diagnostics.periods_to_steady = found > 0 ? n : -1;
  result_.diagnostics.multiplicity = found;
  if (give_up) {
    result_.status = Status::max_periods_reached;
    result_.message =
        fmt("no steady state within %.0f periods (last period-to-period change "
            "%.3g); the last periods are sampled",
            n, change1);
  } else {
    result_.status = Status::steady_state;
    result_.message = fmt(found == 1 ? "steady state after %.0f periods"
                                     : "steady state after %.0f periods, repeating every %.0f "
                                       "excitation periods",
                          n, found);
  }
  sampling_ = true;
  window_periods_ = num_.output_periods * p;
  window_start_ = n * period_;
  window_end_ = (n + window_periods_) * period_;
  total_samples_ = static_cast<long>(window_periods_) * num_.samples_per_period;
  next_sample_ = 0;
  result_.sample_periods = window_periods_;
  result_.samples_per_period = num_.samples_per_period;
}

void Engine::sample(double t, const Vec& x) {
  const State q = State::from_array(x);
  const Accelerations a = accelerations(model_, t, q, phase_, baumgarte_);
  const DrumMotion d = drum_motion(model_, q, a);
  const ContactForces f = contact_forces(model_, q);
  Samples& s = result_.samples;
  s.t.push_back(t);
  s.delta.push_back(q.delta);
  s.phi.push_back(q.phi);
  s.x_A.push_back(q.x_A);
  s.s_A.push_back(q.s_A);
  s.ddelta.push_back(q.ddelta);
  s.dphi.push_back(q.dphi);
  s.dx_A.push_back(q.dx_A);
  s.ds_A.push_back(q.ds_A);
  s.x_M.push_back(d.x_M);
  s.z_M.push_back(d.z_M);
  s.ddx_M.push_back(d.ddx_M);
  s.ddz_M.push_back(d.ddz_M);
  s.N.push_back(f.N);
  s.T.push_back(f.T);
  s.v_rel.push_back(slip_velocity(model_, q));
  s.torque.push_back(model_.torque(t));
  s.phase.push_back(phase_);
}

void Engine::account_phase_time(double ta, double tb) {
  if (!sampling_) return;
  const double lo = std::max(ta, window_start_), hi = std::min(tb, window_end_);
  if (hi <= lo) return;
  switch (phase_) {
    case Phase::stick:
      result_.stick_time += hi - lo;
      break;
    case Phase::slip_positive:
      result_.slip_positive_time += hi - lo;
      break;
    case Phase::slip_negative:
      result_.slip_negative_time += hi - lo;
      break;
  }
}

bool Engine::finish(Status s, const std::string& message) {
  result_.status = s;
  result_.message = message;
  done_ = true;
  return true;
}

Result Engine::run() {
  result_.frequency = model_.parameters().roller.f;
  result_.diagnostics.min_N = std::numeric_limits<double>::infinity();
  const Vec x0 = model_.initial_state().to_array();
  // Start in stick (rest, T = 0 < mu N), except without friction (mu = 0), where the drum slips
  // from the start and the sign of the slip does not matter (fmu1, fmu2 do not depend on it).
  phase_ = (!model_.pure_rolling() && model_.mu() == 0.0) ? Phase::slip_positive : Phase::stick;
  range_lo_ = range_hi_ = x0;
  history_.emplace_front(x0, phase_);
  stepper_.initialize(x0, 0.0, period_ / 100.0);
  e_prev_ = event_values(0.0, x0);

  while (!done_) {
    Rhs rhs{&model_, phase_, baumgarte_, &result_.diagnostics.rhs_evaluations};
    const auto [t0, t1] = stepper_.do_step(rhs);
    ++result_.diagnostics.steps;
    const Vec& x1 = stepper_.current_state();
    if (!std::all_of(x1.begin(), x1.end(), [](double v) { return std::isfinite(v); })) {
      finish(Status::non_finite,
             fmt("non-finite state at t = %.9g s (the integration diverged)", t1));
      break;
    }
    if (kinematics(model_.geometry(), x1[0]).f5 <= 0.0) {
      finish(Status::invalid_geometry,
             fmt("at t = %.9g s, delta = %.6g rad, the trough's curvature radius fell to the "
                 "drum radius (f5 <= 0): rolling is undefined there",
                 t1, x1[0]));
      break;
    }

    const Crossing c = find_event(t0, t1);
    const double t_end = c.found ? c.t : t1;

    // Period boundaries and output samples up to t_end (in time order).
    while (!done_) {
      const double tb = next_boundary_ * period_;
      const double ts = sampling_ && next_sample_ < total_samples_
                            ? window_start_ + static_cast<double>(next_sample_) * period_ /
                                                  num_.samples_per_period
                            : std::numeric_limits<double>::infinity();
      const double tn = std::min(tb, ts);
      if (tn > t_end) break;
      Vec xn;
      stepper_.calc_state(tn, xn);
      if (ts <= tb) {
        sample(ts, xn);
        ++next_sample_;
      } else {
        on_boundary(next_boundary_, xn);
        ++next_boundary_;
      }
    }
    account_phase_time(t0, t_end);
    if (sampling_ && next_sample_ >= total_samples_ && t_end >= window_end_) done_ = true;
    if (done_) break;

    if (c.found) {
      apply_event(c);
    } else {
      track_step_end(x1);
      e_prev_ = event_values(t1, x1);
      e_fresh_ = {false, false, false};
    }
  }

  // Switch counts in the sampled window.
  if (result_.sample_periods > 0) {
    long n = 0;
    for (const Event& e : result_.events)
      if (e.t >= window_start_ && e.t < window_end_ && e.kind != EventKind::contact_lost) ++n;
    result_.diagnostics.switches_per_period = static_cast<double>(n) / result_.sample_periods;
  }
  result_.diagnostics.switches = 0;
  for (const Event& e : result_.events)
    if (e.kind != EventKind::contact_lost) ++result_.diagnostics.switches;
  if (!std::isfinite(result_.diagnostics.min_N)) result_.diagnostics.min_N = 0.0;
  result_.diagnostics.inconsistent_slip_ends = inconsistent_slip_ends_;
  // Odeint retries rejected steps internally. Dormand-Prince with FSAL costs one evaluation per
  // (re)start and six per attempted step, and nothing else calls the right-hand side, so the
  // attempts follow from the count.
  const long starts = 1 + result_.diagnostics.events;
  const long attempts = (result_.diagnostics.rhs_evaluations - starts) / 6;
  result_.diagnostics.rejected_steps = std::max(0L, attempts - result_.diagnostics.steps);
  return result_;
}

}  // namespace

Result simulate(const Model& model, const ProgressCallback& progress) {
  Engine engine(model, progress);
  return engine.run();
}

Result simulate(const Case& c, const ProgressCallback& progress) {
  const Model model(c);
  return simulate(model, progress);
}

}  // namespace oscidrum
