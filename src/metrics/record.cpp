// Metrics of a measured acceleration record by a least-squares harmonic fit (record.hpp).
#include "oscidrum/record.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "indicators.hpp"
#include "metrics/clipping.hpp"
#include "metrics/frequency_step.hpp"
#include "metrics/median_step.hpp"
#include "metrics/spectral_peak.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/output_table.hpp"
#include "util/format.hpp"
#include "util/one_value.hpp"
#include "util/small_angle.hpp"

namespace oscidrum {
namespace {

using detail::shortest;
std::string num(double v) { return shortest(v); }
// Four significant digits, for the lengths and frequencies a message reports.
std::string sig4(double v) { return detail::format("%.4g", v); }

// The least-squares fit of a record on the harmonic basis 1, cos(n w), sin(n w), n = 1 ... n_max,
// w = nu (t - t_ref), by the normal equations without the n x (2 n_max + 1) basis: B^T B needs
// only the sums of cos(m w) and sin(m w), m = 0 ... 2 n_max (products of harmonics are
// harmonics), and B^T y one more pass. O(n n_max) work, O(n_max^2) memory. The signals are taken
// about their means (the constant column absorbs them exactly), so rounding stays at the scale
// of their variation, not of an offset (gravity in a vertical record, a sensor's bias). For a
// record of one period or more B^T B is close to diag(n, n/2, ..., n/2): well conditioned.
struct HarmonicFit {
  Eigen::VectorXd cx, cz;  ///< (a_0, a_1, b_1, ..., a_N, b_N) of x and z
  double x_res = 0.0;      ///< |x - B cx|^2 by |x|^2 - cx . B^T x (sums about the mean)
  double z_res = 0.0;      ///< the same for z
  double x_var = 0.0;      ///< sum of (x - mean)^2
  double z_var = 0.0;      ///< sum of (z - mean)^2
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> gram;  ///< B^T B, factorised
};

// Column j of the basis is cos(k w) (j = 2k - 1, or j = 0 with k = 0) or sin(k w) (j = 2k), w the
// phase 2 pi `turns` (detail::harmonics_turns).
void harmonics_at(double turns, int m_max, std::vector<double>& cm, std::vector<double>& sm) {
  detail::harmonics_turns(turns, m_max, cm.data(), sm.data());
}

// The sums a harmonic fit at f needs over the samples (w = nu tau, tau = t - t_ref): of
// tau^k cos(m w) and tau^k sin(m w) (m = 0 ... 2 n_max) and of each signal about its mean times
// tau^k cos(n w), tau^k sin(n w) (n = 0 ... n_max, in the basis' order), for k = 0 and, with
// kMoments, k = 1 and 2 as well (frequency_step: the basis' derivative in f is 2 pi tau times
// another harmonic, so its products with the basis, the signals and itself are these sums too).
template <bool kMoments>
struct HarmonicSums {
  static constexpr int kOrders = kMoments ? 3 : 1;
  double x_mean = 0.0, z_mean = 0.0;
  double x_var = 0.0, z_var = 0.0;                  ///< sums of (y - mean)^2
  std::array<std::vector<double>, kOrders> sc, ss;  ///< [k][m]: sum tau^k cos(m w), sin(m w)
  std::array<Eigen::VectorXd, kOrders - (kMoments ? 1 : 0)> bx, bz;  ///< [k]: sum tau^k y B
};

template <bool kMoments>
HarmonicSums<kMoments> harmonic_sums(std::span<const double> t, std::span<const double> x,
                                     std::span<const double> z, double f, int n_max, double t_ref) {
  constexpr int K = HarmonicSums<kMoments>::kOrders;
  constexpr int KB = kMoments ? 2 : 1;  // the signals' sums: tau^0 and tau^1
  const std::size_t rows = t.size();
  const int cols = 2 * n_max + 1, m_max = 2 * n_max;
  HarmonicSums<kMoments> out;
  for (std::size_t i = 0; i < rows; ++i) {
    out.x_mean += x[i];
    out.z_mean += z[i];
  }
  out.x_mean /= static_cast<double>(rows);
  out.z_mean /= static_cast<double>(rows);
  for (int k = 0; k < K; ++k) {
    out.sc[k].assign(m_max + 1, 0.0);
    out.ss[k].assign(m_max + 1, 0.0);
  }
  for (int k = 0; k < KB; ++k) {
    out.bx[k] = Eigen::VectorXd::Zero(cols);
    out.bz[k] = Eigen::VectorXd::Zero(cols);
  }
  // Four samples at a time: their angle-addition recurrences are independent chains, which the
  // processor overlaps (one sample's chain of 2 n_max dependent steps left it waiting); each
  // sample's cos and sin are those of harmonics_turns, the sums only grouped differently.
  constexpr std::size_t kLanes = 4;
  const auto sum4 = [](const double* v) { return (v[0] + v[1]) + (v[2] + v[3]); };
  std::size_t row = 0;
  for (; row + kLanes <= rows; row += kLanes) {
    double c1[kLanes], s1[kLanes], c[kLanes], s[kLanes], xi[kLanes], zi[kLanes], tau[kLanes];
    double tc[kLanes], ts[kLanes], v[kLanes];
    for (std::size_t b = 0; b < kLanes; ++b) {
      tau[b] = t[row + b] - t_ref;
      const detail::SinCos one = detail::sincos_turns(f * tau[b]);
      c1[b] = c[b] = one.cos;
      s1[b] = s[b] = one.sin;
      xi[b] = x[row + b] - out.x_mean;
      zi[b] = z[row + b] - out.z_mean;
    }
    out.sc[0][0] += static_cast<double>(kLanes);
    out.bx[0][0] += sum4(xi);
    out.bz[0][0] += sum4(zi);
    for (std::size_t b = 0; b < kLanes; ++b) v[b] = xi[b] * xi[b];
    out.x_var += sum4(v);
    for (std::size_t b = 0; b < kLanes; ++b) v[b] = zi[b] * zi[b];
    out.z_var += sum4(v);
    if constexpr (kMoments) {
      out.sc[1][0] += sum4(tau);
      for (std::size_t b = 0; b < kLanes; ++b) v[b] = tau[b] * tau[b];
      out.sc[2][0] += sum4(v);
      for (std::size_t b = 0; b < kLanes; ++b) v[b] = tau[b] * xi[b];
      out.bx[1][0] += sum4(v);
      for (std::size_t b = 0; b < kLanes; ++b) v[b] = tau[b] * zi[b];
      out.bz[1][0] += sum4(v);
    }
    for (int m = 1; m <= m_max; ++m) {
      if (m > 1) {
        for (std::size_t b = 0; b < kLanes; ++b) {
          const double cn = c[b] * c1[b] - s[b] * s1[b];
          s[b] = s[b] * c1[b] + c[b] * s1[b];
          c[b] = cn;
        }
      }
      out.sc[0][m] += sum4(c);
      out.ss[0][m] += sum4(s);
      if constexpr (kMoments) {
        for (std::size_t b = 0; b < kLanes; ++b) {
          tc[b] = tau[b] * c[b];
          ts[b] = tau[b] * s[b];
        }
        out.sc[1][m] += sum4(tc);
        out.ss[1][m] += sum4(ts);
        for (std::size_t b = 0; b < kLanes; ++b) v[b] = tau[b] * tc[b];
        out.sc[2][m] += sum4(v);
        for (std::size_t b = 0; b < kLanes; ++b) v[b] = tau[b] * ts[b];
        out.ss[2][m] += sum4(v);
      }
      if (m <= n_max) {
        for (int k = 0; k < KB; ++k) {
          const double* cc = k == 0 ? c : tc;
          const double* sk = k == 0 ? s : ts;
          out.bx[k][2 * m - 1] += (xi[0] * cc[0] + xi[1] * cc[1]) + (xi[2] * cc[2] + xi[3] * cc[3]);
          out.bx[k][2 * m] += (xi[0] * sk[0] + xi[1] * sk[1]) + (xi[2] * sk[2] + xi[3] * sk[3]);
          out.bz[k][2 * m - 1] += (zi[0] * cc[0] + zi[1] * cc[1]) + (zi[2] * cc[2] + zi[3] * cc[3]);
          out.bz[k][2 * m] += (zi[0] * sk[0] + zi[1] * sk[1]) + (zi[2] * sk[2] + zi[3] * sk[3]);
        }
      }
    }
  }
  std::vector<double> cm(m_max + 1), sm(m_max + 1);
  for (std::size_t i = row; i < rows; ++i) {
    const double tau = t[i] - t_ref;
    harmonics_at(f * tau, m_max, cm, sm);
    const double xi = x[i] - out.x_mean, zi = z[i] - out.z_mean;
    double power = 1.0;  // tau^k
    for (int k = 0; k < K; ++k, power *= tau) {
      for (int m = 0; m <= m_max; ++m) {
        out.sc[k][m] += power * cm[m];
        out.ss[k][m] += power * sm[m];
      }
      if (k >= KB) continue;
      out.bx[k][0] += power * xi;
      out.bz[k][0] += power * zi;
      for (int n = 1; n <= n_max; ++n) {
        out.bx[k][2 * n - 1] += power * xi * cm[n];
        out.bx[k][2 * n] += power * xi * sm[n];
        out.bz[k][2 * n - 1] += power * zi * cm[n];
        out.bz[k][2 * n] += power * zi * sm[n];
      }
    }
    out.x_var += xi * xi;
    out.z_var += zi * zi;
  }
  return out;
}

// sum_i tau_i^k B_i B_i^T from the sums of tau^k cos(m w) and tau^k sin(m w): products of
// harmonics are harmonics.
Eigen::MatrixXd gram_of(const std::vector<double>& sc, const std::vector<double>& ss, int cols) {
  auto sum_cos = [&](int m) { return sc[static_cast<std::size_t>(std::abs(m))]; };
  auto sum_sin = [&](int m) { return m >= 0 ? ss[m] : -ss[-m]; };
  Eigen::MatrixXd gram(cols, cols);
  for (int i = 0; i < cols; ++i) {
    const int ki = (i + 1) / 2;
    const bool si = i > 0 && i % 2 == 0;
    for (int j = 0; j < cols; ++j) {
      const int kj = (j + 1) / 2;
      const bool sj = j > 0 && j % 2 == 0;
      if (!si && !sj)  // cos a cos b = (cos(a - b) + cos(a + b)) / 2
        gram(i, j) = 0.5 * (sum_cos(ki - kj) + sum_cos(ki + kj));
      else if (si && sj)  // sin a sin b = (cos(a - b) - cos(a + b)) / 2
        gram(i, j) = 0.5 * (sum_cos(ki - kj) - sum_cos(ki + kj));
      else if (!si && sj)  // cos a sin b = (sin(a + b) - sin(a - b)) / 2
        gram(i, j) = 0.5 * (sum_sin(ki + kj) - sum_sin(ki - kj));
      else  // sin a cos b = (sin(a + b) + sin(a - b)) / 2
        gram(i, j) = 0.5 * (sum_sin(ki + kj) + sum_sin(ki - kj));
    }
  }
  return gram;
}

// The fit from its sums (the coefficients' constant term with the mean added back).
template <bool kMoments>
HarmonicFit fit_of(const HarmonicSums<kMoments>& sums, int n_max) {
  HarmonicFit fit;
  fit.x_var = sums.x_var;
  fit.z_var = sums.z_var;
  fit.gram.compute(gram_of(sums.sc[0], sums.ss[0], 2 * n_max + 1));
  fit.cx = fit.gram.solve(sums.bx[0]);
  fit.cz = fit.gram.solve(sums.bz[0]);
  fit.x_res = std::max(0.0, fit.x_var - fit.cx.dot(sums.bx[0]));
  fit.z_res = std::max(0.0, fit.z_var - fit.cz.dot(sums.bz[0]));
  fit.cx[0] += sums.x_mean;
  fit.cz[0] += sums.z_mean;
  return fit;
}

HarmonicFit fit_harmonics(std::span<const double> t, std::span<const double> x,
                          std::span<const double> z, double f, int n_max, double t_ref) {
  return fit_of(harmonic_sums<false>(t, x, z, f, n_max, t_ref), n_max);
}

// RMS of y minus the fitted series, relative to the RMS of y, summed explicitly (a second pass:
// the reported residual does not rest on the difference of sums).
double relative_rms(std::span<const double> t, std::span<const double> y, const Eigen::VectorXd& c,
                    double f, int n_max) {
  detail::HarmonicsInOrder h(t, 0.0, f, n_max);
  // Relative to the RMS about the mean: a steady motion's accelerations average zero, so a
  // record's mean is the sensor's (gravity in an accelerometer's reading, an offset), and a large
  // one would make any fit look good.
  double mean = 0.0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  double yy = 0.0, rr = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    h.at(i);
    double fitted = c[0];
    for (int n = 1; n <= n_max; ++n) fitted += c[2 * n - 1] * h.cos(n) + c[2 * n] * h.sin(n);
    yy += (y[i] - mean) * (y[i] - mean);
    rr += (y[i] - fitted) * (y[i] - fitted);
  }
  return yy > 0 ? std::sqrt(rr / yy) : 0.0;
}

// The subharmonics A(f/2), A(3f/2), A(5f/2) of y [m/s^2], with A(f), A(2f), A(3f) of the same
// fit: the least-squares fit of the record to the harmonics n f (n = 0 ... n_max) and the
// half-harmonics (2j + 1) f / 2 (j = 0, 1, 2) together, so that neither leaks into the other over a
// window that is not a whole number of periods. A
// period-1 record gives noise-level amplitudes; NaN for a record shorter than two periods (f/2 is
// then not resolved).
detail::HalfHarmonics half_harmonics(std::span<const double> t, std::span<const double> y, double f,
                                     int n_max, double cycles) {
  if (cycles < 2.0 - 1e-9) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  const int cols = 2 * n_max + 1 + 6;
  Eigen::MatrixXd B(static_cast<Eigen::Index>(t.size()), cols);
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(t.size()));
  std::vector<double> cm(n_max + 1), sm(n_max + 1), ch(6), sh(6);
  const double t0 = t.front();
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Eigen::Index r = static_cast<Eigen::Index>(i);
    const double tau = t[i] - t0;  // the amplitudes do not depend on the time origin
    harmonics_at(f * tau, n_max, cm, sm);
    B(r, 0) = 1.0;
    for (int n = 1; n <= n_max; ++n) {
      B(r, 2 * n - 1) = cm[n];
      B(r, 2 * n) = sm[n];
    }
    // f/2, 3f/2, 5f/2: the multiples 1, 3, 5 of f/2.
    harmonics_at(0.5 * f * tau, 5, ch, sh);
    for (int j = 0; j < 3; ++j) {
      B(r, 2 * n_max + 1 + 2 * j) = ch[2 * j + 1];
      B(r, 2 * n_max + 2 + 2 * j) = sh[2 * j + 1];
    }
    rhs[r] = y[i];
  }
  const Eigen::VectorXd c = B.colPivHouseholderQr().solve(rhs);
  const int h = 2 * n_max + 1;
  detail::HalfHarmonics out{std::hypot(c[h], c[h + 1]), std::hypot(c[h + 2], c[h + 3]),
                            std::hypot(c[h + 4], c[h + 5])};
  out.a1 = std::hypot(c[1], c[2]);
  out.a2 = std::hypot(c[3], c[4]);
  if (n_max >= 3) out.a3 = std::hypot(c[5], c[6]);
  return out;
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

