// The integrator of the hybrid flow (src/flow/dop853.hpp): Dormand-Prince 8(5,3) with its
// continuous extension. Its coefficients satisfy the order conditions, the method converges with
// order 8 and its continuous extension with order 7, the step control keeps the global error in
// proportion to the tolerance, a step costs the evaluations it should (FSAL), and a step that
// cannot be made fails instead of hanging.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "flow/dop853.hpp"

namespace {

using oscidrum::detail::Dop853;
namespace c = oscidrum::detail::dop853;
using Vec = std::array<double, 2>;

// x'' = -x as a first-order system: x(t) = cos t, x'(t) = -sin t from (1, 0) at t = 0.
struct Oscillator {
  long* calls;
  void operator()(const Vec& x, Vec& dxdt, double /*t*/) const {
    ++*calls;
    dxdt = {x[1], -x[0]};
  }
};

// A tolerance that accepts every step: the steps are all max_step long.
constexpr double kAcceptAll = 1e30;

double error_at(double t_end, double h) {
  long calls = 0;
  Dop853<Vec> st(kAcceptAll, kAcceptAll, h);
  st.initialize({1.0, 0.0}, 0.0, h);
  while (st.current_time() < t_end - 1e-12) st.do_step(Oscillator{&calls});
  const Vec& x = st.current_state();
  return std::hypot(x[0] - std::cos(t_end), x[1] + std::sin(t_end));
}

TEST(Dop853, TheCoefficientsSatisfyTheOrderConditions) {
  // Each stage's node is the sum of its row (the stages of the continuous extension too).
  for (int s = 0; s < 16; ++s) {
    double row = 0.0;
    for (int j = 0; j < s; ++j) row += c::kA[s][j];
    EXPECT_NEAR(row, c::kC[s], 1e-14) << "row " << s;
  }
  // The weights b (row 12) integrate c^(k-1) exactly up to k = 8 (the quadrature conditions of
  // order 8), and sum_j b_j a_jl c_l^(k-2) = 1/(k(k-1)) (the conditions of the bushy trees' next
  // level) up to k = 8.
  for (int k = 1; k <= 8; ++k) {
    double q = 0.0;
    for (int j = 0; j < 12; ++j) q += c::kA[12][j] * std::pow(c::kC[j], k - 1);
    EXPECT_NEAR(q, 1.0 / k, 1e-14) << "quadrature condition " << k;
  }
  for (int k = 2; k <= 8; ++k) {
    double q = 0.0;
    for (int j = 0; j < 12; ++j)
      for (int l = 0; l < j; ++l) q += c::kA[12][j] * c::kA[j][l] * std::pow(c::kC[l], k - 2);
    EXPECT_NEAR(q, 1.0 / (k * (k - 1)), 1e-13) << "second-level condition " << k;
  }
  // The error estimates are differences of two weightings of the same stages: they vanish on a
  // constant right-hand side.
  double e5 = 0.0, e3 = 0.0;
  for (int j = 0; j < 13; ++j) {
    e5 += c::kE5[j];
    e3 += c::kE3[j];
  }
  EXPECT_NEAR(e5, 0.0, 1e-14);
  EXPECT_NEAR(e3, 0.0, 1e-14);
}

TEST(Dop853, ConvergesWithOrderEight) {
  // Halving the step divides the global error by about 2^8 = 256.
  const double e1 = error_at(4.0, 0.8), e2 = error_at(4.0, 0.4), e3 = error_at(4.0, 0.2);
  ASSERT_GT(e3, 1e-13);  // well above round-off
  const double p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e3);
  EXPECT_NEAR(p1, 8.0, 0.4) << e1 << " " << e2;
  EXPECT_NEAR(p2, 8.0, 0.4) << e2 << " " << e3;
}

TEST(Dop853, TheContinuousExtensionHasOrderSevenAndMeetsTheStepsEnds) {
  // One step of length h from the exact state; the extension's error inside the step is
  // O(h^8) (local error of an order-7 extension): halving h divides it by about 256.
  auto inner_error = [](double h, double* at_ends) {
    long calls = 0;
    Dop853<Vec> st(kAcceptAll, kAcceptAll, h);
    st.initialize({1.0, 0.0}, 0.0, h);
    st.do_step(Oscillator{&calls});
    double worst = 0.0;
    for (double s : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      Vec x;
      st.calc_state(s * h, x);
      worst = std::max(worst, std::hypot(x[0] - std::cos(s * h), x[1] + std::sin(s * h)));
    }
    Vec x0, x1;
    st.calc_state(0.0, x0);
    st.calc_state(h, x1);
    *at_ends = std::max(std::hypot(x0[0] - 1.0, x0[1]),
                        std::hypot(x1[0] - st.current_state()[0], x1[1] - st.current_state()[1]));
    return worst;
  };
  double ends1 = 0.0, ends2 = 0.0;
  const double e1 = inner_error(0.8, &ends1), e2 = inner_error(0.4, &ends2);
  ASSERT_GT(e2, 1e-15);
  EXPECT_NEAR(std::log2(e1 / e2), 8.0, 0.5) << e1 << " " << e2;
  EXPECT_LT(ends1, 1e-15);
  EXPECT_LT(ends2, 1e-15);
}

