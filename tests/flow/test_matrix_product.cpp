// The 8x8 product kernels of the variational equations (src/flow/matrix_product.hpp): each one
// this processor can run must give Eigen's lazyProduct to the bit (compiled here with the
// project's flags), so that a study's numbers do not depend on the machine's vector width.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "flow/matrix_product.hpp"

namespace {

using Mat8 = Eigen::Matrix<double, 8, 8>;
using oscidrum::detail::wide_product8_kernels;

// The same bits, or NaN in both (a NaN's payload is not a result).
bool same(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Entries over 24 decades of both signs, some exact zeros (the Jacobians' zero rows and column),
// so that a kernel that summed in another order or fused a multiply and an add would round
// differently somewhere.
Mat8 random_matrix(std::mt19937_64& rng, bool zeros) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), decade(-12.0, 12.0);
  Mat8 M;
  for (int i = 0; i < 64; ++i) M.data()[i] = unit(rng) * std::pow(10.0, decade(rng));
  if (zeros)
    for (int i = 0; i < 64; i += 3) M.data()[i] = 0.0;
  return M;
}

TEST(MatrixProduct, EveryKernelGivesEigensProductToTheBit) {
  const auto kernels = wide_product8_kernels();
  if (kernels.empty()) GTEST_SKIP() << "no AVX2: the products are Eigen's own";
  std::mt19937_64 rng(20261207);
  for (const auto& kernel : kernels) {
    long differing = 0;
    for (int trial = 0; trial < 20000; ++trial) {
      const Mat8 A = random_matrix(rng, trial % 4 == 0), B = random_matrix(rng, trial % 5 == 0);
      const Mat8 expected = A.lazyProduct(B);
      Mat8 C;
      kernel.multiply(A.data(), B.data(), C.data());
      for (int i = 0; i < 64; ++i)
        if (!same(C.data()[i], expected.data()[i])) ++differing;
    }
    EXPECT_EQ(differing, 0) << kernel.name;
  }
}

// Signed zeros, infinities and NaN propagate as in Eigen's product: -0 * 0 + ... keeps the sign
// rules of IEEE addition, inf * 0 gives NaN.
TEST(MatrixProduct, SpecialValuesPropagateAsInEigensProduct) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Mat8 A = Mat8::Zero(), B = Mat8::Zero();
  A.col(0).setConstant(-0.0);
  A(1, 2) = inf;
  A(3, 4) = nan;
  B(2, 5) = 1.0;
  B(2, 6) = 0.0;
  B(0, 7) = -1.0;
  const Mat8 expected = A.lazyProduct(B);
  for (const auto& kernel : wide_product8_kernels()) {
    Mat8 C;
    kernel.multiply(A.data(), B.data(), C.data());
    for (int i = 0; i < 64; ++i)
      EXPECT_TRUE(same(C.data()[i], expected.data()[i]))
          << kernel.name << " entry " << i << ": " << C.data()[i] << " against "
          << expected.data()[i];
  }
}

// product() takes the widest kernel for 8x8 (Eigen's product without one) and Eigen's product for
// any other size (the unilateral drum's 10 states).
TEST(MatrixProduct, OtherSizesUseEigensProduct) {
  std::mt19937_64 rng(7);
  const Mat8 A = random_matrix(rng, false), B = random_matrix(rng, true);
  const Mat8 C = oscidrum::detail::product(A, B), expected = A.lazyProduct(B);
  EXPECT_EQ(std::memcmp(C.data(), expected.data(), sizeof(double) * 64), 0);
  using Mat10 = Eigen::Matrix<double, 10, 10>;
  const Mat10 X = Mat10::Random(), Y = Mat10::Random();
  const Mat10 Z = oscidrum::detail::product(X, Y), W = X.lazyProduct(Y);
  EXPECT_EQ(std::memcmp(Z.data(), W.data(), sizeof(double) * 100), 0);
}

}  // namespace
