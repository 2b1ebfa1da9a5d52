// Tests of continuation in studies (src/drivers/study.cpp, src/drivers/continuation.hpp): a Table 2
// sweep warm-started case to case finds the steady states of the cold start, independently of the
// thread count; a warm start that fails falls back to exactly the cold start; the chains.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstring>
#include <optional>
#include <vector>

#include "bifurcation_cases.hpp"
#include "drivers/continuation.hpp"
#include "drivers/period_recording.hpp"
#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

Case shooting_case(double G, bool pure_rolling) {
  Case c;
  c.soil = table2_soil(G);
  c.contact.pure_rolling = pure_rolling;
  c.numerics.method = SteadyMethod::shooting;
  c.numerics.samples_per_period = 256;
  return c;
}

// Paper Table 2: 14 G values, pure rolling and stick-slip (mu = 0.5); G varies fastest.
std::vector<Case> table2_sweep(bool continuation) {
  std::vector<Case> cases;
  for (bool pure : {true, false})
    for (const Table2Row& row : table2()) {
      Case c = shooting_case(row.G, pure);
      c.numerics.continuation = continuation;
      cases.push_back(c);
    }
  return cases;
}

// Largest difference of two sampled steady states over the state components (phi excluded: it
// is cyclic, its offset is arbitrary), each scaled by its range over the steady period, as
// numerics.steady_tol measures a change.
double scaled_difference(const Samples& a, const Samples& b) {
  double worst = 0.0;
  for (auto member : {&Samples::delta, &Samples::x_A, &Samples::s_A, &Samples::ddelta,
                      &Samples::dx_A, &Samples::ds_A, &Samples::dphi}) {
    const std::vector<double>&x = a.*member, &y = b.*member;
    EXPECT_EQ(x.size(), y.size());
    if (x.size() != y.size() || x.empty()) return INFINITY;
    const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
    const double range = *hi - *lo;
    for (std::size_t j = 0; j < x.size(); ++j)
      worst = std::max(worst, std::abs(x[j] - y[j]) / range);
  }
  return worst;
}

TEST(Continuation, Table2SweepEqualsColdStartToTheSteadyTolerance) {
  const std::vector<Case> warm_cases = table2_sweep(true), cold_cases = table2_sweep(false);
  StudyOptions options;
  options.threads = 2;
  options.keep_samples = true;
  const std::vector<CaseOutcome> warm = run_study(warm_cases, options);
  const std::vector<CaseOutcome> cold = run_study(cold_cases, options);
  ASSERT_EQ(warm.size(), 28u);
  long warm_rhs = 0, cold_rhs = 0;
  int warm_started = 0;
  for (std::size_t i = 0; i < warm.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    ASSERT_TRUE(warm[i].valid && cold[i].valid);
    ASSERT_EQ(warm[i].result.status, Status::steady_state) << warm[i].result.message;
    ASSERT_EQ(cold[i].result.status, Status::steady_state) << cold[i].result.message;
    const Diagnostics &dw = warm[i].result.diagnostics, &dc = cold[i].result.diagnostics;
    EXPECT_EQ(dc.warm_start, 0);
    // Each of the two chains (14 G values) starts from rest; every later case from its neighbour.
    EXPECT_EQ(dw.warm_start, i % 14 == 0 ? 0 : 1) << dw.fallback;
    warm_started += dw.warm_start == 1;
    warm_rhs += dw.rhs_evaluations;
    cold_rhs += dc.rhs_evaluations;
    // Both orbits are steady to steady_tol (a period changes them by less), so they are the same
    // orbit to 2 steady_tol.
    EXPECT_LE(scaled_difference(warm[i].result.samples, cold[i].result.samples),
              2.0 * warm_cases[i].numerics.steady_tol);
    // The switching structure is the same.
    EXPECT_NEAR(warm[i].metrics.stick_fraction, cold[i].metrics.stick_fraction,
                2.0 * warm_cases[i].numerics.steady_tol);
  }
  EXPECT_EQ(warm_started, 26);
  // Starting next to the orbit saves the short transient.
  EXPECT_LT(warm_rhs, cold_rhs);
}

