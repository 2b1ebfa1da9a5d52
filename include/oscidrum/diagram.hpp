// oscidrum/diagram.hpp: the brute-force bifurcation diagram. The motion is followed through a row
// of values of one parameter, each value started from the state the previous one ended in (a
// quasi-static sweep, up, down or both, so that coexisting attractors and hysteresis show); at
// each value the attractor is reached (a stable periodic orbit by shooting from that state, else
// the transient over `discard` periods) and its stroboscopic points (every output column at
// t0 + k T) are kept with the motion's verdict (oscidrum/motion.hpp). The second view of a
// branch (oscidrum/branch.hpp): what the motion does, not which orbits exist
// (docs/bifurcations.md, "The brute-force diagram").
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "oscidrum/motion.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// The order in which the values are visited: up from `from` to `to`, down from `to` to `from`,
/// or both (up, then down from where the up sweep ended).
enum class DiagramSweep { up, down, both };

/// "up", "down", "both".
const char* to_string(DiagramSweep sweep);

struct DiagramOptions {
  std::string key;    ///< the parameter: a real key of the field table in effect in the case
  double from = 0.0;  ///< the smallest value [key's SI unit]
  double to = 0.0;    ///< the largest value (> from) [key's SI unit]
  int steps = 50;     ///< intervals between from and to: steps + 1 values per sweep [-]
  DiagramSweep sweep = DiagramSweep::up;
  /// Excitation periods of transient dropped at a value without a stable periodic orbit (>= 0;
  /// from rest after the start ramp, numerics.start_ramp_periods); also the budget of the
  /// search for one (numerics.max_periods, kept within [100, 399]) [-]
  int discard = 200;
  /// Stroboscopic points kept at each value, and the periods the verdict examines (>= 20) [-]
  int periods = 400;
  /// MMd = MMd_fraction * M0 at every value of the parameter, with the M0 in effect there (it
  /// follows roller.M0, or roller.f with roller.unbalance), as a study takes a case file's
  /// MMd_fraction; NaN (the default): the case's MMd throughout [-]
  double MMd_fraction = std::numeric_limits<double>::quiet_NaN();
  /// Polled at every integration step: true stops the diagram (Diagram::cancelled).
  std::function<bool()> cancelled;
  /// Called after every value (values done, values in all, its parameter); for progress lines.
  std::function<void(int, int, double)> on_value;
};

/// The motion at one value of the parameter.
struct DiagramValue {
  double parameter = 0.0;  ///< q [key's SI unit]
  int direction = 1;       ///< +1: visited on the way up, -1: on the way down
  /// True if the motion started from rest (the first value's transient, shooting's fallback,
  /// or the previous value's flow stopped), as simulate starts (numerics.start_ramp_periods, or
  /// a retry with a ramp when the start loses contact), false if from the previous value's last
  /// state (without the start ramp).
  bool from_rest = false;
  /// True if shooting found a stable periodic orbit here (the stroboscopic points are then on
  /// it from the first), false if the points follow `discard` periods of transient.
  bool shooting = false;
  double excitation_period = 0.0;  ///< T = 1 / f at this value [s]
  /// The verdict (MotionAnalysis::kind: periodic, converging, quasi_periodic, chaotic,
  /// undecided; and gross_slip: the drum spins up, docs/bifurcations.md) with its numbers; its
  /// section is moved into `section` below. Where the flow stopped before the exponent was computed
  /// (undecided, the evidence says why) lyapunov and its halves are NaN.
  MotionAnalysis motion;
  /// The period of the verdict: the recurrence p of a periodic motion, the p a converging motion
  /// approaches (0 if unknown), 0 otherwise [-].
  int period = 0;
  /// The stroboscopic points: every output column (OSCIDRUM_SAMPLE_COLUMNS) at t0 + k T,
  /// k = 1 ... periods, t0 the orbit's section or the end of the discarded transient (fewer if
  /// the flow stopped).
  Samples section;
};

struct Diagram {
  std::string key;                   ///< the parameter
  std::string unit;                  ///< its SI unit
  std::vector<DiagramValue> values;  ///< in the order visited
  bool cancelled = false;            ///< DiagramOptions::cancelled stopped it (values are partial)
  long periods_integrated = 0;       ///< excitation periods integrated in all [-]
  double seconds = 0.0;              ///< wall time [s]
};

/// The brute-force bifurcation diagram of `c` in `options.key`. Throws oscidrum::Error for a key
/// that cannot be varied (not a real field, a numerics.* key, without effect in `c`), `from` or
/// `to` outside the key's rule, from >= to, steps outside [1, 100000], discard outside
/// [0, 1000000] or periods outside [20, 100000].
Diagram bifurcation_diagram(const Case& c, const DiagramOptions& options);

}  // namespace oscidrum
