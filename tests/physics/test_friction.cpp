// Friction laws (oscidrum/friction.hpp) and the static/kinetic law end to end: the cone uses
// mu_static, the slip phase mu; the velocity jump at slip start keeps the drum's velocities and
// satisfies the slip coupling (39) with the kinetic coefficient.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "equations/event_logic.hpp"
#include "oscidrum/oscidrum.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

TEST(Friction, ContactChoosesTheLaw) {
  Contact c;
  EXPECT_TRUE(std::holds_alternative<CoulombFriction>(friction_law(c)));  // mu_static = -1
  c.mu_static = c.mu;
  EXPECT_TRUE(std::holds_alternative<CoulombFriction>(friction_law(c)));
  c.mu_static = 0.6;
  const FrictionLaw law = friction_law(c);
  ASSERT_TRUE(std::holds_alternative<StaticKineticFriction>(law));
  EXPECT_EQ(cone_coefficient(law), 0.6);
  EXPECT_EQ(slip_coefficient(law, 1, 0.0).m, 0.5);
  EXPECT_EQ(slip_coefficient(law, -1, 3.0).m, -0.5);
  c.pure_rolling = true;
  EXPECT_TRUE(never_slips(friction_law(c)));
  EXPECT_TRUE(std::isinf(cone_coefficient(friction_law(c))));
}

TEST(Friction, ContactChoosesTheRegularisedLaw) {
  Contact c;
  c.law = FrictionChoice::regularised;
  c.v_eps = 0.02;
  const FrictionLaw law = friction_law(c);
  ASSERT_TRUE(std::holds_alternative<RegularisedCoulomb>(law));
  EXPECT_EQ(friction_phases(law), FrictionPhases::smooth);
  EXPECT_EQ(initial_phase(law), Phase::smooth);
  EXPECT_TRUE(has_phase(law, Phase::smooth));
  EXPECT_FALSE(has_phase(law, Phase::stick));
  EXPECT_EQ(flow_phase(law, Phase::slip_negative), Phase::smooth);
  EXPECT_EQ(largest_slip_coefficient(law), 0.5);
  c.pure_rolling = true;  // pure rolling wins: no friction limit at all
  EXPECT_TRUE(never_slips(friction_law(c)));
  // The Coulomb laws never are in the smooth phase.
  EXPECT_FALSE(has_phase(CoulombFriction{0.5}, Phase::smooth));
  EXPECT_EQ(flow_phase(CoulombFriction{0.5}, Phase::slip_negative), Phase::slip_negative);
  EXPECT_EQ(initial_phase(CoulombFriction{0.0}), Phase::slip_positive);  // frictionless
}

// m = mu tanh(v / v_eps) with the derivatives the smooth slip equations and their Jacobian use,
// against central differences; odd in v, bounded by mu, and Coulomb's s mu away from v = 0.
TEST(Friction, RegularisedCoefficientAndItsDerivatives) {
  const RegularisedCoulomb law{0.5, 0.01};
  for (double v : {-0.05, -0.01, -0.003, 0.0, 0.002, 0.01, 0.04}) {
    const double h = 1e-6;
    const SlipCoefficient c = law.slip(0, v), p = law.slip(0, v + h), m = law.slip(0, v - h);
    EXPECT_NEAR(c.dm_dv, (p.m - m.m) / (2 * h), test::kFiniteDifference * 0.5 / 0.01) << v;
    EXPECT_NEAR(c.d2m_dv2, (p.dm_dv - m.dm_dv) / (2 * h),
                test::kFiniteDifference * 0.5 / (0.01 * 0.01))
        << v;
    EXPECT_EQ(law.slip(0, -v).m, -c.m);
    EXPECT_LE(std::abs(c.m), 0.5);
  }
  EXPECT_NEAR(law.slip(0, 1.0).m, 0.5, 1e-15);                        // 100 v_eps: Coulomb's law
  EXPECT_EQ(apparent_phase(law, Phase::smooth, 0.03), Phase::stick);  // creep: |v| <= 4 v_eps
  EXPECT_EQ(apparent_phase(law, Phase::smooth, 0.05), Phase::slip_positive);
  EXPECT_EQ(apparent_phase(law, Phase::smooth, -0.05), Phase::slip_negative);
  EXPECT_EQ(apparent_phase(CoulombFriction{0.5}, Phase::slip_negative, 0.0), Phase::slip_negative);
}

