// Tests of oscidrum_io: case and study files, the shorthand keys, CSV/JSON writers, the journal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum_io/case_spec.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/files.hpp"
#include "oscidrum_io/json.hpp"
#include "oscidrum_io/shard.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io {
namespace {

Case read(const std::string& text) {
  CaseSpec spec;
  read_case_text(text, "case.toml", spec);
  const Case c = finalize(spec);
  validate(c, spec);
  return c;
}

// The message of the oscidrum::Error that `f` throws ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string case_error(const std::string& text) {
  return error_of([&] { read(text); });
}

std::string study_error(const std::string& text) {
  return error_of([&] { expand(read_study_text(text, "study.toml", "")); });
}

// The same case: every key in effect (key_in_effect) has the same value (a key without effect, such
// as soil.ksh under soil.input = "table2", is written as a comment and not read back).
bool same_case(const Case& a, const Case& b) {
  for (const Field& f : fields()) {
    if (key_in_effect(a, f.key) != key_in_effect(b, f.key)) return false;
    if (key_in_effect(a, f.key) && f.get(a) != f.get(b)) return false;
  }
  return true;
}

// A fresh temporary directory per test.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("oscidrum_test_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  static inline int counter_ = 0;
  std::filesystem::path path_;
};

// ---- case files ---------------------------------------------------------------------------

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
            "roller.f must be a number [Hz]; got 'abc'");
  EXPECT_EQ(error_of([&] { assign_text(spec, "roller.f", "nan", "--set"); }),
            "roller.f must be in [0.1, 1000] [Hz]; got nan");
  EXPECT_EQ(error_of([&] { assign_text(spec, "contact.pure_rolling", "maybe", "--set"); }),
            "contact.pure_rolling must be true or false; got 'maybe'");
  // Issue 14 (4): the field table's rules, as in a config file: no yes/1 booleans, no 5.0 or
  // 1e3 for an integer.
  for (const char* text : {"yes", "1", "on", "True"})
    EXPECT_EQ(error_of([&] { assign_text(spec, "contact.pure_rolling", text, "--set"); }),
              std::string("contact.pure_rolling must be true or false; got '") + text + "'");
  for (const char* text : {"5.0", "1e3", "0x10", " 5", ""})
    EXPECT_EQ(
        error_of([&] { assign_text(spec, "numerics.max_periods", text, "--set"); }),
        std::string("numerics.max_periods must be an integer (digits only); got '") + text + "'");
  EXPECT_EQ(case_error("[numerics]\nmax_periods = 1e3\n"),
            "case.toml:2:1: numerics.max_periods must be an integer in [1, 10000000]; got 1000.0 "
            "(write an integer without a decimal point or exponent)");
  // A range over an integer key still gives integers.
  const StudySpec st = read_study_text(
      "[sweep]\n\"numerics.max_periods\" = { start = 1000, stop = 3000, num = 3 }\n", "s", "");
  EXPECT_EQ(expand(st).cases.at(2).numerics.max_periods, 3000);
}

// ---- studies ------------------------------------------------------------------------------

