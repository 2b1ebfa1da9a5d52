// oscidrum/simulate.hpp: event-driven hybrid integration from rest to the steady state.
#pragma once

#include <functional>

#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// Called once per integrated excitation period with the period index and the current
/// period-to-period change; return false to cancel (the result then has status cancelled).
using ProgressCallback = std::function<bool(int period, double change)>;

/// Run the hybrid flow (oscidrum/flow.hpp) of `model` from rest at the bottom of the trough
/// (Model::initial_state) until the state at t = n / f repeats (Numerics::steady_tol,
/// multiplicity up to Numerics::max_multiplicity), then sample output_periods * multiplicity
/// steady periods. `cancelled` is polled at every integration step: returning true ends the run
/// promptly with status cancelled. Never throws for numerical trouble: that is reported in
/// Result::status (only Status::steady_state carries a steady state).
Result simulate(const Model& model, const ProgressCallback& progress = {},
                const std::function<bool()>& cancelled = {});

/// Convenience: validate `c` (throws oscidrum::Error) and simulate.
Result simulate(const Case& c, const ProgressCallback& progress = {},
                const std::function<bool()>& cancelled = {});

}  // namespace oscidrum
