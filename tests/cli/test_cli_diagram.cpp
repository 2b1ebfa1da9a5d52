// End-to-end tests of `oscidrum diagram`: the files, the table, bad input, Ctrl-C.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "process.hpp"

namespace oscidrum::test {
namespace {

// Three values of the driving torque, up and down: the CSV has a row per stroboscopic point
// with the value's verdict and every output column; the JSON has a value per visit with its
// points; the table a line per value.
TEST(CliDiagram, WritesThePointsOfEveryValue) {
  TempDir dir;
  const Outcome o = run({"diagram",      "--param",   "MMd", "--from",  "0",           "--to",
                         "2000",         "--steps",   "2",   "--sweep", "both",        "--discard",
                         "20",           "--periods", "20",  "--csv",   dir / "d.csv", "--json",
                         dir / "d.json", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::string csv = slurp(dir / "d.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n'))
                .rfind("sweep[-],value[-],MMd[N m],point[-],verdict[-],period[-],lyapunov[1/s],"
                       "from_rest[-],shooting[-],t[s],delta[rad],phi[rad],x_A[m],s_A[m],",
                       0),
            0u)
      << csv.substr(0, csv.find('\n'));
  EXPECT_NE(csv.find(",ddx_M[m/s^2],ddz_M[m/s^2],"), std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 6 * 20);
  EXPECT_NE(csv.find("\ndown,5,0,20,periodic,1,"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "d.json"));
  EXPECT_EQ(j["schema"], "oscidrum-diagram/1");
  EXPECT_EQ(j["sweep"], "both");
  ASSERT_EQ(j["values"].size(), 6u);
  EXPECT_EQ(j["values"][3]["direction"], "down");
  EXPECT_EQ(j["values"][0]["verdict"], "periodic");
  EXPECT_EQ(j["values"][0]["section"]["ddz_M"].size(), 20u);
  // stdout: the table, one line per value after the header and its rule.
  EXPECT_NE(o.out.find("periodic"), std::string::npos) << o.out;
  EXPECT_EQ(std::count(o.out.begin(), o.out.end(), '\n'), 2 + 6) << o.out;
}

// Two values of one stable period-1 orbit (G 110 and 110.0001 MN/m^2 on a log-spiral trough):
// their points lie within 1e-9 of each other, and counted against that tiny range over the
// diagram the round-off made 390 "distinct" points; each value shows 1.
TEST(CliDiagram, APeriodicOrbitShowsOneDistinctPointWhateverTheOtherValues) {
  const Outcome o = run({"diagram",
                         "--param",
                         "soil.G",
                         "--from",
                         "110",
                         "--to",
                         "110.0001",
                         "--steps",
                         "1",
                         "--set",
                         "soil.input=modulus",
                         "--set",
                         "trough.k=0.002",
                         "--set",
                         "trough.a=0.601",
                         "--mu",
                         "0.7",
                         "--set",
                         "roller.unbalance=0.22877",
                         "--f",
                         "25",
                         "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  std::istringstream lines(o.out);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("up ", 0) != 0) continue;
    std::istringstream cells(line);
    std::string sweep, value, verdict, period, lambda, distinct;
    cells >> sweep >> value >> verdict >> period >> lambda >> distinct;
    EXPECT_EQ(verdict, "periodic") << line;
    EXPECT_EQ(distinct, "1") << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2) << o.out;
}

// A value whose flow stopped (pure rolling without a contact that can open loses contact at
// 66 Hz, with the ramp too) has no exponent: null in the JSON and '-' in the table, not the 0.0
// that reads as the signature of a torus.
TEST(CliDiagram, AValueWhoseFlowStoppedHasANullExponent) {
  TempDir dir;
  const Outcome o = run({"diagram",
                         "--param",
                         "roller.f",
                         "--from",
                         "66",
                         "--to",
                         "67",
                         "--steps",
                         "1",
                         "--set",
                         "soil.input=modulus",
                         "--set",
                         "soil.G=100e6",
                         "--pure-rolling",
                         "--set",
                         "roller.unbalance=0.22877",
                         "--discard",
                         "20",
                         "--periods",
                         "20",
                         "--json",
                         dir / "d.json",
                         "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "d.json"));
  ASSERT_EQ(j["values"].size(), 2u);
  for (const nlohmann::json& v : j["values"]) {
    EXPECT_EQ(v["verdict"], "undecided");
    EXPECT_TRUE(v["lyapunov"].is_null()) << v["lyapunov"];
    EXPECT_TRUE(v["lyapunov_halves"][0].is_null() && v["lyapunov_halves"][1].is_null())
        << v["lyapunov_halves"];
    EXPECT_EQ(v["evidence"].get<std::string>().rfind("the flow stopped (contact_lost)", 0), 0u)
        << v["evidence"];
  }
  std::istringstream lines(o.out);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("up ", 0) != 0) continue;
    std::istringstream cells(line);
    std::string sweep, value, verdict, period, lambda;
    cells >> sweep >> value >> verdict >> period >> lambda;
    EXPECT_EQ(lambda, "-") << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2) << o.out;
}

// --from/--to are typed in the unit of the key's case flag: MN/m^2 for soil.G (as --G), SI for
// the soil's coefficients (as --ksh), although the table shows ksh in MN/m.
TEST(CliDiagram, TheRangeIsInTheUnitOfTheKeysFlag) {
  TempDir dir;
  {
    std::ofstream(dir / "coef.toml") << "[soil]\ninput = \"coefficients\"\nksh = 1e7\nksv = 1e8\n"
                                        "csh = 1e5\ncsv = 1e5\n";
  }
  const Outcome o =
      run({"diagram", dir / "coef.toml", "--param", "soil.ksh", "--from", "1e7", "--to", "2e7",
           "--steps", "1", "--periods", "20", "--json", dir / "k.json", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "k.json"));
  EXPECT_EQ(j["unit"], "N/m");
  EXPECT_EQ(j["from"].get<double>(), 1e7);
  EXPECT_EQ(j["to"].get<double>(), 2e7);
  EXPECT_EQ(j["values"][0]["verdict"], "periodic");
  EXPECT_NE(o.out.find("soil.ksh [MN/m]"), std::string::npos) << o.out;
  const Outcome g =
      run({"diagram", "--param", "soil.G", "--set", "soil.input=modulus", "--from", "20", "--to",
           "30", "--steps", "1", "--periods", "20", "--json", dir / "g.json", "--quiet"});
  ASSERT_EQ(g.code, 0) << g.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "g.json"))["from"].get<double>(), 20e6);
}

TEST(CliDiagram, BadInputIsRefusedWithOneLineNamingTheFlag) {
  const std::vector<std::string> base = {"diagram", "--param", "contact.mu", "--from",
                                         "0.3",     "--to",    "0.5"};
  for (const auto& [extra, flag] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--steps", "0"}, "--steps"},
           {{"--periods", "10"}, "--periods"},
           {{"--discard", "-1"}, "--discard"},
           {{"--sweep", "sideways"}, "--sweep"},
           {{"--plot-quantity", "nope"}, "--plot-quantity"},
           {{"--plot", "x.png"}, "--plot"},
           {{"--format", "xml"}, "--format"}}) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 2) << flag << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_NE(o.err.find(flag), std::string::npos) << o.err;
  }
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"diagram", "--param", "soil.gg", "--from", "1", "--to", "2"},
           {"diagram", "--param", "contact.mu", "--from", "0.5", "--to", "0.3"},
           {"diagram", "--param", "numerics.rtol", "--from", "1e-8", "--to", "1e-7"},
           {"diagram", "--param", "soil.G", "--from", "10", "--to", "abc"}}) {
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 2) << args[2] << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  }
  const Outcome range = run({"diagram", "--param", "contact.mu", "--from", "0.5", "--to", "0.3"});
  EXPECT_NE(range.err.find("must be > its start (from, --from)"), std::string::npos) << range.err;
  // Standard output carries one thing (the table followed a --csv -), for diagram and continue.
  for (const std::string command : {"diagram", "continue"}) {
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"--json", "-"}, {"--format", "json"}}) {
      std::vector<std::string> args = {command, "--param", "MMd",   "--from", "0",
                                       "--to",  "100",     "--csv", "-"};
      args.insert(args.end(), extra.begin(), extra.end());
      const Outcome twice = run(args);
      EXPECT_EQ(twice.code, 2) << command << " " << extra[0] << ": " << twice.err;
      EXPECT_NE(twice.err.find("would both write to standard output"), std::string::npos)
          << twice.err;
    }
    std::vector<std::string> args = {command, "--param", "MMd",   "--from", "0",
                                     "--to",  "100",     "--csv", "-",      "-q"};
    if (command == "diagram") args.insert(args.end(), {"--steps", "1"});
    const Outcome csv = run(args);
    ASSERT_EQ(csv.code, 0) << command << ": " << csv.err;
    std::istringstream rows(csv.out);
    std::string header;
    std::getline(rows, header);
    for (std::string line; std::getline(rows, line);) {
      EXPECT_EQ(std::count(line.begin(), line.end(), ','),
                std::count(header.begin(), header.end(), ','))
          << command << ": " << line;
    }
  }
  // The values named, in the unit typed ("got 1e+08 and 3e+07" read as end 1e8, start 3e7).
  const Outcome g = run({"diagram", "--param", "soil.G", "--from", "100", "--to", "30", "--set",
                         "soil.input=modulus"});
  EXPECT_EQ(g.code, 2) << g.err;
  EXPECT_NE(g.err.find("got from = 100 MN/m^2 and to = 30 MN/m^2 (a diagram visits its range "
                       "upwards; sweep \"down\" (--sweep down) visits it downwards)"),
            std::string::npos)
      << g.err;
}

TEST(CliDiagram, InterruptExits130WithoutWritingFiles) {
  TempDir dir;
  const pid_t pid = start({"diagram", "--param", "MMd", "--from", "0", "--to", "2000", "--steps",
                           "1000", "--csv", dir / "d.csv"},
                          dir / "out", dir / "err");
  ASSERT_TRUE(wait_until_catching(pid, SIGINT));
  ::kill(pid, SIGINT);
  const Outcome o = finish(pid, dir / "out", dir / "err", 60);
  EXPECT_EQ(o.code, 130) << o.err;
  EXPECT_NE(o.err.find("interrupted"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "d.csv"));
}

}  // namespace
}  // namespace oscidrum::test