// Without friction (mu = 0) the slip direction exerts nothing and the flow never switches it:
// samples show the sign of v_rel (they showed the flow's arbitrary slip+ against v_rel < 0).
TEST(Friction, SlipWithoutFrictionShowsTheSignOfTheSlipVelocity) {
  const CoulombFriction none{0.0};
  EXPECT_TRUE(frictionless(none));
  EXPECT_FALSE(frictionless(CoulombFriction{0.5}));
  EXPECT_FALSE(frictionless(PureRolling{}));
  EXPECT_FALSE(frictionless(RegularisedCoulomb{0.0, 0.01}));  // smooth: its own labels
  EXPECT_TRUE(apparent_varies(none, Phase::slip_positive));
  EXPECT_FALSE(apparent_varies(none, Phase::stick));
  EXPECT_FALSE(apparent_varies(CoulombFriction{0.5}, Phase::slip_positive));
  EXPECT_EQ(apparent_phase(none, Phase::slip_positive, -0.2), Phase::slip_negative);
  EXPECT_EQ(apparent_phase(none, Phase::slip_negative, 0.2), Phase::slip_positive);
  EXPECT_EQ(apparent_phase(none, Phase::slip_negative, 0.0), Phase::slip_negative);
  EXPECT_EQ(apparent_phase(CoulombFriction{0.5}, Phase::slip_positive, -0.2), Phase::slip_positive);
}

