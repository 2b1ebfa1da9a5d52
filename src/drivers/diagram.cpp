// The brute-force bifurcation diagram (oscidrum/diagram.hpp). At each value of the parameter the
// motion starts from the state the previous value ended in. Its attractor is sought first as a
// stable periodic orbit by shooting from that state (simulate_from, as a study's continuation:
// near a bifurcation a multiplier near the unit circle makes the transient approach it over
// thousands of periods); without one, the transient from that state is integrated over `discard`
// periods and one period sampled (the components' ranges, which scale the verdict's distances).
// Either way analyze_motion examines `periods` further periods; its stroboscopic points become
// every output column by the roller's sampling. A start from rest (the first value, shooting's
// fallback, after a flow that stopped) is run's: under the case's start ramp, or retried with one
// when it loses contact; a value continued from the previous state runs without the ramp.
#include "oscidrum/diagram.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "drivers/continuation.hpp"
#include "drivers/sampling.hpp"
#include "drivers/steady_state.hpp"
#include "drivers/varied_parameter.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/flow.hpp"
#include "oscidrum/model.hpp"
#include "roller/rollers.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

// Samples per period of the sampled period whose ranges scale the verdict (as simulate's default
// output resolution does not matter here: only the ranges are read).
constexpr int kScaleSamples = 64;

// The periods simulate_from may spend on shooting at a value (numerics.max_periods): --discard,
// at least 100 (shooting's short transient and Newton's period maps), below 400 (from 400 on
// simulate examines a motion without a steady state itself, which the diagram does after its
// own transient).
constexpr int kMinShootingPeriods = 100;
constexpr int kMaxShootingPeriods = 399;

// Where the next value starts: the last stroboscopic state and its phase (empty: from rest).
struct Start {
  std::vector<double> state;
  Phase phase = Phase::stick;
};

// A transient integrated at a value without a stable periodic orbit: how it ended.
struct Transient {
  FlowStop stop = FlowStop::reached;
  double periods = 0.0;  // excitation periods integrated [-]
  std::string message;   // the flow's, when it stopped
};

// The transient under `model` from `x` in `phase` at t = 0: `skip` periods dropped, one sampled
// into `sampled` (the components' ranges that scale the verdict).
template <class R>
Transient transient(const Model& model, const typename detail::Dynamics<R>::Vector& x, Phase phase,
                    int skip, const std::function<bool()>& cancelled, Result& sampled) {
  FlowOptions fo = FlowOptions::from(model);
  fo.cancelled = cancelled;
  BasicFlow<R> flow(model, fo);
  flow.reset(0.0, R::State::from_array(x), phase);
  const double T = model.period();
  sampled = Result{};
  sampled.frequency = model.parameters().roller.f;
  FlowStop stop = flow.advance(skip * T);
  if (stop == FlowStop::reached) stop = detail::sample_periods(flow, 1, kScaleSamples, sampled);
  return {stop, flow.t() / T, stop == FlowStop::reached ? std::string() : flow.message()};
}

// What a start from rest that lost contact without a ramp says of its retry (as run's message).
std::string ramp_retry_note(const std::string& lost) {
  return "; started from rest with the excitation ramped in over " +
         std::to_string(detail::kContactRetryRampPeriods) +
         " periods, as run does: without a ramp the start lost contact" +
         (lost.empty() ? std::string() : " (" + lost + ")");
}

