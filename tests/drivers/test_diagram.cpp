// The brute-force bifurcation diagram (src/drivers/diagram.cpp): its stroboscopic points show the
// period doubling that the continuation locates, the sweep carries the state from value to value,
// and bad options are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bifurcation_cases.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

using test::log_spiral_case;

// The distinct values of a column (apart by more than `tol` of the largest magnitude).
std::vector<double> distinct(std::vector<double> v, double tol) {
  std::sort(v.begin(), v.end());
  double scale = 0.0;
  for (const double x : v) scale = std::max(scale, std::abs(x));
  std::vector<double> out;
  for (const double x : v)
    if (out.empty() || x - out.back() > tol * scale) out.push_back(x);
  return out;
}

// The largest |x - want| over a column.
double largest_deviation(const std::vector<double>& x, double want) {
  double d = 0.0;
  for (const double v : x) d = std::max(d, std::abs(v - want));
  return d;
}

// Below the doubling the motion is the period-1 orbit: one stroboscopic point per value (every
// point the same); above it the period-2 orbit: two points, alternating, each repeating every
// two periods. The horizontal acceleration, the trough's displacements and delta all show it.
// At G = 135 MN/m^2 the stable period-2 orbit (multiplier about 0.97 per two periods) is
// approached slowly and not along one line: from either side, the motion is converging (its
// exponent, about -0.014 per period, is negative in both halves of the window: not a torus,
// which it was called up the sweep), and where the points' distances fall geometrically the
// period is the orbit's 2, not the multiple 16 the noise picked.
TEST(Diagram, ASlowApproachToThePeriod2OrbitIsConvergingFromEitherSide) {
  DiagramOptions o;
  o.key = "soil.G";
  o.from = 130e6;
  o.to = 140e6;
  o.steps = 2;
  o.sweep = DiagramSweep::both;
  const Diagram d = bifurcation_diagram(log_spiral_case(), o);
  int seen = 0;
  for (const DiagramValue& v : d.values) {
    if (v.parameter != 135e6) continue;
    ++seen;
    EXPECT_EQ(v.motion.kind, "converging") << v.motion.evidence;
    EXPECT_LT(v.motion.lyapunov * v.excitation_period, -0.01) << v.motion.evidence;
    EXPECT_TRUE(v.period == 0 || v.period == 2) << v.period << ": " << v.motion.evidence;
  }
  EXPECT_EQ(seen, 2);
}

TEST(Diagram, OnePointBelowThePeriodDoublingAndTwoAbove) {
  DiagramOptions o;
  o.key = "soil.G";
  o.from = 120e6;
  o.to = 130e6;  // the doubling at 125.004 MN/m^2 lies between
  o.steps = 1;
  o.discard = 300;
  o.periods = 40;
  const Diagram d = bifurcation_diagram(log_spiral_case(), o);
  ASSERT_EQ(d.values.size(), 2u);
  EXPECT_EQ(d.unit, "Pa");
  const DiagramValue &below = d.values[0], &above = d.values[1];
  EXPECT_TRUE(below.from_rest);
  EXPECT_FALSE(above.from_rest);  // started from the state at 120 MN/m^2
  EXPECT_EQ(below.parameter, 120e6);
  EXPECT_EQ(above.parameter, 130e6);
  ASSERT_EQ(below.section.size(), 40u);
  ASSERT_EQ(above.section.size(), 40u);
  EXPECT_EQ(below.period, 1) << below.motion.kind << ": " << below.motion.evidence;
  EXPECT_EQ(above.period, 2) << above.motion.kind << ": " << above.motion.evidence;
  for (const auto column :
       {&Samples::ddx_M, &Samples::ddz_M, &Samples::x_A, &Samples::s_A, &Samples::delta}) {
    EXPECT_EQ(distinct(below.section.*column, 1e-4).size(), 1u);
    EXPECT_EQ(distinct(above.section.*column, 1e-4).size(), 2u);
  }
  // Each period-2 point recurs every second period and differs from its neighbour.
  const std::vector<double>& x = above.section.ddx_M;
  const double range =
      *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end());
  for (std::size_t k = x.size() / 2; k + 2 < x.size(); ++k) {
    EXPECT_NEAR(x[k + 2], x[k], 1e-4 * range) << k;
    EXPECT_GT(std::abs(x[k + 1] - x[k]), 0.5 * range) << k;
  }
  // The points are whole periods apart.
  EXPECT_NEAR(below.section.t.back() - below.section.t.front(), 39 * 0.04, 1e-9);
  // Both orbits were found by shooting (from rest, then from the orbit at 120 MN/m^2): by the
  // transient, with a multiplier of -0.998 at 120 MN/m^2, they would take thousands of periods.
  EXPECT_TRUE(below.shooting);
  EXPECT_TRUE(above.shooting);
}