// `origin`: added to the times quoted (a record given from its first sample, e.g. identify_pass's,
// is quoted in its own times).
void check_record(std::span<const double> t, std::span<const double> ddx,
                  std::span<const double> ddz, double origin = 0.0) {
  if (t.size() != ddx.size() || t.size() != ddz.size())
    throw Error("record: t, ddx_M and ddz_M must have the same length; got " +
                std::to_string(t.size()) + ", " + std::to_string(ddx.size()) + ", " +
                std::to_string(ddz.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(ddx[i]) || !std::isfinite(ddz[i]))
      throw Error("record: non-finite value in row " + std::to_string(i + 1));
    if (i > 0 && !(t[i] > t[i - 1]))
      throw Error("record: t must increase strictly; row " + std::to_string(i + 1) +
                  " has t = " + num(t[i] + origin) + " after " + num(t[i - 1] + origin) +
                  (t[i] == t[i - 1]
                       ? " (a repeated time, as an event-driven integrator writes both sides of "
                         "a switch: make each run of them one sample, its accelerations "
                         "averaged, as the CSV reader does)"
                       : " (the time goes back: rows out of order, a logger that restarted its "
                         "clock, or files joined; give each part on its own)"));
  }
  if (t.size() < 2)
    throw Error("record: needs at least 2 samples; got " + std::to_string(t.size()));
}

// The least-squares harmonics of both signals at f with absolute-time phases (t_ref = 0), and
// their residuals relative to the RMS about the mean: analyze_record's fit, and the change gate's
// of each half of a window.
struct RecordFit {
  HarmonicFit fit;
  Spectrum hx, hz;
  double residual_x = 0.0, residual_z = 0.0;
};

RecordFit fit_record(std::span<const double> t, std::span<const double> x,
                     std::span<const double> z, double f, int n_max) {
  RecordFit r;
  r.fit = fit_harmonics(t, x, z, f, n_max, 0.0);
  r.hx = to_harmonics(r.fit.cx, n_max);
  r.hz = to_harmonics(r.fit.cz, n_max);
  r.residual_x = relative_rms(t, x, r.fit.cx, f, n_max);
  r.residual_z = relative_rms(t, z, r.fit.cz, f, n_max);
  return r;
}

// A record's response repeats after p excitation periods (a period-2 motion: an oscillation drum
// past a period doubling on stiff soil, a vibratory drum's "double jump"; period 3 or 4 in the
// windows of periodic motion beyond a drum's lift-off) when the fit on the harmonics of f/p
// leaves at most kSubharmonicShare of the variance that the best fit before it (on those of f, or
// of f/q for a q < p found so) leaves, and the fit on those of f leaves at least
// kSubharmonicLevel^2 of the signals' (the subharmonics are a percent of the response, not noise:
// white noise's share explained by the 2 (p - 1) n_max added coefficients is about
// 2 (p - 1) n_max / n). p = 2 ... kMaxFittedPeriods are tried in turn: a period-4 response is
// also explained in part by f/2, and is taken as period 4 only where f/4 explains most of what
// f/2 leaves; a period-2 response gains nothing from f/3 or f/4. Asked only of a record covering
// 2 p periods: over two, a response whose amplitude changes (a change of soil in a short window)
// has its sidebands at f +- f/2 and would be taken for a period-2 one. `run --csv` writes a
// period-p state as 2 p periods (numerics.output_periods = 2 of the motion's period). Returns p
// (1: the fit on the harmonics of f stands); for p > 1 `rf` holds the fit on the harmonics of
// f/p (p n_max of them).
constexpr int kMaxFittedPeriods = 4;
constexpr double kSubharmonicLevel = 1e-2;
constexpr double kSubharmonicShare = 0.25;
constexpr double kExcitedShare = 0.1;
constexpr double kSubharmonicLow = 0.5;
// low_subharmonic_share's screen: the share of what the harmonics of f leave that the low
// subharmonics of f/p must explain before f is refined on the harmonics of f/p.
constexpr double kSubharmonicScreen = 0.25;
// fitted_period's rule for samples in step with p periods holds below this many samples per
// period.
constexpr double kFoldedOrder = 128.0;

double rms_about_mean(std::span<const double> y);

// What the fit `rf` on the harmonics of f (n_max of them) leaves of x and z, each over its
// variance about the mean (as fitted_period weighs the channels): low_subharmonic_shares' input.
struct Leftover {
  std::vector<double> x, z;
  double scale_x = 0.0, scale_z = 0.0;  // n var
};

Leftover leftover_of(std::span<const double> t, std::span<const double> x,
                     std::span<const double> z, double f, int n_max, const RecordFit& rf) {
  Leftover l;
  l.x.resize(t.size());
  l.z.resize(t.size());
  detail::HarmonicsInOrder h(t, 0.0, f, n_max);
  for (std::size_t i = 0; i < t.size(); ++i) {
    h.at(i);
    double fx = rf.fit.cx[0], fz = rf.fit.cz[0];
    for (int n = 1; n <= n_max; ++n) {
      fx += rf.fit.cx[2 * n - 1] * h.cos(n) + rf.fit.cx[2 * n] * h.sin(n);
      fz += rf.fit.cz[2 * n - 1] * h.cos(n) + rf.fit.cz[2 * n] * h.sin(n);
    }
    l.x[i] = x[i] - fx;
    l.z[i] = z[i] - fz;
  }
  const double n = static_cast<double>(t.size());
  l.scale_x = std::pow(rms_about_mean(x), 2) * n;
  l.scale_z = std::pow(rms_about_mean(z), 2) * n;
  return l;
}

// Of what the fit on the harmonics of f leaves (`l`), the share that the low subharmonics k f / p
// (k < 3 p, not a multiple of p) explain: a cheap screen for a period-p response that an f
// refined on the harmonics of f hides. Over a short window that f is pulled by the subharmonics
// (58.023 Hz for 58 over 12 periods of a period-3 drum), and the fit on the harmonics of f/p at it
// misses the high ones; the low subharmonics, whose phase such an error hardly moves, still carry
// most of what the harmonics of f leave. By projection (the window spans at least 2 p periods, so
// that these frequencies are nearly orthogonal to each other and to the harmonics of f): white
// noise gives about 4 p / n, harmonics beyond n_max (a stick-slip response's) almost nothing.
double low_subharmonic_share(std::span<const double> t, const Leftover& l, double f, int p) {
  const std::size_t top = static_cast<std::size_t>(3 * p - 1);
  std::vector<double> cs(top + 1), sn(top + 1);
  std::vector<double> px(2 * (top + 1), 0.0), pz(px.size(), 0.0);
  for (std::size_t i = 0; i < t.size(); ++i) {
    harmonics_at(f / p * (t[i] - t.front()), static_cast<int>(top), cs, sn);
    for (std::size_t k = 1; k <= top; ++k) {
      if (k % static_cast<std::size_t>(p) == 0) continue;
      px[2 * k] += l.x[i] * cs[k];
      px[2 * k + 1] += l.x[i] * sn[k];
      pz[2 * k] += l.z[i] * cs[k];
      pz[2 * k + 1] += l.z[i] * sn[k];
    }
  }
  const double n = static_cast<double>(t.size());
  double explained = 0.0, left = 0.0;
  for (const auto& [e, scale, proj] :
       {std::tuple{&l.x, l.scale_x, &px}, std::tuple{&l.z, l.scale_z, &pz}}) {
    if (!(scale > 0.0)) continue;
    double sse = 0.0;
    for (const double v : *e) sse += v * v;
    double ex = 0.0;
    for (const double c : *proj) ex += c * c;
    left += sse / scale;
    explained += std::min(sse, 2.0 * ex / n) / scale;
  }
  return left > 0.0 ? explained / left : 0.0;
}

// The words for a residual gate: a slow drift of a channel's offset (a sensor's, 0.01 g over
// seconds) stays in the residual of the harmonic fit (on the harmonics of f, n_max of them), which
// has a mean but no trend; identify's fit takes it with a cubic (docs/identify.md), and a window
// that identify fits well failed the gate without a word of why. Empty unless a cubic explains at
// least a quarter of what the worse channel's fit leaves; `res` is the window's residual,
// `max_residual` the gate's.
std::string offset_drift_hint(std::span<const double> t, std::span<const double> x,
                              std::span<const double> z, double f, int n_max,
                              const RecordMetrics& m, double res, double max_residual) {
  const RecordFit rf = fit_record(t, x, z, f, n_max);
  const Leftover l = leftover_of(t, x, z, f, n_max, rf);
  double without[2] = {m.residual_x, m.residual_z};
  double share[2] = {0.0, 0.0};
  const double mid = 0.5 * (t.front() + t.back()), half = 0.5 * (t.back() - t.front());
  for (int c = 0; c < 2; ++c) {
    const std::vector<double>& e = c == 0 ? l.x : l.z;
    Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
    Eigen::Vector4d b = Eigen::Vector4d::Zero();
    double sse = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double u = half > 0.0 ? (t[i] - mid) / half : 0.0;
      const Eigen::Vector4d row(1.0, u, 0.5 * (3 * u * u - 1), 0.5 * u * (5 * u * u - 3));
      G += row * row.transpose();
      b += e[i] * row;
      sse += e[i] * e[i];
    }
    const double explained = std::max(0.0, b.dot(G.ldlt().solve(b)));
    share[c] = sse > 0.0 ? std::min(1.0, explained / sse) : 0.0;
    without[c] *= std::sqrt(1.0 - share[c]);
  }
  const int worse = m.residual_z > m.residual_x ? 1 : 0;
  if (share[worse] < 0.25) return "";
  const double clean = std::max(without[0], without[1]);
  return std::string(" (a slow drift of the offset of ") + (worse == 0 ? "x_M''" : "z_M''") +
         " explains " + num(std::round(share[worse] * 1000) / 10) +
         " % of what the fit leaves: identify's fit takes it with a cubic trend, this gate's does "
         "not; without it the residual is " +
         num(std::round(clean * 1000) / 1000) +
         (clean <= max_residual
              ? ", and --max-residual " + num(std::ceil(res * 100) / 100) + " passes the window)"
              : ")");
}

int fitted_period(std::span<const double> t, std::span<const double> x, std::span<const double> z,
                  double f, int n_max, double covered, RecordFit& rf) {
  const auto variance = [](const RecordFit& r) {
    return r.residual_x * r.residual_x + r.residual_z * r.residual_z;
  };
  const double left = variance(rf);
  if (!(left > kSubharmonicLevel * kSubharmonicLevel)) return 1;
  // Each channel a response to the excitation: its harmonics of f carry at least
  // kExcitedShare of its variance (a channel with none, a lateral axis read as z_M'', had a
  // sine near 3f/2 taken for a subharmonic).
  if (!(rf.residual_x * rf.residual_x <= 1.0 - kExcitedShare &&
        rf.residual_z * rf.residual_z <= 1.0 - kExcitedShare))
    return 1;
  const double per_period = static_cast<double>(t.size() - 1) / ((t.back() - t.front()) * f);
  int best = 1;
  double best_left = left;
  for (int p = 2; p <= kMaxFittedPeriods; ++p) {
    // (A window of 4 periods at 1 kHz covers 4 to the last sample's step: an f a hair higher
    // than the excitation's made it 3.9999.)
    if (covered < 2.0 * p - 1e-2) break;
    // Samples in step with p periods (a whole number per p periods that is not one per period:
    // 13.5 per period at 500 Hz and 37.037 Hz for p = 2): the harmonics above those the sampling
    // resolves alias onto the multiples of f/p, to within the record's resolution 1 / covered
    // [f], and a stick-slip record's were taken for subharmonics (fitted_periods 2, its area 15 %
    // high). Subharmonics cannot be told from them there.
    // Only where those harmonics may matter: folded there from about the order per_period,
    // they hold about 1 / per_period^2 of the variance of a response that jumps (a 1/k
    // spectrum), below kSubharmonicLevel^2 from kFoldedOrder on (a 1 kHz logger at 39 Hz, 25.6
    // samples per period, is in step with 3 periods over fewer than 39; a simulation's 1024 per
    // period at 57.98 Hz for 58 with 12 periods, and the period-3 response was fitted on f).
    const double in_p = p * per_period, whole = std::round(in_p);
    if (per_period < kFoldedOrder && std::fmod(whole, static_cast<double>(p)) != 0.0 &&
        std::abs(in_p - whole) < static_cast<double>(p) / covered)
      continue;
    RecordFit sub = fit_record(t, x, z, f / p, p * n_max);
    if (!(variance(sub) <= kSubharmonicShare * best_left)) continue;
    // A response's subharmonics are led by its low ones, those below 3f (the doubling drum's
    // z_M'' at 3f/2, a jumping drum's at f/2); harmonics aliased onto the subharmonics by a
    // sampling near p periods' step land on the high ones first (from the highest fitted down).
    double low = 0.0, all = 0.0;
    for (int c = 0; c < 2; ++c) {
      const Spectrum& h = c == 0 ? sub.hx : sub.hz;
      const double scale = rms_about_mean(c == 0 ? x : z);
      if (!(scale > 0.0)) continue;
      for (std::size_t k = 1; k < h.size(); ++k) {
        if (k % static_cast<std::size_t>(p) == 0) continue;  // a harmonic of f
        const double share = std::pow(h[k].amplitude / scale, 2);
        all += share;
        if (k < static_cast<std::size_t>(3 * p)) low += share;
      }
    }
    if (!(low >= kSubharmonicLow * all)) continue;
    best = p;
    best_left = variance(sub);
    rf = std::move(sub);
  }
  return best;
}

}  // namespace

