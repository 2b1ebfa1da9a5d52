// Tests of the continuation of periodic orbits (src/drivers/branch.cpp): the branch's orbits are
// the steady states simulate() finds at the same parameter (with the same multipliers), the
// tangent is the derivative of the branch, and every bifurcation it reports is confirmed by
// simulations on either side of it that do not use the continuation: a phase that vanishes
// (grazing), the gross-slip limit, and a Neimark-Sacker point (a complex pair leaving the unit
// circle), beyond which the transient method finds no steady state.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "bifurcation_cases.hpp"
#include "drivers/branch_continuation.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

using test::log_spiral_case;
using test::modulus_case;
using test::rolling_unilateral_case;

Result run_at(Case c, const std::string& key, double q) {
  set_field(c, key, q);
  return simulate(c);
}

// Every orbit of a branch in G is the steady state simulate() finds there: the same metrics and
// the same largest Floquet multiplier; and the tangent's parameter component is the branch's
// slope dq/ds (the secant between neighbours, to first order in the step).
TEST(Branch, OrbitsAreTheSteadyStatesOfSimulate) {
  const Case c = modulus_case();
  BranchOptions o;
  o.key = "soil.G";
  o.from = 10e6;
  o.to = 60e6;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.end, BranchEnd::reached_end) << b.message;
  ASSERT_GT(b.points.size(), 20u);
  EXPECT_EQ(b.key, "soil.G");
  EXPECT_EQ(b.unit, "Pa");
  // The last point is the orbit at `to` itself (it was the first one past it, up to a step on).
  EXPECT_EQ(b.points.back().parameter, o.to);
  std::vector<std::size_t> checked;
  for (std::size_t k = 0; k < b.points.size(); k += b.points.size() / 5) checked.push_back(k);
  checked.push_back(b.points.size() - 1);
  for (const std::size_t k : checked) {
    const BranchPoint& p = b.points[k];
    SCOPED_TRACE("G = " + std::to_string(p.parameter));
    Case ck = c;
    set_field(ck, "soil.G", p.parameter);
    const Model model(ck);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state);
    const Metrics m = compute_metrics(model, r);
    // Both are steady states to numerics.steady_tol = 1e-8 of the state's range; the metrics
    // follow to ~1e-7 of their scale.
    EXPECT_NEAR(p.metrics.area, m.area, 1e-6 * std::abs(m.area));
    EXPECT_NEAR(p.metrics.ddx_max, m.ddx_max, 1e-6 * std::abs(m.ddx_max));
    EXPECT_NEAR(p.metrics.psi_xz, m.psi_xz, 1e-6);
    // The multipliers do not depend on the section, but their computation does: the variational
    // equations run along the flow's steps (src/flow/monodromy.hpp) from another section (the
    // branch moves it away from switches) than simulate's; the two agree to ~2e-5 (measured:
    // 1.8e-5 at most over this branch, with an earlier Runge-Kutta scheme for them).
    EXPECT_NEAR(p.floquet.max_modulus, r.floquet.max_modulus, 1e-4);
    EXPECT_TRUE(p.stable());
  }
  for (std::size_t k = 1; k + 1 < b.points.size(); ++k) {
    const BranchPoint &a = b.points[k], &n = b.points[k + 1];
    const double secant =
        (n.parameter - a.parameter) / (o.to - o.from) / (n.arclength - a.arclength);
    // dq/ds changes by O(ds) between neighbours: the secant lies between the two tangents up to
    // the curvature's second-order term.
    const double lo = std::min(a.dq_ds, n.dq_ds), hi = std::max(a.dq_ds, n.dq_ds);
    EXPECT_GT(secant, lo - 0.05 * std::abs(hi)) << k;
    EXPECT_LT(secant, hi + 0.05 * std::abs(hi)) << k;
  }
}

// In permanent contact the branch cannot go past where the drum would lift off: it ends there
// (step_too_small), and the message says why (it said "no tangent at the new point" only).
TEST(Branch, ABranchInPermanentContactSaysWhereTheDrumWouldLiftOff) {
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = 100e6;
  c.contact.pure_rolling = true;
  c.roller.unbalance = 0.22877;
  BranchOptions o;
  o.key = "roller.f";
  o.from = 55.0;
  o.to = 75.0;
  o.metrics = false;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.end, BranchEnd::step_too_small) << b.message;
  EXPECT_NE(b.message.find("the orbits' smallest normal force falls to zero there"),
            std::string::npos)
      << b.message;
  EXPECT_NEAR(b.points.back().parameter, 65.7263, 1e-3);
}

