// test_small_angle.cpp: sin and cos of the contact angle by their Taylor series
// (src/util/small_angle.hpp) against libm: within one ulp (plus libm's own half ulp) over the
// series' range, libm's own values beyond it, and exact where both are exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/small_angle.hpp"

namespace oscidrum {
namespace {

TEST(SmallAngle, WithinAnUlpOfLibmOverItsRange) {
  const int n = 200001;
  double worst_sin = 0.0, worst_cos = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = -0.5 + 1.0 * i / (n - 1);
    const auto [s, c] = detail::sincos_small(x);
    const double es = std::sin(x), ec = std::cos(x);
    // In units of the ulp of the exact value.
    if (es != 0.0)
      worst_sin = std::max(worst_sin,
                           std::abs(s - es) / (std::nextafter(std::abs(es), 1.0) - std::abs(es)));
    else
      EXPECT_EQ(s, 0.0);
    worst_cos = std::max(worst_cos, std::abs(c - ec) / (std::nextafter(ec, 2.0) - ec));
  }
  EXPECT_LE(worst_sin, 1.0);
  EXPECT_LE(worst_cos, 1.0);
  // Tiny angles: sin x = x, cos x = 1 in double precision.
  for (const double x : {1e-300, -1e-200, 1e-9, -3e-9}) {
    EXPECT_EQ(detail::sincos_small(x).sin, x);
    EXPECT_EQ(detail::sincos_small(x).cos, 1.0);
  }
}

TEST(SmallAngle, LibmBeyondTheSeriesRange) {
  for (const double x : {0.5000001, -0.75, 2.0, -100.0, 1e6}) {
    EXPECT_EQ(detail::sincos_small(x).sin, std::sin(x));
    EXPECT_EQ(detail::sincos_small(x).cos, std::cos(x));
  }
  EXPECT_TRUE(std::isnan(detail::sincos_small(std::numeric_limits<double>::quiet_NaN()).sin));
}

// sin and cos of 2 pi c by the reduction in turns: against libm where 2 pi c is computed without
// rounding that matters (|c| < 1: within two ulps of the value, plus the ulp of the angle times
// the derivative), exact at the quarter turns, and periodic to the last bit where c + k is exact.
TEST(SmallAngle, TurnsAgreeWithLibmAndArePeriodic) {
  const double pi = 3.14159265358979323846;
  double worst = 0.0;
  for (int i = -100000; i <= 100000; ++i) {
    const double c = 0.99999 * i / 100000.0;
    const auto [s, co] = detail::sincos_turns(c);
    const double angle = 2.0 * pi * c;
    const double slack = std::abs(angle) * 2.3e-16;  // the rounding of 2 pi c for libm
    const double ulp_s = std::nextafter(std::abs(std::sin(angle)), 2.0) - std::abs(std::sin(angle));
    const double ulp_c = std::nextafter(std::abs(std::cos(angle)), 2.0) - std::abs(std::cos(angle));
    worst = std::max(worst, std::abs(s - std::sin(angle)) / (2.0 * ulp_s + slack));
    worst = std::max(worst, std::abs(co - std::cos(angle)) / (2.0 * ulp_c + slack));
  }
  EXPECT_LE(worst, 1.0);
  // Quarter turns exactly; an eighth turn as sqrt(1/2).
  EXPECT_EQ(detail::sincos_turns(0.25).sin, 1.0);
  EXPECT_EQ(detail::sincos_turns(0.25).cos, 0.0);
  EXPECT_EQ(detail::sincos_turns(-0.25).sin, -1.0);
  EXPECT_EQ(detail::sincos_turns(0.5).cos, -1.0);
  EXPECT_EQ(detail::sincos_turns(0.0).sin, 0.0);
  EXPECT_NEAR(detail::sincos_turns(0.125).sin, std::sqrt(0.5), 1.2e-16);
  // Periodic: c + k exact (c a short binary fraction).
  for (const double c : {0.1875, -0.40625, 0.015625, 0.3671875})
    for (const double k : {1.0, -3.0, 1000.0, 123456.0}) {
      EXPECT_EQ(detail::sincos_turns(c + k).sin, detail::sincos_turns(c).sin);
      EXPECT_EQ(detail::sincos_turns(c + k).cos, detail::sincos_turns(c).cos);
    }
}

TEST(SmallAngle, LanesGiveTheSameBitsAsOneAngle) {
  // sincos_small in lanes: the series in every lane where all angles are in its range, libm in
  // each lane where one is not (0.7 below), the same bits as one angle at a time.
  for (const double spread : {0.45, 0.7}) {
    detail::Lanes<8> x, s, c;
    for (int j = 0; j < 8; ++j) x[j] = spread * (j - 3.5) / 3.5 + 1e-3 * j;
    detail::sincos_small(x, s, c);
    for (int j = 0; j < 8; ++j) {
      const detail::SinCos one = detail::sincos_small(x[j]);
      EXPECT_TRUE(one.sin == s[j] && std::signbit(one.sin) == std::signbit(s[j])) << x[j];
      EXPECT_TRUE(one.cos == c[j] && std::signbit(one.cos) == std::signbit(c[j])) << x[j];
    }
  }
}

TEST(SmallAngle, SineInTurnsAloneIsSincosTurnsSine) {
  // The excitation's moment takes sin_turns: the same bits as sincos_turns' sine in every
  // quarter (each quarter picks the sine or the cosine series), at the quarter points and for
  // phases of many periods.
  for (int i = -200000; i <= 200000; ++i) {
    const double c = 1.37 * i / 100000.0;  // about -2.7 ... 2.7 turns, every quarter
    const double a = detail::sin_turns(c), b = detail::sincos_turns(c).sin;
    ASSERT_TRUE(a == b && std::signbit(a) == std::signbit(b)) << c << ": " << a << " " << b;
  }
  for (const double c : {0.0, 0.25, -0.25, 0.5, -0.5, 0.75, 1e6 + 0.3, -4.0e5 - 0.1}) {
    EXPECT_EQ(detail::sin_turns(c), detail::sincos_turns(c).sin) << c;
  }
}

TEST(SmallAngle, RoundingToAnIntegerIsNearbyint) {
  // Ties to even, both signs, the halves, values beyond 2^51 and the largest; only a zero's sign
  // may differ (nearbyint(-0.3) = -0, here +0).
  const double big = 2251799813685248.0;  // 2^51
  for (const double x :
       {0.5, 1.5, 2.5, -0.5, -1.5, -2.5, 0.49999999999999994, 1e6 + 0.5, 1e6 + 1.5, -7.25, 3.75,
        big - 0.5, big, big + 1.0, -big + 0.5, 1e300, -1e300, std::numeric_limits<double>::max()}) {
    EXPECT_EQ(detail::round_to_integer(x), std::nearbyint(x)) << x;
  }
  for (int i = -400000; i <= 400000; ++i) {
    const double x = i / 1024.0 + (i % 7) * 1e-12;
    const double r = detail::round_to_integer(x), n = std::nearbyint(x);
    ASSERT_EQ(r, n) << x;  // == ignores the sign of zero
  }
  EXPECT_TRUE(std::isnan(detail::round_to_integer(std::nan(""))));
  EXPECT_EQ(detail::round_to_integer(std::numeric_limits<double>::infinity()),
            std::numeric_limits<double>::infinity());
}

TEST(SmallAngle, HarmonicsInTurnsAgreeWithLibm) {
  // cos and sin of 2 pi k x, k = 0 ... 20, against libm's of the angle: within (k + 1) 1e-16
  // (the angle addition's rounding grows about linearly with k); periodic in whole turns.
  constexpr int m = 20;
  double c[m + 1], s[m + 1], c2[m + 1], s2[m + 1];
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double x = (i - 1000) / 2048.0;  // short binary fractions in [-0.49, 0.49]
    detail::harmonics_turns(x, m, c, s);
    for (int k = 0; k <= m; ++k) {
      const double angle = 2.0 * 3.14159265358979323846 * k * x;
      const double slack = std::abs(angle) * 2.3e-16;  // the rounding of the angle for libm
      const double tol = (k + 1) * 1e-16 + slack;
      worst = std::max(worst, std::abs(c[k] - std::cos(angle)) / tol);
      worst = std::max(worst, std::abs(s[k] - std::sin(angle)) / tol);
    }
    detail::harmonics_turns(x + 4096.0, m, c2, s2);  // x + 4096 is exact for these x
    for (int k = 0; k <= m; ++k) {
      EXPECT_EQ(c2[k], c[k]);
      EXPECT_EQ(s2[k], s[k]);
    }
  }
  EXPECT_LE(worst, 1.0);
  detail::harmonics_turns(0.25, 4, c, s);  // a quarter turn: 0, 1, 0, -1, 0 (sines) to rounding
  EXPECT_EQ(s[1], 1.0);
  EXPECT_NEAR(s[2], 0.0, 1e-16);
  EXPECT_NEAR(s[3], -1.0, 1e-16);
  EXPECT_NEAR(c[4], 1.0, 1e-16);
}

}  // namespace
}  // namespace oscidrum