RecordMetrics analyze_record(std::span<const double> t, std::span<const double> ddx,
                             std::span<const double> ddz, double f, int n_max) {
  if (!(std::isfinite(f) && f > 0)) throw Error("record: f must be > 0 [Hz]; got " + num(f));
  if (n_max < 2 || n_max > kMaxRecordHarmonics)
    throw Error("record: n_max must be in [2, " + std::to_string(kMaxRecordHarmonics) +
                "] (psi needs the 2f harmonic); got " + std::to_string(n_max));
  check_record(t, ddx, ddz);
  RecordMetrics m;
  m.kb = std::numeric_limits<double>::quiet_NaN();  // needs the case and the unbalance's angle:
                                                    // record_kb
  m.cycles = t.empty() ? 0.0 : (t.back() - t.front()) * f;
  // n samples at the step dt cover n dt: one period of samples (26 at 1 kHz and 39 Hz, 0.975
  // periods from the first to the last) is a period.
  if (t.size() < 2 ||
      m.cycles * static_cast<double>(t.size()) / static_cast<double>(t.size() - 1) < 1.0 - 1e-9)
    throw Error("record: must span at least one excitation period (1/f = " + num(1.0 / f) +
                " s); its samples cover " +
                num(t.size() < 2 ? 0.0
                                 : (t.back() - t.front()) * static_cast<double>(t.size()) /
                                       static_cast<double>(t.size() - 1)) +
                " s");
  const double per_period = static_cast<double>(t.size() - 1) / m.cycles;
  if (per_period < 2.0 * n_max + 1.0)
    throw Error("record: " + num(per_period) + " samples per period are too few for n_max = " +
                std::to_string(n_max) + " (need at least " + std::to_string(2 * n_max + 1) + ")");

  // Harmonics with absolute-time phases (t_ref = 0).
  RecordFit rf = fit_record(t, ddx, ddz, f, n_max);
  // The periods the samples cover, their last interval included (as for the one-period check
  // above): two periods of samples, as `run --csv` writes them, span 1.999 between the first
  // and the last, and f/2 was taken as unresolved (rmv and ccv NaN for run's own CSV).
  const double covered =
      m.cycles * static_cast<double>(t.size()) / static_cast<double>(t.size() - 1);
  // A period-p response (fitted_period): the fit on the harmonics of f/p, which holds those of f
  // (its multiples of p) and the subharmonics together. Without it such a record failed the
  // residual gate (0.77 for z_M'' of a doubling drum) and gave no metric at all, or passed it
  // with the metrics of another figure (a period-3 drum beyond lift-off: the residual of z_M''
  // 0.497, its area 1494 for the motion's 3400 m^2/s^4).
  const int p = fitted_period(t, ddx, ddz, f, n_max, covered, rf);
  m.fitted_periods = p;
  const double f_fit = f / p;   // the fitted signal's fundamental [Hz]
  const int n_fit = p * n_max;  // its harmonics
  const Eigen::VectorXd& cx = rf.fit.cx;
  const Eigen::VectorXd& cz = rf.fit.cz;
  m.residual_x = rf.residual_x;
  m.residual_z = rf.residual_z;
  {
    detail::HalfHarmonics half;
    Spectrum hx, hz;
    if (p == 1) {
      hx = std::move(rf.hx);
      hz = std::move(rf.hz);
      half = half_harmonics(t, ddz, f, n_max, covered);
    } else {
      // The harmonics n f are the fit's multiples of p; the subharmonics k f / p the others.
      const auto at = [p](int n) { return static_cast<std::size_t>(p * n); };
      for (int n = 0; n <= n_max; ++n) {
        hx.push_back(rf.hx[at(n)]);
        hz.push_back(rf.hz[at(n)]);
      }
      if (p % 2 == 0) {
        // f/2, 3f/2, 5f/2 are the multiples p/2, 3p/2, 5p/2 of f/p; 5f/2 only with n_max >= 3
        // (NaN beyond, as A(3f)).
        const auto half_at = [&](int j) {
          const auto k = static_cast<std::size_t>((2 * j + 1) * p / 2);
          return k < rf.hz.size() ? rf.hz[k].amplitude : std::numeric_limits<double>::quiet_NaN();
        };
        half.a05 = half_at(0);
        half.a15 = half_at(1);
        half.a25 = half_at(2);
      }
      // An odd p: the frequencies k f / p hold no half-harmonic (rmv 0, as `run` gives it).
    }
    // THD of the fitted signal: its overtones are the fitted harmonics 2 ... n_max of f.
    double overtones = 0.0;
    for (int n = 2; n <= n_max; ++n) overtones += std::pow(hx[n].amplitude, 2);
    detail::set_spectral_metrics(m, std::move(hx), std::move(hz), overtones, n_max, half);
  }

  // The fitted periodic signals over one period of the fit (two excitation periods for a
  // period-2 fit), for the extremes and the area, without their means (A0): a steady motion's
  // accelerations average zero, so a record's mean is the sensor's (gravity in an
  // accelerometer's reading, an offset) and would shift the peaks away from the model's.
  const int kSamples = 1024 * p;
  const double nu = 2.0 * M_PI * f_fit;
  std::vector<double> x(static_cast<std::size_t>(kSamples)), z(static_cast<std::size_t>(kSamples)),
      cj(n_fit + 1), sj(n_fit + 1);
  for (int j = 0; j < kSamples; ++j) {
    harmonics_at(static_cast<double>(j) / kSamples, n_fit, cj, sj);  // n nu t_j = 2 pi n j / K
    double sx = 0.0, sz = 0.0;
    for (int n = 1; n <= n_fit; ++n) {
      sx += cx[2 * n - 1] * cj[n] + cx[2 * n] * sj[n];
      sz += cz[2 * n - 1] * cj[n] + cz[2 * n] * sj[n];
    }
    x[static_cast<std::size_t>(j)] = sx;
    z[static_cast<std::size_t>(j)] = sz;
  }
  // The extremes: the grid's best point refined by Newton's method on the fitted series, so that
  // they do not depend on where the grid falls on the waveform (on the record's clock): the grid
  // alone is off by up to about (pi / 1024)^2 / 2 of the curvature, ~1e-5 relative.
  const auto extreme = [&](const Eigen::VectorXd& c, int j) {
    const double t_grid = static_cast<double>(j) / (kSamples * f_fit);
    double tj = t_grid;
    double value = 0.0;
    for (int iteration = 0; iteration < 8; ++iteration) {
      double s0 = 0.0, s1 = 0.0, s2 = 0.0;  // without the mean c[0], as the grid
      for (int n = 1; n <= n_fit; ++n) {
        const double w = n * nu, cs = std::cos(w * tj), sn = std::sin(w * tj);
        const double a = c[2 * n - 1], b = c[2 * n];
        s0 += a * cs + b * sn;
        s1 += w * (b * cs - a * sn);
        s2 -= w * w * (a * cs + b * sn);
      }
      value = s0;
      // A step only while it stays within one grid cell of the grid's extremum: a discrete
      // extremum (no neighbour beats it) brackets the true one between its two neighbours, which
      // may lie anywhere there, also about half a cell away.
      if (!(s2 != 0.0)) break;
      const double step = -s1 / s2;
      if (!(std::abs(tj + step - t_grid) <= 1.0 / (kSamples * f_fit))) break;
      tj += step;
      if (std::abs(step) < 1e-15 / f_fit) break;
    }
    return value;
  };
  // Every local extremum of the grid is refined (a trigonometric polynomial of degree n_fit has
  // at most 2 n_fit of them): two nearly equal peaks may swap places once refined.
  const auto pick = [&](const Eigen::VectorXd& c, const std::vector<double>& v, bool largest) {
    const auto better = [largest](double a, double b) { return largest ? a > b : a < b; };
    double best =
        largest ? *std::max_element(v.begin(), v.end()) : *std::min_element(v.begin(), v.end());
    for (int j = 0; j < kSamples; ++j) {
      const double before = v[static_cast<std::size_t>((j + kSamples - 1) % kSamples)],
                   after = v[static_cast<std::size_t>((j + 1) % kSamples)];
      const double here = v[static_cast<std::size_t>(j)];
      if (better(before, here) || better(after, here)) continue;
      const double refined = extreme(c, j);
      if (better(refined, best)) best = refined;  // Newton may only improve on the grid
    }
    return best;
  };
  m.ddx_min = pick(cx, x, false);
  m.ddx_max = pick(cx, x, true);
  m.ddz_min = pick(cz, z, false);
  m.ddz_max = pick(cz, z, true);
  m.area = enclosed_area(x, z);
  return m;
}

}  // namespace oscidrum

// ---- Frequency estimation and windows ----------------------------------------------------------

namespace oscidrum {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Sum over x_M'' and z_M'' of the residual of the harmonic fit at f, each relative to the
// signal's variance about its mean (so that the two signals weigh alike). By the normal
// equations (fit_harmonics): their difference of sums loses ~1e-16 of the variance to rounding,
// far below the residual changes the frequency search resolves.
double fit_residual(std::span<const double> t, std::span<const double> x, std::span<const double> z,
                    double f, int n_max) {
  if (t.size() < static_cast<std::size_t>(2 * n_max + 1)) return kNaN;
  const HarmonicFit fit = fit_harmonics(t, x, z, f, n_max, t[0]);  // the phase origin is free
  return (fit.x_var > 0 ? fit.x_res / fit.x_var : 0.0) +
         (fit.z_var > 0 ? fit.z_res / fit.z_var : 0.0);
}

}  // namespace

namespace {

// Brent's minimisation (golden sections with parabolic steps) of the fit residual over
// [f - h, f + h] to about `tol` [Hz]: the residual is smooth and unimodal in a bracket that holds
// only the main lobe, where the parabolic steps converge in a few evaluations.
double minimise_residual(std::span<const double> t, std::span<const double> ddx,
                         std::span<const double> ddz, double f, double h, int n_max, double tol) {
  // Boost's tolerance is relative: 2^(1 - bits) |f|; more than half the digits of a double
  // cannot be resolved at a minimum.
  const int bits = std::clamp(static_cast<int>(std::ceil(1.0 - std::log2(tol / f))), 8, 26);
  std::uintmax_t max_iter = 200;
  const auto [f_min, residual] = boost::math::tools::brent_find_minima(
      [&](double g) { return fit_residual(t, ddx, ddz, g, n_max); }, f - h, f + h, bits, max_iter);
  (void)residual;
  return f_min;
}

}  // namespace

namespace detail {

FrequencyStep frequency_step(std::span<const double> t, std::span<const double> x,
                             std::span<const double> z, double f, int n_max) {
  FrequencyStep out;
  if (t.size() < static_cast<std::size_t>(2 * n_max + 1)) return out;
  const double t_ref = t[0];  // the phase origin is free (fit_residual's)
  // One pass over the samples: with T = diag(tau) and D = d(B c)/df = 2 pi T B d (d: n b_n at
  // cos(n w), -n a_n at sin(n w)), <r, D> = 2 pi d^T (B^T T y - B^T T B c), |D|^2 =
  // 4 pi^2 d^T (B^T T^2 B) d and u = B^T D = 2 pi (B^T T B) d: sums of tau and tau^2 times the
  // basis' products and the signals (harmonic_sums), not a second pass with D per sample.
  const HarmonicSums<true> sums = harmonic_sums<true>(t, x, z, f, n_max, t_ref);
  const HarmonicFit fit = fit_of(sums, n_max);
  const int cols = 2 * n_max + 1;
  const Eigen::MatrixXd G1 = gram_of(sums.sc[1], sums.ss[1], cols);
  const Eigen::MatrixXd G2 = gram_of(sums.sc[2], sums.ss[2], cols);
  const double wx = fit.x_var > 0 ? 1.0 / fit.x_var : 0.0,
               wz = fit.z_var > 0 ? 1.0 / fit.z_var : 0.0;
  out.residual = wx * fit.x_res + wz * fit.z_res;
  // <r, D> and |(I - P) D|^2 of one signal with coefficients c (about its mean) and B^T T y.
  const auto terms = [&](Eigen::VectorXd c, double mean, const Eigen::VectorXd& bty) {
    c[0] -= mean;
    Eigen::VectorXd d = Eigen::VectorXd::Zero(cols);
    for (int n = 1; n <= n_max; ++n) {
      d[2 * n - 1] = n * c[2 * n];
      d[2 * n] = -n * c[2 * n - 1];
    }
    const double g = 2.0 * M_PI * d.dot(bty - G1 * c);
    const Eigen::VectorXd u = 2.0 * M_PI * (G1 * d);
    const double dd = 4.0 * M_PI * M_PI * d.dot(G2 * d);
    return std::pair{g, dd - u.dot(fit.gram.solve(u))};
  };
  const auto [gx, cx] = terms(fit.cx, sums.x_mean, sums.bx[1]);
  const auto [gz, cz] = terms(fit.cz, sums.z_mean, sums.bz[1]);
  out.slope = -2.0 * (wx * gx + wz * gz);
  out.curvature = 2.0 * (wx * cx + wz * cz);
  if (out.curvature > 0) out.step = -out.slope / out.curvature;
  return out;
}

}  // namespace detail