// A start ramp (numerics.start_ramp_periods) belongs to the start from rest. Warm starts began at
// t = 0, under the ramp, where the neighbour's orbit is no orbit: every one failed and its case
// ran from rest (the same numbers, without the speed-up and without a word).
TEST(Continuation, AStartRampDoesNotStopTheWarmStarts) {
  std::vector<Case> warm_cases = table2_sweep(true), cold_cases = table2_sweep(false);
  for (std::vector<Case>* cases : {&warm_cases, &cold_cases})
    for (Case& c : *cases) c.numerics.start_ramp_periods = 20;
  StudyOptions options;
  options.threads = 2;
  options.keep_samples = true;
  const std::vector<CaseOutcome> warm = run_study(warm_cases, options);
  const std::vector<CaseOutcome> cold = run_study(cold_cases, options);
  int warm_started = 0;
  for (std::size_t i = 0; i < warm.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    ASSERT_EQ(warm[i].result.status, Status::steady_state) << warm[i].result.message;
    ASSERT_EQ(cold[i].result.status, Status::steady_state) << cold[i].result.message;
    warm_started += warm[i].result.diagnostics.warm_start == 1;
    EXPECT_LE(scaled_difference(warm[i].result.samples, cold[i].result.samples),
              2.0 * warm_cases[i].numerics.steady_tol);
    EXPECT_NEAR(warm[i].metrics.area, cold[i].metrics.area, 1e-7 * cold[i].metrics.area);
  }
  EXPECT_EQ(warm_started, 26);
}

// phi's drift per period is measured on the sampled periods of the orbit. It was taken from
// Newton's last map, which starts at the iterate before the last step: after a warm start's chord
// steps a pure-rolling orbit without driving torque, which closes in phi, read a drift of up to
// 1e-5 rad per period (a net slip), warm-started only.
TEST(Continuation, APureRollingOrbitWithoutDrivingTorqueDoesNotDrift) {
  const std::vector<Case> warm_cases = table2_sweep(true), cold_cases = table2_sweep(false);
  StudyOptions options;
  options.threads = 2;
  const std::vector<CaseOutcome> warm = run_study(warm_cases, options);
  const std::vector<CaseOutcome> cold = run_study(cold_cases, options);
  for (std::size_t i = 0; i < warm.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    ASSERT_EQ(warm[i].result.status, Status::steady_state);
    ASSERT_DOUBLE_EQ(warm_cases[i].MMd, 0.0);
    const double dw = warm[i].result.diagnostics.phi_drift;
    const double dc = cold[i].result.diagnostics.phi_drift;
    if (warm_cases[i].contact.pure_rolling) {
      EXPECT_LT(std::abs(dw), 1e-12);
      EXPECT_LT(std::abs(dc), 1e-12);
    }
    // Stick-slip without driving torque: no net slip either, to the orbit's accuracy.
    EXPECT_NEAR(dw, dc, 1e-9);
  }
}

// A warm start that spends numerics.max_periods without a steady state (past the period doubling
// of the log-spiral study, Newton from the period-1 neighbour needs many periods) left nothing for
// the cold start, and the case read max_periods_reached where the cold start finds the period-2
// orbit in 79 periods.
TEST(Continuation, AWarmStartThatSpendsTheBudgetLeavesTheColdStartItsOwn) {
  std::vector<Case> warm_cases, cold_cases;
  for (const double G : {124e6, 126e6}) {
    Case c = test::log_spiral_case();
    set_field(c, "soil.G", G);
    c.numerics.max_periods = 100;
    warm_cases.push_back(c);
    c.numerics.continuation = false;
    cold_cases.push_back(c);
  }
  StudyOptions options;
  options.threads = 1;
  const std::vector<CaseOutcome> warm = run_study(warm_cases, options);
  const std::vector<CaseOutcome> cold = run_study(cold_cases, options);
  for (std::size_t i = 0; i < warm.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    ASSERT_EQ(cold[i].result.status, Status::steady_state) << cold[i].result.message;
    EXPECT_EQ(warm[i].result.status, Status::steady_state) << warm[i].result.message;
    EXPECT_EQ(warm[i].result.diagnostics.multiplicity, cold[i].result.diagnostics.multiplicity);
    EXPECT_NEAR(warm[i].metrics.area, cold[i].metrics.area, 1e-7 * cold[i].metrics.area);
  }
  EXPECT_EQ(cold[1].result.diagnostics.multiplicity, 2);
  EXPECT_EQ(warm[1].result.diagnostics.warm_start, -1);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const CaseOutcome& a, const CaseOutcome& b) {
  ASSERT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.result.status, b.result.status);
  EXPECT_EQ(a.result.diagnostics.warm_start, b.result.diagnostics.warm_start);
  EXPECT_EQ(a.result.diagnostics.rhs_evaluations, b.result.diagnostics.rhs_evaluations);
  EXPECT_EQ(a.result.diagnostics.newton_iterations, b.result.diagnostics.newton_iterations);
  for (auto member : {&Samples::t, &Samples::delta, &Samples::x_A, &Samples::s_A, &Samples::ddx_M,
                      &Samples::ddz_M, &Samples::N, &Samples::T})
    EXPECT_TRUE(same_bits(a.result.samples.*member, b.result.samples.*member));
  EXPECT_TRUE(same_bits(a.metrics.ddx_max, b.metrics.ddx_max));
  EXPECT_TRUE(same_bits(a.metrics.ddz_max, b.metrics.ddz_max));
  EXPECT_TRUE(same_bits(a.metrics.area, b.metrics.area));
}

