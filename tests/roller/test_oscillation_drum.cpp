// The oscillation drum as a roller component (src/roller/oscillation_drum.cpp): its right-hand
// side is the one the Jacobians differentiate, its events do what docs/model.md section 6 says,
// its section projection and its Jacobian agree, its samples give back the state, and its
// gross-slip test reads the slip the driving torque pushes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "equations/event_logic.hpp"
#include "equations/jacobian.hpp"
#include "roller/oscillation_drum.hpp"
#include "tolerances.hpp"

namespace oscidrum::detail {
namespace {

using Dyn = Dynamics<OscillationDrum>;

Case driven_case() {
  Case c;
  c.MMd = 0.05 * c.roller.M0;
  return c;
}

State random_state(std::mt19937& rng, const Model& model) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State q;
  q.delta = 0.3 * u(rng);
  q.x_A = 1e-3 * u(rng);
  q.s_A = model.initial_state().s_A * (1.0 + 0.3 * u(rng));
  q.phi = u(rng);
  q.ddelta = 50.0 * u(rng);
  q.dx_A = 0.2 * u(rng);
  q.ds_A = 0.05 * u(rng);
  q.dphi = 50.0 * u(rng);
  return q;
}

// The flow integrates rhs(); shooting differentiates phase_rhs(): the same numbers, bit for bit.
TEST(OscillationDrum, RightHandSideIsTheOneTheJacobiansDifferentiate) {
  const Model model(driven_case());
  const Dyn dyn(model, 2.0 * model.nu());
  std::mt19937 rng(42);
  for (int i = 0; i < 50; ++i) {
    const State q = random_state(rng, model);
    for (Phase phase : {Phase::stick, Phase::slip_positive, Phase::slip_negative}) {
      Dyn::Vector f;
      dyn.rhs(phase, 0.001 * i, q.to_array(), f);
      const Vec8 g = phase_rhs(model, 0.001 * i, q, phase, 2.0 * model.nu());
      for (int k = 0; k < 8; ++k) EXPECT_EQ(f[k], g[k]) << to_string(phase) << " " << k;
    }
  }
}

// The trough is open above: a state whose point on the trough is past its vertical tangent,
// |delta| >= pi/2, is not one the model follows (contact_lost, saying why), in every phase; up to
// it the state is valid (the paper's rolling cases reach |delta| = 0.45 rad).
TEST(OscillationDrum, APointPastTheTroughsVerticalTangentHasLeftTheTrough) {
  const Model model(driven_case());
  const Dyn dyn(model, 2.0 * model.nu());
  State q = model.initial_state();
  for (Phase phase : {Phase::stick, Phase::slip_positive, Phase::slip_negative}) {
    for (double delta : {-1.5, 0.45, 1.5}) {
      q.delta = delta;
      std::string why;
      FlowStop stop = FlowStop::reached;
      EXPECT_FALSE(dyn.invalid(phase, q.to_array(), 0.1, &why, &stop)) << delta << ": " << why;
    }
    for (double delta : {-1.58, 0.5 * std::numbers::pi, 2.0, 7.0}) {
      q.delta = delta;
      std::string why;
      FlowStop stop = FlowStop::reached;
      ASSERT_TRUE(dyn.invalid(phase, q.to_array(), 0.1, &why, &stop)) << delta;
      EXPECT_EQ(stop, FlowStop::contact_lost);
      EXPECT_NE(why.find("passed the trough's vertical tangent (|delta| >= pi/2)"),
                std::string::npos)
          << why;
    }
  }
}

TEST(OscillationDrum, ContactEventIsTerminal) {
  const Model model(driven_case());
  const Dyn dyn(model, 0.0);
  const Dyn::Switch sw =
      dyn.apply(Phase::stick, kEventContact, 0.5, model.initial_state().to_array());
  EXPECT_TRUE(sw.terminal);
  EXPECT_EQ(sw.kind, EventKind::contact_lost);
  EXPECT_EQ(sw.stop, FlowStop::contact_lost);
  EXPECT_NE(sw.message.find("contact lost at t = 0.5"), std::string::npos) << sw.message;
}

// Stick -> slip: the side of the cone names the slip's sign (T > 0 at mu N - T = 0: slip-), the
// state carries over with one coefficient, and the slip velocity function starts at zero.
TEST(OscillationDrum, ConeEventsStartSlipOfTheirSide) {
  const Model model(driven_case());
  const Dyn dyn(model, 0.0);
  std::mt19937 rng(7);
  const State q = random_state(rng, model);
  for (int which : {kEventConeNegative, kEventConePositive}) {
    const Dyn::Switch sw = dyn.apply(Phase::stick, which, 0.1, q.to_array());
    EXPECT_FALSE(sw.terminal);
    EXPECT_EQ(sw.kind, EventKind::stick_to_slip);
    EXPECT_EQ(sw.to, which == kEventConeNegative ? Phase::slip_negative : Phase::slip_positive);
    EXPECT_EQ(sw.after, q.to_array());
    EXPECT_TRUE(sw.fresh[kEventSlipVelocity]);
  }
}

// Slip -> stick or reversal at v_rel = 0 (docs/model.md section 6): at a state where the stick
// solution stays in the cone, stick, phi' set to f5 delta' (12), and the cone function of the
// old slip's side starts at zero.
TEST(OscillationDrum, SlipEndDecidesByTheRate) {
  const Model model(driven_case());
  const Dyn dyn(model, 0.0);
  std::mt19937 rng(3);
  int sticks = 0, reversals = 0;
  for (int i = 0; i < 200; ++i) {
    State q = random_state(rng, model);
    q.dphi = kinematics(model.geometry(), q.delta).f5 * q.ddelta;  // v_rel = 0
    for (Phase phase : {Phase::slip_positive, Phase::slip_negative}) {
      const Dyn::Switch sw = dyn.apply(phase, kEventSlipVelocity, 0.01 * i, q.to_array());
      const int s = slip_sign(phase);
      const bool stick = stick_margin_rate(model, 0.01 * i, q, -s) >= 0.0;
      if (stick) {
        ++sticks;
        EXPECT_EQ(sw.kind, EventKind::slip_to_stick);
        EXPECT_EQ(sw.to, Phase::stick);
        EXPECT_TRUE(sw.fresh[s > 0 ? kEventConePositive : kEventConeNegative]);
        EXPECT_EQ(sw.after[7], kinematics(model.geometry(), q.delta).f5 * q.ddelta);
      } else if (sw.reversal) {
        ++reversals;
        EXPECT_EQ(sw.kind, EventKind::slip_reversal);
        EXPECT_EQ(sw.to, s > 0 ? Phase::slip_negative : Phase::slip_positive);
        EXPECT_TRUE(sw.fresh[kEventSlipVelocity]);
      }
    }
  }
  EXPECT_GT(sticks, 0);
  EXPECT_GT(reversals, 0);
}

// The section projection (stick: phi' = f5 delta') and its Jacobian by central differences; off
// stick it is the identity (no Jacobian).
TEST(OscillationDrum, SectionProjectionAndItsJacobian) {
  Case c = driven_case();
  c.trough.shape = trough_shape(0.002, 0.601);  // the spiral: f5 depends on delta
  const Model model(c);
  const Dyn dyn(model, 0.0);
  std::mt19937 rng(11);
  const State q = random_state(rng, model);
  const Dyn::Vector z = q.to_array();
  EXPECT_EQ(dyn.consistent(z, Phase::slip_positive), z);
  EXPECT_FALSE(dyn.section_jacobian(z, Phase::slip_negative).has_value());
  const auto G = dyn.section_jacobian(z, Phase::stick);
  ASSERT_TRUE(G.has_value());
  const Dyn::Vector p = dyn.consistent(z, Phase::stick);
  EXPECT_EQ(p[7], kinematics(model.geometry(), z[0]).f5 * z[4]);
  for (int j = 0; j < 8; ++j) {
    const double h = 1e-6 * (1.0 + std::abs(z[j]));
    Dyn::Vector a = z, b = z;
    a[j] += h;
    b[j] -= h;
    const Dyn::Vector pa = dyn.consistent(a, Phase::stick), pb = dyn.consistent(b, Phase::stick);
    for (int i = 0; i < 8; ++i)
      EXPECT_NEAR((*G)(i, j), (pa[i] - pb[i]) / (2 * h),
                  test::kFiniteDifference * (1.0 + std::abs((*G)(i, j))))
          << i << ", " << j;
  }
}

// A sample row gives back the state it was taken at (phi' of stick: the rolling condition).
TEST(OscillationDrum, SamplesGiveBackTheState) {
  const Model model(driven_case());
  const Dyn dyn(model, 2.0 * model.nu());
  std::mt19937 rng(5);
  Samples s;
  const State q = random_state(rng, model);
  dyn.sample(0.01, q.to_array(), Phase::slip_negative, s);
  dyn.sample(0.02, q.to_array(), Phase::stick, s);
  EXPECT_EQ(Dyn::sampled_state(s, 0), q.to_array());
  EXPECT_EQ(s.phase[0], Phase::slip_negative);
  EXPECT_EQ(s.v_rel[0], slip_velocity(model, q));
  State rolled = q;
  rolled.dphi = kinematics(model.geometry(), q.delta).f5 * q.ddelta;
  EXPECT_EQ(Dyn::sampled_state(s, 1), rolled.to_array());
  EXPECT_EQ(s.v_rel[1], 0.0);
  EXPECT_EQ(s.torque[1], model.torque(0.02));
  // The excitation's angle: the moment is M0 sin(alpha) + MMd (5, 6), alpha = nu t in [0, 2 pi).
  const double M0 = oscillation_moment(model.parameters().roller);
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_GE(s.alpha[j], 0.0);
    EXPECT_LT(s.alpha[j], 2.0 * M_PI);
    EXPECT_NEAR(s.torque[j], M0 * std::sin(s.alpha[j]) + model.parameters().MMd, 1e-9 * M0);
  }
}

