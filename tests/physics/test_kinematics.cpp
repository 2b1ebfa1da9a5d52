// Tests of the kinematics (src/physics/kinematics.cpp): the functions on a TroughGeometry give
// the held shape's own formulas (each shape's are tested in tests/physics/test_trough_<name>.cpp),
// and the circle and the spiral join continuously as k -> 0.
#include <gtest/gtest.h>

#include <cmath>
#include <variant>

#include "oscidrum/kinematics.hpp"
#include "tolerances.hpp"
#include "trough_checks.hpp"

namespace oscidrum {
namespace {

using test::deltas;
using test::kDrumRadius;

constexpr double kR = kDrumRadius;

TEST(Kinematics, GeometryHoldsTheShapeTheKeysDescribe) {
  const TroughGeometry c = make_trough_geometry(kR, 0.0, 0.606);
  EXPECT_EQ(c.r, kR);
  ASSERT_TRUE(std::holds_alternative<CircleTrough>(c.shape));
  EXPECT_EQ(std::get<CircleTrough>(c.shape).R, 0.606);
  const TroughGeometry s = make_trough_geometry(kR, 0.05, 0.65);
  ASSERT_TRUE(std::holds_alternative<LogSpiralTrough>(s.shape));
  EXPECT_EQ(std::get<LogSpiralTrough>(s.shape), LogSpiralTrough(0.05, 0.65));
}

// Bit for bit what the shape's own functions give (the dispatch adds no arithmetic).
TEST(Kinematics, DispatchesToTheShapesFormulas) {
  const CircleTrough circle{0.606};
  const LogSpiralTrough spiral(0.002, 0.601);
  const TroughGeometry gc{circle, kR}, gs{spiral, kR};
  for (double d : deltas()) {
    EXPECT_EQ(kinematics(gc, d).f2_bar, kinematics(circle, kR, d).f2_bar);
    EXPECT_EQ(kinematics(gs, d).f2_bar, kinematics(spiral, kR, d).f2_bar);
    EXPECT_EQ(kinematics(gs, d).x_roll, kinematics(spiral, kR, d).x_roll);
    EXPECT_EQ(kinematics_rates(gc, d).df2, kinematics_rates(circle, kR, d).df2);
    EXPECT_EQ(kinematics_rates(gs, d).df6, kinematics_rates(spiral, kR, d).df6);
    EXPECT_EQ(phi_rolling(gc, d), phi_rolling(circle, kR, d));
    EXPECT_EQ(phi_rolling(gs, d), phi_rolling(spiral, kR, d));
  }
}

// k -> 0 is continuous: k = 1e-9 differs from k = 0 by O(k) (here |delta| <= 0.5, so the
// difference in every quantity is below ~ k r = 6e-10 m, or ~ k for f5, f6, phi).
TEST(Kinematics, ContinuousAsKGoesToZero) {
  const double k = 1e-9;
  const TroughGeometry g0 = make_trough_geometry(kR, 0.0, 0.606);
  const TroughGeometry gk = make_trough_geometry(kR, k, 0.606);
  ASSERT_TRUE(std::holds_alternative<CircleTrough>(g0.shape));
  ASSERT_TRUE(std::holds_alternative<LogSpiralTrough>(gk.shape));
  for (double d : deltas()) {
    const Kinematics a = kinematics(g0, d), b = kinematics(gk, d);
    const double tol = 10.0 * k;
    EXPECT_NEAR(a.x_roll, b.x_roll, tol * kR) << d;
    EXPECT_NEAR(a.z_roll, b.z_roll, tol * kR) << d;
    EXPECT_NEAR(a.f1, b.f1, tol * kR) << d;
    EXPECT_NEAR(a.f2, b.f2, tol * kR) << d;
    EXPECT_NEAR(a.f3, b.f3, tol * kR) << d;
    EXPECT_NEAR(a.f4, b.f4, tol * kR) << d;
    EXPECT_NEAR(a.f5, b.f5, tol) << d;
    EXPECT_NEAR(a.f6, b.f6, tol) << d;
    EXPECT_NEAR(phi_rolling(g0, d), phi_rolling(gk, d), tol) << d;
  }
}

}  // namespace
}  // namespace oscidrum
