// The vibratory drum (roller.type = vibratory, docs/model.md section 14): the paper's drum
// equations with a rotating unbalance force on the drum centre instead of the oscillation moment.
// Checks that do not trust the implementation: the steady state of a directed (vertical) exciter
// in permanent contact against the closed-form frequency response of the linear system it
// reduces to; the flight Jacobian with the force against finite differences; shooting against
// the transient method; the energy balance of a steady period; and the parameters' rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <random>
#include <utility>

#include "drivers/modes.hpp"
#include "oscidrum/oscidrum.hpp"
#include "roller/unilateral_checks.hpp"
#include "roller/unilateral_drum.hpp"
#include "tolerances.hpp"

namespace oscidrum::detail {
namespace {

using U = Dynamics<UnilateralDrum>;

// A vibratory drum of the paper's roller (m = 1851 kg, kd, cd, P0) with the static moment
// m_u e_u = 1.5 kg m at 30 Hz (F0 = 53 kN, about 1.2 P0), on soil given by its coefficients.
Case vibratory_case(Exciter exciter) {
  Case c;
  c.roller.type = RollerType::vibratory;
  c.roller.exciter = exciter;
  c.roller.static_moment = 1.5;
  c.roller.f = 30.0;
  c.soil.input = SoilInput::coefficients;
  c.numerics.method = SteadyMethod::shooting;
  return c;
}

// Directed vertical exciter, MMd = 0, permanent contact, linear (Kelvin-Voigt) soil. At
// delta = 0 the trough's roll curve is at its bottom (x_roll = z_roll = 0, sin delta = 0), the
// horizontal balance (30) has no load (F_x = 0) and stays at rest (x_A = 0), so the stick
// equation (32) gives delta'' = 0: the drum never leaves delta = 0. What remains is (31) with
// z_M = s_A (14): m s_A'' + (csv + cd) s_A' + (ksv + kd) s_A = W + F0 sin(nu t): the soil's and
// the buffers' springs and dashpots act in parallel on the drum's vertical motion (the buffers
// measured from z_ref = 0, the paper's). Its steady state is W / (ksv + kd) plus
// Im(F0 e^{i nu t} / (ksv + kd - m nu^2 + i nu (csv + cd))).
TEST(VibratoryDrum, DirectedExciterInPermanentContactIsTheLinearFrequencyResponse) {
  for (double ksv : {40e6, 66.3e6, 150e6}) {
    Case c = vibratory_case(Exciter::vertical);
    // F0 = 18 kN: the soil's dynamic force (up to 29 kN) stays below its static 41-44 kN.
    c.roller.static_moment = 0.5;
    c.soil.ksv = ksv;
    c.soil.csv = 263e3 * std::sqrt(ksv / 66.3e6);
    c.numerics.rtol = 1e-12;
    c.numerics.atol = 1e-15;
    c.numerics.steady_tol = 1e-12;
    const Model model(c);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state) << r.message;
    EXPECT_EQ(r.diagnostics.contact_mode, "permanent contact");
    const double m = c.roller.m, nu = model.nu(), F0 = c.roller.static_moment * nu * nu;
    const double K = ksv + c.roller.kd, C = c.soil.csv + c.roller.cd;
    const std::complex<double> H = 1.0 / std::complex<double>(K - m * nu * nu, nu * C);
    const double amplitude = F0 * std::abs(H);
    double delta_max = 0.0, x_max = 0.0, err = 0.0, err_acc = 0.0;
    for (std::size_t i = 0; i < r.samples.size(); ++i) {
      const double t = r.samples.t[i];
      const std::complex<double> e = F0 * H * std::exp(std::complex<double>(0.0, nu * t));
      delta_max = std::max(delta_max, std::abs(r.samples.delta[i]));
      x_max = std::max(x_max, std::abs(r.samples.x_A[i]));
      err = std::max(err, std::abs(r.samples.s_A[i] - (model.W() / K + e.imag())));
      err = std::max(err, std::abs(r.samples.z_M[i] - r.samples.s_A[i]));
      err_acc = std::max(err_acc, std::abs(r.samples.ddz_M[i] + nu * nu * e.imag()));
    }
    // Zero in exact arithmetic; shooting's Newton steps leave round-off of the order of eps times
    // the section's other components (seen: 4e-38), far below any motion.
    EXPECT_LE(delta_max, 1e-14 * amplitude / c.roller.r) << "ksv " << ksv;
    EXPECT_LE(x_max, 1e-14 * amplitude) << "ksv " << ksv;
    // Seen: 1.4e-12 to 2.1e-12 of the amplitude (4.7e-12 for the acceleration) at rtol 1e-12.
    EXPECT_LE(err, 1e-8 * amplitude) << "ksv " << ksv << ": amplitude " << amplitude;
    EXPECT_LE(err_acc, 1e-8 * nu * nu * amplitude) << "ksv " << ksv;
    EXPECT_GT(amplitude, 1e-4);  // a motion the comparison can see (0.1 mm and more)
    // The Kb-type stiffness, the soil's vertical force in phase with the drum's displacement over
    // that displacement (docs/outputs.md), is the soil spring: F_v = ksv s_A + csv s_A' with
    // z_M = s_A. On the samples (a DFT of sinusoids: exact to round-off) and the dense output.
    EXPECT_NEAR(compute_metrics(r).kb, ksv, 1e-9 * ksv);
    EXPECT_NEAR(compute_metrics(model, r).kb, ksv, 1e-9 * ksv);
  }
}

// The flight phase with the unbalance force, against finite differences (the contact phases'
// Jacobians with the force: tests/equations/test_jacobian.cpp).
TEST(VibratoryDrum, FlightJacobianAgainstFiniteDifferences) {
  std::mt19937 rng(29);
  for (Exciter e : {Exciter::circular, Exciter::circular_reversed, Exciter::vertical}) {
    Case c = vibratory_case(e);
    c.contact.unilateral = true;
    const Model model(c);
    const U u(model, 2.0 * model.nu());
    std::uniform_real_distribution<double> v(-1.0, 1.0);
    for (int i = 0; i < 10; ++i) {
      const double d0 = model.W() / (model.ksv() + model.kd());
      const U::Vector y = {0.05 * v(rng), 1e-4 * v(rng),         d0 * (1.0 + 0.5 * v(rng)),
                           v(rng),        2e-4 * (1.0 + v(rng)), 5.0 * v(rng),
                           0.1 * v(rng),  0.05 * v(rng),         5.0 * v(rng),
                           0.1 * v(rng)};
      const double t = 0.0031 * i;
      const U::Matrix J = u.jacobian(Phase::flight, t, y);
      expect_jacobian(
          J, y,
          [&](const U::Vector& x) {
            U::Vector f;
            u.rhs(Phase::flight, t, x, f);
            return f;
          },
          "exciter " + std::to_string(static_cast<int>(e)));
      // The force is in the flight equations: z_M'' (20) with N = 0 differs from the drum
      // without it by F_z / m.
      Case plain = c;
      plain.roller.type = RollerType::oscillation;
      const Model plain_model(plain);
      const U paper_drum(plain_model, 2.0 * plain_model.nu());
      EXPECT_NEAR(
          u.quantities(t, y, Phase::flight)[1] - paper_drum.quantities(t, y, Phase::flight)[1],
          (model.centre_load(t).z - model.W()) / model.m(), 1e-9 * model.F0() / model.m());
      EXPECT_NEAR(
          u.quantities(t, y, Phase::flight)[0] - paper_drum.quantities(t, y, Phase::flight)[0],
          model.centre_load(t).x / model.m(), 1e-9 * model.F0() / model.m());
    }
  }
}

// Shooting and the paper's transient method find the same steady state of a circular exciter
// (Coulomb friction mu = 0.5) in permanent contact, and with lift-off at a larger static moment.
TEST(VibratoryDrum, ShootingAndTransientAgree) {
  for (bool unilateral : {false, true}) {
    Case c = vibratory_case(Exciter::circular);
    c.contact.unilateral = unilateral;
    if (!unilateral) c.roller.static_moment = 0.4;  // keeps contact
    const Result shot = simulate(c);
    c.numerics.method = SteadyMethod::transient;
    const Result trans = simulate(c);
    ASSERT_EQ(shot.status, Status::steady_state) << shot.message;
    ASSERT_EQ(trans.status, Status::steady_state) << trans.message;
    EXPECT_EQ(shot.diagnostics.method, SteadyMethod::shooting) << shot.diagnostics.fallback;
    EXPECT_EQ(shot.diagnostics.contact_mode, trans.diagnostics.contact_mode);
    EXPECT_EQ(shot.diagnostics.contact_mode,
              unilateral ? "periodic lift-off" : "permanent contact");
    // The literature's names (docs/model.md section 14).
    EXPECT_EQ(shot.diagnostics.operating_mode,
              unilateral ? "partial uplift" : "continuous contact");
    EXPECT_EQ(trans.diagnostics.operating_mode, shot.diagnostics.operating_mode);
    const Metrics a = compute_metrics(shot), b = compute_metrics(trans);
    const double tol = 2e-7;  // the transient's distance from the orbit (steady_tol 1e-8)
    EXPECT_NEAR(a.ddx_max, b.ddx_max, tol * std::abs(b.ddx_max));
    EXPECT_NEAR(a.ddz_max, b.ddz_max, tol * std::abs(b.ddz_max));
    EXPECT_NEAR(a.area, b.area, tol * std::abs(b.area));
    EXPECT_NEAR(a.flight_fraction, b.flight_fraction, tol);
  }
}

// A directed vertical exciter with flight, MMd = 0: the motion is symmetric, so T vanishes with
// N at each lift-off and the friction cone closes exactly where the contact opens. The drum
// switches from stick to slip there with N already at 0 in slip, and must lift off at once: the
// slip's lift-off function, at or below zero after the switch, fires at the switch (before, it
// never fired, and the drum slipped on with N < 0, pulling the soil with up to 11 kN, which
// started a horizontal motion that never settled: max_periods_reached). Both methods find the
// symmetric steady state (delta = x_A = 0 to round-off), with N >= 0 throughout, and agree.
TEST(VibratoryDrum, DirectedExciterWithFlightLiftsOffWhereTheConeCloses) {
  for (double G : {25e6, 50e6}) {
    Case c = vibratory_case(Exciter::vertical);
    c.contact.unilateral = true;
    c.contact.mu = 0.5;
    c.roller.static_moment = 0.9;
    c.soil.input = SoilInput::table2;
    c.soil.G = G;
    const Result shot = simulate(c);
    c.numerics.method = SteadyMethod::transient;
    const Result trans = simulate(c);
    for (const Result* r : {&shot, &trans}) {
      ASSERT_EQ(r->status, Status::steady_state) << "G " << G << ": " << r->message;
      EXPECT_EQ(r->diagnostics.contact_mode, "periodic lift-off");
      // Seen: 666-683 N at G = 25 MN/m^2 (before: -11 kN).
      EXPECT_GE(r->diagnostics.min_N, 0.0) << "G " << G;
      double delta = 0.0, x_A = 0.0, s_A = 0.0;
      for (std::size_t i = 0; i < r->samples.size(); ++i) {
        delta = std::max(delta, std::abs(r->samples.delta[i]));
        x_A = std::max(x_A, std::abs(r->samples.x_A[i]));
        s_A = std::max(s_A, std::abs(r->samples.s_A[i]));
      }
      // Seen: delta 4e-24 rad, x_A 3e-26 m against s_A 1.3 mm (before: 1e-9 rad, 1e-12 m).
      EXPECT_LE(delta * c.roller.r, 1e-14 * s_A) << "G " << G;
      EXPECT_LE(x_A, 1e-14 * s_A) << "G " << G;
    }
    // Seen: 2 transient periods and 3 Newton steps; the transient method 13 periods.
    EXPECT_EQ(shot.diagnostics.method, SteadyMethod::shooting) << shot.diagnostics.fallback;
    EXPECT_LT(trans.diagnostics.periods_simulated, 100);
    const Metrics a = compute_metrics(shot), b = compute_metrics(trans);
    const Metrics shot_dense = compute_metrics(Model(c), shot);
    const double tol = 2e-7;  // the transient's distance from the orbit (steady_tol 1e-8)
    EXPECT_NEAR(a.ddz_max, b.ddz_max, tol * std::abs(b.ddz_max));
    EXPECT_NEAR(a.ddz_min, b.ddz_min, tol * std::abs(b.ddz_min));
    EXPECT_NEAR(a.flight_fraction, b.flight_fraction, tol);
    // x_M'' is round-off (seen: 1e-22 m/s^2): its phase and ratios are NaN, not numbers
    // (before: A2/A1 0.23, THD 2.6e5).
    for (const Metrics* m : {&a, &b, &shot_dense}) {
      EXPECT_TRUE(std::isnan(m->psi_xz)) << m->psi_xz;
      EXPECT_TRUE(std::isnan(m->ddx_A2_A1)) << m->ddx_A2_A1;
      EXPECT_TRUE(std::isnan(m->ddx_A3_A1)) << m->ddx_A3_A1;
      EXPECT_TRUE(std::isnan(m->ddx_thd)) << m->ddx_thd;
      EXPECT_TRUE(std::isfinite(m->ddz_A2_A1) && m->ddz_A2_A1 > 0.0) << m->ddz_A2_A1;
      // No oscillating torque: phi lags nothing (before: -1.96 pi, the phase of 1e-26 rad).
      EXPECT_TRUE(std::isnan(m->phi_lag)) << m->phi_lag;
      // What plots and tables read to show x_M'' as absent rather than scale it up.
      const AbsentSignals absent = absent_signals(m->ddx_harmonics, m->ddz_harmonics);
      EXPECT_TRUE(absent.ddx);
      EXPECT_FALSE(absent.ddz);
    }
  }
}

// A drum thrown almost out of its trough (circular exciter at 2.5 kg m and 40 Hz on stiff soil:
// F0 = 158 kN, 3.5 times its weight; the circle's clearance R - r is 6 mm): in flight the point of
// the trough nearest to it passed the trough's vertical tangent, and it landed there, on soil above
// it, and went on orbiting the circle (delta grew by 2 pi every three periods: the run ended as
// max_periods_reached "converging", or as "chaotic"; at 30 Hz and mu 0.3 as a "steady state" of
// period 2 with delta between -7.5 and -5.2 rad, gone round the circle). The run stops where the
// model stops holding.
TEST(VibratoryDrum, ADrumThrownPastTheTroughsVerticalTangentHasLeftTheTrough) {
  for (Exciter e : {Exciter::circular, Exciter::circular_reversed}) {
    for (const auto& [f, mu] : {std::pair{40.0, 0.6}, std::pair{30.0, 0.3}}) {
      Case c = vibratory_case(e);
      c.contact.unilateral = true;
      c.contact.mu = mu;
      c.roller.static_moment = 2.5;
      c.roller.f = f;
      c.soil.input = SoilInput::table2;
      c.soil.G = 70e6;
      const Result r = simulate(c);
      EXPECT_EQ(r.status, Status::contact_lost) << f << " Hz: " << r.message;
      EXPECT_NE(r.message.find("passed the trough's vertical tangent"), std::string::npos)
          << r.message;
    }
  }
}

// Energy over a steady period with lift-off (circular exciter, Coulomb friction): the unbalance
// force's work on the drum centre, F . M' (the static load W does no net work over a period),
// equals what the buffers' and the soil's dashpots dissipate plus the friction's work in slip, |T
// v_rel| (13), (27). Integrated on the dense output by 8-point Gauss-Legendre quadrature on every
// piece; the centre's velocity is the chart's, M' = A' + (r f5 - g) delta' t - g' n (section 13).
TEST(VibratoryDrum, EnergyBalanceOverAPeriodWithLiftOff) {
  Case c = vibratory_case(Exciter::circular);
  c.contact.unilateral = true;
  c.numerics.rtol = 1e-10;
  const Model model(c);
  const Result r = simulate(model);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  ASSERT_GT(compute_metrics(model, r).flight_fraction, 0.01);
  const PeriodEnergy energy = energy_over_period(model, r);
  ASSERT_TRUE(energy.reached);
  EXPECT_GT(energy.in, 0.0);
  EXPECT_GT(energy.friction, 0.0);  // the drum slips (seen: 1.7 J of 226 J, balance to 4e-11)
  // The orbit repeats to steady_tol and the quadrature is exact to ~1e-12 on smooth pieces (as
  // for the oscillation drum with flight, tests/roller/test_unilateral_drum.cpp).
  EXPECT_NEAR(energy.out / energy.in, 1.0, 1e-6)
      << "in " << energy.in << " J against " << energy.out << " J (friction " << energy.friction
      << " J)";
}

// The samples' column alpha (outputs.hpp) is the angle of the force the model applies: at every
// sample of a steady state, for each exciter, the centre load's vertical part is
// W + F0 sin(alpha) and its horizontal part F0 cos(alpha) (circular), -F0 cos(alpha)
// (circular_reversed) or 0 (vertical), with alpha in [0, 2 pi) and alpha - nu t a multiple of
// 2 pi: the convention `analyze --unbalance-col` reads (record.hpp, unbalance_phase).
TEST(VibratoryDrum, TheSampledExcitationAngleIsTheUnbalanceForcesAngle) {
  for (Exciter e : {Exciter::circular, Exciter::circular_reversed, Exciter::vertical}) {
    SCOPED_TRACE("exciter " + std::to_string(static_cast<int>(e)));
    Case c = vibratory_case(e);
    c.contact.unilateral = true;  // F0 = 1.2 P0 lifts the drum off: samples in flight and contact
    const Model model(c);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state) << r.message;
    const Samples& s = r.samples;
    ASSERT_TRUE(std::count(s.phase.begin(), s.phase.end(), Phase::flight) > 0);
    ASSERT_EQ(s.alpha.size(), s.t.size());
    const double F0 = c.roller.static_moment * model.nu() * model.nu();
    const double sign = e == Exciter::circular ? 1.0 : e == Exciter::circular_reversed ? -1.0 : 0.0;
    for (std::size_t j = 0; j < s.size(); ++j) {
      const double a = s.alpha[j];
      ASSERT_GE(a, 0.0);
      ASSERT_LT(a, 2.0 * M_PI);
      const double turns = (model.nu() * s.t[j] - a) / (2.0 * M_PI);
      // ASSERT: the first sample that breaks it is enough to see.
      ASSERT_NEAR(turns, std::round(turns), 1e-11) << j;
      const CentreLoad L = model.centre_load(s.t[j]);
      ASSERT_NEAR(L.z - model.W(), F0 * std::sin(a), 1e-9 * F0) << j;
      ASSERT_NEAR(L.x, sign * F0 * std::cos(a), 1e-9 * F0) << j;
    }
  }
}

