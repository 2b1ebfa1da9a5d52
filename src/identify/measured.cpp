// The measured response of a record's window (identify.hpp): its harmonics with their
// covariance, noise, peaks and area, as the fit compares them with the model's.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "metrics/median_step.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/identify.hpp"
#include "oscidrum/record.hpp"
#include "util/format.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {
namespace {

std::string num(double v) { return detail::shortest(v); }

// Legendre polynomials P_0 ... P_d at u (Bonnet's recurrence).
void legendre(double u, int d, std::vector<double>& P) {
  P[0] = 1.0;
  if (d >= 1) P[1] = u;
  for (int k = 1; k < d; ++k) P[k + 1] = ((2 * k + 1) * u * P[k] - k * P[k - 1]) / (k + 1);
}

// cos(k w), sin(k w), k = 0 ... m, w the phase 2 pi `turns` (detail::harmonics_turns).
void harmonics_at(double turns, int m, std::vector<double>& c, std::vector<double>& s) {
  detail::harmonics_turns(turns, m, c.data(), s.data());
}

// The periodic signal of harmonics 1 ... N over one period: extremes and area.
void signal_shape(const std::vector<std::complex<double>>& cx,
                  const std::vector<std::complex<double>>& cz, MeasuredResponse& d) {
  constexpr int kSamples = 1024;
  const int N = static_cast<int>(cx.size());
  std::vector<double> x(kSamples), z(kSamples), cn(N + 1), sn(N + 1);
  for (int j = 0; j < kSamples; ++j) {
    harmonics_at(static_cast<double>(j) / kSamples, N, cn, sn);  // w = 2 pi j / 1024
    double sx = 0, sz = 0;
    for (int n = 1; n <= N; ++n) {
      // A sin(n w + theta) = Re C sin(n w) + Im C cos(n w).
      sx += cx[n - 1].real() * sn[n] + cx[n - 1].imag() * cn[n];
      sz += cz[n - 1].real() * sn[n] + cz[n - 1].imag() * cn[n];
    }
    x[j] = sx;
    z[j] = sz;
  }
  const auto [xlo, xhi] = std::minmax_element(x.begin(), x.end());
  const auto [zlo, zhi] = std::minmax_element(z.begin(), z.end());
  d.ddx_min = *xlo;
  d.ddx_max = *xhi;
  d.ddz_min = *zlo;
  d.ddz_max = *zhi;
  d.area = enclosed_area(x, z);
}

// The least-squares fit of two channels (about their means) on a trend (Legendre polynomials
// P_0 ... P_d over the window) and the harmonics of the given orders (ascending) about t_ref:
// normal equations from sums (products of harmonics are harmonics: sums of cos, sin of k w,
// k <= 2 max order; the rest accumulated per sample), O(M n d) work, O(p^2) memory. Columns:
// the trend's, then cos and sin of each order in turn.
struct HarmonicFit {
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
  Eigen::VectorXd cx, cz;
  double rss_x = 0, rss_z = 0;  // residual sums of squares, summed explicitly (residual_pass)
  double explained_x = 0, explained_z = 0;  // b^T c: the sums of squares the fit explains
  bool ok = false;                          // the samples determine every column
};

// d = -1: no trend. The residuals themselves into rx, rz where given; residual_pass false: no
// second pass (rss_x, rss_z left 0).
HarmonicFit fit_harmonics(std::span<const double> t, std::span<const double> yx,
                          std::span<const double> yz, double f, double t_ref, int d,
                          const std::vector<int>& orders, std::vector<double>* rx = nullptr,
                          std::vector<double>* rz = nullptr, bool residual_pass = true) {
  const std::size_t M = t.size();
  const int np = d + 1, n_orders = static_cast<int>(orders.size()), p = np + 2 * n_orders;
  const int top = orders.empty() ? 0 : orders.back();
  const double mid = 0.5 * (t.front() + t.back()), span = t.back() - t.front();
  std::vector<double> P(static_cast<std::size_t>(np)), sc(2 * top + 1, 0.0), ss(2 * top + 1, 0.0);
  Eigen::MatrixXd pc = Eigen::MatrixXd::Zero(np, n_orders),
                  ps = Eigen::MatrixXd::Zero(np, n_orders), pp = Eigen::MatrixXd::Zero(np, np);
  Eigen::VectorXd bx = Eigen::VectorXd::Zero(p), bz = Eigen::VectorXd::Zero(p);
  std::vector<double> co(static_cast<std::size_t>(n_orders)), si(co.size());
  detail::HarmonicsInOrder h(t, t_ref, f, 2 * top);
  for (std::size_t i = 0; i < M; ++i) {
    h.at(i);
    if (np > 0) legendre(2.0 * (t[i] - mid) / span, d, P);
    const double x = yx[i], z = yz[i];
    for (int k = 0; k <= 2 * top; ++k) {
      sc[k] += h.cos(k);
      ss[k] += h.sin(k);
    }
    for (int a = 0; a < n_orders; ++a) {
      co[static_cast<std::size_t>(a)] = h.cos(orders[a]);
      si[static_cast<std::size_t>(a)] = h.sin(orders[a]);
    }
    for (int j = 0; j < np; ++j) {
      for (int a = 0; a < n_orders; ++a) {
        pc(j, a) += P[j] * co[static_cast<std::size_t>(a)];
        ps(j, a) += P[j] * si[static_cast<std::size_t>(a)];
      }
      for (int l = j; l < np; ++l) pp(j, l) += P[j] * P[l];
      bx[j] += x * P[j];
      bz[j] += z * P[j];
    }
    for (int a = 0; a < n_orders; ++a) {
      bx[np + 2 * a] += x * co[static_cast<std::size_t>(a)];
      bx[np + 2 * a + 1] += x * si[static_cast<std::size_t>(a)];
      bz[np + 2 * a] += z * co[static_cast<std::size_t>(a)];
      bz[np + 2 * a + 1] += z * si[static_cast<std::size_t>(a)];
    }
  }
  Eigen::MatrixXd G(p, p);
  for (int j = 0; j < np; ++j) {
    for (int l = j; l < np; ++l) G(j, l) = G(l, j) = pp(j, l);
    for (int a = 0; a < n_orders; ++a) {
      G(j, np + 2 * a) = G(np + 2 * a, j) = pc(j, a);
      G(j, np + 2 * a + 1) = G(np + 2 * a + 1, j) = ps(j, a);
    }
  }
  auto sum_sin = [&](int k) { return k >= 0 ? ss[k] : -ss[-k]; };
  for (int i = 0; i < n_orders; ++i)
    for (int j = 0; j < n_orders; ++j) {
      const int a = orders[i], b = orders[j];
      const int ca = np + 2 * i, sa = ca + 1, cb = np + 2 * j, sb = cb + 1;
      const double cd = sc[std::abs(a - b)], cs = sc[a + b];
      G(ca, cb) = 0.5 * (cd + cs);                          // cos a cos b
      G(sa, sb) = 0.5 * (cd - cs);                          // sin a sin b
      G(ca, sb) = 0.5 * (sum_sin(a + b) - sum_sin(a - b));  // cos a sin b
      G(sb, ca) = G(ca, sb);
    }
  HarmonicFit fit;
  fit.ldlt.compute(G);
  fit.ok = fit.ldlt.info() == Eigen::Success && fit.ldlt.rcond() > 1e-12;
  if (!fit.ok) return fit;
  fit.cx = fit.ldlt.solve(bx);
  fit.cz = fit.ldlt.solve(bz);
  fit.explained_x = bx.dot(fit.cx);
  fit.explained_z = bz.dot(fit.cz);
  detail::HarmonicsInOrder again(t, t_ref, f, top);
  for (std::size_t i = 0; residual_pass && i < M; ++i) {
    again.at(i);
    if (np > 0) legendre(2.0 * (t[i] - mid) / span, d, P);
    double fx = 0, fz = 0;
    for (int j = 0; j < np; ++j) {
      fx += fit.cx[j] * P[j];
      fz += fit.cz[j] * P[j];
    }
    for (int a = 0; a < n_orders; ++a) {
      const double c = again.cos(orders[a]), s = again.sin(orders[a]);
      fx += fit.cx[np + 2 * a] * c + fit.cx[np + 2 * a + 1] * s;
      fz += fit.cz[np + 2 * a] * c + fit.cz[np + 2 * a + 1] * s;
    }
    fit.rss_x += (yx[i] - fx) * (yx[i] - fx);
    fit.rss_z += (yz[i] - fz) * (yz[i] - fz);
    if (rx) (*rx)[i] = yx[i] - fx;
    if (rz) (*rz)[i] = yz[i] - fz;
  }
  return fit;
}

// The harmonics beyond N that the window can tell apart from the fitted ones and from each
// other: order n's frequency n f folded about the sampling rate (1 / the median step) is at least
// two of the window's frequency bins (2 / its span) from 0, from every fitted or chosen order's,
// and at least one from half the rate; up to order 4 (N + 1), at most 100. The noise is
// estimated with them fitted too: a stick-slip signal's harmonics decay slowly (x_M'' jumps at
// each switch), and left in the residual they would count as noise, by a different share in
// each channel (tests/identify, `MeasureWindow.TheNoiseIsNotTheHarmonicsBeyondThoseCompared`).
std::vector<int> separable_orders(double f, double step, double span, int N) {
  std::vector<int> orders;
  if (!(step > 0.0 && span > 0.0)) return orders;
  const double rate = 1.0 / step, bin = 1.0 / span;
  const auto folded = [&](int n) {
    const double a = std::fmod(n * f, rate);
    return std::min(a, rate - a);
  };
  std::vector<double> taken;
  for (int n = 1; n <= N; ++n) taken.push_back(folded(n));
  const int top = std::min(4 * (N + 1), 100);
  for (int n = N + 1; n <= top; ++n) {
    const double a = folded(n);
    if (a < 2.0 * bin || std::abs(a - 0.5 * rate) < bin) continue;
    if (std::any_of(taken.begin(), taken.end(),
                    [&](double b) { return std::abs(a - b) < 2.0 * bin; }))
      continue;
    taken.push_back(a);
    orders.push_back(n);
  }
  return orders;
}

// The lowest order beyond N whose frequency folds to within one bin of half the sampling rate
// (0: none up to separable_orders' top). separable_orders leaves such orders out, as their cosine
// and sine cannot be told apart there; but a record sampled in step with an even number of
// samples per period folds orders M/2, 3M/2, ... exactly onto half the rate, and what they leave
// in the residual (+a, -a, ... the same every period) is not noise.
int nyquist_order(double f, double step, double span, int N) {
  if (!(step > 0.0 && span > 0.0)) return 0;
  const double rate = 1.0 / step, bin = 1.0 / span;
  const int top = std::min(4 * (N + 1), 100);
  for (int n = N + 1; n <= top; ++n) {
    const double a = std::fmod(n * f, rate);
    if (std::abs(std::min(a, rate - a) - 0.5 * rate) < bin) return n;
  }
  return 0;
}

// What the cosine and sine of frequency nu at the samples' times explain of the residuals (their
// projection), and how many independent columns they are: one where nu folds onto half the
// sampling rate exactly (the sine vanishes at every sample), two where it beats against it.
struct Projection {
  double explained_x = 0.0, explained_z = 0.0;
  int rank = 0;
};
Projection project_frequency(std::span<const double> t, double t_ref, double nu,
                             const std::vector<double>& rx, const std::vector<double>& rz) {
  const auto M = static_cast<Eigen::Index>(t.size());
  Eigen::MatrixXd A(M, 2);
  for (Eigen::Index i = 0; i < M; ++i) {
    const double w = 2.0 * M_PI * nu * (t[static_cast<std::size_t>(i)] - t_ref);
    A(i, 0) = std::cos(w);
    A(i, 1) = std::sin(w);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU);
  const Eigen::VectorXd& s = svd.singularValues();
  Projection out;
  const Eigen::Map<const Eigen::VectorXd> x(rx.data(), M), z(rz.data(), M);
  for (Eigen::Index k = 0; k < 2; ++k) {
    if (!(s[k] > 1e-8 * s[0])) continue;
    const double px = svd.matrixU().col(k).dot(x), pz = svd.matrixU().col(k).dot(z);
    out.explained_x += px * px;
    out.explained_z += pz * pz;
    ++out.rank;
  }
  return out;
}

}  // namespace

