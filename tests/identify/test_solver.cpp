// Tests of the bounded Levenberg-Marquardt solver (src/identify/solver.cpp) on problems whose
// minimum is known: an exponential decay fitted to exact data, with a fixed parameter, a bound
// and a region where the "model" fails.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "identify/solver.hpp"

namespace oscidrum::detail {
namespace {

// y_i = a exp(-b x_i), x_i = 0, 0.1, ..., 2; p = (ln a, ln b); fails where b > fail_above.
class Decay : public LeastSquares {
 public:
  Decay(double a, double b) {
    for (int i = 0; i <= 20; ++i) {
      x_.push_back(0.1 * i);
      y_.push_back(a * std::exp(-b * x_.back()));
    }
    bounds_ = {{std::log(1e-3), std::log(1e3)}, {std::log(1e-3), std::log(1e3)}};
  }
  int rows() const override { return static_cast<int>(x_.size()); }
  const std::vector<Bounds>& bounds() const override { return bounds_; }
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
    ++calls;
    const double a = std::exp(p[0]), b = std::exp(p[1]);
    if (b > fail_above) return false;
    r.resize(rows());
    for (int i = 0; i < rows(); ++i) r[i] = y_[i] - a * std::exp(-b * x_[i]);
    return true;
  }
  std::string failure(const Eigen::VectorXd&) override { return "b too large"; }
  std::vector<Bounds> bounds_;
  double fail_above = 1e300;
  int calls = 0;

 private:
  std::vector<double> x_, y_;
};

TEST(LevenbergMarquardt, FindsTheExactMinimumFromAFarStart) {
  Decay d(2.0, 1.5);
  const Fit fit =
      levenberg_marquardt(d, Eigen::Vector2d(std::log(20.0), std::log(0.1)), {true, true}, 100);
  ASSERT_TRUE(fit.converged) << fit.message;
  EXPECT_NEAR(std::exp(fit.p[0]), 2.0, 1e-3);
  EXPECT_NEAR(std::exp(fit.p[1]), 1.5, 1e-3);
  EXPECT_LT(fit.S, 1e-8);
}

TEST(LevenbergMarquardt, AGivenFirstJacobianStandsInForItsFiniteDifferences) {
  // From near the minimum with the Jacobian there: the same minimum, and the first iteration
  // makes no finite differences (one model run per free parameter fewer). The Jacobian given has
  // a non-zero column for the fixed parameter, which must be ignored (it must not move).
  Decay d(2.0, 1.5);
  const Fit exact = levenberg_marquardt(d, Eigen::Vector2d(0.0, 0.0), {true, true}, 100);
  ASSERT_TRUE(exact.converged) << exact.message;
  const Eigen::Vector2d start = exact.p + Eigen::Vector2d(0.01, 0.0);
  Decay plain(2.0, 1.5), given(2.0, 1.5);
  const Fit a = levenberg_marquardt(plain, start, {true, false}, 100);
  const Fit b = levenberg_marquardt(given, start, {true, false}, 100, &exact.J);
  ASSERT_TRUE(a.converged && b.converged) << a.message << " / " << b.message;
  EXPECT_NEAR(b.p[0], exact.p[0], 1e-6);
  EXPECT_NEAR(a.p[0], b.p[0], 1e-6);
  EXPECT_EQ(b.p[1], start[1]);
  EXPECT_EQ(given.calls, plain.calls - 1);
  // A Jacobian of the wrong shape is not used.
  Decay wrong(2.0, 1.5);
  const Eigen::MatrixXd small = Eigen::MatrixXd::Ones(3, 2);
  const Fit c = levenberg_marquardt(wrong, start, {true, false}, 100, &small);
  EXPECT_EQ(wrong.calls, plain.calls);
  EXPECT_EQ(c.p, a.p);
}

TEST(LevenbergMarquardt, AtTheMinimumItTriesNoStepThatCannotCount) {
  // Started at the minimum, the linearised problem predicts no decrease of 1e-8 S for any step:
  // converged after the start and its finite differences, without a trial step (before: trial
  // steps with lambda raised eightfold until they shrank below 1e-7, a model run each).
  Decay d(2.0, 1.5);
  const Fit exact = levenberg_marquardt(d, Eigen::Vector2d(0.0, 0.0), {true, true}, 100);
  ASSERT_TRUE(exact.converged) << exact.message;
  // Noise of the size of the signal (S about 2 at the minimum): the finite differences then
  // tilt the step enough that trial steps used to be tried.
  class Noisy : public Decay {
   public:
    Noisy() : Decay(2.0, 1.5) {}
    bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
      if (!Decay::residual(p, r)) return false;
      for (Eigen::Index i = 0; i < r.size(); ++i) r[i] += (i % 2 == 0 ? 0.3 : -0.3);
      return true;
    }
  } noisy;
  const Fit fit = levenberg_marquardt(noisy, exact.p, {true, true}, 100);
  const Fit again = levenberg_marquardt(noisy, fit.p, {true, true}, 100);
  EXPECT_TRUE(again.converged);
  EXPECT_NE(again.message.find("no step predicts"), std::string::npos) << again.message;
  EXPECT_EQ(again.p, fit.p);
  EXPECT_EQ(again.iterations, 1);
  noisy.calls = 0;
  levenberg_marquardt(noisy, fit.p, {true, true}, 100);
  EXPECT_EQ(noisy.calls, 3);  // the start and two finite differences
}

