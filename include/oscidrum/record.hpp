// oscidrum/record.hpp: the metrics of a measured drum acceleration record, for comparing
// simulations with field measurements (paper Fig. 23). A measured record rarely holds a whole
// number of periods at a sampling rate commensurate with f, so the harmonics are fitted by least
// squares rather than read off a DFT.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "oscidrum/metrics.hpp"

namespace oscidrum {

/// One member per entry of OSCIDRUM_RECORD_METRICS (oscidrum/outputs.hpp): the fit's cycles and
/// residuals, then the acceleration metrics shared with Metrics (peaks and area of the fitted
/// periodic signals, harmonics with absolute-time phases, psi_xz and the compaction indicators).
struct RecordMetrics {
#define OSCIDRUM_MEMBER(type, name, unit, label, description) type name{};
  OSCIDRUM_RECORD_METRICS(OSCIDRUM_MEMBER)
#undef OSCIDRUM_MEMBER
};

/// Fit y(t) = sum_{n=0}^{n_max} (a_n cos(n nu t) + b_n sin(n nu t)) to x_M'' and z_M'' by least
/// squares (t [s] strictly increasing, any spacing, at least one excitation period f [Hz]), then
/// evaluate the metrics on the fitted periodic signals (1024 samples per period). The fitted
/// signal is what repeats from period to period: noise and slow drifts go to the residuals.
/// Throws oscidrum::Error on inconsistent sizes, non-finite values, a record shorter than one
/// period or too coarse for n_max (fewer than 2 n_max + 1 samples per period).
RecordMetrics analyze_record(std::span<const double> t, std::span<const double> ddx_M,
                             std::span<const double> ddz_M, double f, int n_max = 10);

/// The most harmonics a record's fit takes (analyze_record, WindowOptions::n_max,
/// FrequencySearch::n_max; the CLI's --harmonics): the fit's normal equations are
/// (2 n_max + 1)^2 numbers.
inline constexpr int kMaxRecordHarmonics = 200;

/// Search range and method of estimate_frequency.
struct FrequencySearch {
  double f_min = 10.0;   ///< lowest excitation frequency considered [Hz]
  double f_max = 100.0;  ///< highest [Hz] (further limited to fs / 5: two harmonics resolved)
  int n_max = 10;        ///< harmonics of the least-squares refinement (at most those resolved) [-]
};

/// The excitation frequency of a record [Hz]: the peak of the harmonic-sum spectrum
/// P(f) = sum_{n=1}^{3} (|X(n f)|^2 + |Z(n f)|^2) (the n f below the Nyquist frequency; f up to a
/// fifth of the sampling rate) of at most 4096 samples (the first, or where the record's
/// beginning is quiet, those from its first stretch where the drum oscillates) on a grid of
/// at most a quarter of their frequency resolution (an FFT's bins for uniform samples, direct
/// sums otherwise), refined by minimising the residual of the
/// least-squares harmonic fit (n = 0 ... n_max, at most the harmonics the sampling resolves at
/// the peak, 2 N + 1 samples per period for N; both signals) over f itself, first on that
/// segment, then on the rest of the record from its start. Throws oscidrum::Error on the
/// conditions of analyze_record, when the range holds no frequency and when both accelerations
/// are constant.
double estimate_frequency(std::span<const double> t, std::span<const double> ddx_M,
                          std::span<const double> ddz_M, const FrequencySearch& search = {});

/// Refine f [Hz] by minimising the residual of the harmonic fit (n = 0 ... n_max) over
/// [f (1 - half_width), f (1 + half_width)] (first with the fundamental, then with more harmonics
/// in narrower brackets; Gauss-Newton steps in f, Brent's search where they fail; f is returned
/// to about 1e-9 relative, 1e-7 where Brent's search finishes).
double refine_frequency(std::span<const double> t, std::span<const double> ddx_M,
                        std::span<const double> ddz_M, double f, double half_width, int n_max);

/// Quality gates of a window (docs/cli.md, `oscidrum analyze`). A window that fails one is
/// flagged, and its metrics are NaN.
struct RecordGates {
  double max_residual = 0.5;  ///< largest fit residual (relative RMS) of x_M'' or z_M'' [-]
  double max_drift = 0.002;   ///< largest |f(later part) - f(earlier part)| / f in a window [-]
  double clip_level = 0.0;    ///< |a| >= this counts as clipped [m/s^2]; 0: detect plateaus
  int clip_run = 3;  ///< this many equal samples running in the outer quarter of a channel's range
                     ///< in the window (in a record in codes: not a finite resolution's plateau
                     ///< at a smooth peak, docs/identify.md): clipped [-]
  double max_gap = 0.5;  ///< a time step longer than this part of an excitation period: gap [-]
  /// Largest change of the response within a window: |RMS(later part) - RMS(earlier part)| /
  /// RMS(window) of the fitted periodic x_M'' or z_M'', over the window's 4 (3, 2) equal parts
  /// (beyond the noise) [-]. A window that
  /// straddles a change of soil (or of the roller's settings) fits neither side.
  double max_change = 0.05;
};

/// Windows along a record.
struct WindowOptions {
  double f = 0.0;               ///< excitation frequency [Hz]; 0: estimate (estimate_frequency)
  FrequencySearch search;       ///< used when f == 0
  double window_periods = 0.0;  ///< window length in excitation periods; 0: the whole record
  double hop_periods = 0.0;     ///< hop between window starts [periods]; 0: window_periods
  /// A record shorter than one window (but of at least one excitation period) is analysed whole,
  /// as one window (as window_periods = 0), instead of refused: for a default window that the
  /// user did not choose (`oscidrum identify` without --window; Python's window=None).
  bool whole_if_shorter = false;
  /// Harmonics fitted [-], 2 ... kMaxRecordHarmonics; 0: as many as the record's sampling
  /// resolves, at most 10 (resolved_harmonics).
  int n_max = 0;
  RecordGates gates;
  /// Added to the times the reasons quote [s]: a caller that analyses the times less an origin
  /// (for their precision) gives it, so that a gap is reported at the record's own time.
  double time_origin = 0.0;
  /// The record is a reference of one soil and one setting, analysed whole (`oscidrum
  /// calibrate`): a gate's advice is to cut the record where it changes, not the window flags of
  /// `analyze` and `identify` (--window, --max-change), which such a caller does not have.
  bool one_reference = false;
};

/// One window of a record.
struct RecordWindow {
  int index = 0;          ///< 0, 1, ... [-]
  double t_start = 0.0;   ///< first sample time [s]
  double t_end = 0.0;     ///< last sample time [s]
  double t_mid = 0.0;     ///< (t_start + t_end) / 2 [s]
  double position = 0.0;  ///< position at t_mid [m] (NaN without a position)
  std::size_t first = 0;  ///< index of the first sample in the record [-]
  std::size_t count = 0;  ///< samples in the window [-]
  double f = 0.0;         ///< excitation frequency of the window [Hz] (NaN if not fitted)
  /// (f(later part) - f(earlier part)) / f for the two of the window's 4 equal parts (3 or 2
  /// where a part would span less than a period; the halves where those hold too few samples)
  /// whose f differ most beyond the noise (else most) [-] (NaN if not fitted or not measured)
  double drift = 0.0;
  /// (RMS(later part) - RMS(earlier part)) / RMS(window) of the fitted periodic signal, for the
  /// two of the window's 4 equal parts (3 or 2 where shorter ones would not hold a period and
  /// 2 (2 n + 1) samples) and the channel, x_M'' or z_M'', that differ most [-] (NaN if not
  /// fitted, or halves are too short already); RecordGates::max_change bounds it.
  double change = 0.0;
  double samples_per_period = 0.0;  ///< [-]
  /// The whole record as the one window, the window asked being longer than the record
  /// (WindowOptions::whole_if_shorter).
  bool whole = false;
  bool valid = false;     ///< passed every gate
  std::string reason;     ///< why not valid (empty when valid); several joined by "; "
  RecordMetrics metrics;  ///< NaN when not valid (residuals kept when the fit was made)
};

/// A record cut into windows, each with its own f, its metrics and its quality gates. `position`
/// [m] (one per sample, or empty) is interpolated at the window centres. Windows are
/// window_periods / f long at the record's f, start hop_periods / f apart, and the last one
/// ends within the record. Throws oscidrum::Error for inconsistent input (sizes, non-finite or
/// non-increasing t) and for a record shorter than one window (unless whole_if_shorter, or one
/// period); a window that fails a gate is
/// returned with valid == false and its reason.
std::vector<RecordWindow> analyze_windows(std::span<const double> t, std::span<const double> ddx_M,
                                          std::span<const double> ddz_M,
                                          std::span<const double> position,
                                          const WindowOptions& options = {});

/// Whether samples at the increasing times t [s] are taken in step with an excitation at f [Hz]:
/// j M a whole number (M the samples per period at the median step) to within what the span of
/// t resolves, |j M - round(j M)| times its periods below 2, for a band j = 1 ... 4, with the
/// steps' median deviation from the median step below 1 %/j. Harmonic m of the signal then lands,
/// after sampling, on |m - j M| f with the same phase in every period: the harmonics above those
/// a fit resolves alias onto the fitted ones coherently, as they do not at other rates
/// (docs/identify.md). False for fewer than 3 samples.
bool sampled_in_step(std::span<const double> t, double f);

/// The harmonics a record's sampling resolves at its excitation frequency (options.f, or
/// estimated as estimate_frequency's peak is): 2 N + 1 samples per period at the median step, N in
/// [2, 10] (10: analyze's default). For WindowOptions::n_max when it is not given.
int resolved_harmonics(std::span<const double> t, std::span<const double> ddx_M,
                       std::span<const double> ddz_M, const WindowOptions& options = {});

/// The phase phi_u [rad] of a vibratory drum's unbalance over the samples t [s] of a record:
/// its angle alpha [rad] (RecordReading::unbalance_col: the unbalance force's downward
/// component is F0 sin(alpha)) written as alpha = 2 pi f t + phi_u, phi_u the circular mean of
/// alpha - 2 pi f t, in (-pi, pi]. Throws oscidrum::Error on sizes that differ or no samples.
double unbalance_phase(std::span<const double> t, std::span<const double> alpha, double f);

/// The Kb-type stiffness [N/m] of a record (docs/outputs.md, RecordMetrics::kb): from the
/// fundamental ddz_1 of z_M'' (absolute-time phase, record.hpp), the excitation frequency f [Hz],
/// the unbalance's phase phi_u [rad] and the vibratory drum of the case c (roller.m, roller.kd,
/// roller.static_moment): m nu^2 - kd - F0 nu^2 cos(phi_u - theta_1) / A_1 with
/// F0 = m_u e_u nu^2. The same number as Metrics::kb of the steady state the record shows.
/// Throws oscidrum::Error when c's roller is not vibratory; NaN when A_1 is not positive.
double record_soil_stiffness(const Case& c, const Harmonic& ddz_1, double f, double phi_u);

/// kb of every valid window of a record (RecordWindow::metrics.kb) from the case c and the
/// unbalance's angle alpha (one per sample of t, or empty): "" when filled, else why kb is NaN
/// (no case, not a vibratory drum, no angle), in one line, and every window's kb NaN.
std::string record_kb(std::vector<RecordWindow>& windows, std::span<const double> t,
                      std::span<const double> alpha, const Case* c);

/// Position [m] from a speed column [m/s] by the trapezoidal rule, 0 at the first sample.
std::vector<double> integrate_speed(std::span<const double> t, std::span<const double> speed);

}  // namespace oscidrum