// Gross slip: only a slip in the direction the driving torque pushes counts; how fast it spins
// up is the growth of phi' against the slip (v_rel = r f5 delta' - r phi' (13)).
TEST(OscillationDrum, PushedSlipIsTheSlipTheDrivingTorquePushes) {
  Case c;
  const double hold = c.contact.mu * c.roller.P0 * c.roller.r;  // mu W r, W = P0
  c.MMd = 0.5 * hold;
  const Model model(c);
  const Dyn dyn(model, 0.0);
  const Dyn::Vector x = model.initial_state().to_array();
  double h = 0.0;
  // MMd > 0 pushes phi' up, i.e. v_rel down: slip-.
  EXPECT_EQ(dyn.pushed_slip(Phase::slip_negative, x, &h), -1);
  EXPECT_NEAR(h, hold, 1e-9 * hold);
  EXPECT_EQ(dyn.pushed_slip(Phase::slip_positive, x, &h), 0);
  EXPECT_EQ(dyn.pushed_slip(Phase::stick, x, &h), 0);
  c.MMd = 0.0;
  const Model free(c);
  EXPECT_EQ(Dyn(free, 0.0).pushed_slip(Phase::slip_negative, x, &h), 0);
  Dyn::Vector later = x;
  later[Dyn::kSpin] += 3.0;  // phi' grew by 3 rad/s over 3 periods while slipping with s = -1
  EXPECT_EQ(Dyn::spin_up(later, x, -1, 3), 1.0);
  EXPECT_EQ(Dyn::spin_up(later, x, 1, 3), -1.0);
}

