// identify/problem.hpp: the identification as a least-squares problem (solver.hpp): the unknowns
// in internal coordinates, the forward model (simulate_metrics at the record's f, cached), the
// time shift projected out, and the weighted residuals of the measured harmonics.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <complex>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "drivers/continuation.hpp"
#include "drivers/period_recording.hpp"
#include "identify/solver.hpp"
#include "oscidrum/identify.hpp"

namespace oscidrum::detail {

/// x_M'' and z_M'' of a steady state as functions of model time: the interpolants of the steady
/// period's pieces (one per integration step, exact to round-off between the switches), repeated
/// with its period. What the model gives at a record's sample times (MeasuredResponse::alias_t).
struct PeriodicSignal {
  double t0 = 0.0, period = 0.0;  ///< the period recorded: [t0, t0 + period) [s]
  std::vector<double> starts;     ///< the start of each piece [s]
  std::vector<recording::Interpolant> x, z;
  bool empty() const { return starts.empty(); }
  /// x_M'', z_M'' at model time t [s] [m/s^2].
  std::array<double, 2> at(double t) const;
};

/// simulate_metrics (oscidrum/identify.hpp) with shooting started from `warm` (may be null) when
/// the case's method is shooting (simulate_from); `orbit` (may be null) receives the run's steady
/// state as a start for the next run. The metrics read the steady period the sampling recorded;
/// `signal` (may be null) receives that period's x_M'' and z_M'' (empty without a steady state).
ModelResponse simulate_metrics_from(const Case& c, int n_max, long max_steps, const WarmStart* warm,
                                    std::optional<WarmStart>* orbit,
                                    PeriodicSignal* signal = nullptr);

/// The unknowns an identification can estimate.
enum class Unknown { G, ksh, ksv, mu, MMd };

const char* name_of(Unknown k);
const char* unit_of(Unknown k);

/// Internal coordinates: ln G, ln ksh, ln ksv, ln mu, MMd / M0.
double to_internal(Unknown k, double v, double M0);
double to_physical(Unknown k, double p, double M0);

/// The model's response at one point, reduced to what the fit compares.
struct Simulated {
  bool ok = false;
  std::string message;
  std::vector<std::complex<double>> x, z;  ///< C_n, n = 1 ... harmonics
  /// The signal's peaks and area: computed only when the fit compares them (use_peaks,
  /// use_area), else NaN.
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double ddx_max = kNaN, ddx_min = kNaN, ddz_max = kNaN, ddz_min = kNaN, area = kNaN;
  Metrics metrics;
  double friction_ratio = std::numeric_limits<double>::quiet_NaN();  ///< largest |T| / N [-]
  bool rolling = false;   ///< the steady state sticks throughout (no slip)
  PeriodicSignal signal;  ///< the steady state's x_M'', z_M'' (only for a sampled comparison)
};

/// Every model run of an identification is bounded: at most this many integration steps in all
/// (about half a second).
inline constexpr long kMaxStepsPerRun = 160000;
/// ... and the runs of one identification (one window, with the refits of its diagnosis) at most
/// this many in all (about 7 s): a window of the paper's roller takes tens of milliseconds, but a
/// roller whose model hardly settles (a suspension of 1e9 N/m: every trial runs into its 1500
/// periods) took minutes of such trials, the diagnosis's refits multiplying them.
inline constexpr long kMaxStepsPerWindow = 3200000;

/// The misfit of the harmonics n = 1 ... harmonics of the model (`x`, `z`: as Problem::compared
/// gives them) against the measured ones: the RMS of C_n(measured) - C_n(model) over n and both
/// signals [m/s^2], and its norm relative to the measured harmonics' (NaN without any) [-].
struct HarmonicMisfit {
  double rms = 0.0;
  double relative = 0.0;
};
HarmonicMisfit harmonic_misfit(const std::vector<std::complex<double>>& x,
                               const std::vector<std::complex<double>>& z,
                               const MeasuredResponse& data, int harmonics);

/// Whether `data` holds its window's fit as a map of the samples (MeasuredResponse::alias_t: a
/// window sampled in step with the excitation) for `harmonics` compared harmonics.
inline bool has_sampling_map(const MeasuredResponse& data, int harmonics) {
  return !data.alias_t.empty() &&
         data.alias_w.size() >= data.alias_t.size() * static_cast<std::size_t>(2 * harmonics);
}

/// How the model's harmonics are compared with a window's: as the model's own (the default), or
/// as the window's fit measures the model sampled at the window's times (MeasuredResponse::
/// alias_t; a window sampled in step with the excitation, whose raw samples alias).
enum class Comparison { harmonics, sampled };

class Problem : public LeastSquares {
 public:
  /// Throws oscidrum::Error for `sampled` without the window's estimator (data.alias_t) for
  /// options.harmonics harmonics.
  Problem(const Case& base, const MeasuredResponse& data, const IdentifyOptions& options,
          Comparison comparison = Comparison::harmonics);

  int rows() const override { return rows_; }
  const std::vector<Bounds>& bounds() const override { return bounds_; }
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override;
  std::string failure(const Eigen::VectorXd& p) override { return simulate_at(p).message; }

  /// The residual at p and the time shift (as the phase phi = 2 pi f tau) that aligns the model.
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r, double& phi);