// MMd_fraction holds at every point, as in a study: MMd = 0.05 M0 with the M0 of the point. (The
// CLI's continue kept the MMd of --from's M0, 2747 N m, along a branch in roller.M0: area 39.65
// at M0 = 40000 N m, where run gives 30.40.) Without it the case's MMd holds throughout.
TEST(Branch, MMdFractionFollowsTheM0OfEachPoint) {
  Case c;
  BranchOptions o;
  o.key = "roller.M0";
  o.from = 40000.0;
  o.to = 60000.0;
  o.MMd_fraction = 0.05;
  o.metrics = true;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.end, BranchEnd::reached_end) << b.message;
  for (const BranchPoint* p : {&b.points.front(), &b.points.back()}) {
    Case ck = c;
    ck.roller.M0 = p->parameter;
    ck.MMd = 0.05 * p->parameter;
    const Model model(ck);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state);
    EXPECT_NEAR(p->metrics.area, compute_metrics(model, r).area, 1e-6 * p->metrics.area)
        << p->parameter;
  }
  // Without: the case's MMd (0 here) at every point.
  o.MMd_fraction = std::numeric_limits<double>::quiet_NaN();
  c.MMd = 1000.0;
  const Branch fixed = continue_branch(c, o);
  ASSERT_EQ(fixed.end, BranchEnd::reached_end) << fixed.message;
  Case ck = c;
  ck.roller.M0 = 60000.0;
  const Model model(ck);
  EXPECT_NEAR(fixed.points.back().metrics.area, compute_metrics(model, simulate(model)).area,
              1e-6 * fixed.points.back().metrics.area);
  // It cannot hold with MMd varied, nor for a drum without an oscillation moment.
  o.key = "MMd";
  o.from = 0.0;
  o.to = 1000.0;
  o.MMd_fraction = 0.05;
  EXPECT_THROW(continue_branch(c, o), Error);
  o.MMd_fraction = std::numeric_limits<double>::infinity();
  o.key = "roller.M0";
  o.from = 40000.0;
  o.to = 60000.0;
  EXPECT_THROW(continue_branch(c, o), Error);
}

// The driving torque makes the drum slip further each period: the slip+ phase vanishes (a
// grazing of the stick-to-slip+ switch), then the stick phase (the gross-slip limit, where the
// branch ends). Each located point is confirmed by simulate() just below and just above it.
TEST(Branch, GrazingAndGrossSlipInTheDrivingTorque) {
  Case c;
  c.numerics.method = SteadyMethod::shooting;
  BranchOptions o;
  o.key = "MMd";
  o.from = 0.0;
  o.to = 14000.0;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.end, BranchEnd::gross_slip) << b.message;
  ASSERT_EQ(b.bifurcations.size(), 2u);
  // Located to 1e-6 of the range (0.014 N m) where the corrector converges on both sides; at
  // the gross-slip limit the orbits crowd (the stick interval shrinks to nothing) and the
  // bisection stops at the bracket it reached, which it reports.
  EXPECT_LE(b.bifurcations[0].tolerance, o.tolerance * 14000.0);
  EXPECT_LE(b.bifurcations[1].tolerance, 1.0);
  for (const Bifurcation& x : b.bifurcations) EXPECT_EQ(x.kind, BifurcationKind::grazing);
  // A point located short of the tolerance says so in its description, with why; one located
  // to it does not.
  for (const Bifurcation& x : b.bifurcations) {
    const bool wide = 2.0 * x.tolerance > o.tolerance * 14000.0;
    EXPECT_EQ(x.description.find("located within a bracket of") != std::string::npos, wide)
        << x.description;
    if (wide) {
      EXPECT_NE(x.description.find("the corrector failed"), std::string::npos);
    }
  }
  // The slip+ phase vanishes at 6886.03 N m (run's fractions: 2.4e-4 at 6886.02, 0 at 6886.04);
  // a slip+ phase shorter than a step was missed before, and the point read 6883.87.
  EXPECT_NEAR(b.bifurcations[0].parameter, 6886.03, 0.02);
  // The slip+ phase: 4 switches per period below the point, 2 above (slip- and stick).
  const double q1 = b.bifurcations[0].parameter;
  const Result below = run_at(c, "MMd", q1 - 20.0), above = run_at(c, "MMd", q1 + 20.0);
  ASSERT_EQ(below.status, Status::steady_state);
  ASSERT_EQ(above.status, Status::steady_state);
  EXPECT_DOUBLE_EQ(below.diagnostics.switches_per_period, 4.0);
  EXPECT_DOUBLE_EQ(above.diagnostics.switches_per_period, 2.0);
  // The stick phase: a steady state below, gross slip above.
  const double q2 = b.bifurcations[1].parameter;
  EXPECT_NEAR(q2, b.points.back().parameter, 1.0);
  EXPECT_EQ(run_at(c, "MMd", q2 - 20.0).status, Status::steady_state);
  EXPECT_EQ(run_at(c, "MMd", q2 + 20.0).status, Status::gross_slip);
}

