// oscidrum/simulate.hpp: event-driven hybrid integration from rest to the steady state.
#pragma once

#include <functional>

#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// Called once per integrated excitation period with the period index and the current
/// period-to-period change; return false to cancel (the result then has status
/// max_periods_reached and a message saying it was cancelled).
using ProgressCallback = std::function<bool(int period, double change)>;

/// Integrate `model` from rest at the bottom of the trough (Model::initial_state) with
/// Dormand-Prince 5(4) and dense output, locating stick/slip events by root finding on the dense
/// output, until the state at t = n / f repeats (Numerics::steady_tol, multiplicity up to
/// Numerics::max_multiplicity); then sample output_periods * multiplicity steady periods.
/// Never throws for numerical trouble: that is reported in Result::status.
Result simulate(const Model& model, const ProgressCallback& progress = {});

/// Convenience: validate `c` (throws oscidrum::Error) and simulate.
Result simulate(const Case& c, const ProgressCallback& progress = {});

}  // namespace oscidrum