namespace {

// The minimum of fit_residual with n_max harmonics by Gauss-Newton steps from f, to tol [Hz],
// staying within [f - h, f + h] and decreasing the residual at every step; nullopt when it does
// not (a start outside the minimum's basin), and the caller falls back to Brent's search. Each
// step costs about two evaluations of the residual; from a start in the main lobe it converges
// in two or three where Brent's search takes a dozen. Converged: a step of at most tol, or a
// step s_k whose contraction theta = |s_k| / |s_k-1| bounds what is left after it,
// theta / (1 - theta) |s_k| <= tail_tol (the geometric tail of a linearly converging iteration,
// the test of simplified Newton iterations in implicit integrators: Hairer & Wanner, Solving
// Ordinary Differential Equations II, Sect. IV.8), which saves the evaluation that would only
// confirm it.
std::optional<double> newton_frequency(std::span<const double> t, std::span<const double> x,
                                       std::span<const double> z, double f, double h, int n_max,
                                       double tol, double tail_tol) {
  const double lo = f - h, hi = f + h;
  double previous = kNaN, previous_step = kNaN;
  for (int iteration = 0; iteration < 12; ++iteration) {
    const detail::FrequencyStep s = detail::frequency_step(t, x, z, f, n_max);
    if (!std::isfinite(s.step) || !std::isfinite(s.residual)) return std::nullopt;
    // A residual that grows beyond rounding (~1e-16 of the variance per sum): not in the basin.
    if (iteration > 0 && s.residual > previous + 1e-12 * (1.0 + previous)) return std::nullopt;
    previous = s.residual;
    const double next = f + s.step;
    if (!(next >= lo && next <= hi)) return std::nullopt;
    f = next;
    const double size = std::abs(s.step);
    if (size <= tol) return f;
    const double theta = size / std::abs(previous_step);  // NaN at the first step
    if (theta < 0.5 && theta / (1.0 - theta) * size <= tail_tol) return f;
    previous_step = s.step;
  }
  return std::nullopt;
}

// refine_frequency from f that is already its stage with `refined` <= n_max harmonics on these
// samples (from the same start and bracket): the stages up to that one are skipped, and their
// brackets narrowed as they would have been. refined = 0: all stages. `first`: the harmonics of
// the first stage, p for the refinement of f/p on a period-p response, whose harmonic p is the
// excitation's f (a first stage on f/3 alone, a subharmonic of a few per cent, was pulled toward
// the far larger f: 19.9 for 19.33 Hz, the window's fit then failed).
double refine_staged(std::span<const double> t, std::span<const double> ddx,
                     std::span<const double> ddz, double f, double half_width, int n_max,
                     int refined, int first = 1) {
  // The residual of harmonic n has side lobes 1/(n T) apart (T the record's span): refine with
  // the fundamental over the whole bracket first, then with more harmonics in brackets narrow
  // enough to hold only their main lobe. Each stage by Gauss-Newton steps, Brent's search where
  // they fail (a start outside the minimum's basin: a short record whose fundamental alone puts
  // f far off). The last stage goes to 1e-9 f: Gauss-Newton converges fast enough that the
  // minimum is found rather than bracketed (Brent's search stops at 1e-7 f).
  // A stage before the last only has to end well inside the next one's bracket: to a tenth of
  // that bracket's half width.
  const double span = t.empty() ? 0.0 : t.back() - t.front();
  double h = half_width * f;
  for (const int n : {first, 2 * first, 4 * first, n_max}) {
    const int m = std::min(n, n_max);
    const bool last = m == n_max;
    const double h_next = span > 0 ? std::min(h, 0.15 / (m * span)) : h;
    if (m <= refined) {  // done (the last stage only where it is the `refined` one)
      if (last) break;
      h = h_next;
      continue;
    }
    const double tol = last ? 1e-7 * f : 0.1 * h_next;
    // The last stage: a step of 1e-9 f, after which the next would be far smaller, or a tail
    // estimated at 1e-11 f (what such a step leaves).
    const std::optional<double> g =
        last ? newton_frequency(t, ddx, ddz, f, h, m, 1e-9 * f, 1e-11 * f)
             : newton_frequency(t, ddx, ddz, f, h, m, tol, tol);
    f = g ? *g : minimise_residual(t, ddx, ddz, f, h, m, tol);
    if (last) break;
    h = h_next;
  }
  return f;
}

}  // namespace

double refine_frequency(std::span<const double> t, std::span<const double> ddx,
                        std::span<const double> ddz, double f, double half_width, int n_max) {
  return refine_staged(t, ddx, ddz, f, half_width, n_max, 0);
}

namespace {

// The excitation's f of a period-p response from its harmonics of f/p (n of them), refined from
// f as refine_frequency does, from the stage with the first p of them (f among them).
double refine_periodic(std::span<const double> t, std::span<const double> ddx,
                       std::span<const double> ddz, double f, double half_width, int n, int p) {
  return p * refine_staged(t, ddx, ddz, f / p, half_width, n, 0, std::min(p, n));
}

}  // namespace

namespace detail {

std::size_t estimation_start(std::span<const double> ddx, std::span<const double> ddz) {
  constexpr std::size_t n = kEstimationSamples;
  const std::size_t blocks = std::min(ddx.size(), ddz.size()) / n;
  if (blocks < 2) return 0;
  // Mean absolute deviation from the mean, both channels.
  const auto loudness = [&](std::size_t b) {
    double total = 0.0;
    for (const std::span<const double> y : {ddx.subspan(b * n, n), ddz.subspan(b * n, n)}) {
      double mean = 0.0;
      for (double v : y) mean += v;
      mean /= static_cast<double>(n);
      double dev = 0.0;
      for (double v : y) dev += std::abs(v - mean);
      total += dev / static_cast<double>(n);
    }
    return total;
  };
  std::vector<double> loud(blocks);
  for (std::size_t b = 0; b < blocks; ++b) loud[b] = loudness(b);
  const double loudest = *std::max_element(loud.begin(), loud.end());
  if (!(loud[0] < 0.5 * loudest)) return 0;
  std::size_t b = 1;
  while (loud[b] < 0.5 * loudest) ++b;
  return b * n;
}

std::size_t fft_size(std::size_t n) {
  for (std::size_t L = std::max<std::size_t>(n, 1);; ++L) {
    std::size_t m = L;
    for (const std::size_t p : {2, 3, 5})
      while (m % p == 0) m /= p;
    if (m == 1) return L;
  }
}

SpectralPeak spectral_peak(std::span<const double> t, std::span<const double> ddx,
                           std::span<const double> ddz, const FrequencySearch& search,
                           bool allow_fft) {
  check_record(t, ddx, ddz);
  if (t.size() < 8)
    throw Error("record: needs at least 8 samples to estimate f (or give f); got " +
                std::to_string(t.size()));
  // f_min = -1 searched from the lowest positive grid frequency without a word.
  if (!(search.f_min > 0.0) || !std::isfinite(search.f_min))
    throw Error(
        "record: the frequency search's lower limit f_min (--f-min) must be a finite "
        "frequency > 0 [Hz]; got " +
            num(search.f_min),
        "f_min", search.f_min);
  if (!(search.f_min < search.f_max))
    throw Error(
        "record: the frequency search's lower limit f_min (--f-min) must be below its "
        "upper limit f_max (--f-max); got [" +
            num(search.f_min) + ", " + num(search.f_max) + "] Hz",
        "f_min", search.f_min);
  if (search.n_max < 1 || search.n_max > kMaxRecordHarmonics)
    throw Error("record: the frequency search's n_max must be in [1, " +
                std::to_string(kMaxRecordHarmonics) + "]; got " + std::to_string(search.n_max));
  const std::size_t n_seg = std::min<std::size_t>(t.size(), kEstimationSamples);
  {
    // Both channels the same value in every sample (a dead logger, a drum at rest): no
    // oscillation, whatever round-off the means leave below.
    if (one_value(ddx.first(n_seg)) && one_value(ddz.first(n_seg)))
      throw Error("record: the accelerations are constant (x_M'' = " + num(ddx[0]) +
                  ", z_M'' = " + num(ddz[0]) + " m/s^2 in every sample" +
                  (n_seg < t.size() ? " of the " + std::to_string(n_seg) + " searched" : "") +
                  ": a dead or disconnected logger, or the exciter off); no frequency to find");
  }
  const double span = t[n_seg - 1] - t[0];
  const double fs = static_cast<double>(n_seg - 1) / span;
  // Up to fs / 5: the 5 samples per period that a fit of two harmonics needs (psi_xz reads the
  // 2f component); the sum P(f) takes the harmonics below the Nyquist frequency fs / 2 (n = 1 ...
  // 3 up to fs / 6, n = 1, 2 above: a logger at 200 samples/s still finds 39 Hz).
  const double f_hi = std::min(search.f_max, fs / 5.0);
  const double f_lo = std::max(search.f_min, 1.0 / span);
  if (!(f_hi > f_lo))
    throw Error("record: no excitation frequency to search in [" + num(search.f_min) + ", " +
                num(search.f_max) + "] Hz: the record (" + sig4(fs) + " samples/s over " +
                sig4(span) + " s) resolves [" + sig4(f_lo) + ", " + sig4(f_hi) + "] Hz");
  // Harmonic-sum spectrum on a grid of 1/(4 span).
  std::vector<double> xs(ddx.begin(), ddx.begin() + static_cast<std::ptrdiff_t>(n_seg));
  std::vector<double> zs(ddz.begin(), ddz.begin() + static_cast<std::ptrdiff_t>(n_seg));
  auto demean = [](std::vector<double>& v) {
    double m = 0;
    for (double y : v) m += y;
    m /= static_cast<double>(v.size());
    for (double& y : v) y -= m;
  };
  demean(xs);
  demean(zs);
  double best_f = f_lo, best_p = -1.0;
  // P(f) from the transforms X(n f), Z(n f), n = 1, 2, 3. The excitation frequency carries the
  // drum's largest acceleration (x_M'' at f). A frequency whose own term is a small part of the
  // sum is a subharmonic that collects the harmonics of the true f, e.g. f/2 when a change of
  // the soil along a pass shifts the phase abruptly and splits the peak at f in two. So is one
  // where x_M'' at 2 f carries most of the sum and more than x_M'' at f: the f/2 of a period-2
  // response, whose subharmonics f/2 and 3f/2 and harmonics f and 2f sum to more than the
  // harmonics of f alone (a doubling drum's record was read at f/2, its CMV 1235 for 766;
  // x_M'' of a period-1 response is largest at f, the excitation's, also where z_M'' is larger
  // at 2f, a CMV above 300).
  const auto consider = [&](double f, const std::complex<double>(&X)[3],
                            const std::complex<double>(&Z)[3]) {
    const int resolved = 3.0 * f <= 0.5 * fs ? 3 : 2;  // n f below Nyquist
    double p = 0;
    for (int n = 0; n < resolved; ++n) p += std::norm(X[n]) + std::norm(Z[n]);
    if (std::norm(X[0]) + std::norm(Z[0]) < 0.1 * p) return;
    if (std::norm(X[1]) > 0.5 * p && std::norm(X[0]) < std::norm(X[1])) return;
    if (p > best_p) {
      best_p = p;
      best_f = f;
    }
  };
  const auto peak = [&](double df) -> SpectralPeak {
    if (!(best_p > 0)) throw Error("record: the accelerations are constant; no frequency to find");
    return {best_f, df};
  };
  // Uniform samples (every time within 1e-3 steps of t_0 + k h; the peak only starts the
  // refinement, which a phase error of 2 pi 3 f 1e-3 h < 1e-2 rad does not move): the spectrum
  // by one FFT of each signal, zero-padded to L >= 4 (n - 1) points (a 2-3-5 length, Eigen's
  // kissfft), whose bins k / (L h) are a grid at least as fine as the direct sums' below and hold
  // n f at bin n k: 1.6e6 instructions against the sums' 17.5e6 on 1030 samples (bench/README.md).
  const double h = span / static_cast<double>(n_seg - 1);
  bool uniform = allow_fft;
  for (std::size_t k = 0; k < n_seg && uniform; ++k)
    uniform = std::abs((t[k] - t[0]) - static_cast<double>(k) * h) <= 1e-3 * h;
  if (uniform) {
    const std::size_t L = fft_size(4 * (n_seg - 1));
    const double dF = 1.0 / (static_cast<double>(L) * h);
    Eigen::FFT<double> fft;
    std::vector<double> padded(L, 0.0);
    std::vector<std::complex<double>> FX, FZ;
    std::copy(xs.begin(), xs.end(), padded.begin());
    fft.fwd(FX, padded);
    std::copy(zs.begin(), zs.end(), padded.begin());
    fft.fwd(FZ, padded);
    // 2 k <= L / 2 (f_hi <= fs / 5 with fs = 1 / h); bin 3 k is read only below L / 2 (above it
    // is the mirror of another frequency, and consider() leaves n = 3 out there).
    for (auto k = static_cast<std::size_t>(std::ceil(f_lo / dF));
         static_cast<double>(k) * dF <= f_hi && 2 * k < FX.size(); ++k) {
      const std::size_t k3 = 3 * k < FX.size() ? 3 * k : 0;
      const std::complex<double> X[3] = {FX[k], FX[2 * k], FX[k3]};
      const std::complex<double> Z[3] = {FZ[k], FZ[2 * k], FZ[k3]};
      consider(static_cast<double>(k) * dF, X, Z);
    }
    return peak(dF);
  }
  const double df = 0.25 / span;
  // e^{-i 2 pi f (t_k - t_0)} of every sample, carried from one grid frequency to the next by
  // the factor e^{-i 2 pi df (t_k - t_0)} (no sin and cos per sample and frequency; the record's
  // times need not be uniform), and computed afresh every kFresh frequencies so that the
  // rounding of the products (about 1e-16 each) cannot accumulate.
  // Complex arithmetic written out on separate real and imaginary parts: std::complex's product
  // checks every result for NaN (Annex G), which this loop over every sample and frequency of the
  // grid does not need (the same values otherwise).
  constexpr int kFresh = 64;
  std::vector<double> pr(n_seg), pim(n_seg), sr(n_seg), sim(n_seg);
  for (std::size_t k = 0; k < n_seg; ++k) {
    const std::complex<double> e = std::polar(1.0, -2.0 * M_PI * df * (t[k] - t[0]));
    sr[k] = e.real();
    sim[k] = e.imag();
  }
  int grid = 0;
  for (double f = f_lo; f <= f_hi; f += df, ++grid) {
    if (grid % kFresh == 0) {
      for (std::size_t k = 0; k < n_seg; ++k) {
        const std::complex<double> e = std::polar(1.0, -2.0 * M_PI * f * (t[k] - t[0]));
        pr[k] = e.real();
        pim[k] = e.imag();
      }
    } else {
      for (std::size_t k = 0; k < n_seg; ++k) {
        const double a = pr[k], b = pim[k];
        pr[k] = a * sr[k] - b * sim[k];
        pim[k] = a * sim[k] + b * sr[k];
      }
    }
    // The sums over the samples in kLanes interleaved partial sums (sample k in lane k mod
    // kLanes), independent of each other, which the compiler packs into vector instructions; the
    // lanes are added at the end. Only the spectrum's largest value is read, which the order of
    // the additions (rounding, ~1e-16 of the sums) does not move.
    constexpr std::size_t kLanes = 4;
    double lane[12][kLanes] = {};  // Re, Im of X(n f), then of Z(n f), n = 1, 2, 3
    std::size_t k0 = 0;
    const auto add = [&](std::size_t k, std::size_t b) {
      const double c1 = pr[k], s1 = pim[k], x = xs[k], z = zs[k];
      const double c2 = c1 * c1 - s1 * s1, s2 = 2.0 * (c1 * s1);
      const double c3 = c2 * c1 - s2 * s1, s3 = c2 * s1 + s2 * c1;
      const double c[3] = {c1, c2, c3}, sn[3] = {s1, s2, s3};
      for (int n = 0; n < 3; ++n) {
        lane[4 * n][b] += x * c[n];
        lane[4 * n + 1][b] += x * sn[n];
        lane[4 * n + 2][b] += z * c[n];
        lane[4 * n + 3][b] += z * sn[n];
      }
    };
    for (; k0 + kLanes <= n_seg; k0 += kLanes)
      for (std::size_t b = 0; b < kLanes; ++b) add(k0 + b, b);
    for (std::size_t k = k0; k < n_seg; ++k) add(k, k - k0);
    double Xr[3], Xi[3], Zr[3], Zi[3];
    for (int n = 0; n < 3; ++n) {
      const auto total = [&](int j) {
        return (lane[j][0] + lane[j][1]) + (lane[j][2] + lane[j][3]);
      };
      Xr[n] = total(4 * n);
      Xi[n] = total(4 * n + 1);
      Zr[n] = total(4 * n + 2);
      Zi[n] = total(4 * n + 3);
    }
    std::complex<double> X[3], Z[3];
    for (int n = 0; n < 3; ++n) {
      X[n] = {Xr[n], Xi[n]};
      Z[n] = {Zr[n], Zi[n]};
    }
    consider(f, X, Z);
  }
  return peak(df);
}

}  // namespace detail