// Gross slip, as run's search calls it (the transient method's gross-slip test): the drum slips
// the way its driving torque pushes at every stroboscopic point of the window, and phi' grows in
// every period, by no less at the end than at the start (kUnfadingGrowth). Its points neither
// recur nor converge, and the window read a torus ("quasi_periodic") or undecided where `run`
// says gross_slip; or "converging" (period 1 or 2): the other coordinates of a spinning drum
// settle geometrically while phi' grows by the same step every period. A motion that recurs or
// converges to an orbit cannot pass the test (phi' would grow without bound), so it is taken
// whatever the other verdict.
template <class R>
void gross_slip_verdict(const detail::Dynamics<R>& dyn, MotionAnalysis& m) {
  using Dyn = detail::Dynamics<R>;
  using Vector = typename Dyn::Vector;
  if (m.section.size() < 3) return;
  const std::size_t n = m.section.size();
  const auto at = [&](std::size_t k) {
    Vector x{};
    std::copy(m.section[k].begin(), m.section[k].end(), x.begin());
    return x;
  };
  double hold = 0.0;
  // Points in flight say nothing of the slip: the contact phase is the last point's in contact,
  // or where every point is in flight (a drum spinning through its flights: "a torus" before),
  // the slip the driving torque pushes.
  Phase contact = Phase::flight;
  for (std::size_t k = n; k-- > 0;)
    if (m.section_phase[k] != Phase::flight) {
      contact = m.section_phase[k];
      break;
    }
  if (contact == Phase::flight) {
    const double MMd = dyn.model().parameters().MMd;
    if (MMd == 0.0) return;
    contact = MMd > 0.0 ? Phase::slip_negative : Phase::slip_positive;
  }
  const int s = dyn.pushed_slip(contact, at(n - 1), &hold);
  if (s == 0) return;
  for (std::size_t k = 1; k < n; ++k)
    if ((m.section_phase[k] != contact && m.section_phase[k] != Phase::flight) ||
        !(Dyn::spin_up(at(k), at(k - 1), s, 1) > 0.0))
      return;
  const double first = Dyn::spin_up(at(1), at(0), s, 1);
  const double last = Dyn::spin_up(at(n - 1), at(n - 2), s, 1);
  if (!(last >= detail::steady::kUnfadingGrowth * first)) return;
  m.kind = "gross_slip";
  m.evidence = detail::format(
      "gross slip: the drum spins (slipping the way the driving torque pushes at each of the %.0f "
      "stroboscopic points, phi' grows in every period, by %.3g rad/s in the last): friction holds "
      "less than the driving torque on this motion (mu W r = %.6g N m); `run` stops such a case "
      "as gross_slip",
      static_cast<double>(n), last, hold);
}

