// The best fit in the record's time (identify.hpp, fit_curves): what the fit plots draw beside
// the measured samples.
#include <algorithm>
#include <cmath>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/record_reader.hpp"
#include "oscidrum/simulate.hpp"

namespace oscidrum {

FitCurves fit_curves(const Identification& id, std::span<const double> t) {
  Case c = id.fitted;
  c.numerics.output_periods = 1;
  c.numerics.samples_per_period = 4096;  // linear interpolation to about 1e-6 of a peak
  const Result r = simulate(c);
  if (!ok(r.status))
    throw Error("the best fit's model did not reach its steady state: " + r.message);
  const std::size_t m = r.samples.size();
  const double T = 1.0 / c.roller.f;
  // Record time = model time + tau: a record time t is the model's phase (t - tau - t_0) / T
  // past its first sample t_0. The reductions modulo T come first, so that clock times such as
  // 1.7e9 s keep their precision.
  const double origin = std::fmod(id.time_shift + r.samples.t.front(), T);
  const MeasuredResponse& d = id.measured;
  const double mid = 0.5 * (d.t_first + d.t_last), half = 0.5 * (d.t_last - d.t_first);
  FitCurves out;
  out.ddx_M.resize(t.size());
  out.ddz_M.resize(t.size());
  std::vector<double> P;
  for (std::size_t i = 0; i < t.size(); ++i) {
    double u = std::fmod(std::fmod(t[i], T) - origin, T);
    if (u < 0) u += T;
    const double x = u / T * static_cast<double>(m);
    const std::size_t j = static_cast<std::size_t>(std::floor(x)) % m, j1 = (j + 1) % m;
    const double w = x - std::floor(x);
    out.ddx_M[i] = (1 - w) * r.samples.ddx_M[j] + w * r.samples.ddx_M[j1];
    out.ddz_M[i] = (1 - w) * r.samples.ddz_M[j] + w * r.samples.ddz_M[j1];
    // The trend: sum c_k P_k(v), v = (t - mid) / half (Legendre, Bonnet's recurrence).
    const std::size_t nt = std::max(d.trend_x.size(), d.trend_z.size());
    if (nt == 0 || !(half > 0)) continue;
    P.assign(nt, 0.0);
    const double v = (t[i] - mid) / half;
    P[0] = 1.0;
    if (nt > 1) P[1] = v;
    for (std::size_t k = 1; k + 1 < nt; ++k) {
      const double kk = static_cast<double>(k);
      P[k + 1] = ((2.0 * kk + 1) * v * P[k] - kk * P[k - 1]) / (kk + 1.0);
    }
    for (std::size_t k = 0; k < d.trend_x.size(); ++k) out.ddx_M[i] += d.trend_x[k] * P[k];
    for (std::size_t k = 0; k < d.trend_z.size(); ++k) out.ddz_M[i] += d.trend_z[k] * P[k];
  }
  // The model in the record's axes and units as read.
  const double to_read = id.read_in_g ? 1.0 / kStandardGravity : 1.0;
  for (double& x : out.ddx_M) x *= to_read;
  for (double& z : out.ddz_M) z *= id.z_negated ? -to_read : to_read;
  return out;
}

}  // namespace oscidrum