// The Kb-type stiffness (docs/outputs.md) is what the soil stiffness formula of vibratory rollers'
// compaction control estimates from the drum's motion alone: by (20) at the fundamental,
// kb = nu^2 (m + m_u e_u cos(phi) / A) - kd, A the amplitude of z_M's fundamental and phi its lag
// behind the unbalance force F0 sin(nu t). On a steady state with lift-off (the contact force is 0
// for a third of the period). The identity is exact pointwise; kb is the DFT of the sampled contact
// force, which jumps at landing (the massless soil's velocities jump), so its fundamental carries
// the aliasing of a jump, O(1 / samples per period): the difference shrinks as the sampling
// refines (seen: 2.0e-4 at 1024, 1.4e-5 at 8192 samples per period).
TEST(VibratoryDrum, SoilStiffnessIsTheDrumEquationsEstimate) {
  std::vector<double> differences;
  for (int samples : {1024, 8192}) {
    Case c = vibratory_case(Exciter::circular);
    c.contact.unilateral = true;
    c.numerics.samples_per_period = samples;
    const Model model(c);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state) << r.message;
    const Metrics m = compute_metrics(r);
    ASSERT_GT(m.flight_fraction, 0.1);
    const std::vector<Harmonic> z =
        harmonics(r.samples.z_M, r.sample_periods, r.frequency, r.samples.t.front(), 1);
    const double nu = model.nu();
    const double estimate =
        nu * nu * (c.roller.m + c.roller.static_moment * std::cos(z[1].phase) / z[1].amplitude) -
        c.roller.kd;
    EXPECT_GT(m.kb, 0.0);
    differences.push_back(std::abs(m.kb - estimate) / m.kb);
    // run's kb integrates F_v over the dense output (no aliasing); z_M, smooth up to its
    // acceleration's jump, aliases at O(samples^-3): the identity holds to 1e-8 (seen 4e-10).
    const double dense = compute_metrics(model, r).kb;
    EXPECT_NEAR(dense, estimate, 1e-8 * dense) << samples;
  }
  EXPECT_LT(differences[0], 1e-3);
  EXPECT_LT(differences[1], differences[0] / 4.0) << differences[0] << " " << differences[1];
  EXPECT_LT(differences[1], 1e-4);
}

