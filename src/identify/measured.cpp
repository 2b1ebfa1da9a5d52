// The measured response of a record's window (identify.hpp, measured_response): its harmonics
// with their standard uncertainties, peaks and area, as the fit compares them with the model's.
#include <algorithm>
#include <cmath>
#include <complex>

#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"

namespace oscidrum {

MeasuredResponse measured_response(const RecordMetrics& m, double f, std::size_t samples) {
  if (m.ddx_harmonics.size() < 2 || samples == 0)
    throw Error("identify: the record's metrics hold no harmonics");
  MeasuredResponse d;
  d.f = f;
  d.n_signal = static_cast<int>(m.ddx_harmonics.size()) - 1;
  double px = 0, pz = 0;  // mean square of the fitted signals
  for (std::size_t n = 0; n < m.ddx_harmonics.size(); ++n) {
    const double k = n == 0 ? 1.0 : 0.5;
    px += k * m.ddx_harmonics[n].amplitude * m.ddx_harmonics[n].amplitude;
    pz += k * m.ddz_harmonics[n].amplitude * m.ddz_harmonics[n].amplitude;
    if (n > 0) {
      d.ddx.push_back(std::polar(m.ddx_harmonics[n].amplitude, m.ddx_harmonics[n].phase));
      d.ddz.push_back(std::polar(m.ddz_harmonics[n].amplitude, m.ddz_harmonics[n].phase));
    }
  }
  // residual = s / rms with rms^2 = fitted^2 + s^2, so s^2 = fitted^2 r^2 / (1 - r^2).
  auto noise = [](double fitted, double r) {
    const double rr = std::min(r * r, 0.99);
    return std::sqrt(fitted * rr / (1.0 - rr));
  };
  const double k = std::sqrt(2.0 / static_cast<double>(samples));
  // A floor (1e-6 of the signal) keeps the weights finite for noise-free records.
  d.sigma_x = std::max(noise(px, m.residual_x) * k, 1e-6 * std::sqrt(px) + 1e-300);
  d.sigma_z = std::max(noise(pz, m.residual_z) * k, 1e-6 * std::sqrt(pz) + 1e-300);
  d.ddx_max = m.ddx_max;
  d.ddx_min = m.ddx_min;
  d.ddz_max = m.ddz_max;
  d.ddz_min = m.ddz_min;
  d.area = m.area;
  return d;
}

}  // namespace oscidrum