MeasuredResponse measured_response(const RecordMetrics& m, double f, std::size_t samples) {
  if (m.ddx_harmonics.size() < 2 || samples == 0)
    throw Error("identify: the record's metrics hold no harmonics");
  MeasuredResponse d;
  d.f = f;
  d.n_signal = static_cast<int>(m.ddx_harmonics.size()) - 1;
  d.samples = samples;
  // Mean square of the fitted signals about their means (the residuals are relative to the RMS
  // about the mean: analyze_record).
  double px = 0, pz = 0;
  for (std::size_t n = 1; n < m.ddx_harmonics.size(); ++n) {
    px += 0.5 * m.ddx_harmonics[n].amplitude * m.ddx_harmonics[n].amplitude;
    pz += 0.5 * m.ddz_harmonics[n].amplitude * m.ddz_harmonics[n].amplitude;
    d.ddx.push_back(std::polar(m.ddx_harmonics[n].amplitude, m.ddx_harmonics[n].phase));
    d.ddz.push_back(std::polar(m.ddz_harmonics[n].amplitude, m.ddz_harmonics[n].phase));
  }
  // residual = s / rms with rms^2 = fitted^2 + s^2, so s^2 = fitted^2 r^2 / (1 - r^2).
  auto noise = [](double fitted, double r) {
    const double rr = std::min(r * r, 0.99);
    return std::sqrt(fitted * rr / (1.0 - rr));
  };
  d.noise_x = noise(px, m.residual_x);
  d.noise_z = noise(pz, m.residual_z);
  const double k = std::sqrt(2.0 / static_cast<double>(samples));
  // A floor (1e-6 of the signal) keeps the weights finite for noise-free records.
  d.sigma_x = std::max(d.noise_x * k, 1e-6 * std::sqrt(px) + 1e-300);
  d.sigma_z = std::max(d.noise_z * k, 1e-6 * std::sqrt(pz) + 1e-300);
  d.ddx_max = m.ddx_max;
  d.ddx_min = m.ddx_min;
  d.ddz_max = m.ddz_max;
  d.ddz_min = m.ddz_min;
  d.area = m.area;
  return d;
}