namespace {

using detail::spectral_peak;
using detail::SpectralPeak;

// Least squares on f from the spectrum's peak (of the first 4096 samples of t): on those
// samples, then on spans growing fourfold up to the whole of t. `with_two`: the refinement with
// two harmonics on those samples (resolving_frequency), where the one with n_max continues.
double refine_peak(std::span<const double> t, std::span<const double> ddx,
                   std::span<const double> ddz, const SpectralPeak& peak, int n_max,
                   std::optional<double> with_two = std::nullopt) {
  std::size_t len = std::min<std::size_t>(t.size(), 4096);
  if (n_max < 2) with_two.reset();  // (refine_staged: refined <= n_max)
  double f =
      refine_staged(t.first(len), ddx.first(len), ddz.first(len), with_two ? *with_two : peak.f,
                    1.5 * peak.df / peak.f, n_max, with_two ? 2 : 0);
  while (len < t.size()) {
    len = std::min(t.size(), 4 * len);
    const double periods = (t[len - 1] - t[0]) * f;
    f = refine_frequency(t.first(len), ddx.first(len), ddz.first(len), f, 0.3 / periods, n_max);
  }
  return f;
}

// The harmonics that samples `step` apart resolve at f: 2 N + 1 per period, N in [2, 10].
// The record's mean sampling step [s], without the steps that are gaps (longer than half an
// excitation period, which the gap gate judges): the step the harmonics resolved are counted at.
// Not the median step: a fifth of the samples lost at random left the median at the logger's
// 1 ms, 10 harmonics were asked of 20.2 samples per period, and every window was refused as too
// sparse, where half as many samples evenly spaced were identified.
double sampling_step(std::span<const double> t, double f) {
  const double gap = 0.5 / f;
  double covered = 0.0;
  std::size_t steps = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double dt = t[i] - t[i - 1];
    if (dt > gap) continue;
    covered += dt;
    ++steps;
  }
  return steps > 0 ? covered / static_cast<double>(steps) : detail::median_step(t);
}

int harmonics_resolved_at(double f, double step) {
  const double per_period = 1.0 / (f * step);
  return std::clamp(static_cast<int>(std::floor((per_period - 1.0) / 2.0)), 2, 10);
}

// resolved_harmonics' f when none is given: from the spectrum's peak of the first 4096 samples,
// refined with two harmonics on them.
double resolving_frequency(std::span<const double> t, std::span<const double> ddx,
                           std::span<const double> ddz, const SpectralPeak& peak) {
  const std::size_t n = std::min<std::size_t>(t.size(), 4096);
  return refine_peak(t.first(n), ddx.first(n), ddz.first(n), peak, 2);
}

}  // namespace

double estimate_frequency(std::span<const double> t, std::span<const double> ddx,
                          std::span<const double> ddz, const FrequencySearch& search) {
  check_record(t, ddx, ddz);
  // From the first stretch where the drum oscillates (the record's beginning, unless it is quiet).
  const std::size_t s = detail::estimation_start(ddx, ddz);
  t = t.subspan(s), ddx = ddx.subspan(s), ddz = ddz.subspan(s);
  const SpectralPeak peak = spectral_peak(t, ddx, ddz, search);
  // No more harmonics than the sampling resolves at the peak (a slow logger's).
  return refine_peak(t, ddx, ddz, peak,
                     std::min(search.n_max, harmonics_resolved_at(peak.f, detail::median_step(t))));
}

bool sampled_in_step(std::span<const double> t, double f) {
  if (t.size() < 3 || !(f > 0)) return false;
  const double h = detail::median_step(t);
  const double per_period = 1.0 / (f * h), periods = f * (t.back() - t.front());
  std::vector<double> dev(t.size() - 1);  // each step's deviation from h, in steps
  for (std::size_t i = 1; i < t.size(); ++i) dev[i - 1] = std::abs(t[i] - t[i - 1] - h) / h;
  std::nth_element(dev.begin(), dev.begin() + static_cast<std::ptrdiff_t>(dev.size() / 2),
                   dev.end());
  const double jitter = dev[dev.size() / 2];
  for (int j = 1; j <= 4; ++j) {
    const double jm = j * per_period;
    if (std::abs(jm - std::round(jm)) * periods < 2.0 && j * jitter < 0.01) return true;
  }
  return false;
}

int resolved_harmonics(std::span<const double> t, std::span<const double> ddx,
                       std::span<const double> ddz, const WindowOptions& w) {
  if (t.size() < 8) return 10;  // analyze_windows says what is wrong
  double f = w.f;
  if (!(f > 0)) {
    const std::size_t s = detail::estimation_start(ddx, ddz);
    const auto ts = t.subspan(s), xs = ddx.subspan(s), zs = ddz.subspan(s);
    const std::size_t n = std::min<std::size_t>(ts.size(), detail::kEstimationSamples);
    f = resolving_frequency(ts, xs, zs,
                            spectral_peak(ts.first(n), xs.first(n), zs.first(n), w.search));
  }
  return harmonics_resolved_at(f, sampling_step(t, f));
}

std::vector<double> integrate_speed(std::span<const double> t, std::span<const double> speed) {
  if (t.size() != speed.size())
    throw Error("record: t and speed must have the same length; got " + std::to_string(t.size()) +
                ", " + std::to_string(speed.size()));
  std::vector<double> x(t.size(), 0.0);
  for (std::size_t i = 1; i < t.size(); ++i)
    x[i] = x[i - 1] + 0.5 * (speed[i] + speed[i - 1]) * (t[i] - t[i - 1]);
  return x;
}

namespace {

// RMS of a fitted periodic signal without its mean: sqrt(sum over n >= 1 of A_n^2 / 2).
double periodic_rms(const std::vector<Harmonic>& h) {
  double sum = 0.0;
  for (std::size_t n = 1; n < h.size(); ++n) sum += 0.5 * h[n].amplitude * h[n].amplitude;
  return std::sqrt(sum);
}

// The RMS of y about its mean (what relative_rms divides by).
double rms_about_mean(std::span<const double> y) {
  double mean = 0.0, mean_square = 0.0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  for (double v : y) mean_square += (v - mean) * (v - mean);
  return std::sqrt(mean_square / static_cast<double>(y.size()));
}

// The standard deviations of the f / f of each of a window's `parts` equal parts that the noise
// alone makes, against which a frequency drift between two parts is weighed (as the change gate
// weighs a change). Each part's f is a least-squares estimate together with the harmonics'
// coefficients: its variance is sigma^2 /
// |(I - P) D|^2 per channel (the Gauss-Newton covariance), D the derivative of the half's fitted
// series with respect to f / f and P the projection onto the harmonics (what they can absorb of
// a change of f is no information about it), sigma the channel's residual in the window's fit
// (noise, and what the harmonics do not fit: a logger's 26 samples per period alias those above
// the 12th). Two halves of one period each at 1 kHz, with no noise at all, gave a drift of
// -0.004, twice --max-drift; with 1 % noise up to 0.022.
std::vector<double> drift_noise(std::span<const double> t, std::span<const double> x,
                                std::span<const double> z, const RecordMetrics& m, double f,
                                int n_max, std::size_t parts) {
  const double nu = 2.0 * std::numbers::pi * f;
  std::vector<double> sd;  // of each part's f / f
  for (std::size_t part = 0; part < parts; ++part) {
    const std::size_t from = t.size() * part / parts, count = t.size() * (part + 1) / parts - from;
    const std::span<const double> th = t.subspan(from, count);
    const double mid = 0.5 * (th.front() + th.back());
    const auto n = static_cast<Eigen::Index>(count);
    Eigen::MatrixXd B(n, 2 * n_max + 1);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double tau = th[static_cast<std::size_t>(i)] - mid;
      B(i, 0) = 1.0;
      for (int k = 1; k <= n_max; ++k) {
        B(i, 2 * k - 1) = std::cos(k * nu * tau);
        B(i, 2 * k) = std::sin(k * nu * tau);
      }
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(B);
    double information = 0.0;
    for (int c = 0; c < 2; ++c) {
      const std::span<const double> y = (c == 0 ? x : z).subspan(from, count);
      const double sigma = (c == 0 ? m.residual_x : m.residual_z) * rms_about_mean(y);
      if (!(sigma > 0.0)) continue;
      const Eigen::VectorXd coefficients = qr.solve(Eigen::Map<const Eigen::VectorXd>(y.data(), n));
      Eigen::VectorXd D(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const double tau = th[static_cast<std::size_t>(i)] - mid;
        double d = 0.0;
        for (int k = 1; k <= n_max; ++k)
          d += k * (-coefficients[2 * k - 1] * B(i, 2 * k) + coefficients[2 * k] * B(i, 2 * k - 1));
        D[i] = nu * tau * d;
      }
      const Eigen::VectorXd free = D - B * qr.solve(D);
      information += free.squaredNorm() / (sigma * sigma);
    }
    sd.push_back(information > 0.0 ? 1.0 / std::sqrt(information) : 0.0);  // 0: an exact fit
  }
  return sd;
}

// A harmonic beyond the n_max fitted whose frequency, folded about the sampling rate, lies within
// `resolution` of a fitted one's but not on it: the two beat across the window, and each part's
// fit takes the folded one in with a phase that turns from part to part. A record sampled near
// but not in step with the excitation does this: 625 samples/s at 39 Hz folds 14 f (546 Hz) to
// 79 Hz, 1 Hz from 2 f, and z_M'''s fitted RMS moved by 5 % between a window's quarters on a
// steady record (every window failed the change gate as "a change of soil").
struct Beat {
  int order = 0;        ///< the harmonic beyond n_max (0: none)
  int with = 0;         ///< the fitted one it beats with
  double folded = 0.0;  ///< where it folds to [Hz]
};
Beat beating_harmonic(double f, double rate, int n_max, double resolution) {
  const int top = std::min(4 * (n_max + 1), 100);
  for (int n = n_max + 1; n <= top; ++n) {
    const double a = std::fmod(n * f, rate), folded = std::min(a, rate - a);
    const int with = static_cast<int>(std::lround(folded / f));
    if (with < 1 || with > n_max) continue;
    const double apart = std::abs(folded - with * f);
    // On it (within 1e-6 of the resolution): in step, the same in every part. The lowest order
    // (the largest, as harmonics decay) is named.
    if (apart < resolution && apart > 1e-6 * resolution) return {n, with, folded};
  }
  return {};
}

// Does the response change within the window? The window is cut into K equal parts (4, or 3 or 2
// where shorter parts would not hold a period and their samples), each fitted at the window's f
// (f/2 with 2 n_max harmonics for a period-2 fit, so that each part holds two periods);
// the RMS of the fitted periodic signal of each channel is compared between every two parts,
// relative to the window's. Halves alone missed a change inside the window that returns before
// its end (a stiff spot in its middle half: equal halves, a confident G that belongs to neither
// soil). A change counts when it exceeds `max_change` and five times what the noise alone makes
// of it. White noise of deviation sigma (from the residual of the best-fitting part) moves each
// fitted coefficient by about sigma sqrt(2 / n_part), and the RMS R = sqrt(sum A_n^2 / 2) by its
// projection on the signal, about sigma / sqrt(n_part) (the rest changes R only in the second
// order); the difference of two parts by sqrt(2) times that.
void change_within(std::span<const double> t, std::span<const double> x, std::span<const double> z,
                   double f, int n_max, RecordWindow& w, std::vector<std::string>& reasons,
                   const WindowOptions& o) {
  const double max_change = o.gates.max_change;
  // Each part at least one period long and with twice as many samples as its fit has
  // coefficients (2 (2 n_max + 1): the residual, and with it the noise the change is weighed
  // against, means something). Halves of two periods were asked before, and windows of 2 to 4
  // periods, which the docs suggest for placing a change between windows, were never checked:
  // one straddling a change of the soil passed as valid with mixed metrics.
  const auto min_samples = static_cast<std::size_t>(2 * (2 * n_max + 1));
  // A part's span counts its last sample's interval: 1024 samples of one period cover it.
  const double dt = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
  // A part is also as densely sampled as analyze_record asks of a window for n_max harmonics
  // (2 n_max + 1 samples per period between its first and last); one that is not says nothing
  // about a change.
  const auto part_begin = [&t](std::size_t k, std::size_t parts) { return t.size() * k / parts; };
  const auto usable = [&](std::size_t parts) {
    for (std::size_t k = 0; k < parts; ++k) {
      const std::size_t b = part_begin(k, parts), e = part_begin(k + 1, parts);
      if (e - b < min_samples) return false;
      const double cycles = (t[e - 1] - t[b]) * f;
      if (cycles + dt * f < 1.0 - 1e-9 ||
          static_cast<double>(e - b - 1) < (2.0 * n_max + 1.0) * cycles)
        return false;
    }
    return true;
  };
  std::size_t parts = 4;
  while (parts >= 2 && !usable(parts)) --parts;
  if (parts < 2) return;
  // Each part's harmonics and residuals as analyze_record fits them (fit_record), without the
  // peaks, area and subharmonics that are not compared.
  std::vector<RecordFit> fits;
  for (std::size_t k = 0; k < parts; ++k) {
    const std::size_t b = part_begin(k, parts), n = part_begin(k + 1, parts) - b;
    fits.push_back(fit_record(t.subspan(b, n), x.subspan(b, n), z.subspan(b, n), f, n_max));
  }
  // The smallest part (they differ by one sample at most) sets the noise.
  const auto n_part = static_cast<double>(t.size() / parts);
  double worst = 0.0, worst_abs = -1.0;
  std::size_t from = 0, to = 1;
  bool significant = false;
  const char* channel = "x_M''";
  // The fit of the whole window: its harmonics, or for a period-p fit (f, n_max here those of
  // f/p) the fit on the harmonics of f/p, subharmonics included, as each part's.
  std::optional<RecordFit> period_p;
  if (w.metrics.fitted_periods > 1.0) period_p = fit_record(t, x, z, f, n_max);
  for (int c = 0; c < 2; ++c) {
    const std::span<const double> y = c == 0 ? x : z;
    const RecordMetrics& m = w.metrics;
    const double whole = period_p ? periodic_rms(c == 0 ? period_p->hx : period_p->hz)
                                  : periodic_rms(c == 0 ? m.ddx_harmonics : m.ddz_harmonics);
    if (!(whole > 0.0)) continue;
    // One value throughout (a dead channel): its fitted "RMS" is the round-off of a constant.
    if (detail::one_value(y)) continue;
    // The noise from the best-fitting part: a part that straddles the change fits worse, and
    // so does the whole window, whose residual would take the change for noise.
    double residual = std::numeric_limits<double>::infinity();
    std::vector<double> rms;
    for (const RecordFit& fit : fits) {
      residual = std::min(residual, c == 0 ? fit.residual_x : fit.residual_z);
      rms.push_back(periodic_rms(c == 0 ? fit.hx : fit.hz));
    }
    // The residuals are relative to the RMS about the mean (relative_rms).
    const double sigma = residual * rms_about_mean(y);
    const double noise = std::sqrt(2.0) * sigma / std::sqrt(n_part);
    for (std::size_t i = 0; i < parts; ++i) {
      for (std::size_t j = i + 1; j < parts; ++j) {
        const double change = (rms[j] - rms[i]) / whole;
        if (std::abs(change) > worst_abs) {
          worst_abs = std::abs(change);
          worst = change;
          from = i, to = j;
          channel = c == 0 ? "x_M''" : "z_M''";
          significant = std::abs(rms[j] - rms[i]) > 5.0 * noise;
        }
      }
    }
  }
  if (worst_abs < 0.0) return;
  w.change = worst;
  if (significant && worst_abs > max_change) {
    const std::string where = parts == 2 ? "from its first half to its second"
                                         : "from part " + std::to_string(from + 1) + " to part " +
                                               std::to_string(to + 1) + " of " +
                                               std::to_string(parts) + " equal parts";
    // A glitch (one sample far off, an electrical spike of the logger) changes a part's fitted
    // RMS as a change of soil does: a window of constant soil with one spike of 5 m/s^2 in z was
    // said to change by 10 % ("a shorter --window resolves it", which it does not). The two parts
    // compared are searched for one: a sample whose residual from its part's fit exceeds
    // kGlitch robust sigmas (1.4826 times the median |residual|) with every other sample of the
    // part within half of it.
    std::string glitch;
    const std::span<const double> y = std::string(channel) == "x_M''" ? x : z;
    for (const std::size_t part : {from, to}) {
      constexpr double kGlitch = 10.0;
      const std::size_t b = part_begin(part, parts), m = part_begin(part + 1, parts) - b;
      const Eigen::VectorXd& c =
          std::string(channel) == "x_M''" ? fits[part].fit.cx : fits[part].fit.cz;
      detail::HarmonicsInOrder h(t.subspan(b, m), 0.0, f, n_max);
      std::vector<double> r(m);
      for (std::size_t i = 0; i < m; ++i) {
        h.at(i);
        double fitted = c[0];
        for (int k = 1; k <= n_max; ++k) fitted += c[2 * k - 1] * h.cos(k) + c[2 * k] * h.sin(k);
        r[i] = std::abs(y[b + i] - fitted);
      }
      const auto largest = std::max_element(r.begin(), r.end());
      const double peak = *largest;
      const std::size_t at = static_cast<std::size_t>(largest - r.begin());
      double second = 0.0;
      for (std::size_t i = 0; i < m; ++i)
        if (i != at) second = std::max(second, r[i]);
      std::vector<double> sorted = r;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(m / 2),
                       sorted.end());
      const double sigma = 1.4826 * sorted[m / 2];
      if (sigma > 0.0 && peak > kGlitch * sigma && second < 0.5 * peak) {
        glitch = "part " + std::to_string(part + 1) + " holds one sample far off its fit (" +
                 std::string(channel) + " at t = " + num(t[b + at] + o.time_origin) + " s, " +
                 num(std::round(peak / sigma)) +
                 " robust sigmas off, every other sample within half of that): a glitch of the "
                 "logger rather than a change; remove it, or --max-change lets the window pass";
        break;
      }
    }
    // No glitch: a fold of the sampling that beats with a fitted harmonic over the parts (whose
    // frequency resolution is parts / span) moves their fits as a change would.
    std::string beat;
    if (glitch.empty()) {
      const double rate = 1.0 / dt, span = t.back() - t.front() + dt;
      const Beat b = beating_harmonic(f, rate, n_max, static_cast<double>(parts) / span);
      if (b.order > 0)
        beat = "or the sampling's: at " + num(std::round(rate * 10) / 10) + " samples/s (" +
               num(std::round(rate / f * 100) / 100) + " per period) harmonics beyond the " +
               std::to_string(n_max) + " fitted fold to within " +
               num(std::round(std::abs(b.folded - b.with * f) * 100) / 100) +
               " Hz of fitted ones (" + std::to_string(b.order) + " f to " +
               num(std::round(b.folded * 10) / 10) + " Hz, beside " + std::to_string(b.with) +
               " f) and beat with them across the window, which moves the fitted harmonics of a "
               "steady response (a rate in step with f, or further from one, holds them apart; "
               "--max-change lets such windows pass, their harmonics biased by the folds)";
    }
    reasons.push_back(
        "the response changes within the window: the RMS of " + std::string(channel) + " by " +
        (worst > 0 ? "+" : "") + num(std::round(worst * 1000) / 10) + " % of the window's " +
        where + " (> " + num(max_change * 100) +
        (o.one_reference ? " %): " : " %; --max-change): ") +
        (o.one_reference   ? "a reference must be of one soil and one setting: cut the record "
                             "where it changes"
         : !glitch.empty() ? glitch
                           : "a change of soil or of the roller's settings within it; "
                             "a shorter --window resolves it" +
                                 (beat.empty() ? std::string() : "; " + beat)));
  }
}

}  // namespace