// mu_required = max |T| / N has no bound where the drum lifts off (N falls to 0): NaN then, from
// the samples and from the dense output alike (before, 9307 from the samples and 57478 from the
// dense output for examples/vibratory.toml: numbers of where the points fell). In permanent
// contact it is a number.
TEST(VibratoryDrum, NoRequiredFrictionWhereTheDrumLiftsOff) {
  Case c = vibratory_case(Exciter::circular);
  c.contact.unilateral = true;
  const Model model(c);
  const Result r = simulate(model);
  ASSERT_EQ(r.status, Status::steady_state) << r.message;
  ASSERT_GT(compute_metrics(model, r).flight_fraction, 0.1);
  EXPECT_TRUE(std::isnan(compute_metrics(r).mu_required));
  EXPECT_TRUE(std::isnan(compute_metrics(model, r).mu_required));
  c.contact.unilateral = false;
  c.roller.static_moment = 0.5;  // F0 = 18 kN, well below the static load: no lift-off
  const Model held(c);
  const Result contact = simulate(held);
  ASSERT_EQ(contact.status, Status::steady_state) << contact.message;
  const double mu = compute_metrics(held, contact).mu_required;
  EXPECT_TRUE(std::isfinite(mu));
  EXPECT_GT(mu, 0.0);
  EXPECT_NEAR(compute_metrics(contact).mu_required, mu, 1e-3 * mu);
}

