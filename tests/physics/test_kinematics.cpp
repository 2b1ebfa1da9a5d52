// Tests of the trough kinematics (docs/model.md section 2): (15)-(16), their derivatives f1 ... f6
// (46)-(50) by finite differences, the exact identities of section 3, the circle's closed forms,
// and the rolling condition (11)-(12).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "oscidrum/kinematics.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

using test::kFiniteDifference;
using test::kIdentity;

constexpr double kR = 0.6;   // drum radius [m]
constexpr double kH = 1e-5;  // finite-difference step in delta [rad]

struct Shape {
  const char* name;
  double k, a;
};
// The paper's circle, the paper's spiral (trough-shape study) and a strongly curved spiral.
const std::vector<Shape> kShapes = {
    {"circle", 0.0, 0.606}, {"spiral k = 0.002", 0.002, 0.601}, {"spiral k = 0.05", 0.05, 0.65}};

std::vector<double> deltas() {
  std::vector<double> d;
  for (int i = -20; i <= 20; ++i) d.push_back(0.025 * i);  // [-0.5, 0.5]
  d.push_back(0.1234567);
  d.push_back(-0.3141);
  return d;
}

template <class F>
double central_difference(F f, double x) {
  return (f(x + kH) - f(x - kH)) / (2.0 * kH);
}

// The finite differences of quantities built from terms of size ~ r (lengths) or ~ R0 / r ~ 1
// (f5): the tolerance is relative to that scale, not to the (possibly tiny, ~ (R - r)) result.
TEST(Kinematics, DerivativesMatchFiniteDifferences) {
  for (const Shape& s : kShapes) {
    const TroughGeometry g = make_trough_geometry(kR, s.k, s.a);
    auto at = [&](double d) { return kinematics(g, d); };
    const double len = kFiniteDifference * kR;  // lengths [m]
    const double one = kFiniteDifference;       // dimensionless (f5, f6)
    for (double d : deltas()) {
      const Kinematics q = at(d);
      EXPECT_NEAR(q.f1, central_difference([&](double x) { return at(x).x_roll; }, d), len)
          << s.name << " delta = " << d;
      EXPECT_NEAR(q.f2, central_difference([&](double x) { return at(x).f1; }, d), len)
          << s.name << " delta = " << d;
      EXPECT_NEAR(q.f3, central_difference([&](double x) { return at(x).z_roll; }, d), len)
          << s.name << " delta = " << d;
      EXPECT_NEAR(q.f4, central_difference([&](double x) { return at(x).f3; }, d), len)
          << s.name << " delta = " << d;
      EXPECT_NEAR(q.f6, central_difference([&](double x) { return at(x).f5; }, d), one)
          << s.name << " delta = " << d;
      // Rolling condition (12): d phi_rolling / d delta = f5.
      EXPECT_NEAR(q.f5, central_difference([&](double x) { return phi_rolling(g, x); }, d), one)
          << s.name << " delta = " << d;
    }
  }
}

TEST(Kinematics, StartsAtTheBottom) {
  for (const Shape& s : kShapes) {
    const TroughGeometry g = make_trough_geometry(kR, s.k, s.a);
    const Kinematics q = kinematics(g, 0.0);
    EXPECT_NEAR(q.x_roll, 0.0, kIdentity * kR) << s.name;
    EXPECT_NEAR(q.z_roll, 0.0, kIdentity * kR) << s.name;
    EXPECT_EQ(phi_rolling(g, 0.0), 0.0) << s.name;
    EXPECT_EQ(q.sin_delta, 0.0);
    EXPECT_EQ(q.cos_delta, 1.0);
    // At the bottom the centre moves horizontally only, at rate sqrt(1+k^2) R0 - r = r f5.
    EXPECT_NEAR(q.f1, kR * q.f5, kIdentity * kR) << s.name;
    EXPECT_NEAR(q.f3, 0.0, kIdentity * kR) << s.name;
  }
}

