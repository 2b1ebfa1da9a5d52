// Validation against the paper: every result docs/validation.md lists that a simulation can check
// (src/validation.cpp states each acceptance rule next to the claim). The paper's studies run once
// (about 100 cases, a few seconds on two cores) and each claim is one check.
#include <gtest/gtest.h>

#include <set>

#include "oscidrum/oscidrum.hpp"
#include "oscidrum_paper/validation.hpp"

namespace oscidrum {
namespace {

const std::vector<ValidationRow>& rows() {
  static const std::vector<ValidationRow> r = validate(run_paper_studies());
  return r;
}

TEST(Validation, EveryCheckableClaimOfThePaperAgrees) {
  for (const ValidationRow& row : rows()) {
    if (!row.checkable) continue;
    EXPECT_TRUE(row.agrees) << row.id << " (" << row.figure << "): " << row.claim
                            << "\n  paper: " << row.paper << "\n  oscidrum: " << row.oscidrum
                            << "\n  rule: " << row.rule;
  }
}

TEST(Validation, RowsAreWellFormed) {
  std::set<std::string> ids;
  int checkable = 0;
  for (const ValidationRow& row : rows()) {
    EXPECT_TRUE(ids.insert(row.id).second) << "duplicate id " << row.id;
    EXPECT_FALSE(row.claim.empty()) << row.id;
    EXPECT_FALSE(row.paper.empty()) << row.id;
    EXPECT_FALSE(row.rule.empty()) << row.id;
    // A claim that cannot be checked, or does not agree, must say why.
    if (!row.checkable || !row.agrees) {
      EXPECT_FALSE(row.note.empty()) << row.id;
    }
    checkable += row.checkable;
  }
  EXPECT_GE(checkable, 40);  // docs/validation.md holds over 40 checkable statements
  const std::string md = validation_markdown(rows());
  EXPECT_NE(md.find("| fig9a.xmax_G5 |"), std::string::npos);
  EXPECT_NE(md.find("checkable claims agree"), std::string::npos);
}

TEST(Validation, PaperSeriesCoverTheFigures) {
  const std::vector<PaperSeries> s = paper_series();
  std::set<std::string> ids;
  for (const PaperSeries& p : s) ids.insert(p.id);
  for (const char* id :
       {"rolling_MMd0_R0.603", "rolling_MMd0_R0.606", "rolling_MMd0_R0.620", "rolling_MMd0_R0.650",
        "rolling_MMd0.05_R0.606", "stickslip_MMd0_R0.606", "stickslip_MMd0.05_R0.606",
        "shape_circle_R0.603", "shape_spiral_k0.002_a0.601"}) {
    EXPECT_EQ(ids.count(id), 1u) << id;
  }
  const Case c = paper_case(s[0], 25e6);
  EXPECT_EQ(c.soil.ksh, 41.4e6);  // Table 2
  EXPECT_TRUE(c.contact.pure_rolling);
  EXPECT_EQ(get_field(c, "trough.a"), 0.603);
}

}  // namespace
}  // namespace oscidrum
