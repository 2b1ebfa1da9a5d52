// Metrics of a measured acceleration record by a least-squares harmonic fit (record.hpp).
#include "oscidrum/record.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "indicators.hpp"
#include "oscidrum/error.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

using detail::shortest;
std::string num(double v) { return shortest(v); }

// Least-squares coefficients (a_0, a_1, b_1, ..., a_N, b_N) of y on the harmonic basis.
Eigen::VectorXd fit(const Eigen::MatrixXd& basis, std::span<const double> y) {
  const Eigen::Map<const Eigen::VectorXd> v(y.data(), static_cast<Eigen::Index>(y.size()));
  return basis.colPivHouseholderQr().solve(v);
}

std::vector<Harmonic> to_harmonics(const Eigen::VectorXd& c, int n_max) {
  // a cos + b sin = A sin(x + theta) with A sin theta = a, A cos theta = b.
  std::vector<Harmonic> h(n_max + 1);
  h[0] = {std::abs(c[0]), c[0] >= 0 ? M_PI / 2 : -M_PI / 2};
  for (int n = 1; n <= n_max; ++n) {
    const double a = c[2 * n - 1], b = c[2 * n];
    h[n] = {std::hypot(a, b), wrap_pi(std::atan2(a, b))};
  }
  return h;
}

double relative_rms(const Eigen::MatrixXd& basis, const Eigen::VectorXd& c,
                    std::span<const double> y) {
  const Eigen::Map<const Eigen::VectorXd> v(y.data(), static_cast<Eigen::Index>(y.size()));
  const double rms = std::sqrt(v.squaredNorm() / static_cast<double>(y.size()));
  const double res = std::sqrt((basis * c - v).squaredNorm() / static_cast<double>(y.size()));
  return rms > 0 ? res / rms : 0.0;
}

}  // namespace

RecordMetrics analyze_record(std::span<const double> t, std::span<const double> ddx,
                             std::span<const double> ddz, double f, int n_max) {
  if (!(std::isfinite(f) && f > 0)) throw Error("record: f must be > 0 [Hz]; got " + num(f));
  if (n_max < 2)
    throw Error("record: n_max must be >= 2 (psi needs the 2f harmonic); got " +
                std::to_string(n_max));
  if (t.size() != ddx.size() || t.size() != ddz.size())
    throw Error("record: t, ddx_M and ddz_M must have the same length; got " +
                std::to_string(t.size()) + ", " + std::to_string(ddx.size()) + ", " +
                std::to_string(ddz.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(ddx[i]) || !std::isfinite(ddz[i]))
      throw Error("record: non-finite value in row " + std::to_string(i + 1));
    if (i > 0 && !(t[i] > t[i - 1]))
      throw Error("record: t must increase strictly; row " + std::to_string(i + 1) +
                  " has t = " + num(t[i]) + " after " + num(t[i - 1]));
  }
  RecordMetrics m;
  m.cycles = t.empty() ? 0.0 : (t.back() - t.front()) * f;
  if (t.size() < 2 || m.cycles < 1.0)
    throw Error("record: must span at least one excitation period (1/f = " + num(1.0 / f) +
                " s); it spans " + num(t.empty() ? 0.0 : t.back() - t.front()) + " s");
  const double per_period = static_cast<double>(t.size() - 1) / m.cycles;
  if (per_period < 2.0 * n_max + 1.0)
    throw Error("record: " + num(per_period) + " samples per period are too few for n_max = " +
                std::to_string(n_max) + " (need at least " + std::to_string(2 * n_max + 1) + ")");

  const double nu = 2.0 * M_PI * f;
  const Eigen::Index rows = static_cast<Eigen::Index>(t.size());
  Eigen::MatrixXd basis(rows, 2 * n_max + 1);
  for (Eigen::Index i = 0; i < rows; ++i) {
    basis(i, 0) = 1.0;
    for (int n = 1; n <= n_max; ++n) {
      const double phase = n * nu * t[static_cast<std::size_t>(i)];
      basis(i, 2 * n - 1) = std::cos(phase);
      basis(i, 2 * n) = std::sin(phase);
    }
  }
  const Eigen::VectorXd cx = fit(basis, ddx), cz = fit(basis, ddz);
  m.ddx_harmonics = to_harmonics(cx, n_max);
  m.ddz_harmonics = to_harmonics(cz, n_max);
  m.residual_x = relative_rms(basis, cx, ddx);
  m.residual_z = relative_rms(basis, cz, ddz);
  m.psi_xz = wrap_pi(m.ddz_harmonics[2].phase - 2.0 * m.ddx_harmonics[1].phase);
  // THD of the fitted signal: its overtones are the fitted harmonics 2 ... n_max.
  double overtones = 0.0;
  for (int n = 2; n <= n_max; ++n) overtones += std::pow(m.ddx_harmonics[n].amplitude, 2);
  detail::set_acceleration_indicators(m, m.ddx_harmonics, m.ddz_harmonics, overtones);

  // The fitted periodic signals over one period, for the extremes and the area.
  constexpr int kSamples = 1024;
  std::vector<double> x(kSamples), z(kSamples);
  for (int j = 0; j < kSamples; ++j) {
    const double tj = static_cast<double>(j) / (kSamples * f);
    double sx = cx[0], sz = cz[0];
    for (int n = 1; n <= n_max; ++n) {
      const double c = std::cos(n * nu * tj), s = std::sin(n * nu * tj);
      sx += cx[2 * n - 1] * c + cx[2 * n] * s;
      sz += cz[2 * n - 1] * c + cz[2 * n] * s;
    }
    x[j] = sx;
    z[j] = sz;
  }
  const auto [xlo, xhi] = std::minmax_element(x.begin(), x.end());
  const auto [zlo, zhi] = std::minmax_element(z.begin(), z.end());
  m.ddx_min = *xlo;
  m.ddx_max = *xhi;
  m.ddz_min = *zlo;
  m.ddz_max = *zhi;
  m.area = enclosed_area(x, z);
  return m;
}

}  // namespace oscidrum