// The sweep down starts at the largest value and visits every value once per direction; both
// visits the largest twice (up, then down from where the up sweep ended).
TEST(Diagram, SweepsVisitTheValuesInOrder) {
  DiagramOptions o;
  o.key = "MMd";
  o.from = 0.0;
  o.to = 2000.0;
  o.steps = 2;
  o.discard = 20;
  o.periods = 20;
  o.sweep = DiagramSweep::both;
  int calls = 0;
  o.on_value = [&](int done, int total, double) {
    ++calls;
    EXPECT_EQ(done, calls);
    EXPECT_EQ(total, 6);
  };
  const Diagram d = bifurcation_diagram(Case(), o);
  ASSERT_EQ(d.values.size(), 6u);
  const std::vector<double> want = {0, 1000, 2000, 2000, 1000, 0};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(d.values[i].parameter, want[i]);
    EXPECT_EQ(d.values[i].direction, i < 3 ? 1 : -1);
    EXPECT_EQ(d.values[i].from_rest, i == 0);
    // The default case settles on its period-1 orbit at each value.
    EXPECT_EQ(d.values[i].period, 1)
        << d.values[i].motion.kind << ": " << d.values[i].motion.evidence;
  }
  // A value started from its neighbour's state continues it: the down sweep's first value
  // starts where the up sweep's last ended and ends on the same orbit.
  EXPECT_NEAR(d.values[3].section.ddx_M.back(), d.values[2].section.ddx_M.back(),
              1e-4 * std::abs(d.values[2].section.ddx_M.back()));
  EXPECT_GE(d.periods_integrated, 6L * 20);
  o.sweep = DiagramSweep::down;
  o.on_value = {};
  const Diagram down = bifurcation_diagram(Case(), o);
  ASSERT_EQ(down.values.size(), 3u);
  EXPECT_EQ(down.values[0].parameter, 2000.0);
  EXPECT_EQ(down.values[2].parameter, 0.0);
}

// MMd_fraction holds at every value: MMd = 0.05 M0 with the value's M0. The stroboscopic points
// at t = k T (sin(nu t) = 0 there) are on the period-1 orbit simulate() finds with that MMd.
TEST(Diagram, MMdFractionFollowsTheM0OfEachValue) {
  DiagramOptions o;
  o.key = "roller.M0";
  o.from = 40000.0;
  o.to = 60000.0;
  o.steps = 1;
  o.discard = 100;
  o.periods = 20;
  o.MMd_fraction = 0.05;
  const Diagram d = bifurcation_diagram(Case(), o);
  ASSERT_EQ(d.values.size(), 2u);
  for (const DiagramValue& v : d.values) {
    Case c;
    c.roller.M0 = v.parameter;
    c.MMd = 0.05 * v.parameter;
    const Result r = simulate(c);
    ASSERT_EQ(r.status, Status::steady_state);
    ASSERT_FALSE(v.section.delta.empty());
    // The section's delta against the steady samples' delta at the same phase (t = k T).
    EXPECT_NEAR(v.section.delta.back(), r.samples.delta.front(), 1e-6) << v.parameter;
  }
  o.key = "MMd";
  o.from = 0.0;
  o.to = 1000.0;
  EXPECT_THROW(bifurcation_diagram(Case(), o), Error);
}

