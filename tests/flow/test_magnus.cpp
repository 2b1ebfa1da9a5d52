// The variational equations' integrator on its own (src/flow/magnus.hpp): the balanced matrix
// exponential against exponentials known in closed form, on matrices whose entries spread over
// many decades as the state's units spread the Jacobians', and the Magnus step of order 6: exact
// for a constant J, of order 6 for a J that changes (its error falls 64-fold when the step halves).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <cstring>
#include <random>

#include "flow/monodromy.hpp"

namespace {

using Mat = Eigen::Matrix<double, 6, 6>;
using Vec = Eigen::Matrix<double, 6, 1>;
using oscidrum::detail::balanced_exponential;
using oscidrum::detail::magnus6_exponent;

// Largest entry of X, each divided by its scale d_i / d_j (the mixed units of a Jacobian).
double scaled_max(const Mat& X, const Vec& d) {
  double m = 0.0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) m = std::max(m, std::abs(X(i, j)) * d[j] / d[i]);
  return m;
}

// A = D V diag(lambda) V^-1 D^-1 has exp(A) = D V diag(exp(lambda)) V^-1 D^-1: eigenvalues from
// stiff (-40) to growing (+3), a pair rotating (the soil's and the drum's oscillations), and D
// spreading the entries over twelve decades.
TEST(MatrixExponential, AgreesWithTheClosedFormOnBadlyScaledMatrices) {
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), rate(-40.0, 3.0), decade(-6.0, 6.0);
  for (int trial = 0; trial < 100; ++trial) {
    Mat V = Mat::Identity() + 0.5 * Mat::NullaryExpr([&] { return unit(rng); });
    Mat L = Mat::Zero(), eL = Mat::Zero();
    for (int i = 0; i < 4; ++i) {
      L(i, i) = rate(rng);
      eL(i, i) = std::exp(L(i, i));
    }
    const double sigma = rate(rng) / 4.0, omega = 6.0 * unit(rng);  // sigma +- i omega
    L(4, 4) = L(5, 5) = sigma;
    L(4, 5) = omega;
    L(5, 4) = -omega;
    eL(4, 4) = eL(5, 5) = std::exp(sigma) * std::cos(omega);
    eL(4, 5) = std::exp(sigma) * std::sin(omega);
    eL(5, 4) = -eL(4, 5);
    Vec d;
    for (int i = 0; i < 6; ++i) d[i] = std::pow(10.0, decade(rng));
    const Mat Vi = V.inverse();
    const Mat D = d.asDiagonal(), Di = d.cwiseInverse().asDiagonal();
    const Mat A = D * (V * L * Vi) * Di, expected = D * (V * eL * Vi) * Di;
    Vec balance = Vec::Ones();
    const Mat got = balanced_exponential(A, balance, 3);
    EXPECT_LT(scaled_max(got - expected, d), 1e-11 * scaled_max(expected, d)) << trial;
    EXPECT_TRUE((balance.array() > 0.0).all());
  }
}

TEST(MatrixExponential, OfZeroIsTheIdentityAndOfNaNIsNaN) {
  Vec d = Vec::Ones();
  EXPECT_EQ(balanced_exponential(Mat::Zero().eval(), d, 3), Mat::Identity());
  Mat bad = Mat::Identity();
  bad(2, 3) = std::nan("");
  d.setOnes();
  EXPECT_TRUE(balanced_exponential(bad, d, 3).array().isNaN().all());
  bad(2, 3) = HUGE_VAL;
  d.setOnes();
  EXPECT_TRUE(balanced_exponential(bad, d, 3).array().isNaN().all());
}

// A constant J: the exponent is h J, whatever the stiffness h |lambda|.
TEST(Magnus, IsExactForAConstantJacobian) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Mat J = 1e3 * Mat::NullaryExpr([&] { return unit(rng); });
  const Mat omega = magnus6_exponent(0.01, J, J, J);
  EXPECT_LT((omega - 0.01 * J).cwiseAbs().maxCoeff(), 1e-13 * (0.01 * J).cwiseAbs().maxCoeff());
}

