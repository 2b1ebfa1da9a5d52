// Internal: the sampling driver, for any roller type R. Records whole excitation periods of a
// trajectory into a Result: uniform samples (the roller's columns, Dynamics<R>::sample), the
// events and the time spent in each phase.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>

#include "drivers/period_recording.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"
#include "roller/dynamics.hpp"

namespace oscidrum::detail {

/// Two observers of one flow.
template <class R>
class ObserverPair : public BasicFlowObserver<R> {
 public:
  using State = typename R::State;
  ObserverPair(BasicFlowObserver<R>& a, BasicFlowObserver<R>& b) : a_(a), b_(b) {}
  bool on_step(const BasicStepView<R>& step) override {
    const bool a = a_.on_step(step), b = b_.on_step(step);
    return a && b;
  }
  bool on_event(const Event& event, const State& before, const State& after) override {
    const bool a = a_.on_event(event, before, after), b = b_.on_event(event, before, after);
    return a && b;
  }

 private:
  BasicFlowObserver<R>&a_, &b_;
};

namespace sampling {

/// The time of sample j of a sampling that starts at t0 [s] (one expression for the integrated
/// samples and their repeats, so that both give the same bits).
inline double sample_time(double t0, long j, double period, int per_period) {
  return t0 + static_cast<double>(j) * period / per_period;
}

template <class R>
class Sampler : public BasicFlowObserver<R> {
 public:
  using State = typename R::State;
  Sampler(const BasicFlow<R>& flow, double t_start, int periods, int per_period, bool all_samples,
          Result& result)
      : dynamics_(flow.model(), flow.options().baumgarte),
        period_(flow.model().period()),
        t_start_(t_start),
        t_end_(t_start + periods * flow.model().period()),
        per_period_(per_period),
        total_(all_samples ? static_cast<long>(periods) * per_period : 1),
        result_(result) {
    // Every column's storage at once (the columns grew by doubling: a dozen reallocations and
    // copies of each of the ~20 columns for two periods of 1024 samples).
    const auto n = result.samples.size() + static_cast<std::size_t>(total_);
#define OSCIDRUM_RESERVE(type, name, unit, label, description) result.samples.name.reserve(n);
    OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_RESERVE)
#undef OSCIDRUM_RESERVE
  }

  bool on_step(const BasicStepView<R>& step) override {
    // Samples in [t0, t1] not yet taken (a sample on a piece boundary belongs to the first),
    // kBlock at a time where the roller evaluates several at once (sample_many).
    constexpr int kBlock = 16;
    std::array<double, kBlock> ts;
    std::array<State, kBlock> qs;
    std::array<typename Dynamics<R>::Vector, kBlock> xs;
    int n = 0;
    auto flush = [&] {
      step.states(ts.data(), n, qs.data());
      for (int i = 0; i < n; ++i) xs[i] = qs[i].to_array();
      if constexpr (requires {
                      dynamics_.sample_many(ts.data(), xs.data(), n, step.phase(), result_.samples);
                    }) {
        dynamics_.sample_many(ts.data(), xs.data(), n, step.phase(), result_.samples);
      } else {
        for (int i = 0; i < n; ++i) dynamics_.sample(ts[i], xs[i], step.phase(), result_.samples);
      }
      n = 0;
    };
    while (next_ < total_) {
      const double t = sample_time(t_start_, next_, period_, per_period_);
      if (t > step.t1()) break;
      ts[n] = t;
      ++n;
      ++next_;
      if (n == kBlock) flush();
    }
    if (n > 0) flush();
    const double lo = std::max(step.t0(), t_start_), hi = std::min(step.t1(), t_end_);
    if (hi > lo) {
      if (!dynamics_.apparent_varies(step.phase())) {
        add_time(step.phase(), hi - lo);
      } else {
        // The smooth phase of a regularised law, slip without friction: the time in each
        // apparent phase, from the midpoints of kSmoothParts equal parts of the piece (a piece is
        // at most T/16, so the times are good to about 1/500 of a period).
        constexpr int kSmoothParts = 16;
        const double h = (hi - lo) / kSmoothParts;
        for (int i = 0; i < kSmoothParts; ++i)
          add_time(dynamics_.apparent(Phase::smooth, step.state(lo + (i + 0.5) * h).to_array()), h);
      }
    }
    return true;
  }

  bool on_event(const Event& event, const State&, const State&) override {
    if (event.t >= t_start_ && event.t < t_end_) result_.events.push_back(event);
    return true;
  }

 private:
  void add_time(Phase phase, double dt) {
    switch (phase) {
      case Phase::stick:
        result_.stick_time += dt;
        break;
      case Phase::slip_positive:
        result_.slip_positive_time += dt;
        break;
      case Phase::slip_negative:
        result_.slip_negative_time += dt;
        break;
      case Phase::flight:
        result_.flight_time += dt;
        break;
      case Phase::smooth:
        break;  // apparent phases only
    }
  }