// numerics.start_ramp_periods ramps the excitation in from rest: the first value starts under it
// (its points past the ramp), the next continues from its state on the full excitation, and
// ends on the orbit a diagram without the ramp finds there. At each point the excitation is
// MMd (sin(nu t) = 0 at the section t = k T): under the ramp it is MMd times the ramp. (With the
// ramp at every value the excitation climbed from zero again at each, and the value after the
// first fell back to a start from rest.)
TEST(Diagram, TheStartRampAppliesToTheStartFromRestOnly) {
  Case c;
  c.numerics.start_ramp_periods = 20;
  DiagramOptions o;
  o.key = "MMd";
  o.from = 500.0;
  o.to = 1000.0;
  o.steps = 1;
  o.discard = 20;
  o.periods = 20;
  const Diagram d = bifurcation_diagram(c, o);
  c.numerics.start_ramp_periods = 0;
  const Diagram plain = bifurcation_diagram(c, o);
  ASSERT_EQ(d.values.size(), 2u);
  ASSERT_EQ(plain.values.size(), 2u);
  EXPECT_TRUE(d.values[0].from_rest);
  EXPECT_FALSE(d.values[1].from_rest);  // from the state at 500 N m, as without the ramp
  EXPECT_FALSE(plain.values[1].from_rest);
  for (const DiagramValue& v : d.values) {
    EXPECT_TRUE(v.shooting);
    ASSERT_EQ(v.section.size(), 20u);
    EXPECT_EQ(v.period, 1) << v.motion.kind << ": " << v.motion.evidence;
    EXPECT_LT(largest_deviation(v.section.torque, v.parameter), 1e-6 * v.parameter)
        << "MMd " << v.parameter;
  }
  EXPECT_GE(d.values[0].section.t.front(), 20 * d.values[0].excitation_period);
  const DiagramValue &ramped = d.values[1], &unramped = plain.values[1];
  for (const auto column : {&Samples::ddx_M, &Samples::ddz_M, &Samples::delta, &Samples::x_A}) {
    const std::vector<double>&x = ramped.section.*column, &want = unramped.section.*column;
    double size = 0.0;
    for (const double w : want) size = std::max(size, std::abs(w));
    for (std::size_t k = 0; k < want.size(); ++k) EXPECT_NEAR(x[k], want[k], 1e-6 * size) << k;
  }
}

// Where shooting finds no stable orbit the transient decides, under the same rule: from rest
// (130 MN/m^2 on the log-spiral trough, with a driving torque) through the ramp, then `discard`
// periods; from the previous value's state (135 MN/m^2) on the full excitation from its first
// period (its transient started at t = 0 under the ramp: the excitation climbed from zero).
TEST(Diagram, ATransientFromThePreviousStateRunsWithoutTheStartRamp) {
  Case c = log_spiral_case();
  set_field(c, "MMd", 100.0);
  c.numerics.start_ramp_periods = 20;
  DiagramOptions o;
  o.key = "soil.G";
  o.from = 130e6;
  o.to = 135e6;
  o.steps = 1;
  o.discard = 0;
  o.periods = 20;
  const Diagram d = bifurcation_diagram(c, o);
  ASSERT_EQ(d.values.size(), 2u);
  EXPECT_TRUE(d.values[0].from_rest);
  EXPECT_FALSE(d.values[1].from_rest);
  EXPECT_FALSE(d.values[1].shooting);  // the transient from the state at 130 MN/m^2
  for (const DiagramValue& v : d.values) {
    ASSERT_EQ(v.section.size(), 20u) << v.motion.evidence;
    EXPECT_LT(largest_deviation(v.section.torque, 100.0), 1e-6 * 100.0) << "G " << v.parameter;
  }
  EXPECT_GE(d.values[0].section.t.front(), 20 * d.values[0].excitation_period);
}

// Pure rolling on contact that can open at 65 Hz (G = 100 MN/m^2): the start from rest lifts the
// drum out of its trough, and run starts again with the excitation ramped in over 20 periods;
// the diagram's first value does the same, and finds the motion run finds (period 3), where it
// said undecided with no points.
TEST(Diagram, AFirstValueThatLosesContactFromRestIsRetriedWithARampAsRunDoes) {
  Case c = test::rolling_unilateral_case(65.0);
  set_field(c, "soil.G", 100e6);
  DiagramOptions o;
  o.key = "roller.f";
  o.from = 65.0;
  o.to = 66.0;
  o.steps = 1;
  o.periods = 60;
  const Diagram d = bifurcation_diagram(c, o);
  ASSERT_FALSE(d.values.empty());
  const DiagramValue& v = d.values[0];
  EXPECT_TRUE(v.from_rest);
  ASSERT_EQ(v.section.size(), 60u) << v.motion.kind << ": " << v.motion.evidence;
  EXPECT_EQ(v.period, 3) << v.motion.kind << ": " << v.motion.evidence;
  EXPECT_TRUE(std::isfinite(v.motion.lyapunov));
  EXPECT_NE(v.motion.evidence.find("ramped in over 20 periods"), std::string::npos)
      << v.motion.evidence;
}