// The operating modes by the literature's names (docs/model.md section 14) along a sequence of
// stiffening soils (Appendix B soil, G = 10, 50, 300 MN/m^2; m_u e_u = 1.5 kg m at 30 Hz,
// unilateral contact): continuous contact, partial uplift (lift-off every period, period 1),
// double jump (period 2, with the f/2 subharmonic the RMV reads: two lift-offs in one period and
// one in the next, whose contact_mode said "lift-off every period, repeating every 2 periods").
TEST(VibratoryDrum, OperatingModesFromContinuousContactToDoubleJump) {
  struct Expected {
    double G, static_moment;
    const char* mode;
    int multiplicity;
    const char* contact;
  };
  for (const Expected& e :
       {Expected{10e6, 0.9, "continuous contact", 1, "permanent contact"},
        Expected{50e6, 1.5, "partial uplift", 1, "periodic lift-off"},
        Expected{300e6, 1.5, "double jump", 2, "3 lift-offs every 2 periods"}}) {
    Case c = vibratory_case(Exciter::circular);
    c.contact.unilateral = true;
    c.soil.input = SoilInput::modulus;
    c.soil.G = e.G;
    c.roller.static_moment = e.static_moment;
    const Result r = simulate(c);
    ASSERT_EQ(r.status, Status::steady_state) << r.message;
    EXPECT_EQ(r.diagnostics.operating_mode, e.mode) << e.G;
    EXPECT_EQ(r.diagnostics.multiplicity, e.multiplicity) << e.G;
    EXPECT_EQ(r.diagnostics.contact_mode, e.contact) << e.G;
    const Metrics m = compute_metrics(Model(c), r);
    if (e.multiplicity == 2) {
      EXPECT_GT(m.rmv, 0.01) << e.G;  // the f/2 subharmonic of a period-2 motion
    } else {
      EXPECT_EQ(m.rmv, 0.0) << e.G;
    }
  }
  // The oscillation drum has no such name.
  EXPECT_EQ(simulate(Case{}).diagnostics.operating_mode, "");
}

