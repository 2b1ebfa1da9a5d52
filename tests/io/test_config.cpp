// Tests of src/io/config.cpp: case and study files in TOML (sections, dotted and quoted
// keys, types, locations in messages, ranges and nested sweep tables, base files) and a case
// written back as TOML.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

TEST(CaseFile, SectionsTopLevelAndDottedKeysSetFields) {
  const Case c = read(
      "MMd = 1000.0\n"
      "[roller]\nr = 0.55\nf = 30   # an integer is fine for a real field\n"
      "[contact]\npure_rolling = true\n"
      "[numerics]\nmax_periods = 200\n");
  EXPECT_EQ(c.MMd, 1000.0);
  EXPECT_EQ(c.roller.r, 0.55);
  EXPECT_EQ(c.roller.f, 30.0);
  EXPECT_TRUE(c.contact.pure_rolling);
  EXPECT_EQ(c.numerics.max_periods, 200);
  // A dotted key at the top level.
  EXPECT_EQ(get_field(read("trough.a = 0.62\n"), "trough.a"), 0.62);
  // A quoted key with a dot is one key of that name in TOML, not the dotted key (issue 24, 11).
  EXPECT_EQ(case_error("'roller.r' = 0.6\n"),
            "case.toml:1:1: 'roller.r' is a quoted key: TOML reads it as one key named "
            "\"roller.r\", not as a dotted key; write it without quotes (roller.r = ...) or under "
            "its [section]");
  EXPECT_NE(case_error("[roller]\n\"r.x\" = 0.6\n").find("'r.x' is a quoted key"),
            std::string::npos);
  EXPECT_EQ(read("[roller]\n\"r\" = 0.55\n").roller.r, 0.55);  // quoted without a dot: the key
  // ... but after a [section] header it belongs to that section.
  EXPECT_NE(case_error("[numerics]\ntrough.a = 0.62\n").find("unknown parameter 'numerics.trough'"),
            std::string::npos);
}

TEST(CaseFile, ErrorsNameFileLineKeyRuleAndValue) {
  EXPECT_EQ(case_error("[soil]\nksh = -5e6\n"),
            "case.toml:2:1: soil.ksh must be > 0 [N/m]; got -5e+06");
  EXPECT_EQ(case_error("[roller]\nr = \"0.6\"\n"),
            "case.toml:2:1: roller.r must be a number [m]; got a string (\"0.6\") (write numbers "
            "and booleans without quotes)");
  EXPECT_EQ(case_error("[contact]\npure_rolling = 1\n"),
            "case.toml:2:1: contact.pure_rolling must be true or false; got an integer (1)");
  EXPECT_EQ(case_error("[numerics]\nmax_periods = 2.5\n"),
            "case.toml:2:1: numerics.max_periods must be an integer in [1, 10000000]; got 2.5");
  EXPECT_EQ(case_error("[soil]\ninput = \"modulos\"\n"),
            "case.toml:2:1: soil.input must be one of coefficients, modulus, table2; got a string "
            "(\"modulos\")");
  EXPECT_EQ(case_error("[roller]\nr = [1, 2]\n"),
            "case.toml:2:1: roller.r must be a single value [m]; got an array");
  EXPECT_EQ(case_error("[roller]\nr = 1979-05-27\n"),
            "case.toml:2:1: roller.r must be a single value [m]; got a date");
}

TEST(CaseFile, UnknownKeysAreErrorsWithSuggestions) {
  EXPECT_EQ(case_error("[soil]\ng = 5\n"),
            "case.toml:2:1: unknown parameter 'soil.g'; did you mean 'soil.G'?");
  EXPECT_EQ(case_error("G = 5\n"), "case.toml:1:1: unknown parameter 'G'; did you mean 'soil.G'?");
  // A typo of a name without its section (no suggestion before: 'MMd' was the nearest whole key).
  EXPECT_EQ(case_error("muu = 0.4\n"),
            "case.toml:1:1: unknown parameter 'muu'; did you mean 'contact.mu'?");
  EXPECT_EQ(case_error("[numerics]\nmax_period = 5\n"),
            "case.toml:2:1: unknown parameter 'numerics.max_period'; did you mean "
            "'numerics.max_periods'?");
  EXPECT_EQ(case_error("[rollr]\nr = 0.6\n"),
            "case.toml:1:2: unknown section [rollr]; did you mean [roller]?");
  EXPECT_NE(case_error("[roller]\nradius = 0.6\n").find("[roller] has r, b, m, I"),
            std::string::npos);
  EXPECT_NE(case_error("[roller.sub]\nx = 1\n").find("unknown parameter 'roller.sub'"),
            std::string::npos);
  EXPECT_NE(case_error("[sweep]\nx = 1\n").find("belongs in a study file"), std::string::npos);
}

