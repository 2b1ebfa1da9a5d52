// Shards of a study and their merge (see oscidrum_io/shard.hpp).
#include "oscidrum_io/shard.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string_view>

#include "oscidrum/error.hpp"
#include "oscidrum_io/csv.hpp"

namespace oscidrum::io {
namespace {

constexpr std::size_t kMaxShards = 1000000;
constexpr std::string_view kPrefix = "# oscidrum shard ";

// A decimal integer without sign, spaces or exponent; false otherwise.
bool parse_count(std::string_view s, std::size_t* out) {
  if (s.empty() || s.size() > 7) return false;
  std::size_t v = 0;
  for (char ch : s) {
    if (ch < '0' || ch > '9') return false;
    v = v * 10 + static_cast<std::size_t>(ch - '0');
  }
  *out = v;
  return true;
}

std::string shown(std::string_view s) {
  return s.size() > 60 ? std::string(s.substr(0, 60)) + "..." : std::string(s);
}

}  // namespace

std::string Shard::text() const { return std::to_string(index) + "/" + std::to_string(count); }

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  Shard s;
  if (slash == std::string::npos ||
      !parse_count(std::string_view(text).substr(0, slash), &s.index) ||
      !parse_count(std::string_view(text).substr(slash + 1), &s.count))
    throw Error("--shard must be I/N with integers 1 <= I <= N (e.g. --shard 2/4); got '" +
                shown(text) + "'");
  if (s.count < 1 || s.count > kMaxShards || s.index < 1 || s.index > s.count)
    throw Error("--shard I/N needs 1 <= I <= N <= " + std::to_string(kMaxShards) + "; got '" +
                shown(text) + "'");
  return s;
}

std::string shard_line(const ShardInfo& info) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "# oscidrum shard %zu/%zu of study %016" PRIx64 " cases %zu",
                info.shard.index, info.shard.count, info.fingerprint, info.n_cases);
  return buf;
}

ShardInfo read_shard_line(const ShardFile& file) {
  const std::string_view text = file.text;
  const std::size_t end = text.find('\n');
  const std::string_view line = text.substr(0, end);
  ShardInfo info;
  unsigned long long index = 0, count = 0, cases = 0;
  std::uint64_t fp = 0;
  char tail = 0;
  const std::string copy(line);
  if (line.ends_with('\r'))
    throw Error(file.path +
                " has Windows line endings (CR LF), which oscidrum sweep does not write: convert "
                "it back (e.g. dos2unix) and merge again");
  if (!line.starts_with(kPrefix) ||
      std::sscanf(copy.c_str(), "# oscidrum shard %llu/%llu of study %16" SCNx64 " cases %llu%c",
                  &index, &count, &fp, &cases, &tail) != 4 ||
      count < 1 || index < 1 || index > count || count > kMaxShards)
    throw Error(file.path +
                " is not the output of 'oscidrum sweep --shard I/N' (its first line must be '# "
                "oscidrum shard I/N of study ... cases ...'; got '" +
                shown(line) + "')");
  info.shard = {static_cast<std::size_t>(index), static_cast<std::size_t>(count)};
  info.fingerprint = fp;
  info.n_cases = static_cast<std::size_t>(cases);
  return info;
}

