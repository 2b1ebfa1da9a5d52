// End-to-end tests of `oscidrum run`, `soil`, `transmissibility`, `fields` and of bad input:
// every malformed config or flag gives exit code 2 and one clear line, never a crash.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "oscidrum/fields.hpp"
#include "process.hpp"

namespace oscidrum::test {
namespace {

const std::string kSource = OSCIDRUM_SOURCE_DIR;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    out.push_back(text.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

// Exit code 2, nothing on stdout, exactly one line on stderr: "oscidrum: error: ...".
void expect_usage_error(const Outcome& o, const std::string& must_contain) {
  EXPECT_EQ(o.signal, 0) << "crashed: " << o.err;
  EXPECT_EQ(o.code, 2) << o.err;
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(o.err.rfind("oscidrum: error: ", 0), 0u) << o.err;
  EXPECT_EQ(lines(o.err).size(), 1u) << o.err;
  EXPECT_NE(o.err.find(must_contain), std::string::npos)
      << "expected '" << must_contain << "' in: " << o.err;
}

// The corpus: one malformed file per problem, its first line "# expect: <part of the message>".
void check_corpus(const std::string& command, const std::string& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 10u);
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    const std::string first = lines(slurp(file.string())).at(0);
    ASSERT_EQ(first.rfind("# expect: ", 0), 0u) << "corpus file without '# expect: '";
    const Outcome o = run({command, file.string()});
    expect_usage_error(o, first.substr(10));
    EXPECT_NE(o.err.find(file.string()), std::string::npos) << "the message names the file";
  }
}

TEST(CliCorpus, MalformedCaseFiles) { check_corpus("run", kSource + "/tests/cli/corpus/run"); }

TEST(CliCorpus, MalformedStudyFiles) { check_corpus("sweep", kSource + "/tests/cli/corpus/sweep"); }

TEST(CliCorpus, UnreadableAndGarbageFiles) {
  TempDir dir;
  std::ofstream(dir / "empty.toml").close();
  expect_usage_error(run({"run", dir / "empty.toml"}), "empty.toml: the file holds no settings");
  expect_usage_error(run({"sweep", dir / "empty.toml"}), "the file holds no settings");
  std::mt19937 rng(20190101);  // seeded: the same garbage every run
  for (int i = 0; i < 20; ++i) {
    std::string bytes(64 + 97 * i, '\0');
    for (char& ch : bytes) ch = static_cast<char>(rng() & 0xff);
    const std::string path = dir / ("garbage" + std::to_string(i) + ".toml");
    std::ofstream(path, std::ios::binary) << bytes;
    SCOPED_TRACE(path);
    expect_usage_error(run({"run", path}), path);
    expect_usage_error(run({"sweep", path}), path);
  }
  std::ofstream(dir / "utf8.toml", std::ios::binary) << "[roller]\nr = \"\xc3\x28\"\n";
  expect_usage_error(run({"run", dir / "utf8.toml"}), "invalid TOML");
  expect_usage_error(run({"run", dir / "missing.toml"}),
                     "cannot read " + (dir / "missing.toml") + ": No such file or directory");
  expect_usage_error(run({"sweep", dir / "missing.toml"}), "cannot read");
  expect_usage_error(run({"run", dir.path()}), "it is a directory");
  {
    std::ofstream big(dir / "big.toml");
    big << "# " << std::string(17u << 20, 'x') << "\n";
  }
  expect_usage_error(run({"run", dir / "big.toml"}), "larger than 16 MiB");
}

TEST(CliErrors, BadFlagsAndValues) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{}, "a command is required"},
      {{"frobnicate"}, "frobnicate"},
      {{"run", "--bogus"}, "--bogus"},
      {{"run", "--G"}, "--G"},
      {{"run", "--G", "abc"}, "abc"},
      {{"run", "--G", "0"}, "--G must be in [0.01, 100000] [MN/m^2]; got 0"},
      {{"run", "--G", "nan"}, "--G: must be a decimal number; got 'nan'"},
      {{"run", "--G", "25", "--nu", "0.35"}, "add --soil-formula"},
      {{"run", "--G", "25", "--ksh", "1e7"}, "give the soil either by --G or by --ksh"},
      {{"run", "--mu", "-1"}, "--mu -1: contact.mu must be >= 0; got -1"},
      {{"run", "--mu", "0.3", "--pure-rolling"}, "either --mu or --pure-rolling"},
      {{"run", "--MMd", "1", "--MMd-fraction", "0.1"}, "either by --MMd"},
      {{"run", "--R", "0.5"}, "trough.a must be > roller.r"},
      {{"run", "--R", "0.7", "--k", "0.1"}, "either as a circle (--R) or as a log spiral"},
      {{"run", "--m", "-3"}, "roller.m must be > 0 [kg]; got -3"},
      {{"run", "--f", "inf"}, "--f: must be a decimal number; got 'inf'"},
      {{"run", "--set", "x"}, "--set expects KEY=VALUE"},
      {{"run", "--set", "soil.g=5"}, "did you mean 'soil.G'?"},
      {{"run", "--set", "numerics.max_periods=1.5"}, "must be an integer"},
      {{"run", "--set", "soil.input=coefficients", "--set", "soil.G=30e6"}, "soil.G has no effect"},
      {{"run", "--set", "soil.G=27e6"}, "soil.G must be a G of paper Table 2"},
      {{"run", "--set", "soil.nu=0.35"}, "soil.nu has no effect while soil.input = \"table2\""},
      // Issue 25, point 8: --G is MN/m^2; a value plainly in Pa is refused with what was meant.
      {{"run", "--G", "30000000"},
       "--G is the shear modulus in MN/m^2 (soils: about 1 to 500), not in Pa; got 30000000 "
       "MN/m^2 = 3e+13 Pa: did you mean --G 30?"},
      {{"run", "--G", "1e-9"}, "--G must be in [0.01, 100000] [MN/m^2]"},
      {{"soil", "--G", "25e6"}, "did you mean --G 25?"},
      {{"run", "--set", "soil.G=30"}, "did you mean 3e+07, i.e. 30 MN/m^2?"},
      {{"run", "--format", "xml"}, "xml"},
      {{"run", "--harmonics", "600"},
       "--harmonics (default 10) must be below numerics.samples_per_period / 2"},
      {{"run", "a.toml", "b.toml"}, "b.toml"},
      {{"run", "--csv", "/nonexistent/dir/x.csv"}, "the directory /nonexistent/dir does not exist"},
      // A directory that takes no new file although its permissions say otherwise (to root):
      // said before the run, not blamed on the Python package after it.
      {{"run", "--csv", "/proc/x.csv"}, "cannot write"},
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--out", "/tmp/oscidrum_never.csv",
        "--plot", "/proc/x.png"},
       "cannot write"},
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--out", "/tmp/oscidrum_never.csv",
        "--plot", "/tmp"},
       "--plot /tmp is a directory; give the figure's file name (e.g. /tmp/figure.png)"},
      {{"sweep"}, "study"},
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--resume"}, "need --out FILE"},
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--threads", "-1"}, "-1"},
      // A value for a swept key would be replaced in every case (it was, without a word).
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--set", "soil.table2_G=5e6"},
       "--set soil.table2_G=5e6: soil.table2_G is swept by the study"},
      {{"soil", "--G", "-5"}, "--G must be in [0.01, 100000] [MN/m^2]; got -5"},
      {{"soil", "--nu", "0.7"}, "soil.nu must be in [0, 0.5); got 0.7"},
      {{"soil", "--table2", "--G", "30"}, "--G excludes --table2"},
      {{"soil", "--b", "1e300"}, "ksh (Appendix B) is not a finite number"},
      {{"transmissibility", "--mf", "0"}, "m_f must be > 0"},
      {{"fields", "--format", "yaml"}, "yaml"},
  };
  for (const auto& [args, message] : cases) {
    std::string joined;
    for (const std::string& a : args) joined += a + " ";
    SCOPED_TRACE(joined);
    expect_usage_error(run(args), message);
  }
}