// In pure rolling at 58 Hz (the paper's roller with its unbalance, soil by Appendix B, contact
// that can open) a complex
// pair of multipliers leaves the unit circle as the soil stiffens and returns later: between the
// two Neimark-Sacker points the transient method, which knows nothing of the continuation,
// finds no steady state, and outside them it does.
TEST(Branch, NeimarkSackerPointsBoundWhereNoSteadyStateIsFound) {
  // Contact that can open: beyond the points the motion grows (N -> 0).
  Case c = rolling_unilateral_case(58.0);
  BranchOptions o;
  o.key = "soil.G";
  o.from = 30e6;
  o.to = 100e6;
  o.metrics = false;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.end, BranchEnd::reached_end) << b.message;
  // In SI and in the unit G is read in, as the CLI's table and bifurcation lines give it.
  EXPECT_NE(b.message.find("soil.G = 1e+08 Pa (100 MN/m^2)"), std::string::npos) << b.message;
  ASSERT_EQ(b.bifurcations.size(), 2u);
  for (const Bifurcation& x : b.bifurcations) {
    EXPECT_EQ(x.kind, BifurcationKind::neimark_sacker);
    // Located where the pair is on the unit circle (not at the band's edge 1 + 1e-6), to the
    // change of G that moves its modulus by 1e-6 (a few hundred Pa here), above the bisection's
    // 1e-6 of the range.
    EXPECT_LE(x.tolerance, 1000.0);
    EXPECT_GT(x.tolerance, 70.0);
    EXPECT_NEAR(std::abs(x.multiplier), 1.0, 3e-7);
    EXPECT_GT(x.multiplier.imag(), 0.1);
  }
  const double g1 = b.bifurcations[0].parameter, g2 = b.bifurcations[1].parameter;
  EXPECT_LT(g1, g2);
  for (const BranchPoint& p : b.points)
    EXPECT_EQ(p.stable(), p.parameter < g1 || p.parameter > g2) << p.parameter;
  c.numerics.method = SteadyMethod::transient;
  c.numerics.max_periods = 3000;
  // ... and, examining the motion, finds it aperiodic (docs/bifurcations.md).
  const Result mid = run_at(c, "soil.G", 0.5 * (g1 + g2));
  EXPECT_EQ(mid.status, Status::aperiodic) << mid.message;
  EXPECT_EQ(run_at(c, "soil.G", g2 + 5e6).status, Status::steady_state);
}

// In f, in pure rolling with the unbalance (G = 100 MN/m^2 by Appendix B, contact that can open),
// the smallest normal force of the orbit falls to zero at 65.7266 Hz, where the drum lifts off:
// beyond it no orbit in contact continues the branch (the corrector fails there), and the branch
// ends as lift_off with a lift_off bifurcation located at the zero of min N. It must not report a
// fold there: the tangent's dq/ds did turn negative when dF/dq was a forward difference that
// reached across lift-off (the map beside the orbit had a flight phase), and a fold was reported
// with the critical multiplier 0.72 + 0.75i, nowhere near +1.
// Pure rolling on contact that can open at G = 100 MN/m^2, continued in roller.f [Hz] (no
// metrics): the branch, its options and its case.
struct FrequencyBranch {
  Branch b;
  BranchOptions o;
  Case c;
};
FrequencyBranch frequency_branch(double from, double to) {
  Case c = rolling_unilateral_case(from);
  set_field(c, "soil.G", 100e6);
  BranchOptions o;
  o.key = "roller.f";
  o.from = from;
  o.to = to;
  o.metrics = false;
  return {continue_branch(c, o), o, c};
}

