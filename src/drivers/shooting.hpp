// Internal: the periodic steady state by shooting, a driver on the flow of any roller type R
// (docs/periodic.md). Newton's method on the period map P over one excitation period, P(z) = z,
// on the reduced state z of the roller's periodic components (Dynamics<R>::kPeriodic; for the
// oscillation drum (delta, x_A, s_A, delta', x_A', s_A', phi'): phi is cyclic, no right-hand
// side depends on it), with the monodromy matrix from the variational equations
// (src/flow/monodromy.hpp).
#pragma once

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "drivers/sampling.hpp"
#include "flow/monodromy.hpp"
#include "oscidrum/floquet.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail {

template <class R>
struct BasicShootingOutcome {
  using State = typename R::State;
  /// True: a periodic orbit was found; the flow stands at its section t0 (a period boundary)
  /// on the orbit, ready for sampling.
  bool converged = false;
  /// Set when the short transient itself ended (contact lost, chattering, cancelled, ...): the
  /// transient method would meet the same end, so it is the run's status (no fallback).
  bool terminal = false;
  Status status = Status::steady_state;
  std::string message;        ///< why it converged or failed
  int transient_periods = 0;  ///< plain periods integrated from the start before Newton
  /// Excitation periods integrated in all (short transient, period maps of P^p counted p times,
  /// the search for a subharmonic orbit), the share of numerics.max_periods shooting spent.
  int periods_integrated = 0;
  /// The run stopped because the next integration would exceed its budget of periods
  /// (ShootingStart::budget, numerics.max_periods): no fallback has periods left either.
  bool budget_exhausted = false;
  /// Excitation periods per period of the orbit: 1, or p when the period-1 orbit is unstable and
  /// a stable orbit of P^p was found instead (or when ShootingStart::multiplicity asked for it).
  int multiplicity = 1;
  int newton_iterations = 0;  ///< Newton steps taken (each one period with sensitivities)
  int period_maps = 0;        ///< period maps evaluated with sensitivities (incl. trials)
  int plain_maps = 0;         ///< period maps evaluated without them (chord steps)
  /// scaled |P(z) - z| at the last evaluated iterate [-]; NaN before the first
  double final_change = std::numeric_limits<double>::quiet_NaN();
  /// The last Newton step was taken without evaluating the period map at its result (its
  /// predicted residual was far below the threshold); the caller's plain integration of the
  /// sampled periods from the orbit confirms it.
  bool predicted_last_step = false;
  /// The predicted step was a warm start's first (a chord step with the monodromy of its first
  /// map, taken without a map at its result): the caller confirms it on the sampled period, and
  /// when that period's residual is not yet small, takes further chord steps with `M`
  /// (shooting::newton_step), each confirmed on the next sampled period.
  bool warm_prediction = false;
  /// The monodromy of the reduced state the last step was taken with (Newton's M).
  Eigen::Matrix<double, static_cast<int>(Dynamics<R>::kPeriodic.size()),
                static_cast<int>(Dynamics<R>::kPeriodic.size())>
      M;
  double phi_drift = 0.0;  ///< drift of the cyclic coordinate (phi) per period on the orbit [rad]
  long jacobian_evaluations = 0;  ///< evaluations of the phase Jacobians
  Floquet floquet;                ///< the multipliers of P^p at the orbit (p = multiplicity)
  /// The multipliers of the unstable period-1 orbit when a P^p orbit (p > 1) replaced it.
  Floquet period1_floquet;
  std::array<double, R::kStates> scale{};  ///< scale of each component (its range over a period)
  double t0 = 0.0;                         ///< the section [s]
  State orbit;                             ///< the orbit's state at t0
  /// Largest |(39)| / W and smallest N [N] at the step ends of the short transient from rest (a
  /// trajectory of the run; Newton's iterates are not): Diagnostics::max_slip_residual, min_N.
  double transient_max_slip_residual = 0.0;
  double transient_min_N = std::numeric_limits<double>::infinity();
  Phase phase = Phase::stick;
  std::vector<Event> recent_events;  ///< for a terminal end: the events before it
};

/// Where shooting starts: from `flow`'s current state after a short transient (the default), or
/// directly from a supplied state (a neighbouring case's orbit).
template <class R>
struct BasicShootingStart {
  using State = typename R::State;
  bool from_state = false;
  State state;
  Phase phase = Phase::stick;
  /// Excitation periods this run may integrate (0: numerics.max_periods).
  int budget = 0;
  /// Solve P^p(z) = z for this p directly, without the period-1 orbit first, and accept a
  /// period-1 orbit as its solution (tests: P^2 of a stable period-1 orbit is that orbit).
  int multiplicity = 1;
  /// A supplied state's first Newton step is taken without a map at its result, to be confirmed
  /// by the caller (BasicShootingOutcome::warm_prediction). False: Newton maps every step.
  bool predict_first = true;
  /// The contraction of the residual by the first chord step of the neighbour this start comes
  /// from (WarmStart::contraction; negative: unknown).
  double contraction = -1.0;
  /// A supplied state that spends the budget without a steady state ends the attempt, not the
  /// run (WarmStart::cold_start_budget): the caller's cold start follows.
  bool yields_budget = false;
};

using ShootingOutcome = BasicShootingOutcome<OscillationDrum>;
using ShootingStart = BasicShootingStart<OscillationDrum>;

/// Scaled distance between two states at a period boundary, as the transient search measures
/// the period-to-period change: the largest over the roller's periodic components (for the
/// oscillation drum all but phi) of the difference over the scale of that component.
template <class R>
double scaled_change(const typename R::State& a, const typename R::State& b,
                     const std::array<double, R::kStates>& scale) {
  const auto x = a.to_array(), y = b.to_array();
  double change = 0.0;
  for (int i : Dynamics<R>::kPeriodic) change = std::max(change, std::abs(x[i] - y[i]) / scale[i]);
  return change;
}

