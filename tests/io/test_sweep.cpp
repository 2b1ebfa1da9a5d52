// Tests of src/io/sweep.cpp: a study expanded into its cases (product like nested loops,
// zipped lists and groups) and the fingerprint that keeps a journal to its study.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/fields.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/sweep.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

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

// A large study reports its expansion and its fingerprint every kStudyProgressCases cases (the
// CLI's progress line, and Ctrl-C: the callback may throw to stop).
TEST(Study, ExpansionAndFingerprintReportProgressAndMayBeStopped) {
  const StudySpec spec = read_study_text(
      "[soil]\ninput = \"modulus\"\n[sweep]\n\"soil.G\" = { start = 5e6, stop = 100e6, num = "
      "10000 }\n",
      "study.toml", "");
  std::vector<std::size_t> seen;
  const StudyProgress note = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, 10000u);
    seen.push_back(done);
  };
  const Study s = expand(spec, note);
  EXPECT_EQ(seen, (std::vector<std::size_t>{4096, 8192}));
  seen.clear();
  EXPECT_EQ(fingerprint(s, "x", note), fingerprint(s, "x"));
  EXPECT_EQ(seen, (std::vector<std::size_t>{4096, 8192}));
  const StudyProgress stop = [](std::size_t, std::size_t) { throw Error("stopped"); };
  EXPECT_THROW((void)expand(spec, stop), Error);
  EXPECT_THROW((void)fingerprint(s, "x", stop), Error);
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
                        "[0.603, 0.61, 0.62]\n")
                .find("zipped sweep lists must have equal lengths"),
            std::string::npos);
  // A group zips keys inside a product; in zip mode it would be ignored or ambiguous.
  EXPECT_NE(study_error("[sweep]\nmode = \"zip\"\n[[sweep.group]]\n\"trough.k\" = [0.0, 0.002]\n"
                        "\"trough.a\" = [0.603, 0.601]\n")
                .find("[[sweep.group]] zips keys inside a product"),
            std::string::npos);
}

TEST(Study, FingerprintChangesWithAnyField) {
  const StudySpec spec = read_study_text("[sweep]\n\"contact.mu\" = [0.3, 0.5]\n", "s", "");
  Study a = expand(spec);
  Study b = a;
  EXPECT_EQ(fingerprint(a, "h"), fingerprint(b, "h"));
  EXPECT_NE(fingerprint(a, "h"), fingerprint(a, "h2"));
  b.adjust([](Case& c) {
    if (c.contact.mu == 0.5) c.numerics.rtol *= 2;
  });
  EXPECT_NE(fingerprint(a, "h"), fingerprint(b, "h"));
  EXPECT_EQ(a.cases[1].numerics.rtol * 2, b.cases[1].numerics.rtol);  // a is unchanged
}

}  // namespace
}  // namespace oscidrum::io