// The samples, the event functions and the excitation evaluated in lanes (util/lanes.hpp) equal
// those of one point at a time to the bit: stick, both slips, the smooth phase of a regularised
// law (its coefficient depends on v_rel: the slip equations go point by point), the spiral and
// the circle, angles inside and outside the small-angle series (|delta| > 0.5 in one lane), and
// counts that leave lanes unused.
std::vector<Case> lane_cases() {
  std::vector<Case> cases(5, driven_case());
  cases[1].trough.shape = LogSpiralTrough{0.05, 0.62};
  cases[2].contact.law = FrictionChoice::regularised;
  cases[3].numerics.start_ramp_periods = 2;      // the excitation ramped in: scalar torque
  cases[4].roller.type = RollerType::vibratory;  // a centre load, no oscillating moment
  cases[4].roller.static_moment = 2.0;
  return cases;
}

std::vector<Dyn::Vector> lane_states(const Model& model, int n) {
  std::mt19937 rng(20261207);
  std::vector<Dyn::Vector> x;
  for (int i = 0; i < n; ++i) {
    State q = random_state(rng, model);
    if (i == 5) q.delta = 0.7;  // outside the series of sincos_small
    x.push_back(q.to_array());
  }
  return x;
}

TEST(OscillationDrum, SamplesInLanesEqualOneByOne) {
  for (const Case& c : lane_cases()) {
    const Model model(c);
    const Dyn dyn(model, 30.0);
    const auto x = lane_states(model, 19);
    std::vector<double> t;
    for (int i = 0; i < 19; ++i) t.push_back(1e-3 * i + (i == 3 ? 0.0 : 0.01));
    for (Phase phase : {Phase::stick, Phase::slip_positive, Phase::slip_negative, Phase::smooth}) {
      if (!has_phase(model.friction(), phase)) continue;
      for (int count : {19, 8, 3, 1}) {
        Samples one, many;
        for (int i = 0; i < count; ++i) dyn.sample(t[i], x[i], phase, one);
        dyn.sample_many(t.data(), x.data(), count, phase, many);
        ASSERT_EQ(many.size(), static_cast<std::size_t>(count));
#define OSCIDRUM_SAME(type, name, unit, label, description)                     \
  for (int i = 0; i < count; ++i)                                               \
    EXPECT_EQ(std::memcmp(&one.name[i], &many.name[i], sizeof(one.name[i])), 0) \
        << #name << " sample " << i << " of " << count << " in phase " << static_cast<int>(phase);
        OSCIDRUM_SAMPLE_COLUMNS(OSCIDRUM_SAME)
#undef OSCIDRUM_SAME
      }
    }
  }
}

