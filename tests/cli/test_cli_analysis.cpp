// End-to-end tests of `oscidrum validate`, `oscidrum analyze` and `oscidrum paper`.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "process.hpp"

namespace oscidrum::test {
namespace {

const std::string kSource = OSCIDRUM_SOURCE_DIR;

TEST(CliValidate, EveryClaimAgreesAndTheMarkdownIsWritten) {
  TempDir dir;
  const Outcome o = run({"validate", "--quiet", "--format", "json", "--markdown", dir / "v.md",
                         "--csv", dir / "v.csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["schema"], "oscidrum-validation/1");
  EXPECT_EQ(j["disagreements"], 0);
  EXPECT_GE(j["rows"].size(), 40u);
  const std::string md = slurp(dir / "v.md");
  EXPECT_EQ(md.rfind("# Validation against the paper", 0), 0u);
  EXPECT_NE(md.find("| fig12.psi_max |"), std::string::npos);
  EXPECT_EQ(slurp(dir / "v.csv").rfind("id,figure,claim,paper,oscidrum,rule,agrees", 0), 0u);
  EXPECT_EQ(slurp(kSource + "/docs/validation.md"), md)
      << "docs/validation.md is out of date: run 'oscidrum validate --markdown "
         "docs/validation.md'";
  EXPECT_EQ(md.find(std::string("MODEL") + ".md"), std::string::npos);
  // The terminal table shows each claim's text beside its id, and the rule applied (its first
  // 57 characters).
  const Outcome table = run({"validate", "--quiet"});
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_NE(table.out.substr(0, table.out.find('\n')).find(" rule"), std::string::npos);
  for (const auto& row : j["rows"]) {
    EXPECT_NE(table.out.find(row["claim"].get<std::string>()), std::string::npos) << row["id"];
    EXPECT_NE(table.out.find(row["rule"].get<std::string>().substr(0, 57)), std::string::npos)
        << row["id"];
  }
}

TEST(CliValidate, InterruptExits130WithoutWritingTheTable) {
  TempDir dir;
  const pid_t pid =
      start({"validate", "--threads", "1", "--markdown", dir / "v.md"}, dir / "out", dir / "err");
  // As soon as the handler is installed (just before the work starts): on one thread the whole
  // validation takes about 0.27 s on an idle machine (bench/README.md), so a fixed delay either
  // came after the end (300 ms) or, under the sanitizers' slow start-up, before the handler
  // (60 ms).
  ASSERT_TRUE(wait_until_catching(pid, SIGINT));
  ::kill(pid, SIGINT);
  const Outcome o = finish(pid, dir / "out", dir / "err");
  EXPECT_EQ(o.code, 130) << o.err;
  EXPECT_NE(o.err.find("interrupted"), std::string::npos) << o.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "v.md"));
}

// A simulated steady state written by `run --csv` is a perfect "record": analyze must give the
// harmonics that `run` reports (uniform samples over whole periods: least squares = DFT).
TEST(CliAnalyze, RecordOfASimulationGivesItsHarmonics) {
  TempDir dir;
  const Outcome r = run({"run", "--quiet", "--MMd-fraction", "0.05", "--csv", dir / "s.csv",
                         "--json", dir / "s.json"});
  ASSERT_EQ(r.code, 0) << r.err;
  // --f: the record is two periods long, too short to estimate f to 1e-9.
  const Outcome a = run({"analyze", dir / "s.csv", "--f", "39", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  const nlohmann::json rec = nlohmann::json::parse(a.out);
  const nlohmann::json sim = nlohmann::json::parse(slurp(dir / "s.json"));
  EXPECT_EQ(rec["schema"], "oscidrum-record/1");
  EXPECT_EQ(rec["oscidrum_version"], sim["oscidrum_version"]);  // documented, was missing
  const auto& hx = rec["ddx_harmonics"];
  ASSERT_EQ(hx.size(), 11u);
  EXPECT_EQ(hx[3]["n"], 3);  // {n, amplitude, phase} as documented (n was missing)
  const double a1 = hx[1]["amplitude"].get<double>();
  EXPECT_GT(a1, 1.0);
  // The run's JSON holds the same harmonic (docs/outputs.md: metrics.ddx_harmonics), there an
  // integral over the trajectory; the record's fit of 1024 samples per period differs by the
  // aliasing of the kinked signal's overtones above 512 f (about 1e-6 relative).
  const double sim_a1 = sim["metrics"]["ddx_harmonics"][1]["amplitude"].get<double>();
  EXPECT_NEAR(a1, sim_a1, 1e-5 * sim_a1);
  EXPECT_NEAR(rec["psi_xz"].get<double>(), sim["metrics"]["psi_xz"].get<double>(), 1e-5);
  // A stick-slip record's accelerations jump at the switches: the residuals of ten harmonics are
  // the harmonics above them, not noise, and a note says what 40 give (closer to the run's own
  // peaks, which the record's samples hold).
  EXPECT_NE(a.err.find("are mostly harmonics above the 10 fitted, not noise: with 40"),
            std::string::npos)
      << a.err;
  const Outcome more =
      run({"analyze", dir / "s.csv", "--f", "39", "--harmonics", "40", "--format", "json"});
  ASSERT_EQ(more.code, 0) << more.err;
  const double x_max = sim["metrics"]["ddx_max"].get<double>();
  EXPECT_LT(std::abs(nlohmann::json::parse(more.out)["ddx_max"].get<double>() - x_max),
            std::abs(rec["ddx_max"].get<double>() - x_max));
  const Outcome most = run({"analyze", dir / "s.csv", "--f", "39", "--harmonics", "200"});
  ASSERT_EQ(most.code, 0) << most.err;
  EXPECT_EQ(most.err.find("are mostly harmonics above"), std::string::npos) << most.err;
}

// kb of a record (`analyze --case --unbalance-col`, docs/outputs.md): the steady state of
// examples/vibratory.toml (partial uplift) written by `run --csv`, read back with the angle column
// that `run` itself writes (alpha, docs/csv-columns.md: the user computes nothing), gives the kb
// that `run` reports, to the aliasing of the contact force's jump at the landing in 1024 samples
// per period (1.3e-4 seen; docs/outputs.md: of order 1/1024): 1e-3. The column is checked
// against its definition first: 2 pi f t wrapped to [0, 2 pi). Without --case, kb is null and
// kb_note says why.
// A period-2 record whose subharmonic outweighs its response at the excitation's f = 25 Hz is
// read as period 1 at 12.5 Hz (valid, its CMV-type value that of another frequency): x_M'' at 2f
// above half its component at f, which a drum's x_M'' never is at the excitation's frequency, is
// said, with the --f to give. The default case's record, estimated at its own f, says nothing of
// it, nor does the record with --f given.
TEST(CliAnalyze, AnEstimateAtHalfTheExcitationIsSaid) {
  TempDir dir;
  {
    std::ofstream out(dir / "sub.csv");
    out << "t,ddx_M,ddz_M\n";
    for (int k = 0; k < 2000; ++k) {
      const double t = 1e-3 * k, w = 2.0 * M_PI * 25.0 * t;
      out << t << "," << 10.0 * std::cos(0.5 * w) + 6.0 * std::cos(w + 0.3) << ","
          << 2.0 * std::cos(0.5 * w + 1.0) + 3.0 * std::cos(w) + 1.0 * std::cos(2.0 * w) << "\n";
    }
  }
  const Outcome o = run({"analyze", dir / "sub.csv"});
  EXPECT_EQ(o.code, 0) << o.err;
  EXPECT_NE(o.err.find("x_M'' at 2f is 0.6 of its component at the estimated f = 12.5 Hz"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("give --f 25"), std::string::npos) << o.err;
  const Outcome given = run({"analyze", dir / "sub.csv", "--f", "25"});
  EXPECT_EQ(given.err.find("x_M'' at 2f"), std::string::npos) << given.err;
  ASSERT_EQ(
      run({"run", "--quiet", "--csv", dir / "s.csv", "--set", "numerics.output_periods=8"}).code,
      0);
  const Outcome own = run({"analyze", dir / "s.csv"});
  EXPECT_EQ(own.code, 0) << own.err;
  EXPECT_EQ(own.err.find("x_M'' at 2f"), std::string::npos) << own.err;
}

TEST(CliAnalyze, KbOfAVibratoryRecordWithItsUnbalanceAngle) {
  TempDir dir;
  const std::string example = kSource + "/examples/vibratory.toml";
  const Outcome r =
      run({"run", example, "--quiet", "--csv", dir / "s.csv", "--json", dir / "s.json"});
  ASSERT_EQ(r.code, 0) << r.err;
  {
    std::istringstream in(slurp(dir / "s.csv"));
    std::string line;
    std::getline(in, line);
    ASSERT_EQ(line.rfind("t[s],", 0), 0u) << line;
    std::vector<std::string> header;
    for (std::size_t a = 0, b = 0; b != std::string::npos; a = b + 1)
      header.push_back(line.substr(a, (b = line.find(',', a)) - a));
    const auto at = std::find(header.begin(), header.end(), "alpha[rad]");
    ASSERT_NE(at, header.end()) << line;
    const std::size_t col = static_cast<std::size_t>(at - header.begin());
    // Each row's alpha in [0, 2 pi) and alpha - nu t a whole number of turns (compared on the
    // circle: a sample at a whole period may read just below 2 pi as well as 0); rows that are
    // not are counted, and the first of them is shown.
    std::size_t rows = 0, wrong = 0;
    std::string first_wrong;
    while (std::getline(in, line)) {
      std::vector<std::string> cells;
      for (std::size_t a = 0, b = 0; b != std::string::npos; a = b + 1)
        cells.push_back(line.substr(a, (b = line.find(',', a)) - a));
      ASSERT_EQ(cells.size(), header.size()) << line;
      const double nu_t = 2.0 * M_PI * 30.0 * std::stod(cells[0]);
      const double alpha = std::stod(cells[col]);
      const double turns = (nu_t - alpha) / (2.0 * M_PI);
      if (!(alpha >= 0.0 && alpha < 2.0 * M_PI && std::abs(turns - std::round(turns)) < 1e-10) &&
          wrong++ == 0)
        first_wrong = line;
      ++rows;
    }
    EXPECT_GT(rows, 1000u);
    EXPECT_EQ(wrong, 0u) << "rows whose alpha is not 2 pi f t in [0, 2 pi), the first: "
                         << first_wrong;
  }
  const Outcome a = run({"analyze", dir / "s.csv", "--f", "30", "--case", example,
                         "--unbalance-col", "alpha", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  const nlohmann::json rec = nlohmann::json::parse(a.out);
  const nlohmann::json sim = nlohmann::json::parse(slurp(dir / "s.json"));
  const double kb = sim["metrics"]["kb"].get<double>();
  ASSERT_TRUE(rec["kb"].is_number()) << a.out;
  EXPECT_NEAR(rec["kb"].get<double>(), kb, 1e-3 * kb);
  EXPECT_EQ(rec.value("kb_note", "missing"), "");  // present, empty: kb was computed
  const Outcome b = run({"analyze", dir / "s.csv", "--f", "30", "--format", "json"});
  ASSERT_EQ(b.code, 0) << b.err;
  const nlohmann::json none = nlohmann::json::parse(b.out);
  EXPECT_TRUE(none["kb"].is_null());
  EXPECT_NE(none["kb_note"].get<std::string>().find("--case"), std::string::npos);
  // The same record with a dead z_M'' channel (0 in every row): read with a note on stderr, kb
  // and psi_xz null, and kb_note says why.
  {
    std::istringstream in(slurp(dir / "s.csv"));
    std::ofstream out(dir / "dead.csv");
    std::string line;
    std::getline(in, line);
    out << line << "\n";
    std::size_t col = 0;
    for (std::size_t i = 0, j = 0; j != std::string::npos; i = j + 1, ++col)
      if (line.substr(i, (j = line.find(',', i)) - i) == "ddz_M[m/s^2]") break;
    while (std::getline(in, line)) {
      std::size_t from = 0;
      for (std::size_t k = 0; k < col; ++k) from = line.find(',', from) + 1;
      const std::size_t to = line.find(',', from);
      out << line.substr(0, from) << "0" << (to == std::string::npos ? "" : line.substr(to))
          << "\n";
    }
  }
  const Outcome d = run({"analyze", dir / "dead.csv", "--f", "30", "--case", example,
                         "--unbalance-col", "alpha", "--format", "json"});
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_NE(d.err.find("z_M'': the same value (0 m/s^2) in every row"), std::string::npos) << d.err;
  const nlohmann::json dead = nlohmann::json::parse(d.out);
  EXPECT_TRUE(dead["kb"].is_null()) << d.out;
  EXPECT_TRUE(dead["psi_xz"].is_null()) << d.out;
  EXPECT_NE(dead["kb_note"].get<std::string>().find("no component at f"), std::string::npos)
      << d.out;
}

// A record's clock may start anywhere: the same record with its times shifted by -100 s (where
// analyze once found no window and crashed) gives the same harmonics, whole and in windows.
TEST(CliAnalyze, RecordShiftedToNegativeTimesGivesTheSameHarmonics) {
  TempDir dir;
  const Outcome r = run({"run", "--quiet", "--csv", dir / "s.csv"});
  ASSERT_EQ(r.code, 0) << r.err;
  {
    std::ifstream in(dir / "s.csv");
    std::ofstream out(dir / "shifted.csv");
    std::string line;
    std::getline(in, line);
    out << line << "\n";
    out.precision(17);
    while (std::getline(in, line)) {
      const std::size_t comma = line.find(',');
      out << std::stod(line.substr(0, comma)) - 100.0 << line.substr(comma) << "\n";
    }
  }
  const Outcome a = run({"analyze", dir / "s.csv", "--f", "39", "--format", "json"});
  const Outcome b = run({"analyze", dir / "shifted.csv", "--f", "39", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(b.signal, 0);
  const nlohmann::json ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  for (const char* s : {"ddx_harmonics", "ddz_harmonics"}) {
    double scale = 0.0;
    for (const auto& h : ja[s]) scale = std::max(scale, h["amplitude"].get<double>());
    // ulp(100 s) = 1.4e-14 s of rounding in the shifted times: 1e-9 of the signal is ample.
    for (std::size_t n = 1; n < ja[s].size(); ++n)
      EXPECT_NEAR(jb[s][n]["amplitude"].get<double>(), ja[s][n]["amplitude"].get<double>(),
                  1e-9 * scale)
          << s << " " << n;
  }
  EXPECT_NEAR(jb["psi_xz"].get<double>(), ja["psi_xz"].get<double>(), 1e-9);
  // Windows of 0.9 periods (each too short to fit: every one was flagged, exit 1) are refused at
  // once; one of 1.5 periods is analysed (its halves are too short to measure a drift of f: that
  // gate off).
  const Outcome short_window =
      run({"analyze", dir / "shifted.csv", "--f", "39", "--window", "0.9"});
  EXPECT_EQ(short_window.code, 2) << short_window.err;
  EXPECT_NE(short_window.err.find("window (--window) must be >= 1 [periods]"), std::string::npos)
      << short_window.err;
  for (const auto& [window, count, code] : {std::tuple{"1.5", 1u, 0}}) {
    const Outcome w = run({"analyze", dir / "shifted.csv", "--f", "39", "--window", window,
                           "--max-drift", "1", "--format", "json"});
    EXPECT_EQ(w.signal, 0);
    ASSERT_EQ(w.code, code) << w.err;
    EXPECT_EQ(nlohmann::json::parse(w.out)["windows"].size(), count) << window;
  }
}

// A logger's file: a byte-order mark, semicolons and decimal commas, time in ms, accelerations
// in g under their own names, x pointing backwards and z up, an extra channel. Read with
// --x-positive backward --z-positive up it is the simulation's record again: the same numbers.
TEST(CliAnalyze, LoggerConventionsAreReadBackToTheModels) {
  TempDir dir;
  const Outcome r = run({"run", "--quiet", "--csv", dir / "s.csv"});
  ASSERT_EQ(r.code, 0) << r.err;
  {
    std::ifstream in(dir / "s.csv");
    std::ofstream out(dir / "field.csv");
    std::string line;
    std::getline(in, line);
    out << "\xEF\xBB\xBF"
        << "Temp (C);Time [ms];Acc X [g];Acc Z [g]\n";
    while (std::getline(in, line)) {
      std::vector<double> v;
      std::stringstream cells(line);
      for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stod(cell));
      std::ostringstream row;
      row.precision(17);
      // t, ..., ddx_M (column 12), ddz_M (13), 1-based
      row << 20.5 << ";" << v[0] * 1000.0 << ";" << -v[11] / 9.80665 << ";" << -v[12] / 9.80665;
      std::string text = row.str();
      std::replace(text.begin(), text.end(), '.', ',');
      out << text << "\n";
    }
  }
  const Outcome a = run({"analyze", dir / "s.csv", "--f", "39", "--format", "json"});
  const Outcome b = run({"analyze", dir / "field.csv", "--f", "39", "--format", "json",
                         "--x-positive", "backward", "--z-positive", "up"});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.err.find("record: t: column 'Time [ms]' x 0.001 -> s"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("record: x_M'': column 'Acc X [g]' x -9.80665"), std::string::npos) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  // The JSON says how the record was read: columns, factors, axis conventions.
  const auto& reading = jb["reading"];
  EXPECT_EQ(reading["x_positive"], "backward");
  EXPECT_EQ(reading["z_positive"], "up");
  EXPECT_EQ(reading["delimiter"], "semicolon");
  EXPECT_EQ(reading["t"]["column"], "Time [ms]");
  EXPECT_DOUBLE_EQ(reading["t"]["factor"].get<double>(), 0.001);
  EXPECT_EQ(reading["ddx_M"]["column"], "Acc X [g]");
  EXPECT_DOUBLE_EQ(reading["ddx_M"]["factor"].get<double>(), -9.80665);
  EXPECT_DOUBLE_EQ(reading["ddz_M"]["factor"].get<double>(), -9.80665);
  EXPECT_EQ(ja["reading"]["x_positive"], "forward");
  EXPECT_DOUBLE_EQ(ja["reading"]["ddz_M"]["factor"].get<double>(), 1.0);
  for (const char* s : {"ddx_harmonics", "ddz_harmonics"}) {
    const double scale = ja[s][1]["amplitude"].get<double>() + ja[s][2]["amplitude"].get<double>();
    for (std::size_t n = 1; n < ja[s].size(); ++n) {
      EXPECT_NEAR(jb[s][n]["amplitude"].get<double>(), ja[s][n]["amplitude"].get<double>(),
                  1e-9 * scale)
          << s << " " << n;
      // Phases of the harmonics that matter (a harmonic at 1e-6 of the signal has none).
      if (ja[s][n]["amplitude"].get<double>() > 1e-3 * scale) {
        EXPECT_NEAR(jb[s][n]["phase"].get<double>(), ja[s][n]["phase"].get<double>(), 1e-7)
            << s << " " << n;
      }
    }
  }
  EXPECT_NEAR(jb["psi_xz"].get<double>(), ja["psi_xz"].get<double>(), 1e-9);
  EXPECT_NEAR(jb["area"].get<double>(), ja["area"].get<double>(), 1e-9 * ja["area"].get<double>());
  // Read as written (no axis flags) the lag moves: psi_xz is not sign-blind.
  const Outcome c = run({"analyze", dir / "field.csv", "--f", "39", "--format", "json"});
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_GT(
      std::abs(nlohmann::json::parse(c.out)["psi_xz"].get<double>() - ja["psi_xz"].get<double>()),
      0.1);
}

// A logger at 500 Hz resolves 5 harmonics of 39 Hz (12.8 samples per period): without
// --harmonics analyze fits 5 (2 N + 1 samples per period) and the window is valid; the default
// 10 made it fail the samples-per-period gate. A sample-number column and --rate give the time.
TEST(CliAnalyze, ASlowLoggerGetsTheHarmonicsItsSamplingResolves) {
  TempDir dir;
  {
    std::ofstream out(dir / "slow.csv");
    out << "Sample,acc_x [m/s^2],acc_z [m/s^2]\n";
    out.precision(17);
    const double nu = 2 * M_PI * 39.0;
    for (int i = 0; i < 500; ++i) {
      const double t = i / 500.0;
      out << i << "," << 12.0 * std::sin(nu * t) + 3.0 * std::sin(3 * nu * t) << ","
          << 0.5 * std::sin(2 * nu * t + 0.3) << "\n";
    }
  }
  const Outcome a = run({"analyze", dir / "slow.csv", "--rate", "500", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  const auto j = nlohmann::json::parse(a.out);
  EXPECT_EQ(j["ddx_harmonics"].size(), 6u);  // n = 0 ... 5
  EXPECT_NEAR(j["ddx_harmonics"][3]["amplitude"].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(j["ddz_harmonics"][2]["amplitude"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(j["f"].get<double>(), 39.0, 1e-7);
  EXPECT_EQ(a.err.find("are mostly harmonics above"), std::string::npos) << a.err;
  // Asked for more than the sampling resolves: the gate says so (the sampling against the flags:
  // exit 2).
  const Outcome b = run({"analyze", dir / "slow.csv", "--rate", "500", "--harmonics", "10"});
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.err.find("too few samples per period"), std::string::npos) << b.err;
}

TEST(CliAnalyze, BadRecordsGiveOneLineAndExitTwo) {
  TempDir dir;
  {
    std::ofstream(dir / "cols.csv") << "punkt,kanal1,kanal2\n0,1,2\n0.1,1,2\n";
    std::ofstream(dir / "two_x.csv") << "t,ax,acc_x,az\n0,1,1,2\n0.1,1,1,2\n";
    std::ofstream(dir / "unit.csv") << "t [h],ax,az\n0,1,2\n0.1,1,2\n";
    std::ofstream(dir / "aunit.csv") << "t,ax [counts],az\n0,1,2\n0.1,1,2\n";
    std::ofstream(dir / "vunit.csv") << "t,Vib X [mm/s],az\n0,1,2\n0.1,1,2\n";
    std::ofstream(dir / "dunit.csv") << "t,ax [km],az\n0,1,2\n0.1,1,2\n";
    std::ofstream(dir / "text.csv") << "t,ddx_M,ddz_M\n0,1,2\n0.1,x,2\n";
    std::ofstream(dir / "short.csv") << "t,ddx_M,ddz_M\n0,1,2\n0.001,2,1\n";
    std::ofstream(dir / "ragged.csv") << "t,ddx_M,ddz_M\n0,1\n";
  }
  struct Case {
    std::string file, message;
  };
  for (const Case& c :
       {Case{"cols.csv", "no column looks like the time; choose one with --t-col"},
        Case{"two_x.csv",
             "several columns look like the horizontal acceleration x_M'' (ax, acc_x)"},
        Case{"unit.csv", "unit 'h' is not a time unit (s, ms, us, ns); give --t-units"},
        Case{"aunit.csv",
             "unit 'counts' is not an acceleration unit (m/s^2, mm/s^2, cm/s^2, ft/s^2, g, mg); "
             "give --units for the one it is"},
        // A velocity or a displacement is refused as such, not with the advice to give --units
        // (which read a velocity channel as g).
        Case{"vunit.csv", "column 'Vib X [mm/s]': unit 'mm/s' is a velocity, not an acceleration"},
        Case{"dunit.csv", "unit 'km' is a displacement, not an acceleration"},
        Case{"text.csv", "must be a number"}, Case{"short.csv", "at least 8 samples"},
        Case{"ragged.csv", "2 cells, but the header has 3"},
        Case{"missing.csv", "cannot open the file (no such file)"},
        Case{".", "is a directory, not a record file"}}) {
    SCOPED_TRACE(c.file);
    const Outcome o = run({"analyze", dir / c.file});
    EXPECT_EQ(o.code, 2) << o.err;
    EXPECT_EQ(o.signal, 0);
    EXPECT_EQ(o.err.rfind("oscidrum: error: ", 0), 0u) << o.err;
    EXPECT_NE(o.err.find(c.message), std::string::npos) << o.err;
  }
  // --units does not make a velocity an acceleration (it read [mm/s] as g, exit 0).
  const Outcome as_g = run({"analyze", dir / "vunit.csv", "--units", "g"});
  EXPECT_EQ(as_g.code, 2) << as_g.err;
  EXPECT_NE(as_g.err.find("is a velocity, not an acceleration"), std::string::npos) << as_g.err;
  // Columns chosen by flag.
  const Outcome o = run({"analyze", dir / "cols.csv", "--f", "39", "--t-col", "punkt", "--x-col",
                         "kanal1", "--z-col", "3"});
  // 2 samples over 3.9 periods: f = 39 Hz is above half the record's sampling rate (10 Hz), so
  // no harmonic of it can be measured: refused as input.
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("f (--f) must be at most half the record's sampling rate, 5 Hz"),
            std::string::npos)
      << o.err;
  // Too few samples per period for the harmonics asked (200 per period, 200 harmonics need 401):
  // the flags against the record's sampling, exit 2 as for any input the record cannot serve.
  const Outcome rec =
      run({"run", "-q", "--csv", dir / "rec.csv", "--set", "numerics.samples_per_period=200",
           "--set", "numerics.output_periods=4"});
  ASSERT_EQ(rec.code, 0) << rec.err;
  const Outcome dense = run({"analyze", dir / "rec.csv", "--f", "39", "--harmonics", "200"});
  EXPECT_EQ(dense.code, 2) << dense.err;
  EXPECT_NE(dense.err.find("too few samples per period"), std::string::npos) << dense.err;
  // An empty output name is refused, as run refuses it.
  const Outcome empty = run({"validate", "--csv", ""});
  EXPECT_EQ(empty.code, 2);
  EXPECT_NE(empty.err.find("--csv needs a file name"), std::string::npos) << empty.err;
}

// With the Python package: figures, data and the report; without it (a build without Python):
// the validation table alone and exit code 1 with a clear message.
TEST(CliPaper, WritesTheReproductionOrTheValidationAlone) {
  TempDir dir;
  const Outcome o = run({"paper", "--quiet", "--out", dir.path()});
  EXPECT_EQ(o.signal, 0) << o.err;
  if (o.code == 0) {
    EXPECT_TRUE(std::filesystem::exists(dir / "report.md"));
    EXPECT_TRUE(std::filesystem::exists(dir / "validation.md"));
    int figures = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
      figures += e.path().extension() == ".png";
    EXPECT_GE(figures, 10);
  } else {
    EXPECT_EQ(o.code, 1);
    EXPECT_TRUE(std::filesystem::exists(dir / "validation.md"));
    EXPECT_TRUE(std::filesystem::exists(dir / "validation.csv"));
    EXPECT_NE(o.err.find("/validation.csv only"), std::string::npos) << o.err;
  }
}

// Without a Python that can run the package, the validation table is written as the docs say:
// validation.md and validation.csv (only the Markdown was), the CSV that of `validate --csv`.
TEST(CliPaper, WithoutPythonTheValidationTableIsWrittenInBothForms) {
  TempDir dir;
  ::setenv("OSCIDRUM_PYTHON", (dir / "no-python").c_str(), 1);
  const Outcome o = run({"paper", "--quiet", "--out", dir / "paper", "--threads", "1"});
  ::unsetenv("OSCIDRUM_PYTHON");
  EXPECT_EQ(o.code, 1) << o.err;
  EXPECT_NE(o.err.find("validation.md and " + (dir / "paper") + "/validation.csv only"),
            std::string::npos)
      << o.err;
  const Outcome v = run({"validate", "--quiet", "--csv", dir / "v.csv", "--threads", "1"});
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_EQ(slurp(dir / "paper/validation.csv"), slurp(dir / "v.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "paper/validation.md"));
}

}  // namespace
// The windowed CSV carries every number of a record's output table (the compaction indicators
// included), one field per column in every row.
TEST(CliAnalyze, WindowedCsvHasEveryRecordMetric) {
  TempDir dir;
  const Outcome r =
      run({"run", "--quiet", "--csv", dir / "s.csv", "--set", "numerics.output_periods=6"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Outcome a =
      run({"analyze", dir / "s.csv", "--f", "39", "--window", "2", "--format", "csv"});
  ASSERT_EQ(a.code, 0) << a.err;
  std::istringstream lines(a.out);
  std::string header, row;
  ASSERT_TRUE(std::getline(lines, header));
  for (const char* column : {"cycles[-]", "psi_xz[rad]", "area[m^2/s^4]", "ddx_A2_A1[-]",
                             "ddz_A3_A1[-]", "cmv[-]", "ddx_thd[-]", "ddz_A10[m/s^2]"})
    EXPECT_NE(header.find(std::string(",") + column), std::string::npos) << column;
  const auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  int rows = 0;
  while (std::getline(lines, row)) {
    EXPECT_EQ(fields(row), fields(header)) << row;
    ++rows;
  }
  // The samples span 6 periods less one step: windows at 0 and 2 periods, and one ending with the
  // record (the 2 periods left are not dropped).
  EXPECT_EQ(rows, 3);
}

}  // namespace oscidrum::test
