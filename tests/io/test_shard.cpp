// Tests of src/io/shard.cpp: --shard I/N and the merge of the shards' CSV files.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum_io/shard.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

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
  for (std::size_t i : {3u, 1u, 2u}) {
    std::string name = "s";  // (not "s" + to_string(i): GCC 12 -Wrestrict false positive)
    name += std::to_string(i);
    files.push_back({name, shard_csv(i, 3, fp, 7)});
  }
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