std::vector<RecordWindow> analyze_windows(std::span<const double> t, std::span<const double> ddx,
                                          std::span<const double> ddz,
                                          std::span<const double> position,
                                          const WindowOptions& o) {
  check_record(t, ddx, ddz, o.time_origin);
  if (!position.empty() && position.size() != t.size())
    throw Error("record: the position column must have one value per sample; got " +
                std::to_string(position.size()) + " for " + std::to_string(t.size()));
  if (o.n_max != 0 && (o.n_max < 2 || o.n_max > kMaxRecordHarmonics))
    throw Error("record: n_max must be in [2, " + std::to_string(kMaxRecordHarmonics) +
                "] (psi needs the 2f harmonic; 0: as many as the sampling resolves); got " +
                std::to_string(o.n_max));

  if (!(o.f >= 0) || !std::isfinite(o.f))
    throw Error("record: f (--f) must be >= 0 [Hz] (0: estimated); got " + num(o.f));
  // Every size and gate is a finite number in its range (NaN would switch a check off).
  const auto require = [](bool holds, const std::string& what, double value) {
    if (!holds) throw Error("record: " + what + "; got " + num(value));
  };
  // A window shorter than a period holds no period to fit: every window failed its own check.
  require((o.window_periods == 0 || o.window_periods >= 1) && std::isfinite(o.window_periods),
          "window (--window) must be >= 1 [periods] (0: the whole record)", o.window_periods);
  require(o.hop_periods >= 0 && std::isfinite(o.hop_periods),
          "hop (--hop) must be >= 0 [periods] (0: the window)", o.hop_periods);
  require(o.gates.max_residual > 0 && std::isfinite(o.gates.max_residual),
          "max_residual (--max-residual) must be > 0 [-]", o.gates.max_residual);
  require(o.gates.max_drift >= 0 && std::isfinite(o.gates.max_drift),
          "max_drift (--max-drift) must be >= 0 [-]", o.gates.max_drift);
  require(o.gates.clip_level >= 0 && std::isfinite(o.gates.clip_level),
          "clip_level (--clip-level) must be >= 0 [m/s^2] (0: detect plateaus)",
          o.gates.clip_level);
  require(o.gates.max_gap > 0 && std::isfinite(o.gates.max_gap),
          "max_gap (--max-gap) must be > 0 [periods]", o.gates.max_gap);
  require(o.gates.max_change > 0 && std::isfinite(o.gates.max_change),
          "max_change (--max-change) must be > 0 [-]", o.gates.max_change);
  require(o.gates.clip_run >= 2, "clip_run must be >= 2 [samples]", o.gates.clip_run);
  // f: at most half the record's sampling rate (a harmonic fit needs 2 samples per period).
  double sample_step = 0.0;  // the median time step [s]
  {
    sample_step = detail::median_step(t);
    const double rate = 1.0 / sample_step;
    require(o.f <= 0.5 * rate,
            "f (--f) must be at most half the record's sampling rate, " + num(0.5 * rate) + " Hz",
            o.f);
  }
  const bool windowed = o.window_periods > 0;
  // A slow logger's: the frequency searched only up to a fifth of its sampling rate
  // (spectral_peak), below the search's own limit. A poor fit at the f found there may be a faster
  // excitation's harmonic folded below it (39 Hz at 100 samples/s: its third harmonic at 17 Hz).
  const double searched_up_to = 0.2 / sample_step;
  const std::string slow_logger =
      o.f == 0.0 && searched_up_to < o.search.f_max
          ? " (f was searched up to " + sig4(searched_up_to) + " Hz only, a fifth of the " +
                sig4(1.0 / sample_step) +
                " samples/s: a faster excitation, or its harmonic folded below that, is not "
                "resolved; give --f if the excitation frequency is known, or record at 5 f "
                "samples/s or more)"
          : std::string();
  // The record's frequency: given, or from its beginning (windows) or the whole (no windows);
  // the harmonics: given, or as many as the sampling resolves (resolved_harmonics, from the same
  // spectrum's peak: both search the same 4096 samples).
  double f_rec = o.f;
  int n_max = o.n_max;
  if (f_rec == 0.0) {
    // From the record's first stretch where the drum oscillates: its beginning, unless that is
    // quiet (a logger started before the exciter), where a frequency of the noise would be found.
    const std::size_t s = detail::estimation_start(ddx, ddz);
    const auto ts = t.subspan(s), xs = ddx.subspan(s), zs = ddz.subspan(s);
    const std::size_t n =
        windowed ? std::min<std::size_t>(ts.size(), detail::kEstimationSamples) : ts.size();
    const SpectralPeak peak = spectral_peak(ts.first(n), xs.first(n), zs.first(n), o.search);
    std::optional<double> with_two;  // the same peak refined with two harmonics
    if (n_max == 0) {
      with_two = resolving_frequency(ts, xs, zs, peak);
      n_max = harmonics_resolved_at(*with_two, sampling_step(t, *with_two));
    }
    f_rec = refine_peak(ts.first(n), xs.first(n), zs.first(n), peak, o.search.n_max, with_two);
  } else if (n_max == 0) {
    n_max = resolved_harmonics(t, ddx, ddz, o);
  }
  const double span = t.back() - t.front();
  // n samples at the step dt cover n dt: a record of N periods sampled uniformly (its last
  // sample one step before the end of the N-th period, as oscidrum run writes it) holds N periods,
  // up to the error of the f estimated from its beginning (1.6e-5 relative on a 40-period record
  // with 5 % noise, 0.7 steps at 1024 samples per period): a window may reach a thousandth of
  // itself, or half a step, beyond the last sample.
  const double covered = span + sample_step;
  const auto spans = [&](double periods) {
    return !(covered * f_rec < periods * (1.0 - 1e-3) &&
             (covered + 0.5 * sample_step) * f_rec < periods);
  };
  if (windowed && o.whole_if_shorter && !spans(o.window_periods) && spans(1.0)) {
    // A default window longer than the record: the whole record is the window (its f from all
    // of it, as without windows).
    WindowOptions whole = o;
    whole.window_periods = whole.hop_periods = 0.0;
    whole.whole_if_shorter = false;
    std::vector<RecordWindow> one = analyze_windows(t, ddx, ddz, position, whole);
    for (RecordWindow& w : one) w.whole = true;
    return one;
  }
  // More windows than the record has samples is no analysis (a window or hop of a tiny part of
  // a period): refused with the smallest hop that makes sense.
  if (windowed) {
    const double hop = o.hop_periods > 0 ? o.hop_periods : o.window_periods;
    const double count = std::floor((span * f_rec - o.window_periods) / hop) + 1.0;
    if (count > static_cast<double>(t.size()))
      throw Error(
          "record: " + std::string(o.hop_periods > 0 ? "hop (--hop)" : "window (--window)") +
          " of " + num(hop) + " periods gives " + num(count) + " windows, more than the record's " +
          std::to_string(t.size()) + " samples; it must be at least " +
          num((span * f_rec) / static_cast<double>(t.size())) + " periods");
  }
  const double needed = std::max(1.0, o.window_periods);
  if (!spans(needed))
    throw Error("record: must span at least " +
                (windowed ? "one window (" + num(o.window_periods) + " periods"
                          : std::string("one excitation period (1/f")) +
                " = " + sig4(std::max(1.0, o.window_periods) / f_rec) + " s at f = " + sig4(f_rec) +
                " Hz); its samples cover " + sig4(covered) + " s (" + sig4(covered * f_rec) +
                " periods)" +
                (windowed && covered * f_rec >= 1.0
                     ? ": take the whole record as one window with --window 0, or a shorter "
                       "--window"
                 : o.f > 0 ? ""
                           // f estimated from less than a period of samples (0.6 periods at 39
                           // Hz read as 60 Hz, quoted here as if measured): not to be trusted
                           : "; f was estimated from these samples, less than one period of "
                             "it, and is not known from them: the record must be longer"));

  // Time steps (gaps), and the samples at a channel's extreme (plateaus: clipping).
  std::vector<double> dt(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i) dt[i - 1] = t[i] - t[i - 1];
  // With clip_level: every sample at |a| >= clip_level. Without: plateaus, found per window
  // (plateau_samples below).
  std::vector<char> clipped(t.size(), 0);
  if (o.gates.clip_level > 0)
    for (const std::span<const double> y : {ddx, ddz})
      for (std::size_t i = 0; i < y.size(); ++i)
        if (std::abs(y[i]) >= o.gates.clip_level) clipped[i] = 1;
  // The samples of [first, last] on a plateau: runs of at least clip_run equal samples (to 1e-9
  // of the window's range) in the outer quarter of the window's range of a channel, at its
  // extreme and met and left at the signal's slope, not in code-sized steps (clipped_run). Per
  // window, not at the record's extremes: a record clipped only in part of it, or with one sample
  // beyond the clip level (a spike), has its plateaus below the record's extremes.
  const auto plateau_samples = [&](std::size_t first, std::size_t last) {
    std::size_t n = 0;
    const double per_period = static_cast<double>(t.size() - 1) / ((t.back() - t.front()) * f_rec);
    std::vector<char> on(last - first + 1, 0);
    for (const std::span<const double> y : {ddx, ddz}) {
      const auto extremes = std::minmax_element(y.begin() + static_cast<std::ptrdiff_t>(first),
                                                y.begin() + static_cast<std::ptrdiff_t>(last) + 1);
      const double lo = *extremes.first, hi = *extremes.second;
      if (lo == hi) continue;  // constant: no extreme to stick to
      const double range = hi - lo, tol = 1e-9 * range;
      const auto outer = [&](double v) { return v >= hi - 0.25 * range || v <= lo + 0.25 * range; };
      const double quantum = detail::record_code(y, first, last, tol);
      const double noise = quantum > 0.0 ? detail::second_difference_noise(y, first, last) : 0.0;
      std::size_t run = 1;
      for (std::size_t i = first + 1; i <= last + 1; ++i) {
        if (i <= last && std::abs(y[i] - y[i - 1]) <= tol && outer(y[i])) {
          ++run;
          continue;
        }
        if (run >= static_cast<std::size_t>(std::max(2, o.gates.clip_run))) {
          // The window's samples past the run's level (above a top run, below a bottom one),
          // counted where clipped_run asks (a record in codes).
          const double level = y[i - 1];
          const bool upper = level >= hi - 0.25 * range;
          const auto beyond = [&] {
            std::size_t n_beyond = 0;
            for (std::size_t j = first; j <= last; ++j)
              n_beyond += upper ? y[j] > level + tol : y[j] < level - tol;
            return n_beyond;
          };
          // The run as far as it goes in the record (a run at a window's edge).
          std::size_t a = i - run, b = i - 1;
          while (a > 0 && y[a - 1] == y[a]) --a;
          while (b + 1 < y.size() && y[b + 1] == y[b]) ++b;
          if (detail::clipped_run(y, a, b, beyond, per_period, 0.5 * range, quantum, noise))
            for (std::size_t j = i - run; j < i; ++j) on[j - first] = 1;
        }
        run = 1;
      }
    }
    for (char c : on) n += c;
    return n;
  };

  std::vector<RecordWindow> out;
  // The windows are cut at --window periods of f_cut: the record's opening frequency, and where
  // the tracked frequency moves more than 1 % from it (an exciter spinning up, the operator's
  // other setting), the tracked one from there on (cut at the opening frequency throughout, a
  // record that went on at 39 Hz after opening at 30 Hz had windows of 52 periods, reported as
  // 40).
  double f_cut = f_rec;
  double W = windowed ? o.window_periods / f_cut : span;
  double H = windowed ? (o.hop_periods > 0 ? o.hop_periods : o.window_periods) / f_cut : span;
  double f_track = f_rec;
  std::size_t first = 0;
  // Window ends are compared with the sample times up to their rounding: a small fraction of the
  // window plus a few ulps of the times themselves (t.front() + k H rounds at the scale of the
  // times, which may be far from 0: a record may start at t = -100 s or on a clock at 1e6 s). The
  // slack must not depend on the sign of t: a bound scaled by t.back() itself fell below t.back()
  // for a record ending before t = -1 s, no window fitted, and analyze read the empty list.
  const double t_scale = std::max(std::abs(t.front()), std::abs(t.back()));
  double slack = 1e-12 * W + 16.0 * std::numeric_limits<double>::epsilon() * t_scale;
  // The windows start every H from the first sample; the end of the record, where it is left over
  // (a full period or more after the last window), gets a last window that ends with the record
  // (overlapping the one before): the end of a record is never dropped silently.
  bool end_window = false;
  double t_cut = t.front();  // the start of the first window cut at f_cut
  int k_cut = 0;             // its index
  int recut = -1;            // the window cut again at its own frequency
  for (int k = 0;; ++k) {
    double ts = t_cut + (k - k_cut) * H;
    if (windowed && !end_window && std::abs(f_track / f_cut - 1.0) > 0.01) {
      f_cut = f_track;
      t_cut = ts;
      k_cut = k;
      W = o.window_periods / f_cut;
      H = (o.hop_periods > 0 ? o.hop_periods : o.window_periods) / f_cut;
      slack = 1e-12 * W + 16.0 * std::numeric_limits<double>::epsilon() * t_scale;
    }
    if (k > 0 && ts + W > t.back() + slack) {
      if (!windowed || end_window || t.back() - out.back().t_end < 1.0 / f_track) break;
      end_window = true;
      ts = t.back() - W;
      first = 0;
    }
    while (first < t.size() && t[first] < ts - slack) ++first;
    // A window with no sample, or one, lies within a gap of the record (a logger paused between
    // two passes): it keeps its place in time, with the gap as its reason (its one "sample", the
    // first after the gap, gave t_start = t_end there, "-nan" samples per period and the reason of
    // a dead channel). One sample counts so only where a step beside it is a gap.
    const bool none = first >= t.size() || t[first] > ts + W + slack;
    const bool one = !none && (first + 1 >= t.size() || t[first + 1] > ts + W + slack);
    double before = first > 0 ? t[first - 1] : ts, after = first < t.size() ? t[first] : ts + W;
    if (one) {  // the longer step beside the one sample
      const double left = first > 0 ? t[first] - t[first - 1] : 0.0,
                   right = first + 1 < t.size() ? t[first + 1] - t[first] : 0.0;
      if (right > left) before = t[first], after = t[first + 1];
    }
    if (windowed && (none || (one && after - before > o.gates.max_gap / f_track))) {
      RecordWindow w;
      w.index = k;
      w.first = std::min(first, t.size() - 1);
      w.count = 0;
      w.t_start = ts;
      w.t_end = ts + W;
      w.t_mid = ts + 0.5 * W;
      w.f = w.drift = w.change = w.samples_per_period = kNaN;
      w.position = kNaN;
      if (!position.empty() && first > 0 && first < t.size()) {
        const double u = (w.t_mid - t[first - 1]) / (t[first] - t[first - 1]);
        w.position = position[first - 1] + u * (position[first] - position[first - 1]);
      }
      w.reason = std::string(none ? "no samples" : "one sample at its edge, not analysed") +
                 ": the window lies within a gap of " + sig4(after - before) +
                 " s at t = " + num(before + o.time_origin) + " s (" +
                 num(std::round((after - before) * f_track * 100) / 100) +
                 " excitation periods without a sample)";
      RecordMetrics nan = detail::all_unavailable<RecordMetrics>(record_outputs());
      nan.cycles = W * f_track;
      nan.residual_x = nan.residual_z = kNaN;
      nan.ddx_harmonics.assign(static_cast<std::size_t>(n_max) + 1, Harmonic{kNaN, kNaN});
      nan.ddz_harmonics = nan.ddx_harmonics;
      w.metrics = nan;
      out.push_back(std::move(w));
      if (end_window) break;
      continue;
    }
    std::size_t last = first;
    while (last + 1 < t.size() && t[last + 1] <= ts + W + slack) ++last;
    RecordWindow w;
    w.index = k;
    w.first = first;
    w.count = last - first + 1;
    w.t_start = t[first];
    w.t_end = t[last];
    w.t_mid = 0.5 * (w.t_start + w.t_end);
    w.position = kNaN;
    if (!position.empty()) {
      const auto it = std::lower_bound(t.begin(), t.end(), w.t_mid);
      const std::size_t j = static_cast<std::size_t>(it - t.begin());
      if (j == 0) {
        w.position = position[0];
      } else {
        const double u = (w.t_mid - t[j - 1]) / (t[j] - t[j - 1]);
        w.position = position[j - 1] + u * (position[j] - position[j - 1]);
      }
    }
    w.f = kNaN;
    w.drift = kNaN;
    w.change = kNaN;
    const auto tw = t.subspan(first, w.count), xw = ddx.subspan(first, w.count),
               zw = ddz.subspan(first, w.count);
    // Clipping needs no fit and no frequency.
    std::vector<std::string> clip_reasons;
    std::size_t n_clipped = 0;
    if (o.gates.clip_level > 0)
      for (std::size_t i = first; i <= last; ++i) n_clipped += clipped[i] ? 1 : 0;
    else
      n_clipped = plateau_samples(first, last);
    if (n_clipped > 0)
      clip_reasons.push_back("clipped: " + std::to_string(n_clipped) + " samples " +
                             (o.gates.clip_level > 0
                                  ? "at |a| >= " + num(o.gates.clip_level)
                                  : std::string("on a plateau near the extremes")));
    double gap = 0, gap_at = 0;
    for (std::size_t i = first; i < last; ++i)
      if (dt[i] > gap) {
        gap = dt[i];
        gap_at = t[i];
      }
    // Both channels one value throughout (a logger that holds its last value, a dead channel,
    // the exciter off): nothing to fit, and the gates' ratios of a zero signal mean nothing.
    const bool flat = detail::one_value(xw) && detail::one_value(zw);
    // The window analysed about the frequency f0 (the tracked one, or one searched for): its
    // gates, f refined, the fit and its metrics.
    struct Attempt {
      RecordWindow w;
      std::vector<std::string> reasons;
      bool fitted = false;
      bool poor_fit = false;  // fitted, but the residual gate failed
    };
    const auto attempt = [&](double f0) {
      Attempt a{w, clip_reasons};
      RecordWindow& aw = a.w;
      std::vector<std::string>& reasons = a.reasons;
      // A few lost samples are not a gap: the least-squares fit takes the samples where they
      // are. A gap is a step the fit cannot bridge, a sizeable part of an excitation period.
      const double max_gap = o.gates.max_gap / f0;
      if (gap > max_gap)
        reasons.push_back(
            "gap of " + sig4(gap) + " s at t = " + num(gap_at + o.time_origin) + " s (" +
            num(std::round(gap * f0 * 100) / 100) + " excitation periods > " +
            num(o.gates.max_gap) + "; a harmonic fit does not bridge it" +
            (windowed          ? std::string(")")
             : o.one_reference ? std::string("): cut the record at it, a reference per stretch")
                               : std::string("): windows (--window 40) fit the stretches "
                                             "on either side of it")));
      // The density where the window has samples: a gap's step (which the gap gate judges)
      // counts as one sampling step. A window with a 0.2 s gap at a steady 1 kHz also read "too
      // few samples per period (20.49 < 21)", as if the logger were too slow.
      double sampled_span = aw.t_end - aw.t_start;
      for (std::size_t i = first; i < last; ++i)
        if (dt[i] > max_gap) sampled_span -= dt[i] - sample_step;
      aw.samples_per_period = static_cast<double>(aw.count - 1) / (sampled_span * f0);
      // Its samples cover their last interval too (n samples at the step dt cover n dt, as for
      // the record above): a window of one period at 1 kHz, 26 samples spanning 0.975 periods
      // between the first and the last, was refused as shorter than a period.
      const double spanned = (aw.t_end - aw.t_start + sample_step) * f0;
      const bool dense = aw.samples_per_period >= 2.0 * n_max + 1.0,
                 long_enough = spanned >= 1.0 - 1e-9;
      if (!dense)
        reasons.push_back("too few samples per period (" + sig4(aw.samples_per_period) + " < " +
                          std::to_string(2 * n_max + 1) + " for " + std::to_string(n_max) +
                          " harmonics)");
      // Dense enough everywhere, not only on average: a record whose time stamps turn coarser
      // part way (a clock written with 6 significant digits past t = 1000 s: 10 ms stamps, the
      // rows of each averaged into one sample) held 2.6 samples per period there and 25 before,
      // 14 on average, and its fit read "ok" with the area 14 % low. Steps of less than half
      // the density the harmonics need, short of a gap (which the gap gate judges), over more
      // than a tenth of the window's span fail the gate too, where they follow one another for a
      // period or more (samples lost at random leave single long steps among short ones, which
      // the fit takes where they are).
      // Steps of half a period or more are gaps, whatever --max-gap allows.
      const double coarse_step = 2.0 / ((2.0 * n_max + 1.0) * f0);
      const double coarse_max = std::min(max_gap, 0.5 / f0);
      double coarse_span = 0.0, coarsest = 0.0, run = 0.0, run_max = 0.0;
      for (std::size_t i = first; i <= last; ++i) {
        if (i < last && dt[i] > coarse_step && dt[i] <= coarse_max) {
          run += dt[i];
          run_max = std::max(run_max, dt[i]);
          continue;
        }
        if (run * f0 >= 1.0) {
          coarse_span += run;
          coarsest = std::max(coarsest, run_max);
        }
        run = run_max = 0.0;
      }
      if (dense && coarse_span > 0.1 * sampled_span)
        reasons.push_back("too few samples per period in part of the window (" +
                          num(std::round(100.0 * coarse_span / sampled_span)) +
                          " % of its span between samples " + "up to " + sig4(coarsest) +
                          " s apart, " + sig4(1.0 / (coarsest * f0)) + " per period < " +
                          std::to_string(2 * n_max + 1) + " for " + std::to_string(n_max) +
                          " harmonics; time stamps coarser there, their rows averaged?)");
      if (!long_enough)
        reasons.push_back("its samples cover " + num(std::round(spanned * 1000) / 1000) +
                          " excitation periods (< 1)");
      if (flat)
        reasons.push_back(
            "no oscillation: x_M'' and z_M'' are each one value over the window (a "
            "logger that holds its last value, a dead channel, or the exciter off)");
      if (!(dense && long_enough && gap <= max_gap) || flat) return a;
      const double periods = (aw.t_end - aw.t_start) * f0;  // between the first and last samples
      const int nf = n_max;  // all of them: unfitted harmonics would bias f
      double fw =
          o.f > 0 ? o.f : refine_frequency(tw, xw, zw, f0, std::min(0.05, 0.5 / periods), nf);
      aw.f = fw;
      const double hw = std::min(0.05, 1.0 / periods);
      // The frequency of each of 4 equal parts (3 or 2 where shorter ones would be too short), as
      // the change gate cuts the window: halves missed a frequency that wobbles (two cycles of
      // +-0.5 % in a 40-period window left the halves alike, |drift| 2e-4, and biased G by twice
      // its uncertainty). Each part's f with its harmonics' 2 n_max + 1 coefficients: with fewer
      // than twice as many samples the estimate is not a small perturbation that drift_noise can
      // weigh (26 samples per half at 1 kHz over two periods put f at the bounds of its search, a
      // "drift" of 0.05-0.07 for a constant frequency): not measured (NaN).
      // More than two parts only where each spans a period (a quarter of a 1.5-period window
      // says little of f: such parts' f scattered by 0.013 for a constant frequency); two, the
      // halves, as before.
      try {
        aw.metrics = analyze_record(tw, xw, zw, fw, n_max);
        a.fitted = true;
        // A period-p response (analyze_record's fitted_periods): f refined again on the harmonics
        // of f/p, which the refinement on those of f took for noise, and the window fitted there.
        // From the tracked f0, not from fw: the f the harmonics of f gave is biased by the
        // subharmonics in a short window (25.38 Hz for 25 over 4 periods, its rmv 0.70 for 0.24,
        // valid). Kept whatever it finds there: where the window at the better f is no period-p
        // fit, its gates say so.
        if (aw.metrics.fitted_periods > 1.0 && o.f == 0.0) {
          const int p = static_cast<int>(aw.metrics.fitted_periods);
          const double f2 =
              refine_periodic(tw, xw, zw, f0, std::min(0.05, 0.5 / periods), p * nf, p);
          RecordMetrics m = analyze_record(tw, xw, zw, f2, n_max);
          // Kept where it fits at least as well: over a short window the refinement can end
          // elsewhere (57.979 Hz for 58 over 12 periods of a period-3 drum, fitted there on the
          // harmonics of f with the residual 0.497 for 0.166 at the f it started from).
          if (std::max(m.residual_x, m.residual_z) <=
              std::max(aw.metrics.residual_x, aw.metrics.residual_z)) {
            aw.metrics = std::move(m);
            fw = aw.f = f2;
          }
        } else if (o.f == 0.0 &&
                   std::max(aw.metrics.residual_x, aw.metrics.residual_z) > kSubharmonicLevel) {
          // A period-p response that the f refined on the harmonics of f hides (fitted there on
          // those of f with a residual under the gate, its metrics those of another figure: a
          // period-3 drum's 12-period windows, the area 1494 for 3456 m^2/s^4): where the low
          // subharmonics explain a good part of what that fit leaves, f is refined on the
          // harmonics of f/p too, and the window taken there where it fits better.
          const RecordFit rf = fit_record(tw, xw, zw, fw, n_max);
          const Leftover left = leftover_of(tw, xw, zw, fw, n_max, rf);
          const double window_periods = (aw.t_end - aw.t_start + sample_step) * fw;
          for (int p = 2; p <= kMaxFittedPeriods && window_periods >= 2.0 * p - 1e-2; ++p) {
            if (low_subharmonic_share(tw, left, fw, p) < kSubharmonicScreen) continue;
            const double fp =
                refine_periodic(tw, xw, zw, f0, std::min(0.05, 0.5 / periods), p * nf, p);
            RecordMetrics m = analyze_record(tw, xw, zw, fp, n_max);
            if (m.fitted_periods > 1.0 &&
                std::max(m.residual_x, m.residual_z) <
                    std::max(aw.metrics.residual_x, aw.metrics.residual_z)) {
              aw.metrics = std::move(m);
              fw = aw.f = fp;
              break;
            }
          }
        }
      } catch (const Error& e) {
        reasons.push_back(e.what());
      }
      if (!a.fitted) return a;
      // The fitted signal's period in excitation periods: parts of a period-2 fit each hold two.
      const int fp = std::max(1, static_cast<int>(aw.metrics.fitted_periods));
      const auto min_samples = static_cast<std::size_t>(2 * (2 * fp * n_max + 1));
      std::size_t parts = 4;
      while (parts > 2 &&
             (aw.count / parts < min_samples || periods < static_cast<double>(fp * parts)))
        --parts;
      if (aw.count / parts < min_samples) parts = 0;
      std::vector<double> part_f;
      if (parts >= 2) {
        for (std::size_t part = 0; part < parts; ++part) {
          const std::size_t b = aw.count * part / parts, n = aw.count * (part + 1) / parts - b;
          part_f.push_back(refine_periodic(tw.subspan(b, n), xw.subspan(b, n), zw.subspan(b, n), fw,
                                           hw, fp * nf, fp));
        }
      }
      if (o.f > 0.0) {
        // A given f that is not the excitation's: at half of it (a subharmonic) the harmonics
        // 2, 4, 6 hold the whole signal and the fit's residual stays small, so the residual gate
        // passed it with every metric wrong (psi_xz -1.24 for 0.44 rad). The frequency search
        // refuses such a frequency (its own term below a tenth of P(f), spectral_peak); a given
        // one is held to the same rule on the fitted harmonics 1-3 of both channels.
        double at_f = 0.0, first_three = 0.0, largest = 0.0;
        int strongest = 1;
        for (int n = 1; n <= 3; ++n) {
          double p = 0.0;
          for (const std::vector<Harmonic>* h :
               {&aw.metrics.ddx_harmonics, &aw.metrics.ddz_harmonics})
            if (static_cast<std::size_t>(n) < h->size())
              p += (*h)[static_cast<std::size_t>(n)].amplitude *
                   (*h)[static_cast<std::size_t>(n)].amplitude;
          if (n == 1) at_f = p;
          first_three += p;
          if (p > largest) largest = p, strongest = n;
        }
        if (first_three > 0.0 && at_f < 0.1 * first_three)
          reasons.push_back("the given f (--f " + num(fw) + " Hz) carries " +
                            num(std::round(1000.0 * at_f / first_three) / 10) +
                            " % of the power of its first three harmonics (< 10 %; the excitation "
                            "carries the most): the record is not excited at f (its multiple " +
                            num(strongest * fw) + " Hz carries " +
                            num(std::round(1000.0 * largest / first_three) / 10) +
                            " %: f may be a subharmonic, or the record of another frequency); "
                            "leave --f out to estimate the frequency");
      }
      change_within(tw, xw, zw, fw / fp, fp * n_max, aw, reasons, o);
      const double res = std::max(aw.metrics.residual_x, aw.metrics.residual_z);
      if (!(res <= o.gates.max_residual)) {
        a.poor_fit = true;
        // Harmonics beyond the fitted ones above the Nyquist frequency fold between them and stay
        // in the residual: at 300 samples/s and 39 Hz (3 harmonics fitted) the overtones 4f and
        // 6f of z_M'' did, where the hint of a search held below --f-max sent the user after a
        // frequency that was found right.
        // So do the harmonics just above the N fitted where the sampling could not fit one more
        // (2 N + 3 samples per period): at 500 samples/s and 39 Hz (12.8 samples per period, 5
        // harmonics) 6f lies below half the rate unfitted and 7f folds to 227 Hz, and only the
        // hint of a search held below --f-max was given (it follows, as f may be wrong).
        const double nyquist = 0.5 / sample_step;
        const double rate = 1.0 / sample_step;
        const bool beyond = (n_max + 1) * fw > nyquist;
        const bool unfitted = aw.samples_per_period < 2.0 * (n_max + 1) + 1.0;
        const std::string folded =
            beyond || unfitted
                ? " (the harmonics above the " + std::to_string(n_max) + " fitted, from " +
                      sig4((n_max + 1) * fw) + " Hz, " +
                      (beyond
                           ? "lie beyond half the " + sig4(rate) + " samples/s and fold"
                           : "are not fitted, " + sig4(aw.samples_per_period) +
                                 " samples per period holding " + std::to_string(n_max) +
                                 ", and those beyond half the " + sig4(rate) + " samples/s fold") +
                      " between the fitted ones: a response with overtones needs more samples "
                      "per period; record at " +
                      sig4(21.0 * fw) + " samples/s (21 f, 10 harmonics) or more)" + slow_logger
                : slow_logger;
        const std::string drift = offset_drift_hint(tw, xw, zw, fw / fp, fp * n_max, aw.metrics,
                                                    res, o.gates.max_residual);
        reasons.push_back("fit residual " + num(std::round(res * 1000) / 1000) + " > " +
                          num(o.gates.max_residual) + drift + folded);
      }
      // The drift: the two parts whose f differ most, beyond 5 times what the noise makes of
      // their difference where any pair is (else the largest difference, reported and passed).
      if (!part_f.empty()) {
        const std::vector<double> sd =
            drift_noise(tw, xw, zw, aw.metrics, fw / fp, fp * nf, part_f.size());
        double worst = 0.0, worst_significant = 0.0;
        bool significant = false;
        for (std::size_t i = 0; i < part_f.size(); ++i)
          for (std::size_t j = i + 1; j < part_f.size(); ++j) {
            const double d = (part_f[j] - part_f[i]) / fw;
            if (std::abs(d) > std::abs(worst)) worst = d;
            if (std::abs(d) > 5.0 * std::hypot(sd[i], sd[j]) &&
                std::abs(d) > std::abs(worst_significant))
              worst_significant = d, significant = true;
          }
        aw.drift = significant ? worst_significant : worst;
        if (significant && std::abs(aw.drift) > o.gates.max_drift)
          reasons.push_back("frequency drift " + num(std::round(aw.drift * 1e5) / 1e5) +
                            " within the window (|drift| > " + num(o.gates.max_drift) + ")");
      }
      return a;
    };
    Attempt best = attempt(f_track);
    // A fit that explains little at the tracked frequency: the excitation's frequency may have
    // changed (the operator's other setting, a start or a stop). The window's own spectral peak
    // is searched, as the record's was, and the window analysed about it too; the better fit
    // (the smaller residual) is kept.
    if (o.f == 0.0 && best.poor_fit) {
      try {
        const SpectralPeak peak = spectral_peak(tw, xw, zw, o.search);
        const double f_new = refine_peak(
            tw, xw, zw, peak,
            std::min(o.search.n_max, harmonics_resolved_at(peak.f, detail::median_step(tw))));
        if (std::isfinite(f_new) && std::abs(f_new / f_track - 1.0) > 0.01) {
          Attempt other = attempt(f_new);
          const auto residual = [](const Attempt& a) {
            return a.fitted ? std::max(a.w.metrics.residual_x, a.w.metrics.residual_z) : kNaN;
          };
          if (residual(other) < residual(best)) best = std::move(other);
        }
      } catch (const Error&) {
        // no peak to be found in this window: the tracked frequency's analysis stands
      }
    }
    w = std::move(best.w);
    std::vector<std::string>& reasons = best.reasons;
    const bool fitted = best.fitted;
    w.valid = reasons.empty();
    for (const std::string& r : reasons) w.reason += (w.reason.empty() ? "" : "; ") + r;
    if (w.valid) {
      f_track = w.f;
    } else {
      // Metrics that could not be made, or failed a gate, are not reported as valid.
      // Every number NaN (from the output table), then what the window did measure.
      RecordMetrics nan = detail::all_unavailable<RecordMetrics>(record_outputs());
      nan.cycles = (w.t_end - w.t_start) * f_track;
      nan.residual_x = fitted ? w.metrics.residual_x : kNaN;
      nan.residual_z = fitted ? w.metrics.residual_z : kNaN;
      nan.ddx_harmonics.assign(static_cast<std::size_t>(n_max) + 1, Harmonic{kNaN, kNaN});
      nan.ddz_harmonics = nan.ddx_harmonics;
      w.metrics = nan;
    }
    // A window valid at a frequency more than 1 % from the one it was cut at (the first valid
    // one after a change of the excitation's frequency, which the window across the change
    // fails) is cut again, once, at its own (f_track).
    if (windowed && w.valid && !end_window && k != recut && std::abs(w.f / f_cut - 1.0) > 0.01) {
      recut = k--;
      continue;
    }
    out.push_back(std::move(w));
    if (!windowed || end_window) break;
  }
  return out;
}

