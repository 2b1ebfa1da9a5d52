// Internal: the transient steady-state search, a driver on the flow of any roller type R.
// Integrates period by period
// until the state at t = n T repeats (Numerics::steady_tol, multiplicity up to
// Numerics::max_multiplicity), and tells the other ways a run can end.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"
#include "roller/dynamics.hpp"
#include "util/format.hpp"

namespace oscidrum::detail {

/// How the search ended. On Status::steady_state or max_periods_reached, the flow stands at the
/// boundary t = n T where sampling starts.
struct SearchOutcome {
  Status status = Status::steady_state;
  std::string message;
  int multiplicity = 0;  ///< steady period in excitation periods (0: none found)
  int periods = 0;       ///< boundary index n reached
  /// last period-to-period change (scaled) [-]; NaN until two period boundaries were reached
  double final_change = std::numeric_limits<double>::quiet_NaN();
  double phi_drift = 0.0;            ///< gross slip: the drift of phi over the last period [rad]
  std::vector<Event> recent_events;  ///< the last events before a stop other than steady/max
};

namespace steady {

// A steady state repeating only every p > 1 excitation periods is accepted only while every
// comparison over fewer periods differs by more than this (scaled) amount.
inline constexpr double kSubharmonicGap = 1e-4;

// Gross slip: this many consecutive periods in one slip phase without a switch (see gross_slip).
inline constexpr int kGrossSlipPeriods = 3;
// ... and under a friction law whose coefficient grows with the slip speed (the regularised law),
// this many, the growth of phi' in the last of them at least kUnfadingGrowth of the first's.
inline constexpr int kGrossSlipPeriodsSmooth = 8;
inline constexpr double kUnfadingGrowth = 0.95;

// Noise floor: the smallest period-to-period change of the last kStagnationPeriods periods is
// not below kStagnationRatio times the smallest of the kStagnationPeriods before (a transient,
// even one decaying by 1 % per period, gains a factor 0.6 over 50 periods), and the change is
// below the level the integration resolves (noise_floor): the state is as periodic as the
// integration can tell.
inline constexpr int kStagnationPeriods = 50;
inline constexpr double kStagnationRatio = 0.9;

// Events kept for a run that ends early, to show what led to the end.
inline constexpr std::size_t kRecentEvents = 64;

// The components compared between excitation periods are the roller's periodic ones
// (Dynamics<R>::kPeriodic): for the oscillation drum everything but phi, which may drift by the
// net slip per period; phi' is compared instead.
template <class R>
class Search : public BasicFlowObserver<R> {
 public:
  using State = typename R::State;
  using Dyn = Dynamics<R>;
  using Vec = typename Dyn::Vector;
  static constexpr auto kPeriodic = Dyn::kPeriodic;

  Search(BasicFlow<R>& flow, const ProgressCallback& progress, int budget, int spent)
      : budget_(budget > 0 ? budget : flow.model().parameters().numerics.max_periods),
        spent_(spent),
        flow_(flow),
        model_(flow.model()),
        num_(flow.model().parameters().numerics),
        period_(flow.model().period()),
        base_(flow.t()),
        progress_(progress),
        dynamics_(flow.model(), flow.options().baumgarte) {}

  SearchOutcome run();

  bool on_step(const BasicStepView<R>& step) override {
    if (step.ends_step()) {
      const Vec x = step.state(step.t1()).to_array();
      for (int i : kPeriodic) {
        range_lo_[i] = std::min(range_lo_[i], x[i]);
        range_hi_[i] = std::max(range_hi_[i], x[i]);
      }
    }
    return true;
  }

  bool on_event(const Event& event, const State&, const State&) override {
    recent_.push_back(event);
    if (recent_.size() > kRecentEvents) recent_.pop_front();
    // A flight interrupts no slip: the contact phases on either side of it count instead (a drum
    // that spins through its flights, slip- -> flight -> slip- every period, ran 5000 periods to
    // "quasi-periodic: a torus", its phi' growing by 0.25 rad/s a period).
    if (event.kind == EventKind::lift_off)
      touch(event.from);
    else if (event.kind == EventKind::landing)
      touch(event.to);
    else if (event.kind != EventKind::contact_lost)
      ++switches_this_period_;
    return true;
  }