// J(t) = A + sin(3 t) B + t^2 C with A, B, C not commuting: Phi(1) by n Magnus steps against 1024
// of them; the error falls as n^-6.
TEST(Magnus, ConvergesWithOrderSix) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Mat A = Mat::NullaryExpr([&] { return unit(rng); }),
            B = Mat::NullaryExpr([&] { return unit(rng); }),
            C = Mat::NullaryExpr([&] { return unit(rng); });
  const auto J = [&](double t) -> Mat { return A + std::sin(3.0 * t) * B + t * t * C; };
  const auto phi = [&](int n) {
    Mat p = Mat::Identity();
    Vec d = Vec::Ones();
    const double h = 1.0 / n, r = oscidrum::detail::kMagnusNode;
    for (int i = 0; i < n; ++i) {
      const double t = i * h;
      const Mat omega =
          magnus6_exponent(h, J(t + (0.5 - r) * h), J(t + 0.5 * h), J(t + (0.5 + r) * h));
      p = (balanced_exponential(omega, d, 1) * p).eval();
    }
    return p;
  };
  const Mat reference = phi(1024);
  const double scale = reference.cwiseAbs().maxCoeff();
  double previous = 0.0;
  for (int n : {4, 8, 16, 32}) {
    const double error = (phi(n) - reference).cwiseAbs().maxCoeff() / scale;
    if (n > 4) {
      const double order = std::log2(previous / error);
      EXPECT_GT(order, 5.5) << n;
      EXPECT_LT(order, 6.8) << n;
    }
    previous = error;
  }
  EXPECT_LT(previous, 1e-9);
}

// The wide kernels of a Magnus step (src/flow/wide_kernels.cpp: the same code compiled for AVX2
// and AVX-512) give the generic step's exponential to the bit, and update the balance d the same:
// on 8 x 8 Jacobians with the drum's shape (unit rows for the positions' rates, entries over
// twelve decades), steps from 1e-6 to 3e-3 s (no squaring to several), with and without the
// balancing sweeps, and on a non-finite Jacobian.
TEST(Magnus, WideKernelsGiveTheGenericStepToTheBit) {
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  using Vec8 = Eigen::Matrix<double, 8, 1>;
  const auto kernels = oscidrum::detail::wide_magnus_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no AVX2: the generic step runs";
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), decade(-6.0, 6.0), step(-6.0, -2.5);
  const auto same = [](const Mat8& a, const Mat8& b) {
    for (int i = 0; i < 64; ++i) {
      const double x = a.data()[i], y = b.data()[i];
      if (std::isnan(x) || std::isnan(y)) {
        if (!(std::isnan(x) && std::isnan(y))) return false;
      } else if (std::memcmp(&x, &y, sizeof x) != 0) {
        return false;
      }
    }
    return true;
  };
  for (int trial = 0; trial < 400; ++trial) {
    Vec8 scale;
    for (int i = 0; i < 8; ++i) scale[i] = std::pow(10.0, decade(rng));
    const auto jacobian = [&] {
      Mat8 J;
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) J(i, j) = unit(rng) * 300.0 * scale[i] / scale[j];
      for (int i = 0; i < 3; ++i) {  // position rates: unit rows
        J.row(i).setZero();
        J(i, i + 4) = 1.0;
      }
      return J;
    };
    Mat8 J1 = jacobian(), J2 = jacobian(), J3 = jacobian();
    if (trial == 399) J2(5, 1) = std::nan("");
    const double h = std::pow(10.0, step(rng));
    const int sweeps = trial % 2 == 0 ? 3 : 0;
    Vec8 d0 = Vec8::Ones();
    if (sweeps == 0) d0 = scale;
    Vec8 d_generic = d0;
    const Mat8 expected = oscidrum::detail::balanced_exponential(
        oscidrum::detail::magnus6_exponent(h, J1, J2, J3), d_generic, sweeps);
    for (const auto& kernel : kernels) {
      Vec8 d = d0;
      const Mat8 got = kernel.exponential(h, J1, J2, J3, d, sweeps);
      EXPECT_TRUE(same(got, expected)) << kernel.name << " trial " << trial;
      EXPECT_EQ(std::memcmp(d.data(), d_generic.data(), sizeof(double) * 8), 0) << kernel.name;
    }
    Vec8 d = d0;
    EXPECT_TRUE(same(oscidrum::detail::magnus_exponential(h, J1, J2, J3, d, sweeps), expected));
  }
}

}  // namespace
