// A seeded fuzz suite for the command-line tool: the classes of bad input and hostile use that the
// reliability probes found (malformed and extreme numbers in every numeric flag of every command,
// outputs that are not regular files, records with shifted clocks, interrupts at random moments,
// random plausible cases). Each class draws its inputs from one seeded generator and checks what
// must hold for every input: no crash, no hang, bounded memory, a refused value gives exit code 2
// and one line naming the flag, a status that is not a steady state carries no metrics, nothing
// but a regular file is ever replaced.
//
// Fast by default (a few dozen draws per class). Longer runs: scripts/fuzz.sh, or the variables
//   OSCIDRUM_FUZZ_SEED   the seed (default: fixed, so a failure in CI reproduces)
//   OSCIDRUM_FUZZ_SCALE  draws per class as a multiple of the default (default 1)
// Every failure prints the seed and the command line to rerun.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "oscidrum/outputs.hpp"
#include "process.hpp"

namespace oscidrum::test {
namespace {

const std::string kSource = OSCIDRUM_SOURCE_DIR;

unsigned seed() {
  const char* s = std::getenv("OSCIDRUM_FUZZ_SEED");
  return s != nullptr && *s != '\0' ? static_cast<unsigned>(std::strtoul(s, nullptr, 10))
                                    : 20261126u;
}

int draws(int base) {
  const char* s = std::getenv("OSCIDRUM_FUZZ_SCALE");
  const double scale = s != nullptr && *s != '\0' ? std::strtod(s, nullptr) : 1.0;
  return std::max(1, static_cast<int>(std::lround(base * scale)));
}

std::string joined(const std::vector<std::string>& args) {
  std::string out = "oscidrum";
  for (const std::string& a : args) {
    const bool plain = !a.empty() && a.find_first_of(" '\"\\$`") == std::string::npos;
    out += " " + (plain ? a : "'" + a + "'");
  }
  return out;
}

std::string reproduce(unsigned s, const std::vector<std::string>& args) {
  return "seed " + std::to_string(s) + ": " + joined(args);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// `oscidrum args` in `dir`'s files, killed as hung after `limit_s`.
Outcome run_limited(const TempDir& dir, const std::vector<std::string>& args, double limit_s) {
  static int counter = 0;
  const std::string base = dir / ("p" + std::to_string(counter++));
  return finish(start(args, base + ".out", base + ".err"), base + ".out", base + ".err", limit_s);
}

// Files whose name says they are an unfinished output (an atomic write's temporary).
std::vector<std::string> leftovers(const std::string& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") != std::string::npos || name.find(".partial") != std::string::npos)
      found.push_back(e.path().string());
  }
  return found;
}

// A record of the default case: 48 periods at the CLI's sampling (t, ddx_M, ddz_M columns), long
// enough for one identification window (40 periods).
const std::string& default_record(const TempDir& dir) {
  static std::map<std::string, std::string> made;
  auto it = made.find(dir.path());
  if (it != made.end()) return it->second;
  const std::string path = dir / "record.csv";
  const Outcome o = run({"run", "--quiet", "--set", "numerics.output_periods=48", "--csv", path});
  EXPECT_EQ(o.code, 0) << o.err;
  return made[dir.path()] = path;
}

// The numeric flags of a command, read from its --help (CLI11 types FLOAT, INT, UINT).
std::vector<std::pair<std::string, std::string>> numeric_flags(const std::string& command) {
  const Outcome help = run({command, "--help"});
  EXPECT_EQ(help.code, 0) << command << ": " << help.err;
  std::vector<std::pair<std::string, std::string>> flags;
  for (const std::string& line : lines(help.out)) {
    std::istringstream in(line);
    std::string name, type;
    in >> name >> type;
    if (name.rfind("--", 0) != 0) continue;
    if (const auto comma = name.find(','); comma != std::string::npos) name.resize(comma);
    type = type.substr(0, type.find(':'));  // "FLOAT:POSITIVE", "INT:INT in [2 - 200]"
    if (type == "FLOAT" || type == "INT" || type == "UINT") flags.emplace_back(name, type);
  }
  return flags;
}

// What a command needs besides the flag under test to get as far as reading it.
std::vector<std::string> base_args(const std::string& command, const TempDir& dir) {
  if (command == "analyze" || command == "identify") return {command, default_record(dir)};
  if (command == "calibrate") return {command, default_record(dir) + "@25"};
  if (command == "sweep") return {command, kSource + "/examples/table2_sweep.toml"};
  return {command};
}

// Texts that are no number at all (or no finite one, or no integer for an integer flag): always
// refused with exit code 2 and one line naming the flag.
const std::vector<std::string> kNotNumbers = {
    "",      " ",   "abc",   "0x10",     "0X1p3",    "nan",      "NaN",
    "-nan",  "inf", "-inf",  "Infinity", "1e99999",  "-1e99999", "1,5",
    "1.2.3", "1e",  "e5",    "+",        "-",        "--",       ".",
    "5 ",    " 5",  "1_000", "\xd9\xa1", "\xff\xfe", "1e5x",     "0b101"};
const std::vector<std::string> kNotIntegers = {"1.5", "1e3", "2.0", "0.1"};
// Numbers at the edges: accepted or refused, but never a crash, a hang or gigabytes of memory.
const std::vector<std::string> kExtremes = {"0",
                                            "-0",
                                            "-1",
                                            "1e-300",
                                            "1e-9",
                                            "4.9e-324",
                                            "1e9",
                                            "1e308",
                                            "-1e308",
                                            "1.7976931348623157e308",
                                            "2147483648",
                                            "4294967297",
                                            "18446744073709551617",
                                            "0.999999999999",
                                            "1"};

// The limits only catch hangs. Under the sanitizers everything runs about seven times slower, and
// this project's machines differ 2.3x in speed: there they are four times as long.
#ifdef OSCIDRUM_SANITIZED
constexpr double kSlower = 4.0;
#else
constexpr double kSlower = 1.0;
#endif
constexpr double kRefusalSeconds = 10 * kSlower;  // a refusal is instant
constexpr double kRunSeconds = 60 * kSlower;  // an accepted extreme value runs a case or a study
constexpr long kMemoryKiB = 2L * 1024 * 1024;

void check_refused(const Outcome& o, const std::string& flag, const std::string& repro) {
  EXPECT_FALSE(o.hung) << "hung: " << repro;
  EXPECT_EQ(o.signal, 0) << "crashed: " << repro << "\n" << o.err;
  EXPECT_EQ(o.code, 2) << "accepted: " << repro << "\n" << o.err;
  EXPECT_EQ(o.err.rfind("oscidrum: error: ", 0), 0u) << repro << "\n" << o.err;
  EXPECT_EQ(lines(o.err).size(), 1u) << repro << "\n" << o.err;
  EXPECT_NE(o.err.find(flag), std::string::npos) << "the flag is not named: " << repro << "\n"
                                                 << o.err;
  // Raw bytes that are not UTF-8 are escaped in the message, never echoed.
  for (unsigned char c : o.err) EXPECT_NE(c, 0xffu) << repro;
}

// Class 1 and 7: every numeric flag of every command refuses what is not a (finite, decimal)
// number, with the flag's name.
TEST(FuzzCli, MalformedNumbersInEveryNumericFlagAreRefused) {
  const unsigned s = seed();
  std::mt19937 rng(s);
  TempDir dir;
  std::vector<std::pair<std::string, std::pair<std::string, std::string>>> all;
  for (const std::string command : {"run", "sweep", "analyze", "identify", "calibrate", "soil",
                                    "transmissibility", "continue", "diagram"})
    for (const auto& flag : numeric_flags(command)) all.push_back({command, flag});
  ASSERT_GT(all.size(), 40u) << "the numeric flags were not found in --help";
  const int n = draws(60);
  for (int i = 0; i < n; ++i) {
    const auto& [command, flag] = all[rng() % all.size()];
    const bool integer = flag.second != "FLOAT";
    const bool use_integer_case = integer && rng() % 3 == 0;
    const std::vector<std::string>& pool = use_integer_case ? kNotIntegers : kNotNumbers;
    const std::string text = pool[rng() % pool.size()];
    std::vector<std::string> args = base_args(command, dir);
    args.push_back(flag.first);
    args.push_back(text);
    check_refused(run_limited(dir, args, kRefusalSeconds), flag.first, reproduce(s, args));
  }
}

// Class 4: numbers at the edges of every numeric flag: accepted (and then the run ends in time
// within bounded memory) or refused with one line; never a crash, a hang or gigabytes.
TEST(FuzzCli, ExtremeNumbersEndInTimeWithBoundedMemory) {
  const unsigned s = seed() + 1;
  std::mt19937 rng(s);
  TempDir dir;
  std::vector<std::pair<std::string, std::string>> all;
  for (const std::string command :
       {"run", "analyze", "identify", "calibrate", "soil", "transmissibility"})
    for (const auto& flag : numeric_flags(command)) all.push_back({command, flag.first});
  const int n = draws(40);
  for (int i = 0; i < n; ++i) {
    const auto& [command, flag] = all[rng() % all.size()];
    const std::string text = kExtremes[rng() % kExtremes.size()];
    std::vector<std::string> args = base_args(command, dir);
    args.insert(args.end(), {flag, text});
    // A case's own budget bounds an accepted value that makes it stiff (a suspension damping of
    // 2e9 N s/m: 14 000 steps per period, 40 s for the default 5000 periods).
    if (command == "run") args.insert(args.end(), {"--quiet", "--set", "numerics.max_periods=200"});
    const std::string repro = reproduce(s, args);
    const Outcome o = run_limited(dir, args, kRunSeconds);
    if (std::getenv("OSCIDRUM_FUZZ_VERBOSE"))
      std::cerr << o.seconds << " s, " << o.max_rss_kb / 1024 << " MB, exit " << o.code << ": "
                << repro << "\n";
    EXPECT_FALSE(o.hung) << "hung: " << repro;
    EXPECT_EQ(o.signal, 0) << "crashed: " << repro << "\n" << o.err;
    EXPECT_LT(o.max_rss_kb, kMemoryKiB) << "memory: " << repro;
    EXPECT_TRUE(o.code == 0 || o.code == 1 || o.code == 2) << repro << "\n" << o.err;
    if (o.code == 2) {
      EXPECT_EQ(lines(o.err).size(), 1u) << repro << "\n" << o.err;
      EXPECT_EQ(o.err.rfind("oscidrum: error: ", 0), 0u) << repro << "\n" << o.err;
    }
  }
}

// Found by the suite: identify with a roller whose model hardly settles (a suspension of 1e9
// N/m: every trial of the fit runs into its 1500 periods) took over a minute without a word;
// the model runs of one window now share a budget of integration steps.
TEST(FuzzCli, IdentifyWithARollerThatHardlySettlesEndsInSeconds) {
  TempDir dir;
  const std::string record = dir / "record.csv";
  ASSERT_EQ(run({"run", "--quiet", "--set", "numerics.output_periods=41", "--csv", record}).code,
            0);
  const std::vector<std::string> args = {"identify", record, "--kd", "1e9", "--quiet"};
#ifdef OSCIDRUM_SANITIZED
  // About 20 s of work on a slow machine, seven times that under the sanitizers: the limit must
  // leave room for a loaded machine (103 s in a CI run, 260 s in one beside a build). A hang
  // still runs forever. (kRunSeconds is 240 s here.)
  const double limit = 2.5 * kRunSeconds;
#else
  // About 24 s of work on the slower of this project's machines (26 s in its CI run), 73 s there
  // beside a sanitizer build: the wall-time limit only catches a hang, the bound on the work is
  // the CPU-time test below.
  const double limit = 4.0 * kRunSeconds;
#endif
  const Outcome o = run_limited(dir, args, limit);
  EXPECT_FALSE(o.hung) << joined(args);
  EXPECT_TRUE(o.code == 0 || o.code == 1) << o.err;
  // The fit as read spends the window's budget, and the refits of the reading left open (the
  // model's record has no gravity to tell its z axis) share it rather than each spending one of
  // their own (which doubled the work): the diagnosis after them finds it used up, and says so.
  EXPECT_NE(o.out.find("had used up their budget"), std::string::npos) << o.out;
#ifndef OSCIDRUM_SANITIZED
  // The bound is on the work (CPU time), not the wall time, which a loaded machine stretches, and
  // relative to the work of the same record's identification with the case's roller, on the same
  // machine (CPU times differ 2.3x between this project's machines): about 4 times that (7.4 s
  // against 1.9 s on an Intel Xeon of this project; 8 times while the open reading's refits had
  // a budget of their own), a window without the shared budget over 200 times.
  const Outcome normal = run_limited(dir, {"identify", record, "--quiet"}, kRunSeconds);
  ASSERT_EQ(normal.code, 0) << normal.err;
  EXPECT_LT(o.cpu_seconds, 60.0 * std::max(normal.cpu_seconds, 0.05))
      << joined(args) << ": " << o.cpu_seconds << " s against " << normal.cpu_seconds
      << " s for the case's roller";
#endif
}

// Class 3: a record's clock may start anywhere (and run at any offset): the metrics of analyze do
// not depend on it.
TEST(FuzzCli, RecordsWithShiftedClocksGiveTheSameMetrics) {
  const unsigned s = seed() + 2;
  std::mt19937 rng(s);
  TempDir dir;
  const std::string& record = default_record(dir);
  const Outcome reference = run({"analyze", record, "--format", "json"});
  ASSERT_EQ(reference.code, 0) << reference.err;
  const auto want = nlohmann::json::parse(reference.out);
  std::ifstream in(record);
  std::string header;
  std::getline(in, header);
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(line);
  const int n = draws(8);
  for (int i = 0; i < n; ++i) {
    // Offsets from -1e5 s to 1e5 s, on a log scale, either sign.
    const double offset = (rng() % 2 ? -1.0 : 1.0) *
                          std::pow(10.0, std::uniform_real_distribution<double>(-3, 5)(rng));
    const std::string shifted = dir / ("shifted" + std::to_string(i) + ".csv");
    {
      std::ofstream out(shifted);
      out << header << '\n' << std::setprecision(17);
      for (const std::string& row : rows) {
        const auto comma = row.find(',');
        out << std::stod(row.substr(0, comma)) + offset << row.substr(comma) << '\n';
      }
    }
    const std::vector<std::string> args = {"analyze", shifted, "--format", "json"};
    const std::string repro = reproduce(s, args) + " (t shifted by " + std::to_string(offset) + ")";
    const Outcome o = run_limited(dir, args, kRefusalSeconds);
    ASSERT_EQ(o.signal, 0) << "crashed: " << repro;
    ASSERT_EQ(o.code, 0) << repro << "\n" << o.err;
    const auto got = nlohmann::json::parse(o.out);
    for (const char* key : {"f", "ddx_max", "ddz_min", "psi_xz", "area"}) {
      ASSERT_TRUE(want.contains(key) && want[key].is_number()) << key;
      ASSERT_TRUE(got.contains(key) && got[key].is_number()) << key << ": " << repro;
      const double a = want[key].get<double>();
      const double b = got[key].get<double>();
      // The times are written with 17 digits: what moves is the fit's rounding (~1e-12 of the
      // offset relative to the period), far below this.
      EXPECT_NEAR(b, a, 1e-6 * std::abs(a))
          << key << ": " << repro << " (f " << got["f"].get<double>() << " against "
          << want["f"].get<double>() << ", window " << got["t_start"].get<double>() << " ... "
          << got["t_end"].get<double>() << ")";
    }
  }
}

// Class 1: outputs that are not regular files are never replaced: a symbolic link is written
// through (atomically at its target), a FIFO or character device is written directly, a
// directory is refused with one line; nothing half-written is left behind.
TEST(FuzzCli, OutputsThatAreNotRegularFilesAreNeverReplaced) {
  const unsigned s = seed() + 3;
  std::mt19937 rng(s);
  const int n = draws(12);
  for (int i = 0; i < n; ++i) {
    TempDir dir;
    const std::string& record = default_record(dir);
    // A writer: (command..., flag)
    const std::vector<std::pair<std::vector<std::string>, std::string>> writers = {
        {{"run", "--quiet"}, "--csv"},
        {{"run", "--quiet"}, "--json"},
        {{"identify", record, "--quiet"}, "--csv"},
        {{"identify", record, "--quiet"}, "--json"},
        {{"sweep", kSource + "/examples/table2_sweep.toml", "--quiet"}, "--out"},
    };
    const auto& [command, flag] = writers[rng() % writers.size()];
    enum Kind { link_to_file, dangling_link, link_chain, fifo, dev_null, directory, link_to_dir };
    const Kind kind = static_cast<Kind>(rng() % 7);
    std::string path = dir / "out.dat";
    std::string target = dir / "target.dat";
    switch (kind) {
      case link_to_file:
        std::ofstream(target) << "old\n";
        std::filesystem::create_symlink("target.dat", path);
        break;
      case dangling_link:
        std::filesystem::create_symlink("target.dat", path);
        break;
      case link_chain:
        std::ofstream(target) << "old\n";
        std::filesystem::create_symlink("target.dat", dir / "middle.dat");
        std::filesystem::create_symlink("middle.dat", path);
        break;
      case fifo:
        ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
        break;
      case dev_null:
        path = "/dev/null";
        break;
      case directory:
        std::filesystem::create_directory(path);
        break;
      case link_to_dir:
        std::filesystem::create_directory(target);
        std::filesystem::create_symlink("target.dat", path);
        break;
    }
    struct stat before {};
    ASSERT_EQ(::lstat(path.c_str(), &before), 0);
    std::vector<std::string> args = command;
    args.insert(args.end(), {flag, path});
    const std::string repro = reproduce(s, args) + " (output kind " + std::to_string(kind) + ")";
    std::string fifo_text;
    std::thread reader;
    if (kind == fifo)
      reader = std::thread([&] {
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        fifo_text = text.str();
      });
    const Outcome o = run_limited(dir, args, kRunSeconds);
    if (reader.joinable()) reader.join();
    EXPECT_FALSE(o.hung) << repro;
    EXPECT_EQ(o.signal, 0) << "crashed: " << repro << "\n" << o.err;
    struct stat after {};
    ASSERT_EQ(::lstat(path.c_str(), &after), 0) << repro;
    EXPECT_EQ(before.st_mode & S_IFMT, after.st_mode & S_IFMT) << "replaced: " << repro;
    if (kind == dev_null) {
      EXPECT_EQ(before.st_rdev, after.st_rdev) << repro;
    }
    if (kind == directory || kind == link_to_dir) {
      EXPECT_EQ(o.code, 2) << repro << "\n" << o.err;
      EXPECT_EQ(lines(o.err).size(), 1u) << repro << "\n" << o.err;
      EXPECT_NE(o.err.find("directory"), std::string::npos) << repro << "\n" << o.err;
    } else {
      // Written (exit 0, or 1 when a run or window is not steady / ok, which still writes).
      EXPECT_TRUE(o.code == 0 || o.code == 1) << repro << "\n" << o.err;
      if (kind == link_to_file || kind == dangling_link || kind == link_chain) {
        EXPECT_TRUE(std::filesystem::is_regular_file(target)) << repro;
        EXPECT_NE(slurp(target), "old\n") << "not written through the link: " << repro;
        EXPECT_GT(slurp(target).size(), 10u) << repro;
      }
      if (kind == fifo) {
        EXPECT_GT(fifo_text.size(), 10u) << repro;
      }
    }
    EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{}) << repro;
  }
}

// Class 6 and 5: random plausible cases (soil, friction, driving torque, frequency, trough) end
// with a status; a status that is not a steady state carries no metrics; a drum driven beyond
// what friction can hold is reported as slipping through, not as an unfinished run.
TEST(FuzzCli, RandomPlausibleCasesEndWithAnHonestStatus) {
  const unsigned s = seed() + 4;
  std::mt19937 rng(s);
  TempDir dir;
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  auto text = [](double v) {
    std::ostringstream out;
    out << std::setprecision(6) << v;
    return out.str();
  };
  std::set<std::string> statuses;  // every status the library has, but cancelled
#define OSCIDRUM_STATUS_NAME(name, description) statuses.insert(#name);
  OSCIDRUM_STATUSES(OSCIDRUM_STATUS_NAME)
#undef OSCIDRUM_STATUS_NAME
  statuses.erase("cancelled");
  // The roller's static load W = P0 [N] and radius r [m], from its defaults.
  const Outcome defaults = run({"run", "--quiet", "--format", "json"});
  ASSERT_EQ(defaults.code, 0) << defaults.err;
  const auto parameters = nlohmann::json::parse(defaults.out)["parameters"];
  const double W = parameters["roller.P0"].get<double>();
  const double r = parameters["roller.r"].get<double>();
  const int n = draws(16);
  for (int i = 0; i < n; ++i) {
    const double G = std::exp(uniform(std::log(5.0), std::log(150.0)));
    const bool pure_rolling = rng() % 4 == 0;
    const double mu = uniform(0.2, 1.0);
    // MMd as a multiple of mu W r: none, within what friction holds, or beyond it.
    const double spin = rng() % 3 == 0 ? 0.0 : uniform(0.0, 1.5);
    const double f = uniform(20.0, 60.0);
    std::vector<std::string> args = {"run",      "--quiet",
                                     "--format", "json",
                                     "--set",    "soil.input=modulus",
                                     "--set",    "soil.G=" + text(G * 1e6),
                                     "--f",      text(f)};
    if (pure_rolling)
      args.push_back("--pure-rolling");
    else
      args.insert(args.end(), {"--mu", text(mu)});
    if (!pure_rolling) args.insert(args.end(), {"--MMd", text(spin * mu * W * r)});
    if (rng() % 2) args.insert(args.end(), {"--R", text(uniform(0.62, 1.5))});
    const std::string repro = reproduce(s, args);
    const Outcome o = run_limited(dir, args, kRunSeconds);
    if (std::getenv("OSCIDRUM_FUZZ_VERBOSE"))
      std::cerr << o.seconds << " s, exit " << o.code << ": " << repro << "\n";
    ASSERT_FALSE(o.hung) << repro;
    ASSERT_EQ(o.signal, 0) << "crashed: " << repro << "\n" << o.err;
    ASSERT_TRUE(o.code == 0 || o.code == 1) << repro << "\n" << o.err;
    const auto j = nlohmann::json::parse(o.out);
    const std::string status = j["status"].get<std::string>();
    EXPECT_TRUE(statuses.count(status)) << status << ": " << repro;
    EXPECT_EQ(o.code == 0, status == "steady_state") << repro;
    if (status != "steady_state") {
      EXPECT_TRUE(j["metrics"].is_null()) << "metrics beside " << status << ": " << repro;
    } else {
      // (Ratios to a fundamental that vanishes by symmetry are null in a steady state too.)
      for (const char* key : {"ddx_max", "ddx_min", "ddz_max", "ddz_min", "area", "delta_max",
                              "stick_fraction", "slip_fraction"})
        EXPECT_TRUE(j["metrics"][key].is_number()) << key << " in a steady state: " << repro;
    }
    // The status does not depend on how the case was started (a gentler start: the excitation
    // ramped in over 20 periods).
    std::vector<std::string> ramped = args;
    ramped.insert(ramped.end(), {"--set", "numerics.start_ramp_periods=20"});
    const Outcome g = run_limited(dir, ramped, kRunSeconds);
    ASSERT_TRUE(g.code == 0 || g.code == 1) << reproduce(s, ramped) << "\n" << g.err;
    EXPECT_EQ(nlohmann::json::parse(g.out)["status"].get<std::string>(), status)
        << "the status changes with the start: " << repro << " against " << reproduce(s, ramped);
    // MMd beyond what friction can carry at the static load (mu W r, W = P0; the mean of N is
    // at most W): the drum spins, reported as such and not as an unfinished run.
    if (!pure_rolling && spin > 1.02) {
      EXPECT_EQ(status, "gross_slip") << "MMd = " << spin << " mu W r: " << repro;
    }
  }
}

// Class 2: every command stops within 1 s of SIGINT or SIGTERM (exit 130 or 143), at a random
// moment, and leaves no half-written output.
TEST(FuzzCli, InterruptsAtRandomMomentsStopEveryCommandPromptly) {
  const unsigned s = seed() + 5;
  std::mt19937 rng(s);
  const int n = draws(8);
  for (int i = 0; i < n; ++i) {
    TempDir dir;
    const std::string& record = default_record(dir);
    const std::vector<std::vector<std::string>> commands = {
        {"run", "--set", "numerics.output_periods=1000", "--set",
         "numerics.samples_per_period=10000", "--set", "numerics.max_multiplicity=1", "--csv",
         dir / "s.csv", "--json", dir / "s.json"},
        {"run", "--f", "0.1", "--csv", dir / "s.csv"},
        {"sweep", kSource + "/bench/sweep/memory.toml", "--out", dir / "sweep.csv", "--threads",
         "1"},
        {"identify", record, "--window", "4", "--hop", "0.05", "--csv", dir / "id.csv"},
        {"analyze", record, "--window", "1", "--hop", "0.001", "--format", "json"},
        {"diagram", "--param", "MMd", "--from", "0", "--to", "2000", "--steps", "1000", "--csv",
         dir / "d.csv"},
#ifdef OSCIDRUM_WITH_PYTHON  // paper runs the Python package
        {"paper", "--out", dir / "paper", "--threads", "1"},
#endif
    };
    const std::vector<std::string>& args = commands[rng() % commands.size()];
    const int sig = rng() % 2 ? SIGINT : SIGTERM;
    const int delay_ms = static_cast<int>(20 + rng() % 400);
    const std::string repro = reproduce(s, args) + " (signal " + std::to_string(sig) + " after " +
                              std::to_string(delay_ms) + " ms)";
    const pid_t pid = start(args, dir / "out", dir / "err");
    ASSERT_TRUE(wait_until_catching(pid, sig)) << repro;
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    const bool sent = ::kill(pid, sig) == 0;
    const Outcome o = finish(pid, dir / "out", dir / "err", 30);
    ASSERT_FALSE(o.hung) << repro;
    EXPECT_EQ(o.signal, 0) << repro;
    if (o.code == 0 || o.code == 1) continue;  // it had finished before the signal
    ASSERT_TRUE(sent) << repro;
    EXPECT_EQ(o.code, 128 + sig) << repro << "\n" << o.err;
#ifndef OSCIDRUM_SANITIZED  // the sanitizers' own exit work is not the command's
    EXPECT_LT(o.seconds, 1.0) << "stopped " << o.seconds << " s after the signal: " << repro;
#endif
    EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{}) << repro;
    for (const char* name : {"s.csv", "s.json", "d.csv", "paper"})
      EXPECT_FALSE(std::filesystem::exists(dir / name)) << name << ": " << repro;
  }
}