  const Dynamics<R> dynamics_;
  const double period_, t_start_, t_end_;
  const int per_period_;
  const long total_;  // samples to record
  long next_ = 0;
  Result& result_;
};

/// The samples, events and phase times after the first `integrated` of `periods` periods from
/// t0, repeated: the steady state was confirmed periodic over them (its period map's residual
/// below numerics.steady_tol), so each later period is the first ones again, with t and the
/// cyclic phi moved on by `drift` [rad] per `integrated` periods. False: `cancelled` said stop
/// (polled once per repeat; a million samples of a long window take a while).
template <class R>
bool repeat_periods(Result& result, double t0, double period, int integrated, int periods,
                    int per_period, bool all_samples, double drift,
                    const std::function<bool()>& cancelled) {
  const double t_repeat = t0 + integrated * period;
  std::vector<Event> events;
  for (const Event& e : result.events)
    if (e.t < t_repeat) events.push_back(e);
  const std::size_t n_events = events.size();
  Samples& s = result.samples;
  // Integration may have stopped just past the repeat's first sample: the repeat starts there.
  const std::size_t n = all_samples ? static_cast<std::size_t>(integrated) * per_period : 1;
  if (s.size() > n) {
#define OSCIDRUM_TRIM(type, name, unit, label, description) s.name.resize(n);
    OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_TRIM)
#undef OSCIDRUM_TRIM
  }
  const int copies = periods / integrated;
  if (copies <= 1) return true;
  for (int k = 1; k < copies; ++k) {
    if (cancelled && cancelled()) return false;
    for (std::size_t i = 0; i < n_events; ++i) {
      Event e = events[i];
      e.t += k * integrated * period;
      events.push_back(e);
    }
    if (!all_samples || s.size() < n) continue;
    // Each column grows by its first n entries, copied as a block (element by element, with a
    // capacity test per entry, the copies were 3 % of a case from rest).
    const std::size_t first = static_cast<std::size_t>(k) * n;
#define OSCIDRUM_REPEAT(type, name, unit, label, description) \
  s.name.resize(first + n);                                   \
  std::copy_n(s.name.begin(), n, s.name.begin() + static_cast<std::ptrdiff_t>(first));
    OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_REPEAT)
#undef OSCIDRUM_REPEAT
    for (std::size_t j = 0; j < n; ++j) {
      s.t[first + j] = sample_time(t0, static_cast<long>(first + j), period, per_period);
      s.phi[first + j] += k * drift;
    }
  }
  result.events = std::move(events);
  const double scale = static_cast<double>(copies);
  result.stick_time *= scale;
  result.slip_positive_time *= scale;
  result.slip_negative_time *= scale;
  result.flight_time *= scale;
  return true;
}

}  // namespace sampling

/// Integrate `flow` from its current time t0 (a period boundary) over `periods` excitation
/// periods, writing result.samples (t_j = t0 + j T / samples_per_period, j = 0 ... n-1), the
/// events in [t0, t0 + periods T) into result.events, the phase times, sample_periods,
/// samples_per_period and switches_per_period. Returns how the flow ended.
/// With all_samples false only the first sample (j = 0: the state at t0, where the metrics and a
/// neighbour's continuation start) is recorded; the integration, the events and the phase times
/// are the same.
/// `record` (may be null; only where the flow was just restarted at t0): the first
/// `record_periods` periods, [t0, t0 + record_periods / f], are also recorded for the steady
/// metrics (src/drivers/period_recording.hpp), on the same integration; cleared unless the
/// flow reached the end.
/// `confirm` (may be empty): called when the flow has integrated the first `record_periods`
/// periods (the flow stands there); when it returns false the sampling stops there and returns
/// FlowStop::observer (what was sampled so far is left in `result`, the recording cleared).
/// When it returns true the steady state is periodic over those periods: the later periods are
/// not integrated but repeat them (sampling::repeat_periods), and the flow stays at their end.
template <class R>
FlowStop sample_periods(BasicFlow<R>& flow, int periods, int samples_per_period, Result& result,
                        bool all_samples = true, recording::Recording* record = nullptr,
                        int record_periods = 1, const std::function<bool()>& confirm = {}) {
  const double t0 = flow.t();
  const auto start = flow.state().to_array();
  result.sample_periods = periods;
  result.samples_per_period = samples_per_period;
  sampling::Sampler<R> sampler(flow, t0, periods, samples_per_period, all_samples, result);
  const double t_end = t0 + periods * flow.model().period();
  FlowStop stop;
  if (record != nullptr) {
    // The span compute_metrics reads: t0 + p / f, p the multiplicity (the same expression).
    recording::Recorder<R> recorder(flow.model(), flow.options().baumgarte, t0,
                                    t0 + record_periods / result.frequency,
                                    std::move(record->pieces));
    const auto x = flow.state().to_array();
    recorder.out.start.assign(x.begin(), x.end());
    recorder.out.phase = flow.phase();
    ObserverPair<R> both(sampler, recorder);
    // Ending an advance inside a step leaves the step pending (the integration goes on with the
    // same steps): stopping at the recording's end changes nothing that follows.
    stop = flow.advance(confirm ? t0 + record_periods / result.frequency : t_end, &both);
    *record = std::move(recorder.out);
  } else {
    stop = flow.advance(confirm ? t0 + record_periods * flow.model().period() : t_end, &sampler);
  }
  if (stop == FlowStop::reached && confirm) {
    if (!confirm()) {
      stop = FlowStop::observer;
    } else if (periods % record_periods == 0) {
      if (!sampling::repeat_periods<R>(result, t0, flow.model().period(), record_periods, periods,
                                       samples_per_period, all_samples,
                                       Dynamics<R>::cyclic_drift(flow.state().to_array(), start),
                                       flow.options().cancelled))
        stop = FlowStop::cancelled;
    } else {
      stop = flow.advance(t_end, &sampler);
    }
  }
  if (record != nullptr && stop != FlowStop::reached) recording::clear(*record);
  long switches = 0;
  for (const Event& e : result.events)
    if (e.kind != EventKind::contact_lost) ++switches;
  result.diagnostics.switches_per_period = static_cast<double>(switches) / periods;
  return stop;
}

}  // namespace oscidrum::detail