TEST(Dop853, TheContinuousExtensionAtManyTimesIsItsValueAtEach) {
  // calc_states evaluates the extension in lanes of times: the same bits as calc_state at each,
  // for counts that fill the lanes, leave some unused, and span two blocks.
  long calls = 0;
  const double h = 0.3;
  Dop853<Vec> st(1e-10, 1e-10, h);
  st.initialize({1.0, 0.0}, 0.2, h);
  st.do_step(Oscillator{&calls});
  st.do_step(Oscillator{&calls});
  const double t0 = st.current_time() - h;
  std::array<double, 19> t{};
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = t0 + h * static_cast<double>(i) / 18.0;
  for (const int n : {19, 8, 5, 1}) {
    std::array<Vec, 19> many{};
    st.calc_states(t.data(), n, many.data());
    for (int i = 0; i < n; ++i) {
      Vec one{};
      st.calc_state(t[static_cast<std::size_t>(i)], one);
      EXPECT_EQ(one, many[static_cast<std::size_t>(i)]) << n << " times, time " << i;
    }
  }
}

TEST(Dop853, AStepToATimeInsideTheLastStepIsTheMethodsOwnStep) {
  // step_to(t) is the method's step from the last step's start to t: at the step's end the step
  // itself, bit for bit; inside it an 8th-order step, more accurate than the continuous extension
  // (order 7), with 11 evaluations.
  long calls = 0;
  const double h = 0.8;
  Dop853<Vec> st(kAcceptAll, kAcceptAll, h);
  st.initialize({1.0, 0.0}, 0.0, h);
  st.do_step(Oscillator{&calls});
  const long before = calls;
  const Vec end = st.step_to(h, Oscillator{&calls});
  EXPECT_EQ(calls - before, 11);
  EXPECT_EQ(end, st.current_state());
  for (double s : {0.3, 0.5, 0.7}) {
    const Vec own = st.step_to(s * h, Oscillator{&calls});
    Vec extension;
    st.calc_state(s * h, extension);
    const double e_own = std::hypot(own[0] - std::cos(s * h), own[1] + std::sin(s * h));
    const double e_ext = std::hypot(extension[0] - std::cos(s * h), extension[1] + std::sin(s * h));
    EXPECT_LT(e_own, 0.1 * e_ext) << "s = " << s;
  }
}

TEST(Dop853, TheGlobalErrorFollowsTheTolerance) {
  // Ten periods of the oscillator: the error stays within a small multiple of the tolerance and
  // falls with it; an accepted step costs 15 evaluations, a rejected one 12, a start one (FSAL).
  double previous = 1.0;
  for (double tol : {1e-6, 1e-8, 1e-10}) {
    long calls = 0;
    Dop853<Vec> st(tol, tol, 1.0);
    st.initialize({1.0, 0.0}, 0.0, 1e-3);
    long steps = 0;
    const double t_end = 20.0 * M_PI;
    while (st.current_time() < t_end) {
      st.do_step(Oscillator{&calls});
      ++steps;
    }
    Vec x;
    st.calc_state(t_end, x);
    const double err = std::hypot(x[0] - 1.0, x[1]);
    EXPECT_LT(err, 100.0 * tol) << "tol " << tol;
    EXPECT_LT(err, previous) << "tol " << tol;
    previous = err;
    const long rejected_calls = calls - 1 - 15 * steps;
    EXPECT_EQ(rejected_calls % 12, 0) << "tol " << tol;
    EXPECT_GE(rejected_calls, 0);
  }
}

TEST(Dop853, AStepThatCannotBeMadeFailsInsteadOfHanging) {
  // A right-hand side that jumps by 1e30 at t = 1: every step across it is rejected, the steps
  // before it shrink until they reach t's round-off, and the stepper says it failed.
  long calls = 0;
  auto jump = [&calls](const Vec&, Vec& dxdt, double t) {
    ++calls;
    dxdt = {t >= 1.0 ? 1e30 : 0.0, 0.0};
  };
  Dop853<Vec> st(1e-8, 1e-8, 0.5);
  st.initialize({0.0, 0.0}, 0.0, 0.1);
  int steps = 0;
  while (!st.failed() && steps < 100000) {
    st.do_step(jump);
    ++steps;
  }
  EXPECT_TRUE(st.failed());
  EXPECT_LT(steps, 100000);
  EXPECT_LT(st.current_time(), 1.0);
  EXPECT_GT(st.current_time(), 1.0 - 1e-12);
  // A right-hand side that is not a number at the start gives an accepted step with a state that
  // is not a number (the flow stops there as non_finite), not an endless loop of rejections.
  Dop853<Vec> nan(1e-8, 1e-8, 0.5);
  nan.initialize({0.0, 0.0}, 0.0, 0.1);
  nan.do_step([](const Vec&, Vec& dxdt, double) { dxdt = {std::nan(""), 0.0}; });
  EXPECT_FALSE(nan.failed());
  EXPECT_TRUE(std::isnan(nan.current_state()[0]));
  // One that overflows only away from the start (a stiff phase whose stages blow up on too long
  // a step) has its step shortened until the stages stay finite.
  long overflow_calls = 0;
  auto stiff = [&overflow_calls](const Vec& x, Vec& dxdt, double) {
    ++overflow_calls;
    dxdt = {std::abs(x[0]) > 1e-3 ? std::nan("") : 1.0, 0.0};
  };
  Dop853<Vec> shrinking(1e-8, 1e-8, 0.5);
  shrinking.initialize({0.0, 0.0}, 0.0, 0.1);
  shrinking.do_step(stiff);
  EXPECT_FALSE(shrinking.failed());
  EXPECT_TRUE(std::isfinite(shrinking.current_state()[0]));
  EXPECT_LE(shrinking.current_time(), 1e-3);
  EXPECT_NEAR(shrinking.current_state()[0], shrinking.current_time(), 1e-15);
}

}  // namespace