template <class R>
DiagramValue value_at(const Case& c, const Field& field, double q, Start& start,
                      const DiagramOptions& o, long& periods_integrated) {
  using Dyn = detail::Dynamics<R>;
  using Vector = typename Dyn::Vector;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  DiagramValue v;
  v.parameter = q;
  Case ck = c;
  detail::set_varied(ck, field, q, o.MMd_fraction);
  // The attractor as a periodic orbit first: shooting from the previous value's last state (the
  // first value: simulate's start), with a budget of periods below the one at which simulate
  // examines a motion itself (the transient below does that here).
  ck.numerics.method = SteadyMethod::shooting;
  ck.numerics.max_periods = std::clamp(o.discard, kMinShootingPeriods, kMaxShootingPeriods);
  // The start ramp (numerics.start_ramp_periods) brings the excitation in from rest: `rest`
  // starts from rest with it. A value started from the previous value's state runs on the full
  // excitation from t = 0 (`model`, no ramp): under the ramp its excitation climbed from zero
  // again, and its points with it. The examination runs under `model` too: it starts past any
  // ramp, where the two agree.
  Case steady = ck;
  steady.numerics.start_ramp_periods = 0;
  const Model rest(ck), model(steady);
  const int ramp = ck.numerics.start_ramp_periods;
  const double T = model.period();
  v.excitation_period = T;
  const bool first = start.state.empty();
  Result sampled;
  if (first) {
    sampled = detail::simulate_from(rest, {}, o.cancelled, nullptr);
    periods_integrated += sampled.diagnostics.periods_simulated;
  } else {
    // Where Newton from that state fails, the transient from it follows below, not a start from
    // rest: the sweep follows its attractor (a start from rest jumped to another one, and a finer
    // step gave another picture).
    detail::WarmStart warm{start.state, start.phase, {}};
    warm.cold_start = false;
    sampled = detail::simulate_from(model, {}, o.cancelled, &warm);
    periods_integrated += sampled.diagnostics.periods_simulated;
  }
  const Dyn dyn(model, FlowOptions::from(model).baumgarte);
  std::string note;  // a start from rest ramped in after it lost contact
  if (sampled.status == Status::steady_state) {
    v.shooting = true;
    v.from_rest = first || sampled.diagnostics.warm_start != 1;
    // simulate's retry of a start from rest that lost contact (its ramp is in the diagnostics).
    if (v.from_rest && ramp == 0 && sampled.diagnostics.start_ramp_periods > 0)
      note = ramp_retry_note("");
  } else {
    if (sampled.status == Status::cancelled) return v;
    // No stable periodic orbit found: the transient from the previous value's last state (or
    // from rest), `discard` periods dropped, one sampled (the ranges that scale the verdict).
    v.from_rest = first;
    Transient tr;
    if (first) {
      // From rest as run starts: under the case's ramp, run through before `discard` periods
      // are dropped; without one, again with the excitation ramped in when the start loses
      // contact (at once when shooting's start from rest did: simulate's retry).
      const auto from_rest = [&](int periods) {
        Case ramped = ck;
        ramped.numerics.start_ramp_periods = periods;
        const Model m(ramped);
        return transient<R>(m, dyn.initial_state(), dyn.initial_phase(), periods + o.discard,
                            o.cancelled, sampled);
      };
      const bool retried = ramp == 0 && sampled.diagnostics.start_ramp_periods > 0;
      tr = from_rest(retried ? detail::kContactRetryRampPeriods : ramp);
      if (retried) note = ramp_retry_note("");
      if (ramp == 0 && !retried && tr.stop == FlowStop::contact_lost) {
        periods_integrated += static_cast<long>(std::ceil(tr.periods - 1e-9));
        note = ramp_retry_note("after " + std::to_string(static_cast<int>(tr.periods)) +
                               " periods: " + tr.message);
        tr = from_rest(detail::kContactRetryRampPeriods);
      }
    } else {
      // A phase the new value cannot be in (as a study's warm start maps it), and the state
      // made consistent with it (the constraints of stick depend on the parameters).
      const Phase phase = dyn.flow_phase(start.phase);
      Vector x{};
      std::copy(start.state.begin(), start.state.end(), x.begin());
      tr = transient<R>(model, dyn.consistent(x, phase), phase, o.discard, o.cancelled, sampled);
    }
    periods_integrated += static_cast<long>(std::ceil(tr.periods - 1e-9));
    if (tr.stop != FlowStop::reached) {
      start = {};  // the next value from rest
      v.motion.kind = "undecided";
      // No exponent was computed (0 would read as a torus's).
      v.motion.lyapunov = v.motion.lyapunov_first = v.motion.lyapunov_second = kNaN;
      v.motion.evidence = std::string("the flow stopped (") + to_string(tr.stop) + ") after " +
                          std::to_string(static_cast<int>(tr.periods)) + " periods: " + tr.message +
                          note;
      return v;
    }
  }
  v.motion = analyze_motion(model, sampled, o.periods, o.cancelled);
  periods_integrated += v.motion.periods;
  // The flow stopped within the examination: its exponent was not computed.
  if (v.motion.periods < o.periods)
    v.motion.lyapunov = v.motion.lyapunov_first = v.motion.lyapunov_second = kNaN;
  v.motion.evidence += note;
  gross_slip_verdict<R>(dyn, v.motion);
  if (v.motion.kind == "periodic") v.period = v.motion.recurrence;
  if (v.motion.kind == "converging") v.period = v.motion.converging_period;
  const double t0 = sampled.samples.t.front();
  for (std::size_t k = 1; k < v.motion.section.size(); ++k) {
    Vector x{};
    std::copy(v.motion.section[k].begin(), v.motion.section[k].end(), x.begin());
    dyn.sample(t0 + static_cast<double>(k) * T, x, v.motion.section_phase[k], v.section);
  }
  // The next value starts where this one ended, unless the flow stopped early.
  if (v.motion.periods == o.periods && !v.motion.section.empty())
    start = {v.motion.section.back(), v.motion.section_phase.back()};
  else
    start = {};
  v.motion.section.clear();
  v.motion.section_phase.clear();
  return v;
}

}  // namespace