TEST(Continuation, OutcomesDoNotDependOnTheThreadCount) {
  // Two chains of 7 (every other G value), stick-slip then pure rolling.
  std::vector<Case> cases;
  for (bool pure : {false, true})
    for (std::size_t k = 0; k < table2().size(); k += 2)
      cases.push_back(shooting_case(table2()[k].G, pure));
  StudyOptions one, two;
  one.threads = 1;
  two.threads = 2;
  one.keep_samples = two.keep_samples = true;
  const std::vector<CaseOutcome> a = run_study(cases, one), b = run_study(cases, two);
  ASSERT_EQ(a.size(), b.size());
  int warm_started = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    expect_identical(a[i], b[i]);
    warm_started += a[i].result.diagnostics.warm_start == 1;
  }
  EXPECT_EQ(warm_started, 12);  // the continuation did run
}

TEST(Continuation, AFailingWarmStartFallsBackToTheColdStart) {
  const Case c = shooting_case(25e6, false);
  const Model model(c);
  const Result cold = simulate(model);
  ASSERT_EQ(cold.status, Status::steady_state);
  // A start far from any orbit: the drum high up the trough and spinning; it is no state of the
  // slip+ phase it is given in (an event function of that phase is below zero), so the flow
  // refuses it at once (FlowStop::inconsistent_state; before that guard the flow lost contact or
  // Newton failed from it).
  State far_state;
  far_state.delta = 0.6;
  far_state.ddelta = 300.0;
  far_state.dphi = 30.0;
  const auto x = far_state.to_array();
  const detail::WarmStart far{std::vector<double>(x.begin(), x.end()), Phase::slip_positive, {}};
  const Result r = detail::simulate_from(model, {}, {}, &far);
  EXPECT_EQ(r.diagnostics.warm_start, -1);
  EXPECT_EQ(r.status, Status::steady_state) << r.message;
  // The cold start that follows is the cold start: the same steady state, bit for bit.
  EXPECT_TRUE(same_bits(r.samples.ddz_M, cold.samples.ddz_M));
  EXPECT_TRUE(same_bits(r.samples.delta, cold.samples.delta));
  EXPECT_EQ(r.diagnostics.newton_iterations >= cold.diagnostics.newton_iterations, true);
  EXPECT_EQ(r.diagnostics.rhs_evaluations, cold.diagnostics.rhs_evaluations);  // refused at once

  // A warm start from the orbit itself converges at once.
  const std::optional<detail::WarmStart> own = detail::orbit_start(model, cold);
  ASSERT_TRUE(own.has_value());
  const Result again = detail::simulate_from(model, {}, {}, &*own);
  EXPECT_EQ(again.diagnostics.warm_start, 1);
  EXPECT_EQ(again.diagnostics.newton_iterations, 0);
}

// A case of the performance issue's sweep (Appendix B soil, mu 0.5, MMd 0.05 M0) at G [Pa].
Case appendix_b_case(double G) {
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = G;
  c.MMd = 0.05 * c.roller.M0;
  c.numerics.method = SteadyMethod::shooting;
  c.numerics.samples_per_period = 256;
  return c;
}

