// oscidrum sweep: a study file expanded into cases, run on all cores, one result row per case.
// Finished rows go to a journal as they come, so --resume after Ctrl-C or a kill runs only the
// missing cases; the final files are written atomically.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <utility>
#include <variant>

#include "case_options.hpp"
#include "commands.hpp"
#include "flags.hpp"
#include "oscidrum/error.hpp"
#include "oscidrum/study.hpp"
#include "oscidrum_io/config.hpp"
#include "oscidrum_io/csv.hpp"
#include "oscidrum_io/files.hpp"
#include "oscidrum_io/hdf5.hpp"
#include "oscidrum_io/json.hpp"
#include "oscidrum_io/shard.hpp"
#include "oscidrum_io/sweep.hpp"
#include "output.hpp"
#include "plot.hpp"
#include "terminal.hpp"

namespace oscidrum::cli {
namespace {

struct SweepOptions {
  std::string study;
  CaseOptions c;  // --set only: changes the base case
  std::string out, cases_dir, format, shard, hdf5;
  CLI::Option *out_flag = nullptr, *cases_dir_flag = nullptr, *shard_flag = nullptr,
              *hdf5_flag = nullptr;
  std::string plot, plot_metric = "area";  // --plot FILE: the study's figure
  CLI::Option* plot_flag = nullptr;
  bool out_is_stdout = false;  // --out -
  int threads = 0, harmonics = 10;
  bool resume = false, restart = false, quiet = false, list = false, no_continuation = false;
};

// Continuation (docs/periodic.md): each case of `pending` (study indices, increasing) starts from
// the steady state of the pending case before it on its line: the cases that differ only in the
// values of the chain factor, the factor with the most values (the last of those on a tie; every
// key of a zipped study). Only cases this run computes are linked, so a shard's chains stay in
// the shard and a resumed sweep continues from the cases it runs.
std::vector<std::ptrdiff_t> continuation_links(const io::StudySpec& spec, const io::Study& study,
                                               const std::vector<std::size_t>& pending) {
  const std::size_t n_keys = study.keys.size();
  std::size_t along_begin = 0, along_end = n_keys;  // the chain factor's key columns
  if (spec.mode == io::SweepMode::product) {
    std::size_t column = 0, longest = 0;
    for (const io::SweepFactor& f : spec.factors) {
      if (f.size() >= longest) {
        longest = f.size();
        along_begin = column;
        along_end = column + f.axes.size();
      }
      column += f.axes.size();
    }
  }
  std::map<std::string, std::ptrdiff_t> last_on_line;  // line -> index into pending
  std::vector<std::ptrdiff_t> previous(pending.size(), -1);
  for (std::size_t j = 0; j < pending.size(); ++j) {
    // Ctrl-C: the links so far (run_study sees the signal too and runs nothing).
    if (j % io::kStudyProgressCases == 0 && interrupted()) break;
    std::string line;
    for (std::size_t k = 0; k < n_keys; ++k)
      if (k < along_begin || k >= along_end)
        line += io::format_value(study.varied[pending[j]][k]) + '\n';
    const auto [it, fresh] = last_on_line.try_emplace(line, static_cast<std::ptrdiff_t>(j));
    if (!fresh) previous[j] = std::exchange(it->second, static_cast<std::ptrdiff_t>(j));
  }
  return previous;
}

std::string journal_path(const std::string& out) {
  return io::output_target(out).path + ".journal";
}

std::string case_file_name(std::size_t index, std::size_t total) {
  std::string digits = std::to_string(total > 0 ? total - 1 : 0);
  std::string n = std::to_string(index);
  const std::size_t width = std::max<std::size_t>(4, digits.size());
  return "case_" + std::string(width - std::min(width, n.size()), '0') + n + ".csv";
}

// The table for people: the swept values, status and a few metrics.
std::string rows_table(const std::string& header, const std::vector<std::string>& rows,
                       std::size_t n_keys) {
  const std::vector<std::string> columns = io::csv_split(header);
  std::vector<std::size_t> pick;
  for (std::size_t i = 0; i <= n_keys + 1; ++i) pick.push_back(i);  // case, keys, status
  for (const char* name : {"periods_to_steady[-]", "ddx_max[m/s^2]", "ddz_max[m/s^2]",
                           "psi_xz[rad]", "area[m^2/s^4]", "stick_fraction[-]"})
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) pick.push_back(i);
  TextTable t;
  for (std::size_t i : pick) {
    t.header.push_back(columns[i]);
    t.right.push_back(i != n_keys + 1);
  }
  for (const std::string& row : rows) {
    const std::vector<std::string> cells = io::csv_split(row);
    std::vector<std::string> out;
    for (std::size_t i : pick) {
      std::string cell = i < cells.size() ? cells[i] : std::string();
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (i > n_keys + 1 && !cell.empty() && end == cell.c_str() + cell.size()) cell = fmt(v, 5);
      out.push_back(cell);
    }
    t.rows.push_back(out);
  }
  return t.text();
}

// What the study's cases say that no single key does, said once and found in one walk over the
// cases (each is made from the study's table as it is read):
// - a frequency study with M0 fixed is rarely what is meant (M0 = 4 m_u e_u e_w nu^2 (5)), as
//   io::finalize says for one case;
// - a friction key swept where the drum rolls without a friction limit in every case
//   (contact.pure_rolling = true; a warning in a case file, so that pure_rolling itself can be
//   swept over a base with mu): a study of mu under pure rolling ran with exit 0 and no word,
//   every row the same motion;
// - roller.m_f swept: the frame's mass enters the Appendix A transmissibility only, which no
//   sweep output holds (continue and diagram refuse it); numerics.continuation swept where every
//   case integrates from rest by the transient method. Both ran with exit 0 and no word.
void warn_about_cases(const io::StudySpec& spec, const io::Study& study,
                      const io::StudyProgress& progress) {
  bool M0_given = spec.base.given("roller.M0"), continuation = false;
  std::vector<std::string> friction_keys;
  for (const std::string& k : study.keys) {
    M0_given = M0_given || k == "roller.M0";
    if (friction_key(k)) friction_keys.push_back(k);
    if (k == "roller.m_f")
      warn(
          "roller.m_f is swept, but nothing a sweep computes depends on it: the frame's mass "
          "enters only the Appendix A transmissibility (oscidrum transmissibility), and the "
          "rows are the same motion for every value");
    continuation = continuation || k == "numerics.continuation";
  }
  if (M0_given && friction_keys.empty() && !continuation) return;
  std::size_t fixed = 0, rolling = 0, transient = 0;
  const std::size_t total = study.cases.size();
  for (std::size_t n = 0; n < total; ++n) {
    if (n % io::kStudyProgressCases == 0 && n > 0) progress(n, total);
    const Case c = study.cases[n];  // the vibratory drum has no M0 (docs/model.md section 14)
    fixed += c.roller.type == RollerType::oscillation && c.roller.unbalance == 0.0 &&
             c.roller.f != Roller{}.f;
    rolling += c.contact.pure_rolling ? 1 : 0;
    transient += c.numerics.method == SteadyMethod::transient ? 1 : 0;
  }
  if (continuation && transient == total)
    warn("numerics.continuation is swept, but has no effect in any of the " +
         std::to_string(total) +
         " cases: numerics.method = \"transient\" starts every case from rest, and the rows "
         "are the same for every value");
  if (!M0_given && fixed > 0)
    warn(std::to_string(fixed) + " of the " + std::to_string(total) +
         " cases change roller.f with M0 fixed at " + fmt(study.cases.front().roller.M0) +
         " N m (the paper's roller at 39 Hz); a real roller's M0 = 4 m_u e_u e_w nu^2 (5) grows "
         "with f^2: give roller.unbalance (the paper's: 0.22877 kg m^2), or set roller.M0 to say "
         "the moment is meant");
  // A study that sweeps pure_rolling too compares rolling with friction: meant.
  if (rolling == total)
    for (const std::string& key : friction_keys)
      warn(key + " is swept, but has no effect in any of the " + std::to_string(rolling) +
           " cases: contact.pure_rolling = true (rolling without a friction limit), and the rows "
           "are the same motion for every value");
}

// Every option that can be checked without running a case: a sweep must not fail at its end,
// after every case ran.
void check_options(const SweepOptions& o) {
  if (given(o.out_flag) && !o.out_is_stdout) check_output_file("--out", o.out, false);
  if (given(o.hdf5_flag)) check_output_file("--hdf5", o.hdf5, false);
  if (given(o.plot_flag)) check_plot_file("--plot", o.plot);
  check_distinct_files({{"the study file", o.study, true},
                        {"--out", o.out_is_stdout ? std::string() : o.out},
                        {"--hdf5", o.hdf5},
                        {"--plot", o.plot}});
  // The sweep's own files beside --out (its journal, removed at the end) and beside --hdf5 (the
  // file being written, renamed at the end): an output named as one of them was deleted or
  // overwritten without a word (--hdf5 r.csv.journal, exit 0, no HDF5 file).
  if (!o.hdf5.empty() && !o.out.empty() && !o.out_is_stdout) {
    const std::string journal = o.out + ".journal";
    if (same_file(o.hdf5, journal) || same_file(o.out, o.hdf5 + ".partial"))
      throw Error("--hdf5 " + o.hdf5 + " and --out " + o.out + ": the sweep keeps its journal in " +
                  journal + " and writes the HDF5 file as " + o.hdf5 +
                  ".partial until it is done; name the outputs otherwise");
  }
  if (given(o.cases_dir_flag) && o.cases_dir.empty())
    throw Error("--cases-dir needs a directory name; got an empty one");
  // The directory is made before the cases run: named as an output file, it was made first and
  // the file refused after ("it is a directory"), an empty directory left behind.
  if (!o.cases_dir.empty()) {
    const auto same = [](const std::string& a, const std::string& b) {
      return std::filesystem::absolute(a).lexically_normal() ==
             std::filesystem::absolute(b).lexically_normal();
    };
    for (const auto& [flag, file] : {std::pair{"--out", o.out}, std::pair{"--hdf5", o.hdf5}})
      if (!file.empty() && file != "-" && same(o.cases_dir, file))
        throw Error("--cases-dir " + o.cases_dir + " and " + flag + " " + file +
                    ": a directory and a file cannot have one name; name them otherwise");
  }
}

// The study expanded into cases, and the cases this run is for (all, or its shard's).
struct SweepPlan {
  io::StudySpec spec;
  io::Study study;
  bool sharded = false;
  io::Shard shard;
  io::StudyColumns columns;
  std::string header;
  std::uint64_t fingerprint = 0;
  std::vector<bool> mine;
  std::size_t total = 0, n_mine = 0;
};

SweepPlan plan_sweep(const SweepOptions& o) {
  SweepPlan p;
  p.sharded = given(o.shard_flag);
  p.shard = p.sharded ? io::parse_shard(o.shard) : io::Shard{};
  p.spec = io::read_study_file(o.study);
  apply(o.c, p.spec.base);
  // Every case is built and checked before the first runs (seconds for the largest studies),
  // with a progress line on a terminal; Ctrl-C stops it (main reports the signal).
  ProgressLine line(stderr_is_terminal() && !o.quiet);
  const auto progress = [&line](const char* what) {
    return [&line, what](std::size_t done, std::size_t total) {
      if (interrupted()) throw Error(std::string("interrupted while ") + what);
      line.update(std::string(what) + ": case " + std::to_string(done) + " of " +
                  std::to_string(total));
    };
  };
  // A value given for a swept key would be replaced in every case: from the command line that
  // is a mistake (said, exit 2); in the study's base case a default the sweep overrides (warned).
  std::vector<std::string> swept;
  for (const io::SweepFactor& f : p.spec.factors)
    for (const io::SweepAxis& a : f.axes) swept.push_back(a.key);
  for (const auto& [key, origin] : p.spec.base.origin) {
    if (std::find(swept.begin(), swept.end(), key) == swept.end()) continue;
    if (origin.rfind("--", 0) == 0)
      throw Error(origin + ": " + key + " is swept by the study " + o.study +
                      ": this value would be replaced in every case (change the sweep instead)",
                  key);
    // A warning, not progress: --quiet hides progress and the summary only (docs/cli.md).
    warn(origin + ": " + key + " is swept by the study: this value is replaced in every case");
  }
  p.study = io::expand(p.spec, progress("checking the study's cases"));
  // --no-continuation is a flag: a --set of numerics.continuation after it holds (flags, then
  // each --set, docs/config.md), said as a --set over a case flag is.
  if (o.no_continuation) {
    const auto set = p.spec.base.origin.find("numerics.continuation");
    if (set != p.spec.base.origin.end() && set->second.rfind("--set ", 0) == 0)
      warn(set->second + " overrides --no-continuation");
    else
      p.study.adjust([](Case& c) { c.numerics.continuation = false; });
  }
  p.total = p.study.cases.size();
  warn_about_cases(p.spec, p.study, progress("checking each case's M0, f and contact"));
  p.columns = io::StudyColumns{p.study.keys, o.harmonics};
  p.header = io::study_csv_header(p.columns);
  p.fingerprint = io::fingerprint(p.study, p.header, progress("fingerprinting the study"));
  p.mine.assign(p.total, true);
  p.n_mine = p.total;
  if (p.sharded) {
    p.n_mine = 0;
    for (std::size_t i = 0; i < p.total; ++i) p.n_mine += (p.mine[i] = p.shard.holds(i));
  }
  return p;
}

// --list: the expanded cases, nothing run.
int list_cases(const SweepPlan& p, const std::string& format) {
  // Streamed: a million-case study is listed without holding its table.
  std::vector<std::string> header = {"case"};
  for (const std::string& k : p.study.keys) header.push_back(k);
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < p.total; ++i)
    if (p.mine[i]) mine.push_back(i);
  // --format as for the results (it was ignored): csv and json rows, or nothing.
  if (format == "none") return kExitOk;
  if (format == "csv") {
    for (std::size_t k = 0; k < header.size(); ++k)
      std::cout << (k ? "," : "") << io::csv_quote(header[k]);
    std::cout << "\n";
    for (const std::size_t i : mine) {
      std::cout << i;
      for (const io::Value& v : p.study.varied[i])
        std::cout << "," << io::csv_quote(io::format_value(v));
      std::cout << "\n";
    }
    return kExitOk;
  }
  if (format == "json") {
    // {"cases": [{"case": 0, KEY: VALUE, ...}, ...], "count": N}, one case per line.
    std::cout << "{\"cases\": [";
    for (std::size_t k = 0; k < mine.size(); ++k) {
      nlohmann::ordered_json row;
      row["case"] = mine[k];
      const std::vector<io::Value>& values = p.study.varied[mine[k]];
      for (std::size_t j = 0; j < values.size(); ++j)
        std::visit([&](const auto& v) { row[p.study.keys[j]] = v; }, values[j]);
      std::cout << (k ? ",\n  " : "\n  ") << row.dump();
    }
    std::cout << "\n], \"count\": " << p.n_mine << "}\n";
    return kExitOk;
  }
  write_text_table(std::cout, header, std::vector<bool>(header.size(), true), mine.size(),
                   [&](std::size_t k) {
                     std::vector<std::string> row = {std::to_string(mine[k])};
                     for (const io::Value& v : p.study.varied[mine[k]])
                       row.push_back(io::format_value(v));
                     return row;
                   });
  std::cout << p.n_mine << " cases";
  if (p.sharded) std::cout << " (shard " << p.shard.text() << " of a study of " << p.total << ")";
  std::cout << "\n";
  return kExitOk;
}

