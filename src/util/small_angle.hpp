// Internal: sin and cos of a small angle, the contact angle delta of the trough kinematics
// (paper (15)-(16), (46)-(50)) evaluated in every right-hand side. The drum's contact point stays
// within a few degrees of the trough's bottom, where the Taylor series converge fast: through
// x^13 (sin) and x^14 (cos) the first omitted terms are below 5e-17 relative for |x| <= 0.5, half
// an ulp, at a fraction of the cost of libm's general sincos (which a profile of a study found
// taking a tenth of its time). Larger angles go to libm.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "util/lanes.hpp"

namespace oscidrum::detail {

struct SinCos {
  double sin, cos;
};

/// The series of sincos_small for |x| <= 0.5, for T double or lanes of doubles (util/lanes.hpp).
template <class T>
inline void sincos_small_series(const T& x, T& sin_x, T& cos_x) {
  const T x2 = x * x;
  // sin x = x (1 - x^2/3! + x^4/5! - ... - x^12/13!), cos x = 1 - x^2/2! + ... + x^14/14!.
  constexpr double s3 = -1.0 / 6.0, s5 = 1.0 / 120.0, s7 = -1.0 / 5040.0, s9 = 1.0 / 362880.0,
                   s11 = -1.0 / 39916800.0, s13 = 1.0 / 6227020800.0;
  constexpr double c2 = -0.5, c4 = 1.0 / 24.0, c6 = -1.0 / 720.0, c8 = 1.0 / 40320.0,
                   c10 = -1.0 / 3628800.0, c12 = 1.0 / 479001600.0, c14 = -1.0 / 87178291200.0;
  // Estrin's scheme (pairs of terms in x^2, then in x^4): a shorter chain of dependent
  // operations than Horner's, on a machine without fused multiply-adds.
  const T x4 = x2 * x2;
  const T ps = (s3 + x2 * s5) + x4 * ((s7 + x2 * s9) + x4 * (s11 + x2 * s13));
  const T pc = (c2 + x2 * c4) + x4 * ((c6 + x2 * c8) + x4 * ((c10 + x2 * c12) + x4 * c14));
  sin_x = x + x * x2 * ps;
  cos_x = 1.0 + x2 * pc;
}

inline SinCos sincos_small(double x) {
  if (!(std::abs(x) <= 0.5)) return {std::sin(x), std::cos(x)};
  SinCos r;
  sincos_small_series(x, r.sin, r.cos);
  return r;
}

/// sincos_small in every lane: the series in all lanes at once where every |x| <= 0.5.
template <int N>
inline void sincos_small(const Lanes<N>& x, Lanes<N>& sin_x, Lanes<N>& cos_x) {
  bool small = true;
  for (int j = 0; j < N; ++j) small = small && std::abs(x[j]) <= 0.5;
  if (small) return sincos_small_series(x, sin_x, cos_x);
  for (int j = 0; j < N; ++j) {
    const SinCos r = sincos_small(x[j]);
    sin_x[j] = r.sin;
    cos_x[j] = r.cos;
  }
}

/// std::nearbyint(x) in the default rounding mode (to nearest, ties to even), without libm's call
/// (which saves and restores the floating-point environment: two calls per evaluation of the
/// excitation were 4 % of a study's time). Adding and subtracting 1.5 * 2^52 rounds |x| < 2^51 to
/// an integer as the hardware rounds the sum; larger values (already integers) and nan go to
/// libm. Only the sign of a zero result may differ from nearbyint's (-0.3 gives +0).
inline double round_to_integer(double x) {
  constexpr double kShift = 6755399441055744.0;                       // 1.5 * 2^52
  if (!(std::abs(x) < 2251799813685248.0)) return std::nearbyint(x);  // 2^51
  return (x + kShift) - kShift;
}

namespace turns_series {

/// A turn reduced exactly (see sincos_turns): 2 pi turns = q pi/2 + x, q in {-2, ..., 2}, |x| <=
/// pi/4.
struct Reduced {
  double x, q;
};
inline Reduced reduce(double turns) {
  const double frac = turns - round_to_integer(turns);               // [-1/2, 1/2], exact
  const double quarters = 4.0 * frac;                                // exact
  const double q = round_to_integer(quarters);                       // -2 ... 2
  const double x = (quarters - q) * (0.5 * 3.14159265358979323846);  // |x| <= pi/4
  return {x, q};
}
/// sin x and cos x on |x| <= pi/4 by the series through x^17 and x^16 (Estrin's scheme); T is
/// double or lanes of doubles (util/lanes.hpp), the same operations in each lane.
template <class T>
inline T sin_series(const T& x) {
  const T x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  constexpr double s3 = -1.0 / 6.0, s5 = 1.0 / 120.0, s7 = -1.0 / 5040.0, s9 = 1.0 / 362880.0,
                   s11 = -1.0 / 39916800.0, s13 = 1.0 / 6227020800.0, s15 = -1.0 / 1307674368000.0,
                   s17 = 1.0 / 355687428096000.0;
  const T ps =
      (s3 + x2 * s5) + x4 * (s7 + x2 * s9) + x8 * ((s11 + x2 * s13) + x4 * (s15 + x2 * s17));
  return x + x * x2 * ps;
}
template <class T>
inline T cos_series(const T& x) {
  const T x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  constexpr double c2 = -0.5, c4 = 1.0 / 24.0, c6 = -1.0 / 720.0, c8 = 1.0 / 40320.0,
                   c10 = -1.0 / 3628800.0, c12 = 1.0 / 479001600.0, c14 = -1.0 / 87178291200.0,
                   c16 = 1.0 / 20922789888000.0;
  const T pc =
      (c2 + x2 * c4) + x4 * (c6 + x2 * c8) + x8 * ((c10 + x2 * c12) + x4 * (c14 + x2 * c16));
  return 1.0 + x2 * pc;
}

}  // namespace turns_series

/// sin and cos of 2 pi `turns` for any `turns`: reduced exactly to a quarter turn about the nearest
/// multiple of a quarter (turns - round(turns) and 4 turns - q are exact in floating point), then
/// the series on |x| <= pi/4 (through x^17 and x^16: the first omitted terms below 1e-19). The
/// excitation's phase nu t = 2 pi f t taken in turns, f t, so that no general range reduction of a
/// large angle is needed (libm's sin was 7 % of a study's case); within about an ulp of the angle's
/// sine and cosine.
inline SinCos sincos_turns(double turns) {
  const auto [x, q] = turns_series::reduce(turns);
  const double s = turns_series::sin_series(x), c = turns_series::cos_series(x);
  // 2 pi turns = q pi/2 + x.
  switch (static_cast<int>(q)) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case -1:
      return {-c, s};
    default:
      return {-s, -c};  // +-2: half a turn
  }
}

