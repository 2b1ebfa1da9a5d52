// oscidrum/record.hpp: the metrics of a measured drum acceleration record, for comparing
// simulations with field measurements (paper Fig. 23). A measured record rarely holds a whole
// number of periods at a sampling rate commensurate with f, so the harmonics are fitted by least
// squares rather than read off a DFT.
#pragma once

#include <span>
#include <vector>

#include "oscidrum/metrics.hpp"

namespace oscidrum {

struct RecordMetrics {
  std::vector<Harmonic> ddx_harmonics;  ///< n = 0 ... n_max of x_M'' (absolute-time phases) [m/s^2]
  std::vector<Harmonic> ddz_harmonics;  ///< n = 0 ... n_max of z_M'' [m/s^2]
  double ddx_max = 0.0, ddx_min = 0.0;  ///< extremes of the fitted periodic x_M'' [m/s^2]
  double ddz_max = 0.0, ddz_min = 0.0;  ///< extremes of the fitted periodic z_M'' [m/s^2]
  double psi_xz = 0.0;      ///< theta_2(z) - 2 theta_1(x), wrapped (docs/model.md sec. 8)
  double area = 0.0;        ///< area of the fitted periodic figure [m^2/s^4]
  double cycles = 0.0;      ///< excitation periods the record spans [-]
  double residual_x = 0.0;  ///< RMS of record minus fit, relative to the RMS of x_M'' [-]
  double residual_z = 0.0;  ///< the same for z_M'' [-]
};

/// Fit y(t) = sum_{n=0}^{n_max} (a_n cos(n nu t) + b_n sin(n nu t)) to x_M'' and z_M'' by least
/// squares (t [s] strictly increasing, any spacing, at least one excitation period f [Hz]), then
/// evaluate the metrics on the fitted periodic signals (1024 samples per period). The fitted
/// signal is what repeats from period to period: noise and slow drifts go to the residuals.
/// Throws oscidrum::Error on inconsistent sizes, non-finite values, a record shorter than one
/// period or too coarse for n_max (fewer than 2 n_max + 1 samples per period).
RecordMetrics analyze_record(std::span<const double> t, std::span<const double> ddx_M,
                             std::span<const double> ddz_M, double f, int n_max = 10);

}  // namespace oscidrum