TEST(CaseFile, MalformedFilesAreClearErrors) {
  EXPECT_NE(case_error("").find("case.toml: the file holds no settings"), std::string::npos);
  EXPECT_NE(case_error("# only a comment\n").find("holds no settings"), std::string::npos);
  EXPECT_NE(case_error(std::string("a\0b", 3)).find("contains NUL bytes"), std::string::npos);
  EXPECT_NE(case_error("\xff\xfe\x80garbage").find("case.toml:1:1: invalid TOML"),
            std::string::npos);
  EXPECT_NE(case_error("[roller\nr = 1\n").find("case.toml:1:8: invalid TOML"), std::string::npos);
  EXPECT_NE(case_error("[roller]\nr = 1\nr = 2\n").find("invalid TOML"), std::string::npos);
  EXPECT_NE(error_of([] {
              CaseSpec spec;
              read_case_file("/nonexistent/case.toml", spec);
            }).find("cannot read /nonexistent/case.toml: No such file"),
            std::string::npos);
}

TEST(CaseFile, LaterFilesOverrideEarlierOnes) {
  CaseSpec spec;
  read_case_text("[roller]\nr = 0.55\nm = 2000\n", "a.toml", spec);
  read_case_text("[roller]\nr = 0.58\n", "b.toml", spec);
  const Case c = finalize(spec);
  EXPECT_EQ(c.roller.r, 0.58);
  EXPECT_EQ(c.roller.m, 2000.0);
  EXPECT_EQ(spec.origin.at("roller.r"), "b.toml:2:1");
}

TEST(CaseFile, WrittenCaseReadsBackIdentically) {
  Case c;
  c.roller.r = 0.1 + 0.2;  // not short in decimal
  c.MMd = 1.0 / 3.0;
  c.contact.pure_rolling = true;
  c.numerics.max_periods = 1234;
  c.soil.input = SoilInput::coefficients;
  c.soil.ksh = 12345678.9;
  EXPECT_TRUE(same_case(read(case_to_toml(c)), c));

  Case m = c;
  m.soil.input = SoilInput::modulus;
  m.soil.G = 27e6;
  m.soil.nu = 0.35;
  const Case back = read(case_to_toml(m));
  EXPECT_EQ(back.soil.input, SoilInput::modulus);
  EXPECT_EQ(back.soil.G, 27e6);
  EXPECT_EQ(back.soil.nu, 0.35);

  Case t;
  t.soil = table2_soil(30e6);
  EXPECT_TRUE(same_case(read(case_to_toml(t)), t));
  EXPECT_EQ(read(case_to_toml(t)).soil.input, SoilInput::table2);

  Case u;  // given by its unbalance: M0 is written as a comment (both would be an error)
  u.roller.unbalance = 0.22877;
  u.roller.f = 30.0;
  const std::string text = case_to_toml(u);
  EXPECT_NE(text.find("# M0 = "), std::string::npos) << text;
  EXPECT_TRUE(same_case(read(text), u));
}

TEST(Study, RangesAllAndNestedTables) {
  Study s = expand(read_study_text("[sweep]\n\"soil.table2_G\" = \"all\"\n", "study.toml", ""));
  ASSERT_EQ(s.cases.size(), 14u);
  EXPECT_EQ(Model(s.cases[13]).ksv(), table2_soil(70e6).ksv);
  s = expand(read_study_text("[sweep.trough]\na = { start = 0.61, stop = 0.65, step = 0.01 }\n",
                             "study.toml", ""));
  ASSERT_EQ(s.cases.size(), 5u);
  EXPECT_EQ(s.keys.front(), "trough.a");
  EXPECT_DOUBLE_EQ(get_field(s.cases[4], "trough.a"), 0.65);
  s = expand(read_study_text(
      "[soil]\ninput = \"modulus\"\n[sweep]\n\"soil.G\" = { start = 5e6, stop = 70e6, num = 3 }\n",
      "study.toml", ""));
  ASSERT_EQ(s.cases.size(), 3u);
  EXPECT_EQ(s.cases[1].soil.G, 37.5e6);
  EXPECT_EQ(s.cases[2].soil.G, 70e6);
  s = expand(read_study_text(
      "[sweep]\n\"numerics.max_periods\" = { start = 100, stop = 300, step = 100 }\n", "s", ""));
  EXPECT_EQ(format_value(s.varied[2][0]), "300");
}

