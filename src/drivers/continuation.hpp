// Internal: continuation in studies (docs/periodic.md, "Continuation in studies"). A case of a
// study may start shooting from the steady state of its neighbour, the case before it in its
// chain, instead of from a short transient from rest.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/result.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum::detail {

namespace recording {
struct Recording;  // drivers/period_recording.hpp
}  // namespace recording

/// A neighbour's steady state at its section, as a start for shooting: the roller's state vector
/// and the phase of the sample there (the roller maps it to a phase the new case can be in).
struct WarmStart {
  std::vector<double> state;  ///< the roller's state components (Dynamics<R>::Vector)
  Phase phase = Phase::stick;
  /// A second start (same phase) tried when Newton fails from `state`, before the cold start:
  /// the neighbour's own state behind a predicted one (secant_start). Empty: none.
  std::vector<double> then;
  /// The contraction of the residual by the neighbour's first chord step, when it had one
  /// (negative: unknown). Predicts this case's: when that predicts convergence, the step is
  /// confirmed on the recorded period directly, without a plain period map first.
  double contraction = -1.0;
  /// A study's case: a warm start that fails (also one that spends numerics.max_periods) leaves
  /// the cold start all of numerics.max_periods, so that the case's status does not depend on
  /// continuation. False (the diagram, which follows the attractor from the previous value's
  /// state with a transient of its own; the check of a motion by shooting): the cold start gets
  /// what the warm start left, and a warm start that spends the budget ends the run.
  bool cold_start_budget = false;
  /// False: a warm start that fails ends the run (status max_periods_reached, no samples)
  /// instead of the cold start from rest (the diagram follows the previous value's attractor
  /// with a transient of its own: a start from rest jumped to another attractor).
  bool cold_start = true;
};

/// The state of a steady state at its section (the first sample, t0 a period boundary) as a
/// start for a neighbouring case; empty unless `result` is a period-1 steady state with samples.
std::optional<WarmStart> orbit_start(const Model& model, const Result& result);
/// The same, with the contraction of the warm start `record` was recorded after
/// (recording::Recording::chord_contraction: simulate_from's record of `result`).
std::optional<WarmStart> orbit_start(const Model& model, const Result& result,
                                     const recording::Recording& record);

/// A secant predictor along a chain: the start for case c0 extrapolated from the steady states
/// w2 (of case c2) and w1 (of c1, the predecessor): w1 + s (w1 - w2), s the step from c1 to c0
/// over the step from c2 to c1 in the first parameter in which c0 and c1 differ. Empty when the
/// two states are in different phases, the steps do not continue one another (s outside
/// (0, kMaxSecantRatio]) or a value is not finite: the predecessor's state is then the start.
/// The prediction keeps w1's state as its `then`: a prediction that misleads Newton costs its
/// attempt, not a cold start.
inline constexpr double kMaxSecantRatio = 1.5;
std::optional<WarmStart> secant_start(const WarmStart& w2, const WarmStart& w1, const Case& c2,
                                      const Case& c1, const Case& c0, const WarmStart* w3 = nullptr,
                                      const Case* c3 = nullptr);

/// A start from rest that loses contact before a steady state is found is run again with the
/// excitation ramped in over this many periods (numerics.start_ramp_periods), unless it had a
/// ramp already (simulate; the brute-force diagram's transient from rest likewise).
inline constexpr int kContactRetryRampPeriods = 20;

/// simulate(), but with numerics.method = shooting and `warm` given, Newton starts from `warm`
/// first; when that fails (Newton, the orbit's confirmation, or the flow from it), the case runs
/// exactly as simulate() runs it. Diagnostics::warm_start says which happened. The transient
/// method ignores `warm` (it always integrates from rest).
/// all_samples false: result.samples holds only the first sample (the steady state at its
/// section, enough for compute_metrics and orbit_start); every other number is the same.
/// `record` (may be null) receives the steady period recorded for the metrics when the sampling
/// of a shooting orbit made it on the way (detail::compute_metrics with it integrates nothing
/// again; the same numbers); else it is emptied.
Result simulate_from(const Model& model, const ProgressCallback& progress,
                     const std::function<bool()>& cancelled, const WarmStart* warm,
                     bool all_samples = true, recording::Recording* record = nullptr);

}  // namespace oscidrum::detail