TEST(LevenbergMarquardt, AfterARejectedStepBelowTheConvergenceSizeItTriesNoShorterOne) {
  // One parameter, its minimum 1e-5 from the start, and a second residual that is 0 at the start
  // and 1e-3 everywhere else (the start is the best point there is, as the integration noise of a
  // model's residual can make it): the first step (5e-6, below kStepConverged) is rejected, and
  // every shorter step with a larger lambda would be too, each a model run (before: eight calls in
  // all).
  class Sticky : public LeastSquares {
   public:
    int rows() const override { return 2; }
    const std::vector<Bounds>& bounds() const override { return bounds_; }
    bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
      ++calls;
      r.resize(2);
      r[0] = p[0] - 1e-5;
      r[1] = p[0] == 0.0 ? 0.0 : 1e-3;
      return true;
    }
    std::vector<Bounds> bounds_{{-1.0, 1.0}};
    int calls = 0;
  } sticky;
  const Fit fit = levenberg_marquardt(sticky, Eigen::VectorXd::Zero(1), {true}, 100);
  EXPECT_TRUE(fit.converged);
  EXPECT_NE(fit.message.find("below 1e-4"), std::string::npos) << fit.message;
  EXPECT_EQ(fit.p[0], 0.0);
  EXPECT_EQ(sticky.calls, 3);  // the start, its finite difference and the one step tried
}

TEST(LevenbergMarquardt, AFixedParameterDoesNotMove) {
  Decay d(2.0, 1.5);
  const Fit fit =
      levenberg_marquardt(d, Eigen::Vector2d(std::log(1.0), std::log(1.5)), {true, false}, 100);
  EXPECT_EQ(fit.p[1], std::log(1.5));
  EXPECT_NEAR(std::exp(fit.p[0]), 2.0, 1e-3);
  EXPECT_TRUE(fit.J.col(1).isZero());
}

TEST(LevenbergMarquardt, StaysInsideTheBounds) {
  Decay d(2.0, 1.5);
  d.bounds_[1].hi = std::log(1.0);  // the truth lies beyond: the fit ends on the bound
  const Fit fit =
      levenberg_marquardt(d, Eigen::Vector2d(std::log(1.0), std::log(0.5)), {true, true}, 100);
  EXPECT_LE(fit.p[1], std::log(1.0) + 1e-15);
  EXPECT_NEAR(fit.p[1], std::log(1.0), 1e-6);
  EXPECT_GT(fit.S, 1e-4);
}

TEST(LevenbergMarquardt, StepsBackFromWhereTheModelFails) {
  Decay d(2.0, 1.5);
  d.fail_above = 1.6;  // a failing region next to the minimum
  const Fit fit =
      levenberg_marquardt(d, Eigen::Vector2d(std::log(20.0), std::log(0.1)), {true, true}, 100);
  EXPECT_TRUE(std::isfinite(fit.S));
  EXPECT_LE(std::exp(fit.p[1]), 1.6);
  // The failure at the start is reported, not thrown.
  const Fit bad =
      levenberg_marquardt(d, Eigen::Vector2d(std::log(2.0), std::log(3.0)), {true, true}, 100);
  EXPECT_FALSE(std::isfinite(bad.S));
  EXPECT_EQ(bad.message, "the model fails at the start");
}

