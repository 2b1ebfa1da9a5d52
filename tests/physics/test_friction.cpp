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
