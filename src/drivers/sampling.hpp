// Internal: the sampling driver. Records whole excitation periods of a trajectory into a Result:
// uniform samples, the events and the time spent in each phase.
#pragma once

#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum::detail {

/// Integrate `flow` from its current time t0 (a period boundary) over `periods` excitation
/// periods, writing result.samples (t_j = t0 + j T / samples_per_period, j = 0 ... n-1), the
/// events in [t0, t0 + periods T) into result.events, the phase times, sample_periods,
/// samples_per_period and switches_per_period. Returns how the flow ended.
/// With all_samples false only the first sample (j = 0: the state at t0, where the metrics and a
/// neighbour's continuation start) is recorded; the integration, the events and the phase times
/// are the same.
FlowStop sample_periods(Flow& flow, int periods, int samples_per_period, Result& result,
                        bool all_samples = true);

/// One row of the samples: the state, the drum motion (14), (17), (18), the contact forces
/// (24)-(26), the slip velocity (13) and the excitation (5), (6) at time t in the given phase.
void append_sample(const Model& model, double baumgarte, double t, const State& q, Phase phase,
                   Samples& samples);

}  // namespace oscidrum::detail