// The options that need the expanded study (or only matter when cases run).
void check_run_options(const SweepOptions& o, const SweepPlan& p) {
  if (o.resume && o.restart) throw Error("give either --resume or --restart, not both");
  if ((o.resume || o.restart) && !o.out.empty() && io::output_target(o.out).direct)
    throw Error("--resume and --restart need --out to be a file: " + o.out +
                " is a FIFO or a device, which keeps no journal");
  if ((o.resume || o.restart) && o.out.empty())
    throw Error("--resume and --restart need --out FILE (the journal lives beside it)");
  if (!o.plot.empty() && o.out.empty())
    throw Error("--plot " + o.plot + " needs --out FILE (the plot is drawn from the results CSV)");
  // As run says it (the library would name its option, StudyOptions::n_harmonics). Every case
  // has the base case's samples per period unless the study sweeps them.
  const bool spp_swept = std::find(p.study.keys.begin(), p.study.keys.end(),
                                   "numerics.samples_per_period") != p.study.keys.end();
  for (std::size_t i = 0; i < p.total; ++i) {
    if (!p.mine[i]) continue;
    const int spp = p.study.cases[i].numerics.samples_per_period;
    check_harmonics(o.harmonics, spp, " (case " + std::to_string(i) + ")");
    if (!spp_swept) break;
  }
  if (!o.plot.empty()) {
    // Before the first case: a figure that cannot be drawn must not cost a whole sweep.
    check_plot_file("--plot", o.plot);
    // The columns after "status", by name without the unit: "area[m^2/s^4]" is "area".
    std::vector<std::string> columns = io::csv_split(p.header);
    for (std::string& c : columns) c = c.substr(0, c.find('['));
    const auto status = std::find(columns.begin(), columns.end(), "status");
    if (status == columns.end() ||
        std::find(status + 1, columns.end(), o.plot_metric) == columns.end())
      throw Error("--plot-metric " + o.plot_metric +
                  ": not a column of the results (those after 'status', docs/outputs.md), e.g. "
                  "area, ddx_max, ddz_max, psi_xz, ddx_A3_A1, cmv");
  }
  if (!o.cases_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.cases_dir, ec);
    if (ec) throw Error("cannot create --cases-dir " + o.cases_dir + ": " + ec.message());
  }
}

