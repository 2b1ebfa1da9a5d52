// oscidrum/identify.hpp: the soil under the drum from its measured accelerations. The inverse of
// simulate: nonlinear least squares (Levenberg-Marquardt) of the model's complex harmonics of
// x_M'' and z_M'' against the measured ones (docs/identify.md). What is identified is the soil
// of this lumped model (Appendix B (42)-(45) or the springs ksh, ksv directly), not a property
// of the ground measured independently of the model.
#pragma once

#include <complex>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "oscidrum/metrics.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/record.hpp"
#include "oscidrum/result.hpp"

namespace oscidrum {

/// What the model says for one case: the forward model of the identification. Every
/// identification goes through simulate_metrics, so that a faster steady-state solver can
/// replace the transient run in one place.
struct ModelResponse {
  Status status = Status::steady_state;
  std::string message;
  Metrics metrics;  ///< harmonics n = 0 ... n_max of x_M'', z_M'' (absolute-time phases)
  /// The largest |T| / N over the sampled steady state [-] (NaN without one). For a steady state
  /// that sticks throughout, the friction coefficient it needs: every mu (of the friction cone)
  /// at least this large admits it (docs/identify.md, "mu of a drum that does not slip").
  double friction_ratio = 0.0;
  double switches_per_period = 0.0;  ///< stick/slip switches per period of the steady state [-]
  long steps = 0;  ///< accepted integration steps the run took (its share of a budget) [-]
};

/// Simulate `c` to its steady state and return its metrics with n_max harmonics. `max_steps` > 0
/// bounds the run's accepted integration steps in total: a run that needs more ends with
/// Status::budget_exceeded and a message saying so (the identification's bound on one model
/// run). Throws oscidrum::Error only for an invalid case; numerical trouble is in `status`.
ModelResponse simulate_metrics(const Case& c, int n_max, long max_steps = 0);

/// The measured quantities an identification compares with the model.
struct MeasuredResponse {
  double f = 0.0;  ///< excitation frequency [Hz]
  /// Record time [s] at which the phases below are taken (the model's time shift tau is found
  /// against it and reported in record time): the window's first sample.
  double t_ref = 0.0;
  /// C_n = A_n exp(i theta_n) of x_M'' and z_M'', n = 1 ... N (index n - 1), with the phases of
  /// y(t) = sum A_n sin(n 2 pi f (t - t_ref) + theta_n) [m/s^2]
  std::vector<std::complex<double>> ddx, ddz;
  /// Covariance of (Re C_1, Im C_1, ..., Re C_K, Im C_K) of x_M'' (row-major 2K x 2K, K <= N)
  /// [(m/s^2)^2]; empty: sigma_x^2 times the identity.
  std::vector<double> cov_x, cov_z;
  double sigma_x = 1.0;  ///< standard uncertainty of Re C_n and Im C_n of x_M'' [m/s^2]
  double sigma_z = 1.0;  ///< the same for z_M'' [m/s^2]
  int n_signal = 10;     ///< harmonics of the fitted signal the peaks and area are taken from
  double ddx_max = 0, ddx_min = 0, ddz_max = 0, ddz_min = 0;  ///< peaks [m/s^2]
  double area = 0;  ///< area of the z_M''(x_M'') figure [m^2/s^4]
  /// The fit of a window (measure_window): samples, residual RMS [m/s^2] (the noise and the
  /// harmonics beyond those fitted; cov_x and cov_z take their noise without what of those
  /// harmonics the window resolves), and the trend beside the harmonics (Legendre coefficients
  /// c_k of sum c_k P_k(u), u from -1 at t_first to 1 at t_last; c_0 holds the offset) [m/s^2].
  std::size_t samples = 0;
  double noise_x = 0.0, noise_z = 0.0;
  double t_first = 0.0, t_last = 0.0;
  std::vector<double> trend_x, trend_z;
  /// A window sampled in step with the excitation (measure_window: a whole number of samples per
  /// period, or so nearly one that the window cannot tell): the harmonics above those fitted
  /// alias onto the fitted ones coherently, as they do not at other rates. For such a window, the
  /// fit as a linear map of the samples, so that the model can be sampled as the record was:
  /// the sample times t_i - t_ref [s], and for each sample the weights of Re C_n and Im C_n,
  /// n = 1 ... K (2 K per sample, K as for cov_x): C_n = sum_i w_i y_i. Empty for other windows.
  /// identify() fits such a window both ways (the model's harmonics themselves, as a logger with
  /// an anti-aliasing filter records them, and the model sampled at the record's times, as raw
  /// samples do) and keeps the better fit; Identification::measured does not keep these.
  std::vector<double> alias_t, alias_w;
  /// The period p whose subharmonics f/p, 2f/p, ... the fit took as signal (MeasureOptions::period;
  /// 1 where it was 1, or where the window's samples leave too few degrees of freedom for them:
  /// they then count as noise).
  int subharmonics_of = 1;
};

/// The measured response of a fitted record (or window) of `samples` samples at f [Hz] from
/// analyze's metrics (phases in the record's own time, t_ref = 0). The uncertainty of each
/// harmonic coefficient is s sqrt(2 / samples), s the RMS of the fit's residual (white noise;
/// drift and misfit make it conservative).
MeasuredResponse measured_response(const RecordMetrics& m, double f, std::size_t samples);

/// Harmonics fitted to a window when chosen from its sampling: at most this many.
inline constexpr int kMaxMeasuredHarmonics = 40;

/// How the harmonics of a window are measured (measure_window).
struct MeasureOptions {
  /// Harmonics n = 1 ... N fitted [-]; 0: from the sampling, the largest N with at least
  /// 2 N + 2 samples per period at the median time step, at most kMaxMeasuredHarmonics, so that
  /// few harmonics are left out to leak into the compared ones (docs/identify.md).
  int harmonics = 0;
  /// Degree of the polynomial fitted beside the harmonics [-]: offsets and slow drifts, which
  /// would otherwise leak into the harmonics.
  int trend_degree = 3;
  int covariance = 4;  ///< harmonics whose covariance is kept (K above) [-]
  /// Excitation periods after which the window's response repeats (analyze_record's
  /// fitted_periods: 1 ... 4) [-]: for p > 1 its subharmonics k f / p (k not a multiple of p,
  /// up to p N) are fitted to what the harmonics leave and are not counted as noise.
  int period = 1;
};

/// The measured response of one window (t [s] strictly increasing, any spacing; x_M'', z_M''
/// [m/s^2]) at f [Hz]: y(t) = trend + sum_{n=1}^{N} (a_n cos + b_n sin)(n 2 pi f (t - t_ref)) by
/// least squares, the noise s^2 = RSS / (samples - parameters) of each channel, and the
/// covariance s^2 (B^T B)^-1 of the kept harmonics. Throws oscidrum::Error for fewer than 2 N +
/// 2 samples per period with N given, or too few samples for the fit.
MeasuredResponse measure_window(std::span<const double> t, std::span<const double> ddx_M,
                                std::span<const double> ddz_M, double f,
                                const MeasureOptions& options = {});

/// The scale a G is identified on: which soil coefficients a G stands for.
enum class SoilScale {
  formulas,  ///< Appendix B (42)-(45) with the case's nu and rho (soil.input = modulus)
  table2,    ///< the paper's Table 2, interpolated between its rows (table2_coefficients)
};
const char* to_string(SoilScale scale);  ///< "formulas", "table2"
/// SoilScale from its name; throws oscidrum::Error naming `what` and the choices.
SoilScale soil_scale_from(const std::string& name, const std::string& what = "soil_scale");
/// The soil of shear modulus G [Pa] on `scale`: Appendix B's (soil.input = modulus, with nu and
/// rho of `base`) or Table 2's coefficients interpolated at G (soil.input = coefficients). Throws
/// oscidrum::Error when G is outside the scale's range (formulas: [1e5, 2e9] Pa, the
/// identification's; table2: [kTable2InterpolatedMin, kTable2InterpolatedMax]).
Soil soil_on_scale(double G, SoilScale scale, const Soil& base = {});

/// What is estimated, and how.
struct IdentifyOptions {
  bool modulus = true;  ///< true: G [Pa] (on soil_scale); false: ksh, ksv
  /// The scale of G: Appendix B's formulas, or Table 2's (what `oscidrum run --G 30` simulates:
  /// the Table 2 soil; (42) as printed does not reproduce Table 2's stiffness columns, so the
  /// same record gives different G on the two scales, docs/identify.md).
  SoilScale soil_scale = SoilScale::formulas;
  bool fit_mu = false;     ///< estimate contact.mu too
  bool fit_MMd = false;    ///< estimate the driving torque MMd too
  int harmonics = 4;       ///< compare C_n for n = 1 ... harmonics [-]
  bool use_peaks = false;  ///< also compare the four peaks of x_M'' and z_M''
  bool use_area = false;   ///< also compare the area of the z_M''(x_M'') figure
  bool profile = true;     ///< 95 % intervals from the profile of the objective
  /// Relative standard uncertainty of each accelerometer channel's gain (its calibration), the
  /// channels independent [-]; 0: not counted. The harmonics alone cannot tell a gain error from
  /// the soil (z_M'' 2 % high moves G by about -1.7 % at a reduced chi^2 near 1): its effect on
  /// each estimate (Estimate::gain_uncertainty, from refits with each channel's gain one standard
  /// uncertainty off) is added to the standard uncertainty and to the 95 % interval in quadrature
  /// (the interval in the fit's coordinates: ln G, ln mu, MMd / M0).
  double gain_uncertainty = 0.0;
  int max_iterations = 40;        ///< Levenberg-Marquardt iterations [-]
  double max_condition = 1e6;     ///< a larger condition number of the scaled Jacobian: warn [-]
  double model_tolerance = 1e-6;  ///< numerics.rtol and steady_tol of the model (at least) [-]
  double max_correlation = 0.99;  ///< a larger |correlation| of two estimates: warn [-]
  /// A larger reduced chi^2 (the model misses the measured harmonics by more than their noise):
  /// warn that the estimates are biased [-]. Fits of the right model give 0.3-1.2 on synthetic
  /// records; a mu 16 % off the truth, not fitted, gives 300-800.
  double max_reduced_chi2 = 4.0;
  /// When the fit is poor (max_reduced_chi2), fit the record again with x_M'' and/or z_M''
  /// negated and G on the other soil scale, and warn when one of them fits: the record's axis
  /// conventions or soil scale are then likely wrong (a few more fits, only for a poor fit).
  bool diagnose = true;
  /// The record's vertical axis is open: nothing said which way it points (z_positive "auto" on
  /// a column without gravity's mean, RecordColumns::z_open). A fit that is poor as read
  /// (max_reduced_chi2) but good with z_M'' negated is then taken so, with a warning
  /// (Identification::z_negated): the axis points the other way. False: the record is fitted
  /// as read, and a poor fit's diagnosis only names the axis.
  bool z_open = false;
  /// The record's accelerations had no unit and were read in m/s^2 (RecordColumns::units_open):
  /// a fit that is poor so but good with them read in g (x 9.80665; with z_M'' negated too when
  /// z_open) is taken so, with a warning (Identification::read_in_g).
  bool units_open = false;
  /// How the record's axes were read (the CLI's --x-positive backward and --z-positive up, Python's
  /// x_positive and z_positive, z_positive "auto" included): a poor fit's diagnosis that finds an
  /// axis the other way names the reading to change from these (it told a record read with
  /// --z-positive up to be read with --z-positive up).
  bool x_read_backward = false;
  bool z_read_up = false;
  /// How each window's harmonics are measured (identify_pass); measure.covariance is raised to
  /// `harmonics`.
  MeasureOptions measure;
  /// Find the model's steady states by shooting (numerics.method = shooting; about three times
  /// faster than the transient from rest, and the same estimates, bench/README.md); false: the
  /// base case's numerics.method.
  bool shooting = true;
};

/// One estimated parameter.
struct Estimate {
  std::string name;  ///< G, ksh, ksv, mu, MMd
  std::string unit;  ///< Pa, N/m, -, N m
  double value = 0.0;
  /// From the Jacobian and the residual noise, and the gains' (gain_uncertainty) [unit]
  double standard_uncertainty = 0.0;
  double lower = 0.0, upper = 0.0;  ///< 95 % interval from the profile [unit] (NaN: none)
  /// The part of the standard uncertainty that the channels' gain uncertainty makes
  /// (IdentifyOptions::gain_uncertainty; 0 when not counted) [unit]
  double gain_uncertainty = 0.0;
  /// The profile stayed flat down to the parameter's bound, or the gains' part of the interval
  /// (gain_uncertainty) widened it beyond the bound: `lower` is the bound.
  bool lower_open = false;
  bool upper_open = false;  ///< ... up to its bound
};

/// The result of one identification.
struct Identification {
  bool converged = false;
  std::string message;              ///< why it stopped
  std::vector<Estimate> estimates;  ///< in the order G (or ksh, ksv), mu, MMd
  double f = 0.0;                   ///< excitation frequency used [Hz]
  double time_shift = 0.0;          ///< tau [s]: record time = model time + tau (modulo 1/f)
  double rms_residual = 0.0;        ///< RMS of C_n(measured) - C_n(model), over n and both [m/s^2]
  double relative_residual = 0.0;   ///< ||C(measured) - C(model)|| / ||C(measured)|| [-]
  double reduced_chi2 = 0.0;        ///< weighted sum of squares / degrees of freedom [-]
  double condition = 0.0;           ///< condition number of the column-scaled Jacobian [-]
  int iterations = 0;               ///< Levenberg-Marquardt iterations [-]
  int simulations = 0;              ///< calls of simulate_metrics [-]
  std::vector<std::string> warnings;  ///< parameters that cannot be told apart, flat profiles
  /// The model was compared as the window's fit measures it sampled at the record's times, not
  /// by its harmonics themselves: a window sampled in step with the excitation whose raw samples
  /// alias (MeasuredResponse::alias_t), where that fits better (docs/identify.md).
  bool model_sampled = false;
  /// IdentifyOptions::z_open: the window was fitted with its z_M'' negated (its axis taken to
  /// point the other way than read), which fits well where the record as read did not.
  /// `measured` is the window so negated; fit_curves gives the model in the record as read.
  bool z_negated = false;
  /// IdentifyOptions::units_open: the window's accelerations were fitted read in g (times
  /// 9.80665), which fits well where m/s^2 did not; `measured` is so scaled, fit_curves gives
  /// the model in the record's units as read.
  bool read_in_g = false;
  Case fitted;                ///< the case at the estimate (f and M0 of the record)
  Metrics simulated;          ///< its metrics
  MeasuredResponse measured;  ///< what the model was fitted to
};

/// The unknowns `options` estimate, in the order of Identification::estimates, with their SI
/// units: G [Pa] (or ksh, ksv [N/m]), then mu [-] and MMd [N m] where fitted. A window that
/// failed has none: its outputs give these names NaN.
struct IdentifiedUnknown {
  std::string name;
  std::string unit;
};
std::vector<IdentifiedUnknown> identified_unknowns(const IdentifyOptions& options);

/// Estimate the soil (and optionally mu, MMd) so that the model's harmonics match `data`. The
/// case `base` gives everything else; its roller.f is set to data.f and roller.M0 scaled by
/// (data.f / base.roller.f)^2 (5). `start` (optional) is a previous identification to start
/// from (a pass); without it a coarse scan of G picks the start. Throws oscidrum::Error for
/// invalid input or if the model fails at every start.
Identification identify(const Case& base, const MeasuredResponse& data,
                        const IdentifyOptions& options = {}, const Identification* start = nullptr);

/// The best fit in the record's time, for plots: the model's accelerations at record times t
/// [s], the steady state of id.fitted shifted by id.time_shift, plus the trend of the window
/// (id.measured: offsets and slow drift; none from analyze's metrics), in the record's axes as
/// it was read (z_M'' negated back for a window fitted negated, Identification::z_negated, and
/// divided by 9.80665 for one fitted in g, Identification::read_in_g). Throws
/// oscidrum::Error when the fitted case does not reach its steady state.
struct FitCurves {
  std::vector<double> ddx_M, ddz_M;  ///< [m/s^2]
};
FitCurves fit_curves(const Identification& id, std::span<const double> t);

/// One window of a pass with its identification (valid == false: the window failed a gate or
/// the identification failed; `reason` says why and the estimates are NaN).
struct PassEstimate {
  RecordWindow window;
  bool valid = false;
  std::string reason;
  Identification identification;
};

/// Called after each window with its index and the number of windows; return false to stop.
using PassProgress = std::function<bool(std::size_t index, std::size_t count)>;

/// Identify every window of a record, each started from the previous valid estimate. The windows
/// and their gates are analyze_windows' (windows.n_max == 0: the gates' harmonics from the
/// sampling, at most 10), on the record's times less its first (so that clock times such as
/// 1.7e9 s keep their precision; the windows report record times); each window's harmonics are
/// measured by measure_window (options.measure). Throws oscidrum::Error when options.harmonics
/// is more than every measured window resolves (rather than failing each window alike).
std::vector<PassEstimate> identify_pass(
    const Case& base, std::span<const double> t, std::span<const double> ddx_M,
    std::span<const double> ddz_M, std::span<const double> position, const WindowOptions& windows,
    const IdentifyOptions& options = {}, const PassProgress& progress = {});

/// A synthetic record made by oscidrum itself, for tests and benchmarks.
struct SyntheticRecord {
  double duration = 1.0;      ///< [s]
  double sample_rate = 1000;  ///< [1/s]
  double noise = 0.0;         ///< white noise, standard deviation / peak |a| of each signal [-]
  double drift = 0.0;         ///< slow drift amplitude / peak |a| (a sine of period `duration`)
  double jitter = 0.0;        ///< random sample-time jitter / sample interval, in [0, 1) [-]
  unsigned seed = 1;
  double speed = 0.0;    ///< roller speed for the position column [m/s]
  double start = 0.0;    ///< time of the first sample [s] (a logger's clock)
  double dropped = 0.0;  ///< fraction of the samples lost at random [-], in [0, 1)
};

/// Most harmonics an identification compares (IdentifyOptions::harmonics, --compare).
inline constexpr int kMaxComparedHarmonics = 50;

/// Samples of a synthetic record: t [s], x_M'', z_M'' [m/s^2], position [m].
struct RecordSamples {
  std::vector<double> t, ddx_M, ddz_M, position;
};

/// Simulate each case of `segments` (consecutive, each duration / segments.size() long) to its
/// steady state and sample it at the record's times (linear interpolation of 8192 samples per
/// period; record time = model time modulo the period, so a fit's time shift is 0), then add
/// noise and drift. Throws oscidrum::Error if a case does not reach its steady state.
RecordSamples synthetic_record(const std::vector<Case>& segments, const SyntheticRecord& options);

}  // namespace oscidrum
