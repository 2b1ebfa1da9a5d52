// test_small_angle.cpp: sin and cos of the contact angle by their Taylor series
// (src/util/small_angle.hpp) against libm: within one ulp (plus libm's own half ulp) over the
// series' range, libm's own values beyond it, and exact where both are exact.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace oscidrum