// The result rows as they come, in completion order, in an unlinked temporary file with an
// index (16 bytes per case), read back in case order at the end: a sweep's memory does not grow
// with its number of cases (a million rows of ~700 bytes stay on disk).
class RowStore {
 public:
  RowStore(std::size_t total, const std::string& near) : where_(total, {0, kNone}) {
    // Beside the output (a large study's rows belong on its disk), else in $TMPDIR or /tmp.
    std::vector<std::string> dirs;
    if (!near.empty() && near != "-" && !io::output_target(near).direct) {
      const std::string parent = std::filesystem::path(near).parent_path().string();
      dirs.push_back(parent.empty() ? "." : parent);
    }
    const char* tmp = std::getenv("TMPDIR");
    dirs.push_back(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp");
    int fd = -1;
    std::string name;
    for (const std::string& dir : dirs) {
      name = dir + "/.oscidrum-rows-XXXXXX";
      fd = ::mkstemp(name.data());
      if (fd >= 0) break;
    }
    if (fd < 0)
      throw Error("cannot create a temporary file for the result rows in " + name + ": " +
                  std::strerror(errno));
    ::unlink(name.c_str());  // gone with the process, whatever ends it
    file_ = ::fdopen(fd, "w+b");
    if (file_ == nullptr) {
      ::close(fd);
      throw Error(std::string("cannot open a temporary file for the result rows: ") +
                  std::strerror(errno));
    }
  }
  ~RowStore() {
    if (file_ != nullptr) std::fclose(file_);
  }
  RowStore(const RowStore&) = delete;
  RowStore& operator=(const RowStore&) = delete;

  void put(std::size_t i, const std::string& row) {
    if (::fseeko(file_, 0, SEEK_END) != 0) fail();
    const off_t at = ::ftello(file_);
    if (at < 0 || std::fwrite(row.data(), 1, row.size(), file_) != row.size()) fail();
    where_[i] = {static_cast<std::uint64_t>(at), static_cast<std::uint32_t>(row.size())};
  }
  bool has(std::size_t i) const { return where_[i].second != kNone; }
  std::string get(std::size_t i) {
    std::string row(where_[i].second, '\0');
    if (::fseeko(file_, static_cast<off_t>(where_[i].first), SEEK_SET) != 0 ||
        std::fread(row.data(), 1, row.size(), file_) != row.size())
      fail();
    return row;
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  [[noreturn]] static void fail() {
    throw Error(std::string("cannot keep the result rows in a temporary file: ") +
                std::strerror(errno));
  }
  std::FILE* file_ = nullptr;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> where_;
};

// Where the rows go while the cases run: the journal (for --resume), the HDF5 file and the row
// store (the rows a resumed sweep already has, and every new one); the status of each row counted
// as it comes.
struct SweepOutputs {
  std::unique_ptr<io::Journal> journal;
  std::unique_ptr<io::StudyHdf5Writer> hdf5;
  std::unique_ptr<RowStore> rows;
  std::map<std::string, std::size_t> statuses;
  std::size_t finished = 0;  // rows of this run's cases (resumed ones included)
  void add(std::size_t i, const std::string& row, std::size_t n_keys) {
    rows->put(i, row);
    const std::vector<std::string> cells = io::csv_split(row);
    statuses[cells.size() > n_keys + 1 ? cells[n_keys + 1] : "?"]++;
    ++finished;
  }
};

SweepOutputs open_outputs(const SweepOptions& o, const SweepPlan& p) {
  SweepOutputs out;
  out.rows = std::make_unique<RowStore>(p.total, o.out);
  // The journal lives beside a regular output file; a FIFO or a device (--out /dev/stdout) has no
  // "beside" (no journal next to a device node): such a sweep is not resumable.
  if (!o.out.empty() && !io::output_target(o.out).direct) {
    // A shard's journal is its own: resuming shard 2 never picks up the rows of shard 3.
    // And a sweep that also writes --hdf5 is another journal than one that does not: resumed
    // without it, its FILE.partial was left unfinished without a word.
    std::uint64_t journal_fingerprint =
        p.sharded ? io::fingerprint(p.study, p.header + "\nshard " + p.shard.text())
                  : p.fingerprint;
    if (!o.hdf5.empty())  // FNV-1a of the HDF5 file's path, mixed in
      for (const char ch :
           "hdf5 " + std::filesystem::weakly_canonical(std::filesystem::absolute(o.hdf5)).string())
        journal_fingerprint =
            (journal_fingerprint ^ static_cast<unsigned char>(ch)) * 0x100000001b3ULL;
    // Beside the file --out names, through symbolic links (--out /dev/stdout redirected to a
    // file: beside that file, never in /dev).
    out.journal = std::make_unique<io::Journal>(journal_path(o.out), journal_fingerprint, p.total,
                                                o.resume, o.restart);
  }
  // The steady states go into FILE.hdf5.partial as they come (kept for --resume).
  if (!o.hdf5.empty()) {
    if (o.restart) io::StudyHdf5Writer::discard_partial(o.hdf5);
    out.hdf5 = std::make_unique<io::StudyHdf5Writer>(
        o.hdf5, io::Hdf5StudyInfo{p.fingerprint, p.total, p.sharded, p.shard}, o.resume);
  }
  if (out.journal) {
    // Streamed from the journal into the row store: a resumed million-case sweep holds no rows.
    const std::vector<std::string> header = io::csv_split(p.header);
    // The journal's cases whose steady state the partial HDF5 file lacks (said below).
    std::vector<bool> lost(out.hdf5 ? p.total : 0);
    // ... and those whose case file --cases-dir lacks (another directory than the interrupted
    // run's, or files deleted): run again, said (they were run again without a word).
    std::size_t missing_files = 0;
    out.journal->for_each_done([&](std::size_t index, const std::string& row) {
      // A row the sweep did not write as it reads (edited, damaged) is refused, never copied
      // into the results: its cells, status and numbers, and its swept values, the case's.
      std::string defect = io::study_row_defect(header, row);
      if (defect.empty()) {
        const std::vector<std::string> cells = io::csv_split(row);
        const std::vector<io::Value>& values = p.study.varied[index];
        for (std::size_t k = 0; k < values.size() && defect.empty(); ++k)
          if (cells[1 + k] != io::format_value(values[k]))
            defect = "its " + p.study.keys[k] + " is '" + cells[1 + k] + "', the case's is '" +
                     io::format_value(values[k]) + "'";
      }
      if (!defect.empty())
        throw Error("the journal " + out.journal->path() +
                    " is damaged or edited: the row of case " + std::to_string(index) +
                    " cannot be this sweep's (" + defect + "); run with --restart to discard it");
      if (!p.mine[index] || out.rows->has(index)) return;
      if (!o.cases_dir.empty() &&
          !std::filesystem::exists(o.cases_dir + "/" + case_file_name(index, p.total))) {
        ++missing_files;
        return;
      }
      if (out.hdf5 && !out.hdf5->has_case(index)) {  // run again for its steady state
        lost[index] = true;
        return;
      }
      out.add(index, row, p.study.keys.size());
    });
    if (missing_files > 0)
      warn("--cases-dir " + o.cases_dir + " lacks the case files of " +
           std::to_string(missing_files) + " finished case" + (missing_files == 1 ? "" : "s") +
           " of the journal (another directory than the interrupted run's, or files removed): " +
           (missing_files == 1 ? "it is" : "they are") + " run again");
    // A kill -9 keeps the journal's rows, but the HDF5 file only as it was at its last flush (at
    // most a second before), or damaged (its later writes half done): the cases it lost run again.
    if (const auto n = std::count(lost.begin(), lost.end(), true); n > 0) {
      const std::string cases = std::to_string(n) + " finished case" + (n == 1 ? "" : "s");
      if (out.hdf5->partial_was_damaged())
        warn("the partial HDF5 file " + o.hdf5 + ".partial was damaged (the sweep was killed " +
             "before it was written out): " + cases + (n == 1 ? " is" : " are") +
             " run again for " + (n == 1 ? "its steady state" : "their steady states"));
      else
        warn("the partial HDF5 file " + o.hdf5 + ".partial lacks the steady state" +
             (n == 1 ? "" : "s") + " of " + cases + " (the sweep was killed before " +
             (n == 1 ? "it was" : "they were") +
             " written out): " + (n == 1 ? "it is" : "they are") + " run again");
    }
  }
  return out;
}

// Runs the cases this run still has to do, on all cores, with a progress line; each finished
// case goes to the journal, the case files and the HDF5 file as it comes. Returns the seconds.
double run_cases(const SweepOptions& o, const SweepPlan& p, SweepOutputs& out) {
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < p.total; ++i)
    if (p.mine[i] && !out.rows->has(i)) pending.push_back(i);
  const std::size_t already = p.n_mine - pending.size();
  if (already > 0 && !o.quiet)
    std::cerr << "oscidrum: resuming: " << already << " of " << p.n_mine << " cases already done\n";

  install_interrupt_handlers();
  ProgressLine line(stderr_is_terminal() && !o.quiet);
  const auto start = std::chrono::steady_clock::now();
  StudyOptions options;
  options.threads = o.threads;
  options.n_harmonics = o.harmonics;
  options.cancelled = [] { return interrupted(); };
  options.previous = continuation_links(p.spec, p.study, pending);
  options.keep_outcomes = false;  // every outcome is used in on_case_done and dropped
  // The steady states' samples only for the files that hold them.
  options.samples_in_callback = !o.cases_dir.empty() || out.hdf5 != nullptr;
  // Called by the workers concurrently: the row, the case file and the compression of the steady
  // state for the HDF5 file are made in parallel; the HDF5 file, the journal and the row store
  // (which are shared) one case at a time.
  options.concurrent_on_case_done = true;
  std::mutex shared;
  options.on_case_done = [&](std::size_t i, const CaseOutcome& outcome) {
    const std::size_t g = pending[i];
    const std::string row = io::study_csv_row(p.columns, g, p.study.varied[g], outcome);
    if (!o.cases_dir.empty() && outcome.result.samples.size() > 0) {
      std::ostringstream csv;
      io::write_steady_state_csv(csv, outcome.result);
      io::write_file_atomic(o.cases_dir + "/" + case_file_name(g, p.total), csv.str());
    }
    std::optional<io::StudyHdf5Writer::PreparedCase> prepared;
    if (out.hdf5) prepared = io::StudyHdf5Writer::prepare(outcome);
    const std::lock_guard lock(shared);
    if (out.hdf5) out.hdf5->add_case(g, outcome, *prepared);
    if (out.journal) out.journal->append(g, row);
    out.add(g, row, p.study.keys.size());
  };
  options.progress = [&](std::size_t done, std::size_t n) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
    const double eta = rate > 0 ? static_cast<double>(n - done) / rate : 0.0;
    line.update(
        "oscidrum sweep: " + std::to_string(already + done) + "/" + std::to_string(p.n_mine) +
            " cases (" +
            fmt(100.0 * static_cast<double>(already + done) / static_cast<double>(p.n_mine), 3) +
            " %), " + fmt(rate, 3) + " cases/s, ETA " + duration(eta),
        done == n);
  };
  run_study(
      pending.size(), [&](std::size_t j) { return p.study.cases[pending[j]]; }, options);
  line.clear();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// An interrupted sweep: what is kept and how to finish it.
int report_interrupted(const SweepOptions& o, const SweepPlan& p, SweepOutputs& out,
                       std::size_t finished) {
  std::cerr << "oscidrum: interrupted: " << finished << " of " << p.n_mine << " cases done";
  if (out.journal)
    // The same command with --resume: a hint that rebuilt it named --out and --shard only, and
    // without the others (--hdf5, --harmonics, --set, --no-continuation) the journal was another
    // study's, or the HDF5 file was left unfinished.
    std::cerr << " (kept in " << out.journal->path()
              << "); run the same command with --resume added to finish it (every other flag as "
                 "it was)\n";
  else {
    // Not resumable (no journal without --out): the HDF5 file's .partial could never be finished
    // and was left behind (30-50 MB) while this said "nothing written"; the case files of
    // --cases-dir are whole files of finished cases and stay, said.
    if (out.hdf5) {
      out.hdf5.reset();
      io::StudyHdf5Writer::discard_partial(o.hdf5);
    }
    std::cerr << "; no results written"
              << (o.cases_dir.empty() ? std::string()
                                      : " (the finished cases' files are in " + o.cases_dir + ")")
              << "; give --out FILE to make a sweep resumable\n";
  }
  return interrupted_exit_code();
}

// This run's rows in case order, from the row store.
std::vector<std::string> all_rows(const SweepPlan& p, SweepOutputs& out) {
  std::vector<std::string> rows;
  for (std::size_t i = 0; i < p.total; ++i)
    if (p.mine[i]) rows.push_back(out.rows->get(i));
  return rows;
}

// The results CSV, streamed row by row: a shard's first line names the study and the slice (for
// oscidrum merge), then the header and the rows in case order.
void write_csv(std::ostream& os, const SweepPlan& p, SweepOutputs& out) {
  if (p.sharded) os << io::shard_line({p.fingerprint, p.total, p.shard}) << "\n";
  os << p.header << "\n";
  for (std::size_t i = 0; i < p.total; ++i)
    if (p.mine[i]) os << out.rows->get(i) << "\n";
}

// The finished study: the HDF5 file and the results CSV (atomically).
void write_results(const SweepOptions& o, const SweepPlan& p, SweepOutputs& out) {
  if (out.hdf5) {
    std::vector<std::size_t> indices;
    for (std::size_t i = 0; i < p.total; ++i)
      if (p.mine[i]) indices.push_back(i);
    out.hdf5->finish(p.study, indices, p.header,
                     [&](std::size_t k) { return out.rows->get(indices[k]); });
  }
  if (!o.out.empty()) {
    io::write_file_atomic(o.out, [&](std::ostream& os) { write_csv(os, p, out); });
    if (out.journal) out.journal->remove();
  }
}

// The status counts on stderr (resumed rows included); true if every case is a steady state.
bool report_statuses(const SweepOptions& o, const SweepPlan& p, const SweepOutputs& out,
                     double elapsed) {
  const std::map<std::string, std::size_t>& counts = out.statuses;
  if (!o.quiet) {
    std::string summary;
    for (const auto& [status, n] : counts)
      summary += (summary.empty() ? "" : ", ") + std::to_string(n) + " " + status;
    if (summary.empty()) summary = "the shard holds none of the study's cases";
    std::cerr << "oscidrum: " << p.n_mine << " cases"
              << (p.sharded ? " of shard " + p.shard.text() : std::string()) << " (" << summary
              << ") in " << duration(elapsed)
              << (o.out.empty() ? std::string() : "; wrote " + o.out) << "\n";
  }
  // Every case a steady state; a shard that holds no case (more shards than cases) failed none.
  return counts.empty() || (counts.size() == 1 && counts.begin()->first == "steady_state");
}

int run(const SweepOptions& o) {
  check_options(o);
  const SweepPlan p = plan_sweep(o);
  if (o.list) return list_cases(p, o.format);
  check_run_options(o, p);
  SweepOutputs out = open_outputs(o, p);
  const double elapsed = run_cases(o, p, out);
  // Interrupted (a signal after the last case changes nothing).
  if (out.finished < p.n_mine) return report_interrupted(o, p, out, out.finished);

  write_results(o, p, out);
  std::string format = o.format;
  if (format.empty()) format = o.out.empty() ? "csv" : "none";
  if (format == "csv") write_csv(std::cout, p, out);
  // json and table hold every row (for studies that people read; csv streams).
  if (format == "json") std::cout << io::study_json(p.header, all_rows(p, out));
  if (format == "table") std::cout << rows_table(p.header, all_rows(p, out), p.study.keys.size());
  std::cout.flush();
  const bool all_ok = report_statuses(o, p, out, elapsed);
  // --plot: curves over the first swept key (a panel per contact regime), or a heat map over two
  // numeric keys (oscidrum.plot.plot_study).
  if (!o.plot.empty() && run_python({"oscidrum.plot", "study", "--csv", o.out, "--metric",
                                     o.plot_metric, "--out", o.plot},
                                    "the results are in " + o.out, {}, o.quiet) != 0)
    return interrupted() ? plot_interrupted("the results are in " + o.out) : kExitCaseFailed;
  return all_ok ? kExitOk : kExitCaseFailed;
}

}  // namespace

