// oscidrum/branch.hpp: a branch of periodic orbits followed through a parameter (pseudo-arclength
// continuation of the shooting problem P(z; q) = z), each orbit with its Floquet multipliers and
// CCC metrics, and the bifurcations on it: folds, period doublings, Neimark-Sacker points, branch
// points and the non-smooth ones of the hybrid system (a stick, slip or flight phase appearing or
// vanishing). docs/bifurcations.md.
#pragma once

#include <complex>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "oscidrum/floquet.hpp"
#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/state.hpp"

namespace oscidrum {

/// What to follow and how. Steps are in units of the parameter's range |to - from| measured
/// along the branch (the arclength of the scaled state and parameter, docs/bifurcations.md).
struct BranchOptions {
  std::string key;    ///< the parameter: a real key of the field table in effect in the case
  double from = 0.0;  ///< the branch starts at the steady state found here [key's SI unit]
  double to = 0.0;    ///< the end of the range [key's SI unit]
  double initial_step = 0.02;  ///< first arclength step, as a fraction of |to - from| [-]
  double max_step = 0.05;      ///< largest arclength step [-]
  double min_step = 1e-6;      ///< smallest arclength step: below it the branch ends [-]
  /// Bifurcations are located to this fraction of |to - from| in the parameter [-].
  double tolerance = 1e-6;
  int max_points = 2000;  ///< points on the branch, at most
  bool metrics = true;    ///< compute the CCC metrics of every point
  int harmonics = 10;     ///< harmonics n = 0 ... N in the metrics
  /// Branch switching at period doublings: 0 none, 1 onto the period-2p branch, 2 also from
  /// it onto 4p, ... (at most 5)
  int switch_depth = 1;
  /// MMd = MMd_fraction * M0 at every value of the parameter, with the M0 in effect there (it
  /// follows roller.M0, or roller.f with roller.unbalance), as a study takes a case file's
  /// MMd_fraction; NaN (the default): the case's MMd throughout [-]
  double MMd_fraction = std::numeric_limits<double>::quiet_NaN();
  /// Polled during every period map; true stops the continuation (BranchEnd::cancelled).
  std::function<bool()> cancelled;
  /// Called after every accepted point (points so far, its parameter); for progress lines.
  std::function<void(int, double)> on_point;
};

/// One periodic orbit on a branch.
struct BranchPoint {
  double parameter = 0.0;      ///< q [key's SI unit]
  double arclength = 0.0;      ///< along the branch, in the scaled (z, q) of the corrector [-]
  int multiplicity = 1;        ///< p: the orbit repeats every p excitation periods
  Phase phase = Phase::stick;  ///< the phase at the section t0
  std::vector<double> state;   ///< the roller's state at the section (its components)
  /// The section's time t0 [s]: the orbit passes through `state` at t0 (the excitation's phase
  /// there is nu t0); with `state` and `phase` the orbit's initial condition.
  double section_time = 0.0;
  Floquet floquet;       ///< the multipliers of P^p at the orbit
  int unstable = 0;      ///< multipliers outside the unit circle (by more than 1e-6) [-]
  double dq_ds = 0.0;    ///< the tangent's parameter component (its sign changes at a fold) [-]
  double min_N = 0.0;    ///< smallest normal force at the step ends of one period [N]
  std::string sequence;  ///< the switches of one period in time order from the section
  int corrector_iterations = 0;              ///< Newton steps of the corrector for this point
  Metrics metrics = Metrics::unavailable();  ///< the CCC metrics (NaN when not computed)