const char* to_string(DiagramSweep sweep) {
  switch (sweep) {
    case DiagramSweep::up:
      return "up";
    case DiagramSweep::down:
      return "down";
    case DiagramSweep::both:
      return "both";
  }
  return "?";
}

Diagram bifurcation_diagram(const Case& c, const DiagramOptions& o) {
  const Field& field = detail::varied_field(c, o.key, o.from, o.to, "diagram", o.MMd_fraction);
  if (!(o.from < o.to))
    // The values named as the rule names them ("got 5000 and 1000" read as end 5000, start
    // 1000), in the unit they are typed in (soil.G in MN/m^2, not 1e+08 without a unit).
    throw Error(
        "diagram: the range's end (to, --to) must be > its start (from, --from); got "
        "from = " +
            detail::quoted_value(field, o.from) + " and to = " + detail::quoted_value(field, o.to) +
            " (a diagram visits its range upwards; sweep \"down\" (--sweep down) visits it "
            "downwards)",
        o.key, o.to);
  if (o.steps < 1 || o.steps > 100000)
    throw Error("diagram: steps (--steps) must be in [1, 100000]; got " + std::to_string(o.steps),
                "steps", o.steps);
  if (o.discard < 0 || o.discard > 1000000)
    throw Error(
        "diagram: discard (--discard) must be in [0, 1000000]; got " + std::to_string(o.discard),
        "discard", o.discard);
  if (o.periods < 20 || o.periods > 100000)
    throw Error(
        "diagram: periods (--periods) must be in [20, 100000]; got " + std::to_string(o.periods),
        "periods", o.periods);
  const Model model(c);  // validates the case
  const auto t_start = std::chrono::steady_clock::now();
  Diagram d;
  d.key = o.key;
  d.unit = field.unit;
  // The values in the order visited: (parameter, direction).
  std::vector<std::pair<double, int>> order;
  const auto value = [&](int i) {
    return i == o.steps ? o.to : o.from + (o.to - o.from) * i / o.steps;
  };
  if (o.sweep != DiagramSweep::down)
    for (int i = 0; i <= o.steps; ++i) order.push_back({value(i), 1});
  if (o.sweep != DiagramSweep::up)
    for (int i = o.steps; i >= 0; --i) order.push_back({value(i), -1});
  // Every value the diagram visits is a valid case, checked before any work: soil.G on Table 2
  // soil from 5 to 70 MN/m^2 in 3 steps stopped at 26.7 MN/m^2 with the field's message alone,
  // not saying that the diagram's steps put it there (continue checks its whole range alike).
  for (int i = 0; i <= o.steps; ++i) {
    const std::string why = detail::invalid_at(c, field, value(i), o.MMd_fraction);
    if (!why.empty())
      throw Error("diagram: " + o.key + " = " + detail::quoted_value(field, value(i)) + ", value " +
                      std::to_string(i) + " of --steps " + std::to_string(o.steps) + " from " +
                      detail::quoted_value(field, o.from) + " to " +
                      detail::quoted_value(field, o.to) + ": the case is not valid there (" + why +
                      "); choose --from, --to and --steps whose every value is valid",
                  o.key, value(i));
  }
  Start start;
  const int total = static_cast<int>(order.size());
  detail::with_roller(model, [&]<class R>() {
    for (const auto& [q, direction] : order) {
      DiagramValue v = value_at<R>(c, field, q, start, o, d.periods_integrated);
      v.direction = direction;
      if (o.cancelled && o.cancelled()) {
        d.cancelled = true;
        break;
      }
      d.values.push_back(std::move(v));
      if (o.on_value) o.on_value(static_cast<int>(d.values.size()), total, q);
    }
  });
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return d;
}

}  // namespace oscidrum