TEST(Friction, RegularisedLawRefusesAStaticCoefficient) {
  Case c;
  c.contact.law = FrictionChoice::regularised;
  c.contact.mu_static = 0.6;
  try {
    Model m(c);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("contact.mu_static must be -1"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(set_field(c, "contact.v_eps", 0.0), Error);
  EXPECT_THROW(set_field(c, "contact.v_eps", -1e-3), Error);
}

// As v_eps -> 0 the regularised law tends to Coulomb's: the steady state's metrics approach the
// Coulomb case's at the rate O(v_eps) (the creep next to each stick phase moves the drum by
// ~v_eps per unit time), and the apparent stick fraction approaches the stick fraction.
TEST(Friction, RegularisedLawConvergesToCoulombAsVepsVanishes) {
  Case c;
  c.MMd = 0.05 * c.roller.M0;
  const Result coulomb_run = simulate(c);
  ASSERT_EQ(coulomb_run.status, Status::steady_state) << coulomb_run.message;
  const Metrics coulomb = compute_metrics(coulomb_run);
  c.contact.law = FrictionChoice::regularised;
  std::vector<double> area_error, peak_error, a3_error;
  for (double v_eps : {1e-2, 1e-3, 1e-4}) {
    c.contact.v_eps = v_eps;
    const Result r = simulate(c);
    ASSERT_EQ(r.status, Status::steady_state) << r.message;
    EXPECT_EQ(r.diagnostics.switches, 0);  // one smooth phase: no events
    const Metrics m = compute_metrics(r);
    area_error.push_back(std::abs(m.area - coulomb.area) / coulomb.area);
    peak_error.push_back(std::abs(m.ddx_max - coulomb.ddx_max) / coulomb.ddx_max);
    a3_error.push_back(std::abs(m.ddx_harmonics[3].amplitude - coulomb.ddx_harmonics[3].amplitude) /
                       coulomb.ddx_harmonics[3].amplitude);
    if (v_eps == 1e-4) {
      EXPECT_NEAR(m.stick_fraction, coulomb.stick_fraction, 0.01);
      EXPECT_NEAR(m.slip_positive_fraction, coulomb.slip_positive_fraction, 0.01);
    }
  }
  for (std::size_t i = 1; i < area_error.size(); ++i) {
    // First order: each tenfold smaller v_eps cuts the error by about ten (5 to 20).
    EXPECT_GT(area_error[i - 1] / area_error[i], 5.0) << i;
    EXPECT_LT(area_error[i - 1] / area_error[i], 20.0) << i;
    EXPECT_GT(a3_error[i - 1] / a3_error[i], 5.0) << i;
    EXPECT_LT(peak_error[i], peak_error[i - 1]) << i;
  }
  EXPECT_LT(area_error.back(), 1e-3);
  EXPECT_LT(a3_error.back(), 1e-3);
}

// Without a driving torque the circular trough is mirror-symmetric (a half period later the
// motion is mirrored) for the regularised law too: x_M'' has only odd harmonics, z_M'' only
// even ones.
TEST(Friction, RegularisedLawKeepsTheMirrorSymmetry) {
  Case c;
  c.contact.law = FrictionChoice::regularised;
  c.contact.v_eps = 1e-3;
  const Result r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  const Metrics m = compute_metrics(r);
  const double ax = m.ddx_harmonics[1].amplitude, az = m.ddz_harmonics[2].amplitude;
  for (int n : {2, 4}) EXPECT_LT(m.ddx_harmonics[n].amplitude, 1e-6 * ax) << n;
  for (int n : {1, 3}) EXPECT_LT(m.ddz_harmonics[n].amplitude, 1e-6 * az) << n;
  EXPECT_NEAR(m.slip_positive_fraction, m.slip_negative_fraction, 1e-3);
}

TEST(Friction, StaticBelowKineticIsRejectedNamingTheField) {
  Case c;
  c.contact.mu_static = 0.4;  // < mu = 0.5
  try {
    Model m(c);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("contact.mu_static must be >= contact.mu"),
              std::string::npos)
        << e.what();
  }
  c.contact.mu_static = -0.5;  // only -1 means "equal to mu"
  EXPECT_THROW(Model{c}, Error);
  EXPECT_THROW(set_field(c, "contact.mu_static", -2.0), Error);
}

TEST(Friction, EqualCoefficientsGiveTheCoulombResultExactly) {
  Case a;
  a.soil = table2_soil(25e6);
  a.MMd = 0.05 * a.roller.M0;
  Case b = a;
  b.contact.mu_static = a.contact.mu;
  const Metrics ma = compute_metrics(simulate(a)), mb = compute_metrics(simulate(b));
  EXPECT_EQ(ma.area, mb.area);
  EXPECT_EQ(ma.ddx_max, mb.ddx_max);
}

// At the start of slip with mu_static > mu, the soil's velocities jump so that (39) holds with
// the kinetic coefficient, while x_M', z_M' (17) and phi' stay continuous, and the drum slips in
// the direction of the new phase. Checked at every stick -> slip switch of a real trajectory.
TEST(Friction, SlipStartJumpKeepsTheDrumVelocitiesAndSatisfiesTheCoupling) {
  Case c;
  c.soil = table2_soil(25e6);
  c.MMd = 0.05 * c.roller.M0;
  c.contact.mu_static = 0.6;
  const Model model(c);
  struct Starts : FlowObserver {
    std::vector<std::pair<State, State>> jumps;
    std::vector<int> signs;
    bool on_event(const Event& e, const State& before, const State& after) override {
      if (e.kind == EventKind::stick_to_slip) {
        jumps.emplace_back(before, after);
        signs.push_back(static_cast<int>(e.to));
      }
      return true;
    }
  } starts;
  Flow flow(model);
  flow.reset(0.0, model.initial_state(), initial_phase(model));
  ASSERT_EQ(flow.advance(20 * model.period(), &starts), FlowStop::reached);
  ASSERT_GE(starts.jumps.size(), 20u);
  const Accelerations none{};
  for (std::size_t i = 0; i < starts.jumps.size(); ++i) {
    const auto& [q, r] = starts.jumps[i];
    const int s = starts.signs[i];
    // Before: at the static cone, |T| = mu_static N.
    const ContactForces f0 = contact_forces(model, q), f1 = contact_forces(model, r);
    EXPECT_NEAR(std::abs(f0.T), 0.6 * f0.N, 1e-9 * model.W());
    // After: T = -s mu N (39) with the kinetic coefficient.
    EXPECT_NEAR(f1.T, -s * 0.5 * f1.N, 1e-9 * model.W());
    EXPECT_NEAR(slip_constraint_residual(model, r, s), 0.0, 1e-9 * model.W());
    const DrumMotion before = drum_motion(model, q, none), after = drum_motion(model, r, none);
    EXPECT_NEAR(after.dx_M, before.dx_M, test::kIdentity);
    EXPECT_NEAR(after.dz_M, before.dz_M, test::kIdentity);
    EXPECT_EQ(r.dphi, q.dphi);
    EXPECT_GT(s * slip_velocity(model, r), 0.0);
  }
  EXPECT_EQ(flow.counters().inconsistent_slip_ends, 0);
  // With one coefficient nothing jumps.
  Case one = c;
  one.contact.mu_static = -1.0;
  const Model m1(one);
  const State q = starts.jumps.front().first;
  const SlipStart same = decide_slip_start(m1, q, starts.signs.front());
  EXPECT_TRUE(same.consistent);
  EXPECT_EQ(same.state.to_array(), q.to_array());
}

// A larger static coefficient widens the cone: the drum sticks longer, and the run reaches its
// steady state with every switch consistent.
TEST(Friction, StaticAboveKineticSticksLonger) {
  Case c;
  c.soil = table2_soil(25e6);
  const Metrics coulomb = compute_metrics(simulate(c));
  c.contact.mu_static = 0.6;
  const Result r = simulate(c);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  const Metrics sk = compute_metrics(r);
  EXPECT_GT(sk.stick_fraction, coulomb.stick_fraction + 0.01);
  EXPECT_EQ(r.diagnostics.inconsistent_slip_ends, 0);
}

}  // namespace
}  // namespace oscidrum
