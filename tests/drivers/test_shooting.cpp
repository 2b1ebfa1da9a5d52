// Tests of the shooting driver (src/drivers/shooting.cpp) and the variational equations along the
// flow (src/flow/monodromy.cpp): the monodromy matrix against a finite-difference Jacobian of the
// period map (across stick/slip switches), the decay of the transient against the largest Floquet
// multiplier, and the agreement of the two steady-state methods.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "drivers/shooting.hpp"
#include "flow/monodromy.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

constexpr int kPeriodic[7] = {0, 1, 2, 4, 5, 6, 7};

// Shooting is opt-in (numerics.method; the transient is the default): these cases ask for it.
Case stick_slip_case() {
  Case c;  // G = 25 MN/m^2 (Table 2), mu = 0.5, circle R = 0.606 m
  c.MMd = 0.05 * c.roller.M0;
  c.numerics.method = SteadyMethod::shooting;
  return c;
}

Case pure_rolling_case() {
  Case c;
  c.contact.pure_rolling = true;
  c.numerics.method = SteadyMethod::shooting;
  return c;
}

State project(const Model& model, State q, Phase phase) {
  if (phase == Phase::stick) q.dphi = kinematics(model.geometry(), q.delta).f5 * q.ddelta;
  return q;
}

// The monodromy from the variational equations equals the central-difference Jacobian of the
// period map at the orbit. Tight integration tolerances make the period map smooth enough for
// differences: rtol 1e-11 leaves noise ~1e-11 of each range in P, i.e. ~1e-7 after dividing by
// the step of 1e-4 of the range; the truncation error is ~1e-8 of the curvature.
void check_monodromy(Case c, bool expect_switches) {
  c.numerics.rtol = 1e-11;
  c.numerics.atol = 1e-14;
  const Model model(c);
  Flow flow(model);
  flow.reset(0.0, model.initial_state(), initial_phase(model));
  const detail::ShootingOutcome shot = detail::shoot_periodic_orbit(flow, {});
  ASSERT_TRUE(shot.converged) << shot.message;
  const double T = model.period();

  detail::MonodromyObserver mono(model, flow.options().baumgarte, T / 64.0);
  flow.reset(shot.t0, shot.orbit, shot.phase);
  ASSERT_EQ(flow.advance(shot.t0 + T, &mono), FlowStop::reached);
  if (expect_switches) {
    EXPECT_GE(mono.switches().size(), 2u);
  } else {
    EXPECT_TRUE(mono.switches().empty());
  }
  detail::Mat8 phi = mono.phi();
  if (shot.phase == Phase::stick) phi = phi * detail::jump_jacobian(model, shot.orbit, true, 0);

  auto period_map = [&](const State& z) {
    flow.reset(shot.t0, project(model, z, shot.phase), shot.phase);
    EXPECT_EQ(flow.advance(shot.t0 + T), FlowStop::reached);
    return flow.state().to_array();
  };
  const auto z0 = shot.orbit.to_array();
  double largest = 0.0;
  Eigen::Matrix<double, 7, 7> M, fd;
  for (int j = 0; j < 7; ++j) {
    const int cj = kPeriodic[j];
    const double h = 1e-4 * shot.scale[cj];
    auto zp = z0, zm = z0;
    zp[cj] += h;
    zm[cj] -= h;
    const auto Pp = period_map(State::from_array(zp)), Pm = period_map(State::from_array(zm));
    for (int i = 0; i < 7; ++i) {
      const int ci = kPeriodic[i];
      // Scaled: the response of component i in its range to a unit-range change of j.
      fd(i, j) = (Pp[ci] - Pm[ci]) / (2.0 * h) * shot.scale[cj] / shot.scale[ci];
      M(i, j) = phi(ci, cj) * shot.scale[cj] / shot.scale[ci];
      largest = std::max(largest, std::abs(fd(i, j)));
    }
  }
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j)
      EXPECT_NEAR(M(i, j), fd(i, j), 1e-5 * largest) << "entry " << i << ", " << j;
}

TEST(Shooting, MonodromyIsTheJacobianOfThePeriodMapAcrossSwitches) {
  check_monodromy(stick_slip_case(), true);
}

