// oscidrum_io/shard.hpp: a study split into N deterministic slices (shards) that run as separate
// processes or cluster jobs, and the merge of their outputs into the result of the whole study.
// Shard I of N (1-based) holds the cases whose index i satisfies i mod N = I - 1: neighbouring
// cases, which often cost alike, are spread over all shards.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace oscidrum::io {

/// Shard `index` of `count` (1 <= index <= count).
struct Shard {
  std::size_t index = 1;
  std::size_t count = 1;

  /// True if the case with this (0-based) study index belongs to the shard.
  bool holds(std::size_t case_index) const { return case_index % count == index - 1; }
  /// "2/4".
  std::string text() const;
};

/// Parse "I/N" (decimal integers, 1 <= I <= N <= 1000000). Throws oscidrum::Error naming
/// --shard and the rule.
Shard parse_shard(const std::string& text);

/// What identifies a shard's output: the study (fingerprint of every case and of the output
/// columns, and its number of cases) and the slice.
struct ShardInfo {
  std::uint64_t fingerprint = 0;
  std::size_t n_cases = 0;
  Shard shard;
};

/// The first line of a shard's CSV: "# oscidrum shard 2/4 of study 0123456789abcdef cases 56".
std::string shard_line(const ShardInfo& info);

/// The CSV text of a shard, as `oscidrum sweep --shard` writes it.
struct ShardFile {
  std::string path;  ///< for messages
  std::string text;  ///< the whole file
};

/// Join the CSV outputs of every shard of one study into the CSV of the whole study, byte for
/// byte what the unsharded sweep writes (header, then one row per case in case order). Throws
/// oscidrum::Error when a file is not a shard output, when shards of different studies or of
/// different splits are mixed, when a shard is given twice or is missing, or when a shard's rows
/// are not exactly the cases it holds.
std::string merge_csv_shards(const std::vector<ShardFile>& files);

/// Read the shard line of a shard CSV (throws oscidrum::Error naming the file if it has none).
ShardInfo read_shard_line(const ShardFile& file);

/// Check that `infos` (one per file, same order as `paths`) are every shard of one study exactly
/// once; throws oscidrum::Error otherwise. Shared by the CSV and the HDF5 merge.
void check_shard_set(const std::vector<ShardInfo>& infos, const std::vector<std::string>& paths);

}  // namespace oscidrum::io
