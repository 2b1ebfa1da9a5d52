// Tests of the circular trough (src/physics/trough_circle.cpp): the checks of every shape
// (trough_checks.hpp), its closed forms, its check against the drum radius and what it says of
// itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "oscidrum/kinematics.hpp"
#include "tolerances.hpp"
#include "trough_checks.hpp"

namespace oscidrum {
namespace {

using test::deltas;
using test::kDrumRadius;
using test::kIdentity;

constexpr double kR = kDrumRadius;

TEST(CircleTrough, PassesTheChecksOfEveryShape) {
  for (double R : {0.603, 0.606, 0.62, 0.65})
    test::expect_a_valid_shape(CircleTrough{R}, "circle R = " + std::to_string(R));
}

TEST(CircleTrough, ClosedForms) {
  for (double R : {0.603, 0.606, 0.62, 0.65}) {
    const CircleTrough circle{R};
    for (double d : deltas()) {
      const Kinematics q = kinematics(circle, kR, d);
      const double tol = kIdentity * kR;
      EXPECT_NEAR(q.x_roll, (R - kR) * std::sin(d), tol) << R << " " << d;
      EXPECT_NEAR(q.z_roll, -(R - kR) * (1.0 - std::cos(d)), tol) << R << " " << d;  // rises
      EXPECT_NEAR(q.f1, (R - kR) * std::cos(d), tol);
      EXPECT_NEAR(q.f2, -(R - kR) * std::sin(d), tol);
      EXPECT_NEAR(q.f3, -(R - kR) * std::sin(d), tol);
      EXPECT_NEAR(q.f4, -(R - kR) * std::cos(d), tol);
      EXPECT_NEAR(q.f5, (R - kR) / kR, kIdentity);
      EXPECT_EQ(q.f6, 0.0);
      EXPECT_NEAR(phi_rolling(circle, kR, d), (R - kR) * d / kR, kIdentity);  // (11), k -> 0
      const KinematicsRates rates = kinematics_rates(circle, kR, d);
      EXPECT_NEAR(rates.df2, -(R - kR) * std::cos(d), tol);
      EXPECT_NEAR(rates.df4, (R - kR) * std::sin(d), tol);
      EXPECT_EQ(rates.df6, 0.0);
    }
  }
}

// The contact point C = M + r (sin delta, cos delta) (z down) stays on the trough: the circle of
// radius R about the trough's centre (0, r - R).
TEST(CircleTrough, ContactPointLiesOnTheCircle) {
  const double R = 0.606;
  for (double d : deltas()) {
    const Kinematics q = kinematics(CircleTrough{R}, kR, d);
    const double cx = q.x_roll + kR * std::sin(d), cz = q.z_roll + kR * std::cos(d);
    EXPECT_NEAR(std::hypot(cx, cz - (kR - R)), R, kIdentity * kR) << d;
  }
}

TEST(CircleTrough, MustBeLargerThanTheDrum) {
  EXPECT_EQ(curvature_radius_at_bottom(CircleTrough{0.606}), 0.606);
  EXPECT_EQ(fit_problem(CircleTrough{0.606}, kR).message, "");
  EXPECT_EQ(fit_problem(CircleTrough{0.603}, kR).message, "");  // the paper's smallest R
  for (double R : {0.6, 0.59}) {                                // R = r, R < r
    const FitProblem p = fit_problem(CircleTrough{R}, kR);
    EXPECT_NE(p.message.find("trough.a must be > roller.r"), std::string::npos) << p.message;
    EXPECT_EQ(std::string(p.key), "trough.a");
  }
}

TEST(CircleTrough, DescribesItself) {
  const CircleTrough circle{0.62};
  EXPECT_EQ(std::string(CircleTrough::name), "circle");
  EXPECT_EQ(summary(circle), "circle, R = 0.62 m");
  ASSERT_EQ(parameters(circle).size(), 1u);
  EXPECT_EQ(std::string(parameters(circle)[0].symbol), "R");
  EXPECT_EQ(parameters(circle)[0].value, 0.62);
  // The case keys: the circle is the spiral family's k = 0 with a = R.
  EXPECT_EQ(key_value(circle, "trough.k"), 0.0);
  EXPECT_EQ(key_value(circle, "trough.a"), 0.62);
  EXPECT_EQ(std::string(curvature_radius_formula(circle)), "trough.a");
}

}  // namespace
}  // namespace oscidrum
