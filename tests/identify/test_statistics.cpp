// Tests of the uncertainties of a least-squares fit (src/identify/statistics.cpp) on a straight
// line, where everything is known in closed form: the linearised standard errors are the
// ordinary least-squares ones, and the profile interval is the t interval.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "identify/solver.hpp"
#include "identify/statistics.hpp"

namespace oscidrum::detail {
namespace {

// y_i = a + b x_i + noise, residuals unweighted; p = (a, b).
class Line : public LeastSquares {
 public:
  Line(double a, double b, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, sigma);
    for (int i = 0; i < 30; ++i) {
      x_.push_back(0.1 * i);
      y_.push_back(a + b * x_.back() + g(rng));
    }
    bounds_ = {{-100, 100}, {-100, 100}};
  }
  int rows() const override { return static_cast<int>(x_.size()); }
  const std::vector<Bounds>& bounds() const override { return bounds_; }
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
    ++calls;
    r.resize(rows());
    for (int i = 0; i < rows(); ++i) r[i] = y_[i] - p[0] - p[1] * x_[i];
    return true;
  }
  Eigen::MatrixXd design() const {
    Eigen::MatrixXd X(rows(), 2);
    for (int i = 0; i < rows(); ++i) X.row(i) << 1.0, x_[i];
    return X;
  }
  std::vector<Bounds> bounds_;
  int calls = 0;

 private:
  std::vector<double> x_, y_;
};

// y_i = a exp(b x_i) + noise, p = (a, b): a profile that is not a straight line's.
class Growth : public LeastSquares {
 public:
  Growth() {
    std::mt19937 rng(11);
    std::normal_distribution<double> g(0.0, 0.05);
    for (int i = 0; i < 25; ++i) {
      x_.push_back(0.1 * i);
      y_.push_back(1.5 * std::exp(0.8 * x_.back()) + g(rng));
    }
  }
  int rows() const override { return static_cast<int>(x_.size()); }
  const std::vector<Bounds>& bounds() const override { return bounds_; }
  bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
    r.resize(rows());
    for (int i = 0; i < rows(); ++i) r[i] = y_[i] - p[0] * std::exp(p[1] * x_[i]);
    return true;
  }

 private:
  std::vector<Bounds> bounds_{{-100, 100}, {-10, 10}};
  std::vector<double> x_, y_;
};

TEST(TQuantile, KnownValues) {
  EXPECT_NEAR(t_quantile(1), 12.706, 1e-3);
  EXPECT_NEAR(t_quantile(10), 2.228, 1e-3);
  EXPECT_NEAR(t_quantile(1e6), 1.960, 1e-3);
}

TEST(LinearisedUncertainty, IsOrdinaryLeastSquaresOnALine) {
  Line line(1.0, 2.0, 0.1, 3);
  const Fit fit = levenberg_marquardt(line, Eigen::Vector2d(0, 0), {true, true}, 50);
  const int dof = line.rows() - 2;
  const double s2 = fit.S / dof;
  Eigen::MatrixXd J;
  ASSERT_TRUE(jacobian(line, fit.p, fit.r, {true, true}, J));
  const LinearisedUncertainty u = linearised_uncertainty(J, s2, {"a", "b"}, 1e6, 0.99);
  const Eigen::MatrixXd X = line.design();
  const Eigen::MatrixXd cov = s2 * (X.transpose() * X).inverse();
  EXPECT_NEAR(u.se[0], std::sqrt(cov(0, 0)), 1e-9 * std::sqrt(cov(0, 0)));
  EXPECT_NEAR(u.se[1], std::sqrt(cov(1, 1)), 1e-9 * std::sqrt(cov(1, 1)));
  EXPECT_NEAR(u.correlation(0, 1), cov(0, 1) / std::sqrt(cov(0, 0) * cov(1, 1)), 1e-9);
  EXPECT_TRUE(u.warnings.empty());
}

TEST(ProfileLimit, IsTheTIntervalOfALinearModel) {
  Line line(1.0, 2.0, 0.1, 5);
  const Fit fit = levenberg_marquardt(line, Eigen::Vector2d(0, 0), {true, true}, 50);
  const int dof = line.rows() - 2;
  const double s2 = fit.S / dof, c = t_quantile(dof);
  Eigen::MatrixXd J;
  ASSERT_TRUE(jacobian(line, fit.p, fit.r, {true, true}, J));
  const LinearisedUncertainty u = linearised_uncertainty(J, s2, {"a", "b"}, 1e6, 0.99);
  for (std::size_t j = 0; j < 2; ++j)
    for (const int side : {-1, 1}) {
      const ProfileLimit limit = profile_limit(line, fit, j, side, u.se[j], c, s2);
      ASSERT_TRUE(std::isfinite(limit.at));
      EXPECT_FALSE(limit.open);
      // The search stops within 3 % of the level: the profile of a linear model is exact.
      const double half = side * (limit.at - fit.p[static_cast<Eigen::Index>(j)]);
      EXPECT_NEAR(half / (c * u.se[j]), 1.0, 0.03) << "parameter " << j << " side " << side;
    }
}