TEST(Kinematics, Geometry) {
  const TroughGeometry c = make_trough_geometry(kR, 0.0, 0.606);
  EXPECT_NEAR(c.alpha, M_PI / 2.0, kIdentity);  // (8) k = 0: alpha = pi/2, R0 = a
  EXPECT_EQ(c.R0, 0.606);
  EXPECT_EQ(c.r, kR);
  for (double k : {0.002, 0.05}) {
    const TroughGeometry g = make_trough_geometry(kR, k, 0.6);
    EXPECT_NEAR(g.alpha, std::atan(1.0 / k), kIdentity);
    EXPECT_NEAR(g.R0, 0.6 * std::exp(k * (M_PI - std::atan(1.0 / k))), kIdentity);
  }
}

// docs/model.md section 2: f3~ == 0 (the centre moves tangentially to the trough), f1_bar == r f5,
// f4~ == -f1_bar; and the shorthands are what (33) and (37) define.
TEST(Kinematics, ExactIdentities) {
  for (const Shape& s : kShapes) {
    const TroughGeometry g = make_trough_geometry(kR, s.k, s.a);
    for (double d : deltas()) {
      const Kinematics q = kinematics(g, d);
      const double tol = kIdentity * kR;
      EXPECT_NEAR(q.sin_delta, std::sin(d), kIdentity);
      EXPECT_NEAR(q.cos_delta, std::cos(d), kIdentity);
      const double sn = std::sin(d), cs = std::cos(d);
      EXPECT_NEAR(q.f1_bar, q.f1 * cs - q.f3 * sn, tol);  // (33)
      EXPECT_NEAR(q.f2_bar, q.f2 * cs - q.f4 * sn, tol);
      EXPECT_NEAR(q.f3_tilde, q.f1 * sn + q.f3 * cs, tol);  // (37)
      EXPECT_NEAR(q.f4_tilde, q.f2 * sn + q.f4 * cs, tol);
      EXPECT_NEAR(q.f3_tilde, 0.0, tol) << s.name << " delta = " << d;
      EXPECT_NEAR(q.f1_bar, kR * q.f5, tol) << s.name << " delta = " << d;
      EXPECT_NEAR(q.f4_tilde, -q.f1_bar, tol) << s.name << " delta = " << d;
      // Differentiating f1_bar = r f5: f2_bar - f4 ... gives f2_bar = r f6 (d/d delta of (33)
      // uses f3~ = 0).
      EXPECT_NEAR(q.f2_bar, kR * q.f6, tol) << s.name << " delta = " << d;
    }
  }
}

// The contact point C = M + r (sin delta, cos delta) (z down) traces the trough: a log spiral
// about a fixed pole, of radius R0 exp(-k delta), whose tangent is perpendicular to the drum's
// radius MC. This checks (15)-(16) against the spiral (8) itself.
TEST(Kinematics, ContactPointLiesOnTheSpiral) {
  for (const Shape& s : kShapes) {
    const TroughGeometry g = make_trough_geometry(kR, s.k, s.a);
    // Pole P from the bottom point C(0) = (0, r): it lies at distance R0 along the direction
    // that makes angle alpha with the tangent (the log spiral's constant angle).
    const double px = g.R0 * std::cos(g.alpha), pz = kR - g.R0 * std::sin(g.alpha);
    for (double d : deltas()) {
      const Kinematics q = kinematics(g, d);
      const double cx = q.x_roll + kR * std::sin(d), cz = q.z_roll + kR * std::cos(d);
      EXPECT_NEAR(std::hypot(cx - px, cz - pz), g.R0 * std::exp(-s.k * d), kIdentity * kR)
          << s.name << " delta = " << d;
    }
  }
}