TEST(Study, ProductCountsLikeNestedLoopsInFileOrder) {
  const Study s = expand(read_study_text(
      "[sweep]\n\"soil.table2_G\" = [5e6, 10e6]\n\"contact.pure_rolling\" = [true, false]\n"
      "MMd_fraction = [0, 0.05]\n",
      "study.toml", ""));
  ASSERT_EQ(s.cases.size(), 8u);
  EXPECT_EQ(s.keys,
            (std::vector<std::string>{"soil.table2_G", "contact.pure_rolling", "MMd_fraction"}));
  EXPECT_EQ(format_value(s.varied[0][0]), "5000000");
  EXPECT_EQ(format_value(s.varied[1][2]), "0.05");
  EXPECT_EQ(format_value(s.varied[2][1]), "false");
  EXPECT_EQ(format_value(s.varied[4][0]), "10000000");
  EXPECT_EQ(Model(s.cases[5]).ksh(), table2_soil(10e6).ksh);
  EXPECT_TRUE(s.cases[5].contact.pure_rolling);
  EXPECT_DOUBLE_EQ(s.cases[5].MMd, 0.05 * Roller{}.M0);
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

TEST(Study, ZipAndGroups) {
  Study s = expand(read_study_text(
      "[sweep]\nmode = \"zip\"\n\"trough.k\" = [0.0, 0.002]\n\"trough.a\" = [0.603, 0.601]\n",
      "study.toml", ""));
  ASSERT_EQ(s.cases.size(), 2u);
  EXPECT_EQ(get_field(s.cases[1], "trough.k"), 0.002);
  EXPECT_EQ(get_field(s.cases[1], "trough.a"), 0.601);
  s = expand(read_study_text(
      "[sweep]\nMMd_fraction = [0, 0.05]\n[[sweep.group]]\n\"trough.k\" = [0.0, 0.002]\n"
      "\"trough.a\" = [0.603, 0.601]\n",
      "study.toml", ""));
  ASSERT_EQ(s.cases.size(), 4u);
  EXPECT_EQ(s.keys, (std::vector<std::string>{"MMd_fraction", "trough.k", "trough.a"}));
  EXPECT_EQ(get_field(s.cases[3], "trough.a"), 0.601);
  EXPECT_NE(study_error("[sweep]\nmode = \"zip\"\n\"trough.k\" = [0.0, 0.002]\n\"trough.a\" = "
                        "[0.603]\n")
                .find("zipped sweep lists must have equal lengths"),
            std::string::npos);
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
  EXPECT_NE(study_error("[sweep]\nmode = \"cartesian\"\n\"roller.r\" = [0.5]\n")
                .find("sweep.mode must be \"product\" or \"zip\""),
            std::string::npos);
  EXPECT_NE(study_error("[sweep]\n\"trough.a\" = {start = 0.6, stop = 0.5, step = 0.01}\n")
                .find("step must be non-zero and go from start towards stop"),
            std::string::npos);
  EXPECT_EQ(study_error("[sweep]\n\"trough.a\" = [0.62, 0.55]\n")
                .rfind("case 1 (trough.a = 0.55): study.toml:2:1: trough.a must be > roller.r", 0),
            0u);
  EXPECT_NE(study_error("[soil]\ninput = \"coefficients\"\n[sweep]\n\"soil.G\" = [5e6]\n")
                .find("soil.G has no effect"),
            std::string::npos);
  // On the default Table 2 soil a swept G picks the row; a G it does not hold names its case.
  EXPECT_NE(study_error("[sweep]\n\"soil.G\" = [5e6, 27e6]\n")
                .find("case 1 (soil.G = 27000000): study.toml:2:1: soil.G must be a G of paper "
                      "Table 2"),
            std::string::npos);
}

TEST(Study, FingerprintChangesWithAnyField) {
  const StudySpec spec = read_study_text("[sweep]\n\"contact.mu\" = [0.3, 0.5]\n", "s", "");
  Study a = expand(spec);
  Study b = a;
  EXPECT_EQ(fingerprint(a, "h"), fingerprint(b, "h"));
  EXPECT_NE(fingerprint(a, "h"), fingerprint(a, "h2"));
  b.cases[1].numerics.rtol *= 2;
  EXPECT_NE(fingerprint(a, "h"), fingerprint(b, "h"));
}

// ---- CSV, JSON, files ---------------------------------------------------------------------

TEST(Csv, QuoteSplitAndNumbersRoundTrip) {
  const std::vector<std::string> cells = {"plain", "a,b", "say \"hi\"", "", "x\ny"};
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line += ',';
    line += csv_quote(cells[i]);
  }
  EXPECT_EQ(csv_split(line), cells);
  for (double v : {0.05, 1.0 / 3.0, 5e6, -2.5e-300, 0.1 + 0.2}) {
    EXPECT_EQ(std::strtod(format_double(v).c_str(), nullptr), v);
    EXPECT_EQ(std::strtod(format_double_short(v).c_str(), nullptr), v);
  }
  EXPECT_EQ(format_double_short(0.05), "0.05");
  EXPECT_EQ(format_double(std::nan("")), "nan");
}