// Largest distance between two sets of Floquet multipliers (each sorted by decreasing modulus).
double multiplier_distance(const Floquet& a, const Floquet& b) {
  EXPECT_EQ(a.multipliers.size(), b.multipliers.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.multipliers.size(), b.multipliers.size()); ++i)
    worst = std::max(worst, std::abs(a.multipliers[i] - b.multipliers[i]));
  return worst;
}

TEST(Continuation, AWarmStartIntegratesTheVariationalEquationsOnce) {
  // The case at G = 25 MN/m^2 warm-started from its neighbour one step of the sweep
  // below (95/399 MN/m^2): Newton's steps after the first map are chord steps with the first
  // map's monodromy (shooting::kChordContraction).
  const Model model(appendix_b_case(25e6)), neighbour(appendix_b_case(25e6 - 95e6 / 399.0));
  const Result cold = simulate(model);
  const Result before = simulate(neighbour);
  ASSERT_EQ(cold.status, Status::steady_state) << cold.message;
  ASSERT_EQ(before.status, Status::steady_state) << before.message;
  const std::optional<detail::WarmStart> from_neighbour = detail::orbit_start(neighbour, before);
  const std::optional<detail::WarmStart> from_orbit = detail::orbit_start(model, cold);
  ASSERT_TRUE(from_neighbour.has_value() && from_orbit.has_value());
  const Result warm = detail::simulate_from(model, {}, {}, &*from_neighbour);
  // From the orbit itself Newton stops at its first map: its monodromy is the orbit's own, and
  // its Jacobians are those of one map with the variational equations.
  const Result exact = detail::simulate_from(model, {}, {}, &*from_orbit);
  ASSERT_EQ(warm.status, Status::steady_state) << warm.message;
  ASSERT_EQ(exact.status, Status::steady_state) << exact.message;
  EXPECT_EQ(warm.diagnostics.warm_start, 1);
  EXPECT_EQ(exact.diagnostics.newton_iterations, 0);
  EXPECT_GE(warm.diagnostics.newton_iterations, 1);  // it did iterate from the neighbour
  // One map with the variational equations (about 400 Jacobians; two maps would be twice that).
  EXPECT_LT(static_cast<double>(warm.diagnostics.jacobian_evaluations),
            1.5 * static_cast<double>(exact.diagnostics.jacobian_evaluations));
  // The same orbit as the cold start (each steady to steady_tol).
  const double tol = model.parameters().numerics.steady_tol;
  EXPECT_LE(scaled_difference(warm.samples, cold.samples), 2.0 * tol);
  // The multipliers: the warm start's from the monodromy at its start, the cold start's from its
  // last fresh one; both as close to the orbit's own as a Newton iterate with a residual above
  // shooting::kFreshMonodromy allows.
  EXPECT_EQ(warm.floquet.stability, exact.floquet.stability);
  EXPECT_EQ(warm.floquet.multipliers.size(), 7u);
  // Measured: 4.6e-4 (warm) and 8e-5 (cold) from the orbit's multipliers, whose largest
  // modulus is 0.77 (before the chord steps a warm start took a second fresh monodromy, at the
  // iterate after its first step).
  EXPECT_LE(multiplier_distance(warm.floquet, exact.floquet), 1e-3);
  EXPECT_LE(multiplier_distance(cold.floquet, exact.floquet), 1e-3);

  // From a distant neighbour (G = 15 MN/m^2) the chord steps do not contract by
  // kChordContraction: Newton takes a fresh monodromy and goes on as from a cold start.
  const Model distant(appendix_b_case(15e6));
  const Result far_case = simulate(distant);
  ASSERT_EQ(far_case.status, Status::steady_state) << far_case.message;
  const std::optional<detail::WarmStart> from_far = detail::orbit_start(distant, far_case);
  ASSERT_TRUE(from_far.has_value());
  const Result refreshed = detail::simulate_from(model, {}, {}, &*from_far);
  ASSERT_EQ(refreshed.status, Status::steady_state) << refreshed.message;
  EXPECT_EQ(refreshed.diagnostics.warm_start, 1);
  EXPECT_GT(static_cast<double>(refreshed.diagnostics.jacobian_evaluations),
            1.5 * static_cast<double>(exact.diagnostics.jacobian_evaluations));
  EXPECT_LE(scaled_difference(refreshed.samples, cold.samples), 2.0 * tol);
  EXPECT_LE(multiplier_distance(refreshed.floquet, exact.floquet), 1e-3);
}