// In pure rolling without a contact that can open, the drum loses contact at 66 Hz even with the
// ramp: no points, no exponent (NaN, not the 0 that reads as a torus), and the evidence says the
// flow stopped.
TEST(Diagram, AValueWhoseFlowStoppedHasNoExponent) {
  Case c = test::rolling_unilateral_case(66.0);
  set_field_text(c, "contact.unilateral", "false");
  set_field(c, "soil.G", 100e6);
  DiagramOptions o;
  o.key = "roller.f";
  o.from = 66.0;
  o.to = 67.0;
  o.steps = 1;
  o.discard = 20;
  o.periods = 20;
  const Diagram d = bifurcation_diagram(c, o);
  ASSERT_EQ(d.values.size(), 2u);
  for (const DiagramValue& v : d.values) {
    EXPECT_EQ(v.motion.kind, "undecided");
    EXPECT_TRUE(v.section.size() == 0);
    EXPECT_TRUE(std::isnan(v.motion.lyapunov)) << v.motion.lyapunov;
    EXPECT_TRUE(std::isnan(v.motion.lyapunov_first));
    EXPECT_TRUE(std::isnan(v.motion.lyapunov_second));
    EXPECT_EQ(v.motion.evidence.rfind("the flow stopped (contact_lost)", 0), 0u)
        << v.motion.evidence;
  }
}

// Where shooting from the previous value's state finds no stable orbit, the transient from that
// state decides, not a start from rest: at 74 Hz a start from rest (simulate's fallback, taken
// before) jumped to another period-2 orbit (x_M'' -150.2 / -1.1 for the followed one's -170.5 /
// -139.1), so that steps of 1 and 2 Hz drew different pictures of one branch.
TEST(Diagram, AValueFollowsThePreviousValuesAttractorNotAStartFromRest) {
  Case c = test::rolling_unilateral_case(73.0);
  set_field(c, "soil.G", 100e6);
  DiagramOptions o;
  o.key = "roller.f";
  o.from = 73.0;
  o.to = 75.0;
  o.steps = 2;
  const Diagram d = bifurcation_diagram(c, o);
  ASSERT_EQ(d.values.size(), 3u);
  for (std::size_t k = 1; k < 3; ++k) {
    const DiagramValue& v = d.values[k];
    SCOPED_TRACE("f = " + std::to_string(v.parameter));
    EXPECT_FALSE(v.from_rest);
    EXPECT_EQ(v.period, 2) << v.motion.evidence;
    const std::vector<double> x = distinct(v.section.ddx_M, 1e-6);
    ASSERT_EQ(x.size(), 2u);
    EXPECT_LT(x[1], -100.0);  // both points of the followed orbit are deep; the other's -1.1
  }
}

// A driving torque beyond what friction holds: the drum spins up, its stroboscopic points neither
// recur nor converge, and the window read a torus ("quasi_periodic") where run says gross_slip.
TEST(Diagram, ASpinningDrumIsGrossSlipNotATorus) {
  Case c;
  c.numerics.method = SteadyMethod::shooting;
  DiagramOptions o;
  o.key = "MMd";
  o.from = 12000.0;
  o.to = 13000.0;
  o.steps = 1;
  const auto every_value_is_gross_slip = [&](const char* window) {
    const Diagram d = bifurcation_diagram(c, o);
    ASSERT_EQ(d.values.size(), 2u) << window;
    for (const DiagramValue& v : d.values) {
      EXPECT_EQ(v.motion.kind, "gross_slip") << window << ": " << v.motion.evidence;
      EXPECT_EQ(v.period, 0) << window;
    }
  };
  every_value_is_gross_slip("the default window");
  // After a longer discard the other coordinates have settled and a short window read the
  // spinning drum "converging" with period 1 or 2 (phi' growing by 0.07 rad/s every period).
  o.discard = 200;
  o.periods = 50;
  every_value_is_gross_slip("after 200 periods, 50 periods");
  set_field(c, "MMd", 12000.0);
  EXPECT_EQ(simulate(c).status, Status::gross_slip);
}

// A vibratory drum that lifts off every period and spins: slip- -> flight -> slip-, never stick,
// phi' growing by 0.25 rad/s a period. A flight interrupts no slip: run says gross_slip within
// some 40 periods, the diagram too (run integrated 5000 periods and said "aperiodic: a torus",
// the diagram "quasi_periodic"; every stroboscopic point is in flight).
TEST(Diagram, ASpinningDrumThatLiftsOffIsGrossSlip) {
  Case c;
  c.roller.type = RollerType::vibratory;
  c.roller.static_moment = 0.9;
  c.roller.f = 30.0;
  c.contact.unilateral = true;
  c.MMd = 15000.0;
  const Result r = simulate(c);
  EXPECT_EQ(r.status, Status::gross_slip) << r.message;
  EXPECT_LT(r.diagnostics.periods_simulated, 100) << r.message;
  DiagramOptions o;
  o.key = "MMd";
  o.from = 15000.0;
  o.to = 15100.0;
  o.steps = 1;
  o.discard = 100;
  o.periods = 100;
  const Diagram d = bifurcation_diagram(c, o);
  ASSERT_EQ(d.values.size(), 2u);
  for (const DiagramValue& v : d.values) {
    EXPECT_EQ(v.motion.kind, "gross_slip") << v.motion.evidence;
    ASSERT_FALSE(v.section.phase.empty());
    EXPECT_EQ(v.section.phase.back(), Phase::flight);
  }
}