TEST(Branch, TheBranchEndsWhereTheDrumLiftsOff) {
  const auto [b, o, c] = frequency_branch(58.0, 70.0);
  ASSERT_EQ(b.end, BranchEnd::lift_off) << b.message;
  const BranchPoint& last = b.points.back();
  // N's minimum between step ends counts (the parabola through each step's samples): the point
  // is 65.726274 Hz at every rtol from 1e-8 to 1e-11; from the step ends alone it was 65.726661,
  // 65.726295 or 65.726375 Hz as the steps fell, or the corrector failed short of it.
  EXPECT_NEAR(last.parameter, 65.726274, 5e-6);
  EXPECT_LT(last.min_N, 1e-3 * 45224.0);  // below 1e-3 of the static axle load P0
  EXPECT_GT(last.dq_ds, 0.0);
  for (const Bifurcation& x : b.bifurcations)
    EXPECT_NE(x.kind, BifurcationKind::fold) << "at f = " << x.parameter;
  ASSERT_FALSE(b.bifurcations.empty());
  const Bifurcation& lift = b.bifurcations.back();
  ASSERT_EQ(lift.kind, BifurcationKind::lift_off);
  EXPECT_EQ(lift.after_point, static_cast<int>(b.points.size()) - 1);
  EXPECT_GE(lift.parameter, last.parameter);
  EXPECT_LE(lift.tolerance, o.tolerance * (o.to - o.from));  // located to the tolerance asked

  // Independently of the continuation and of the unilateral drum's equations: the paper's drum
  // in permanent contact, integrated over one period from the last orbit (its section state and
  // time), keeps N > 0 a little below the reported point and drives N below zero a little above
  // it (the flow of permanent contact then stops as contact_lost).
  UnilateralState z;
  {
    std::array<double, 10> q{};
    std::copy(last.state.begin(), last.state.end(), q.begin());
    z = UnilateralState::from_array(q);
  }
  ASSERT_EQ(z.gap, 0.0);
  auto smallest_N = [&](double f) {
    Case p = c;
    set_field_text(p, "contact.unilateral", "false");
    set_field(p, "roller.f", f);
    const Model model(p);
    Flow flow(model);
    const double t0 = last.section_time * last.parameter / f;  // the same excitation phase
    flow.reset(t0, z.contact(), last.phase);
    const FlowStop stop = flow.advance(t0 + model.period());
    return std::pair{stop, flow.counters().min_N};
  };
  const double df = 2e-4;  // [Hz]: min N moves about 6000 N/Hz here, so by about 1.2 N
  const auto [stop_below, N_below] = smallest_N(lift.parameter - df);
  EXPECT_EQ(stop_below, FlowStop::reached);
  EXPECT_GT(N_below, 0.0);
  const auto [stop_above, N_above] = smallest_N(lift.parameter + df);
  EXPECT_TRUE(stop_above == FlowStop::contact_lost || N_above < 0.0)
      << to_string(stop_above) << ", min N " << N_above;
}

// A crossing of the unit circle changes the number of multipliers outside it; a complex pair
// outside it that meets the real axis and parts into two reals there (or two reals that join)
// changes only the counts by kind, and is no bifurcation.
TEST(Branch, OnlyAChangeOfTheNumberOutsideTheUnitCircleIsACrossing) {
  using detail::branching::crossings;
  using detail::branching::MultiplierCounts;
  const auto counts = [](int plus, int minus, int pairs) {
    MultiplierCounts c;
    c.beyond_plus_one = plus, c.beyond_minus_one = minus, c.complex_outside = pairs;
    return c;
  };
  const auto none = [](const detail::branching::Crossings& c) {
    return !c.plus_one && !c.minus_one && !c.complex_pair;
  };
  // Collisions outside the circle, either way, beside +1 and beside -1.
  EXPECT_TRUE(none(crossings(counts(0, 0, 1), counts(2, 0, 0))));
  EXPECT_TRUE(none(crossings(counts(2, 0, 0), counts(0, 0, 1))));
  EXPECT_TRUE(none(crossings(counts(1, 0, 1), counts(1, 2, 0))));
  EXPECT_TRUE(none(crossings(counts(0, 0, 0), counts(0, 0, 0))));
  // One real crossing at +1 and one at -1: the number outside unchanged, each side's parity not.
  const auto both = crossings(counts(0, 1, 0), counts(1, 0, 0));
  EXPECT_TRUE(both.plus_one && both.minus_one && !both.complex_pair);
  const auto both_and_collision = crossings(counts(0, 0, 1), counts(1, 1, 0));
  EXPECT_TRUE(both_and_collision.plus_one && both_and_collision.minus_one &&
              !both_and_collision.complex_pair);
  // A collision beside +1 with one real crossing inwards there: one bifurcation, no pair's.
  for (const auto& [from, to] :
       {std::pair{counts(1, 0, 1), counts(2, 0, 0)}, std::pair{counts(2, 0, 0), counts(1, 0, 1)}}) {
    const auto c = crossings(from, to);
    EXPECT_TRUE(c.plus_one && !c.minus_one && !c.complex_pair);
  }
  const auto flip = crossings(counts(0, 1, 1), counts(0, 2, 0));
  EXPECT_TRUE(!flip.plus_one && flip.minus_one && !flip.complex_pair);
  // Crossings: a real one at +1, at -1, a pair; both ways.
  for (const bool out : {true, false}) {
    const auto c = [&](MultiplierCounts a, MultiplierCounts b) {
      return out ? crossings(a, b) : crossings(b, a);
    };
    const auto plus = c(counts(0, 0, 1), counts(1, 0, 1));
    EXPECT_TRUE(plus.plus_one && !plus.minus_one && !plus.complex_pair);
    const auto minus = c(counts(1, 0, 0), counts(1, 1, 0));
    EXPECT_TRUE(!minus.plus_one && minus.minus_one && !minus.complex_pair);
    const auto pair = c(counts(1, 1, 0), counts(1, 1, 1));
    EXPECT_TRUE(!pair.plus_one && !pair.minus_one && pair.complex_pair);
  }
}

