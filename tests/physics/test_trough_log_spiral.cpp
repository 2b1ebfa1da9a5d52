// Tests of the log-spiral trough (src/physics/trough_log_spiral.cpp): the checks of every shape
// (trough_checks.hpp), its derived values (8), the contact point on the spiral, the closed form
// of the rolling relation (11) and its series near k delta = 0, its check against the drum and
// what it says of itself.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "oscidrum/kinematics.hpp"
#include "tolerances.hpp"
#include "trough_checks.hpp"

namespace oscidrum {
namespace {

using test::deltas;
using test::kDrumRadius;
using test::kIdentity;

constexpr double kR = kDrumRadius;

struct Spiral {
  const char* name;
  double k, a;
};
// The paper's spiral (trough-shape study), a strongly curved one and a nearly circular one.
const std::vector<Spiral> kSpirals = {{"spiral k = 0.002", 0.002, 0.601},
                                      {"spiral k = 0.05", 0.05, 0.65},
                                      {"spiral k = 2e-5", 2e-5, 0.606}};

TEST(LogSpiralTrough, PassesTheChecksOfEveryShape) {
  for (const Spiral& s : kSpirals) test::expect_a_valid_shape(LogSpiralTrough(s.k, s.a), s.name);
}

// (8): alpha = atan(1/k), theta0 = pi - alpha, R0 = a exp(k theta0); k = 0 gives the circle's
// alpha = pi/2 and R0 = a exactly.
TEST(LogSpiralTrough, DerivedValues) {
  const LogSpiralTrough flat(0.0, 0.606);
  EXPECT_NEAR(flat.alpha(), M_PI / 2.0, kIdentity);
  EXPECT_EQ(flat.R0(), 0.606);
  EXPECT_EQ(flat.cos_alpha(), 0.0);
  for (double k : {0.002, 0.05}) {
    const LogSpiralTrough g(k, 0.6);
    EXPECT_EQ(g.k(), k);
    EXPECT_EQ(g.a(), 0.6);
    EXPECT_NEAR(g.alpha(), std::atan(1.0 / k), kIdentity);
    EXPECT_NEAR(g.R0(), 0.6 * std::exp(k * (M_PI - std::atan(1.0 / k))), kIdentity);
    EXPECT_NEAR(g.sin_alpha(), std::sin(g.alpha()), kIdentity);
    EXPECT_NEAR(g.cos_alpha(), std::cos(g.alpha()), kIdentity);
    EXPECT_NEAR(g.root(), std::sqrt(1.0 + k * k), kIdentity);
  }
}

// The contact point C = M + r (sin delta, cos delta) (z down) traces the trough: a log spiral
// about a fixed pole, of radius R0 exp(-k delta), whose tangent is perpendicular to the drum's
// radius MC. This checks (15)-(16) against the spiral (8) itself.
TEST(LogSpiralTrough, ContactPointLiesOnTheSpiral) {
  for (const Spiral& s : kSpirals) {
    const LogSpiralTrough g(s.k, s.a);
    // Pole P from the bottom point C(0) = (0, r): it lies at distance R0 along the direction
    // that makes angle alpha with the tangent (the log spiral's constant angle).
    const double px = g.R0() * std::cos(g.alpha()), pz = kR - g.R0() * std::sin(g.alpha());
    for (double d : deltas()) {
      const Kinematics q = kinematics(g, kR, d);
      const double cx = q.x_roll + kR * std::sin(d), cz = q.z_roll + kR * std::cos(d);
      EXPECT_NEAR(std::hypot(cx - px, cz - pz), g.R0() * std::exp(-s.k * d), kIdentity * kR)
          << s.name << " delta = " << d;
    }
  }
}

// phi_rolling (11): the closed form for k > 0, checked here directly.
TEST(LogSpiralTrough, RollingConditionClosedForm) {
  // (Not k = 2e-5: there the closed form itself cancels, 1 - exp(-k delta) ~ 1e-5.)
  for (const Spiral& s : {kSpirals[0], kSpirals[1]}) {
    const LogSpiralTrough g(s.k, s.a);
    for (double d : deltas()) {
      const double phi =
          std::sqrt(1.0 + s.k * s.k) / (s.k * kR) * g.R0() * (1.0 - std::exp(-s.k * d)) - d;
      EXPECT_NEAR(phi_rolling(g, kR, d), phi, kIdentity) << s.name << " delta = " << d;
    }
  }
}

// phi_rolling switches from a series to expm1 at |k delta| = 1e-5: no jump there. Across a step
// of 2e-9 rad in delta, phi changes by f5 * 2e-9 (~1e-11); a jump would be far larger than the
// round-off allowance.
TEST(LogSpiralTrough, RollingConditionHasNoJumpAtTheSeriesSwitch) {
  const LogSpiralTrough g(2e-5, 0.606);
  for (double edge : {0.5, -0.5}) {  // |k delta| = 1e-5
    const double below = edge * (1.0 - 2e-9), above = edge * (1.0 + 2e-9);
    const double f5 = kinematics(g, kR, edge).f5;
    EXPECT_NEAR(phi_rolling(g, kR, above) - phi_rolling(g, kR, below), f5 * (above - below),
                kIdentity)
        << edge;
  }
}

TEST(LogSpiralTrough, MustBeWiderThanTheDrumAtItsBottom) {
  const LogSpiralTrough paper(0.002, 0.601);
  EXPECT_EQ(fit_problem(paper, kR).message, "");
  EXPECT_NEAR(curvature_radius_at_bottom(paper), std::sqrt(1.0 + 0.002 * 0.002) * paper.R0(),
              kIdentity);
  // A spiral whose bottom is tighter than the drum: sqrt(1 + k^2) a exp(k (pi - atan(1/k))) =
  // 0.155 m < r.
  const FitProblem p = fit_problem(LogSpiralTrough(0.5, 0.05), kR);
  EXPECT_NE(p.message.find("curvature radius"), std::string::npos) << p.message;
  EXPECT_EQ(std::string(p.key), "trough.a");
}

TEST(LogSpiralTrough, DescribesItself) {
  const LogSpiralTrough g(0.002, 0.601);
  EXPECT_EQ(std::string(LogSpiralTrough::name), "log_spiral");
  EXPECT_EQ(summary(g), "log spiral, k = 0.002, a = 0.601 m");
  const std::vector<TroughParameter> p = parameters(g);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(std::string(p[0].symbol) + p[1].symbol + p[2].symbol + p[3].symbol, "kaalphaR0");
  EXPECT_EQ(p[2].value, g.alpha());
  EXPECT_EQ(p[3].value, g.R0());
  EXPECT_EQ(p[2].key, nullptr);  // derived
  EXPECT_EQ(key_value(g, "trough.k"), 0.002);
  EXPECT_EQ(key_value(g, "trough.a"), 0.601);
  EXPECT_EQ(std::string(curvature_radius_formula(g)), "sqrt(1+k^2) R0");
}

}  // namespace
}  // namespace oscidrum