/// sin(2 pi turns) alone, the same bits as sincos_turns(turns).sin: one series of the two (the
/// excitation's moment, evaluated in every right-hand side, needs no cosine).
inline double sin_turns(double turns) {
  const auto [x, q] = turns_series::reduce(turns);
  switch (static_cast<int>(q)) {
    case 0:
      return turns_series::sin_series(x);
    case 1:
      return turns_series::cos_series(x);
    case -1:
      return -turns_series::cos_series(x);
    default:
      return -turns_series::sin_series(x);  // +-2: half a turn
  }
}

/// cos(2 pi k turns) and sin(2 pi k turns), k = 0 ... m, into c[0 ... m] and s[0 ... m]: the
/// fundamental by sincos_turns, its multiples by angle addition (the rounding grows about linearly
/// with k, some 1e-15 at k = 20). The harmonic fits of records and their fitted waveforms; the
/// phase in turns (f t) needs no range reduction of a large angle (libm's sincos of nu t was a
/// seventh of an identification window).
inline void harmonics_turns(double turns, int m, double* c, double* s) {
  const SinCos one = sincos_turns(turns);
  c[0] = 1.0;
  s[0] = 0.0;
  for (int k = 1; k <= m; ++k) {
    c[k] = c[k - 1] * one.cos - s[k - 1] * one.sin;
    s[k] = s[k - 1] * one.cos + c[k - 1] * one.sin;
  }
}

/// cos(2 pi k f (t_i - t_ref)) and sin(...), k = 0 ... m, of the samples t_i visited in order
/// (at(0), at(1), ...): the values of harmonics_turns bit for bit, made for kLanes samples at a
/// time as the first of them is visited, so that their chains of dependent angle additions (up to
/// 2 m steps each) overlap rather than leave the processor waiting for one.
class HarmonicsInOrder {
 public:
  static constexpr std::size_t kLanes = 4;
  HarmonicsInOrder(std::span<const double> t, double t_ref, double f, int m)
      : t_(t),
        t_ref_(t_ref),
        f_(f),
        m_(m),
        c_(kLanes * static_cast<std::size_t>(m + 1)),
        s_(c_.size()) {}
  /// Sample i; every sample from 0 on, in increasing order.
  void at(std::size_t i) {
    b_ = i % kLanes;
    if (b_ != 0) return;
    const std::size_t count = std::min(kLanes, t_.size() - i);
    double c1[kLanes] = {}, s1[kLanes] = {};
    for (std::size_t b = 0; b < count; ++b) {
      const SinCos one = sincos_turns(f_ * (t_[i + b] - t_ref_));
      c1[b] = one.cos;
      s1[b] = one.sin;
      c_[b] = 1.0;
      s_[b] = 0.0;
    }
    for (int k = 1; k <= m_; ++k) {
      const std::size_t j = static_cast<std::size_t>(k) * kLanes, p = j - kLanes;
      for (std::size_t b = 0; b < count; ++b) {
        c_[j + b] = c_[p + b] * c1[b] - s_[p + b] * s1[b];
        s_[j + b] = s_[p + b] * c1[b] + c_[p + b] * s1[b];
      }
    }
  }
  double cos(int k) const { return c_[static_cast<std::size_t>(k) * kLanes + b_]; }
  double sin(int k) const { return s_[static_cast<std::size_t>(k) * kLanes + b_]; }

 private:
  std::span<const double> t_;
  double t_ref_, f_;
  int m_;
  std::vector<double> c_, s_;
  std::size_t b_ = 0;
};

}  // namespace oscidrum::detail
