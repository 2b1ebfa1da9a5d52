// oscidrum/metrics.hpp: what continuous compaction control reads off the drum accelerations.
// The signal-level functions work on any uniformly sampled record (simulated or measured).
#pragma once

#include <span>
#include <vector>

#include "oscidrum/model.hpp"
#include "oscidrum/outputs.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// One harmonic n f of a signal written as  y(t) = sum_n A_n sin(n nu t + theta_n)  with t the
/// absolute time (t = 0 at the start of the excitation M0 sin(nu t)). n = 0: A_0 = |mean| and
/// theta_0 = +-pi/2, so that A_0 sin(theta_0) is the mean.
struct Harmonic {
  double amplitude = 0.0;  ///< A_n >= 0 [unit of the signal]
  double phase = 0.0;      ///< theta_n in (-pi, pi] [rad]
};

/// Harmonics n = 0 ... n_max of y sampled uniformly over exactly `cycles` periods of f:
/// y[j] = y(t0 + j / (f * samples_per_cycle)), j = 0 ... cycles*samples_per_cycle - 1. A DFT over
/// whole periods: no window, no leakage. Only multiples of f (bin n * cycles) are returned.
/// Throws oscidrum::Error if y.size() is not a positive multiple of `cycles` or n_max is too
/// large for the sampling (n_max < samples_per_cycle / 2).
std::vector<Harmonic> harmonics(std::span<const double> y, int cycles, double f, double t0,
                                int n_max);

/// Area of the region enclosed by the closed polygon (x[j], y[j]) (last point joins the first):
/// the set of points with non-zero winding number. For a figure-eight this is the sum of both
/// lobes (the signed shoelace sum would cancel them). [unit x * unit y]
double enclosed_area(std::span<const double> x, std::span<const double> y);

/// Area enclosed (non-zero winding) by the closed curve made of arcs, arc j from point j to point
/// j + 1 (the last back to the first), where bulge[j] is the signed area between arc j and its
/// chord:  bulge[j] = integral over the arc of x dy - (x[j] + x[j+1]) / 2 * (y[j+1] - y[j]),
/// positive when the arc lies to the right of the chord (seen along the curve). Exact when every
/// self-intersection of the curve is one of the points and each arc stays close enough to its chord
/// to cross no other arc or chord; a crossing inside an arc costs an error of the order of that
/// arc's bulge. [unit x * unit y]
double enclosed_area(std::span<const double> x, std::span<const double> y,
                     std::span<const double> bulge);

/// Wrap an angle to (-pi, pi].
double wrap_pi(double angle);

using Spectrum = std::vector<Harmonic>;  ///< harmonics n = 0 ... n_max of one signal

/// Metrics of a simulated steady state: one member per entry of OSCIDRUM_METRICS
/// (oscidrum/outputs.hpp), where each is defined with its unit (ddx_max, ..., ddx_harmonics,
/// ddz_harmonics, psi_xz, area, the compaction indicators, delta_max, ..., phi_lag, the phase
/// fractions, mu_required, friction_work). docs/outputs.md gives the formulas.
struct Metrics {
#define OSCIDRUM_MEMBER(type, name, unit, label, description) type name{};
  OSCIDRUM_METRICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER

  /// Every number NaN and no harmonics: what a result that is not a steady state has.
  static Metrics unavailable();
};

/// Which of x_M'' and z_M'' is absent as a whole: every component of its spectrum (mean
/// included) at or below 1e-6 of the largest component of the two spectra, or below 1e-12 g
/// [m/s^2] (the spectra in m/s^2; both signals of a drum without friction). Such a signal is the
/// round-off of a motion that has none (the directed vertical exciter's x_M'', a record's dead
/// channel): its ratios and phases are NaN (docs/outputs.md), and plots and tables show it as
/// absent instead of scaling its round-off up to look like a signal.
struct AbsentSignals {
  bool ddx = false;  ///< x_M'' absent
  bool ddz = false;  ///< z_M'' absent
};
AbsentSignals absent_signals(const Spectrum& ddx_harmonics, const Spectrum& ddz_harmonics);
/// The same from a steady state's metrics, their peaks counted with the harmonics: a signal whose
/// peak is above the level is there however few harmonics were computed (with n_max = 1, z_M''
/// of a drum without driving torque, which has even harmonics only, read as absent).
AbsentSignals absent_signals(const Metrics& m);

/// Compute the metrics from a Result's samples (harmonics up to n_max). Throws oscidrum::Error if
/// the result holds no samples or its status is not Status::steady_state.
Metrics compute_metrics(const Result& result, int n_max = 10);

/// The same metrics from the trajectory itself instead of its samples: one steady period is
/// integrated again from the first sample through the flow (oscidrum/flow.hpp) and every metric
/// is evaluated on the dense output: peaks at both one-sided limits of every switch and at every
/// interior extremum, harmonics, lags, THD and friction work as integrals over each piece, the
/// area of the dense curve exactly (every piece's quantities as Chebyshev interpolants accurate to
/// round-off; docs/outputs.md). Independent of
/// numerics.samples_per_period. `model` must be the one `result` was simulated with. Throws
/// oscidrum::Error as compute_metrics(result) does.
Metrics compute_metrics(const Model& model, const Result& result, int n_max = 10);

/// Lundberg's (1939) settlement [m] of a rigid cylinder of radius R [m] and length L [m] pressed
/// by the force F >= 0 [N] into an elastic half-space of Young's modulus E > 0 [Pa] and Poisson's
/// ratio nu in [0, 0.5), as the Evib evaluation uses it (docs/outputs.md):
///   z = (1 - nu^2) / E * F / L * (2 / pi) * (1.8864 + ln(L / b)),
///   b = sqrt(16 R (1 - nu^2) F / (pi L E))   (the half-width of the contact strip).
/// Throws oscidrum::Error naming the argument out of its range.
double lundberg_displacement(double F, double E, double R, double L, double nu);

/// The E [Pa] for which Lundberg's relation rises by z2 - z1 between the forces F1 and F2:
/// lundberg_displacement(F2, E) - lundberg_displacement(F1, E) = z2 - z1 (0 <= F1 < F2,
/// z1 < z2). NaN when there is no such E with a contact strip narrower than about 1.5 L
/// (docs/outputs.md). Throws oscidrum::Error for R, L, nu out of range.
double lundberg_modulus(double F1, double z1, double F2, double z2, double R, double L, double nu);

/// The Evib-type vibration modulus [Pa] of a closed force-displacement loop: z [m] the drum
/// centre's vertical displacement (downwards) and F [N] the soil's vertical force on the drum at
/// the same instants, in time order over one steady period. The loading branch runs from the
/// loop's least z forward to its largest; its end point is the branch's largest F, its start the
/// landing (the point where F rises from 0, interpolated linearly) after a flight, else the
/// branch's first point; the result is lundberg_modulus between the two. NaN for a degenerate
/// branch (no positive force, no rise in force or in z). docs/outputs.md gives the source and
/// the choices.
double vibration_modulus(std::span<const double> z, std::span<const double> F, double R, double L,
                         double nu);

}  // namespace oscidrum