TEST(CliRun, DefaultCaseReachesSteadyState) {
  const Outcome o = run({"run"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("steady_state"), std::string::npos);
  EXPECT_NE(o.out.find("paper Table 2 at G = 25 MN/m^2"), std::string::npos);
  EXPECT_NE(o.out.find("m^2/s^4"), std::string::npos);
  EXPECT_EQ(o.err, "");  // no progress line: stderr is not a terminal
  // MMd = 0: the even harmonics of x_M'' and the odd ones of z_M'' vanish by symmetry; rounding
  // leaves ~1e-9 of the largest, which the summary prints as 0 and says so.
  ASSERT_NE(o.out.find("x_M'' harmonics A(f) ... A(5f)"), std::string::npos) << o.out;
  ASSERT_NE(o.out.find("z_M'' harmonics A(f) ... A(5f)"), std::string::npos) << o.out;
  const std::string x = o.out.substr(o.out.find("x_M'' harmonics A(f) ... A(5f)"));
  const std::string x_line = x.substr(0, x.find('\n'));
  EXPECT_NE(x_line.find(", 0, "), std::string::npos) << x_line;
  EXPECT_EQ(x_line.find("e-"), std::string::npos) << x_line;
  const std::string z = o.out.substr(o.out.find("z_M'' harmonics A(f) ... A(5f)"));
  const std::string z_line = z.substr(0, z.find('\n'));
  EXPECT_NE(z_line.find("  0, "), std::string::npos) << z_line;  // A(f) of z_M'': 0
  EXPECT_NE(o.out.find("(0: below 1e-6 of the signal's largest harmonic"), std::string::npos);
  // Codes of the CSV and JSON in words: a single run starts from rest.
  EXPECT_NE(o.out.find("warm start (continuation)       no: started from rest"), std::string::npos)
      << o.out;
  // With fewer harmonics kept (--harmonics 0 or 2) the ratios read the same in words: no NaN and
  // no ratio of round-off (5.6e-11 for A(2f)/A(f) of x_M'' was printed).
  for (const char* n : {"0", "2"}) {
    const Outcome few = run({"run", "--harmonics", n});
    ASSERT_EQ(few.code, 0) << few.err;
    for (const char* line :
         {"x_M'' A(2f)/A(f)", "z_M'' A(2f)/A(f)", "z_M'' A(3f)/A(f)", "CMV-type value"}) {
      const std::string rest = few.out.substr(few.out.find(line) + std::string(line).size());
      const std::string text = rest.substr(rest.find_first_not_of(' '));
      EXPECT_TRUE(text.rfind("0 (", 0) == 0 || text.rfind("n/a (", 0) == 0)
          << n << ": " << line << text.substr(0, text.find('\n'));
    }
  }
}

// f changed with M0 fixed is rarely meant (M0 = 4 m_u e_u e_w nu^2 (5)): a warning on stderr. The
// roller given by its unbalance (or M0 given explicitly) says what is meant: no warning.
// The summary's contact line names the law the numbers come from: a regularised law, a static
// coefficient and a contact that can open all read "Coulomb friction, mu = 0.5".
TEST(CliRun, TheSummaryNamesTheContactLaw) {
  Outcome o = run({"run", "-q", "--set", "contact.law=regularised", "--set", "contact.v_eps=0.05"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("regularised friction, mu tanh(v_rel / v_eps), mu = 0.5, v_eps = 0.05"),
            std::string::npos)
      << o.out;
  o = run({"run", "-q", "--set", "contact.mu_static=0.8", "--set", "contact.unilateral=true"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("Coulomb friction, mu = 0.5, static mu_static = 0.8; unilateral"),
            std::string::npos)
      << o.out;
  o = run({"run", "-q", "--MMd-fraction", "0.05", "--harmonics", "1"});
  EXPECT_NE(o.out.find("harmonics A(f) "), std::string::npos) << o.out;
  EXPECT_EQ(o.out.find("A(1f)"), std::string::npos) << o.out;
}

TEST(CliRun, FrequencyWithFixedM0Warns) {
  Outcome o = run({"run", "--f", "30", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("warning: "), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("roller.f = 30 Hz with M0 fixed at 54947 N m"), std::string::npos) << o.err;
  EXPECT_EQ(nlohmann::json::parse(o.out)["derived"]["M0"], 54947.0);
  o = run({"run", "--f", "30", "--unbalance", "0.22877", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err, "");
  const double nu = 2.0 * M_PI * 30.0;
  EXPECT_NEAR(nlohmann::json::parse(o.out)["derived"]["M0"].get<double>(), 4.0 * 0.22877 * nu * nu,
              1e-6);
  o = run({"run", "--f", "30", "--M0", "40000", "--format", "json"});
  EXPECT_EQ(o.err, "");
  o = run({"run", "--M0", "40000", "--unbalance", "0.2"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("cannot be given together with roller.M0"), std::string::npos) << o.err;
  // A friction coefficient from a case file under --pure-rolling changes nothing: said.
  o = run({"run", kSource + "/examples/case.toml", "--pure-rolling", "-q", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("contact.mu has no effect while contact.pure_rolling = true"),
            std::string::npos)
      << o.err;
  // ... and so does a friction law (it was silent).
  o = run({"run", "--pure-rolling", "--set", "contact.law=regularised", "-q", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("contact.law has no effect while contact.pure_rolling = true"),
            std::string::npos)
      << o.err;
}

// The column names of docs/csv-columns.md, in order.
std::string documented_header() {
  std::string header;
  for (const std::string& line : lines(slurp(kSource + "/docs/csv-columns.md")))
    if (line.rfind("| `", 0) == 0) {
      const std::size_t end = line.find('`', 3);
      if (!header.empty()) header += ',';
      header += line.substr(3, end - 3);
    }
  return header;
}

// A run that ended before its sampling (gross slip) has phase_times null, as documented (it was
// an object of four nulls).
TEST(CliRun, ARunWithoutSamplesHasNoPhaseTimes) {
  const Outcome o = run({"run", "--MMd", "20000", "--format", "json", "-q"});
  ASSERT_EQ(o.code, 1) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["status"], "gross_slip");
  EXPECT_TRUE(j["phase_times"].is_null()) << j["phase_times"];
  // The summary's diagnostics that do not apply say so in words (they printed "nan").
  const Outcome text = run({"run", "--MMd", "20000"});
  ASSERT_EQ(text.code, 1) << text.err;
  EXPECT_NE(text.out.find("switches per period"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("n/a (no sampled window)"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("nan"), std::string::npos) << text.out;
  // --plot has nothing to draw, and says so (the plotting module failed on the empty CSV and the
  // message asked whether the Python package was installed).
  TempDir dir;
  const Outcome plot = run({"run", "--MMd", "20000", "--plot", dir / "p", "-q"});
  EXPECT_EQ(plot.code, 1) << plot.err;
  EXPECT_NE(plot.err.find("no plots: the run ended (gross_slip) before any sampled period"),
            std::string::npos)
      << plot.err;
  EXPECT_EQ(plot.err.find("installed"), std::string::npos) << plot.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "p/summary.json"));
}

TEST(CliRun, FilesFollowTheContracts) {
  TempDir dir;
  const Outcome o = run({"run", kSource + "/examples/case.toml", "--csv", dir / "s.csv", "--json",
                         dir / "s.json", "--events", dir / "e.csv", "-q"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> csv = lines(slurp(dir / "s.csv"));
  ASSERT_GT(csv.size(), 1u);
  EXPECT_EQ(csv[0], documented_header());
  EXPECT_EQ(csv.size(), 1u + 2u * 1024u);  // two steady periods (multiplicity 1) x 1024

  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "s.json"));
  EXPECT_EQ(j["schema"], "oscidrum-case/1");
  EXPECT_EQ(j["status"], "steady_state");
  EXPECT_TRUE(j["ok"].get<bool>());
  for (const Field& f : fields()) EXPECT_TRUE(j["parameters"].contains(f.key)) << f.key;
  // A key the case does not read is named (soil.ksh under Table 2 read 41.4e6 at every G as if
  // used); the coefficients used are under "soil".
  const auto& unused = j["unused_parameters"];
  for (const char* key : {"soil.ksh", "soil.nu", "roller.static_moment"})
    EXPECT_NE(std::find(unused.begin(), unused.end(), key), unused.end()) << key;
  EXPECT_EQ(std::find(unused.begin(), unused.end(), "soil.G"), unused.end());
  EXPECT_DOUBLE_EQ(j["parameters"]["MMd"].get<double>(), 0.05 * 54947.0);
  EXPECT_EQ(j["soil"]["source"], "table2");
  EXPECT_DOUBLE_EQ(j["soil"]["ksh"].get<double>(), 41.4e6);
  EXPECT_EQ(j["origins"]["soil.table2_G"], kSource + "/examples/case.toml:14:1");
  EXPECT_EQ(j["metrics"]["ddx_harmonics"].size(), 11u);
  EXPECT_GT(j["metrics"]["ddx_max"].get<double>(), 0.0);
  for (const char* key : {"diagnostics", "sampling", "phase_times", "derived"})
    EXPECT_TRUE(j.contains(key)) << key;

  const std::vector<std::string> events = lines(slurp(dir / "e.csv"));
  EXPECT_EQ(events.at(0), "t[s],kind,from,to");
  // The events of the sampled window: two steady periods of four switches each.
  EXPECT_EQ(events.size(), 1u + 2u * 4u);

  // stdout formats equal the files.
  EXPECT_EQ(run({"run", kSource + "/examples/case.toml", "--format", "csv"}).out,
            slurp(dir / "s.csv"));
  EXPECT_EQ(run({"run", kSource + "/examples/case.toml", "--format", "json"}).out,
            slurp(dir / "s.json"));
}

// The vibratory drum's example (docs/model.md section 14): it runs to a steady state with lift-off,
// says which roller it is, reports its force and no oscillation moment, and refuses the
// oscillation drum's keys.
TEST(CliRun, VibratoryExampleRunsAndRefusesTheOscillationKeys) {
  const std::string file = kSource + "/examples/vibratory.toml";
  Outcome o = run({"run", file});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("vibratory drum on soil"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("unbalance force F0 = m_u e_u nu^2 = 31977"), std::string::npos) << o.out;
  EXPECT_EQ(o.err, "");  // no warning about M0 and f: the vibratory drum has no M0
  o = run({"run", file, "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["status"], "steady_state");
  EXPECT_EQ(j["derived"]["M0"].get<double>(), 0.0);
  EXPECT_NEAR(j["derived"]["F0"].get<double>(), 0.9 * std::pow(2.0 * M_PI * 30.0, 2), 1e-6);
  EXPECT_GT(j["metrics"]["flight_fraction"].get<double>(), 0.0);
  o = run({"run", file, "--set", "roller.M0=50000"});
  EXPECT_NE(o.code, 0);
  EXPECT_NE(o.err.find("roller.M0 has no effect while roller.type = \"vibratory\""),
            std::string::npos)
      << o.err;
  o = run({"run", "--set", "roller.type=vibratory"});
  EXPECT_NE(o.code, 0);
  EXPECT_NE(o.err.find("roller.static_moment must be > 0"), std::string::npos) << o.err;
}

TEST(CliRun, ChoiceFlagsTakeTheChoicesNames) {
  // --type and --exciter were generated as number flags and refused every name their help
  // offered ("--type: must be a decimal number; got 'vibratory'").
  Outcome o = run({"run", "--help"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("--type {oscillation,vibratory}"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("--exciter {circular,circular_reversed,vertical}"), std::string::npos);
  o = run({"run", "--type", "vibratory", "--static_moment", "0.9", "--f", "30", "--G", "40",
           "--exciter", "vertical", "--unilateral", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["parameters"]["roller.type"], "vibratory") << o.out;
  EXPECT_EQ(j["origins"]["roller.type"], "--type vibratory") << o.out;
  EXPECT_EQ(j["parameters"]["roller.exciter"], "vertical") << o.out;
  o = run({"run", "--type", "vibrating"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--type vibrating: roller.type must be one of oscillation, vibratory"),
            std::string::npos)
      << o.err;
}

// The example's vibratory drum with a directed vertical exciter: a steady state (it ended as
// max_periods_reached, a drum slipping on with N < 0 after a symmetric lift-off), whose x_M'' is
// --harmonics 0 or 1: z_M'' of the default case (MMd = 0: even harmonics only, 0.97 m/s^2) was
// said to be round-off ("z_M'' is absent"), its area too, from the harmonics computed alone.
TEST(CliRun, FewHarmonicsDoNotMakeASignalAbsent) {
  for (const char* n : {"0", "1"}) {
    const Outcome o = run({"run", "--harmonics", n, "-q"});
    ASSERT_EQ(o.code, 0) << o.err;
    EXPECT_NE(o.out.find("z_M'' max"), std::string::npos) << o.out;
    EXPECT_EQ(o.out.find("is absent)"), std::string::npos) << n << "\n" << o.out;
  }
}

// round-off: the metrics that would be ratios or phases of round-off say so in words, not as
// numbers (the summary printed A2/A1 0.23, THD 2.6e5, a lag of -1.96 pi), and JSON has null.
TEST(CliRun, AVerticalExcitersMetricsOfRoundOffSayWhy) {
  Outcome o =
      run({"run", kSource + "/examples/vibratory.toml", "--set", "roller.exciter=vertical"});
  ASSERT_EQ(o.code, 0) << o.err << o.out;
  EXPECT_NE(o.out.find("steady_state"), std::string::npos) << o.out;
  for (const char* label : {"lag psi_xz", "x_M'' A(2f)/A(f)", "x_M'' A(3f)/A(f)", "x_M'' THD"}) {
    const std::size_t at = o.out.find(std::string(label) + " ");
    ASSERT_NE(at, std::string::npos) << label << "\n" << o.out;
    const std::string line = o.out.substr(at, o.out.find('\n', at) - at);
    EXPECT_NE(line.find("is absent: below 1e-6 of the largest component"), std::string::npos)
        << line;
  }
  EXPECT_NE(o.out.find("n/a (no oscillating torque: M0 = 0, or the vibratory drum)"),
            std::string::npos);
  // The numbers of round-off (1e-22 m/s^2) are printed, and said to be round-off; z_M'' is not.
  const auto line_of = [&](const std::string& label) {
    const std::size_t at = o.out.find("\n  " + label + " ");
    return at == std::string::npos ? std::string()
                                   : o.out.substr(at + 1, o.out.find('\n', at + 1) - at - 1);
  };
  for (const char* label : {"x_M'' max", "x_M'' min", "x_M'' harmonics", "area z_M''(x_M'')"})
    EXPECT_NE(line_of(label).find("(round-off: x_M'' is absent)"), std::string::npos)
        << label << "\n"
        << o.out;
  for (const char* label : {"z_M'' max", "z_M'' harmonics"}) {
    ASSERT_FALSE(line_of(label).empty()) << label;
    EXPECT_EQ(line_of(label).find("round-off"), std::string::npos) << line_of(label);
  }
  o = run({"run", kSource + "/examples/vibratory.toml", "--set", "roller.exciter=vertical",
           "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  for (const char* key : {"psi_xz", "ddx_A2_A1", "ddx_A3_A1", "ddx_thd", "phi_lag"})
    EXPECT_TRUE(j["metrics"][key].is_null()) << key << ": " << j["metrics"][key];
  EXPECT_GT(j["metrics"]["ddz_A2_A1"].get<double>(), 0.0);
}

// A steady state that repeats every 11 excitation periods (the vertical exciter at 2.5 kg m,
// 40 Hz: the drum rocks in its trough) is beyond the search's default max_multiplicity of 8: the
// run ends as max_periods_reached, and its message names the setting that finds it; with it, the
// run is steady.
TEST(CliRun, ASteadyStateBeyondMaxMultiplicityNamesTheSetting) {
  const std::vector<std::string> rocking = {"run",   kSource + "/examples/vibratory.toml",
                                            "--set", "roller.exciter=vertical",
                                            "--set", "roller.static_moment=2.5",
                                            "--f",   "40",
                                            "--mu",  "0.6",
                                            "--set", "numerics.max_periods=1500"};
  Outcome o = run(rocking);
  EXPECT_EQ(o.code, 1) << o.err;
  EXPECT_NE(o.out.find("max_periods_reached"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("it repeats every 11 excitation periods, beyond "
                       "numerics.max_multiplicity = 8: set it to 11"),
            std::string::npos)
      << o.out;
  std::vector<std::string> set = rocking;
  set.insert(set.end(), {"--set", "numerics.max_multiplicity=11"});
  o = run(set);
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("repeating every 11 excitation periods"), std::string::npos) << o.out;
  // Its frequencies are k f / 11: no f/2, for that reason, not because it repeats every period.
  EXPECT_NE(o.out.find("0 (no f/2 component: the steady state repeats every 11 periods, an odd "
                       "number)"),
            std::string::npos)
      << o.out;
}

TEST(CliRun, FlagsOverrideTheFileAndPrintConfigRoundTrips) {
  TempDir dir;
  Outcome o = run({"run", kSource + "/examples/case.toml", "--G", "40", "--pure-rolling", "--MMd",
                   "0", "--print-config"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("input = \"table2\""), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("\nG = 40000000.0"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("pure_rolling = true"), std::string::npos);
  std::ofstream(dir / "resolved.toml") << o.out;
  const Outcome a = run({"run", dir / "resolved.toml", "--format", "json"});
  const Outcome b = run({"run", kSource + "/examples/case.toml", "--G", "40", "--pure-rolling",
                         "--MMd", "0", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_EQ(nlohmann::json::parse(a.out)["metrics"], nlohmann::json::parse(b.out)["metrics"]);
  EXPECT_EQ(nlohmann::json::parse(a.out)["parameters"], nlohmann::json::parse(b.out)["parameters"]);

  o = run({"run", "--G", "27", "-q"});
  EXPECT_NE(o.out.find("Appendix B (42)-(45) from G = 27 MN/m^2"), std::string::npos);
  o = run({"run", "--G", "25", "--soil-formula", "--format", "json"});
  EXPECT_EQ(nlohmann::json::parse(o.out)["soil"]["source"], "appendix_b");
  o = run({"run", "--set", "soil.table2_G=10e6", "--format", "json"});
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(o.out)["soil"]["ksh"].get<double>(), 19.7e6);
  // --set after a flag (or an earlier --set) of the same key: the later holds, said; a flag
  // over the file's value is what flags are for, not said.
  o = run({"run", "--mu", "0.3", "--set", "contact.mu=0.4", "--set", "contact.mu=0.45",
           "--print-config"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("mu = 0.45"), std::string::npos) << o.out;
  EXPECT_NE(o.err.find("warning: --set contact.mu=0.4 overrides --mu 0.3"), std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("--set contact.mu=0.45 overrides --set contact.mu=0.4"), std::string::npos)
      << o.err;
  o = run({"run", kSource + "/examples/case.toml", "--mu", "0.3", "--print-config"});
  EXPECT_EQ(o.err.find("overrides"), std::string::npos) << o.err;
  // A --set of the value a flag implied overrides nothing (--G 80, not a G of Table 2, is the
  // modulus input: "--set soil.input=modulus overrides --G 80" read as if G were dropped).
  o = run({"run", "--G", "80", "--set", "soil.input=modulus", "--print-config"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(o.err.find("overrides"), std::string::npos) << o.err;
  EXPECT_NE(o.out.find("G = 80000000.0"), std::string::npos) << o.out;
}

TEST(CliRun, ExitCodeOneWhenNotSteady) {
  // The transient method's budget (shooting would find the orbit within it).
  const Outcome o =
      run({"run", "--set", "numerics.method=transient", "--set", "numerics.max_periods=3"});
  EXPECT_EQ(o.code, 1) << o.err;
  EXPECT_NE(o.out.find("max_periods_reached"), std::string::npos);
  EXPECT_NE(o.err.find("status max_periods_reached"), std::string::npos);
  // No number that looks like a steady state's: the "none" codes in words.
  EXPECT_NE(o.out.find("never (no steady state)"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("none (no steady state)"), std::string::npos) << o.out;
}

TEST(CliRun, InterruptExits130) {
  TempDir dir;
  // A long run: 1000 sampled periods of 10^4 samples (an impossible steady_tol no longer
  // runs forever: the run accepts the steady state at the integration's noise floor).
  const pid_t pid = start(
      {"run", "--set", "numerics.output_periods=1000", "--set", "numerics.samples_per_period=10000",
       "--set", "numerics.max_multiplicity=1", "--csv", dir / "s.csv"},
      dir / "out", dir / "err");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, SIGINT);
  const Outcome o = finish(pid, dir / "out", dir / "err");
  EXPECT_EQ(o.code, 130) << o.err;
  EXPECT_NE(o.err.find("interrupted"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "s.csv"));
}

TEST(CliRun, PlotFailsCleanly) {
  TempDir dir;
  const Outcome o = run({"run", "-q", "--plot", dir / "plots"});
  EXPECT_EQ(o.signal, 0);
  if (o.code != 0) {  // no Python package or no matplotlib here: a message and exit code 1
    EXPECT_EQ(o.code, 1) << o.err;
    EXPECT_NE(o.err.find("plot"), std::string::npos);
  } else {
    EXPECT_EQ(o.err, "");  // -q: not the names of the figures
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "plots/steady_state.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "plots/summary.json"));
}

// A plotting module that does not stop within the grace period after Ctrl-C (a figure being drawn
// on a loaded machine) is killed by the watcher, whose "oscidrum: interrupted" lost the line that
// says where the data are; it keeps it now. The module here ignores SIGINT and sleeps.
TEST(CliRun, APlotSlowToStopStillSaysWhereTheDataAre) {
  TempDir dir;
  const std::string python = dir / "slow-python";
  {
    std::ofstream script(python);
    script << "#!/bin/sh\ntrap '' INT TERM\n: > \"$(dirname \"$0\")/started\"\nsleep 20\n";
  }
  ::chmod(python.c_str(), 0755);
  ::setenv("OSCIDRUM_PYTHON", python.c_str(), 1);
  const pid_t pid = start({"run", "-q", "--plot", dir / "plots"}, dir / "out", dir / "err");
  ::unsetenv("OSCIDRUM_PYTHON");
  for (int i = 0; i < 2000 && !std::filesystem::exists(dir / "started"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(std::filesystem::exists(dir / "started"));
  ::kill(pid, SIGINT);
  const auto begin = std::chrono::steady_clock::now();
  const Outcome o = finish(pid, dir / "out", dir / "err");
  EXPECT_LT(std::chrono::steady_clock::now() - begin, std::chrono::seconds(5));
  EXPECT_EQ(o.code, 130) << o.err;
  EXPECT_NE(o.err.find("oscidrum: interrupted while plotting; the data are in " + (dir / "plots") +
                       "/steady_state.csv"),
            std::string::npos)
      << o.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "plots/steady_state.csv"));
}

// Results written to a standard output that cannot take them are lost: exit code 2, not 0.
TEST(CliRun, AStandardOutputThatCannotBeWrittenIsAnError) {
  TempDir dir;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "-q"}, {"run", "-q", "--format", "csv"}, {"fields"}}) {
    const pid_t pid = start(args, "/dev/full", dir / "err");
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << args.back();
    EXPECT_NE(slurp(dir / "err").find("writing to standard output failed"), std::string::npos)
        << slurp(dir / "err");
  }
}

// Standard output carries one thing: --csv - replaces the summary table; two claims are refused.
TEST(CliRun, StandardOutputCarriesOneThing) {
  Outcome o = run({"run", "-q", "--csv", "-"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> l = lines(o.out);
  ASSERT_GT(l.size(), 2u);
  EXPECT_EQ(l.front().rfind("t[s],", 0), 0u);
  EXPECT_EQ(std::count(o.out.begin(), o.out.end(), '\n'), 1 + 2 * 1024);  // header + samples
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "--csv", "-", "--format", "csv"},
        {"run", "--csv", "-", "--json", "-"},
        {"run", "--events", "-", "--format", "table"}}) {
    o = run(args);
    EXPECT_EQ(o.code, 2) << args[1] << " " << args[3];
    EXPECT_NE(o.err.find("would both write to standard output"), std::string::npos) << o.err;
  }
}

TEST(CliSoil, CalculatorAndTable2) {
  Outcome o = run({"soil", "--G", "25"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("does not follow equation (42)"), std::string::npos);
  o = run({"soil", "--table2", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<std::string> rows = lines(o.out);
  ASSERT_EQ(rows.size(), 15u);
  EXPECT_EQ(rows[0].rfind("G[Pa],nu[-],rho[kg/m^3],a0[m],table2_a0[m],a0_rel_diff[-]", 0), 0u);
  o = run({"soil", "--G", "27", "--format", "json"});
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_TRUE(j["rows"][0]["table2"].is_null());  // 27 is no Table 2 G
  // (44)-(45): the dashpots do not depend on G.
  EXPECT_NEAR(j["rows"][0]["formula"]["csh"].get<double>(), 140577.4, 0.1);
  // Another roller: the JSON's note makes no claim about Table 2 (it said that (44)-(45)
  // reproduce the table's dashpots, which r = 0.5 m does not).
  o = run({"soil", "--r", "0.5", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_EQ(
      nlohmann::json::parse(o.out)["note"].get<std::string>().rfind("No Table 2 comparison", 0),
      0u);
}

TEST(CliTransmissibility, AppendixA) {
  Outcome o = run({"transmissibility", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_NEAR(j["omega"].get<double>(), 38.1, 0.05);
  EXPECT_NEAR(j["zeta"].get<double>(), 0.014, 0.0005);
  EXPECT_NEAR(j["ratio"].get<double>(), 6.4, 0.05);
  EXPECT_NEAR(j["Tp"].get<double>(), 0.025, 0.0005);
  o = run({"transmissibility", "--format", "csv", "--mf", "3000"});
  EXPECT_EQ(lines(o.out).at(0), "quantity,value,unit,meaning");
  // roller.kd = 0 is a valid case (the field's rule is >= 0): run simulates it and reports no
  // transmissibility; the calculator, which needs a natural frequency, names the field.
  o = run({"run", "--kd", "0", "--format", "json", "-q"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_TRUE(nlohmann::json::parse(o.out)["derived"]["transmissibility"].is_null());
  o = run({"run", "--kd", "0", "-q"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("n/a (roller.kd = 0"), std::string::npos) << o.out;
  o = run({"transmissibility", "--kd", "0"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("roller.kd must be > 0 [N/m]; got 0"), std::string::npos) << o.err;
}

// A key a command does not use would be silently ignored: it is an error instead (exit code 2),
// and the command's own --help suggests only keys it uses.
TEST(CliSet, KeysACommandDoesNotUseAreErrors) {
  struct Bad {
    const char* command;
    const char* set;
    const char* key;
  };
  for (const Bad& b :
       {Bad{"soil", "numerics.max_periods=3", "numerics.max_periods"},
        Bad{"transmissibility", "soil.ksh=5", "soil.ksh"}, Bad{"soil", "roller.f=30", "roller.f"},
        Bad{"transmissibility", "roller.M0=1", "roller.M0"}}) {
    SCOPED_TRACE(b.set);
    const Outcome o = run({b.command, "--set", b.set});
    EXPECT_EQ(o.code, 2) << o.out;
    EXPECT_EQ(o.out, "");
    EXPECT_NE(o.err.find("oscidrum: error: --set " + std::string(b.set)), std::string::npos)
        << o.err;
    EXPECT_NE(o.err.find(std::string("does not use ") + b.key), std::string::npos) << o.err;
  }
  // Keys they use still work and change the result.
  const Outcome soil = run({"soil", "--format", "json", "--set", "roller.P0=50000"});
  ASSERT_EQ(soil.code, 0) << soil.err;
  EXPECT_EQ(nlohmann::json::parse(soil.out)["roller"]["P0"], 50000.0);
  const Outcome tr = run({"transmissibility", "--format", "json", "--set", "roller.kd=5e6"});
  ASSERT_EQ(tr.code, 0) << tr.err;
  EXPECT_EQ(nlohmann::json::parse(tr.out)["inputs"]["kd"], 5e6);
  for (const char* command : {"soil", "transmissibility"}) {
    const std::string help = run({command, "--help"}).out;
    EXPECT_EQ(help.find("numerics."), std::string::npos) << help;
    EXPECT_EQ(help.find("soil.ksh"), std::string::npos) << help;
  }
}

TEST(CliFields, DocsConfigTableIsTheGeneratedOne) {
  const Outcome o = run({"fields", "--format", "markdown"});
  ASSERT_EQ(o.code, 0) << o.err;
  for (const char* file : {"/docs/config.md", "/README.md"}) {
    SCOPED_TRACE(file);
    const std::string doc = slurp(kSource + file);
    const std::string begin = "<!-- BEGIN oscidrum fields --format markdown -->\n";
    const std::string end = "<!-- END oscidrum fields -->";
    const std::size_t b = doc.find(begin), e = doc.find(end);
    ASSERT_NE(b, std::string::npos);
    ASSERT_NE(e, std::string::npos);
    EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), o.out)
        << file << " is out of date: paste the output of 'oscidrum fields --format markdown' "
        << "between its markers";
  }
  const nlohmann::json j = nlohmann::json::parse(run({"fields", "--format", "json"}).out);
  EXPECT_EQ(j.at("schema"), "oscidrum-fields/1");  // as every JSON document (docs/outputs.md)
  EXPECT_EQ(j.at("fields").size(), fields().size() + 2);
  EXPECT_EQ(run({"params"}).code, 0);
}

// Every generated output table in the docs (between "<!-- BEGIN oscidrum outputs ARGS -->" and
// "<!-- END oscidrum outputs -->") is the current output of `oscidrum outputs ARGS`.
TEST(CliOutputs, DocsOutputTablesAreTheGeneratedOnes) {
  int blocks = 0;
  for (const char* file : {"/docs/outputs.md", "/docs/csv-columns.md", "/README.md"}) {
    SCOPED_TRACE(file);
    const std::string doc = slurp(kSource + file);
    const std::string begin = "<!-- BEGIN oscidrum outputs", end = "<!-- END oscidrum outputs -->";
    int in_file = 0;
    for (std::size_t b = doc.find(begin); b != std::string::npos; b = doc.find(begin, b + 1)) {
      const std::size_t args_end = doc.find(" -->\n", b);
      ASSERT_NE(args_end, std::string::npos);
      std::vector<std::string> args = {"outputs"};
      std::istringstream words(doc.substr(b + begin.size(), args_end - b - begin.size()));
      for (std::string w; words >> w;) args.push_back(w);
      const std::size_t e = doc.find(end, args_end);
      ASSERT_NE(e, std::string::npos);
      const Outcome o = run(args);
      ASSERT_EQ(o.code, 0) << o.err;
      const std::size_t body = args_end + 5;
      EXPECT_EQ(doc.substr(body, e - body), o.out)
          << file << " is out of date: paste the output of 'oscidrum"
          << doc.substr(b + 19, args_end - b - 19) << "' between its markers";
      ++in_file;
      ++blocks;
    }
    EXPECT_GT(in_file, 0) << "no generated output table";
  }
  EXPECT_GE(blocks, 5);
  // The JSON of the table lists what a case summary holds.
  const nlohmann::json table = nlohmann::json::parse(run({"outputs", "--format", "json"}).out);
  const nlohmann::json summary = nlohmann::json::parse(run({"run", "--format", "json"}).out);
  for (const auto& d : table["diagnostics"])
    EXPECT_TRUE(summary["diagnostics"].contains(d["name"]));
  for (const auto& m : table["metrics"]) EXPECT_TRUE(summary["metrics"].contains(m["name"]));
  EXPECT_EQ(summary["metrics"].size(), table["metrics"].size());
  EXPECT_NEAR(summary["metrics"]["mu_required"].get<double>(), 0.5, 1e-6);  // it slips: mu
  EXPECT_EQ(summary["floquet"]["stability"], "stable");
  EXPECT_TRUE(summary["floquet"]["period1"].is_null());  // a period-1 steady state
}

// A period doubling (docs/periodic.md): the JSON and the summary give the multipliers of the
// stable period-2 orbit and of the unstable period-1 orbit it replaced.
TEST(CliRun, PeriodDoublingShowsBothOrbitsFloquetMultipliers) {
  const std::vector<std::string> args = {
      "run",  "--G", "150",   "--unbalance",    "0.22877", "--f",           "25",
      "--mu", "0.7", "--set", "trough.k=0.002", "--set",   "trough.a=0.601"};
  const Outcome text = run(args);
  EXPECT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("period-1 orbit (replaced)       period_doubling"), std::string::npos)
      << text.out;
  auto json_args = args;
  json_args.insert(json_args.end(), {"--format", "json"});
  const nlohmann::json j = nlohmann::json::parse(run(json_args).out);
  EXPECT_EQ(j["diagnostics"]["multiplicity"], 2);
  EXPECT_EQ(j["floquet"]["stability"], "stable");
  EXPECT_EQ(j["floquet"]["period1"]["stability"], "period_doubling");
  EXPECT_GT(j["floquet"]["period1"]["max_modulus"].get<double>(), 1.0);
  EXPECT_EQ(j["floquet"]["period1"]["multipliers"].size(), 7u);
}

TEST(CliHelp, EveryCommandExplainsItselfWithAnExample) {
  for (const char* command : {"run", "sweep", "analyze", "validate", "paper", "soil",
                              "transmissibility", "fields", "outputs", "continue", "diagram"}) {
    SCOPED_TRACE(command);
    const Outcome o = run({command, "--help"});
    EXPECT_EQ(o.code, 0);
    EXPECT_NE(o.out.find("Examples:"), std::string::npos);
    EXPECT_NE(o.out.find(std::string("oscidrum ") + command), std::string::npos);
  }
  const Outcome o = run({"--help"});
  EXPECT_EQ(o.code, 0);
  EXPECT_NE(o.out.find("Exit codes"), std::string::npos);
  EXPECT_EQ(run({"--version"}).code, 0);
}

// Issue 14 (4): one rule set, the field table's, for --set as for config files: integer keys
// take integers only, booleans only true or false; empty paths are errors, not ignored.
TEST(CliIssue14, StrictValuesAndEmptyPaths) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"run", "--set", "numerics.max_periods=5.0"}, "numerics.max_periods must be an integer"},
      {{"run", "--set", "numerics.max_periods=1e3"}, "numerics.max_periods must be an integer"},
      // (Blanks around a value are not part of it, as in a TOML line: "= 2" is 2.)
      {{"run", "--set", "numerics.output_periods=2 periods"}, "must be an integer"},
      {{"run", "--set", "contact.pure_rolling=yes"}, "contact.pure_rolling must be true or false"},
      {{"run", "--set", "contact.pure_rolling=1"}, "contact.pure_rolling must be true or false"},
      {{"run", "--set", "contact.pure_rolling=TRUE"}, "must be true or false"},
      {{"run", "--set", "numerics.max_periods=9223372036854775807"},
       "numerics.max_periods must be an integer in [1, 10000000]; got 9223372036854775807"},
      {{"run", ""}, "the case file name is empty"},
      {{"run", "--csv", ""}, "--csv needs a file name"},
      {{"run", "--events", ""}, "--events needs a file name"},
      {{"run", "--json", ""}, "--json needs a file name"},
      {{"run", "--plot", ""}, "--plot needs a directory name"},
      {{"run", "--csv", "/"}, "--csv / is a directory"},
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--out", ""}, "--out needs a file name"},
      {{"sweep", kSource + "/examples/table2_sweep.toml", "--hdf5", ""}, "--hdf5 needs a file"},
      // Issue 14 (6): --set followed by another flag read the flag's value as the case file.
      {{"run", "--set", "--csv", "out.csv"}, "--set expects KEY=VALUE"},
  };
  for (const auto& [args, message] : cases) {
    std::string joined;
    for (const std::string& a : args) joined += "'" + a + "' ";
    SCOPED_TRACE(joined);
    expect_usage_error(run(args), message);
  }
  EXPECT_EQ(run({"run", "--set", "contact.pure_rolling=true", "--print-config"}).code, 0);
  {
    // The printed case of pure rolling read back does not warn of the friction keys nobody gave
    // (mu, mu_static and law were printed as keys, and reading the file warned of each).
    TempDir dir;
    const Outcome printed = run({"run", "--pure-rolling", "--print-config"});
    ASSERT_EQ(printed.code, 0) << printed.err;
    EXPECT_NE(printed.out.find("# mu = 0.5"), std::string::npos) << printed.out;
    std::ofstream(dir / "pr.toml") << printed.out;
    const Outcome back = run({"run", dir / "pr.toml", "-q"});
    EXPECT_EQ(back.code, 0) << back.err;
    EXPECT_EQ(back.err.find("warning"), std::string::npos) << back.err;
    // A mu given with pure rolling is the user's: printed as a key (its warning is theirs).
    const Outcome given = run(
        {"run", "--set", "contact.pure_rolling=true", "--set", "contact.mu=0.3", "--print-config"});
    EXPECT_NE(given.out.find("\nmu = 0.3"), std::string::npos) << given.out;
  }
  EXPECT_EQ(run({"run", "--set", "numerics.max_periods=+300", "--print-config"}).code, 0);
}

// Issue 14 (5): crashes and internal errors.
TEST(CliIssue14, DeepNestingBadFrequencyAndHugeKeys) {
  TempDir dir;
  {  // dotted headers and keys 50 000 deep (about 100 KB): a stack overflow in the parser
    std::string parts;
    for (int i = 0; i < 50000; ++i) parts += i ? ".a" : "a";
    std::ofstream(dir / "header.toml") << "[" << parts << "]\nx = 1\n";
    std::ofstream(dir / "key.toml") << parts << " = 1\n";
    std::ofstream(dir / "inline.toml") << "x = {" << parts << " = 1}\n";
  }
  for (const char* file : {"header.toml", "key.toml", "inline.toml"})
    for (const char* command : {"run", "sweep"}) {
      SCOPED_TRACE(std::string(command) + " " + file);
      expect_usage_error(run({command, dir / file}), "more than 32 dotted parts");
    }
  // A frequency the integrator cannot handle (5e-324: exit 3) or that overflows nu = 2 pi f
  // (1e308: "nu must be > 0; got inf", no key): the field's range, named.
  expect_usage_error(run({"run", "--f", "5e-324"}),
                     "--f 4.940656458e-324: roller.f must be in [0.1, 1000] [Hz]");
  expect_usage_error(run({"run", "--f", "1e308"}),
                     "roller.f must be in [0.1, 1000] [Hz]; got 1e+308");
  expect_usage_error(run({"run", "--set", "roller.f=5e-324"}), "roller.f must be in [0.1, 1000]");
  // A 1 MB unknown key: the message quotes its start, not all of it.
  const std::string huge(1u << 20, 'k');
  std::ofstream(dir / "huge.toml") << "[roller]\n" << huge << " = 1\n";
  const std::string long_key(100000, 'k');  // an argument may hold at most 128 KiB
  for (const Outcome& o : {run({"run", dir / "huge.toml"}), run({"run", "--set", long_key + "=1"}),
                           run({"sweep", dir / "huge.toml"})}) {
    expect_usage_error(o, "unknown parameter");
    EXPECT_LT(o.err.size(), 400u);
    EXPECT_NE(o.err.find(" bytes)"), std::string::npos) << o.err.substr(0, 400);
  }
}

// Issue 14 (8): trough.k <= 1 is enforced, so the rules `oscidrum fields` prints say it; and a
// named pipe (FIFO) works as a case file: oscidrum waits for the writer (docs/config.md).
TEST(CliIssue14, TroughRuleInFieldsAndAFifoCaseFile) {
  const Outcome f = run({"fields", "--format", "csv"});
  ASSERT_EQ(f.code, 0);
  EXPECT_NE(f.out.find("trough.k,-,0,\"in [0, 1]\""), std::string::npos) << f.out.substr(0, 2000);
  expect_usage_error(run({"run", "--set", "trough.k=1.5"}), "trough.k must be in [0, 1]; got 1.5");

  TempDir dir;
  const std::string fifo = dir / "case.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const pid_t pid = start({"run", fifo, "--print-config"}, dir / "out", dir / "err");
  {
    std::ofstream writer(fifo);  // blocks until oscidrum opens the pipe for reading
    writer << "[roller]\nm = 1900\n";
  }
  const Outcome o = finish(pid, dir / "out", dir / "err");
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("m = 1900.0"), std::string::npos) << o.out;
}

// Every document a help text or an output cites must be part of the project: the paper, or a
// file of docs/ that exists.
void expect_only_project_documents(const std::string& text) {
  // Named in parts, so that the project's own texts (this one included) never cite them.
  for (const char* stem : {"MODEL", "PERIODIC", "STYLE"}) {
    const std::string missing = std::string(stem) + ".md";
    EXPECT_EQ(text.find(missing), std::string::npos) << missing << " cited in:\n" << text;
  }
  for (std::size_t p = text.find("docs/"); p != std::string::npos; p = text.find("docs/", p + 1)) {
    const std::size_t end = text.find(".md", p);
    if (end == std::string::npos) continue;
    const std::string path = text.substr(p, end + 3 - p);
    if (path.find_first_of(" \n") != std::string::npos) continue;
    EXPECT_TRUE(std::filesystem::exists(kSource + "/" + path)) << path;
  }
}

TEST(CliHelp, CitesOnlyDocumentsTheProjectHas) {
  for (const char* command :
       {"run", "sweep", "merge", "analyze", "identify", "validate", "paper", "soil",
        "transmissibility", "fields", "outputs", "continue", "diagram"}) {
    SCOPED_TRACE(command);
    expect_only_project_documents(run({command, "--help"}).out);
  }
  const Outcome soil = run({"soil", "--G", "25"});
  ASSERT_EQ(soil.code, 0) << soil.err;
  EXPECT_NE(soil.out.find("docs/model.md section 1.3"), std::string::npos) << soil.out;
  expect_only_project_documents(soil.out);
  expect_only_project_documents(run({"soil", "--format", "json"}).out);
}

}  // namespace
// Outputs are replaced atomically only where they are regular files: through a symbolic link the
// target is written (the link stays), a FIFO is written directly (a reader gets the JSON), and
// neither is replaced by a regular file (issue 24 point 1).
TEST(CliFiles, OutputsThroughSymlinksAndFifos) {
  TempDir dir;
  { std::ofstream(dir / "target.csv") << "old\n"; }
  std::filesystem::create_symlink("target.csv", dir / "link.csv");
  ASSERT_EQ(::mkfifo((dir / "f.json").c_str(), 0600), 0);
  std::string fifo_text;
  std::thread reader([&] {
    std::ifstream in(dir / "f.json");
    std::stringstream s;
    s << in.rdbuf();
    fifo_text = s.str();
  });
  const Outcome o = run({"run", "--quiet", "--csv", dir / "link.csv", "--json", dir / "f.json"});
  reader.join();
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "link.csv"));
  EXPECT_EQ(slurp(dir / "target.csv").rfind("t[s],delta[rad]", 0), 0u);
  EXPECT_EQ(std::filesystem::status(dir / "f.json").type(), std::filesystem::file_type::fifo);
  EXPECT_EQ(nlohmann::json::parse(fifo_text)["status"], "steady_state");
}

// Numbers on the command line are decimal text: empty, hexadecimal, inf and nan are refused with
// the flag's name (issue 24 point 7); a number too large for the key names its range.
TEST(CliFiles, MalformedNumbersAreRefused) {
  for (const auto& [flag, text] : std::vector<std::pair<std::string, std::string>>{
           {"--mu", ""}, {"--G", "0x10"}, {"--M0", "inf"}, {"--MMd", "nan"}, {"--r", ""}}) {
    const Outcome o = run({"run", "--quiet", flag, text});
    EXPECT_EQ(o.code, 2) << flag << " '" << text << "': " << o.err;
    EXPECT_NE(o.err.find(flag + ": must be a decimal number; got '" + text + "'"),
              std::string::npos)
        << o.err;
  }
  const Outcome big = run({"run", "--quiet", "--G", "1e308"});
  EXPECT_EQ(big.code, 2);
  EXPECT_NE(big.err.find("--G must be in [0.01, 100000] [MN/m^2]"), std::string::npos) << big.err;
}

// The summary puts the result first and the solver's diagnostics after it, and never prints an
// unexplained nan: ratios to a fundamental that vanishes by symmetry say so (issue 25 point 9).
TEST(CliSummary, ResultFirstAndNoUnexplainedNaN) {
  const Outcome o = run({"run"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::size_t metrics = o.out.find("\nsteady state ("),
                    how = o.out.find("\nhow it was computed"),
                    steps = o.out.find("integrator steps");
  ASSERT_NE(metrics, std::string::npos) << o.out;
  ASSERT_NE(how, std::string::npos) << o.out;
  EXPECT_LT(metrics, how);
  EXPECT_GT(steps, how);
  EXPECT_EQ(o.out.find("nan"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("CMV-type value                  n/a (A(f) of z_M'' is 0"),
            std::string::npos)
      << o.out;
  EXPECT_NE(o.out.find("x_M'' A(2f)/A(f)                0 (A(2f) of x_M'' is 0)"),
            std::string::npos)
      << o.out;
}

// One output named twice, or an output naming an input, however spelt: one file silently replaced
// another (run --csv a.csv --json a.csv kept only the JSON, exit 0; sweep -o ./r.out --hdf5 r.out
// lost the HDF5 file; sweep s.toml -o s.toml overwrote the study; identify rec.csv --csv rec.csv
// would overwrite the logger's record). Refused before any work, exit 2, the inputs untouched.
TEST(CliFiles, AnOutputNamingAnotherOutputOrAnInputIsRefused) {
  TempDir dir;
  const std::string study = dir / "s.toml", case_file = dir / "case.toml", rec = dir / "rec.csv";
  const std::string study_text = "[sweep]\n\"contact.mu\" = [0.3, 0.5]\n";
  const std::string case_text = "[roller]\nf = 39\n", rec_text = "t,ddx_M,ddz_M\n0,0,0\n";
  std::ofstream(study) << study_text;
  std::ofstream(case_file) << case_text;
  std::ofstream(rec) << rec_text;
  std::filesystem::create_directory(dir / "sub");
  const std::string dot = dir.path() + "/sub/../";
  struct Refusal {
    std::vector<std::string> args;
    std::string said;
  };
  const std::vector<Refusal> refusals = {
      {{"run", "-q", "--csv", dir / "a.csv", "--json", dot + "a.csv"}, "name the same file"},
      {{"run", "-q", "--csv", dir / "b.csv", "--events", dir / "b.csv"}, "name the same file"},
      {{"run", case_file, "-q", "--json", case_file}, "names the input, the case file"},
      {{"sweep", study, "-q", "-o", dir / "r.out", "--hdf5", dot + "r.out"}, "name the same file"},
      {{"sweep", study, "-q", "-o", dot + "s.toml"}, "names the input, the study file"},
      {{"sweep", study, "-q", "-o", dir / "x.csv", "--hdf5", study}, "names the input"},
      {{"identify", rec, "--csv", dot + "rec.csv"}, "names the input, the record"},
      {{"calibrate", rec + "@30", "--json", rec}, "names the input, the reference record"},
      {{"continue", case_file, "--param", "soil.G", "--from", "20", "--to", "21", "--csv",
        case_file},
       "names the input, the case file"},
  };
  for (const Refusal& r : refusals) {
    const Outcome o = run(r.args);
    std::string cmd;
    for (const std::string& a : r.args) cmd += a + " ";
    EXPECT_EQ(o.code, 2) << cmd << o.err;
    EXPECT_NE(o.err.find(r.said), std::string::npos) << cmd << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << cmd << o.err;
  }
  EXPECT_EQ(slurp(study), study_text);
  EXPECT_EQ(slurp(case_file), case_text);
  EXPECT_EQ(slurp(rec), rec_text);
  for (const char* name : {"a.csv", "b.csv", "r.out", "x.csv"})
    EXPECT_FALSE(std::filesystem::exists(dir / name)) << name;
  // A hard link is the same file too.
  std::filesystem::create_hard_link(case_file, dir / "link.toml");
  const Outcome linked = run({"run", case_file, "-q", "--csv", dir / "link.toml"});
  EXPECT_EQ(linked.code, 2) << linked.err;
  EXPECT_EQ(slurp(case_file), case_text);
  // Distinct files still pass.
  const Outcome fine =
      run({"run", case_file, "-q", "--csv", dir / "c.csv", "--json", dir / "c.json"});
  EXPECT_EQ(fine.code, 0) << fine.err;
}

// --set as a TOML line writes it ('roller.f = 40') sets the key (it was "unknown parameter
// 'roller.f '"), and --help shows the syntax that is accepted (it showed KEY=VALUE:KEY=VALUE,
// which is refused).
TEST(CliRun, SetTakesBlanksAroundKeyAndValue) {
  const Outcome o = run({"run", "--set", "roller.f = 40", "--set", " contact.mu =0.3 ", "--set",
                         "roller.M0=54947", "--print-config"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.out.find("\nf = 40.0"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("\nmu = 0.3"), std::string::npos) << o.out;
  const Outcome help = run({"run", "--help"});
  EXPECT_NE(help.out.find("--set KEY=VALUE ..."), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("KEY=VALUE:KEY=VALUE"), std::string::npos) << help.out;
}

// A flag given twice, a misspelled flag or command: CLI11's words ("At Most 1 required but
// received 2", "The following argument was not expected: --Mu") with what to do.
TEST(CliRun, ParseErrorsSayWhatToDo) {
  const Outcome twice = run({"run", "--mu", "0.3", "--mu", "0.4"});
  EXPECT_EQ(twice.code, 2);
  EXPECT_NE(twice.err.find("--mu is given more than once"), std::string::npos) << twice.err;
  const Outcome flag = run({"run", "--Mu", "0.3"});
  EXPECT_EQ(flag.code, 2);
  EXPECT_NE(flag.err.find("(did you mean --mu?)"), std::string::npos) << flag.err;
  const Outcome command = run({"sweeep", "study.toml"});
  EXPECT_EQ(command.code, 2);
  EXPECT_NE(command.err.find("(did you mean sweep?)"), std::string::npos) << command.err;
  const Outcome two = run({"run", "--Mu", "0.3", "--Nu", "2"});
  // (CLI11 lists the unexpected words in an order of its own.)
  EXPECT_NE(two.err.find("did you mean --"), std::string::npos) << two.err;
  EXPECT_NE(two.err.find("--mu for --Mu"), std::string::npos) << two.err;
  EXPECT_NE(two.err.find("--nu for --Nu"), std::string::npos) << two.err;
  // sweep's --out given to run: no guess two edits away ("--nu"), run's own output flags.
  const Outcome out = run({"run", "--out", "r.csv"});
  EXPECT_EQ(out.code, 2);
  EXPECT_EQ(out.err.find("did you mean"), std::string::npos) << out.err;
  EXPECT_NE(out.err.find("writes its outputs with --csv FILE and --json FILE"), std::string::npos)
      << out.err;
  for (const Outcome* o : {&twice, &flag, &command, &two, &out})
    EXPECT_EQ(std::count(o->err.begin(), o->err.end(), '\n'), 1) << o->err;
  // Far from every name: no guess.
  const Outcome far = run({"run", "--zzzzzzzz"});
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

}  // namespace oscidrum::test
