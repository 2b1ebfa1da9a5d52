// End-to-end tests of `oscidrum continue`: the branch's files, the exit codes, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "process.hpp"

namespace oscidrum::test {
namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The driving torque up to the gross-slip limit: the CSV has a row per orbit with the parameter,
// the multipliers and every metric; the bifurcations file and the JSON name the two grazings;
// the branch ends in gross slip (exit 0: the end of the orbits, not a failure).
TEST(CliContinue, BranchToTheGrossSlipLimitWritesItsFiles) {
  TempDir dir;
  const Outcome o = run({"continue", "--param", "MMd", "--from", "0", "--to", "14000", "--csv",
                         dir / "b.csv", "--bifurcations", dir / "bif.csv", "--json", dir / "b.json",
                         "--format", "none", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::string csv = read(dir / "b.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  for (const char* column : {"branch[-],point[-],MMd[N m],arclength[-]", ",stable[-],",
                             ",mu1_re[-],", ",mu7_im[-],", ",area[m^2/s^4],", ",cmv[-],"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
  const std::string bif = read(dir / "bif.csv");
  EXPECT_EQ(bif.substr(0, bif.find('\n')),
            "branch[-],kind[-],MMd[N m],tolerance[N m],after_point[-],multiplier_re[-],"
            "multiplier_im[-],child_branch[-],description[-]");
  const nlohmann::json j = nlohmann::json::parse(read(dir / "b.json"));
  EXPECT_EQ(j["schema"], "oscidrum-branch/1");
  EXPECT_EQ(j["end"], "gross_slip");
  ASSERT_EQ(j["bifurcations"].size(), 2u);
  EXPECT_EQ(j["bifurcations"][0]["kind"], "grazing");
  EXPECT_EQ(j["points"].size(),
            static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n') - 1));
}

// --MMd-fraction (or a case file's MMd_fraction) holds at every point, as in a sweep: along
// roller.M0 the first point's area is run's at --from with the same flag (39.65 m^2/s^4 before,
// the MMd of the default M0 kept, against run's 30.40).
TEST(CliContinue, MMdFractionFollowsTheVariedM0) {
  TempDir dir;
  const Outcome o =
      run({"continue", "--param", "roller.M0", "--from", "40000", "--to", "60000", "--MMd-fraction",
           "0.05", "--json", dir / "b.json", "--format", "none", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(read(dir / "b.json"));
  const Outcome single =
      run({"run", "--M0", "40000", "--MMd-fraction", "0.05", "--format", "json"});
  ASSERT_EQ(single.code, 0) << single.err;
  const double area = nlohmann::json::parse(single.out)["metrics"]["area"].get<double>();
  const double first = j["points"][0]["metrics"]["area"].get<double>();
  EXPECT_NEAR(first, area, 1e-6 * area);
}

// A value of the varied key given on the command line was replaced by the branch's without a
// word; now it is named in a warning (continue and diagram), and the run goes on.
TEST(CliContinue, AFlagOfTheVariedKeyIsNamedAsWithoutEffect) {
  const Outcome o =
      run({"continue", "--set", "soil.input=modulus", "--set", "soil.G=30e6", "--param", "soil.G",
           "--from", "20", "--to", "21", "--format", "none", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("oscidrum: warning: --set soil.G=30e6 has no effect: --param soil.G "
                       "takes its values from --from to --to"),
            std::string::npos)
      << o.err;
  const Outcome d = run({"diagram",    "--set",     "soil.input=modulus",
                         "--mu",       "0.4",       "--param",
                         "contact.mu", "--from",    "0.4",
                         "--to",       "0.5",       "--steps",
                         "1",          "--discard", "20",
                         "--periods",  "20",        "--format",
                         "none",       "--quiet"});
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_NE(d.err.find("warning: --mu 0.4 has no effect: --param contact.mu"), std::string::npos)
      << d.err;
  // Without it, no warning.
  const Outcome quiet = run({"continue", "--set", "soil.input=modulus", "--param", "soil.G",
                             "--from", "20", "--to", "21", "--format", "none", "--quiet"});
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("warning"), std::string::npos) << quiet.err;
}

// --harmonics had no effect: the branch's files held the scalar metrics only. Each point now has
// the amplitudes A_1 ... A_H of x_M'' and z_M'' (H = --harmonics), as a sweep's rows do: the
// first point, at --from, the same as `run` gives there.
TEST(CliContinue, HarmonicsGiveEachPointsAmplitudes) {
  TempDir dir;
  const Outcome o =
      run({"continue", "--param", "MMd", "--from", "0", "--to", "2000", "--harmonics", "3", "--csv",
           dir / "b.csv", "--json", dir / "b.json", "--format", "none", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::string csv = read(dir / "b.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  for (const char* column : {",ddx_A1[m/s^2],", ",ddx_A3[m/s^2],", ",ddz_A1[m/s^2],"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
  EXPECT_EQ(header.find("ddx_A4"), std::string::npos);
  EXPECT_TRUE(header.ends_with(",ddz_A3[m/s^2]")) << header;
  const nlohmann::json j = nlohmann::json::parse(read(dir / "b.json"));
  const auto& first = j["points"][0]["metrics"];
  ASSERT_EQ(first["ddx_harmonics"].size(), 4u);  // n = 0 ... 3, as run --json
  ASSERT_EQ(first["ddz_harmonics"].size(), 4u);
  const Outcome single = run({"run", "--MMd", "0", "--json", dir / "r.json", "--quiet"});
  ASSERT_EQ(single.code, 0) << single.err;
  const nlohmann::json r = nlohmann::json::parse(read(dir / "r.json"));
  const double a1 = r["metrics"]["ddx_harmonics"][1]["amplitude"].get<double>();
  EXPECT_EQ(first["ddx_harmonics"][1]["n"], 1);
  const double b1 = first["ddx_harmonics"][1]["amplitude"].get<double>();
  EXPECT_NEAR(b1, a1, 1e-6 * a1);
  EXPECT_GT(a1, 1.0);
}

TEST(CliContinue, BadInputIsRefusedWithExitCode2) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"continue", "--param", "soil.gg", "--from", "1", "--to", "2"},
           {"continue", "--param", "contact.mu", "--from", "0.5", "--to", "x"},
           {"continue", "--param", "contact.mu", "--from", "0.5", "--to", "0.5"},
           {"continue", "--param", "numerics.rtol", "--from", "1e-8", "--to", "1e-7"},
           {"continue", "--param", "contact.mu", "--from", "0.5", "--to", "0.3", "--plot",
            "x.png"}}) {
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 2) << args[2] << ": " << o.err;
    EXPECT_NE(o.err.find("error"), std::string::npos) << o.err;
  }
  // A malformed range value names its flag and the unit it is typed in.
  const Outcome to = run({"continue", "--param", "soil.G", "--from", "10", "--to", "abc"});
  EXPECT_EQ(to.code, 2);
  EXPECT_NE(to.err.find("--to: must be a decimal number [MN/m^2]; got 'abc'"), std::string::npos)
      << to.err;
  // soil.G along a branch on the default soil (Table 2 holds 14 values of G): said before any
  // integration, not as a failed start (exit 1, "no tangent at the start").
  const Outcome table2 = run({"continue", "--param", "soil.G", "--from", "20", "--to", "30"});
  EXPECT_EQ(table2.code, 2) << table2.err;
  EXPECT_NE(table2.err.find("set soil.input = \"modulus\""), std::string::npos) << table2.err;
  // Output names given empty (exit 0, nothing written, before) and an HDF5 file named '-'.
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"continue", "--param", "MMd", "--from", "0", "--to", "100", "--csv", ""},
           {"continue", "--param", "MMd", "--from", "0", "--to", "100", "--json", ""},
           {"continue", "--param", "MMd", "--from", "0", "--to", "100", "--bifurcations", ""},
           {"continue", "--param", "MMd", "--from", "0", "--to", "100", "--hdf5", ""},
           {"continue", "--param", "MMd", "--from", "0", "--to", "100", "--hdf5", "-"},
           {"diagram", "--param", "MMd", "--from", "0", "--to", "100", "--csv", ""},
           {"diagram", "--param", "MMd", "--from", "0", "--to", "100", "--plot", ""}}) {
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 2) << args[0] << " " << args[7] << ": " << o.err;
    EXPECT_TRUE(o.err.find("needs a file name") != std::string::npos ||
                o.err.find("writes a file, not standard output") != std::string::npos)
        << o.err;
  }
  // G typed in MN/m^2 below its range: said in MN/m^2 (it was said in Pa, with a hint to type
  // 5000 MN/m^2).
  const Outcome low = run({"continue", "--param", "soil.G", "--from", "30", "--to", "0.005",
                           "--set", "soil.input=modulus"});
  EXPECT_EQ(low.code, 2) << low.err;
  EXPECT_NE(low.err.find("--to: soil.G must be in [0.01, 100000] [MN/m^2] here; got 0.005"),
            std::string::npos)
      << low.err;
  // MMd_fraction with MMd varied: one of them.
  const Outcome both =
      run({"continue", "--param", "MMd", "--from", "0", "--to", "100", "--MMd-fraction", "0.05"});
  EXPECT_EQ(both.code, 2) << both.err;
  EXPECT_NE(both.err.find("MMd is the varied parameter"), std::string::npos) << both.err;
  // G typed in Pa where the flag takes MN/m^2: said with what was meant.
  const Outcome pa = run({"continue", "--param", "soil.G", "--from", "20e6", "--to", "30", "--set",
                          "soil.input=modulus"});
  EXPECT_EQ(pa.code, 2);
  EXPECT_NE(pa.err.find("did you mean --from 20?"), std::string::npos) << pa.err;
  // A range whose end no case can have (the drum larger than the trough) is refused before the
  // branch crawls towards it (705 points, then exit 1, "the corrector did not converge").
  const Outcome r = run({"continue", "--param", "roller.r", "--from", "0.55", "--to", "0.7"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("continue: to (--to) 0.7 m: the case is not valid there: trough.a must be "
                       "> roller.r"),
            std::string::npos)
      << r.err;
  // --plot-metric is checked before the branch is followed (it ran the whole branch, then failed
  // with exit 1, or drew a text column), and is refused without --plot.
  TempDir dir;
  for (const auto& [metric, plot, message] :
       std::vector<std::tuple<std::string, bool, std::string>>{
           {"nosuch", true, "--plot-metric nosuch: not a numeric column of the branch CSV"},
           {"sequence", true, "--plot-metric sequence: not a numeric column"},
           {"area", false, "--plot-metric area needs --plot FILE"},
           // the amplitude columns of the spectra (they were refused though the CSV holds them)
           {"ddz_A11", true,
            "--plot-metric ddz_A11: the branch CSV holds the amplitudes ddz_A1 ... ddz_A10"}}) {
    std::vector<std::string> args = {"continue", "--param", "MMd",           "--from", "0",
                                     "--to",     "1000",    "--plot-metric", metric};
    if (plot) args.insert(args.end(), {"--csv", dir / "b.csv", "--plot", dir / "b.png"});
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 2) << metric << ": " << o.err;
    EXPECT_NE(o.err.find(message), std::string::npos) << o.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "b.csv"));
  }
  // ... and ddx_A2 is one: the check lets it through, the branch is followed and written (and
  // drawn where the Python package is there).
  const Outcome a =
      run({"continue", "--param", "MMd", "--from", "0", "--to", "300", "--plot-metric", "ddx_A2",
           "--csv", dir / "a.csv", "--plot", dir / "a.png", "-q"});
  EXPECT_EQ(a.err.find("--plot-metric"), std::string::npos) << a.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "a.csv")) << a.err;
  // Drawn: -q says nothing (the figure's name was printed on stderr).
  if (std::filesystem::exists(dir / "a.png")) {
    EXPECT_EQ(a.err, "");
  }
}

}  // namespace
}  // namespace oscidrum::test