// Kill -9 at random moments, once or twice, then --resume: the results equal an uninterrupted
// run byte for byte (the transient method: independent cases), and nothing half-written stays.
TEST(FuzzCli, KillAndResumeAtRandomMomentsLosesNothing) {
  const unsigned s = seed() + 6;
  std::mt19937 rng(s);
  TempDir dir;
  {
    std::ofstream(dir / "study.toml")
        << "[soil]\ninput = \"modulus\"\n[contact]\npure_rolling = true\n"
           "[numerics]\nmethod = \"transient\"\n"
           "[sweep]\n\"soil.G\" = { start = 5e6, stop = 70e6, num = 24 }\n";
  }
  const Outcome reference = run({"sweep", dir / "study.toml", "-q"});
  ASSERT_EQ(reference.code, 0) << reference.err;
  const int n = draws(3);
  for (int i = 0; i < n; ++i) {
    const std::string out = dir / ("r" + std::to_string(i) + ".csv");
    const std::vector<std::string> args = {"sweep",     dir / "study.toml",           "--out", out,
                                           "--threads", std::to_string(1 + rng() % 2)};
    std::string repro = reproduce(s, args);
    for (int kill = 0, kills = 1 + static_cast<int>(rng() % 2); kill < kills; ++kill) {
      std::vector<std::string> again = args;
      if (kill > 0) again.push_back("--resume");
      const int delay_ms = static_cast<int>(30 + rng() % 600);
      repro += " (killed after " + std::to_string(delay_ms) + " ms)";
      const pid_t pid = start(again, dir / "out", dir / "err");
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      ::kill(pid, SIGKILL);
      const Outcome o = finish(pid, dir / "out", dir / "err", 30);
      ASSERT_FALSE(o.hung) << repro;
      // Never half-written: absent, or the whole result (of a run that finished before a kill).
      if (o.signal == SIGKILL && std::filesystem::exists(out)) {
        EXPECT_EQ(slurp(out), reference.out) << "a half-written result: " << repro;
      }
    }
    std::vector<std::string> resume = args;
    resume.push_back("--resume");
    const Outcome o = run_limited(dir, resume, kRunSeconds);
    ASSERT_EQ(o.code, 0) << repro << "\n" << o.err;
    EXPECT_EQ(slurp(out), reference.out) << repro;
    EXPECT_FALSE(std::filesystem::exists(out + ".journal")) << repro;
    EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{}) << repro;
  }
}

}  // namespace
}  // namespace oscidrum::test