TEST(Shooting, MonodromyIsTheJacobianOfThePeriodMapInPureRolling) {
  check_monodromy(pure_rolling_case(), false);
}

// Period-to-period change of the transient from rest, one value per period.
std::vector<double> transient_changes(Case c) {
  c.numerics.method = SteadyMethod::transient;
  std::vector<double> changes;
  simulate(c, [&](int, double change) {
    changes.push_back(change);
    return true;
  });
  return changes;
}

// The transient decays like |lambda_max|^n. The dominant multipliers here are a complex pair, so
// the change oscillates within its envelope; the envelope is the largest change over a window of
// 8 periods (about two oscillations at these arguments, ~1.5-1.8 rad per period), so each
// window's value is within a factor ~2 of the envelope, and over n periods the rate is off by at
// most log(2)/n of itself.
void check_decay(const Case& c, int n1, int n2) {
  const Result shot = simulate(c);
  ASSERT_EQ(shot.status, Status::steady_state) << shot.message;
  ASSERT_EQ(shot.diagnostics.method, SteadyMethod::shooting);
  const double lambda = shot.floquet.max_modulus;
  const std::vector<double> changes = transient_changes(c);
  ASSERT_GT(static_cast<int>(changes.size()), n2 + 8);
  auto envelope = [&](int n) { return *std::max_element(&changes[n], &changes[n] + 8); };
  const double rate = std::pow(envelope(n2) / envelope(n1), 1.0 / (n2 - n1));
  EXPECT_NEAR(std::log(rate), std::log(lambda), std::log(2.0) / (n2 - n1))
      << "transient rate " << rate << ", |lambda_max| " << lambda;
}

TEST(Shooting, TransientDecaysLikeTheLargestMultiplierInStickSlip) {
  check_decay(stick_slip_case(), 15, 55);
}

TEST(Shooting, TransientDecaysLikeTheLargestMultiplierInPureRolling) {
  check_decay(pure_rolling_case(), 60, 260);
}

TEST(Shooting, AgreesWithTheTransientMethod) {
  for (const Case& c0 : {stick_slip_case(), pure_rolling_case()}) {
    Case c = c0;
    const Result shot = simulate(c);
    c.numerics.method = SteadyMethod::transient;
    const Result trans = simulate(c);
    ASSERT_EQ(shot.status, Status::steady_state);
    ASSERT_EQ(trans.status, Status::steady_state);
    EXPECT_EQ(shot.diagnostics.method, SteadyMethod::shooting) << shot.diagnostics.fallback;
    EXPECT_EQ(trans.diagnostics.method, SteadyMethod::transient);
    EXPECT_EQ(shot.floquet.stability, Stability::stable);
    EXPECT_EQ(trans.floquet.stability, Stability::unknown);
    EXPECT_GT(shot.diagnostics.newton_iterations, 0);
    EXPECT_LT(shot.diagnostics.period_equivalents, trans.diagnostics.period_equivalents);
    const Metrics a = compute_metrics(shot), b = compute_metrics(trans);
    // The transient stops when the period-to-period change is below steady_tol = 1e-8; its
    // distance from the orbit is then about change / (1 - |lambda_max|), below 2e-7 here.
    const double tol = 2e-7;
    EXPECT_NEAR(a.ddx_max, b.ddx_max, tol * std::abs(b.ddx_max));
    EXPECT_NEAR(a.ddz_max, b.ddz_max, tol * std::abs(b.ddz_max));
    EXPECT_NEAR(a.area, b.area, tol * std::abs(b.area));
    EXPECT_NEAR(a.phi_lag, b.phi_lag, tol * std::abs(b.phi_lag));
    // Both methods report the drift of phi per period (the net slip over r): the same, and zero
    // when the drum cannot slip.
    const double scale = std::max(std::abs(b.phi_amplitude), 1e-300);
    EXPECT_NEAR(shot.diagnostics.phi_drift, trans.diagnostics.phi_drift, tol * scale);
    if (c.contact.pure_rolling)
      EXPECT_NEAR(trans.diagnostics.phi_drift, 0.0, tol * scale);
    else
      EXPECT_GT(std::abs(trans.diagnostics.phi_drift), 1e-3 * scale);  // MMd drives it on
  }
}

}  // namespace
}  // namespace oscidrum