  const std::vector<Unknown>& unknowns() const { return unknowns_; }
  int simulations() const { return simulations_; }
  /// Integration steps of the model runs counted against kMaxStepsPerWindow so far.
  long steps() const { return *steps_used_; }
  /// Count the steps in `counter` instead (shared by the refits of one window's diagnosis).
  void count_steps_in(long& counter) { steps_used_ = &counter; }
  /// The counter the steps are counted in (for another problem of the same window).
  long& steps_counter() { return *steps_used_; }
  double M0() const { return case_.roller.M0; }
  /// The base case at the record's f (M0 scaled by (f / roller.f)^2, (5)), with the numerics of
  /// the identification.
  const Case& base() const { return case_; }
  Case case_at(const Eigen::VectorXd& p) const;
  /// The internal coordinates of the unknowns of c, clamped to their bounds.
  Eigen::VectorXd internal_of(const Case& c) const;
  /// The model at p (cached).
  const Simulated& simulate_at(const Eigen::VectorXd& p);
  /// The model's harmonics n = 1 ... harmonics as the fit compares them with the measured ones at
  /// the time shift phi: C_n e^{i n phi}, or (Comparison::sampled) the window's fit of the model
  /// sampled at the window's times shifted by phi / (2 pi f).
  void compared(const Simulated& s, double phi, std::vector<std::complex<double>>& x,
                std::vector<std::complex<double>>& z) const;
  Comparison comparison() const { return comparison_; }

 private:
  /// One bounded model run of c, the case at the internal coordinates p.
  ModelResponse run(const Case& c, const Eigen::VectorXd& p);
  ModelResponse rolling_instead(const Case& c, const Eigen::VectorXd& p, const ModelResponse& r);
  double best_phase(const Simulated& s) const;
  /// The weighted residual of the harmonics at phase phi, into r[0 ... 4 harmonics).
  void harmonic_residual(const Simulated& s, double phi, Eigen::VectorXd& r) const;

  MeasuredResponse data_;
  IdentifyOptions o_;
  Comparison comparison_ = Comparison::harmonics;
  Case case_;
  std::vector<Unknown> unknowns_;
  std::vector<Bounds> bounds_;
  // Whitening of the measured harmonics: W^T W = Cov^-1 of (Re C_1, Im C_1, ...) of each signal.
  Eigen::MatrixXd wx_, wz_;
  int n_sim_ = 10, rows_ = 0, simulations_ = 0;
  long steps_ = 0;              // integration steps of this identification's model runs so far
  long* steps_used_ = &steps_;  // where they are counted (steps_, or a shared counter)
  PeriodicSignal signal_;       // the last run's steady state (Comparison::sampled)
  std::map<std::vector<double>, Simulated> cache_;
  std::map<std::vector<double>, std::pair<ModelResponse, PeriodicSignal>> rolling_cache_;
  // The steady states of the last kOrbits model runs that found one, each at its point p: a run
  // within kWarmRadius of one starts shooting at the nearest (run()), as the cases of a study
  // continue their neighbours.
  static constexpr double kWarmRadius = 2.0 * kJacobianStep;
  static constexpr std::size_t kOrbits = 8;
  struct SolvedOrbit {
    Eigen::VectorXd p;
    bool pure_rolling = false;
    WarmStart orbit;
  };
  std::vector<SolvedOrbit> orbits_;  // oldest first
  bool warm_starts_ = true;          // false with mu among the unknowns (run())
};

/// The record read the other way round: x_M'' (or z_M'') negated, its harmonics, peaks and trend
/// with it (the area and the covariances do not change sign).
MeasuredResponse flipped(MeasuredResponse d, bool x, bool z);

/// Why a record (`where`: "the window", "the record") whose x_M'' (x) or z_M'' is one value in
/// every sample cannot be fitted.
std::string dead_channel(bool x, const std::string& where);

/// Throws oscidrum::Error (dead_channel) when x_M'' or z_M'' is one value in every sample.
void require_live_channels(std::span<const double> ddx, std::span<const double> ddz,
                           const std::string& where);

/// The record with x_M'' and z_M'' exchanged (a logger turned by 90 degrees about the axle, or its
/// columns named the other way round): harmonics, covariances, noise, trends and peaks (the
/// enclosed area is the same).
MeasuredResponse swapped(MeasuredResponse d);

/// The record with its accelerations s times as large: read in another unit (s = g: a record in
/// g read as m/s^2; s = 1/g the other way round).
MeasuredResponse scaled(MeasuredResponse d, double s);
/// The record's x_M'' times sx and z_M'' times sz (a gain of each channel's sensor).
MeasuredResponse scaled_channels(MeasuredResponse d, double sx, double sz);
/// Throws oscidrum::Error unless IdentifyOptions::gain_uncertainty is in [0, 0.5] (identify's
/// check, and identify_pass's before any window, so that a pass refuses it once).
void check_gain_uncertainty(double gain_uncertainty);

/// What a fit in a reading the record left open says (IdentifyOptions::z_open, units_open;
/// Reference::z_open, units_open): z_M'' negated, the accelerations in g, or both, `where` (a
/// calibration's references; empty: the window), chi2 the reduced chi^2 so, s2 as read.
std::string open_reading_warning(bool z_negated, bool in_g, double chi2, double s2,
                                 const std::string& where);

}  // namespace oscidrum::detail