TEST(VibratoryDrum, OperatingModeNamesFromTheRunsDiagnostics) {
  // The table of docs/model.md section 14: from contact_mode, the multiplicity and, without a
  // periodic steady state, the motion examined after numerics.max_periods. "Chaotic" only where
  // that examination found a positive largest Lyapunov exponent.
  const auto name = [](const char* contact, int p, const char* motion) {
    Diagnostics d;
    d.contact_mode = contact;
    d.multiplicity = p;
    d.motion = motion;
    return detail::operating_mode(RollerType::vibratory, d);
  };
  EXPECT_EQ(name("permanent contact", 1, ""), "continuous contact");
  EXPECT_EQ(name("periodic lift-off", 1, ""), "partial uplift");
  EXPECT_EQ(name("lift-off every 2 periods", 2, ""), "double jump");
  EXPECT_EQ(name("3 lift-offs every 2 periods", 2, ""), "double jump");
  EXPECT_EQ(name("lift-off every period, repeating every 2 periods", 2, ""), "double jump");
  EXPECT_EQ(name("lift-off every 3 periods", 3, ""), "lift-off with period 3");
  EXPECT_EQ(name("aperiodic", 0, "chaotic"), "chaotic");
  EXPECT_EQ(name("aperiodic", 0, "quasi_periodic"), "quasi-periodic");
  EXPECT_EQ(name("aperiodic", 0, "converging"), "");  // no steady state found, and no verdict
  EXPECT_EQ(name("aperiodic", 0, "undecided"), "");
  EXPECT_EQ(name("", 0, ""), "");
  Diagnostics d;
  d.contact_mode = "periodic lift-off";
  EXPECT_EQ(detail::operating_mode(RollerType::oscillation, d), "");
}