TEST(Continuation, TheNeighboursContractionSkipsThePlainMap) {
  // Without a contraction known, the first chord step is confirmed on a plain period map before
  // the recorded period; with the neighbour's, when it predicts convergence, on the recorded
  // period directly: one period less, the same orbit.
  // The start predicted from the two cases before, a quarter of a step of the sweep apart
  // (a full step: contraction 6.6e-7, too little to predict convergence, and the plain map
  // follows as without the neighbour's contraction).
  const double h = 95e6 / 399.0 / 4.0;
  const Case c0 = appendix_b_case(25e6), c1 = appendix_b_case(25e6 - h),
             c2 = appendix_b_case(25e6 - 2.0 * h);
  const Model model(c0), m1(c1), m2(c2);
  const Result cold = simulate(model), r1 = simulate(m1), r2 = simulate(m2);
  ASSERT_EQ(cold.status, Status::steady_state) << cold.message;
  const std::optional<detail::WarmStart> w1 = detail::orbit_start(m1, r1),
                                         w2 = detail::orbit_start(m2, r2);
  ASSERT_TRUE(w1.has_value() && w2.has_value());
  std::optional<detail::WarmStart> start = detail::secant_start(*w2, *w1, c2, c1, c0);
  ASSERT_TRUE(start.has_value());
  EXPECT_LT(start->contraction, 0.0);  // unknown unless a study sets it
  detail::recording::Recording rec;
  const Result plain = detail::simulate_from(model, {}, {}, &*start, true, &rec);
  ASSERT_EQ(plain.status, Status::steady_state) << plain.message;
  // The contraction of the first chord step, for the next case (seen: 4.2e-8).
  EXPECT_GT(rec.chord_contraction, 0.0);
  EXPECT_LT(rec.chord_contraction, 1e-5);

  start->contraction = rec.chord_contraction;
  const Result direct = detail::simulate_from(model, {}, {}, &*start, true, &rec);
  ASSERT_EQ(direct.status, Status::steady_state) << direct.message;
  EXPECT_EQ(direct.diagnostics.warm_start, 1);
  EXPECT_EQ(direct.diagnostics.periods_simulated, plain.diagnostics.periods_simulated - 1);
  EXPECT_EQ(direct.diagnostics.jacobian_evaluations, plain.diagnostics.jacobian_evaluations);
  const double tol = model.parameters().numerics.steady_tol;
  EXPECT_LE(scaled_difference(direct.samples, cold.samples), 2.0 * tol);
  EXPECT_LE(scaled_difference(direct.samples, plain.samples), 0.1 * tol);

  // A contraction that misleads (0: every step predicted exact) from a distant neighbour: the
  // recorded period does not confirm the step, and the case still converges to the orbit.
  const Model distant(appendix_b_case(15e6));
  const Result far_case = simulate(distant);
  ASSERT_EQ(far_case.status, Status::steady_state) << far_case.message;
  std::optional<detail::WarmStart> from_far = detail::orbit_start(distant, far_case);
  ASSERT_TRUE(from_far.has_value());
  from_far->contraction = 0.0;
  const Result misled = detail::simulate_from(model, {}, {}, &*from_far);
  ASSERT_EQ(misled.status, Status::steady_state) << misled.message;
  EXPECT_EQ(misled.diagnostics.warm_start, 1)
      << misled.message << " / " << misled.diagnostics.fallback;
  EXPECT_LE(scaled_difference(misled.samples, cold.samples), 2.0 * tol);
}