  bool stable() const { return unstable == 0; }
};

/// The kinds of bifurcation a branch reports.
enum class BifurcationKind {
  fold,             ///< a real multiplier through +1 and the parameter turns back (saddle-node)
  branch_point,     ///< a real multiplier through +1 without a turn (pitchfork, transcritical)
  period_doubling,  ///< a real multiplier through -1 (flip): a period-2p orbit emanates
  neimark_sacker,   ///< a complex pair leaves the unit circle (torus)
  grazing,  ///< the switching sequence changes: a stick, slip or flight phase appears or vanishes
  /// Unilateral contact: the smallest normal force of the orbit reaches zero and the branch in
  /// contact ends there, no orbit near it continuing it (in pure rolling the orbit that lifts off
  /// is another one, docs/lift-off.md); the branch ends with BranchEnd::lift_off. (A flight phase
  /// that appears continuously along a branch is a grazing.)
  lift_off,
};

/// "fold", "branch_point", "period_doubling", "neimark_sacker", "grazing", "lift_off".
const char* to_string(BifurcationKind kind);

struct Bifurcation {
  BifurcationKind kind = BifurcationKind::fold;
  int after_point = 0;     ///< it lies between points after_point and after_point + 1
  double parameter = 0.0;  ///< where [key's SI unit]
  double tolerance = 0.0;  ///< it lies within this of `parameter` [key's SI unit]
  /// The critical multiplier at the located point (fold, branch point: the one nearest +1;
  /// period doubling: nearest -1; Neimark-Sacker: the pair's member with positive imaginary
  /// part); 0 for grazing.
  std::complex<double> multiplier = 0.0;
  std::string description;  ///< what changes, in words
  /// A period doubling: the index in Branch::children of the branch switched onto here: the
  /// period-2p branch born there, or, where this branch's period-p orbit shrinks onto a period-p/2
  /// orbit (BranchEnd::period_halved), that period-p/2 branch towards `to` (-1: none, or not
  /// found).
  int child = -1;
};

/// Why a branch ended.
enum class BranchEnd {
  reached_end,     ///< the parameter reached `to`
  left_range,      ///< the branch turned back at a fold and left the range at `from`
  max_points,      ///< BranchOptions::max_points
  step_too_small,  ///< the corrector failed down to the smallest step (message says why)
  gross_slip,      ///< the stick phase vanished: the drum slips throughout, no orbit beyond
  start_failed,    ///< no periodic orbit to start from (message says why)
  cancelled,       ///< BranchOptions::cancelled returned true
  /// Unilateral contact: the orbit's smallest normal force reached zero and the corrector found
  /// no orbit beyond (the last bifurcation, lift_off, locates the point; message says where)
  lift_off,
  /// The period-p orbit shrank onto a period-p/2 orbit (the last bifurcation, a period doubling
  /// of that orbit met from the period-p side): beyond it the branch turns back through its own
  /// orbits shifted by p/2 periods; the period-p/2 branch towards `to` is its child
  period_halved,
};

/// "reached_end", "left_range", "max_points", "step_too_small", "gross_slip", "start_failed",
/// "cancelled", "lift_off", "period_halved".
const char* to_string(BranchEnd end);

struct Branch {
  std::string key;       ///< the parameter
  std::string unit;      ///< its SI unit (the field table's)
  int multiplicity = 1;  ///< p of its orbits
  std::vector<BranchPoint> points;
  std::vector<Bifurcation> bifurcations;  ///< in the order they were passed
  BranchEnd end = BranchEnd::reached_end;
  std::string message;   ///< how it ended, in words
  long period_maps = 0;  ///< period maps integrated (with and without sensitivities)
  double seconds = 0.0;  ///< wall time [s]
  /// The period-2p branches born at this branch's period doublings (Bifurcation::child), each
  /// followed from its doubling to the end of the range on its side.
  std::vector<Branch> children;
};

/// Follow the periodic orbits of `c` through `options.key` from `options.from` to `options.to`:
/// the steady state at `from` (simulate, numerics.method = shooting) is the first point;
/// pseudo-arclength continuation of its shooting problem follows it, stable or not, through
/// folds; bifurcations are detected between points from the multipliers, the tangent and the
/// switching sequence, and located by bisection along the branch to `options.tolerance`
/// (docs/bifurcations.md). Throws oscidrum::Error for a key that cannot be continued (not a real
/// field, a numerics.* key, without effect in `c`), `from` or `to` outside the key's rule, or bad
/// options.
Branch continue_branch(const Case& c, const BranchOptions& options);

}  // namespace oscidrum
