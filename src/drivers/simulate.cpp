// simulate (oscidrum/simulate.hpp): the flow from rest, the transient steady-state search and
// the sampling of the steady state, composed.
#include "oscidrum/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drivers/sampling.hpp"
#include "drivers/steady_state.hpp"
#include "oscidrum/flow.hpp"

namespace oscidrum {
namespace {

Status status_of(FlowStop stop) {
  switch (stop) {
    case FlowStop::contact_lost:
      return Status::contact_lost;
    case FlowStop::chattering:
      return Status::chattering;
    case FlowStop::non_finite:
      return Status::non_finite;
    case FlowStop::invalid_geometry:
      return Status::invalid_geometry;
    case FlowStop::budget_exceeded:
      return Status::budget_exceeded;
    default:
      return Status::cancelled;
  }
}

}  // namespace

Result simulate(const Model& model, const ProgressCallback& progress,
                const std::function<bool()>& cancelled) {
  FlowOptions options = FlowOptions::from(model);
  options.cancelled = cancelled;
  Flow flow(model, options);
  flow.reset(0.0, model.initial_state(), initial_phase(model));

  Result result;
  result.frequency = model.parameters().roller.f;
  const detail::SearchOutcome search = detail::find_steady_state(flow, progress);
  result.status = search.status;
  result.message = search.message;
  Diagnostics& d = result.diagnostics;
  d.final_change = search.final_change;
  d.periods_simulated = search.periods;
  if (search.status == Status::steady_state) {
    d.periods_to_steady = search.periods;
    d.multiplicity = search.multiplicity;
  }

  // Sample the steady state (or, when no steady state was found, the periods that follow, for
  // inspection: they carry no metrics).
  if (search.status == Status::steady_state || search.status == Status::max_periods_reached) {
    const Numerics& num = model.parameters().numerics;
    const int periods = num.output_periods * std::max(1, search.multiplicity);
    const FlowStop stop = detail::sample_periods(flow, periods, num.samples_per_period, result);
    d.periods_simulated = search.periods + periods;
    if (stop != FlowStop::reached) {  // the steady state did not survive its own sampling
      result.status = status_of(stop);
      result.message = flow.message();
    }
  } else {
    result.events = search.recent_events;
  }

  const FlowCounters& c = flow.counters();
  d.steps = c.steps;
  d.rhs_evaluations = c.rhs_evaluations;
  d.events = c.events;
  d.switches = c.switches;
  d.reversals = c.reversals;
  d.inconsistent_slip_ends = c.inconsistent_slip_ends;
  d.max_slip_residual = c.max_slip_residual;
  d.min_N = std::isfinite(c.min_N) ? c.min_N : 0.0;
  // Odeint retries rejected steps internally. Dormand-Prince with FSAL costs one evaluation per
  // (re)start and six per attempted step, and nothing else calls the right-hand side, so the
  // attempts follow from the count.
  const long starts = 1 + c.events;
  const long attempts = (c.rhs_evaluations - starts) / 6;
  d.rejected_steps = std::max(0L, attempts - c.steps);
  return result;
}

Result simulate(const Case& c, const ProgressCallback& progress,
                const std::function<bool()>& cancelled) {
  const Model model(c);
  return simulate(model, progress, cancelled);
}

}  // namespace oscidrum
