// tests/physics/trough_checks.hpp: the checks every trough shape must pass (oscidrum/trough.hpp),
// shared by the test file of each shape (tests/physics/test_trough_<name>.cpp): its derivatives
// f1 ... f6 (46)-(50) and their rates by finite differences, the rolling relation (12), the exact
// identities of docs/model.md section 3, and the start at the bottom of the trough.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "oscidrum/kinematics.hpp"
#include "tolerances.hpp"

namespace oscidrum::test {

inline constexpr double kDrumRadius = 0.6;  // the paper's r [m]
inline constexpr double kStep = 1e-5;       // finite-difference step in delta [rad]

/// delta in [-0.5, 0.5] and two odd values [rad].
inline std::vector<double> deltas() {
  std::vector<double> d;
  for (int i = -20; i <= 20; ++i) d.push_back(0.025 * i);
  d.push_back(0.1234567);
  d.push_back(-0.3141);
  return d;
}

template <class F>
double central_difference(F f, double x) {
  return (f(x + kStep) - f(x - kStep)) / (2.0 * kStep);
}

/// Every coded derivative of the geometry's shape against a finite difference of the quantity it
/// differentiates. The tolerance is relative to the scale of the terms (lengths ~ r; f5 ~ 1), not
/// to the (possibly tiny, ~ R - r) result.
inline void expect_derivatives_match_finite_differences(const TroughGeometry& g,
                                                        const std::string& name) {
  auto at = [&](double d) { return kinematics(g, d); };
  const double len = kFiniteDifference * g.r;  // lengths [m]
  const double one = kFiniteDifference;        // dimensionless (f5, f6)
  for (double d : deltas()) {
    const Kinematics q = at(d);
    const KinematicsRates rates = kinematics_rates(g, d);
    EXPECT_NEAR(q.f1, central_difference([&](double x) { return at(x).x_roll; }, d), len)
        << name << " delta = " << d;
    EXPECT_NEAR(q.f2, central_difference([&](double x) { return at(x).f1; }, d), len)
        << name << " delta = " << d;
    EXPECT_NEAR(q.f3, central_difference([&](double x) { return at(x).z_roll; }, d), len)
        << name << " delta = " << d;
    EXPECT_NEAR(q.f4, central_difference([&](double x) { return at(x).f3; }, d), len)
        << name << " delta = " << d;
    EXPECT_NEAR(q.f6, central_difference([&](double x) { return at(x).f5; }, d), one)
        << name << " delta = " << d;
    EXPECT_NEAR(rates.df2, central_difference([&](double x) { return at(x).f2; }, d), len)
        << name << " delta = " << d;
    EXPECT_NEAR(rates.df4, central_difference([&](double x) { return at(x).f4; }, d), len)
        << name << " delta = " << d;
    EXPECT_NEAR(rates.df6, central_difference([&](double x) { return at(x).f6; }, d), one)
        << name << " delta = " << d;
    // Rolling condition (12): d phi_rolling / d delta = f5.
    EXPECT_NEAR(q.f5, central_difference([&](double x) { return phi_rolling(g, x); }, d), one)
        << name << " delta = " << d;
  }
}

/// At delta = 0 the drum sits at the bottom: no displacement, no rolled angle, and the centre
/// moves horizontally only, at the rate (curvature radius - r) = r f5.
inline void expect_starts_at_the_bottom(const TroughGeometry& g, const std::string& name) {
  const Kinematics q = kinematics(g, 0.0);
  EXPECT_NEAR(q.x_roll, 0.0, kIdentity * g.r) << name;
  EXPECT_NEAR(q.z_roll, 0.0, kIdentity * g.r) << name;
  EXPECT_EQ(phi_rolling(g, 0.0), 0.0) << name;
  EXPECT_EQ(q.sin_delta, 0.0);
  EXPECT_EQ(q.cos_delta, 1.0);
  EXPECT_NEAR(q.f1, g.r * q.f5, kIdentity * g.r) << name;
  EXPECT_NEAR(q.f3, 0.0, kIdentity * g.r) << name;
  EXPECT_NEAR(curvature_radius_at_bottom(g.shape), g.r * (1.0 + q.f5), kIdentity * g.r) << name;
}

/// docs/model.md section 3: f3~ == 0 (the centre moves tangentially to the trough),
/// f1_bar == r f5, f4~ == -f1_bar, f2_bar == r f6; and the shorthands are what (33) and (37)
/// define.
inline void expect_exact_identities(const TroughGeometry& g, const std::string& name) {
  for (double d : deltas()) {
    const Kinematics q = kinematics(g, d);
    const double tol = kIdentity * g.r;
    EXPECT_NEAR(q.sin_delta, std::sin(d), kIdentity);
    EXPECT_NEAR(q.cos_delta, std::cos(d), kIdentity);
    const double sn = std::sin(d), cs = std::cos(d);
    EXPECT_NEAR(q.f1_bar, q.f1 * cs - q.f3 * sn, tol);  // (33)
    EXPECT_NEAR(q.f2_bar, q.f2 * cs - q.f4 * sn, tol);
    EXPECT_NEAR(q.f3_tilde, q.f1 * sn + q.f3 * cs, tol);  // (37)
    EXPECT_NEAR(q.f4_tilde, q.f2 * sn + q.f4 * cs, tol);
    EXPECT_NEAR(q.f3_tilde, 0.0, tol) << name << " delta = " << d;
    EXPECT_NEAR(q.f1_bar, g.r * q.f5, tol) << name << " delta = " << d;
    EXPECT_NEAR(q.f4_tilde, -q.f1_bar, tol) << name << " delta = " << d;
    // Differentiating f1_bar = r f5: f2_bar = r f6 (d/d delta of (33) uses f3~ = 0).
    EXPECT_NEAR(q.f2_bar, g.r * q.f6, tol) << name << " delta = " << d;
  }
}

/// What the shape says of itself agrees with what it is: its name is among the registered ones,
/// its summary names it, and each parameter set by a case key reads back through key_value.
inline void expect_describes_itself(const TroughShape& shape, const std::string& name) {
  bool registered = false;
  for (const std::string& n : trough_shape_names())
    registered = registered || n == trough_name(shape);
  EXPECT_TRUE(registered) << name;
  EXPECT_FALSE(summary(shape).empty()) << name;
  for (const TroughParameter& p : parameters(shape)) {
    EXPECT_TRUE(std::isfinite(p.value)) << name << " " << p.symbol;
    if (p.key != nullptr) {
      EXPECT_EQ(key_value(shape, p.key), p.value) << name << " " << p.symbol;
    }
  }
  EXPECT_TRUE(std::isnan(key_value(shape, "no.such.key"))) << name;
}

/// All of the above.
inline void expect_a_valid_shape(const TroughShape& shape, const std::string& name) {
  const TroughGeometry g{shape, kDrumRadius};
  expect_derivatives_match_finite_differences(g, name);
  expect_starts_at_the_bottom(g, name);
  expect_exact_identities(g, name);
  expect_describes_itself(shape, name);
}

}  // namespace oscidrum::test