// The vibratory drum with lift-off at 21.5 Hz, reached from 22 Hz: just below the flip of the
// period-1 orbit (21.509 Hz), its two stroboscopic points drift apart over the 400 periods
// (exponent 1e-4 per period) towards the stable period-2 orbit that simulate finds; they were
// called a torus. A longer transient reaches the period-2 orbit.
TEST(Diagram, AMotionLeavingAnUnstableOrbitIsNoTorus) {
  Case c = test::vibratory_lift_off_case(1.5, 20e6);
  DiagramOptions o;
  o.key = "roller.f";
  o.from = 21.5;
  o.to = 22.0;
  o.steps = 1;
  o.sweep = DiagramSweep::down;
  const Diagram d = bifurcation_diagram(c, o);
  ASSERT_EQ(d.values.size(), 2u);
  const DiagramValue& v = d.values.back();
  ASSERT_EQ(v.parameter, 21.5);
  EXPECT_EQ(v.motion.kind, "undecided") << v.motion.evidence;
  EXPECT_NE(v.motion.evidence.find("lie on 2 branches that drift apart"), std::string::npos)
      << v.motion.evidence;
  o.discard = 2000;
  const DiagramValue longer = bifurcation_diagram(c, o).values.back();
  EXPECT_EQ(longer.motion.kind, "periodic") << longer.motion.evidence;
  EXPECT_EQ(longer.period, 2);
  set_field(c, "roller.f", 21.5);
  const Result r = simulate(c);
  EXPECT_EQ(r.status, Status::steady_state) << r.message;
  EXPECT_EQ(r.diagnostics.multiplicity, 2);
}

TEST(Diagram, RefusesBadOptions) {
  const Case c;
  const auto refused = [&](DiagramOptions o, const std::string& says) {
    try {
      bifurcation_diagram(c, o);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  DiagramOptions o;
  o.key = "contact.mu";
  o.from = 0.3;
  o.to = 0.5;
  DiagramOptions bad = o;
  bad.key = "soil.gg";
  refused(bad, "unknown key");
  bad = o;
  bad.key = "numerics.rtol";
  refused(bad, "numerical setting");
  bad = o;
  bad.to = 0.3;
  refused(bad, "must be > its start (from, --from)");
  bad = o;
  bad.steps = 0;
  refused(bad, "steps (--steps) must be in [1, 100000]");
  bad = o;
  bad.periods = 19;
  refused(bad, "periods (--periods) must be in [20, 100000]");
  bad = o;
  bad.discard = -1;
  refused(bad, "discard (--discard) must be in [0, 1000000]");
  bad = o;
  bad.from = -1;
  refused(bad, "--from");
  // soil.G on Table 2 soil (the default) from 5 to 70 MN/m^2 in 3 steps: 26.7 MN/m^2 is no row of
  // the table. The diagram stopped there with the field's message alone; it is refused before any
  // work, naming the step; in 13 steps every value is a row, and the diagram runs.
  bad = o;
  bad.key = "soil.G";
  bad.from = 5e6;
  bad.to = 70e6;
  bad.steps = 3;
  refused(bad,
          "diagram: soil.G = 26.666666666666668 MN/m^2, value 1 of --steps 3 from 5 MN/m^2 to "
          "70 MN/m^2: the case is not valid there (soil.G must be a G of paper Table 2");
  bad.steps = 13;
  bad.discard = 10;
  bad.periods = 20;
  EXPECT_EQ(bifurcation_diagram(c, bad).values.size(), 14u);
}

TEST(Diagram, CancelledStopsPromptly) {
  DiagramOptions o;
  o.key = "MMd";
  o.from = 0.0;
  o.to = 2000.0;
  o.steps = 10;
  o.cancelled = [] { return true; };
  const Diagram d = bifurcation_diagram(Case(), o);
  EXPECT_TRUE(d.cancelled);
  EXPECT_TRUE(d.values.empty());
}

}  // namespace
}  // namespace oscidrum