void add_sweep_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = app.add_subcommand(
      "sweep",
      "Run a study of many cases on all cores, one CSV row per case. A study is a base case and "
      "parameters to vary (lists, ranges {start, stop, step|num}, "
      "the G values of paper Table 2), combined as a cartesian product or zipped, on all cores. "
      "Writes one CSV row per case: the swept values, status, diagnostics and metrics (peaks of "
      "x_M'', z_M'' [m/s^2], harmonic amplitudes A1..AN [m/s^2], lags, area [m^2/s^4], stick/slip "
      "fractions; columns in docs/outputs.md). The result is identical to a serial run, in case "
      "order. Progress (cases done, rate, ETA) goes to stderr when it is a terminal.");
  sub->footer(
      "Examples:\n"
      "  oscidrum sweep examples/table2_sweep.toml --out results.csv\n"
      "  oscidrum sweep examples/table2_sweep.toml --out results.csv --resume   (after Ctrl-C)\n"
      "  oscidrum sweep study.toml --list                 show the cases, run nothing\n"
      "  oscidrum sweep study.toml --shard 2/4 --out shard_2.csv   one of 4 slices\n"
      "  oscidrum sweep study.toml --out results.csv --hdf5 results.h5\n"
      "  oscidrum sweep examples/frequency_sweep.toml --out f.csv --plot f.png   heat map of "
      "the area over f and G\n"
      "  oscidrum sweep study.toml --format table --set numerics.max_periods=500\n"
      "Study file syntax: docs/config.md (\"Sweeps\"). Exit codes: 0 all cases steady, 1 some "
      "case ended otherwise (see its status), 2 bad input, 130 interrupted (resume with "
      "--resume).");
  sub->add_option("study", o->study, "study file (TOML): base case + [sweep]")
      ->required()
      ->type_name("STUDY.toml");
  add_set_flag(*sub, o->c);
  o->out_flag =
      sub->add_option(
             "--out,-o", o->out,
             "write the results CSV to FILE (atomically, at the end; finished rows are kept "
             "in FILE.journal meanwhile). Without it, or with '-', the CSV goes to stdout")
          ->type_name("FILE");
  o->cases_dir_flag =
      sub->add_option(
             "--cases-dir", o->cases_dir,
             "also write each case's steady state to DIR/case_NNNN.csv (docs/csv-columns.md)")
          ->type_name("DIR");
  sub->add_option("--threads,-j", o->threads, "worker threads (default 0: all cores)")
      ->check(CLI::Range(0, 4096));
  sub->add_flag("--resume", o->resume,
                "finish an interrupted sweep: run only the cases missing from FILE.journal");
  sub->add_flag("--restart", o->restart, "discard the journal of an interrupted sweep");
  sub->add_option("--format", o->format,
                  "what to print on stdout: csv, json, table or none (default: csv without --out, "
                  "none with it)")
      ->check(CLI::IsMember({"csv", "json", "table", "none"}));
  sub->add_option("--harmonics", o->harmonics,
                  "harmonic amplitude columns A1 ... AN of x_M'' and z_M'' (default 10)")
      ->check(CLI::Range(0, 100000));
  o->hdf5_flag =
      sub->add_option("--hdf5", o->hdf5,
                      "also write the study to one HDF5 file: every case's parameters, results "
                      "and sampled steady state, with units (layout in docs/outputs.md; h5py "
                      "reads it). Written as FILE.partial while running, renamed at the end")
          ->type_name("FILE");
  o->shard_flag =
      sub->add_option("--shard", o->shard,
                      "run only shard I of N (1 <= I <= N): the cases whose index i has i mod N = "
                      "I - 1. The CSV starts with a line naming the study and the shard; join the "
                      "shards with 'oscidrum merge' (examples/slurm/ for a cluster job array)")
          ->type_name("I/N");
  o->plot_flag =
      sub->add_option(
             "--plot", o->plot,
             "also draw the study into FILE (.png or .svg; needs --out): the metric against "
             "the first swept key, one curve per value of the others and a panel per "
             "contact regime when contact.pure_rolling is swept, or a heat map over two "
             "numeric swept keys (Python package, docs/python.md)")
          ->type_name("FILE");
  sub->add_option("--plot-metric", o->plot_metric,
                  "the results column --plot shows (default area; e.g. ddx_max, psi_xz)")
      ->type_name("COLUMN");
  sub->add_flag("--no-continuation", o->no_continuation,
                "start every case from rest (numerics.continuation = false): with numerics.method "
                "= shooting, a case otherwise starts from the steady state of its neighbour "
                "along the swept key with the most values (docs/periodic.md)");
  sub->add_flag("--list", o->list, "print the expanded cases and exit without running them");
  sub->add_flag("--quiet,-q", o->quiet, "no progress line and no summary on stderr");
  sub->callback([o, &action] {
    if (o->out == "-") {  // stdout, as without --out (and as run's --csv -)
      o->out.clear();
      o->out_is_stdout = true;
    }
    action = [o] { return run(*o); };
  });
}

}  // namespace oscidrum::cli