TEST(Continuation, ThePredictorIsExactOnAQuadraticChain) {
  // States quadratic in mu at unequal steps: three of them predict the fourth exactly (to
  // rounding); two predict it by the secant; a third in another phase, or a step that does not
  // continue the one before it (ratio above kMaxSecantRatio), leaves the secant.
  const auto state = [](double mu) {
    const double u = 10.0 * mu;
    return std::vector<double>{1.0 + u * u, -2.0 * u + 0.5 * u * u, 3.0, u * u * u / 10.0};
  };
  const std::array<double, 4> mu = {0.40, 0.44, 0.472, 0.516};  // c3, c2, c1, c0
  std::array<Case, 4> c;
  std::array<detail::WarmStart, 4> w;
  for (std::size_t k = 0; k < 4; ++k) {
    c[k] = shooting_case(25e6, false);
    c[k].contact.mu = mu[k];
    w[k] = detail::WarmStart{state(mu[k]), Phase::stick, {}};
  }
  const auto quadratic = detail::secant_start(w[1], w[2], c[1], c[2], c[3], &w[0], &c[0]);
  ASSERT_TRUE(quadratic.has_value());
  EXPECT_EQ(quadratic->then, w[2].state);
  const std::vector<double> exact = state(mu[3]);
  for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(quadratic->state[j], exact[j], 1e-12);
  // The cubic component is not reproduced: a quadratic through three points misses u^3 / 10 by
  // (u0 - u1)(u0 - u2)(u0 - u3) / 10.
  EXPECT_NEAR(quadratic->state[3], exact[3] - 0.44 * 0.76 * 1.16 / 10.0, 1e-12);

  const auto secant = detail::secant_start(w[1], w[2], c[1], c[2], c[3]);
  ASSERT_TRUE(secant.has_value());
  const double s = (mu[3] - mu[2]) / (mu[2] - mu[1]);
  for (std::size_t j = 0; j < 4; ++j)
    EXPECT_DOUBLE_EQ(secant->state[j], w[2].state[j] + s * (w[2].state[j] - w[1].state[j]));
  EXPECT_GT(std::abs(secant->state[0] - exact[0]), 1e-3);  // the quadratic did better
  detail::WarmStart other = w[0];
  other.phase = Phase::slip_positive;
  const auto mixed = detail::secant_start(w[1], w[2], c[1], c[2], c[3], &other, &c[0]);
  ASSERT_TRUE(mixed.has_value());
  EXPECT_EQ(mixed->state, secant->state);
  Case near = c[0];
  near.contact.mu = 0.42;  // the step c3 -> c2 (0.02) is too short for the next (0.032)
  ASSERT_GT((mu[2] - mu[1]) / (mu[1] - 0.42), detail::kMaxSecantRatio);
  const auto uneven = detail::secant_start(w[1], w[2], c[1], c[2], c[3], &w[0], &near);
  ASSERT_TRUE(uneven.has_value());
  EXPECT_EQ(uneven->state, secant->state);
}

TEST(Continuation, ChainsAreCutIntoPiecesThatDependOnlyOnTheStudy) {
  EXPECT_EQ(max_continuation_piece(1), kMinContinuationPiece);
  EXPECT_EQ(max_continuation_piece(400), 16u);
  EXPECT_EQ(max_continuation_piece(2400), 38u);  // the performance issue's sweep: 66 pieces
  EXPECT_EQ(max_continuation_piece(64 * 100), 100u);
  // One chain of 40 cases: pieces of 16, 16 and 8, each starting from rest.
  std::vector<Case> cases;
  for (int k = 0; k < 40; ++k) cases.push_back(appendix_b_case(20e6 + 0.25e6 * k));
  StudyOptions o;
  o.threads = 2;
  o.keep_samples = false;
  const std::vector<CaseOutcome> out = run_study(cases, o);
  ASSERT_EQ(out.size(), 40u);
  for (std::size_t i = 0; i < out.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    ASSERT_EQ(out[i].result.status, Status::steady_state) << out[i].result.message;
    EXPECT_EQ(out[i].result.diagnostics.warm_start, i % 16 == 0 ? 0 : 1);
  }
}

TEST(Continuation, TheTransientMethodAlwaysStartsFromRest) {
  Case c = shooting_case(25e6, true);
  c.numerics.method = SteadyMethod::transient;
  const Model model(c);
  const Result cold = simulate(model);
  const std::optional<detail::WarmStart> own = detail::orbit_start(model, cold);
  ASSERT_TRUE(own.has_value());
  const Result r = detail::simulate_from(model, {}, {}, &*own);
  EXPECT_EQ(r.diagnostics.warm_start, 0);
  EXPECT_TRUE(same_bits(r.samples.ddz_M, cold.samples.ddz_M));
}