TEST(Jacobian, ForwardDifferencesOfAnExactDerivative) {
  Decay d(2.0, 1.5);
  const Eigen::Vector2d p(std::log(1.7), std::log(1.2));
  Eigen::VectorXd r;
  ASSERT_TRUE(d.residual(p, r));
  Eigen::MatrixXd J;
  ASSERT_TRUE(jacobian(d, p, r, {true, true}, J));
  for (int i = 0; i < d.rows(); ++i) {
    const double x = 0.1 * i, a = 1.7, b = 1.2, y = a * std::exp(-b * x);
    // dr/dln a = -y, dr/dln b = y b x; forward differences of step h: error O(h) relative.
    EXPECT_NEAR(J(i, 0), -y, 2 * kJacobianStep * std::abs(y) + 1e-12);
    EXPECT_NEAR(J(i, 1), y * b * x, 2 * kJacobianStep * (1 + b * x) * std::abs(y * b * x) + 1e-12);
  }
}

// downhill_on_grid on six points: the grid's minimum for every single-minimum S, found without
// evaluating the points beyond it; every point where the two middle ones fail.
TEST(DownhillOnGrid, FindsTheMinimumOfEverySingleMinimumGridWithoutThePointsBeyondIt) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < 6; ++m) {
    std::vector<int> calls(6, 0);
    const auto S = [&](std::size_t k) {
      ++calls[k];
      return std::abs(static_cast<double>(k) - static_cast<double>(m)) +
             0.1 * static_cast<double>(k);
    };
    const GridMinimum found = downhill_on_grid(6, S);
    EXPECT_EQ(found.k, m);
    EXPECT_EQ(found.S, 0.1 * static_cast<double>(m));
    for (std::size_t k = 0; k < 6; ++k) {
      EXPECT_LE(calls[k], 1) << "minimum " << m << ", point " << k;
      // Evaluated: the middle two, the points between them and the minimum, and the one past it.
      const bool needed =
          k == 2 || k == 3 || (m <= 2 && k < 2 && k + 1 >= m) || (m >= 3 && k > 3 && k <= m + 1);
      EXPECT_EQ(calls[k], needed ? 1 : 0) << "minimum " << m << ", point " << k;
    }
  }
  // A failing point (S = inf) ends the walk like a rise.
  std::vector<double> v{1.0, 2.0, 3.0, 4.0, inf, 0.5};
  EXPECT_EQ(downhill_on_grid(6, [&](std::size_t k) { return v[k]; }).k, 0u);
  v = {5.0, inf, 3.0, 2.0, 1.0, 0.5};
  EXPECT_EQ(downhill_on_grid(6, [&](std::size_t k) { return v[k]; }).k, 5u);
  // Both middle points failing: every point is tried.
  std::vector<int> calls(6, 0);
  v = {inf, 7.0, inf, inf, 6.0, inf};
  EXPECT_EQ(downhill_on_grid(6,
                             [&](std::size_t k) {
                               ++calls[k];
                               return v[k];
                             })
                .k,
            4u);
  EXPECT_EQ(calls, std::vector<int>(6, 1));
  // One point, or none.
  EXPECT_EQ(downhill_on_grid(1, [](std::size_t) { return 2.0; }).k, 0u);
  EXPECT_EQ(downhill_on_grid(1, [](std::size_t) { return 2.0; }).S, 2.0);
  EXPECT_EQ(downhill_on_grid(1, [&](std::size_t) { return inf; }).k, 1u);
  EXPECT_EQ(downhill_on_grid(0, [](std::size_t) { return 2.0; }).k, 0u);
  // Nowhere finite: n.
  EXPECT_EQ(downhill_on_grid(6, [](std::size_t) { return inf; }).k, 6u);
  EXPECT_EQ(downhill_on_grid(6, [](std::size_t) { return inf; }).S, inf);
  // A grid with two minima: the walk stops at the one on its side (documented, not the grid's).
  v = {0.1, 3.0, 2.0, 2.5, 1.0, 4.0};
  EXPECT_EQ(downhill_on_grid(6, [&](std::size_t k) { return v[k]; }).k, 2u);
  EXPECT_EQ(downhill_on_grid(6, [&](std::size_t k) { return v[k]; }).S, 2.0);
}

}  // namespace
}  // namespace oscidrum::detail