// A study with continuation finds what each case finds from rest (Table 2 soils, G = 40 ... 70
// MN/m^2, the example's roller, partial uplift throughout), with warm starts from neighbours'
// sections in flight. Shooting from them once converged on G >= 55 to a spurious orbit in flight
// for the whole period: a flight state at or inside the trough never fired its landing. The flow
// now refuses a state inside the trough and lands one on it at once (FlowStop::
// inconsistent_state, docs/vibratory.md), so Newton's iterates cannot close into such an orbit.
TEST(VibratoryDrum, ContinuationAlongTheSoilsAgreesWithTheStartFromRest) {
  std::vector<Case> cases;
  for (double G = 40e6; G <= 70e6; G += 5e6) {
    Case c = vibratory_case(Exciter::circular);
    c.roller.static_moment = 0.9;
    c.soil.input = SoilInput::table2;
    c.soil.G = G;
    c.contact.unilateral = true;
    cases.push_back(c);
  }
  StudyOptions options;
  options.threads = 1;
  const std::vector<CaseOutcome> out = run_study(cases, options);
  ASSERT_EQ(out.size(), cases.size());
  int warm = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    ASSERT_EQ(out[i].result.status, Status::steady_state) << out[i].result.message;
    const Result alone = simulate(cases[i]);
    ASSERT_EQ(alone.status, Status::steady_state) << alone.message;
    EXPECT_EQ(out[i].result.diagnostics.operating_mode, "partial uplift") << cases[i].soil.G;
    EXPECT_EQ(alone.diagnostics.operating_mode, "partial uplift") << cases[i].soil.G;
    const Metrics a = compute_metrics(Model(cases[i]), alone);
    EXPECT_LT(out[i].metrics.flight_fraction, 0.5) << cases[i].soil.G;
    EXPECT_NEAR(out[i].metrics.flight_fraction, a.flight_fraction, 1e-6) << cases[i].soil.G;
    EXPECT_NEAR(out[i].metrics.kb, a.kb, 1e-6 * a.kb) << cases[i].soil.G;
    warm += out[i].result.diagnostics.warm_start == 1;
  }
  EXPECT_GE(warm, 3);  // half or more continue their neighbour (3 of the 6 that can)
}

