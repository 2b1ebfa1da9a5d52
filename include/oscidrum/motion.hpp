// oscidrum/motion.hpp: what a motion that does not settle is. When no periodic steady state is
// found within numerics.max_periods, the motion is examined over further periods: its
// stroboscopic (Poincare) points at the excitation period, its largest Lyapunov exponent from the
// variational equations, and whether the points recur; from these a verdict (quasi-periodic,
// chaotic, periodic after all, still converging) with the numbers behind it
// (docs/bifurcations.md, "Beyond the last periodic orbit").
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "oscidrum/model.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

struct MotionAnalysis {
  /// "quasi_periodic" (largest Lyapunov exponent zero within its uncertainty, no recurrence),
  /// "chaotic" (positive exponent beyond the spread of the window's halves), "periodic" (the
  /// points recur every `recurrence` periods: a steady state approached slowly or of a period
  /// beyond numerics.max_multiplicity), "converging" (negative exponent: still approaching an
  /// attractor), "undecided"; "" if not analysed.
  std::string kind;
  double lyapunov = 0.0;         ///< largest Lyapunov exponent [1/s]
  double lyapunov_first = 0.0;   ///< the same from the window's first half [1/s]
  double lyapunov_second = 0.0;  ///< ... and from its second half [1/s]
  int periods = 0;               ///< excitation periods examined [-]
  int recurrence = 0;            ///< p > 0: the points repeat every p periods [-]
  /// p > 0: the distance between stroboscopic points p periods apart shrinks geometrically (ln of
  /// it falls on a line, R^2 >= 0.9, over the second half; the p of the steepest fall): the
  /// motion still converges [-]
  int converging_period = 0;
  /// That distance's shrink factor over the second half (1 if not converging) [-]
  double contraction = 1.0;
  /// The stroboscopic points: the roller's state at t0 + k T, k = 0 ... periods (every
  /// component, in the order of its state; docs/bifurcations.md).
  std::vector<std::vector<double>> section;
  std::vector<Phase> section_phase;  ///< the flow's phase at each stroboscopic point
  std::string evidence;              ///< the verdict with its numbers, in words
};

/// Examine the motion from the first sample of `result` (a period boundary; any status with
/// samples) over `periods` further excitation periods. Throws oscidrum::Error if the result has
/// no samples or periods < 20. The flow stopping early (contact lost, ...) gives kind
/// "undecided" with the reason; `cancelled` (optional) is polled at every step.
MotionAnalysis analyze_motion(const Model& model, const Result& result, int periods = 400,
                              const std::function<bool()>& cancelled = {});

}  // namespace oscidrum
