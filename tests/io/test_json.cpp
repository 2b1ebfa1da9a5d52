// Tests of src/io/json.cpp: the study JSON types its cells; a case's JSON holds every parameter,
// the soil the model used and the trough as its shape describes itself.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "io/io_test_util.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/json.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

TEST(Json, StudyJsonTypesCells) {
  const std::string j = study_json("case[-],status[-],x[m],message[-]",
                                   {"0,steady_state,1.5,\"a, b\"", "1,contact_lost,,7"});
  EXPECT_NE(j.find("\"x[m]\": 1.5"), std::string::npos);
  EXPECT_NE(j.find("\"x[m]\": null"), std::string::npos);
  EXPECT_NE(j.find("\"message[-]\": \"7\""), std::string::npos);
  EXPECT_NE(j.find("\"case[-]\": 1"), std::string::npos);
}

// A case's JSON: every parameter, the soil the model used (its conversion of the soil input) and
// the trough as its shape describes itself.
TEST(Json, CaseJsonHoldsTheSoilAndTheTroughAsTheModelUsedThem) {
  CaseSpec spec;
  read_case_text("[soil]\nG = 40e6\n[trough]\nk = 0.002\na = 0.601\n", "case.toml", spec);
  const Case c = finalize(spec);
  const nlohmann::json j =
      nlohmann::json::parse(case_json(spec, c, Result{}, nullptr, "case.toml"));
  EXPECT_EQ(j["parameters"]["soil.input"], "table2");
  EXPECT_EQ(j["parameters"]["soil.G"], 40e6);
  EXPECT_EQ(j["origins"]["soil.G"], "case.toml:2:1");
  const Model model(c);
  EXPECT_EQ(j["soil"]["source"], "table2");
  EXPECT_EQ(j["soil"]["description"], "paper Table 2 at G = 40 MN/m^2");
  EXPECT_EQ(j["soil"]["ksh"], model.ksh());
  EXPECT_EQ(j["soil"]["csv"], model.csv());
  EXPECT_EQ(j["soil"]["a0"], table2_row(40e6)->a0);
  EXPECT_EQ(j["soil"]["nu"], kTable2Nu);
  const nlohmann::json& trough = j["derived"]["trough"];
  const auto& spiral = std::get<LogSpiralTrough>(c.trough.shape);
  EXPECT_EQ(trough["shape"], "log_spiral");
  EXPECT_EQ(trough["k"], 0.002);
  EXPECT_EQ(trough["a"], 0.601);
  EXPECT_EQ(trough["R0"], spiral.R0());
  EXPECT_EQ(trough["alpha"], spiral.alpha());
  EXPECT_EQ(trough["curvature_radius"], curvature_radius_at_bottom(c.trough.shape));
  // A soil given by its coefficients has no G, nu, rho or contact length.
  CaseSpec given;
  read_case_text("[soil]\nksh = 5e7\n", "case.toml", given);
  const nlohmann::json k =
      nlohmann::json::parse(case_json(given, finalize(given), Result{}, nullptr, ""));
  EXPECT_EQ(k["soil"]["source"], "coefficients");
  EXPECT_TRUE(k["soil"]["G"].is_null() && k["soil"]["a0"].is_null());
  EXPECT_EQ(k["soil"]["ksh"], 5e7);
  EXPECT_EQ(k["derived"]["trough"]["shape"], "circle");
  EXPECT_EQ(k["derived"]["trough"]["R"], 0.606);
}

}  // namespace
}  // namespace oscidrum::io
