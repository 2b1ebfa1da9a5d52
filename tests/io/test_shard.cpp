// Tests of src/io/shard.cpp: --shard I/N and the merge of the shards' CSV files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/shard.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

// A row as a sweep writes it: case c, its swept value x = c, the status of a rejected case.
std::string study_row(std::size_t c) {
  CaseOutcome invalid;
  invalid.valid = false;
  invalid.error = "rejected";
  return study_csv_row(StudyColumns{{"x"}, 1}, c, {Value{static_cast<double>(c)}}, invalid);
}

std::string shard_csv(std::size_t i, std::size_t n, std::uint64_t fp, std::size_t total,
                      const std::string& header = study_csv_header(StudyColumns{{"x"}, 1})) {
  std::string text = shard_line({fp, total, {i, n}}) + "\n" + header + "\n";
  for (std::size_t c = 0; c < total; ++c)
    if (c % n == i - 1) text += study_row(c) + "\n";
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
  for (std::size_t i : {3u, 1u, 2u}) {
    std::string name = "s";  // (not "s" + to_string(i): GCC 12 -Wrestrict false positive)
    name += std::to_string(i);
    files.push_back({name, shard_csv(i, 3, fp, 7)});
  }
  std::string merged = study_csv_header(StudyColumns{{"x"}, 1}) + "\n";
  for (std::size_t c = 0; c < 7; ++c) merged += study_row(c) + "\n";
  EXPECT_EQ(merge_csv_shards(files), merged);

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
  cut.resize(cut.rfind(study_row(4)));
  EXPECT_NE(refused({files[0], files[1], {"cut", cut}}).find("holds 1 cases, but the shard has 2"),
            std::string::npos);
  std::string foreign_row = files[2].text + study_row(0) + "\n";
  EXPECT_NE(refused({files[0], files[1], {"edited", foreign_row}})
                .find("holds case 0, which belongs to another shard"),
            std::string::npos);
  // A row edited or damaged: a cell missing or added, a status or a number that oscidrum never
  // writes. Refused with the file, the case and the line (shard 2's second row: case 4, line 4).
  const std::string row4 = study_row(4);
  const auto edited = [&](const std::string& row) {
    std::string text = files[2].text;
    text.replace(text.find(row4), row4.size(), row);
    return refused({files[0], files[1], {"s2", text}});
  };
  const std::string damaged = "s2 is damaged or edited: the row of case 4 (line 4)";
  const std::string one_less = edited(row4.substr(0, row4.rfind(',')));
  EXPECT_NE(one_less.find(damaged), std::string::npos) << one_less;
  EXPECT_NE(one_less.find("cells where the header has"), std::string::npos) << one_less;
  EXPECT_NE(edited(row4 + ",1").find("cells where the header has"), std::string::npos);
  std::string status = row4;
  status.replace(status.find(",invalid,"), 9, ",steady_stat,");
  EXPECT_NE(edited(status).find("its status 'steady_stat' is not one of oscidrum's statuses"),
            std::string::npos);
  std::string number = row4;
  number.replace(number.rfind(','), 1, ",abc");  // the last metric column
  EXPECT_NE(edited(number).find("its cell 'abc' in column evib[Pa] is not a number"),
            std::string::npos)
      << edited(number);
  // CR LF line endings (a file passed through a Windows tool): said as such, not as "not the
  // output of oscidrum sweep --shard" quoting a line that looks right.
  std::string crlf;
  for (char ch : files[2].text) {
    if (ch == '\n') crlf += '\r';
    crlf += ch;
  }
  EXPECT_NE(refused({files[0], files[1], {"s2", crlf}}).find("s2 has Windows line endings"),
            std::string::npos);
  std::string index = row4;
  index[0] = 'x';
  EXPECT_NE(edited(index).find("is damaged"), std::string::npos);
}

// study_row_defect on a steady state's row: numbers, nan, empty cells and the text diagnostics
// pass; a word in a numeric diagnostic does not.
TEST(Shards, ARowOfASteadyStateIsASweepsRow) {
  const StudyColumns columns{{"soil.G"}, 2};
  const std::vector<std::string> header = csv_split(study_csv_header(columns));
  CaseOutcome steady;
  steady.result.diagnostics.final_change = std::numeric_limits<double>::quiet_NaN();
  steady.result.diagnostics.fallback = "a, text \"with\" commas";
  const std::string row = study_csv_row(columns, 3, {Value{25e6}}, steady);
  EXPECT_EQ(study_row_defect(header, row), "");
  std::vector<std::string> cells = csv_split(row);
  const auto at = std::find(header.begin(), header.end(), "min_N[N]") - header.begin();
  cells[static_cast<std::size_t>(at)] = "many";
  std::string edited;
  for (const std::string& c : cells) {
    if (!edited.empty()) edited += ',';
    edited += csv_quote(c);
  }
  EXPECT_EQ(study_row_defect(header, edited), "its cell 'many' in column min_N[N] is not a number");
}

}  // namespace
}  // namespace oscidrum::io