MeasuredResponse measure_window(std::span<const double> t, std::span<const double> ddx,
                                std::span<const double> ddz, double f, const MeasureOptions& o) {
  if (!(std::isfinite(f) && f > 0)) throw Error("identify: f must be > 0 [Hz]; got " + num(f));
  if (t.size() != ddx.size() || t.size() != ddz.size())
    throw Error("identify: t, ddx_M and ddz_M must have the same length; got " +
                std::to_string(t.size()) + ", " + std::to_string(ddx.size()) + ", " +
                std::to_string(ddz.size()));
  if (o.trend_degree < 0 || o.trend_degree > 10)
    throw Error("identify: the trend's degree must be in [0, 10]; got " +
                std::to_string(o.trend_degree));
  if (o.harmonics < 0 || o.harmonics > kMaxRecordHarmonics)
    throw Error("identify: the harmonics fitted must be in [0, " +
                std::to_string(kMaxRecordHarmonics) + "] (0: from the sampling); got " +
                std::to_string(o.harmonics));
  if (o.period < 1 || o.period > 4)
    throw Error("identify: the window's period must be in [1, 4] excitation periods; got " +
                std::to_string(o.period));
  if (t.size() < 8) throw Error("identify: a window needs at least 8 samples");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(ddx[i]) || !std::isfinite(ddz[i]))
      throw Error("identify: non-finite value in sample " + std::to_string(i + 1));
    if (i > 0 && !(t[i] > t[i - 1]))
      throw Error("identify: t must increase strictly; sample " + std::to_string(i + 1) +
                  " has t = " + num(t[i]) + " after " + num(t[i - 1]));
  }
  const std::size_t M = t.size();
  const double span = t.back() - t.front();
  const double per_period = 1.0 / (f * detail::median_step(t));  // samples per period
  int N = o.harmonics;
  if (N == 0)
    N = std::min(kMaxMeasuredHarmonics, static_cast<int>(std::floor((per_period - 2) / 2)));
  if (N < 1 || 2.0 * N + 2 > per_period + 1e-9)
    throw Error("identify: " + num(std::round(per_period * 10) / 10) +
                " samples per period are too few for " + std::to_string(std::max(N, 1)) +
                " harmonics (need at least " + std::to_string(2 * std::max(N, 1) + 2) + ")");
  const int d = o.trend_degree, np = d + 1, p = np + 2 * N;
  if (M < static_cast<std::size_t>(p) + 8)
    throw Error("identify: " + std::to_string(M) + " samples are too few for " + std::to_string(p) +
                " fitted parameters");
  // The columns of harmonic n of f: of order n in the fit on the harmonics of f, of order
  // stride n in the joint fit on the harmonics of f / stride (a period-p window, below).
  int stride = 1;
  auto col_cos = [&](int n) { return np + 2 * (stride * n - 1); };
  auto col_sin = [&](int n) { return np + 2 * (stride * n - 1) + 1; };

  MeasuredResponse out;
  out.f = f;
  out.t_ref = t.front();
  out.t_first = t.front();
  out.t_last = t.back();
  out.samples = M;
  out.n_signal = N;
  double mean_x = 0, mean_z = 0;  // fitted about the means: no cancellation against offsets
  for (std::size_t i = 0; i < M; ++i) {
    mean_x += ddx[i];
    mean_z += ddz[i];
  }
  mean_x /= static_cast<double>(M);
  mean_z /= static_cast<double>(M);

  std::vector<double> yx(M), yz(M);
  for (std::size_t i = 0; i < M; ++i) {
    yx[i] = ddx[i] - mean_x;
    yz[i] = ddz[i] - mean_z;
  }
  std::vector<int> orders(static_cast<std::size_t>(N));
  for (int n = 1; n <= N; ++n) orders[static_cast<std::size_t>(n - 1)] = n;
  std::vector<double> rx(M), rz(M);
  HarmonicFit fit = fit_harmonics(t, yx, yz, f, out.t_ref, d, orders, &rx, &rz);
  if (!fit.ok)
    throw Error("identify: the window's samples do not determine " + std::to_string(N) +
                " harmonics and a trend of degree " + std::to_string(d) +
                " (a gap too large, or too few samples per period)");
  const Eigen::LDLT<Eigen::MatrixXd>& ldlt = fit.ldlt;
  const Eigen::VectorXd& cx = fit.cx;
  const Eigen::VectorXd& cz = fit.cz;
  double dof = static_cast<double>(M) - p;
  // The residual the noise is taken from: the harmonics' fit's, or the joint fit's with the
  // subharmonics of a period-p window.
  double rss_x = fit.rss_x, rss_z = fit.rss_z;
  if (o.period > 1) {
    // A period-p response: its subharmonics are the motion's, not noise. Counted as noise (a
    // drum lifting off every second period: 17 m/s^2 for the 1.4 m/s^2 of the record's noise),
    // they made the chi-square of a far-off fit look good, and a G 1.5 % off came with an
    // interval of 0.04 % and no warning. The noise is the residual of the joint fit of the
    // trend, the harmonics and the subharmonics, as the harmonics of f/p (its multiples of p
    // are the harmonics of f, whose coefficients above stay those compared): the residual
    // alone refitted on the subharmonics kept what the trend had taken of them (0.6 % of an
    // f/2 component over 40 periods: a noise 1.27 times the true one).
    std::vector<int> all;
    for (int k = 1; k <= o.period * N; ++k) all.push_back(k);
    const double dof_sub = static_cast<double>(M) - np - 2.0 * static_cast<double>(all.size());
    if (dof_sub >= 0.5 * static_cast<double>(M)) {
      std::vector<double> sx(M), sz(M);
      HarmonicFit s = fit_harmonics(t, yx, yz, f / o.period, out.t_ref, d, all, &sx, &sz);
      if (s.ok) {
        // The compared harmonics of f and their covariance from the joint fit too: the first
        // fit's cubic trend took part of the subharmonics and biased them (A(f) of x_M'' 7e-4
        // low on a noise-free period-2 record of 20 periods, a relative residual of 8e-4 at the
        // right G; the joint fit: 7e-7).
        rss_x = s.rss_x;
        rss_z = s.rss_z;
        rx = std::move(sx);
        rz = std::move(sz);
        dof = dof_sub;
        out.subharmonics_of = o.period;
        fit = std::move(s);
        stride = o.period;
      }
    }
  }
  out.noise_x = std::sqrt(rss_x / dof);
  out.noise_z = std::sqrt(rss_z / dof);
  // The noise that weighs the compared harmonics: the residual less what the separable
  // harmonics beyond N, and the harmonic on half the sampling rate, explain of it (where the
  // samples leave the degrees of freedom for them). Without the latter, a record sampled in step
  // at 12, 14 or 16 samples per period had one channel's noise 5 to 30 times too large: that
  // channel hardly counted, the reduced chi^2 fell to 0.45, and the 95 % intervals covered the
  // truth in 81-87 % of windows (`MeasureWindow.TheHarmonicOnHalfTheSamplingRateIsNotNoise`).
  // In a period-p window's joint fit the orders are those of f / p up to p N: beyond them the
  // subharmonics' orders are the motion's as much as the harmonics' (a period-2 window at 15
  // samples per period folds order 7.5 exactly onto half the sampling rate).
  double noise2_x = out.noise_x * out.noise_x, noise2_z = out.noise_z * out.noise_z;
  {
    const double step = detail::median_step(t);
    const double f_base = f / stride;
    const int N_base = stride * N;
    const std::vector<int> extra = separable_orders(f_base, step, span, N_base);
    const int nyquist = nyquist_order(f_base, step, span, N_base);
    double explained_x = 0.0, explained_z = 0.0, dof_more = dof;
    if (!extra.empty() &&
        dof - 2.0 * static_cast<double>(extra.size()) >= 0.5 * static_cast<double>(M)) {
      // The residual fitted on the separable harmonics alone (no trend): it is orthogonal to
      // the first fit's columns, and theirs nearly so to these, so that this explains what the
      // joint fit would to second order in their small correlations, without their products
      // with the trend and the first fit's harmonics.
      const HarmonicFit more =
          fit_harmonics(t, rx, rz, f_base, out.t_ref, -1, extra, nullptr, nullptr, false);
      if (more.ok) {
        explained_x += more.explained_x;
        explained_z += more.explained_z;
        dof_more -= 2.0 * static_cast<double>(extra.size());
      }
    }
    if (nyquist > 0) {
      const Projection half = project_frequency(t, out.t_ref, nyquist * f_base, rx, rz);
      if (dof_more - half.rank >= 0.5 * static_cast<double>(M)) {
        explained_x += half.explained_x;
        explained_z += half.explained_z;
        dof_more -= half.rank;
      }
    }
    if (dof_more < dof) {
      noise2_x = std::min(noise2_x, std::max(0.0, rss_x - explained_x) / dof_more);
      noise2_z = std::min(noise2_z, std::max(0.0, rss_z - explained_z) / dof_more);
    }
  }
  for (int n = 1; n <= N; ++n) {
    // a cos + b sin = A sin(x + theta): C = A e^{i theta} = b + i a.
    out.ddx.emplace_back(cx[col_sin(n)], cx[col_cos(n)]);
    out.ddz.emplace_back(cz[col_sin(n)], cz[col_cos(n)]);
  }
  out.trend_x.assign(cx.data(), cx.data() + np);
  out.trend_z.assign(cz.data(), cz.data() + np);
  out.trend_x[0] += mean_x;
  out.trend_z[0] += mean_z;

  // Covariance of (Re C_n, Im C_n) = (b_n, a_n), n <= K: s^2 [G^-1] on those rows and columns.
  const int K = std::clamp(o.covariance, 1, N);
  const int cols = static_cast<int>(ldlt.rows());  // the fit's: trend and (sub)harmonics
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(cols, 2 * K);
  std::vector<int> idx;
  for (int n = 1; n <= K; ++n) {
    idx.push_back(col_sin(n));
    idx.push_back(col_cos(n));
  }
  for (int k = 0; k < 2 * K; ++k) E(idx[static_cast<std::size_t>(k)], k) = 1.0;
  const Eigen::MatrixXd X = ldlt.solve(E);
  // A floor (1e-6 of the signal) keeps the weights finite for noise-free records.
  double power_x = 0, power_z = 0;
  for (int n = 1; n <= N; ++n) {
    power_x += 0.5 * std::norm(out.ddx[n - 1]);
    power_z += 0.5 * std::norm(out.ddz[n - 1]);
  }
  const double floor_x = 1e-6 * std::sqrt(power_x) + 1e-300,
               floor_z = 1e-6 * std::sqrt(power_z) + 1e-300;
  const double s2x = std::max(noise2_x, floor_x * floor_x * static_cast<double>(M) / 2);
  const double s2z = std::max(noise2_z, floor_z * floor_z * static_cast<double>(M) / 2);
  out.cov_x.resize(static_cast<std::size_t>(4 * K * K));
  out.cov_z.resize(out.cov_x.size());
  double var_x = 0, var_z = 0;
  for (int a = 0; a < 2 * K; ++a) {
    for (int b = 0; b < 2 * K; ++b) {
      const double g =
          0.5 * (X(idx[static_cast<std::size_t>(a)], b) + X(idx[static_cast<std::size_t>(b)], a));
      out.cov_x[static_cast<std::size_t>(a * 2 * K + b)] = s2x * g;
      out.cov_z[static_cast<std::size_t>(a * 2 * K + b)] = s2z * g;
    }
    var_x += out.cov_x[static_cast<std::size_t>(a * 2 * K + a)];
    var_z += out.cov_z[static_cast<std::size_t>(a * 2 * K + a)];
  }
  out.sigma_x = std::sqrt(var_x / (2 * K));
  out.sigma_z = std::sqrt(var_z / (2 * K));
  signal_shape(out.ddx, out.ddz, out);

  // Sampled in step with the excitation (record.hpp): the harmonics above the N fitted alias onto
  // the fitted ones the same way in every period. (From the median step, which lost samples do
  // not shift; times rounded coarsely to a logger's resolution do, and such a record is not taken
  // to be in step.)
  const bool in_step = sampled_in_step(t, f);
  if (in_step) {
    // The estimator's rows: C_n = sum_i w_i y_i with w_i = B_i X, B_i the basis at sample i.
    out.alias_t.resize(M);
    out.alias_w.assign(M * static_cast<std::size_t>(2 * K), 0.0);
    // The fit's basis: the harmonics of f / stride (of f itself unless a period-p window's joint
    // fit gives the harmonics).
    const int top = stride * N;
    std::vector<double> basis(static_cast<std::size_t>(cols)), P(static_cast<std::size_t>(np)),
        cm(static_cast<std::size_t>(top) + 1), sm(static_cast<std::size_t>(top) + 1);
    const double mid = 0.5 * (t.front() + t.back());
    for (std::size_t i = 0; i < M; ++i) {
      legendre(2.0 * (t[i] - mid) / span, d, P);
      harmonics_at(f / stride * (t[i] - out.t_ref), top, cm, sm);
      for (int j = 0; j < np; ++j) basis[static_cast<std::size_t>(j)] = P[j];
      for (int k = 1; k <= top; ++k) {
        basis[static_cast<std::size_t>(np + 2 * (k - 1))] = cm[k];
        basis[static_cast<std::size_t>(np + 2 * (k - 1) + 1)] = sm[k];
      }
      out.alias_t[i] = t[i] - out.t_ref;
      for (int k = 0; k < 2 * K; ++k) {
        double w = 0.0;
        for (int j = 0; j < cols; ++j) w += basis[static_cast<std::size_t>(j)] * X(j, k);
        out.alias_w[i * static_cast<std::size_t>(2 * K) + static_cast<std::size_t>(k)] = w;
      }
    }
  }
  return out;
}

}  // namespace oscidrum
