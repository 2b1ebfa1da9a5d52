// oscidrum/calibrate.hpp: the roller from reference records of known soil. A real roller is not
// the paper's Table 1: its unbalance, its suspension, its frame's load differ, and an
// identification with the wrong roller puts the difference into G. Calibration fits chosen
// parameters of the case (any positive real field, e.g. roller.M0, roller.kd, roller.cd,
// roller.P0) so that the model's harmonics of x_M'' and z_M'' match those measured on one or
// more references whose soil is known, all at once (one least-squares problem, each reference
// with its own time shift); the calibrated case is then the base of `identify` (docs/identify.md,
// "Calibrating the roller").
#pragma once

#include <limits>
#include <span>
#include <string>
#include <vector>

#include "oscidrum/identify.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/record.hpp"

namespace oscidrum {

/// One reference: a record's measured harmonics over a soil that is known.
struct Reference {
  std::string name;       ///< for the messages and the report (e.g. the file name)
  Soil soil;              ///< the soil under the reference (any soil.input)
  MeasuredResponse data;  ///< its measured harmonics (measure_record)
  /// Nothing said which way its z axis points, or in what unit its accelerations are
  /// (RecordColumns::z_open, units_open): a calibration that fits poorly as read but well with
  /// the open references read the other way (z_M'' negated, in g, or both) is taken so, with a
  /// warning (ReferenceFit::z_negated, read_in_g), as identify does a window.
  bool z_open = false;
  bool units_open = false;
  /// The G [Pa] on `scale` that `soil` was made from (soil_on_scale), when it was: a calibration
  /// that fits poorly as given but far better with every reference's G on the other scale says
  /// so in a warning (the calibration itself stays on the scale given). NaN: the soil was given
  /// otherwise.
  double G = std::numeric_limits<double>::quiet_NaN();
  SoilScale scale = SoilScale::formulas;
};

/// The measured response of a whole record (a reference): its f (windows.f, or estimated), the
/// gates of analyze_windows over the whole record (windows.window_periods is ignored), and its
/// harmonics by measure_window. Throws oscidrum::Error with the gate's reason when the record
/// fails one (a reference must be clean), when x_M'' or z_M'' is one value in every sample (a
/// dead channel), or for inconsistent input.
MeasuredResponse measure_record(std::span<const double> t, std::span<const double> ddx_M,
                                std::span<const double> ddz_M, const WindowOptions& windows = {},
                                const MeasureOptions& measure = {});

/// What is calibrated, and how (the fit's settings are identify's: IdentifyOptions).
struct CalibrateOptions {
  /// Keys of the case fields fitted (fields.hpp): real fields whose range is positive and whose
  /// value in the base case is > 0 and in effect (not roller.f, which each record gives, nor the
  /// soil, which each reference gives). Each is fitted on a log scale.
  std::vector<std::string> parameters{"roller.M0"};
  /// Each estimate stays within [start / range, start * range] (and the field's range) [-].
  double range = 10.0;
  int harmonics = 4;              ///< compare C_n for n = 1 ... harmonics of each reference [-]
  bool profile = true;            ///< 95 % intervals from the profile of the objective
  int max_iterations = 40;        ///< Levenberg-Marquardt iterations [-]
  double max_condition = 1e6;     ///< as IdentifyOptions::max_condition [-]
  double max_correlation = 0.99;  ///< as IdentifyOptions::max_correlation [-]
  double max_reduced_chi2 = 4.0;  ///< as IdentifyOptions::max_reduced_chi2 [-]
  double model_tolerance = 1e-6;  ///< as IdentifyOptions::model_tolerance [-]
  bool shooting = true;           ///< as IdentifyOptions::shooting
};

/// How the calibrated model fits one reference.
struct ReferenceFit {
  std::string name;
  double f = 0.0;                  ///< the record's excitation frequency [Hz]
  double time_shift = 0.0;         ///< tau [s]: record time = model time + tau (modulo 1/f)
  double rms_residual = 0.0;       ///< RMS of C_n(measured) - C_n(model) [m/s^2]
  double relative_residual = 0.0;  ///< ||C(measured) - C(model)|| / ||C(measured)|| [-]
  /// This reference's weighted sum of squares / (its measured values - 1) [-] (its share of the
  /// fit; about 1 when the model fits it to its noise).
  double reduced_chi2 = 0.0;
  /// The model was compared sampled at this reference's times (a record sampled in step with the
  /// excitation, whose raw samples alias; as Identification::model_sampled).
  bool model_sampled = false;
  bool z_negated = false;  ///< fitted with its z_M'' negated (Reference::z_open)
  bool read_in_g = false;  ///< fitted with its accelerations in g (Reference::units_open)
};

/// The result of a calibration.
struct Calibration {
  bool converged = false;
  std::string message;              ///< why it stopped
  std::vector<Estimate> estimates;  ///< one per CalibrateOptions::parameters, name = the key
  std::vector<ReferenceFit> references;
  double reduced_chi2 = 0.0;  ///< weighted sum of squares / degrees of freedom [-]
  double condition = 0.0;     ///< condition number of the column-scaled Jacobian [-]
  int iterations = 0;
  int simulations = 0;  ///< model runs [-]
  /// Parameters that cannot be told apart or have no effect, flat profiles, estimates at the
  /// edge of their range, a poor fit, a reference that fits much worse than the others.
  std::vector<std::string> warnings;
  Case calibrated;  ///< the base case with the estimates: the case to identify with
};

/// Fit options.parameters of `base` to the references (at least one; each with its own soil and
/// f; everything else, mu and MMd included, from `base`). Throws oscidrum::Error for invalid
/// input (an unknown or unfit key, no reference, fewer measured values than unknowns) or when the
/// model fails at the start.
Calibration calibrate(const Case& base, std::span<const Reference> references,
                      const CalibrateOptions& options = {});

}  // namespace oscidrum