TEST(Continuation, ChainsFollowTheInnermostLoopOfAProduct) {
  // 3 radii (outer) x 4 G values (inner): one chain per radius.
  std::vector<Case> cases;
  for (double R : {0.606, 0.62, 0.65})
    for (double G : {5e6, 10e6, 15e6, 20e6}) {
      Case c = shooting_case(G, true);
      c.trough.shape = CircleTrough{R};
      cases.push_back(c);
    }
  const std::vector<std::ptrdiff_t> p = continuation_chains(cases);
  const std::vector<std::ptrdiff_t> expected = {-1, 0, 1, 2, -1, 4, 5, 6, -1, 8, 9, 10};
  EXPECT_EQ(p, expected);
  // Zipped values (G and f change together at every step) make one chain.
  std::vector<Case> zip;
  for (std::size_t i = 0; i < 6; ++i) {
    zip.push_back(shooting_case(table2()[i].G, true));
    zip.back().roller.f = 30.0 + static_cast<double>(i);
  }
  const std::vector<std::ptrdiff_t> zipped = continuation_chains(zip);
  EXPECT_EQ(std::count(zipped.begin(), zipped.end(), -1), 1);
  // No links where continuation is off or the method is the transient one.
  cases[3].numerics.continuation = false;
  cases[7].numerics.method = SteadyMethod::transient;
  const std::vector<std::ptrdiff_t> off = continuation_chains(cases);
  EXPECT_EQ(off[3], -1);
  EXPECT_EQ(off[4], -1);
  EXPECT_EQ(off[7], -1);
  EXPECT_EQ(off[8], -1);
  EXPECT_EQ(off[5], 4);
}

TEST(Continuation, NearTheUnitCircleTheMultipliersAreTakenAtTheOrbit) {
  // Pure rolling at 58 Hz with contact that can open (the Neimark-Sacker study of
  // docs/bifurcations.md, first point at 42.51 MN/m^2): at G = 40 MN/m^2 the period-1 orbit is
  // stable, largest multiplier modulus 0.9956. Warm-started from the orbit at 35 MN/m^2, the
  // monodromy of the first map (scaled residual 0.17) gave 1.00003: an unstable verdict, a futile
  // search for a subharmonic and a start from rest (the brute-force diagram called the orbit
  // quasi-periodic). Within kMultiplierDrift times that residual of 1 the monodromy is taken
  // again at the orbit.
  const auto case_at = [](double G) {
    Case c = test::rolling_unilateral_case(58.0);
    c.soil.G = G;
    return c;
  };
  const Model model(case_at(40e6)), neighbour(case_at(35e6));
  const Result cold = simulate(model);
  const Result before = simulate(neighbour);
  ASSERT_EQ(cold.status, Status::steady_state) << cold.message;
  ASSERT_EQ(before.status, Status::steady_state) << before.message;
  ASSERT_EQ(cold.floquet.stability, Stability::stable);
  ASSERT_GT(cold.floquet.max_modulus, 0.99);
  const std::optional<detail::WarmStart> from_neighbour = detail::orbit_start(neighbour, before);
  ASSERT_TRUE(from_neighbour.has_value());
  const Result warm = detail::simulate_from(model, {}, {}, &*from_neighbour);
  ASSERT_EQ(warm.status, Status::steady_state) << warm.message;
  EXPECT_EQ(warm.diagnostics.warm_start, 1) << warm.diagnostics.fallback;
  EXPECT_EQ(warm.floquet.stability, Stability::stable);
  EXPECT_NEAR(warm.floquet.max_modulus, cold.floquet.max_modulus, 1e-4);
  EXPECT_LE(scaled_difference(warm.samples, cold.samples),
            2.0 * model.parameters().numerics.steady_tol);
}

TEST(Continuation, LinksAreChecked) {
  const std::vector<Case> cases(3, shooting_case(25e6, true));
  StudyOptions o;
  o.previous = {-1, 0, 0};  // case 0 would continue into two chains
  EXPECT_THROW(run_study(cases, o), Error);
  o.previous = {-1, 2, -1};  // a later case
  EXPECT_THROW(run_study(cases, o), Error);
  o.previous = {-1, 0};  // one per case
  EXPECT_THROW(run_study(cases, o), Error);
}

}  // namespace
}  // namespace oscidrum
