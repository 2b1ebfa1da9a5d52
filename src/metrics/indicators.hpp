// indicators.hpp (internal): the compaction indicators that simulated steady states (Metrics)
// and measured records (RecordMetrics) share, from their harmonics (docs/outputs.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "oscidrum/metrics.hpp"

namespace oscidrum::detail {

/// A fundamental below this fraction of the signal's largest harmonic counts as absent: it is
/// numerical noise (the integration tolerances leave ~1e-8), not a physical component.
inline constexpr double kAbsentFundamental = 1e-6;

/// a / A_1 of the spectrum h; NaN when the fundamental is absent (a ratio to it is undefined:
/// e.g. z_M'' without driving torque has only even harmonics, paper Fig. 19b).
inline double ratio_to_fundamental(double a, const Spectrum& h) {
  double largest = 0.0;
  for (std::size_t n = 1; n < h.size(); ++n) largest = std::max(largest, h[n].amplitude);
  return h[1].amplitude > kAbsentFundamental * largest ? a / h[1].amplitude
                                                       : std::numeric_limits<double>::quiet_NaN();
}

/// Harmonic ratios A_2/A_1, A_3/A_1 of x_M'' and z_M'', the CMV-type value 300 A_2/A_1 of z_M''
/// and the THD of x_M'' from `ddx_overtones` = sum_{k>=2} A_k^2 of x_M'' [(m/s^2)^2]. The
/// harmonics must reach n = 2; the A_3 ratios are NaN without n = 3. M is Metrics or
/// RecordMetrics (OSCIDRUM_ACCELERATION_METRICS).
template <class M>
void set_acceleration_indicators(M& m, const Spectrum& hx, const Spectrum& hz,
                                 double ddx_overtones) {
  m.ddx_A2_A1 = ratio_to_fundamental(hx[2].amplitude, hx);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  m.ddx_A3_A1 = hx.size() > 3 ? ratio_to_fundamental(hx[3].amplitude, hx) : nan;
  m.ddz_A2_A1 = ratio_to_fundamental(hz[2].amplitude, hz);
  m.ddz_A3_A1 = hz.size() > 3 ? ratio_to_fundamental(hz[3].amplitude, hz) : nan;
  // The compaction meter value CMV = C A(2f)/A(f) with C = 300 (Thurner and Sandstroem 1980),
  // here of the oscillation drum's vertical acceleration z_M''.
  m.cmv = 300.0 * m.ddz_A2_A1;
  m.ddx_thd = ratio_to_fundamental(std::sqrt(ddx_overtones), hx);
}

}  // namespace oscidrum::detail