// The same on a branch: in pure rolling with lift-off near 68.44 Hz (G = 100 MN/m^2) the
// unstable orbit's complex pair outside the circle (2.03 +- 1.23i) parts into two reals (3.82,
// 2.24) between two points. It was reported as a branch point and a Neimark-Sacker point at
// once, with "critical" multipliers of modulus 0.02. The one crossing in the range, the pair
// leaving the circle at 68.4724 Hz, is reported, with its multiplier on the circle.
TEST(Branch, APairThatPartsOutsideTheUnitCircleIsNoBifurcation) {
  const Branch b = frequency_branch(68.6, 68.2).b;
  // The collision happens between two points of the branch (else this tests nothing).
  const auto outside = [](const BranchPoint& p, bool complex) {
    int n = 0;
    for (const std::complex<double> m : p.floquet.multipliers)
      n += std::abs(m) > 1.5 && (std::abs(m.imag()) > 1e-6) == complex;
    return n;
  };
  bool collision = false;
  for (std::size_t i = 1; i < b.points.size(); ++i)
    collision =
        collision || (outside(b.points[i - 1], true) == 2 && outside(b.points[i - 1], false) == 0 &&
                      outside(b.points[i], true) == 0 && outside(b.points[i], false) == 2);
  ASSERT_TRUE(collision);
  int crossings = 0;
  for (const Bifurcation& x : b.bifurcations) {
    if (x.kind != BifurcationKind::branch_point && x.kind != BifurcationKind::period_doubling &&
        x.kind != BifurcationKind::neimark_sacker)
      continue;
    ++crossings;
    EXPECT_EQ(x.kind, BifurcationKind::neimark_sacker) << x.description;
    EXPECT_NEAR(x.parameter, 68.4724, 1e-3);
    EXPECT_NEAR(std::abs(x.multiplier), 1.0, 1e-3) << "at f = " << x.parameter;
  }
  EXPECT_EQ(crossings, 1);
}