TEST(OscillationDrum, EventFunctionsInLanesEqualOneByOne) {
  for (const Case& c : lane_cases()) {
    const Model model(c);
    const Dyn dyn(model, 30.0);
    const auto x = lane_states(model, 11);
    for (Phase phase : {Phase::stick, Phase::slip_positive, Phase::slip_negative, Phase::smooth}) {
      if (!has_phase(model.friction(), phase)) continue;
      std::vector<EventValues> e(11);
      std::vector<double> N(11);
      dyn.events_many(phase, x.data(), 11, e.data(), N.data());
      for (int i = 0; i < 11; ++i) {
        double N_one = 0.0;
        const EventValues one = dyn.events(phase, x[i], &N_one);
        EXPECT_EQ(std::memcmp(&N_one, &N[i], sizeof(double)), 0) << i;
        for (int k = 0; k < kEventCount; ++k)
          EXPECT_EQ(std::memcmp(&one[k], &e[i][k], sizeof(double)), 0)
              << "function " << k << " at state " << i << " in phase " << static_cast<int>(phase);
      }
    }
  }
}

TEST(OscillationDrum, ExcitationInLanesEqualsOneByOne) {
  for (const Case& c : lane_cases()) {
    const Model model(c);
    // t = 0, times inside a start ramp (case 3), late times (2^20 periods on), uneven spacing.
    std::vector<double> t;
    for (int i = 0; i < 21; ++i) t.push_back(i * 0.0123 * model.period());
    t.push_back(0.0);
    for (int i = 0; i < 9; ++i) t.push_back((1048576.0 + 0.37 * i) * model.period());
    const int n = static_cast<int>(t.size());
    std::vector<double> MM(t.size()), angle(t.size());
    std::vector<CentreLoad> load(t.size());
    model.excitation(t.data(), n, MM.data(), angle.data(), load.data());
    for (int i = 0; i < n; ++i) {
      const double MM_one = model.torque(t[i]), angle_one = model.excitation_angle(t[i]);
      const CentreLoad load_one = model.centre_load(t[i]);
      EXPECT_EQ(std::memcmp(&MM_one, &MM[i], sizeof(double)), 0) << i << ": " << MM_one;
      EXPECT_EQ(std::memcmp(&angle_one, &angle[i], sizeof(double)), 0) << i << ": " << angle_one;
      EXPECT_EQ(std::memcmp(&load_one.x, &load[i].x, sizeof(double)), 0) << i;
      EXPECT_EQ(std::memcmp(&load_one.z, &load[i].z, sizeof(double)), 0) << i;
    }
  }
}

}  // namespace
}  // namespace oscidrum::detail
