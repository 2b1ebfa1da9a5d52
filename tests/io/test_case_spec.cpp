// Tests of src/io/case_spec.cpp: a case as the user wrote it becomes a Case: typed assignment,
// the shorthands soil.table2_G and MMd_fraction, the soil input and the keys in effect, the rules
// that tie keys together, each error naming the origin of its key.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "oscidrum_io/config.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

TEST(CaseFile, CrossFieldRulesNameTheOrigin) {
  EXPECT_EQ(
      case_error("[trough]\na = 0.5\n").rfind("case.toml:2:1: trough.a must be > roller.r", 0), 0u);
  EXPECT_EQ(
      case_error("[soil]\ninput = \"coefficients\"\nG = 30e6\n")
          .rfind("case.toml:3:1: soil.G has no effect while soil.input = \"coefficients\"", 0),
      0u);
  // The default soil is Table 2: G picks its row (a G it does not hold is an error at G's line),
  // nu and rho have no effect there.
  EXPECT_EQ(case_error("[soil]\nG = 27e6\n")
                .rfind("case.toml:2:1: soil.G must be a G of paper Table 2 while soil.input = "
                       "\"table2\"",
                       0),
            0u);
  EXPECT_EQ(case_error("[soil]\nnu = 0.35\n")
                .rfind("case.toml:2:1: soil.nu has no effect while soil.input = \"table2\"", 0),
            0u);
  EXPECT_NE(case_error("[soil]\ninput = \"modulus\"\nksh = 1e7\n").find("soil.ksh has no effect"),
            std::string::npos);
  EXPECT_NE(case_error("MMd = 1\nMMd_fraction = 0.05\n").find("MMd cannot be given together"),
            std::string::npos);
  // Finite inputs whose product is not: the key written is named, at its line (the message named
  // MMd, or the run ended non_finite with M0 = inf).
  EXPECT_EQ(case_error("MMd_fraction = 1e308\n")
                .rfind("case.toml:1:1: MMd_fraction = 1e+308 gives MMd = MMd_fraction * M0 beyond "
                       "double precision",
                       0),
            0u)
      << case_error("MMd_fraction = 1e308\n");
  EXPECT_EQ(case_error("[roller]\nunbalance = 1e308\n")
                .rfind("case.toml:2:1: roller.unbalance = 1e+308 kg m^2 at roller.f = 39 Hz gives "
                       "M0",
                       0),
            0u)
      << case_error("[roller]\nunbalance = 1e308\n");
}

TEST(CaseFile, Table2ShorthandTakesTheTableRow) {
  const Case c = read("[soil]\ntable2_G = 40e6\n");
  const Soil t = table2_soil(40e6);
  EXPECT_EQ(c.soil.input, SoilInput::table2);  // the shorthand is a value of the soil input
  EXPECT_EQ(c.soil.G, 40e6);
  // The model makes the one conversion.
  const Model model(c);
  EXPECT_EQ(model.ksh(), t.ksh);
  EXPECT_EQ(model.ksv(), t.ksv);
  EXPECT_EQ(model.csh(), t.csh);
  EXPECT_EQ(model.csv(), t.csv);
  EXPECT_EQ(read("[soil]\ninput = \"table2\"\nG = 40e6\n").soil.G, 40e6);  // the same, spelt out
  EXPECT_NE(case_error("[soil]\ntable2_G = 42e6\n").find("must be a G of paper Table 2"),
            std::string::npos);
  EXPECT_NE(case_error("[soil]\ntable2_G = 40\n").find("did you mean 40000000?"),
            std::string::npos);
  EXPECT_NE(case_error("[soil]\ntable2_G = 40e6\nksh = 1e7\n")
                .find("soil.ksh has no effect while soil.input = \"table2\""),
            std::string::npos);
  EXPECT_NE(case_error("[soil]\ntable2_G = 40e6\ninput = \"modulus\"\n")
                .find("soil.input cannot be set together with soil.table2_G"),
            std::string::npos);
  // A later soil.G keeps the Table 2 choice (a sweep over soil.G on a Table 2 base).
  CaseSpec spec;
  read_case_text("[soil]\ntable2_G = 40e6\n", "case.toml", spec);
  assign(spec, "soil.G", 10e6, "sweep");
  EXPECT_EQ(Model(finalize(spec)).ksh(), table2_soil(10e6).ksh);
  // A soil.G given before soil.table2_G would be dropped: refused, naming both (in one file, in
  // either order, and a --set soil.G under a sweep over soil.table2_G).
  for (const char* text :
       {"[soil]\nG = 25e6\ntable2_G = 30e6\n", "[soil]\ntable2_G = 30e6\nG = 25e6\n"}) {
    const std::string error = case_error(text);
    EXPECT_NE(error.find("soil.table2_G cannot be set together with soil.G (case.toml:"),
              std::string::npos)
        << error;
  }
  CaseSpec set_first;
  assign(set_first, "soil.G", 30e6, "--set soil.G=30e6");
  EXPECT_THROW(assign(set_first, "soil.table2_G", 5e6, "sweep"), Error);
  // The same soil.table2_G again (a sweep over it on a base case that has it) is no conflict.
  CaseSpec again;
  read_case_text("[soil]\ntable2_G = 40e6\n", "case.toml", again);
  assign(again, "soil.table2_G", 10e6, "sweep");
  EXPECT_EQ(finalize(again).soil.G, 10e6);
}