double unbalance_phase(std::span<const double> t, std::span<const double> alpha, double f) {
  if (t.size() != alpha.size() || t.empty())
    throw Error("unbalance_phase: t has " + std::to_string(t.size()) +
                " samples and the unbalance angle " + std::to_string(alpha.size()) +
                "; expected the same number, at least 1");
  // The circular mean of alpha - nu t: a sum of unit vectors, immune to the 2 pi wraps of alpha.
  const double nu = 2.0 * M_PI * f;
  double c = 0.0, s = 0.0;
  for (std::size_t j = 0; j < t.size(); ++j) {
    const double d = alpha[j] - nu * t[j];
    c += std::cos(d);
    s += std::sin(d);
  }
  return std::atan2(s, c);
}

double record_soil_stiffness(const Case& c, const Harmonic& ddz_1, double f, double phi_u) {
  if (c.roller.type != RollerType::vibratory)
    throw Error(
        "record_soil_stiffness: roller.type must be \"vibratory\" (the unbalance force "
        "F0 sin(alpha) on the drum's centre); got the oscillation drum");
  // The drum's vertical balance (20) with the unbalance force: F_v = W + F_z - cd z_M' - kd z_M
  // - m z_M''. At f, as phasors of e^{i nu t} (y = A sin(nu t + theta) <-> A e^{i theta}):
  // F_z(f) = F0 e^{i phi_u}, z_M(f) = -A_1 e^{i theta_1} / nu^2, so
  // Re(F_v(f) / z_M(f)) = m nu^2 - kd - F0 nu^2 cos(phi_u - theta_1) / A_1 (the cd term is
  // imaginary). The same identity as VibratoryDrum.SoilStiffnessIsTheDrumEquationsEstimate's.
  if (!(ddz_1.amplitude > 0.0)) return kNaN;
  const double nu = 2.0 * M_PI * f, F0 = c.roller.static_moment * nu * nu;
  return c.roller.m * nu * nu - c.roller.kd -
         F0 * nu * nu * std::cos(phi_u - ddz_1.phase) / ddz_1.amplitude;
}