TEST(ProfileLimit, TheInnerFitsStartWhereTheLinearisedProblemPutsTheOthers) {
  // On a straight line the others' conditional minimiser is exactly where the fit's Jacobian
  // puts them: each probe's inner fit starts at its minimum and needs no finite differences, so
  // that a limit costs one model run per probe (it was 1 + 1 finite difference + its trials).
  Line line(1.0, 2.0, 0.1, 5);
  const Fit fit = levenberg_marquardt(line, Eigen::Vector2d(0, 0), {true, true}, 50);
  const int dof = line.rows() - 2;
  const double s2 = fit.S / dof, c = t_quantile(dof);
  const LinearisedUncertainty u = linearised_uncertainty(fit.J, s2, {"a", "b"}, 1e6, 0.99);
  for (std::size_t j = 0; j < 2; ++j)
    for (const int side : {-1, 1}) {
      line.calls = 0;
      const ProfileLimit limit = profile_limit(line, fit, j, side, u.se[j], c, s2);
      ASSERT_TRUE(std::isfinite(limit.at));
      EXPECT_EQ(line.calls, 1) << "parameter " << j << " side " << side;
    }
}

TEST(ProfileLimit, ItsLevelIsTheIndependentlyMinimisedObjectivesOnACurvedModel) {
  // At each limit, the objective minimised over the other parameter from scratch (a fit of 100
  // iterations from the estimate, nothing carried over from the profile's search) must be at
  // the profile's level S + s2 c^2 to the search's tolerance (3 % of c).
  Growth model;
  const Fit fit = levenberg_marquardt(model, Eigen::Vector2d(1, 1), {true, true}, 100);
  ASSERT_TRUE(fit.converged) << fit.message;
  const int dof = model.rows() - 2;
  const double s2 = fit.S / dof, c = t_quantile(dof);
  const LinearisedUncertainty u = linearised_uncertainty(fit.J, s2, {"a", "b"}, 1e6, 0.99);
  for (std::size_t j = 0; j < 2; ++j)
    for (const int side : {-1, 1}) {
      const ProfileLimit limit = profile_limit(model, fit, j, side, u.se[j], c, s2);
      ASSERT_TRUE(std::isfinite(limit.at));
      Eigen::VectorXd p = fit.p;
      p[static_cast<Eigen::Index>(j)] = limit.at;
      std::vector<bool> others(2, true);
      others[j] = false;
      const Fit inner = levenberg_marquardt(model, p, others, 100);
      const double delta = std::sqrt((inner.S - fit.S) / s2);
      EXPECT_NEAR(delta / c, 1.0, 0.03) << "parameter " << j << " side " << side;
    }
}

TEST(ProfileLimit, AParameterWithoutEffectIsFlat) {
  // Columns 2 and 3 both multiply x: the line cannot tell them apart.
  class Twins : public Line {
   public:
    Twins() : Line(1.0, 2.0, 0.1, 7) { bounds_ = {{-100, 100}, {-100, 100}, {-1, 1}}; }
    int rows() const override { return Line::rows(); }
    bool residual(const Eigen::VectorXd& p, Eigen::VectorXd& r) override {
      return Line::residual(Eigen::Vector2d(p[0], p[1] + 0.0 * p[2]), r);
    }
  } twins;
  const Fit fit = levenberg_marquardt(twins, Eigen::Vector3d(0, 0, 0), {true, true, true}, 50);
  Eigen::MatrixXd J;
  ASSERT_TRUE(jacobian(twins, fit.p, fit.r, {true, true, true}, J));
  const LinearisedUncertainty u = linearised_uncertainty(J, fit.S / 27, {"a", "b", "c"}, 1e6, 0.99);
  EXPECT_TRUE(std::isnan(u.se[2]));
  ASSERT_FALSE(u.warnings.empty());
  EXPECT_NE(u.warnings.front().find("c has no effect"), std::string::npos) << u.warnings.front();
  const ProfileLimit limit = profile_limit(twins, fit, 2, 1, u.se[2], t_quantile(27), fit.S / 27);
  EXPECT_TRUE(limit.open);
}

TEST(LinearisedUncertainty, CollinearColumnsCannotBeToldApart) {
  Eigen::MatrixXd J(10, 2);
  for (int i = 0; i < 10; ++i) J.row(i) << i + 1.0, (i + 1.0) * (1 + 1e-6 * (i % 2));
  const LinearisedUncertainty u = linearised_uncertainty(J, 1.0, {"ksh", "ksv"}, 1e6, 0.99);
  EXPECT_GT(u.condition, 1e6);
  bool singular = false, apart = false;
  for (const std::string& w : u.warnings) {
    singular = singular || w.find("near-singular") != std::string::npos;
    apart = apart || w.find("ksh and ksv cannot be told apart") != std::string::npos;
  }
  EXPECT_TRUE(singular);
  EXPECT_TRUE(apart);
}

}  // namespace
}  // namespace oscidrum::detail