// The trough as a component (oscidrum/trough.hpp): k = 0 is the circle of radius a, k > 0 the
// spiral; each owns its curvature at the bottom and its check against the drum radius.
TEST(Trough, ShapeComponentsAndTheirChecks) {
  const TroughShape circle = trough_shape(0.0, 0.606);
  ASSERT_TRUE(std::holds_alternative<CircleTrough>(circle));
  EXPECT_EQ(std::get<CircleTrough>(circle).R, 0.606);
  EXPECT_EQ(curvature_radius_at_bottom(circle), 0.606);
  EXPECT_TRUE(std::holds_alternative<CircleTrough>(make_trough_geometry(kR, 0.0, 0.606).shape));
  const TroughShape spiral = trough_shape(0.05, 0.65);
  ASSERT_TRUE(std::holds_alternative<LogSpiralTrough>(spiral));
  const TroughGeometry g = make_trough_geometry(kR, 0.05, 0.65);
  EXPECT_TRUE(std::holds_alternative<LogSpiralTrough>(g.shape));
  // Curvature radius of the spiral at the bottom: sqrt(1 + k^2) R0 = r (1 + f5(0)) by (50).
  EXPECT_NEAR(curvature_radius_at_bottom(spiral), kR * (1.0 + kinematics(g, 0.0).f5),
              kIdentity * kR);
  EXPECT_EQ(trough_problem(circle, kR), "");
  EXPECT_EQ(trough_problem(spiral, kR), "");
  EXPECT_NE(trough_problem(trough_shape(0.0, 0.6), kR).find("trough.a must be > roller.r"),
            std::string::npos);
  // A spiral whose bottom is tighter than the drum: sqrt(1 + k^2) a exp(k (pi - atan(1/k))) =
  // 0.155 m < r.
  EXPECT_NE(trough_problem(trough_shape(0.5, 0.05), kR).find("curvature radius"),
            std::string::npos);
}

TEST(Kinematics, CircleClosedForms) {
  for (double R : {0.603, 0.606, 0.62, 0.65}) {
    const TroughGeometry g = make_trough_geometry(kR, 0.0, R);
    for (double d : deltas()) {
      const Kinematics q = kinematics(g, d);
      const double tol = kIdentity * kR;
      EXPECT_NEAR(q.x_roll, (R - kR) * std::sin(d), tol) << R << " " << d;
      EXPECT_NEAR(q.z_roll, -(R - kR) * (1.0 - std::cos(d)), tol) << R << " " << d;  // rises
      EXPECT_NEAR(q.f1, (R - kR) * std::cos(d), tol);
      EXPECT_NEAR(q.f2, -(R - kR) * std::sin(d), tol);
      EXPECT_NEAR(q.f3, -(R - kR) * std::sin(d), tol);
      EXPECT_NEAR(q.f4, -(R - kR) * std::cos(d), tol);
      EXPECT_NEAR(q.f5, (R - kR) / kR, kIdentity);
      EXPECT_EQ(q.f6, 0.0);
      EXPECT_NEAR(phi_rolling(g, d), (R - kR) * d / kR, kIdentity);  // (11), k -> 0
    }
  }
}

// phi_rolling (11): the closed form for k > 0, checked here directly.
TEST(Kinematics, RollingConditionClosedForm) {
  for (const Shape& s : kShapes) {
    if (s.k == 0.0) continue;
    const TroughGeometry g = make_trough_geometry(kR, s.k, s.a);
    for (double d : deltas()) {
      const double phi =
          std::sqrt(1.0 + s.k * s.k) / (s.k * kR) * g.R0 * (1.0 - std::exp(-s.k * d)) - d;
      EXPECT_NEAR(phi_rolling(g, d), phi, kIdentity) << s.name << " delta = " << d;
    }
  }
}

// k -> 0 is continuous: k = 1e-9 differs from k = 0 by O(k) (here |delta| <= 0.5, so the
// difference in every quantity is below ~ k r = 6e-10 m, or ~ k for f5, f6, phi).
TEST(Kinematics, ContinuousAsKGoesToZero) {
  const double k = 1e-9;
  const TroughGeometry g0 = make_trough_geometry(kR, 0.0, 0.606);
  const TroughGeometry gk = make_trough_geometry(kR, k, 0.606);
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

// phi_rolling switches from a series to expm1 at |k delta| = 1e-5: no jump there. Across a step
// of 2e-9 rad in delta, phi changes by f5 * 2e-9 (~1e-11); a jump would be far larger than the
// round-off allowance.
TEST(Kinematics, RollingConditionHasNoJumpAtTheSeriesSwitch) {
  const double k = 2e-5;
  const TroughGeometry g = make_trough_geometry(kR, k, 0.606);
  for (double edge : {0.5, -0.5}) {  // |k delta| = 1e-5
    const double below = edge * (1.0 - 2e-9), above = edge * (1.0 + 2e-9);
    const double f5 = kinematics(g, edge).f5;
    EXPECT_NEAR(phi_rolling(g, above) - phi_rolling(g, below), f5 * (above - below), kIdentity)
        << edge;
  }
}

}  // namespace
}  // namespace oscidrum
