// Tests of the trough shape as a component (src/physics/trough.cpp): the case keys' meaning
// (k = 0 is the circle of radius a), the registered shapes, and the functions on a TroughShape,
// which must give what the held shape's own functions give.
#include <gtest/gtest.h>

#include <string>
#include <variant>
#include <vector>

#include "oscidrum/error.hpp"
#include "oscidrum/trough.hpp"

namespace oscidrum {
namespace {

constexpr double kR = 0.6;  // drum radius [m]

TEST(Trough, TheCaseKeysDescribeTheSpiralFamily) {
  const TroughShape circle = trough_shape(0.0, 0.606);
  ASSERT_TRUE(std::holds_alternative<CircleTrough>(circle));
  EXPECT_EQ(std::get<CircleTrough>(circle).R, 0.606);
  const TroughShape spiral = trough_shape(0.05, 0.65);
  ASSERT_TRUE(std::holds_alternative<LogSpiralTrough>(spiral));
  EXPECT_EQ(std::get<LogSpiralTrough>(spiral), LogSpiralTrough(0.05, 0.65));
  // And back: key_value reads the keys that built the shape.
  for (const auto& [k, a] :
       {std::pair{0.0, 0.606}, std::pair{0.002, 0.601}, std::pair{0.05, 0.65}}) {
    const TroughShape s = trough_shape(k, a);
    EXPECT_EQ(key_value(s, "trough.k"), k);
    EXPECT_EQ(key_value(s, "trough.a"), a);
  }
}

TEST(Trough, ShapesAreRegisteredByName) {
  EXPECT_EQ(trough_shape_names(), (std::vector<std::string>{"circle", "log_spiral"}));
  EXPECT_EQ(std::string(trough_name(trough_shape(0.0, 0.606))), "circle");
  EXPECT_EQ(std::string(trough_name(trough_shape(0.002, 0.601))), "log_spiral");
}

// The functions on the variant hand over to the held shape's own.
TEST(Trough, DispatchesToTheHeldShape) {
  const CircleTrough circle{0.62};
  const LogSpiralTrough spiral(0.002, 0.601);
  EXPECT_EQ(summary(TroughShape(circle)), summary(circle));
  EXPECT_EQ(summary(TroughShape(spiral)), summary(spiral));
  EXPECT_EQ(curvature_radius_at_bottom(TroughShape(circle)), curvature_radius_at_bottom(circle));
  EXPECT_EQ(curvature_radius_at_bottom(TroughShape(spiral)), curvature_radius_at_bottom(spiral));
  EXPECT_EQ(std::string(curvature_radius_formula(TroughShape(spiral))),
            curvature_radius_formula(spiral));
  EXPECT_EQ(parameters(TroughShape(spiral)).size(), parameters(spiral).size());
  EXPECT_EQ(fit_problem(TroughShape(CircleTrough{0.59}), kR).message,
            fit_problem(CircleTrough{0.59}, kR).message);
}

// check_fit raises the shape's problem as an oscidrum::Error that carries the key and its value.
TEST(Trough, CheckFitRaisesTheShapesProblemWithItsKey) {
  EXPECT_NO_THROW(check_fit(trough_shape(0.0, 0.606), kR));
  EXPECT_NO_THROW(check_fit(trough_shape(0.002, 0.601), kR));
  try {
    check_fit(trough_shape(0.0, 0.6), kR);
    ADD_FAILURE() << "R = r accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("trough.a must be > roller.r"), std::string::npos);
    EXPECT_EQ(e.key(), "trough.a");
    EXPECT_EQ(e.value(), 0.6);
  }
  try {
    check_fit(trough_shape(0.5, 0.05), kR);
    ADD_FAILURE() << "a spiral tighter than the drum accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("curvature radius"), std::string::npos);
    EXPECT_EQ(e.key(), "trough.a");
    EXPECT_EQ(e.value(), 0.05);
  }
}

}  // namespace
}  // namespace oscidrum
