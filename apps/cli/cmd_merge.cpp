// oscidrum merge: join the outputs of the shards of one study (oscidrum sweep --shard I/N) into
// the output of the whole study, exactly what one unsharded sweep writes.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/hdf5.hpp"
#include "oscidrum_io/shard.hpp"
#include "output.hpp"

namespace oscidrum::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out;
  CLI::Option* out_flag = nullptr;
  bool quiet = false;
};

int run(const MergeOptions& o) {
  if (given(o.out_flag)) check_output_file("--out", o.out);
  std::size_t n_hdf5 = 0;
  for (const std::string& path : o.shards) {
    if (path.empty()) throw Error("merge: a shard file name is empty");
    // The output replacing one of its inputs would lose that shard if the merge failed later
    // (and a rerun would find it merged, not a shard).
    std::error_code ec;
    if (!o.out.empty() && o.out != "-" && std::filesystem::exists(o.out, ec) &&
        std::filesystem::equivalent(o.out, path, ec))
      throw Error("merge: --out " + o.out + " is the shard " + path +
                  ": write the merged study to another file");
    n_hdf5 += io::is_hdf5_file(path);
  }
  if (n_hdf5 > 0) {  // the HDF5 files of the shards (sweep --shard I/N --hdf5 FILE)
    if (n_hdf5 != o.shards.size())
      throw Error("merge: give either the CSV files or the HDF5 files of the shards, not both");
    if (o.out.empty()) throw Error("merge of HDF5 shards needs --out FILE.h5");
    // An HDF5 file named .csv was written without a word (and a CSV reader then fails on it).
    std::string ext = std::filesystem::path(o.out).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ext == ".csv" || ext == ".txt" || ext == ".tsv")
      throw Error("merge: the shards are HDF5 files, and so is the merged study: --out " + o.out +
                  " names a text file; name it FILE.h5 (merge the shards' CSV files for a CSV)");
    io::merge_hdf5_shards(o.shards, o.out);
    if (!o.quiet)
      std::cerr << "oscidrum: merged " << o.shards.size() << " HDF5 shards; wrote " << o.out
                << "\n";
    return kExitOk;
  }
  std::vector<io::ShardFile> files;
  for (const std::string& path : o.shards) files.push_back({path, io::read_file(path)});
  const std::string text = io::merge_csv_shards(files);
  write_output(o.out.empty() ? "-" : o.out, text);
  if (!o.quiet && !o.out.empty())
    std::cerr << "oscidrum: merged " << files.size() << " shards; wrote " << o.out << "\n";
  return kExitOk;
}

}  // namespace

void add_merge_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "merge",
      "Join the outputs of the shards of one study into the output of the whole study. Each "
      "shard comes from 'oscidrum sweep study.toml --shard I/N --out FILE'; the merge is byte for "
      "byte the CSV one unsharded sweep writes. It refuses files that are not shard outputs, "
      "shards of another study or of another split (N), a shard given twice, a missing shard and "
      "a shard whose rows are not exactly its cases or were edited or damaged (cells, statuses, "
      "numbers). The HDF5 files of shards (sweep --shard I/N "
      "--hdf5 FILE) merge the same way into the HDF5 file of the whole study.");
  sub->footer(
      "Examples:\n"
      "  oscidrum merge shards/shard_*.csv --out results.csv\n"
      "  oscidrum merge s1.csv s2.csv s3.csv s4.csv > results.csv\n"
      "  oscidrum merge shards/shard_*.h5 --out results.h5\n"
      "A cluster job array that runs the shards: examples/slurm/.\n"
      "Exit codes: 0 merged, 2 bad input (a missing, duplicated or foreign shard).");
  sub->add_option("shards", o->shards, "the shard outputs (CSV, or HDF5), in any order")
      ->required()
      ->type_name("SHARD.csv ...");
  o->out_flag =
      sub->add_option("--out,-o", o->out,
                      "write the merged CSV (or HDF5) to FILE (atomically); default: stdout "
                      "(CSV only)")
          ->type_name("FILE");
  sub->add_flag("--quiet,-q", o->quiet, "no note on stderr");
  sub->callback([o, &action] { action = [o] { return run(*o); }; });
}

}  // namespace oscidrum::cli