void check_shard_set(const std::vector<ShardInfo>& infos, const std::vector<std::string>& paths) {
  if (infos.empty()) throw Error("merge needs the output files of every shard; got none");
  const ShardInfo& first = infos.front();
  std::map<std::size_t, std::string> seen;  // shard index -> path
  for (std::size_t i = 0; i < infos.size(); ++i) {
    const ShardInfo& s = infos[i];
    if (s.fingerprint != first.fingerprint || s.n_cases != first.n_cases)
      throw Error(paths[i] + " (shard " + s.shard.text() + ") belongs to a different study than " +
                  paths.front() +
                  " (its cases or output columns differ); merge only the shards of one sweep");
    if (s.shard.count != first.shard.count)
      throw Error(paths[i] + " is shard " + s.shard.text() + " but " + paths.front() +
                  " is shard " + first.shard.text() +
                  ": the shards come from different splits of the study (N differs)");
    const auto [it, fresh] = seen.emplace(s.shard.index, paths[i]);
    if (!fresh)
      throw Error("shard " + s.shard.text() + " is given twice: " + it->second + " and " +
                  paths[i]);
  }
  std::string missing;
  std::size_t n_missing = 0;
  for (std::size_t k = 1; k <= first.shard.count; ++k)
    if (!seen.count(k)) {
      if (++n_missing <= 10) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    }
  if (n_missing > 0)
    throw Error(std::to_string(n_missing) + " of " + std::to_string(first.shard.count) +
                " shards missing: " + missing + (n_missing > 10 ? ", ..." : "") + " (of N = " +
                std::to_string(first.shard.count) + "); give the output of every shard");
}

std::string merge_csv_shards(const std::vector<ShardFile>& files) {
  std::vector<ShardInfo> infos;
  std::vector<std::string> paths;
  for (const ShardFile& f : files) {
    infos.push_back(read_shard_line(f));
    paths.push_back(f.path);
  }
  check_shard_set(infos, paths);
  const std::size_t total = infos.front().n_cases;
  std::string header;
  std::vector<std::string> header_cells;
  std::vector<std::string_view> rows(total);
  std::vector<bool> have(total, false);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string_view text = files[i].text;
    const std::string& path = files[i].path;
    std::size_t pos = text.find('\n') + 1;
    const std::size_t h_end = text.find('\n', pos);
    if (h_end == std::string_view::npos)
      throw Error(path + " is damaged: no header line after the shard line");
    const std::string_view h = text.substr(pos, h_end - pos);
    if (i == 0) {
      header = std::string(h);
      header_cells = csv_split(header);
    } else if (h != header)
      throw Error(path + " has other columns than " + paths.front() +
                  " (a different --harmonics?); merge only the shards of one sweep");
    pos = h_end + 1;
    std::size_t n_rows = 0, line = 2;
    while (pos < text.size()) {
      ++line;
      const std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos)
        throw Error(path + " is damaged: its last line is cut off");
      const std::string_view row = text.substr(pos, end - pos);
      std::size_t index = 0;
      const std::size_t comma = row.find(',');
      if (comma == std::string_view::npos || !parse_count(row.substr(0, comma), &index) ||
          index >= total)
        throw Error(path + " is damaged: a row does not start with a case index below " +
                    std::to_string(total) + " (row: " + shown(row) + ")");
      if (!infos[i].shard.holds(index))
        throw Error(path + " (shard " + infos[i].shard.text() + ") holds case " +
                    std::to_string(index) + ", which belongs to another shard");
      if (have[index]) throw Error(path + " holds case " + std::to_string(index) + " twice");
      if (const std::string defect = study_row_defect(header_cells, row); !defect.empty())
        throw Error(path + " is damaged or edited: the row of case " + std::to_string(index) +
                    " (line " + std::to_string(line) + ") cannot be a sweep's: " + defect +
                    "; run that shard again");
      rows[index] = row;
      have[index] = true;
      ++n_rows;
      pos = end + 1;
    }
    const ShardInfo& s = infos[i];
    const std::size_t expected =
        total / s.shard.count + (s.shard.index - 1 < total % s.shard.count ? 1 : 0);
    if (n_rows != expected)
      throw Error(path + " (shard " + s.shard.text() + ") holds " + std::to_string(n_rows) +
                  " cases, but the shard has " + std::to_string(expected) +
                  " (an unfinished or edited shard?)");
  }
  std::string out = header + "\n";
  for (std::string_view row : rows) {
    out += row;
    out += '\n';
  }
  return out;
}

}  // namespace oscidrum::io