// Coefficients given while soil.input is left at its default (Table 2) give the soil by its
// coefficients, the others from the Table 2 row at soil.G, as before Table 2 was an input.
TEST(CaseFile, CoefficientKeysAloneGiveTheSoilByItsCoefficients) {
  const Case c = read("[soil]\nksh = 5e7\n");
  EXPECT_EQ(c.soil.input, SoilInput::coefficients);
  EXPECT_EQ(c.soil.ksh, 5e7);
  EXPECT_EQ(c.soil.ksv, table2_soil(25e6).ksv);
  EXPECT_NE(case_error("[soil]\nksh = 5e7\nG = 30e6\n")
                .find("soil.G has no effect while soil.input = \"coefficients\""),
            std::string::npos);
  EXPECT_NE(case_error("[soil]\ninput = \"table2\"\nksh = 5e7\n")
                .find("case.toml:3:1: soil.ksh has no effect while soil.input = \"table2\""),
            std::string::npos);
}

TEST(CaseFile, MMdFractionFollowsM0) {
  CaseSpec spec;
  read_case_text("MMd_fraction = 0.05\n", "case.toml", spec);
  EXPECT_DOUBLE_EQ(finalize(spec).MMd, 0.05 * Roller{}.M0);
  assign(spec, "roller.M0", 40000.0, "sweep");
  EXPECT_DOUBLE_EQ(finalize(spec).MMd, 2000.0);
}

// roller.unbalance is the alternative to roller.M0: M0 = 4 m_u e_u e_w nu^2 (5). Giving both is
// an error; changing f with M0 fixed is a warning; MMd_fraction refers to the M0 in use.
TEST(CaseFile, UnbalanceReplacesM0AndFixedM0WithNewFWarns) {
  CaseSpec spec;
  read_case_text("MMd_fraction = 0.05\n[roller]\nunbalance = 0.22877\nf = 19.5\n", "case.toml",
                 spec);
  std::vector<std::string> warnings;
  Case c = finalize(spec, &warnings);
  EXPECT_TRUE(warnings.empty());
  EXPECT_NEAR(c.MMd, 0.05 * 54947.0 / 4.0, 0.05);
  EXPECT_NE(case_error("[roller]\nunbalance = 0.2\nM0 = 50000\n")
                .find("roller.unbalance gives M0 = 4 m_u e_u e_w nu^2 (5), so it cannot be given "
                      "together with roller.M0"),
            std::string::npos);
  CaseSpec fixed;
  read_case_text("[roller]\nf = 30\n", "case.toml", fixed);
  c = finalize(fixed, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("case.toml:2:1: roller.f = 30 Hz with M0 fixed at 54947 N m"),
            std::string::npos)
      << warnings[0];
  EXPECT_EQ(c.roller.M0, 54947.0);
  // Saying the moment is meant (roller.M0 given) silences it.
  warnings.clear();
  read_case_text("[roller]\nM0 = 54947\n", "more.toml", fixed);
  finalize(fixed, &warnings);
  EXPECT_TRUE(warnings.empty());
}

TEST(CaseSpec, AssignTextParsesEachType) {
  CaseSpec spec;
  assign_text(spec, "contact.pure_rolling", "true", "--set");
  assign_text(spec, "soil.input", "modulus", "--set");
  assign_text(spec, "numerics.max_periods", "300", "--set");
  assign_text(spec, "roller.f", "3.5e1", "--set");
  EXPECT_TRUE(spec.values.contact.pure_rolling);
  EXPECT_EQ(spec.values.soil.input, SoilInput::modulus);
  EXPECT_EQ(spec.values.numerics.max_periods, 300);
  EXPECT_EQ(spec.values.roller.f, 35.0);
  EXPECT_EQ(error_of([&] { assign_text(spec, "roller.f", "abc", "--set"); }),
            "roller.f must be a decimal number in [0.1, 1000] [Hz]; got 'abc'");
  EXPECT_EQ(error_of([&] { assign_text(spec, "roller.f", "nan", "--set"); }),
            "roller.f must be a decimal number in [0.1, 1000] [Hz]; got 'nan'");
  EXPECT_EQ(error_of([&] { assign_text(spec, "contact.pure_rolling", "maybe", "--set"); }),
            "contact.pure_rolling must be true or false; got 'maybe'");
  // Issue 14 (4): the field table's rules, as in a config file: no yes/1 booleans, no 5.0 or
  // 1e3 for an integer.
  for (const char* text : {"yes", "1", "on", "True"})
    EXPECT_EQ(error_of([&] { assign_text(spec, "contact.pure_rolling", text, "--set"); }),
              std::string("contact.pure_rolling must be true or false; got '") + text + "'");
  for (const char* text : {"5.0", "1e3", "0x10", " 5", ""})
    EXPECT_EQ(error_of([&] { assign_text(spec, "numerics.max_periods", text, "--set"); }),
              std::string(
                  "numerics.max_periods must be an integer in [1, 10000000] (digits only); got '") +
                  text + "'");
  EXPECT_EQ(case_error("[numerics]\nmax_periods = 1e3\n"),
            "case.toml:2:1: numerics.max_periods must be an integer in [1, 10000000]; got 1000 "
            "written as a float (5.0, 1e3 are floats): write 1000, without a decimal point or "
            "exponent");
  // A range over an integer key still gives integers.
  const StudySpec st = read_study_text(
      "[sweep]\n\"numerics.max_periods\" = { start = 1000, stop = 3000, num = 3 }\n", "s", "");
  EXPECT_EQ(expand(st).cases.at(2).numerics.max_periods, 3000);
}

}  // namespace
}  // namespace oscidrum::io