TEST(Csv, StudyRowHasAsManyCellsAsTheHeader) {
  const StudyColumns columns{{"soil.table2_G", "contact.pure_rolling"}, 4};
  const std::size_t n = csv_split(study_csv_header(columns)).size();
  CaseOutcome invalid;
  invalid.valid = false;
  invalid.error = "bad, really";
  EXPECT_EQ(csv_split(study_csv_row(columns, 3, {5e6, true}, invalid)).size(), n);
  CaseOutcome no_samples;
  no_samples.result.status = Status::contact_lost;
  EXPECT_EQ(csv_split(study_csv_row(columns, 3, {5e6, true}, no_samples)).size(), n);
  CaseOutcome full;
  full.result.samples.t = {0.0};
  full.metrics.ddx_harmonics.resize(5);
  full.metrics.ddz_harmonics.resize(5);
  EXPECT_EQ(csv_split(study_csv_row(columns, 3, {5e6, true}, full)).size(), n);
  EXPECT_EQ(csv_split(study_csv_header(columns))[1], "soil.table2_G[Pa]");
}

TEST(Csv, SteadyStateHeaderIsTheContract) {
  std::ostringstream out;
  write_steady_state_csv(out, Result{});
  EXPECT_EQ(out.str(),
            "t[s],delta[rad],phi[rad],x_A[m],s_A[m],ddelta[rad/s],dphi[rad/s],dx_A[m/s],ds_A[m/s],"
            "x_M[m],z_M[m],ddx_M[m/s^2],ddz_M[m/s^2],N[N],T[N],v_rel[m/s],torque[N m],phase[-]\n");
}

TEST(Json, StudyJsonTypesCells) {
  const std::string j = study_json("case[-],status[-],x[m],message[-]",
                                   {"0,steady_state,1.5,\"a, b\"", "1,contact_lost,,7"});
  EXPECT_NE(j.find("\"x[m]\": 1.5"), std::string::npos);
  EXPECT_NE(j.find("\"x[m]\": null"), std::string::npos);
  EXPECT_NE(j.find("\"message[-]\": \"7\""), std::string::npos);
  EXPECT_NE(j.find("\"case[-]\": 1"), std::string::npos);
}

TEST(Files, AtomicWriteReplacesWholeFile) {
  TempDir dir;
  const std::string path = dir.file("out.csv");
  write_file_atomic(path, "old\n");
  write_file_atomic(path, "new\n");
  EXPECT_EQ(read_file(path), "new\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.file("")),
                          std::filesystem::directory_iterator{}),
            1);
  EXPECT_NE(
      error_of([&] { write_file_atomic(dir.file("no/such/dir/x"), "x"); }).find("cannot write"),
      std::string::npos);
}

TEST(Files, JournalResumesAndDropsATornLine) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  {
    Journal j(path, 42, 5, false);
    EXPECT_TRUE(j.done().empty());
    j.append(3, "3,a");
    j.append(0, "0,b");
  }
  {  // a kill in the middle of a row
    std::ofstream(path, std::ios::app) << "4,tor";
  }
  EXPECT_NE(error_of([&] { Journal j(path, 42, 5, false); }).find("run again with --resume"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Journal j(path, 43, 5, true); }).find("belongs to a different study"),
            std::string::npos);
  {
    Journal j(path, 42, 5, true);
    ASSERT_EQ(j.done().size(), 2u);
    EXPECT_EQ(j.done().at(3), "3,a");
    EXPECT_EQ(j.done().at(0), "0,b");
    j.append(4, "4,c");
  }
  Journal j(path, 42, 5, true);
  EXPECT_EQ(j.done().size(), 3u);
  EXPECT_EQ(j.done().at(4), "4,c");
  j.remove();
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Issue 14 (6): a journal killed before its first line was written is empty; --resume used to
// call it "a different study".
TEST(Files, EmptyOrTornHeaderJournalHoldsNoCaseAndIsResumable) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  std::ofstream(path).flush();  // 0 bytes
  {
    Journal j(path, 42, 5, true);
    EXPECT_TRUE(j.done().empty());
    j.append(1, "1,x");
  }
  std::ofstream(path) << "# oscidrum sweep jour";  // the header cut short
  Journal j(path, 42, 5, true);
  EXPECT_TRUE(j.done().empty());
  EXPECT_EQ(read_file(path).rfind("# oscidrum sweep journal v1 fingerprint", 0), 0u);
}