// On the paper's log-spiral trough (k = 0.002, a = 0.601 m) at 25 Hz with mu = 0.7 a real
// multiplier passes -1 as the soil stiffens: the continuation locates the period doubling,
// shooting, started from rest on either side, finds a period-1 orbit below it and a period-2
// orbit above it, and the branch switched onto there is made of those period-2 orbits.
TEST(Branch, PeriodDoublingOnTheLogSpiralTrough) {
  const Case c = log_spiral_case();
  BranchOptions o;
  o.key = "soil.G";
  o.from = 100e6;
  o.to = 300e6;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.end, BranchEnd::reached_end) << b.message;
  ASSERT_EQ(b.bifurcations.size(), 1u);
  const Bifurcation& pd = b.bifurcations[0];
  EXPECT_EQ(pd.kind, BifurcationKind::period_doubling);
  // Located where the modulus passes 1 itself, not the edge 1 + 1e-6 of the band that counts a
  // multiplier as on the circle (2.8 kPa from it here, where |mu| moves by 3.5e-4 per MN/m^2);
  // its tolerance is that change of G (a multiplier is known to 1e-6), wider than the bisection's
  // bracket of 1e-6 of the range (200 Pa), which it was.
  EXPECT_NEAR(std::abs(pd.multiplier), 1.0, 3e-7);
  EXPECT_GT(pd.tolerance, 1000.0);
  EXPECT_LT(pd.tolerance, 10000.0);
  EXPECT_NEAR(pd.multiplier.real(), -1.0, 1e-3);
  const Result below = run_at(c, "soil.G", pd.parameter - 3e6),
               above = run_at(c, "soil.G", pd.parameter + 3e6);
  ASSERT_EQ(below.status, Status::steady_state);
  ASSERT_EQ(above.status, Status::steady_state);
  EXPECT_EQ(below.diagnostics.multiplicity, 1);
  EXPECT_EQ(above.diagnostics.multiplicity, 2);
  // Branch switching: the period-2 branch born there, stable, followed to the end of the range;
  // its orbits are the period-2 steady states shooting finds from rest.
  ASSERT_EQ(pd.child, 0);
  ASSERT_EQ(b.children.size(), 1u);
  const Branch& p2 = b.children[0];
  EXPECT_EQ(p2.multiplicity, 2);
  EXPECT_EQ(p2.end, BranchEnd::reached_end) << p2.message;
  ASSERT_GT(p2.points.size(), 10u);
  EXPECT_NEAR(p2.points.front().parameter, pd.parameter, 2e-3 * 200e6);  // starts 1e-3 beyond
  // (Away from the doubling: within about 1 MN/m^2 of it the orbits converge so slowly that
  // shooting from rest falls back and the transient runs out of periods, which is what the
  // continuation is for.)
  for (const std::size_t k : {p2.points.size() / 4, p2.points.size() / 2}) {
    const BranchPoint& p = p2.points[k];
    EXPECT_TRUE(p.stable()) << p.parameter;
    Case ck = c;
    set_field(ck, "soil.G", p.parameter);
    const Model model(ck);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state);
    ASSERT_EQ(r.diagnostics.multiplicity, 2) << p.parameter;
    const Metrics m = compute_metrics(model, r);
    EXPECT_NEAR(p.metrics.ddx_max, m.ddx_max, 1e-6 * m.ddx_max) << p.parameter;
    EXPECT_NEAR(p.metrics.area, m.area, 1e-6 * m.area) << p.parameter;
  }
}

// The same doubling met from the period-2 side: started at 140 MN/m^2 (shooting finds the
// period-2 orbit there) and followed down, the period-2 orbit shrinks onto the period-1 orbit at
// the doubling, where the branch of P^2 turns back through its own orbits shifted by a period. It
// was reported as a fold ("a stable and an unstable orbit meet", all orbits stable on both
// sides) and the branch climbed back out of the range, never reaching --to. Now: the doubling
// where the forward branch locates it, the end period_halved, and the period-1 branch from there
// to `to` as its child.
TEST(Branch, APeriodTwoBranchEndsWhereItShrinksOntoThePeriodOneOrbit) {
  const Case c = log_spiral_case();
  BranchOptions o;
  o.key = "soil.G";
  o.from = 140e6;
  o.to = 100e6;
  const Branch down = continue_branch(c, o);
  ASSERT_EQ(down.multiplicity, 2);
  EXPECT_EQ(down.end, BranchEnd::period_halved) << down.message;
  ASSERT_EQ(down.bifurcations.size(), 1u);
  const Bifurcation& at = down.bifurcations[0];
  EXPECT_EQ(at.kind, BifurcationKind::period_doubling) << at.description;
  std::swap(o.from, o.to);
  const Branch up = continue_branch(c, o);
  ASSERT_EQ(up.bifurcations.size(), 1u);
  const Bifurcation& pd = up.bifurcations[0];
  ASSERT_EQ(pd.kind, BifurcationKind::period_doubling);
  EXPECT_NEAR(at.parameter, pd.parameter, pd.tolerance);
  // The period-1 branch from there on down to 100 MN/m^2: its orbits are the up branch's.
  ASSERT_EQ(at.child, 0);
  ASSERT_EQ(down.children.size(), 1u);
  const Branch& p1 = down.children[0];
  EXPECT_EQ(p1.multiplicity, 1);
  EXPECT_EQ(p1.end, BranchEnd::reached_end) << p1.message;
  ASSERT_GT(p1.points.size(), 5u);
  EXPECT_EQ(p1.points.back().parameter, 100e6);  // the orbit at `to` itself
  const BranchPoint& last = p1.points.back();
  const Result r = run_at(c, "soil.G", last.parameter);
  ASSERT_EQ(r.status, Status::steady_state);
  EXPECT_EQ(r.diagnostics.multiplicity, 1);
  EXPECT_NEAR(last.floquet.max_modulus, r.floquet.max_modulus, 1e-3);
}

