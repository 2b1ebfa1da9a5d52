// simulate (oscidrum/simulate.hpp): the flow from rest, the transient steady-state search and
// the sampling of the steady state, composed; written once for any roller type R and dispatched
// on the model's roller (src/roller/rollers.hpp).
#include "oscidrum/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "drivers/continuation.hpp"
#include "drivers/modes.hpp"
#include "drivers/sampling.hpp"
#include "drivers/shooting.hpp"
#include "drivers/steady_state.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/motion.hpp"
#include "roller/rollers.hpp"
#include "util/format.hpp"

namespace oscidrum {

namespace {

// Periods a shooting orbit may be integrated on plainly to settle (see shooting()), at most.
constexpr int kSettlePeriods = 32;

// A warm start's predicted step (shooting::BasicShootingOutcome::warm_prediction): chord steps
// (each confirmed on a period map), at most.
constexpr int kWarmChordSteps = 4;

// Cost of one evaluation of a phase Jacobian (src/equations/jacobian.cpp) together with its share
// of the Magnus step of Phi (a third of its exponent's commutators and of its exponential), in
// right-hand-side evaluations, for Diagnostics::period_equivalents: measured by
// bench/bench_monodromy.cpp (one period at a steady orbit, plainly and with the variational
// equations, CPU time): 4.8 (pure rolling) to 5.2 (the paper's stick-slip case) on the paper's
// roller and the performance issue's sweep with the AVX-512 kernels of the Magnus step
// (src/flow/wide_kernels.cpp; 6.1-6.6 with the baseline build's Eigen code: bench/README.md,
// "Issue 26: the Magnus step in wide vectors"). A processor without AVX-512 spends more on a
// Magnus step than this weight says.
constexpr double kJacobianCost = 5.0;

// The transient search from rest and the sampling of what it found. It may integrate what is left
// of numerics.max_periods after the periods shooting spent before falling back.
template <class R>
void transient(const Model& model, BasicFlow<R>& flow, const ProgressCallback& progress,
               Result& result, long* sample_rhs, bool all_samples) {
  const detail::Dynamics<R> dynamics(model, flow.options().baumgarte);
  flow.reset(0.0, R::State::from_array(dynamics.initial_state()), dynamics.initial_phase());
  // Diagnostics::max_slip_residual and min_N: over this run from rest and its sampled periods.
  flow.reset_extremes();
  const Numerics& num = model.parameters().numerics;
  Diagnostics& d = result.diagnostics;
  const int spent = d.periods_simulated;
  detail::SearchOutcome search;
  if (spent >= num.max_periods) {
    search.status = Status::max_periods_reached;
    search.message = detail::format(
        "no steady state: shooting integrated all numerics.max_periods = %.0f periods before it "
        "fell back; the periods from rest are sampled for inspection, with no metrics",
        num.max_periods);
  } else {
    search = detail::find_steady_state(flow, progress, num.max_periods - spent, spent);
  }
  result.status = search.status;
  result.message = search.message;
  d.method = SteadyMethod::transient;
  d.final_change = search.final_change;
  d.periods_simulated += search.periods;
  if (search.status == Status::steady_state) {
    d.periods_to_steady = search.periods;
    d.multiplicity = search.multiplicity;
  }
  // Sample the steady state (or, when no steady state was found, the periods that follow, for
  // inspection: they carry no metrics).
  if (search.status == Status::steady_state || search.status == Status::max_periods_reached) {
    const int periods = num.output_periods * std::max(1, search.multiplicity);
    const long rhs_before = flow.counters().rhs_evaluations;
    const auto section = flow.state().to_array();
    const FlowStop stop =
        detail::sample_periods(flow, periods, num.samples_per_period, result, all_samples);
    *sample_rhs = (flow.counters().rhs_evaluations - rhs_before) / std::max(1, periods);
    d.periods_simulated += periods;
    if (stop != FlowStop::reached) {  // the steady state did not survive its own sampling
      result.status = status_of(stop);
      result.message = flow.message();
    } else if (result.samples.size() > 0) {
      // phi(t0 + T) - phi(t0), averaged over the sampled periods (net slip per period / r).
      d.phi_drift = detail::Dynamics<R>::cyclic_drift(flow.state().to_array(), section) / periods;
    }
  } else {
    result.events = search.recent_events;
    if (search.status == Status::gross_slip) d.phi_drift = search.phi_drift;
  }
  d.max_slip_residual = flow.counters().max_slip_residual;
  d.min_N = flow.counters().min_N;
}

// Shooting (src/drivers/shooting.hpp); returns false when the run must fall back to the
// transient method.
// `warm`: start Newton from a neighbouring case's orbit (continuation in studies) instead of a
// short transient from rest; a failed warm start returns false without ending the run.
// `record` (may be null): the steady period recorded for the metrics when the orbit's sampling
// starts from the flow's restart at the section (detail::sample_periods).
template <class R>
bool shooting(const Model& model, BasicFlow<R>& flow, const ProgressCallback& progress,
              Result& result, long* sample_rhs, bool all_samples,
              detail::recording::Recording* record,
              const detail::BasicShootingStart<R>& warm = {}) {
  const Numerics& num = model.parameters().numerics;
  Diagnostics& d = result.diagnostics;
  if (d.periods_simulated >= num.max_periods) return false;  // the fallback reports it
  const detail::Dynamics<R> dynamics(model, flow.options().baumgarte);
  // A warm start begins on the orbit's section after the start ramp (numerics.start_ramp_periods;
  // the excitation is T-periodic from there): under the ramp the neighbour's orbit is no orbit,
  // and every warm start of a study with a ramp failed and ran from rest.
  if (warm.from_state)
    flow.reset(num.start_ramp_periods * model.period(), warm.state, warm.phase);
  else
    flow.reset(0.0, R::State::from_array(dynamics.initial_state()), dynamics.initial_phase());
  flow.reset_extremes();
  // Every period shooting integrates counts against numerics.max_periods, a failed warm start's
  // too: the fallbacks get what is left.
  detail::BasicShootingStart<R> start = warm;
  start.budget = num.max_periods - d.periods_simulated;
  const auto shot = detail::shoot_periodic_orbit(flow, progress, start);
  d.newton_iterations += shot.newton_iterations;
  d.jacobian_evaluations += shot.jacobian_evaluations;
  d.periods_simulated += shot.periods_integrated;
  // A warm start that ends the flow (contact lost, ...) says nothing about the cold start;
  // only cancellation ends the run.
  if (shot.terminal && warm.from_state && shot.status != Status::cancelled) return false;
  if (shot.terminal) {  // the transient from rest meets the same end
    result.status = shot.status;
    result.message = shot.message;
    result.events = shot.recent_events;
    d.method = SteadyMethod::shooting;
    d.final_change = shot.final_change;
    d.max_slip_residual = flow.counters().max_slip_residual;
    d.min_N = flow.counters().min_N;
    return true;
  }
  // A warm start that spent the budget without a steady state says nothing about the cold start,
  // which gets a budget of its own (simulate_once): a failed warm start must not turn a case the
  // cold start solves into max_periods_reached.
  if (!shot.converged && shot.budget_exhausted && warm.from_state && warm.yields_budget)
    return false;
  if (!shot.converged && shot.budget_exhausted) {
    // No periods are left for a fallback: the run ends as the transient method ends when it
    // reaches numerics.max_periods, with the periods that follow sampled for inspection.
    result.status = Status::max_periods_reached;
    result.message =
        "no steady state within numerics.max_periods = " + std::to_string(num.max_periods) +
        " periods: " + shot.message +
        "; the last periods are sampled for inspection, with no metrics";
    d.method = SteadyMethod::shooting;
    d.final_change = shot.final_change;
    flow.reset_extremes();
    const long rhs_before = flow.counters().rhs_evaluations;
    const FlowStop stop = detail::sample_periods(flow, num.output_periods, num.samples_per_period,
                                                 result, all_samples);
    *sample_rhs = (flow.counters().rhs_evaluations - rhs_before) / num.output_periods;
    d.periods_simulated += num.output_periods;
    if (stop != FlowStop::reached) {
      result.status = status_of(stop);
      result.message = flow.message();
    }
    d.max_slip_residual = flow.counters().max_slip_residual;
    d.min_N = flow.counters().min_N;
    return true;
  }
  if (!shot.converged) {
    if (!warm.from_state) d.fallback = shot.message;
    return false;
  }
  // A steady state repeating every p excitation periods is sampled over output_periods * p
  // periods, as the transient method samples one; a study's case that keeps no samples samples
  // the steady period alone (its metrics read nothing else).
  const int p = shot.multiplicity;
  const int periods = all_samples ? num.output_periods * p : p;
  // Diagnostics::max_slip_residual and min_N: over the trajectory of the result, the short
  // transient from rest and the sampled periods of the orbit (Newton's iterates are not on it).
  flow.reset_extremes();
  // The flow was restarted on the orbit at its section (shoot_periodic_orbit): the sampling's
  // first p periods are the period map P^p at the orbit (the same integration, so the same
  // steps: `change` is its residual |P^p(z) - z|, scaled), and the steady period
  // compute_metrics would integrate again. The orbit is confirmed on them, and the rest of the
  // sampled periods repeat them (the orbit is periodic to steady_tol: integrating them again
  // cost about a sixth of a case from rest and changed nothing beyond that). A warm start's
  // predicted step (warm_prediction) is accepted when its residual meets Newton's own convergence
  // test (kNewtonTol steady_tol, so that a warm case's orbit is as converged as a cold one's);
  // until then period maps give the next chord steps with the first map's monodromy, as long as
  // each contracts the residual kChordContraction-fold (below).
  auto orbit = shot.orbit;
  double change = std::numeric_limits<double>::infinity();
  double previous = shot.final_change;  // the residual the last step was taken from
  const auto accepted = [&] {
    if (!shot.warm_prediction) return change < num.steady_tol;
    // Newton's tests: converged, or below steady_tol and no longer halving (the noise floor).
    return change < detail::shooting::kNewtonTol * num.steady_tol ||
           (change < num.steady_tol && change > 0.5 * previous);
  };
  // The state after the sampling's first p periods, the period map P^p at the orbit (the same
  // integration with or without the further samples): phi's drift per period is taken there.
  typename detail::Dynamics<R>::Vector mapped{};
  bool have_mapped = false;
  const auto confirm = [&] {
    change = detail::scaled_change<R>(flow.state(), orbit, shot.scale);
    mapped = flow.state().to_array();
    have_mapped = true;
    return accepted();
  };
  const auto discard_samples = [&] {
    if (record != nullptr) detail::recording::clear(*record);
    result.samples = Samples{};
    result.events.clear();
    result.stick_time = result.slip_positive_time = result.slip_negative_time = 0.0;
    result.flight_time = 0.0;
    *sample_rhs = 0;
  };
  // Newton goes on from the last iterate with a fresh monodromy, mapping every step, as a warm
  // start from there (when the chord steps contract too little: a large step from the
  // neighbour, where the first map's monodromy is too far from the orbit's).
  const auto start_again = [&] {
    detail::BasicShootingStart<R> again = warm;
    again.state = orbit;
    again.phase = shot.phase;
    again.predict_first = false;
    return shooting(model, flow, progress, result, sample_rhs, all_samples, record, again);
  };
  // The sampled (and recorded) period confirms the orbit. A warm start's predicted step is first
  // confirmed on plain period maps (no sampling, no recording: a recorded period costs about
  // three plain ones), each giving the next chord step, until the last contraction predicts a
  // residual well below Newton's test; a recorded period that does not confirm gives a chord
  // step too.
  // No contraction known yet, unless the neighbour's first chord step gives one (its orbit's
  // monodromy was as accurate as this one's: on the performance issue's sweep the contraction
  // varies by a factor of about 3 from case to case, well inside kPredictMargin).
  double predicted = std::numeric_limits<double>::infinity();
  if (shot.warm_prediction && warm.contraction >= 0.0) predicted = previous * warm.contraction;
  double first_contraction = -1.0;  // of this case's first chord step (-1: none)
  const auto note_contraction = [&] {
    if (shot.warm_prediction && previous > 0.0 && std::isfinite(change))
      first_contraction = change / previous;
  };
  long rhs_before = flow.counters().rhs_evaluations;
  FlowStop stop = FlowStop::reached;
  bool unconfirmed = false;
  for (int chord_steps = 0;; ++chord_steps) {
    const bool record_now = !shot.warm_prediction || predicted < detail::shooting::kPredictMargin *
                                                                     detail::shooting::kNewtonTol *
                                                                     num.steady_tol;
    if (chord_steps > 0) flow.reset(shot.t0, orbit, shot.phase);
    if (record_now) {
      discard_samples();
      rhs_before = flow.counters().rhs_evaluations;
      stop = detail::sample_periods(flow, periods, num.samples_per_period, result, all_samples,
                                    record, p, confirm);
      // FlowStop::observer: the flow reached the end of a period that did not confirm the orbit.
      unconfirmed = stop == FlowStop::observer;
      if (chord_steps == 0) note_contraction();
      if (!unconfirmed || !shot.warm_prediction) break;
      d.periods_simulated += p;  // the recorded period that did not confirm the step
    } else {
      // (stop may still hold FlowStop::observer of a recorded period that did not confirm.)
      stop = flow.advance(shot.t0 + p * model.period());
      d.periods_simulated += p;
      if (stop != FlowStop::reached) break;
      change = detail::scaled_change<R>(flow.state(), orbit, shot.scale);
      if (chord_steps == 0) note_contraction();
      if (accepted()) {
        predicted = 0.0;  // confirmed: its recorded period follows, from the same state
        continue;
      }
    }
    if (!(change < detail::shooting::kChordContraction * previous) ||
        chord_steps + 1 >= kWarmChordSteps || d.periods_simulated + p > num.max_periods)
      break;
    const auto step = detail::shooting::newton_step<R>(shot.M, shot.scale, orbit, flow.state());
    if (!step.finite()) break;
    orbit = step.apply(dynamics, orbit, shot.phase);
    ++d.newton_iterations;
    predicted = change * (change / previous);
    previous = change;
    unconfirmed = false;
  }
  if (unconfirmed) stop = FlowStop::reached;
  // The periods the sampling integrated: once confirmed, the orbit's first p periods (the later
  // ones repeat them, detail::sample_periods).
  const int integrated = std::max(
      1, std::min(periods, static_cast<int>(std::lround((flow.t() - shot.t0) / model.period()))));
  *sample_rhs = (flow.counters().rhs_evaluations - rhs_before) / integrated;
  if (shot.warm_prediction && !(stop == FlowStop::reached && accepted())) {
    // The chord steps did not converge (they contract too little: a large step from the
    // neighbour, where the first map's monodromy is too far from the orbit's): Newton goes on
    // from the last iterate with a fresh monodromy (start_again) while the residual decreased;
    // else, and when that fails too, the cold start follows.
    discard_samples();
    if (stop != FlowStop::reached || !(change < previous)) return false;
    return start_again();
  }
  // Settled: the orbit moved a little under plain integration and the transient method's own
  // test, run on from there, found it steady (sampled again after it).
  std::optional<detail::SearchOutcome> settled;
  double section = shot.t0;                                // where the samples start
  typename detail::Dynamics<R>::Vector settled_section{};  // the state there, once settled
  if (stop == FlowStop::reached && !accepted() && p == 1) {
    // A predicted last step whose period did not confirm it: the transient method's test, run
    // on from there for at most kSettlePeriods periods, accepts the orbit; otherwise the run
    // falls back.
    discard_samples();
    d.periods_simulated += p;  // integrated, and counted against the budget
    const int budget = std::min(kSettlePeriods, num.max_periods - d.periods_simulated);
    if (budget > 0) {
      const detail::SearchOutcome search = detail::find_steady_state(flow, progress, budget);
      d.periods_simulated += search.periods;
      if (search.status == Status::steady_state && search.multiplicity == 1) {
        section = flow.t();
        settled_section = flow.state().to_array();
        const long rhs_again = flow.counters().rhs_evaluations;
        const FlowStop again =
            detail::sample_periods(flow, periods, num.samples_per_period, result, all_samples);
        *sample_rhs = (flow.counters().rhs_evaluations - rhs_again) / std::max(1, periods);
        if (again == FlowStop::reached) {
          settled = search;
        } else {
          discard_samples();
        }
      }
    }
    if (!settled) {
      if (!warm.from_state)
        d.fallback =
            "the orbit did not repeat under plain integration (its change over the "
            "sampled period was " +
            detail::format("%.3g", change) + ") and did not settle within " +
            std::to_string(kSettlePeriods) + " more periods";
      return false;
    }
  } else if (stop != FlowStop::reached || !accepted()) {
    if (!warm.from_state)
      d.fallback = stop != FlowStop::reached
                       ? "the orbit did not survive its sampling: " + flow.message()
                       : "the orbit did not repeat under plain integration";
    discard_samples();
    d.periods_simulated += integrated;  // integrated, and counted against the budget
    return false;
  }
  result.status = Status::steady_state;
  result.message =
      warm.from_state ? shot.message + " from the neighbouring case's orbit" : shot.message;
  if (settled)
    result.message +=
        detail::format(
            "; integrated on plainly (its change over the sampled periods was %.3g, above "
            "numerics.steady_tol), it settled after %.0f more period",
            change, settled->periods) +
        (settled->periods == 1 ? "" : "s");
  result.floquet = shot.floquet;
  if (p > 1) result.period1_floquet = shot.period1_floquet;
  d.method = SteadyMethod::shooting;
  // A last Newton step taken on prediction was never mapped: what the sampled periods measured
  // (the change over output_periods periods, at most about twice the one-period change) is the
  // evaluated residual then.
  d.final_change = settled                    ? settled->final_change
                   : shot.predicted_last_step ? change
                                              : shot.final_change;
  d.periods_to_steady =
      settled ? static_cast<int>(std::lround(section / model.period())) : shot.transient_periods;
  d.multiplicity = p;
  // The drift of phi over the orbit's own period map (the sampling's first p periods from the
  // orbit). Newton's last map started from the iterate before the last step (shot.phi_drift): a
  // warm start's chord steps from the neighbour's orbit moved phi by up to 1e-5 rad, and a
  // pure-rolling orbit without driving torque, which closes in phi, read a net slip.
  d.phi_drift =
      settled && result.samples.size() > 0
          ? detail::Dynamics<R>::cyclic_drift(flow.state().to_array(), settled_section) / periods
      : have_mapped ? detail::Dynamics<R>::cyclic_drift(mapped, orbit.to_array()) / p
                    : shot.phi_drift;
  d.periods_simulated += settled ? periods : integrated;
  d.max_slip_residual = std::max(flow.counters().max_slip_residual,
                                 warm.from_state ? 0.0 : shot.transient_max_slip_residual);
  d.min_N =
      std::min(flow.counters().min_N,
               warm.from_state ? std::numeric_limits<double>::infinity() : shot.transient_min_N);
  if (record != nullptr && !settled) record->chord_contraction = first_contraction;
  return true;
}

template <class R>
Result simulate_once(const Model& model, const ProgressCallback& progress,
                     const std::function<bool()>& cancelled, const detail::WarmStart* warm,
                     bool all_samples, detail::recording::Recording* record) {
  if (record != nullptr) detail::recording::clear(*record);
  FlowOptions options = FlowOptions::from(model);
  options.cancelled = cancelled;
  BasicFlow<R> flow(model, options);
  const Numerics& num = model.parameters().numerics;
  const detail::Dynamics<R> dynamics(model, options.baumgarte);

  Result result;
  result.frequency = model.parameters().roller.f;
  long sample_rhs = 0;  // right-hand-side evaluations of one sampled period
  const long rhs_start = flow.counters().rhs_evaluations;
  bool done = false;
  int warm_periods = 0;  // of a failed warm start
  if (num.method == SteadyMethod::shooting && warm &&
      warm->state.size() == static_cast<std::size_t>(R::kStates)) {
    // Continuation (docs/periodic.md): Newton from the neighbour's orbit (or from the state
    // predicted along the chain, then from the neighbour's own); when it fails, the cold start
    // below runs as if it had not been tried (only its cost remains).
    for (const std::vector<double>* from : {&warm->state, &warm->then}) {
      if (done || from->size() != static_cast<std::size_t>(R::kStates)) continue;
      detail::BasicShootingStart<R> start;
      start.from_state = true;
      typename detail::Dynamics<R>::Vector x{};
      std::copy(from->begin(), from->end(), x.begin());
      start.state = R::State::from_array(x);
      // A phase the new case cannot be in (slip under pure rolling, stick without friction,
      // stick or slip under a smooth law): its start phase instead.
      start.phase = dynamics.flow_phase(warm->phase);
      start.contraction = warm->contraction;
      start.yields_budget = warm->cold_start_budget;
      done = shooting(model, flow, progress, result, &sample_rhs, all_samples, record, start);
    }
    result.diagnostics.warm_start = done ? 1 : -1;
    if (!done) {
      result.floquet = Floquet{};
      result.events.clear();
      // The cold start runs "exactly as it runs alone": with all of numerics.max_periods. The
      // failed attempt's periods are counted as work below (Diagnostics::periods_simulated), not
      // against the budget.
      if (warm->cold_start_budget) {
        warm_periods = result.diagnostics.periods_simulated;
        result.diagnostics.periods_simulated = 0;
      }
    }
  }
  // A warm start whose caller wants no start from rest after it (WarmStart::cold_start).
  const bool no_cold = warm != nullptr && !warm->cold_start && result.diagnostics.warm_start == -1;
  if (no_cold) {
    result.status = Status::max_periods_reached;
    result.message = "no stable periodic orbit by shooting from the given state";
  }
  if (!done && !no_cold && num.method == SteadyMethod::shooting)
    done = shooting(model, flow, progress, result, &sample_rhs, all_samples, record);
  if (!done && !no_cold) {
    // The transient method's sampling continues its search: no restart, no recording.
    if (record != nullptr) detail::recording::clear(*record);
    transient(model, flow, progress, result, &sample_rhs, all_samples);
  }
  Diagnostics& d = result.diagnostics;
  d.periods_simulated += warm_periods;

  const FlowCounters& c = flow.counters();
  d.steps = c.steps;
  d.rhs_evaluations = c.rhs_evaluations - rhs_start;
  d.events = c.events;
  d.switches = c.switches;
  d.reversals = c.reversals;
  d.inconsistent_slip_ends = c.inconsistent_slip_ends;
  if (!std::isfinite(d.min_N)) d.min_N = 0.0;  // no step end seen
  // The stepper retries rejected steps internally. Dormand-Prince 8(5,3) with FSAL costs one
  // evaluation per (re)start, twelve per attempted step and three more per accepted one (its
  // continuous extension), eleven per partial step (to an event or the end of an advance()
  // interval inside a step), and nothing else calls the right-hand side, so the attempts follow
  // from the count.
  const long starts = c.restarts;
  const long attempts = (c.rhs_evaluations - starts - 3 * c.steps - 11 * c.partial_steps) / 12;
  d.rejected_steps = std::max(0L, attempts - c.steps);
  // sample_rhs: right-hand-side evaluations of one plain sampled period.
  if (sample_rhs > 0) {
    const double per_period = static_cast<double>(sample_rhs);
    d.period_equivalents = (static_cast<double>(d.rhs_evaluations) +
                            kJacobianCost * static_cast<double>(d.jacobian_evaluations)) /
                           per_period;
  } else {
    d.period_equivalents = d.periods_simulated;
  }
  return result;
}

// A start from rest can be violent enough to lift the drum off although the steady orbit keeps
// contact (the status must not depend on how a case is started). A run that loses contact before
// a steady state is found is run again with the excitation ramped in over kRampPeriods periods
// (numerics.start_ramp_periods); contact_lost stands only when that run loses contact too, or
// when the steady orbit itself does (its sampling loses contact: no retry).
constexpr int kRampPeriods = detail::kContactRetryRampPeriods;

// Diagnostics::contact_mode from the sampled window's lift-offs (docs/model.md section 13).
std::string contact_mode(const Result& r) {
  const int p = std::max(1, r.diagnostics.multiplicity);
  std::vector<int> per_period(static_cast<std::size_t>(std::max(1, r.sample_periods)), 0);
  int lift_offs = 0;
  const double t0 = r.samples.size() > 0 ? r.samples.t.front() : 0.0;
  for (const Event& e : r.events) {
    if (e.kind != EventKind::lift_off) continue;
    ++lift_offs;
    const auto k = static_cast<std::size_t>(std::floor((e.t - t0) * r.frequency));
    if (k < per_period.size()) ++per_period[k];
  }
  // A run without a steady state: its lift-offs may all lie before the sampled periods (an
  // intermittent, chaotic flight). N reached 0 somewhere on its trajectory (min_N, 0 at every
  // lift-off) without the contact being lost (another status): it lifted off.
  if (r.status == Status::max_periods_reached || r.status == Status::aperiodic)
    return lift_offs > 0 || r.diagnostics.min_N <= 0.0 ? "aperiodic" : "";
  if (r.status != Status::steady_state) return "";
  if (lift_offs == 0) return "permanent contact";
  const bool every = std::all_of(per_period.begin(), per_period.end(), [](int n) { return n > 0; });
  // Lift-offs in one repetition of the orbit (p periods): one, or several (a 3-period orbit of
  // the lift-off study lifts off twice in its 3 periods, and read "lift-off every 3 periods").
  const int sampled = std::max(1, r.sample_periods);
  const long per_repetition = std::lround(static_cast<double>(lift_offs) * p / sampled);
  if (every && p == 1) return "periodic lift-off";
  // A lift-off in every period, one each (a period-2 orbit with two lift-offs in one of its
  // periods and one in the other, 3 in 2 periods, read "lift-off every period"): counted.
  if (every && per_repetition == p)
    return "lift-off every period, repeating every " + std::to_string(p) + " periods";
  if (per_repetition > 1)
    return std::to_string(per_repetition) + " lift-offs every " + std::to_string(p) + " periods";
  return "lift-off every " + std::to_string(p) + " periods";
}

template <class R>
Result simulate_ramped(const Model& model, const ProgressCallback& progress,
                       const std::function<bool()>& cancelled, const detail::WarmStart* warm,
                       bool all_samples, detail::recording::Recording* record) {
  Result first = simulate_once<R>(model, progress, cancelled, warm, all_samples, record);
  const Numerics& num = model.parameters().numerics;
  first.diagnostics.start_ramp_periods = num.start_ramp_periods;
  if (first.status != Status::contact_lost || first.diagnostics.periods_to_steady >= 0 ||
      num.start_ramp_periods > 0 || first.diagnostics.periods_simulated >= num.max_periods)
    return first;
  Case gentle = model.parameters();
  gentle.numerics.start_ramp_periods = kRampPeriods;
  gentle.numerics.max_periods = num.max_periods - first.diagnostics.periods_simulated;
  const Model ramped(gentle);
  Result again = simulate_once<R>(ramped, progress, cancelled, nullptr, all_samples, record);
  Diagnostics& d = again.diagnostics;
  const Diagnostics& f = first.diagnostics;
  d.start_ramp_periods = kRampPeriods;
  // The work of both runs.
  d.periods_simulated += f.periods_simulated;
  d.steps += f.steps;
  d.rejected_steps += f.rejected_steps;
  d.rhs_evaluations += f.rhs_evaluations;
  d.jacobian_evaluations += f.jacobian_evaluations;
  d.newton_iterations += f.newton_iterations;
  d.period_equivalents += f.period_equivalents;
  const std::string lost = first.message;
  if (again.status == Status::contact_lost) {
    again.message = lost + "; started again with the excitation ramped in over " +
                    std::to_string(kRampPeriods) + " periods, " + again.message;
    return again;
  }
  again.message += "; the start from rest lost contact (" + lost +
                   "), so the excitation was ramped in over " + std::to_string(kRampPeriods) +
                   " periods (diagnostic start_ramp_periods)";
  return again;
}

// No steady state within numerics.max_periods: what is the motion? (oscidrum/motion.hpp) A torus
// or chaos is a verdict, status aperiodic; otherwise the status stands, with what was seen.
constexpr int kMotionPeriods = 400;

// A window that examined all its periods and still did not decide (the exponent's halves
// disagree: the motion is still changing) is followed by one kLongerMotion times as long, from
// the same start (a period-2 orbit approached over about a thousand periods decides there).
constexpr int kLongerMotion = 4;

constexpr int kShootingCheckPeriods = 200;

// A warm start from the first sample (the state at the start of the sampled window, where the
// samples of a steady state start on its section), when there is one and it is finite.
template <class R>
std::optional<detail::WarmStart> first_sample_start(const Samples& s) {
  if (s.size() == 0) return {};
  const auto x = detail::Dynamics<R>::sampled_state(s, 0);
  for (double v : x)
    if (!std::isfinite(v)) return {};
  return detail::WarmStart{std::vector<double>(x.begin(), x.end()), s.phase[0], {}};
}

// Whether shooting from the state where the search ended (the first sample of `result`) converges
// to a stable periodic orbit (warm-started from that state, not from rest): its description, or
// nothing.
std::optional<std::string> stable_orbit_nearby(const Model& model, const Result& result,
                                               const std::function<bool()>& cancelled) {
  const std::optional<detail::WarmStart> start =
      detail::with_roller(model, [&]<class R>() { return first_sample_start<R>(result.samples); });
  if (!start) return {};
  Case c = model.parameters();
  c.numerics.method = SteadyMethod::shooting;
  c.numerics.max_periods = kShootingCheckPeriods;
  const Model shooting(c);
  const Result orbit = detail::simulate_from(shooting, {}, cancelled, &*start, false);
  if (orbit.status != Status::steady_state || orbit.diagnostics.warm_start != 1 ||
      orbit.floquet.stability != Stability::stable)
    return {};
  return detail::format(
      "shooting from the last state finds a stable periodic orbit (period %.0f, largest Floquet "
      "multiplier modulus %.7g), which the motion approaches too slowly for "
      "numerics.max_periods (by |mu| per period); numerics.method = shooting gives it",
      orbit.diagnostics.multiplicity, orbit.floquet.max_modulus);
}

// A run stopped while its motion was to be examined, or during it, has no verdict: it is
// cancelled, not max_periods_reached (a sweep interrupted there kept such a case as finished,
// status max_periods_reached for an aperiodic one, and --resume kept it).
void cancel_examination(Result& result) {
  result.status = Status::cancelled;
  result.message += "; cancelled before the motion was examined";
}

void examine_motion(const Model& model, Result& result, const std::function<bool()>& cancelled) {
  MotionAnalysis a = analyze_motion(model, result, kMotionPeriods, cancelled);
  if (cancelled && cancelled()) return cancel_examination(result);
  if (a.kind == "undecided" && a.periods == kMotionPeriods) {
    a = analyze_motion(model, result, kLongerMotion * kMotionPeriods, cancelled);
    if (cancelled && cancelled()) return cancel_examination(result);
    a.evidence += " (" + std::to_string(kMotionPeriods) + " periods did not decide)";
  }
  result.diagnostics.motion = a.kind;
  result.diagnostics.lyapunov_exponent = a.lyapunov;
  // A "zero" exponent over the window is also an approach to a periodic orbit whose multiplier
  // lies within about 1e-4 of the unit circle (0.9999852: the transient settled after 954 972
  // periods, and the status said aperiodic, a torus). Shooting from the last state (at most
  // kShootingCheckPeriods, below kMotionPeriods: no examination of its own) tells them apart: a
  // stable orbit it reaches from there is not a torus.
  if (a.kind == "quasi_periodic" && !(cancelled && cancelled())) {
    const std::optional<std::string> orbit = stable_orbit_nearby(model, result, cancelled);
    if (cancelled && cancelled()) return cancel_examination(result);
    if (orbit) {
      result.diagnostics.motion = "converging";
      result.message += "; examined over " + std::to_string(a.periods) +
                        " further periods: converging (the largest Lyapunov exponent reads zero, " +
                        detail::format("%.4g", a.lyapunov / model.parameters().roller.f) +
                        " per period, as on a torus, but " + *orbit + ")";
      return;
    }
  }
  if (a.kind == "quasi_periodic" || a.kind == "chaotic") {
    result.status = Status::aperiodic;
    result.message = "no periodic steady state within numerics.max_periods; the motion is " +
                     std::string(a.kind == "chaotic" ? "chaotic" : "quasi-periodic") + ": " +
                     a.evidence;
  } else {
    result.message += "; examined over " + std::to_string(a.periods) +
                      " further periods: " + a.kind + " (" + a.evidence + ")";
    // A steady state of a longer period than the search looks for: say which setting finds it.
    const int longest = model.parameters().numerics.max_multiplicity;
    if (a.kind == "periodic" && a.recurrence > longest)
      result.message += detail::format(
          "; it repeats every %.0f excitation periods, beyond numerics.max_multiplicity = %.0f: "
          "set it to %.0f (at most 64) to find this steady state",
          a.recurrence, longest, a.recurrence);
  }
}

template <class R>
Result simulate_roller(const Model& model, const ProgressCallback& progress,
                       const std::function<bool()>& cancelled, const detail::WarmStart* warm,
                       bool all_samples, detail::recording::Recording* record) {
  Result result = simulate_ramped<R>(model, progress, cancelled, warm, all_samples, record);
  // Examined when the search had at least as many periods as the examination takes (a run cut
  // short on purpose, numerics.max_periods = 3, is a transient, not a motion to judge).
  if (result.status == Status::max_periods_reached && result.samples.size() > 0 &&
      model.parameters().numerics.max_periods >= kMotionPeriods) {
    if (cancelled && cancelled())
      cancel_examination(result);
    else
      examine_motion(model, result, cancelled);
  }
  result.diagnostics.contact_mode = contact_mode(result);
  result.diagnostics.operating_mode =
      detail::operating_mode(model.parameters().roller.type, result.diagnostics);
  // Without a sampled window (a run that ended before sampling: gross slip, contact lost, ...)
  // no time was spent in any phase of it: unknown, not 0 (a spinning drum with zero slip time).
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (result.samples.size() == 0) {
    result.stick_time = result.slip_positive_time = result.slip_negative_time = result.flight_time =
        kNaN;
    result.diagnostics.switches_per_period = kNaN;  // counted in the sampled window
  }
  // The drift of phi per period is the steady state's; a gross slip keeps the drift of its last
  // period (what the status reports); any other run that is not steady has none, not 0.
  if (!ok(result.status) && result.status != Status::gross_slip)
    result.diagnostics.phi_drift = kNaN;
  return result;
}

template <class R>
std::optional<detail::WarmStart> orbit_start_of(const Result& result) {
  if (!ok(result.status) || result.diagnostics.multiplicity != 1) return {};
  return first_sample_start<R>(result.samples);
}

}  // namespace

namespace detail {

std::optional<WarmStart> orbit_start(const Model& model, const Result& result) {
  return with_roller(model, [&]<class R>() { return orbit_start_of<R>(result); });
}

std::optional<WarmStart> orbit_start(const Model& model, const Result& result,
                                     const recording::Recording& record) {
  std::optional<WarmStart> start = orbit_start(model, result);
  if (start) start->contraction = record.chord_contraction;
  return start;
}

Result simulate_from(const Model& model, const ProgressCallback& progress,
                     const std::function<bool()>& cancelled, const WarmStart* warm,
                     bool all_samples, recording::Recording* record) {
  return with_roller(model, [&]<class R>() {
    return simulate_roller<R>(model, progress, cancelled, warm, all_samples, record);
  });
}

}  // namespace detail

Result simulate(const Model& model, const ProgressCallback& progress,
                const std::function<bool()>& cancelled) {
  return detail::simulate_from(model, progress, cancelled, nullptr);
}

Result simulate(const Case& c, const ProgressCallback& progress,
                const std::function<bool()>& cancelled) {
  const Model model(c);
  return simulate(model, progress, cancelled);
}

}  // namespace oscidrum