 private:
  void touch(Phase contact) {
    contact_phases_ |= 1 << (static_cast<int>(contact) + 1);
    last_contact_ = contact;
  }
  // A new period: no switch yet, and the contact phase it starts in (if in contact).
  void new_period() {
    switches_this_period_ = 0;
    contact_phases_ = 0;
    if (flow_.phase() != Phase::flight) touch(flow_.phase());
  }
  // Returns true when the search ends at boundary n.
  bool on_boundary(int n, const Vec& x);
  bool gross_slip(int n, const Vec& x);
  double noise_floor() const;

  const int budget_;  // periods this search may integrate
  const int spent_;   // periods shooting integrated before this fallback
  BasicFlow<R>& flow_;
  const Model& model_;
  const Numerics& num_;
  const double period_;
  const double base_;  // the flow's time at the start: a boundary, t = 0 from rest
  const ProgressCallback& progress_;
  const Dyn dynamics_;
  SearchOutcome out_;

  std::deque<std::pair<Vec, Phase>> history_;  // states at the last boundaries, newest first
  Vec range_lo_{}, range_hi_{}, last_range_{};
  // Each finished period's extremes of every component, newest first (as history_): the scale of
  // a p-period comparison is the range over the last p periods.
  std::deque<std::pair<Vec, Vec>> period_extremes_;
  std::array<int, 65> below_{};  // consecutive boundaries with change_p < steady_tol, per p
  std::deque<Event> recent_;
  long switches_this_period_ = 0;  // switches in contact (lift-offs and landings not)
  int contact_phases_ = 0;         // bit phase + 1: the contact phases of this period
  Phase last_contact_ = Phase::stick;
  int slipping_periods_ = 0;
  std::deque<double> changes_;  // the last 2 kStagnationPeriods period-to-period changes
};

// What the integration can resolve of the scaled period-to-period change: local errors of about
// rtol per step, and the rounding of the excitation's phase nu t, which grows with the simulated
// time t (eps nu t), both amplified by the sensitivity of the period map (the factors 10 and
// 1e3 are generous bounds for this model, measured on pure-rolling cases at 10-40 Hz).
template <class R>
double Search<R>::noise_floor() const {
  const double t = flow_.t();
  return 10.0 * num_.rtol + 1e3 * std::numeric_limits<double>::epsilon() * model_.nu() * t;
}

template <class R>
bool Search<R>::gross_slip(int n, const Vec& x) {
  // Slip of one sign s through whole periods cannot be periodic: phi' is periodic only if the
  // mean of (23), I phi'' = MM + s mu N r, vanishes, i.e. MMd = -s mu mean(N) r, which Coulomb
  // friction (its torque does not depend on the slip speed) meets only by coincidence. So once
  // the drum has slipped without a switch for kGrossSlipPeriods periods, in the direction its
  // driving torque pushes (-s MMd > 0), and phi' has grown in that direction in each of those
  // periods by more than the steady state's tolerance allows, it spins: the friction cannot hold
  // the driving torque on this motion. This reads the motion, not a threshold: mean(N) is below
  // W when the suspension carries part of the load, so a drum can spin with MMd below mu W r.
  // The roller says which slip that is (Dynamics<R>::pushed_slip) and how fast phi' grows
  // (spin_up, its component kSpin).
  double hold = 0.0;
  // In flight at the boundary: the slip it lifted off from (or landed in) is the period's.
  const Phase contact = flow_.phase() == Phase::flight ? last_contact_ : flow_.phase();
  const int s = dynamics_.pushed_slip(contact, x, &hold);
  const bool one_phase = (contact_phases_ & ~(1 << (static_cast<int>(contact) + 1))) == 0;
  if (s != 0 && switches_this_period_ == 0 && one_phase)
    ++slipping_periods_;
  else
    slipping_periods_ = 0;
  // A coefficient that grows with the slip speed (the regularised law, T = -mu tanh(v / v_eps) N)
  // holds a driving torque in steady creep: phi' approaches its creep rate, growing less in each
  // period (the paper's roller at MMd = 0.1 M0, v_eps = 1 m/s: a stable orbit, multiplier 0.88,
  // was called gross slip after 3 periods). There spin is growth that does not fade.
  const bool smooth = flow_.model().parameters().contact.law == FrictionChoice::regularised &&
                      !flow_.model().parameters().contact.pure_rolling;
  const int periods = smooth ? kGrossSlipPeriodsSmooth : kGrossSlipPeriods;
  if (slipping_periods_ < periods || static_cast<int>(history_.size()) <= periods) return false;
  // Growth in each of the periods, above what a steady state may still change by.
  const double noise = 10.0 * num_.steady_tol * last_range_[Dyn::kSpin];
  for (int k = 0; k < periods; ++k)
    if (!(Dyn::spin_up(history_[k].first, history_[k + 1].first, s, 1) > noise)) return false;
  if (smooth &&
      !(Dyn::spin_up(history_[0].first, history_[1].first, s, 1) >=
        kUnfadingGrowth * Dyn::spin_up(history_[periods - 1].first, history_[periods].first, s, 1)))
    return false;
  const double growth = Dyn::spin_up(x, history_[periods].first, s, periods);
  const double MMd = flow_.model().parameters().MMd;
  out_.status = Status::gross_slip;
  out_.phi_drift = Dyn::cyclic_drift(x, history_[1].first);
  out_.message = detail::format(
      "gross slip: the drum spins (phi' grows by %.3g rad/s per excitation period, slipping "
      "without stick for %.0f periods): the driving torque MMd = %.6g N m exceeds what friction "
      "holds on this motion, mu mean(N) r (mu W r = %.6g N m)",
      growth, slipping_periods_, MMd, hold);
  out_.message += detail::format("; no steady state (stopped after %.0f periods)", n + spent_);
  return true;
}

template <class R>
bool Search<R>::on_boundary(int n, const Vec& x) {
  out_.periods = n;
  // The scale of each compared component: its range over the last period, floored at a level
  // the integration tolerances can resolve (a component that hardly moves, like s_A around its
  // static value, must not demand more than the integrator delivers).
  period_extremes_.emplace_front(range_lo_, range_hi_);
  if (static_cast<int>(period_extremes_.size()) > num_.max_multiplicity)
    period_extremes_.pop_back();
  const auto scale_of = [this](double lo, double hi) {
    const double floor = 100.0 * (num_.atol + num_.rtol * std::max(std::abs(hi), std::abs(lo)));
    return std::max(hi - lo, floor);
  };
  for (int i : kPeriodic) {
    last_range_[i] = scale_of(range_lo_[i], range_hi_[i]);
    range_lo_[i] = range_hi_[i] = x[i];
  }

  history_.emplace_front(x, flow_.phase());
  // The comparisons need max_multiplicity periods back, the gross-slip test its own (with
  // max_multiplicity < 3 it never had enough: a drum that spun ran to max_periods).
  if (static_cast<int>(history_.size()) >
      std::max(num_.max_multiplicity, kGrossSlipPeriodsSmooth) + 1)
    history_.pop_back();

  // During a start ramp (numerics.start_ramp_periods) the excitation is not yet periodic: no
  // verdict on steadiness or gross slip, only the progress and the budget.
  if (flow_.t() < num_.start_ramp_periods * period_ - 0.5 * period_) {
    new_period();
    if (progress_ && !progress_(n, std::numeric_limits<double>::infinity())) {
      out_.status = Status::cancelled;
      out_.message = detail::format("cancelled after %.0f periods", n);
      return true;
    }
    if (n >= budget_) {
      out_.status = Status::max_periods_reached;
      out_.message = detail::format(
          "no steady state within %.0f periods: they did not reach the end of the start ramp "
          "(numerics.start_ramp_periods = %.0f)",
          n, num_.start_ramp_periods);
      return true;
    }
    return false;
  }

  // A p-periodic steady state must repeat at p consecutive boundaries (a whole cycle of the
  // subharmonic), and for p > 1 every shorter comparison must stay macroscopic (above
  // kSubharmonicGap): the slow, lightly damped pendulum mode of the drum in its trough can alias
  // to almost a whole number of cycles over p periods, making the p-period change of a decaying
  // transient smaller than the 1-period change although the motion tends to period 1.
  int found = 0;
  double change1 = std::numeric_limits<double>::infinity();
  double shorter_min = std::numeric_limits<double>::infinity();
  // The scale of the p-period comparison: each component's range over the last p periods (over
  // the last one only, a component that moves in one period of a p-cycle, as the gap of a
  // period-3 orbit that lifts off in one of its three periods, was scaled by the integration's
  // floor in the others: a change of 1e8 for an orbit repeating to 1e-9, never accepted).
  Vec lo = range_lo_, hi = range_hi_;  // (reset above: only x)
  for (int p = 1; p < static_cast<int>(history_.size()) && p <= num_.max_multiplicity; ++p) {
    const auto& [xp, phase_p] = history_[p];
    if (static_cast<std::size_t>(p) <= period_extremes_.size()) {
      const auto& [plo, phi] = period_extremes_[static_cast<std::size_t>(p - 1)];
      for (int i : kPeriodic) lo[i] = std::min(lo[i], plo[i]), hi[i] = std::max(hi[i], phi[i]);
    }
    double change = 0.0;
    for (int i : kPeriodic)
      change = std::max(change, std::abs(x[i] - xp[i]) / scale_of(lo[i], hi[i]));
    if (phase_p != history_.front().second) change = std::max(change, 1.0);
    if (p == 1) change1 = change;
    below_[p] = change < num_.steady_tol ? below_[p] + 1 : 0;
    if (found == 0 && below_[p] >= p && (p == 1 || shorter_min > kSubharmonicGap)) found = p;
    shorter_min = std::min(shorter_min, change);
  }
  out_.final_change = change1;
  const bool spinning = gross_slip(n, x);
  new_period();
  if (spinning) return true;
  if (progress_ && !progress_(n, change1)) {
    out_.status = Status::cancelled;
    out_.message = detail::format("cancelled after %.0f periods", n);
    return true;
  }

  // The noise floor: the change no longer decreases and is within what the integration
  // resolves. Accept period 1 there, and say so.
  bool at_floor = false;
  changes_.push_back(change1);
  if (changes_.size() > 2 * kStagnationPeriods) changes_.pop_front();
  if (found == 0 && changes_.size() == 2 * kStagnationPeriods && change1 < noise_floor()) {
    const auto mid = changes_.begin() + kStagnationPeriods;
    const double before = *std::min_element(changes_.begin(), mid);
    const double recent = *std::min_element(mid, changes_.end());
    if (recent > kStagnationRatio * before) {
      at_floor = true;
      found = 1;
    }
  }

  if (found > 0) {
    out_.status = Status::steady_state;
    out_.multiplicity = found;
    if (at_floor)
      out_.message = detail::format(
          "steady state after %.0f periods, at the noise floor of the integration: the "
          "period-to-period change stopped decreasing at %.3g, above numerics.steady_tol but "
          "within what numerics.rtol = %.3g resolves (tighten rtol for a smaller change)",
          n, change1, num_.rtol);
    else
      out_.message =
          detail::format(found == 1 ? "steady state after %.0f periods"
                                    : "steady state after %.0f periods, repeating every %.0f "
                                      "excitation periods",
                         n, found);
    return true;
  }
  if (n >= budget_) {
    out_.status = Status::max_periods_reached;
    out_.message = detail::format(
        "no steady state within %.0f periods (last period-to-period change %.3g); the last "
        "periods are sampled for inspection, with no metrics",
        n, change1);
    if (spent_ > 0)
      out_.message += detail::format(
          " (numerics.max_periods = %.0f counts the %.0f periods shooting integrated before it "
          "fell back)",
          num_.max_periods, spent_);
    return true;
  }
  return false;
}

template <class R>
SearchOutcome Search<R>::run() {
  const Vec x0 = flow_.state().to_array();
  range_lo_ = range_hi_ = x0;
  history_.emplace_front(x0, flow_.phase());
  for (int n = 1;; ++n) {
    const FlowStop stop = flow_.advance(base_ + n * period_, this);
    if (stop != FlowStop::reached) {
      out_.status = status_of(stop);
      out_.message = flow_.message();
      out_.recent_events.assign(recent_.begin(), recent_.end());
      return out_;
    }
    if (on_boundary(n, flow_.state().to_array())) {
      if (out_.status != Status::steady_state && out_.status != Status::max_periods_reached)
        out_.recent_events.assign(recent_.begin(), recent_.end());
      return out_;
    }
  }
}

}  // namespace steady

/// Run the search on `flow` (reset by the caller at t = 0, or standing at a later period boundary:
/// the periods are counted from there). `progress` is called once per period.
/// It gives up after `budget` periods (0: numerics.max_periods); `spent` > 0 periods were already
/// integrated by shooting before it fell back, and the message says so.
template <class R>
SearchOutcome find_steady_state(BasicFlow<R>& flow, const ProgressCallback& progress,
                                int budget = 0, int spent = 0) {
  steady::Search<R> search(flow, progress, budget, spent);
  return search.run();
}

}  // namespace oscidrum::detail