// The same turn where the bisection closes its bracket in the parameter before the orbit is close
// to the collapse (the parameter is quadratic in the arclength at the turn, the P residual
// linear): the vibratory drum on Table 2 soil of G = 20 MN/m^2 from 18 Hz up (`oscidrum continue
// examples/vibratory.toml --param roller.f --from 18 --to 26 --G 20 --static_moment 1.5`) turned
// at 25.736014 Hz with a P residual of 0.0063 against 0.041 at the last point, and was reported as
// a fold ("a stable and an unstable orbit meet"; stable on both sides) and retraced to 18 Hz.
// Now: the doubling where the period-1 branch meets it from above, and the period-1 orbit on.
TEST(Branch, APeriodTwoBranchTurningAtItsDoublingIsNoSaddleNode) {
  Case c = test::vibratory_lift_off_case(1.5, 20e6);
  set_field_text(c, "soil.input", "table2");
  BranchOptions o;
  o.key = "roller.f";
  o.from = 18.0;
  o.to = 26.0;
  const Branch up = continue_branch(c, o);
  ASSERT_EQ(up.multiplicity, 2);
  EXPECT_EQ(up.end, BranchEnd::period_halved) << up.message;
  ASSERT_FALSE(up.bifurcations.empty());
  for (const Bifurcation& b : up.bifurcations)
    EXPECT_NE(b.kind, BifurcationKind::fold) << b.parameter << ": " << b.description;
  const Bifurcation& at = up.bifurcations.back();
  ASSERT_EQ(at.kind, BifurcationKind::period_doubling) << at.description;
  ASSERT_EQ(up.children.size(), 1u);
  EXPECT_EQ(up.children[0].multiplicity, 1);
  EXPECT_EQ(up.children[0].end, BranchEnd::reached_end) << up.children[0].message;
  // The period-1 branch followed down from 27 Hz flips there.
  o.from = 27.0;
  o.to = 25.5;
  o.switch_depth = 0;
  const Branch down = continue_branch(c, o);
  ASSERT_EQ(down.multiplicity, 1);
  ASSERT_EQ(down.bifurcations.size(), 1u);
  const Bifurcation& pd = down.bifurcations[0];
  ASSERT_EQ(pd.kind, BifurcationKind::period_doubling);
  EXPECT_NEAR(at.parameter, pd.parameter, at.tolerance + pd.tolerance);
}

// A period-2 branch that meets the period-1 orbits at their period doubling without turning
// back there (the step lands on the period-1 orbits, which pass through the point): the
// vibratory drum on G = 20 MN/m^2 from its stable period-2 orbit at 20 Hz up over a fold at
// 21.98 Hz and down again went on from 21.45 Hz to 20 Hz as the flip-unstable period-1 orbits,
// labelled period 2 with the squares of their multipliers, the crossing read as a grazing. The
// branch ends at its last period-2 point.
TEST(Branch, APeriodTwoBranchDoesNotGoOnAsThePeriodOneOrbits) {
  Case c = test::vibratory_lift_off_case(1.5, 20e6);
  BranchOptions o;
  o.key = "roller.f";
  o.from = 20.0;
  o.to = 22.0;
  o.switch_depth = 0;
  const Branch b = continue_branch(c, o);
  ASSERT_EQ(b.multiplicity, 2);
  EXPECT_EQ(b.end, BranchEnd::period_halved) << b.message;
  // Below 21.45 Hz the points are the stable period-2 orbits the branch started on, not the
  // flip-unstable period-1 orbits, whose squared multipliers are above 1 there (1.0175 at
  // 21.45 Hz to 1.405 at 20 Hz).
  ASSERT_GT(b.points.size(), 10u);
  for (const BranchPoint& pt : b.points) {
    if (pt.parameter < 21.45) {
      EXPECT_LT(pt.floquet.max_modulus, 1.0) << pt.parameter;
    }
  }
  EXPECT_GT(b.points.back().parameter, 21.45);
  // From 17 Hz the period-1 branch switches onto the period-2 branches at both doublings; each
  // folds (subcritical) and returns to the doubling it started at, which it says (it said it
  // "left the range at roller.f = 17.2219 Hz", inside the range of 17 to 22 Hz).
  o.from = 17.0;
  o.switch_depth = 1;
  const Branch p1 = continue_branch(c, o);
  ASSERT_EQ(p1.children.size(), 2u);
  for (const Branch& child : p1.children) {
    EXPECT_EQ(child.end, BranchEnd::left_range);
    EXPECT_NE(child.message.find("turned back to the period doubling it was switched on at"),
              std::string::npos)
        << child.message;
  }
}