// The parameters: the static moment must be positive for a vibratory drum, and the keys of the
// other roller have no effect.
TEST(VibratoryDrum, ParametersAndTheirRules) {
  Case c;
  EXPECT_THROW(set_field(c, "roller.static_moment", -1.0), Error);
  c.roller.type = RollerType::vibratory;
  try {
    (void)Model(c);
    ADD_FAILURE() << "a vibratory drum without a static moment was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.key(), "roller.static_moment");
  }
  c.roller.static_moment = 1.5;
  EXPECT_NO_THROW((void)Model(c));
  EXPECT_FALSE(key_in_effect(c, "roller.M0"));
  EXPECT_FALSE(key_in_effect(c, "roller.unbalance"));
  EXPECT_TRUE(key_in_effect(c, "roller.static_moment"));
  EXPECT_TRUE(key_in_effect(c, "roller.exciter"));
  EXPECT_FALSE(key_in_effect(Case{}, "roller.static_moment"));
  EXPECT_FALSE(key_in_effect(Case{}, "roller.exciter"));
  set_field_text(c, "roller.exciter", "vertical");
  EXPECT_EQ(c.roller.exciter, Exciter::vertical);
  set_field_text(c, "roller.type", "oscillation");
  EXPECT_EQ(c.roller.type, RollerType::oscillation);
  // The load on the centre: F0 = m_u e_u nu^2 in the exciter's direction, W added below; no
  // moment (MMd only).
  c = vibratory_case(Exciter::circular);
  c.MMd = 100.0;
  const Model model(c);
  const double nu = model.nu(), F0 = 1.5 * nu * nu, t = 0.0123;
  EXPECT_NEAR(model.F0(), F0, test::kIdentity * F0);
  EXPECT_NEAR(model.centre_load(t).x, F0 * std::cos(nu * t), test::kIdentity * F0);
  EXPECT_NEAR(model.centre_load(t).z, model.W() + F0 * std::sin(nu * t), test::kIdentity * F0);
  EXPECT_EQ(model.torque(t), 100.0);
  c.roller.exciter = Exciter::circular_reversed;
  EXPECT_NEAR(Model(c).centre_load(t).x, -F0 * std::cos(nu * t), test::kIdentity * F0);
  c.roller.exciter = Exciter::vertical;
  EXPECT_EQ(Model(c).centre_load(t).x, 0.0);
  // The oscillation drum: the paper's W, no force.
  const Model paper{Case{}};
  EXPECT_EQ(paper.centre_load(t).x, 0.0);
  EXPECT_EQ(paper.centre_load(t).z, paper.W());
  EXPECT_EQ(paper.F0(), 0.0);
}

