// Dual numbers (src/util/dual.hpp): each operation carries the derivatives by the chain rule,
// checked against closed-form derivatives of a composite expression and against differences.
#include <gtest/gtest.h>

#include <cmath>

#include "tolerances.hpp"
#include "util/dual.hpp"

namespace oscidrum::detail {
namespace {

using D = Dual<2>;

// f(x, y) = (x y + 3) / (x - y) - 2 x / y + 5 - x, with its gradient written out.
template <class T>
T f(const T& x, const T& y) {
  return (x * y + 3.0) / (x - y) - 2.0 * x / y + 5.0 - x;
}

TEST(Dual, ArithmeticCarriesTheGradient) {
  for (double x : {0.3, 1.7, -2.5}) {
    for (double y : {-0.8, 0.45, 3.0}) {
      const D r = f(D::variable(x, 0), D::variable(y, 1));
      EXPECT_DOUBLE_EQ(r.v, f(x, y));
      const double u = x * y + 3.0, w = x - y;
      const double dfdx = (y * w - u) / (w * w) - 2.0 / y - 1.0;
      const double dfdy = (x * w + u) / (w * w) + 2.0 * x / (y * y);
      EXPECT_NEAR(r.d[0], dfdx, test::kIdentity * (1.0 + std::abs(dfdx)));
      EXPECT_NEAR(r.d[1], dfdy, test::kIdentity * (1.0 + std::abs(dfdy)));
    }
  }
}

TEST(Dual, ChainAppliesTheSlope) {
  // tanh through chain(): value tanh(a), slope 1 - tanh^2, against central differences.
  const double x = 0.37, h = 1e-6;
  const D a = D::variable(x, 0) * 2.0 - 0.1;
  const double th = std::tanh(a.v);
  const D t = D::chain(a, th, 1.0 - th * th);
  const double fd = (std::tanh(2.0 * (x + h) - 0.1) - std::tanh(2.0 * (x - h) - 0.1)) / (2 * h);
  EXPECT_NEAR(t.d[0], fd, test::kFiniteDifference);
  EXPECT_EQ(t.d[1], 0.0);
  EXPECT_EQ(value_of(t), th);
  EXPECT_EQ(value_of(2.5), 2.5);
}

TEST(Dual, ConstantsHaveNoDerivative) {
  const D c = 4.0;
  EXPECT_EQ(c.d[0], 0.0);
  EXPECT_EQ(c.d[1], 0.0);
  const D v = D::variable(2.0, 1);
  const D q = 1.0 / v;  // -1 / v^2
  EXPECT_DOUBLE_EQ(q.d[1], -0.25);
  EXPECT_DOUBLE_EQ((-v).d[1], -1.0);
}

}  // namespace
}  // namespace oscidrum::detail