TEST(Branch, RefusesWhatCannotBeContinued) {
  const Case c;
  BranchOptions o;
  o.key = "soil.g";
  o.from = 1;
  o.to = 2;
  EXPECT_THROW(continue_branch(c, o), Error);  // unknown key
  o.key = "numerics.rtol";
  EXPECT_THROW(continue_branch(c, o), Error);  // a numerical setting
  o.key = "soil.nu";
  o.from = 0.2;
  o.to = 0.3;
  EXPECT_THROW(continue_branch(c, o), Error);  // no effect under soil.input = table2
  // Keys a case file keeps without effect (a warning there) are not varied: the branch was 23
  // equal orbits, exit 0.
  {
    Case rolling;
    rolling.contact.pure_rolling = true;
    BranchOptions mu = o;
    mu.key = "contact.mu";
    mu.from = 0.3;
    mu.to = 0.4;
    const auto message = [](const Case& k, const BranchOptions& b) {
      try {
        (void)continue_branch(k, b);
      } catch (const Error& e) {
        return std::string(e.what());
      }
      return std::string("no error");
    };
    EXPECT_NE(message(rolling, mu)
                  .find("contact.mu has no effect in this case: "
                        "contact.pure_rolling = true"),
              std::string::npos)
        << message(rolling, mu);
    BranchOptions frame = mu;
    frame.key = "roller.m_f";
    frame.from = 2000;
    frame.to = 3000;
    EXPECT_NE(message(c, frame).find("Appendix A transmissibility only"), std::string::npos)
        << message(c, frame);
    // Both ends valid, the values between not: mu_static -1 ("equal to mu") to 0.6 passes values
    // below mu = 0.5 (the branch failed at its start, "no tangent at the start", exit 1).
    BranchOptions friction = o;
    friction.key = "contact.mu_static";
    friction.from = -1.0;
    friction.to = 0.6;
    const std::string why = message(c, friction);
    EXPECT_NE(why.find("continue: contact.mu_static = -0.9999984, between from = -1 and to = "
                       "0.6 (--from, --to): the case is not valid there ("),
              std::string::npos)
        << why;
    EXPECT_NE(why.find("choose a range whose every value is valid"), std::string::npos) << why;
    friction.from = 0.5;  // mu_static from mu up: valid throughout
    friction.max_points = 2;
    EXPECT_EQ(message(c, friction), "no error");
  }
  o.key = "contact.mu";
  o.from = 0.5;
  o.to = 0.5;
  EXPECT_THROW(continue_branch(c, o), Error);  // an empty range
  o.to = -0.1;
  EXPECT_THROW(continue_branch(c, o), Error);  // outside the key's rule
  o.to = 0.3;
  o.initial_step = 0.0;
  EXPECT_THROW(continue_branch(c, o), Error);  // a step of 0
  // --step 0.1 above the default --max-step 0.05: the message names the flags and the values.
  o.initial_step = 0.1;
  try {
    (void)continue_branch(c, o);
    ADD_FAILURE() << "a first step above the largest was taken";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("initial_step 0.1, max_step 0.05"), std::string::npos) << m;
    EXPECT_NE(m.find("needs a --max-step at least as large"), std::string::npos) << m;
  }
  // Metrics' harmonics the samples cannot resolve: refused, not NaN metrics at every point.
  o.initial_step = BranchOptions{}.initial_step;
  Case coarse;
  coarse.numerics.samples_per_period = 16;
  try {
    continue_branch(coarse, o);
    ADD_FAILURE() << "harmonics 10 at 16 samples per period accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the samples' Nyquist limit; got 10"), std::string::npos)
        << e.what();
    EXPECT_EQ(e.key(), "harmonics");
  }
  // Each refusal names what it is about (Python's error.key): the option, or the varied key
  // with the value received.
  const auto key_of = [&](const Case& cc, const BranchOptions& oo) {
    try {
      continue_branch(cc, oo);
    } catch (const Error& e) {
      return std::pair{e.key(), e.value()};
    }
    return std::pair{std::string("accepted"), 0.0};
  };
  BranchOptions depth = o;
  for (int d : {-1, 6}) {
    depth.switch_depth = d;
    EXPECT_EQ(key_of(c, depth), std::pair(std::string("switch_depth"), double(d)));
  }
  // roller.unbalance = 0 is "M0 as roller.M0 gives it": M0 jumps there (the start failed with
  // "no tangent at the start").
  BranchOptions unbalance = o;
  unbalance.key = "roller.unbalance";
  unbalance.from = 0.0;
  unbalance.to = 0.3;
  EXPECT_EQ(key_of(c, unbalance), std::pair(std::string("roller.unbalance"), 0.0));
  BranchOptions outside = o;
  outside.to = -0.1;
  EXPECT_EQ(key_of(c, outside), std::pair(std::string("contact.mu"), -0.1));
}

}  // namespace
}  // namespace oscidrum
