// Internal: the transient steady-state search, a driver on the flow. Integrates period by period
// until the state at t = n T repeats (Numerics::steady_tol, multiplicity up to
// Numerics::max_multiplicity), and tells the other ways a run can end.
#pragma once

#include <functional>
#include <string>

#include "oscidrum/flow.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum::detail {

/// How the search ended. On Status::steady_state or max_periods_reached, the flow stands at the
/// boundary t = n T where sampling starts.
struct SearchOutcome {
  Status status = Status::steady_state;
  std::string message;
  int multiplicity = 0;              ///< steady period in excitation periods (0: none found)
  int periods = 0;                   ///< boundary index n reached
  double final_change = 0.0;         ///< last period-to-period change (scaled) [-]
  std::vector<Event> recent_events;  ///< the last events before a stop other than steady/max
};

/// Run the search on `flow` (reset by the caller at t = 0, or standing at a later period boundary:
/// the periods are counted from there). `progress` is called once per period.
/// It gives up after `budget` periods (0: numerics.max_periods); `spent` > 0 periods were already
/// integrated by shooting before it fell back, and the message says so.
SearchOutcome find_steady_state(Flow& flow, const ProgressCallback& progress, int budget = 0,
                                int spent = 0);

}  // namespace oscidrum::detail