// Range values print as the user would write them: rounded to the decimals of start, stop and
// step, not start + i * step with its binary rounding (0.30000000000000004).
TEST(Study, RangeValuesAreTheDecimalsAsWritten) {
  Study s = expand(read_study_text(
      "[sweep]\n\"contact.mu\" = { start = 0.2, stop = 0.8, num = 13 }\n", "s", ""));
  ASSERT_EQ(s.cases.size(), 13u);
  const char* want[] = {"0.2",  "0.25", "0.3",  "0.35", "0.4",  "0.45", "0.5",
                        "0.55", "0.6",  "0.65", "0.7",  "0.75", "0.8"};
  for (std::size_t i = 0; i < 13; ++i) {
    EXPECT_EQ(format_value(s.varied[i][0]), want[i]);
    EXPECT_EQ(s.cases[i].contact.mu, std::strtod(want[i], nullptr));
  }
  s = expand(read_study_text("[sweep]\n\"contact.mu\" = { start = 0.1, stop = 0.7, step = 0.1 }\n",
                             "s", ""));
  ASSERT_EQ(s.cases.size(), 7u);
  EXPECT_EQ(format_value(s.varied[2][0]), "0.3");  // 0.1 + 2 * 0.1 = 0.30000000000000004
  EXPECT_EQ(format_value(s.varied[6][0]), "0.7");
  s = expand(read_study_text("[sweep]\n\"roller.f\" = { start = 25.5, stop = 40, step = 0.725 }\n",
                             "s", ""));
  EXPECT_EQ(format_value(s.varied[1][0]), "26.225");
  // A step without a short decimal form keeps the computed values.
  s = expand(
      read_study_text("[sweep]\n\"contact.mu\" = { start = 0, stop = 1, num = 4 }\n", "s", ""));
  EXPECT_EQ(s.cases[1].contact.mu, 1.0 / 3.0);
}

TEST(Study, BaseKeysAndBaseFile) {
  TempDir dir;
  std::ofstream(dir.file("base.toml")) << "[roller]\nm = 2000\n";
  std::ofstream(dir.file("study.toml")) << "base = \"base.toml\"\n[roller]\nr = 0.55\n"
                                           "[sweep]\n\"contact.mu\" = [0.3, 0.5]\n";
  const Study s = expand(read_study_file(dir.file("study.toml")));
  ASSERT_EQ(s.cases.size(), 2u);
  EXPECT_EQ(s.cases[0].roller.m, 2000.0);
  EXPECT_EQ(s.cases[0].roller.r, 0.55);
  EXPECT_EQ(s.cases[1].contact.mu, 0.5);
}

TEST(Study, ErrorsNameTheLineOrTheCase) {
  EXPECT_NE(study_error("[roller]\nr = 0.6\n").find("needs a [sweep] table"), std::string::npos);
  EXPECT_NE(study_error("[sweep]\n").find("names no parameter to vary"), std::string::npos);
  EXPECT_EQ(study_error("[sweep]\n\"soil.ksh\" = [1e7, -1]\n"),
            "study.toml:2:1: sweep value of soil.ksh must be > 0 [N/m]; got -1");
  EXPECT_EQ(study_error("[sweep]\n\"soil.kh\" = [1]\n"),
            "study.toml:2:1: unknown parameter 'soil.kh'; did you mean 'soil.ksh'?");
  EXPECT_NE(study_error("[sweep]\n\"roller.r\" = 0.5\n").find("must be a list"), std::string::npos);
  EXPECT_NE(study_error("[sweep]\n\"roller.r\" = []\n").find("is empty"), std::string::npos);
  // One value sweeps nothing: as a list, a range of num = 1, start = stop or a step past stop.
  EXPECT_NE(study_error("[sweep]\n\"roller.r\" = [0.5]\n").find("has one value"),
            std::string::npos);
  EXPECT_NE(study_error("[sweep]\n\"roller.r\" = {start = 0.5, stop = 0.55, num = 1}\n")
                .find("num must be an integer in [2, "),
            std::string::npos);
  EXPECT_NE(study_error("[sweep]\n\"roller.r\" = {start = 0.5, stop = 0.5, step = 0.01}\n")
                .find("start and stop are both 0.5"),
            std::string::npos);
  EXPECT_NE(study_error("[sweep]\n\"roller.r\" = {start = 0.5, stop = 0.51, step = 0.02}\n")
                .find("range gives one value (0.5)"),
            std::string::npos);
  EXPECT_NE(study_error("[sweep]\nmode = \"cartesian\"\n\"roller.r\" = [0.5]\n")
                .find("sweep.mode must be \"product\" or \"zip\""),
            std::string::npos);
  EXPECT_NE(study_error("[sweep]\n\"trough.a\" = {start = 0.6, stop = 0.5, step = 0.01}\n")
                .find("step must be non-zero and go from start towards stop"),
            std::string::npos);
  EXPECT_EQ(study_error("[sweep]\n\"trough.a\" = [0.62, 0.55]\n")
                .rfind("case 1 (trough.a = 0.55): study.toml:2:1: trough.a must be > roller.r", 0),
            0u);
  EXPECT_NE(study_error("[soil]\ninput = \"coefficients\"\n[sweep]\n\"soil.G\" = [5e6, 6e6]\n")
                .find("soil.G has no effect"),
            std::string::npos);
  // On the default Table 2 soil a swept G picks the row; a G it does not hold names its case.
  EXPECT_NE(study_error("[sweep]\n\"soil.G\" = [5e6, 27e6]\n")
                .find("case 1 (soil.G = 27000000): study.toml:2:1: soil.G must be a G of paper "
                      "Table 2"),
            std::string::npos);
}

}  // namespace
}  // namespace oscidrum::io