namespace shooting {

// Short transient: at least kMinTransient periods, until the switching sequence of a period
// repeats in the next one; at most kMaxTransient.
inline constexpr int kMinTransient = 2;
inline constexpr int kMaxTransient = 24;
// Transient periods integrated as period maps with sensitivities, at most (see short_transient).
inline constexpr int kMaxTransientMaps = 2;
// Extensions of the short transient when Newton's first map changes phase (see run()), at most.
inline constexpr int kMaxExtensions = 3;
// When Newton fails from the short transient: the transient goes on plainly for this many
// periods from where Newton started, and Newton tries once more (see run()).
inline constexpr int kRetryTransient = 20;

// Newton: at most kMaxNewton steps; each halves its step up to kMaxHalvings times until the
// scaled residual decreases; more than kMaxSequenceChanges changes of the switching sequence
// between accepted iterates mean the linearisation does not hold (fall back).
inline constexpr int kMaxNewton = 12;
inline constexpr int kMaxHalvings = 4;
inline constexpr int kMaxSequenceChanges = 3;

// Converged when the scaled residual is below kNewtonTol times the steady-state tolerance (the
// orbit is then closer to periodic than any state the transient accepts), or below the
// steady-state tolerance and no longer decreasing by half (the integration's noise floor).
inline constexpr double kNewtonTol = 1e-2;

// Below this scaled residual, Newton steps reuse the last monodromy matrix (chord steps).
inline constexpr double kFreshMonodromy = 1e-3;

// A warm start (from a neighbouring case's orbit, continuation) is close to its orbit: after its
// first map, with the variational equations, every Newton step is a chord step with that
// monodromy, on a plain map, while each contracts the residual by at least this factor (about
// 1e-6 per step on the performance issue's sweep). A step that does not gets a fresh monodromy
// at the better iterate, and Newton goes on as from a cold start. The warm case integrates the
// variational equations once, and its Floquet multipliers come from that monodromy, as a cold
// start's come from its last fresh one (at an iterate whose residual was above kFreshMonodromy).
// A map with the variational equations costs two to 2.5 plain ones in CPU time: with 0.1 instead,
// the Table 2 sweep's large steps in G took up to 7 slow chord steps and ran about 15 % slower
// than with fresh monodromies (bench/README.md).
inline constexpr double kChordContraction = 1e-2;

// The last step is taken without evaluating the period map at its result when the previous full
// step contracted the residual by at least kPredictContraction and the same contraction predicts
// a residual below kPredictMargin times the convergence threshold: the plain integration of the
// sampled periods that follows confirms it (or the run falls back).
inline constexpr double kPredictContraction = 1e-2;
inline constexpr double kPredictMargin = 0.1;

// Subharmonic orbits (the period-1 orbit is unstable): the orbit is displaced along the
// eigenvector of the critical multiplier by kKick of each component's range, then followed for at
// most kSubharmonicTransient plain periods; Newton on P^p starts there for the (at most
// kSubharmonicTries) p = 2 ... max_multiplicity whose p-period change is smallest. An orbit of
// P^p is accepted only when it is not one of P^d, d < p dividing p: the change over d periods
// stays above kSubharmonicGap (as in the transient search) and above what the integration
// resolves (Shooter::distinct).
inline constexpr double kKick = 1e-2;
inline constexpr int kSubharmonicTransient = 32;
inline constexpr int kSubharmonicTries = 3;
inline constexpr double kSubharmonicGap = 1e-4;
// Past a period doubling, Newton on P^2 starts from the period-1 orbit displaced along the
// eigenvector by these multiples of the components' ranges (both sides), before the search above.
inline constexpr std::array<double, 6> kFlipKicks = {0.03, -0.03, 0.1, -0.1, 0.3, -0.3};

// The multipliers of a monodromy taken at an iterate at scaled residual r differ from those at
// the orbit by up to about 0.04 r (the warm and cold starts of the product sweep and of a
// diagram near a Neimark-Sacker point: at most 1.3 r where r is tiny); a largest modulus within
// kMultiplierDrift r of 1 (at most kMultiplierMargin) is taken again at the orbit.
inline constexpr double kMultiplierDrift = 2.0;
inline constexpr double kMultiplierMargin = 0.05;

inline std::string fmt(const char* format, double a = 0.0, double b = 0.0, double c = 0.0) {
  char buf[512];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

template <int P>
Floquet multipliers_of(const Eigen::Matrix<double, P, P>& M) {
  const Eigen::EigenSolver<Eigen::Matrix<double, P, P>> eig(M, false);
  std::vector<std::complex<double>> mult(P);
  for (int i = 0; i < P; ++i) mult[i] = eig.eigenvalues()[i];
  return classify_multipliers(std::move(mult));
}

// Records the switches and the range of each component over a plain period.
template <class R>
class PlainObserver : public BasicFlowObserver<R> {
 public:
  using State = typename R::State;
  using Dyn = Dynamics<R>;
  using Vec = typename Dyn::Vector;
  static constexpr int P = static_cast<int>(Dyn::kPeriodic.size());
  using Mat7 = Eigen::Matrix<double, P, P>;
  using Vec7 = Eigen::Matrix<double, P, 1>;
  static constexpr auto kPeriodic = Dyn::kPeriodic;
  bool on_step(const BasicStepView<R>& step) override {
    if (step.ends_step()) include(step.state(step.t1()).to_array());
    return true;
  }
  bool on_event(const Event& event, const State&, const State&) override {
    if (event.kind != EventKind::contact_lost) switches.push_back(event);
    recent.push_back(event);
    if (recent.size() > 64) recent.erase(recent.begin());
    return true;
  }
  void start(const Vec& x) {
    lo = hi = x;
    switches.clear();
  }
  void include(const Vec& x) {
    for (int i = 0; i < Dyn::kStates; ++i) {
      lo[i] = std::min(lo[i], x[i]);
      hi[i] = std::max(hi[i], x[i]);
    }
  }
  Vec lo{}, hi{};
  std::vector<Event> switches, recent;
};

// Two observers of one flow.
template <class R>
using Tee = ObserverPair<R>;

template <class R>
struct PeriodMap {
  using State = typename R::State;
  using Dyn = Dynamics<R>;
  using Vec = typename Dyn::Vector;
  static constexpr int P = static_cast<int>(Dyn::kPeriodic.size());
  using Mat7 = Eigen::Matrix<double, P, P>;
  using Vec7 = Eigen::Matrix<double, P, 1>;
  static constexpr auto kPeriodic = Dyn::kPeriodic;
  FlowStop stop = FlowStop::reached;
  State end;
  Phase phase = Phase::stick;
  Mat7 M = Mat7::Zero();
  std::vector<Event> switches;
  bool grazing = false;
  bool has_monodromy = false;  // M was computed at this state (else: carried over)
  bool over_budget = false;    // not integrated: it would exceed the budget of periods
  double residual = std::numeric_limits<double>::infinity();  // scaled |P(z) - z|
  // The scaled residual of the iterate M was computed at (carried over with M): how far from
  // the orbit its multipliers were taken (see kMultiplierDrift).
  double monodromy_residual = std::numeric_limits<double>::infinity();
};

// Newton's step on the reduced state: (M - I) dz = -(end - z), with end = P^p(z), solved in
// units of each component's scale. A multiplier at 1 (a neutral direction: phi' of the
// frictionless drum, whose mean any constant shifts) makes the matrix singular; the minimum-norm
// step leaves that direction where it is.
template <class R>
struct NewtonStep {
  static constexpr int P = static_cast<int>(Dynamics<R>::kPeriodic.size());
  Eigen::Matrix<double, P, 1> dz, s;  // the step in scaled units, and the scales
  bool finite() const { return dz.allFinite(); }
  // z + lambda dz, projected onto the phase's constraints (Dynamics::consistent: in stick
  // phi' = f5 delta' (12); a Newton update must not break them).
  typename R::State apply(const Dynamics<R>& dynamics, const typename R::State& z, Phase phase,
                          double lambda = 1.0) const {
    auto y = z.to_array();
    for (int i = 0; i < P; ++i) y[Dynamics<R>::kPeriodic[i]] += lambda * dz[i] * s[i];
    return R::State::from_array(dynamics.consistent(y, phase));
  }
};

template <class R>
NewtonStep<R> newton_step(const Eigen::Matrix<double, NewtonStep<R>::P, NewtonStep<R>::P>& M,
                          const std::array<double, R::kStates>& scale, const typename R::State& z,
                          const typename R::State& end) {
  constexpr int P = NewtonStep<R>::P;
  using Mat = Eigen::Matrix<double, P, P>;
  NewtonStep<R> step;
  Eigen::Matrix<double, P, 1> F;
  const auto e = end.to_array(), x = z.to_array();
  for (int i = 0; i < P; ++i) {
    const int c = Dynamics<R>::kPeriodic[i];
    step.s[i] = scale[c];
    F[i] = (e[c] - x[c]) / step.s[i];
  }
  const Mat A = step.s.asDiagonal().inverse() * (M - Mat::Identity()) * step.s.asDiagonal();
  const Eigen::CompleteOrthogonalDecomposition<Mat> cod(A);
  step.dz = cod.solve(-F);
  return step;
}

template <class R>
class Shooter {
 public:
  using State = typename R::State;
  using Dyn = Dynamics<R>;
  using Vec = typename Dyn::Vector;
  static constexpr int P = static_cast<int>(Dyn::kPeriodic.size());
  using Mat7 = Eigen::Matrix<double, P, P>;
  using Vec7 = Eigen::Matrix<double, P, 1>;
  static constexpr auto kPeriodic = Dyn::kPeriodic;
  using Flow = BasicFlow<R>;
  using ShootingOutcome = BasicShootingOutcome<R>;
  using ShootingStart = BasicShootingStart<R>;
  using PeriodMap = shooting::PeriodMap<R>;
  using PlainObserver = shooting::PlainObserver<R>;
  using Tee = shooting::Tee<R>;

  Shooter(Flow& flow, const ProgressCallback& progress)
      : flow_(flow),
        model_(flow.model()),
        num_(flow.model().parameters().numerics),
        period_(flow.model().period()),
        progress_(progress),
        dynamics_(flow.model(), flow.options().baumgarte),
        mono_(flow.model(), flow.options().baumgarte,
              flow.model().period() / kMonodromyStepsPerPeriod) {}

  ShootingOutcome run(const ShootingStart& start);

 private:
  bool short_transient(ShootingOutcome& out);
  // The short transient from the flow's state; on success z and phase (at the section t0_) are
  // Newton's start, and first_ its first map when have_first_. False: `out` says why.
  bool transient_start(ShootingOutcome& out, State& z, Phase& phase);
  bool newton(State& z, Phase phase, PeriodMap& cur, ShootingOutcome& out);
  bool subharmonic(const State& orbit, Phase phase, const Mat7& M, State& z, PeriodMap& cur,
                   ShootingOutcome& out);
  bool try_orbit(State& w, Phase wphase, PeriodMap& map, ShootingOutcome& out);
  bool begin(const ShootingStart& start, ShootingOutcome& out, State& z, Phase& phase,
             PeriodMap& cur);
  bool extend_while_the_phase_changes(const ShootingStart& start, ShootingOutcome& out, State& z,
                                      Phase& phase, PeriodMap& cur);
  std::optional<bool> retry_after_a_longer_transient(const ShootingStart& start,
                                                     ShootingOutcome& out, const State& z_start,
                                                     Phase phase_start, double t_start, State& z,
                                                     Phase& phase, PeriodMap& cur);
  bool stable_orbit(ShootingOutcome& out, State& z, Phase phase, PeriodMap& cur);
  // Count k periods against the budget; false (and nothing counted) when they would exceed it.
  bool spend(int k) {
    if (used_ + k > budget_) {
      budget_hit_ = true;
      return false;
    }
    used_ += k;
    return true;
  }
  std::string budget_message() const {
    return fmt("shooting reached numerics.max_periods: %.0f periods integrated of the %.0f it had",
               used_, budget_);
  }
  // `range` (optional, with sensitivities): the scales are set from the components' ranges
  // along the map before its residual is taken.
  PeriodMap period_map(const State& z, Phase phase, bool sensitivities,
                       PlainObserver* range = nullptr);
  void set_scales(const PlainObserver& range);
  // What the integration resolves of a component of this magnitude: the floor of its scale.
  double resolved(double magnitude) const { return 100.0 * (num_.atol + num_.rtol * magnitude); }
  // True when a and b differ by more than kSubharmonicGap of some component's scale, and by more
  // than the integration resolves of it.
  bool distinct(const State& a, const State& b) const;
  State consistent(State z, Phase phase) const;

  Flow& flow_;
  const Model& model_;
  const Numerics& num_;
  const double period_;
  const ProgressCallback& progress_;
  // The last period reported: a Newton step's count starts from the transient's periods, of
  // which the last, integrated as the first map, was reported already (the caller saw 1, 2, 3, 3).
  int reported_ = 0;
  bool report(int period, double change) {
    reported_ = std::max(period, reported_ + 1);
    return progress_(reported_, change);
  }
  const Dyn dynamics_;
  MonodromyObserver<R> mono_;
  // The last period of the short transient, integrated as the period map of its start.
  bool have_first_ = false;
  PeriodMap first_;
  State first_z_;
  Phase first_phase_ = Phase::stick;
  double t0_ = 0.0;
  Phase phase_ = Phase::stick;  // the phase at the section of the orbit
  std::array<double, Dyn::kStates> scale_{};
  int maps_ = 0, plain_maps_ = 0;
  int p_ = 1;  // periods of the map: P^p
  // Newton's steps are chord steps with the first map's monodromy (kChordContraction).
  bool chord_ = false;
  bool predict_first_ = true;  // ShootingStart::predict_first
  int budget_ = 0, used_ = 0;
  bool budget_hit_ = false;
};

template <class R>
typename R::State Shooter<R>::consistent(State z, Phase phase) const {
  // The roller's projection onto the phase's constraints (in stick phi' = f5 delta' (12)): a
  // Newton update must not break them.
  return State::from_array(dynamics_.consistent(z.to_array(), phase));
}

template <class R>
bool Shooter<R>::short_transient(ShootingOutcome& out) {
  PlainObserver obs;
  std::vector<Event> previous;
  bool have_previous = false;
  int map_periods = 0;
  // Periods are counted from where the flow is (rest at t = 0, or the end of a first map that
  // changed phase, see run()).
  const double base = flow_.t();
  const int before = out.transient_periods;
  // A start ramp (numerics.start_ramp_periods) is no period of the periodic system: the
  // transient runs through it first.
  const int ramp =
      std::max(0, num_.start_ramp_periods - static_cast<int>(std::lround(base / period_)));
  const int min_periods = kMinTransient + ramp;
  for (int n = 1; n <= kMaxTransient + ramp; ++n) {
    // A period that may be the last one (the third, or the second after a period without
    // switches, as in pure rolling) is integrated as the period map of its consistent start,
    // with sensitivities: if its switching sequence repeats, it is Newton's first map.
    // Only up to kMaxTransientMaps such periods: a transient that takes longer to settle goes on
    // plainly, and Newton's first map follows it.
    const bool as_map = map_periods < kMaxTransientMaps &&
                        (n >= min_periods + 1 || (n >= min_periods && previous.empty()));
    if (!spend(1)) {
      out.budget_exhausted = true;
      out.message = budget_message();
      return false;
    }
    if (as_map) ++map_periods;
    FlowStop stop;
    std::vector<Event> switches;
    if (as_map) {
      t0_ = flow_.t();
      const Phase phase = flow_.phase();
      const State z = consistent(flow_.state(), phase);
      used_ -= 1;  // counted by period_map
      first_ = period_map(z, phase, true);
      first_z_ = z;
      first_phase_ = phase;
      stop = first_.stop;
      switches = first_.switches;
    } else {
      obs.start(flow_.state().to_array());
      stop = flow_.advance(base + n * period_, &obs);
      switches = obs.switches;
    }
    if (stop != FlowStop::reached) {
      out.terminal = true;
      out.recent_events = as_map ? first_.switches : obs.recent;
      out.status = status_of(stop);
      out.message = flow_.message();
      return false;
    }
    out.transient_periods = before + n - map_periods;  // the maps are counted as such
    // A period integrated as a map keeps the scale of the period before.
    if (!as_map) set_scales(obs);
    if (progress_ && !report(before + n, std::numeric_limits<double>::infinity())) {
      out.terminal = true;
      out.status = Status::cancelled;
      out.message = fmt("cancelled after %.0f periods", n);
      return false;
    }
    const bool same = have_previous && same_switching_sequence(previous, switches);
    if (n >= min_periods && same) {
      have_first_ = as_map;
      break;
    }
    previous = switches;
    have_previous = true;
  }
  return true;
}

template <class R>
void Shooter<R>::set_scales(const PlainObserver& range) {
  // The scale of each component: its range over the period, floored at what the integration
  // tolerances resolve (as in the transient search).
  for (int i = 0; i < Dyn::kStates; ++i) {
    const double width = range.hi[i] - range.lo[i];
    scale_[i] = std::max(width, resolved(std::max(std::abs(range.hi[i]), std::abs(range.lo[i]))));
  }
}

template <class R>
bool Shooter<R>::distinct(const State& a, const State& b) const {
  // A difference below what the integration resolves does not count, however small the
  // component's range: the drum's rotation rate in flight on a period-2 orbit of the vibratory
  // drum (range 1.7e-7 rad/s about 0.09 rad/s) changed by 1.8e-11 over two periods, 1.07e-4 of
  // its range, and the orbit was accepted as one of P^4.
  const auto x = a.to_array(), y = b.to_array();
  for (int i : Dyn::kPeriodic) {
    const double floor = resolved(std::max(std::abs(x[i]), std::abs(y[i])));
    if (std::abs(x[i] - y[i]) > std::max(kSubharmonicGap * scale_[i], floor)) return true;
  }
  return false;
}

template <class R>
bool Shooter<R>::transient_start(ShootingOutcome& out, State& z, Phase& phase) {
  const bool ok = short_transient(out);
  // The short transient from rest is a trajectory of the run (the transient method integrates
  // it too); what Newton integrates next is not.
  out.transient_max_slip_residual = flow_.counters().max_slip_residual;
  out.transient_min_N = flow_.counters().min_N;
  if (!ok) {
    out.periods_integrated = used_;
    out.period_maps = maps_;
    out.jacobian_evaluations = mono_.jacobian_evaluations();
    return false;
  }
  if (have_first_) {  // t0_ is its start
    z = first_z_;
    phase = first_phase_;
  } else {
    t0_ = flow_.t();
    z = flow_.state();
    phase = flow_.phase();
  }
  return true;
}

template <class R>
PeriodMap<R> Shooter<R>::period_map(const State& z, Phase phase, bool sensitivities,
                                    PlainObserver* range) {
  PeriodMap p;
  if (!spend(p_)) {
    p.over_budget = true;
    p.stop = FlowStop::observer;
    return p;
  }
  flow_.reset(t0_, z, phase);
  const double t_end = t0_ + p_ * period_;
  if (sensitivities) {
    ++maps_;
    mono_.reset();
    if (range != nullptr) {
      Tee both(mono_, *range);
      p.stop = flow_.advance(t_end, &both);
    } else {
      p.stop = flow_.advance(t_end, &mono_);
    }
    p.switches = mono_.switches();
    p.grazing = mono_.grazing();
  } else {
    ++plain_maps_;
    PlainObserver obs;
    p.stop = flow_.advance(t_end, &obs);
    p.switches = obs.switches;
  }
  if (p.stop != FlowStop::reached) return p;
  if (range != nullptr) set_scales(*range);
  p.end = flow_.state();
  p.phase = flow_.phase();
  p.residual = p.phase == phase ? scaled_change<R>(p.end, z, scale_)
                                : std::numeric_limits<double>::infinity();
  if (!sensitivities) return p;
  // Over p periods the variational equations run on through the section boundaries, so Phi is
  // the product of the p period monodromies with every saltation between.
  // The map Newton sees is P(consistent(z)): at a stick section phi' is set to f5 delta' (12)
  // before the period starts (the flow's stick phase integrates phi' without ever reading it, so
  // without the projection its offset would be a neutral direction, a multiplier 1).
  const auto G = dynamics_.section_jacobian(z.to_array(), phase);
  const typename Dyn::Matrix phi = G ? typename Dyn::Matrix(mono_.phi() * *G) : mono_.phi();
  for (int i = 0; i < P; ++i)
    for (int j = 0; j < P; ++j) p.M(i, j) = phi(kPeriodic[i], kPeriodic[j]);
  p.has_monodromy = true;
  p.monodromy_residual = p.residual;
  return p;
}

// Newton on P^p(z) = z from z, whose map is cur; on success z is the orbit and cur its map.
template <class R>
bool Shooter<R>::newton(State& z, Phase phase, PeriodMap& cur, ShootingOutcome& out) {
  int sequence_changes = 0;
  bool converged = false;
  // Contraction of the residual by the last accepted full step (1: none yet).
  double contraction = 1.0;
  for (int k = 0; k <= kMaxNewton; ++k) {
    if (cur.over_budget) {
      out.message = budget_message();
      break;
    }
    if (cur.stop != FlowStop::reached || cur.grazing || !std::isfinite(cur.residual)) {
      out.message = cur.stop != FlowStop::reached
                        ? "the period map failed at a Newton iterate: " + flow_.message()
                        : (cur.grazing ? "a switch grazes the switching surface"
                                       : "the phase at the section changed over a period");
      break;
    }
    if (cur.residual < kNewtonTol * num_.steady_tol) {
      converged = true;
      break;
    }
    if (k == kMaxNewton) {
      out.message =
          fmt("Newton did not converge in %.0f steps (scaled residual %.3g)", k, cur.residual);
      break;
    }
    if (progress_ && !report(out.transient_periods + out.newton_iterations + 1, cur.residual)) {
      out.terminal = true;
      out.status = Status::cancelled;
      out.message = "cancelled during the Newton iteration";
      return false;
    }
    // (M - I) dz = -(P^p(z) - z) on the reduced state, in scaled units.
    const NewtonStep<R> step = newton_step<R>(cur.M, scale_, z, cur.end);
    if (!step.finite()) {
      out.message = "Newton's matrix M - I is singular";
      break;
    }
    // A warm start's first step (a chord step with the monodromy of its first map; on the
    // performance issue's sweep it contracts the residual by about 1e-7) is taken without a map
    // at its result: the sampled period that follows is that map, and confirms it (the caller
    // takes further chord steps while it does not; warm_prediction).
    const bool warm_first = chord_ && k == 0 && predict_first_;
    if (warm_first ||
        (contraction < kPredictContraction &&
         contraction * cur.residual < kPredictMargin * kNewtonTol * num_.steady_tol)) {
      out.M = cur.M;
      z = step.apply(dynamics_, z, phase);
      ++out.newton_iterations;
      out.predicted_last_step = true;
      out.warm_prediction = warm_first;
      converged = true;
      break;
    }
    if (chord_) {
      // A chord step of a warm start (kChordContraction), with the full step only.
      const State trial = step.apply(dynamics_, z, phase);
      PeriodMap next = period_map(trial, phase, false);
      if (next.over_budget) {
        out.message = budget_message();
        break;
      }
      const bool decreased = next.stop == FlowStop::reached && std::isfinite(next.residual) &&
                             next.residual < cur.residual;
      if (decreased) {
        if (!same_switching_sequence(next.switches, cur.switches)) ++sequence_changes;
        contraction = next.residual / cur.residual;
        z = trial;
        ++out.newton_iterations;
      }
      if (decreased && contraction < kChordContraction) {
        next.M = cur.M;
        next.monodromy_residual = cur.monodromy_residual;
        cur = std::move(next);
      } else {
        // A fresh monodromy at the better iterate (unless M is already its own), and Newton
        // goes on from there with its halvings.
        chord_ = false;
        contraction = 1.0;
        if (decreased || !cur.has_monodromy) cur = period_map(z, phase, true);
      }
      if (sequence_changes > kMaxSequenceChanges) {
        out.message = "the switching sequence changed between Newton iterates";
        break;
      }
      continue;
    }
    bool accepted = false;
    double lambda = 1.0;
    for (int h = 0; h <= kMaxHalvings; ++h, lambda *= 0.5) {
      const State trial = step.apply(dynamics_, z, phase, lambda);
      // Close to the orbit (residual below kFreshMonodromy) the step is small and the monodromy
      // hardly changes: the trial is integrated without sensitivities and keeps the current M.
      PeriodMap next = period_map(trial, phase, cur.residual > kFreshMonodromy);
      if (next.over_budget) break;
      if (next.stop != FlowStop::reached || !std::isfinite(next.residual)) continue;
      if (!next.has_monodromy) {
        next.M = cur.M;
        next.monodromy_residual = cur.monodromy_residual;
      }
      // Accept a decrease; near the noise floor (below the steady tolerance) a full step that
      // does not halve the residual ends the iteration as converged.
      if (next.residual < (1.0 - 0.1 * lambda) * cur.residual) {
        if (!same_switching_sequence(next.switches, cur.switches)) ++sequence_changes;
        const bool stalled =
            lambda == 1.0 && cur.residual < num_.steady_tol && next.residual > 0.5 * cur.residual;
        contraction = lambda == 1.0 ? next.residual / cur.residual : 1.0;
        z = trial;
        cur = std::move(next);
        accepted = true;
        ++out.newton_iterations;
        if (stalled) converged = true;
        break;
      }
      if (cur.residual < num_.steady_tol) break;  // already steady: halving will not help
    }
    if (converged) break;
    if (!accepted) {
      if (cur.residual < num_.steady_tol) {
        converged = true;  // at the integration's noise floor
        break;
      }
      out.message = budget_hit_ ? budget_message()
                                : fmt("Newton's step did not reduce the residual (scaled %.3g)",
                                      cur.residual);
      break;
    }
    if (sequence_changes > kMaxSequenceChanges) {
      out.message = "the switching sequence changed between Newton iterates";
      break;
    }
  }
  chord_ = false;
  out.final_change = cur.residual;
  return converged;
}

// Newton on P^p_ from w (its map `map`); true when it converges to a stable orbit of P^p that is
// not one of P^d for a d < p dividing p (the change over d periods stays above kSubharmonicGap and
// above what the integration resolves: distinct).
template <class R>
bool Shooter<R>::try_orbit(State& w, Phase wphase, PeriodMap& map, ShootingOutcome& out) {
  const int p = p_;
  ShootingOutcome trial;
  trial.transient_periods = out.transient_periods;
  const bool converged = newton(w, wphase, map, trial);
  out.newton_iterations += trial.newton_iterations;
  if (!converged) {
    if (trial.terminal || budget_hit_) {
      out.terminal = trial.terminal;
      out.status = trial.status;
      out.message = trial.message;
    }
    return false;
  }
  if (multipliers_of(map.M).stability != Stability::stable) return false;
  if (!spend(p)) {
    out.message = budget_message();
    return false;
  }
  flow_.reset(t0_, w, wphase);
  for (int d = 1; d < p; ++d) {
    if (flow_.advance(t0_ + d * period_) != FlowStop::reached) return false;
    if (p % d == 0 && flow_.phase() == wphase && !distinct(flow_.state(), w)) return false;
  }
  out.final_change = trial.final_change;
  out.predicted_last_step = trial.predicted_last_step;
  return true;
}

// The period-1 orbit `orbit` (monodromy M) is unstable: look for a stable orbit of P^p,
// p = 2 ... max_multiplicity (docs/periodic.md, "Subharmonic orbits"). On success, t0_ and p_ are
// the new orbit's section and multiplicity, z its state and cur its map.
template <class R>
bool Shooter<R>::subharmonic(const State& orbit, Phase phase, const Mat7& M, State& z,
                             PeriodMap& cur, ShootingOutcome& out) {
  const int max_p = num_.max_multiplicity;
  if (max_p < 2) return false;
  // The eigenvector of the critical (largest) multiplier, in units of each component's range.
  const Eigen::EigenSolver<Mat7> eig(M, true);
  int lead = 0;
  for (int i = 1; i < P; ++i)
    if (std::abs(eig.eigenvalues()[i]) > std::abs(eig.eigenvalues()[lead])) lead = i;
  Vec7 v = eig.eigenvectors().col(lead).real();
  double amplitude = 0.0;
  for (int i = 0; i < P; ++i)
    amplitude = std::max(amplitude, std::abs(v[i]) / scale_[kPeriodic[i]]);
  if (!(amplitude > 0.0)) return false;
  v /= amplitude;
  const double t_orbit = t0_;
  // Newton on P^p from `start` at the section t0: 1 found (z, cur and phase_ set), -1 give up
  // (terminal or out of budget), 0 try the next start.
  const auto attempt = [&](int p, double t0, const State& start, Phase start_phase) {
    p_ = p;
    t0_ = t0;
    State w = consistent(start, start_phase);
    PeriodMap map = period_map(w, start_phase, true);
    if (try_orbit(w, start_phase, map, out)) {
      z = w;
      cur = std::move(map);
      phase_ = start_phase;
      return 1;
    }
    return out.terminal || budget_hit_ ? -1 : 0;
  };
  // Near a period doubling (a real multiplier just beyond -1) the period-2 orbit lies on both
  // sides of the period-1 orbit along v, at a distance that grows like the square root of the
  // distance from the bifurcation, and the flow leaves the period-1 orbit only slowly (by the
  // multiplier's modulus per period): Newton on P^2 starts directly from displaced states.
  const std::complex<double> critical = eig.eigenvalues()[lead];
  if (critical.real() < -1.0 && std::abs(critical.imag()) <= 1e-8 * std::abs(critical)) {
    for (const double kick : kFlipKicks) {
      Vec y = orbit.to_array();
      for (int i = 0; i < P; ++i) y[kPeriodic[i]] += kick * v[i];
      const int found = attempt(2, t_orbit, State::from_array(y), phase);
      if (found != 0) return found > 0;
    }
  }
  for (const double sign : {1.0, -1.0}) {
    // Displace the orbit and follow the flow: it leaves the unstable orbit along v.
    Vec y = orbit.to_array();
    for (int i = 0; i < P; ++i) y[kPeriodic[i]] += sign * kKick * v[i];
    flow_.reset(t_orbit, consistent(State::from_array(y), phase), phase);
    std::vector<std::pair<State, Phase>> boundary{{flow_.state(), flow_.phase()}};
    bool survived = true;
    for (int n = 1; n <= kSubharmonicTransient; ++n) {
      if (!spend(1)) {
        out.message = budget_message();
        return false;
      }
      const FlowStop stop = flow_.advance(t_orbit + n * period_);
      if (stop == FlowStop::cancelled) {
        out.terminal = true;
        out.status = Status::cancelled;
        out.message = "cancelled during the search for a subharmonic orbit";
        return false;
      }
      if (stop != FlowStop::reached) {
        survived = false;
        break;
      }
      boundary.emplace_back(flow_.state(), flow_.phase());
    }
    if (!survived) continue;
    // The p whose p-period change at the end is smallest are tried first.
    const int last = static_cast<int>(boundary.size()) - 1;
    std::vector<std::pair<double, int>> candidates;
    for (int p = 2; p <= max_p && p <= last; ++p) {
      const auto& [a, pa] = boundary[last];
      const auto& [b, pb] = boundary[last - p];
      candidates.emplace_back(pa == pb ? scaled_change<R>(a, b, scale_) : 1e300, p);
    }
    std::sort(candidates.begin(), candidates.end());
    if (static_cast<int>(candidates.size()) > kSubharmonicTries)
      candidates.resize(kSubharmonicTries);
    for (const auto& [change, p] : candidates) {
      (void)change;
      const int found =
          attempt(p, t_orbit + last * period_, boundary[last].first, boundary[last].second);
      if (found != 0) return found > 0;
    }
  }
  p_ = 1;
  t0_ = t_orbit;
  return false;
}

// Newton's start: the supplied state (a neighbour's orbit) with its first map, or the short
// transient from the flow's state with its last period as the first map; then the extensions
// while the first map changes phase. False: the run ends here (`out` says how).
template <class R>
bool Shooter<R>::begin(const ShootingStart& start, ShootingOutcome& out, State& z, Phase& phase,
                       PeriodMap& cur) {
  if (start.from_state) {
    phase = start.phase;
    z = consistent(start.state, phase);
    t0_ = flow_.t();
    p_ = std::max(1, start.multiplicity);
    // Newton's first map, from the supplied state, gives the scales too: the range of each
    // component along it.
    PlainObserver range;
    range.start(z.to_array());
    first_ = period_map(z, phase, true, &range);
    if (first_.over_budget) {
      out.budget_exhausted = true;
      out.message = budget_message();
      return false;
    }
    if (first_.stop != FlowStop::reached) {
      out.message = "the supplied start state does not survive one period: " + flow_.message();
      out.periods_integrated = used_;
      out.period_maps = maps_;
      out.jacobian_evaluations = mono_.jacobian_evaluations();
      return false;
    }
    have_first_ = true;
    // Its monodromy serves every Newton step that follows (kChordContraction).
    chord_ = p_ == 1;
  } else if (!transient_start(out, z, phase)) {
    return false;
  }
  z = consistent(z, phase);
  phase_ = phase;

  p_ = std::max(1, start.multiplicity);
  // The short transient's last period is the first map of P (p = 1); a supplied state's first
  // map is that of P^p.
  cur =
      have_first_ && (p_ == 1 || start.from_state) ? std::move(first_) : period_map(z, phase, true);
  return extend_while_the_phase_changes(start, out, z, phase, cur);
}

// A short transient whose switches were still moving (the sequence repeated, the switch times
// not yet) can stop just before a switch drifts across the period boundary: the first map then
// ends in another phase than it started in, and Newton cannot start. The transient goes on from
// the end of that map instead (the map is one of its periods), up to kMaxExtensions times.
// False: the transient ended the run (`out` says how).
template <class R>
bool Shooter<R>::extend_while_the_phase_changes(const ShootingStart& start, ShootingOutcome& out,
                                                State& z, Phase& phase, PeriodMap& cur) {
  for (int extension = 0; extension < kMaxExtensions && !start.from_state && p_ == 1 &&
                          cur.stop == FlowStop::reached && !cur.over_budget && cur.phase != phase;
       ++extension) {
    ++out.transient_periods;
    have_first_ = false;
    if (!transient_start(out, z, phase)) return false;
    z = consistent(z, phase);
    phase_ = phase;
    cur = have_first_ ? std::move(first_) : period_map(z, phase, true);
  }
  return true;
}

// From rest, a few periods can leave the state too far from the orbit for Newton (with a
// driving torque at high frequency, where the transient method needs 100-600 periods: on a
// random scan every such failure converged from 20 periods later). The transient goes on plainly
// from where Newton started (z_start, phase_start at t_start), and Newton tries once more,
// before the run falls back. Empty: the run ends here (the transient ended it); else whether
// Newton converged.
template <class R>
std::optional<bool> Shooter<R>::retry_after_a_longer_transient(
    const ShootingStart& start, ShootingOutcome& out, const State& z_start, Phase phase_start,
    double t_start, State& z, Phase& phase, PeriodMap& cur) {
  PlainObserver range;
  flow_.reset(t_start, z_start, phase_start);
  // The longer transient continues the run's trajectory from where Newton started; Newton's
  // iterates, integrated since, are off it (their slip residual of 1e-3 was reported as the run's).
  flow_.reset_extremes();
  FlowStop stop = flow_.advance(t_start + (kRetryTransient - 1) * period_);
  if (stop == FlowStop::reached) {
    range.start(flow_.state().to_array());
    stop = flow_.advance(t_start + kRetryTransient * period_, &range);
  }
  out.transient_max_slip_residual =
      std::max(out.transient_max_slip_residual, flow_.counters().max_slip_residual);
  out.transient_min_N = std::min(out.transient_min_N, flow_.counters().min_N);
  if (stop != FlowStop::reached) return false;
  set_scales(range);
  out.transient_periods += kRetryTransient;
  t0_ = flow_.t();
  phase = flow_.phase();
  z = consistent(flow_.state(), phase);
  phase_ = phase;
  cur = period_map(z, phase, true);
  if (!extend_while_the_phase_changes(start, out, z, phase, cur)) return std::nullopt;
  return newton(z, phase, cur, out);
}

// The converged orbit's Floquet multipliers; an unstable period-1 orbit is replaced by a stable
// orbit of P^p when one is found (subharmonic). Returns whether a stable orbit stands.
template <class R>
bool Shooter<R>::stable_orbit(ShootingOutcome& out, State& z, Phase phase, PeriodMap& cur) {
  // Floquet multipliers: eigenvalues of the monodromy at the orbit. Newton's last monodromy was
  // taken at an iterate some way from it (a warm start's first map, from a neighbour's orbit;
  // a cold start's last fresh one, above kFreshMonodromy): where the largest modulus lies so
  // close to 1 that this distance could move it across, the monodromy is taken again at the
  // orbit (a warm start from a neighbour 5 MN/m^2 away, near a Neimark-Sacker point, read 1.00003
  // at its first map and 0.99555 at the orbit: an unstable verdict, a futile search for a
  // subharmonic and a start from rest).
  out.floquet = multipliers_of(cur.M);
  if (std::abs(out.floquet.max_modulus - 1.0) <
      std::min(kMultiplierMargin, kMultiplierDrift * cur.monodromy_residual)) {
    PeriodMap fresh = period_map(z, phase, true);
    if (fresh.stop == FlowStop::reached && fresh.phase == phase && !fresh.grazing) {
      cur = std::move(fresh);
      out.M = cur.M;
      out.floquet = multipliers_of(cur.M);
    }
  }
  if (out.floquet.stability == Stability::stable) return true;
  if (p_ != 1) {
    out.message = fmt("the orbit of P^%.0f is unstable (largest Floquet multiplier modulus %.6g)",
                      p_, out.floquet.max_modulus);
    return false;
  }
  const std::string why =
      fmt("the period-1 orbit is unstable (largest Floquet multiplier modulus %.6g, ",
          out.floquet.max_modulus) +
      to_string(out.floquet.stability) + ")";
  out.period1_floquet = out.floquet;
  const Mat7 M = cur.M;
  const State orbit = z;
  if (subharmonic(orbit, phase, M, z, cur, out)) {
    out.floquet = multipliers_of(cur.M);
    // Newton on P^p starts from a kicked period-1 orbit, and its last fresh monodromy was taken
    // far from the orbit: a period-2 orbit of the log-spiral study read 0.987198 where the
    // orbit's monodromy (and the Lyapunov exponent over 3000 periods) give 0.988320. A
    // subharmonic is rare, so its monodromy is always taken again at the orbit (p periods).
    PeriodMap fresh = period_map(z, phase, true);
    if (fresh.stop == FlowStop::reached && fresh.phase == phase && !fresh.grazing) {
      cur = std::move(fresh);
      out.M = cur.M;
      out.floquet = multipliers_of(cur.M);
    }
    if (out.floquet.stability != Stability::stable) {
      out.message = why + fmt(", and the orbit of P^%.0f Newton found is unstable by its "
                              "monodromy at the orbit (largest modulus %.6g): the transient is "
                              "followed instead",
                              p_, out.floquet.max_modulus);
      out.floquet = Floquet{};
      return false;
    }
    out.message = why + fmt(": a stable orbit repeating every %.0f excitation periods by "
                            "shooting on P^%.0f",
                            p_, p_);
    return true;
  }
  if (!out.terminal) {
    out.floquet = Floquet{};
    out.message = why +
                  ", and no stable orbit of P^p, p = 2 ... numerics.max_multiplicity, "
                  "was found: the transient is followed instead" +
                  (budget_hit_ ? " (" + budget_message() + ")" : std::string());
  }
  return false;
}

template <class R>
BasicShootingOutcome<R> Shooter<R>::run(const ShootingStart& start) {
  ShootingOutcome out;
  budget_ = start.budget > 0 ? start.budget : num_.max_periods;
  predict_first_ = start.predict_first;
  State z;
  Phase phase;
  PeriodMap cur;
  if (!begin(start, out, z, phase, cur)) return out;
  const State z_start = z;
  const Phase phase_start = phase;
  const double t_start = t0_;
  bool converged = newton(z, phase, cur, out);
  if (!converged && !start.from_state && p_ == 1 && !out.terminal && !budget_hit_ &&
      spend(kRetryTransient)) {
    const std::optional<bool> retried =
        retry_after_a_longer_transient(start, out, z_start, phase_start, t_start, z, phase, cur);
    if (!retried) return out;
    converged = *retried;
  }
  if (converged) converged = stable_orbit(out, z, phase, cur);
  out.period_maps = maps_;
  out.plain_maps = plain_maps_;
  out.jacobian_evaluations = mono_.jacobian_evaluations();
  out.periods_integrated = used_;
  out.budget_exhausted = budget_hit_;
  if (!converged) {
    if (out.message.empty()) out.message = "Newton failed";
    return out;
  }
  out.converged = true;
  out.multiplicity = p_;
  out.t0 = t0_;
  out.scale = scale_;
  out.orbit = z;
  out.phase = phase_;
  out.phi_drift = Dyn::cyclic_drift(cur.end.to_array(), z.to_array()) / p_;
  if (p_ == 1 || start.multiplicity > 1)
    out.message =
        fmt("periodic orbit by shooting after %.0f transient period", out.transient_periods) +
        (out.transient_periods == 1 ? "" : "s") +
        fmt(" and %.0f Newton step", out.newton_iterations) +
        (out.newton_iterations == 1 ? "" : "s");
  flow_.reset(t0_, z, phase_);
  return out;
}

}  // namespace shooting

/// Run the short transient (from the flow's current state, reset by the caller at t = 0) and
/// Newton. Never throws for numerical trouble.
template <class R>
BasicShootingOutcome<R> shoot_periodic_orbit(BasicFlow<R>& flow, const ProgressCallback& progress,
                                             const BasicShootingStart<R>& start = {}) {
  shooting::Shooter<R> shooter(flow, progress);
  return shooter.run(start);
}

}  // namespace oscidrum::detail