// The Evib-type modulus (docs/outputs.md) of the vibratory drum of examples/vibratory.toml
// (m_u e_u = 0.9 kg m at 30 Hz, mu = 0.5, unilateral contact) on Appendix B soils of increasing
// G, through continuous contact and partial uplift: finite, positive and increasing with G. Not
// E = 2 G (1 + nu) of the soil: the soil is a Kelvin-Voigt pair, not Lundberg's half-space (the
// values are in docs/vibratory.md). NaN for a soil given by its coefficients (no Poisson's
// ratio), for the oscillation drum, and from compute_metrics(result), which has no drum geometry.
TEST(VibratoryDrum, VibrationModulusGrowsWithTheSoil) {
  Case c = vibratory_case(Exciter::circular);
  c.roller.static_moment = 0.9;
  c.contact.unilateral = true;
  c.soil.input = SoilInput::modulus;
  double previous = 0.0;
  for (double G : {10e6, 25e6, 50e6, 100e6}) {
    c.soil.G = G;
    const Model model(c);
    const Result r = simulate(model);
    ASSERT_EQ(r.status, Status::steady_state) << G << ": " << r.message;
    const Metrics m = compute_metrics(model, r);
    EXPECT_TRUE(std::isfinite(m.evib)) << G;
    EXPECT_GT(m.evib, previous) << G << " (" << r.diagnostics.contact_mode << ")";
    previous = m.evib;
    EXPECT_TRUE(std::isnan(compute_metrics(r).evib));
  }
  c.soil = Soil{};  // Table 2 at 25 MN/m^2: nu = 0.3
  EXPECT_GT(compute_metrics(Model(c), simulate(Model(c))).evib, 0.0);
  c.soil.input = SoilInput::coefficients;
  EXPECT_TRUE(std::isnan(compute_metrics(Model(c), simulate(Model(c))).evib));
  const Case paper;
  EXPECT_TRUE(std::isnan(compute_metrics(Model(paper), simulate(Model(paper))).evib));
}

// Evib converges as the tolerances tighten, as the other metrics do: its end points (the least
// z_M, the greatest F_v) are extrema of the curve, located on the pieces' interpolants. Read at the
// nearest of 33 points a step, each carried an error of the first order in their spacing, and
// evib moved by 2e-4 between tolerances, the default no closer to rtol 1e-12 than rtol 1e-9
// (continuous contact at G = 10 MN/m^2 and partial uplift at 25 MN/m^2).
TEST(VibratoryDrum, VibrationModulusConvergesWithTheTolerance) {
  Case c = vibratory_case(Exciter::circular);
  c.roller.static_moment = 0.9;
  c.contact.unilateral = true;
  c.soil.input = SoilInput::modulus;
  for (double G : {10e6, 25e6}) {
    c.soil.G = G;
    std::vector<double> evib;
    for (double rtol : {1e-8, 1e-10, 1e-12}) {
      Case ck = c;
      ck.numerics.rtol = rtol;
      ck.numerics.atol = 1e-3 * rtol;
      const Model model(ck);
      const Result r = simulate(model);
      ASSERT_EQ(r.status, Status::steady_state) << G << ": " << r.message;
      evib.push_back(compute_metrics(model, r).evib);
    }
    EXPECT_NEAR(evib[0], evib[2], 1e-7 * evib[2]) << G;
    EXPECT_NEAR(evib[1], evib[2], 1e-7 * evib[2]) << G;
  }
}

}  // namespace
}  // namespace oscidrum::detail