std::string record_kb(std::vector<RecordWindow>& windows, std::span<const double> t,
                      std::span<const double> alpha, const Case* c) {
  std::string why;
  if (c == nullptr)
    why =
        "no roller: give the vibratory drum's case (--case) for its mass, buffers and static "
        "moment";
  else if (c->roller.type != RollerType::vibratory)
    why =
        "the case's roller is the oscillation drum: kb reads the unbalance force of "
        "roller.type = \"vibratory\"";
  else if (alpha.empty())
    why =
        "the record has no unbalance angle (--unbalance-col): without the exciter's phase the "
        "contact force is unknown";
  else if (alpha.size() != t.size())
    throw Error("record_kb: the unbalance angle has " + std::to_string(alpha.size()) +
                " samples and t " + std::to_string(t.size()) + "; expected the same number");
  for (RecordWindow& w : windows) {
    w.metrics.kb = kNaN;
    if (!why.empty() || !w.valid || w.metrics.ddz_harmonics.size() < 2) continue;
    const double phi_u =
        unbalance_phase(t.subspan(w.first, w.count), alpha.subspan(w.first, w.count), w.f);
    w.metrics.kb = record_soil_stiffness(*c, w.metrics.ddz_harmonics[1], w.f, phi_u);
  }
  return why;
}

}  // namespace oscidrum
