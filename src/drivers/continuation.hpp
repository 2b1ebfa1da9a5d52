// Internal: continuation in studies (docs/periodic.md, "Continuation in studies"). A case of a
// study may start shooting from the steady state of its neighbour, the case before it in its
// chain, instead of from a short transient from rest.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum::detail {

/// A neighbour's steady state at its section, as a start for shooting: the roller's state vector
/// and the phase of the sample there (the roller maps it to a phase the new case can be in).
struct WarmStart {
  std::vector<double> state;  ///< the roller's state components (Dynamics<R>::Vector)
  Phase phase = Phase::stick;
};

/// The state of a steady state at its section (the first sample, t0 a period boundary) as a
/// start for a neighbouring case; empty unless `result` is a period-1 steady state with samples.
std::optional<WarmStart> orbit_start(const Model& model, const Result& result);

/// simulate(), but with numerics.method = shooting and `warm` given, Newton starts from `warm`
/// first; when that fails (Newton, the orbit's confirmation, or the flow from it), the case runs
/// exactly as simulate() runs it. Diagnostics::warm_start says which happened. The transient
/// method ignores `warm` (it always integrates from rest).
/// all_samples false: result.samples holds only the first sample (the steady state at its
/// section, enough for compute_metrics and orbit_start); every other number is the same.
Result simulate_from(const Model& model, const ProgressCallback& progress,
                     const std::function<bool()>& cancelled, const WarmStart* warm,
                     bool all_samples = true);

}  // namespace oscidrum::detail