// Issue 14 (6): two sweeps on one journal (two --resume at once) both ran every remaining case.
TEST(Files, JournalIsLockedWhileInUse) {
  TempDir dir;
  const std::string path = dir.file("r.csv.journal");
  {
    Journal first(path, 42, 5, false);
    first.append(0, "0,a");
    EXPECT_NE(error_of([&] {
                Journal second(path, 42, 5, true);
              }).find("another oscidrum sweep is running"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                Journal second(path, 42, 5, false, true);
              }).find("another oscidrum sweep is running"),
              std::string::npos);  // --restart must not pull it away either
  }
  Journal again(path, 42, 5, true);  // released with the first
  EXPECT_EQ(again.done().size(), 1u);
}

std::string shard_csv(std::size_t i, std::size_t n, std::uint64_t fp, std::size_t total,
                      const std::string& header = "case[-],x[-]") {
  std::string text = shard_line({fp, total, {i, n}}) + "\n" + header + "\n";
  for (std::size_t c = 0; c < total; ++c)
    if (c % n == i - 1) text += std::to_string(c) + ",v" + std::to_string(c) + "\n";
  return text;
}

TEST(Shards, ParseAndSlice) {
  const Shard s = parse_shard("2/4");
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 4u);
  EXPECT_TRUE(s.holds(1));
  EXPECT_TRUE(s.holds(5));
  EXPECT_FALSE(s.holds(2));
  for (const char* bad : {"0/4", "5/4", "2", "2/", "/4", "2/4x", "-1/4", "1.0/4", "1/0", ""})
    EXPECT_NE(error_of([&] { parse_shard(bad); }).find("--shard"), std::string::npos) << bad;
}

TEST(Shards, MergeJoinsInCaseOrderAndRefusesBadSets) {
  const std::uint64_t fp = 0x1234;
  std::vector<ShardFile> files;
  for (std::size_t i : {3u, 1u, 2u})
    files.push_back({"s" + std::to_string(i), shard_csv(i, 3, fp, 7)});
  EXPECT_EQ(merge_csv_shards(files), "case[-],x[-]\n0,v0\n1,v1\n2,v2\n3,v3\n4,v4\n5,v5\n6,v6\n");

  auto refused = [&](std::vector<ShardFile> set) {
    return error_of([&] { merge_csv_shards(set); });
  };
  EXPECT_NE(refused({files[0], files[1]}).find("1 of 3 shards missing: 2"), std::string::npos);
  EXPECT_NE(refused({files[0], files[1], files[2], {"again", files[1].text}})
                .find("shard 1/3 is given twice: s1 and again"),
            std::string::npos);
  EXPECT_NE(refused({files[0], files[1], {"other", shard_csv(2, 3, fp + 1, 7)}})
                .find("other (shard 2/3) belongs to a different study than s3"),
            std::string::npos);
  EXPECT_NE(
      refused({files[0], files[1], {"split", shard_csv(2, 4, fp, 7)}}).find("different splits"),
      std::string::npos);
  EXPECT_NE(refused({files[0], files[1], {"cols", shard_csv(2, 3, fp, 7, "case[-],y[-]")}})
                .find("other columns"),
            std::string::npos);
  EXPECT_NE(refused({files[0], files[1], {"plain", "case[-],x[-]\n0,v0\n"}})
                .find("plain is not the output of 'oscidrum sweep --shard I/N'"),
            std::string::npos);
  std::string cut = files[2].text;  // shard 2: cases 1 and 4; drop the last row
  cut.resize(cut.rfind("4,v4"));
  EXPECT_NE(refused({files[0], files[1], {"cut", cut}}).find("holds 1 cases, but the shard has 2"),
            std::string::npos);
  std::string foreign_row = files[2].text + "0,v0\n";
  EXPECT_NE(refused({files[0], files[1], {"edited", foreign_row}})
                .find("holds case 0, which belongs to another shard"),
            std::string::npos);
}

}  // namespace
}  // namespace oscidrum::io
