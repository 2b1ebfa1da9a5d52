// End-to-end tests of `oscidrum identify` and of the robust `oscidrum analyze`: synthetic
// records made by oscidrum itself (identify.hpp, synthetic_record), 1 % away from 39 Hz, 5 %
// noise, a slow drift.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <tuple>

#include "oscidrum/oscidrum.hpp"
#include "process.hpp"

namespace oscidrum::test {
namespace {

constexpr double kF = 39.0 * 1.01;

Case truth(double G) {
  Case c;
  c.soil.input = SoilInput::modulus;
  c.soil.G = G;
  c.roller.M0 *= (kF / 39.0) * (kF / 39.0);  // (5)
  c.roller.f = kF;
  return c;
}

// t, ddx_M, ddz_M, v (speed 0.8 m/s) of consecutive cases.
void write_record(const std::string& path, const std::vector<Case>& cases, double duration,
                  double rate = 1000, double start = 0.0) {
  SyntheticRecord o;
  o.duration = duration;
  o.sample_rate = rate;
  o.noise = 0.05;
  o.drift = 0.05;
  o.seed = 4;
  o.start = start;
  const RecordSamples r = synthetic_record(cases, o);
  std::ofstream out(path);
  out << "t,ddx_M,ddz_M,v\n";
  char line[160];
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    // A logger's clock (s since 1970) to the microsecond, as loggers write it.
    if (start >= 1e5)
      std::snprintf(line, sizeof line, "%.6f,%.9g,%.9g,0.8\n", r.t[i], r.ddx_M[i], r.ddz_M[i]);
    else
      std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,0.8\n", r.t[i], r.ddx_M[i], r.ddz_M[i]);
    out << line;
  }
}

// The record `from` (t, x_M'', z_M'' as write_record writes them) written again as a logger
// writes it, to `to`: `header`, then per row the time (in ms with `ms`, else s) and the
// accelerations in g with the z axis pointing up, `gravity` [g] added to z, separated by `sep`.
void write_logger_file(const std::string& from, const std::string& to, const std::string& header,
                       char sep, bool ms, double gravity) {
  std::ifstream in(from);
  std::ofstream out(to);
  out << header << "\n";
  std::string line;
  std::getline(in, line);  // the header
  char row[160];
  while (std::getline(in, line)) {
    double t = 0, x = 0, z = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &x, &z), 3) << line;
    std::snprintf(row, sizeof row, ms ? "%.3f%c%.9g%c%.9g\n" : "%.6f%c%.9g%c%.9g\n",
                  ms ? t * 1e3 : t, sep, x / kStandardGravity, sep, gravity - z / kStandardGravity);
    out << row;
  }
}

// Column `name` (without unit) of a CSV text, as numbers (NaN for text).
std::vector<double> column(const std::string& csv, const std::string& name) {
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> names;
  std::stringstream hs(header);
  for (std::string h; std::getline(hs, h, ',');) names.push_back(h.substr(0, h.find('[')));
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name << " not in " << header;
  const std::size_t k = static_cast<std::size_t>(it - names.begin());
  std::vector<double> v;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (char ch : line) {
      if (ch == '"')
        quoted = !quoted;
      else if (ch == ',' && !quoted) {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += ch;
      }
    }
    cells.push_back(cell);
    v.push_back(k < cells.size() && !cells[k].empty() ? std::strtod(cells[k].c_str(), nullptr)
                                                      : NAN);
  }
  return v;
}

// A poor fit's warnings (hundreds of characters) are numbered notes below the table: the status
// column stays short, so the rows stay readable.
TEST(CliIdentify, TheTablesWarningsAreNotesBelowIt) {
  TempDir dir;
  // A Table 2 soil identified on the formulas' scale: a poor fit in every window.
  Case c = truth(30e6);
  const SoilCoefficients k = table2_coefficients(30e6);
  c.soil.input = SoilInput::coefficients;
  c.soil.ksh = k.ksh;
  c.soil.ksv = k.ksv;
  c.soil.csh = k.csh;
  c.soil.csv = k.csv;
  write_record(dir / "r.csv", {c}, 1.2);
  const Outcome o = run({"identify", dir / "r.csv", "--window", "20", "--no-profile", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err << o.out;
  std::istringstream lines(o.out);
  std::size_t widest = 0, rows = 0;
  bool in_notes = false;
  std::vector<std::string> notes;
  for (std::string line; std::getline(lines, line);) {
    if (line == "notes:") in_notes = true;
    if (in_notes && line.rfind("[", 0) == 0) notes.push_back(line);
    if (!in_notes) widest = std::max(widest, line.size());
    rows += !in_notes && line.find("WARNING, note [") != std::string::npos;
  }
  EXPECT_GE(rows, 2u) << o.out;
  EXPECT_LT(widest, 200u) << o.out;
  // Every window has the same cause, each with its own numbers (its reduced chi^2): one note.
  ASSERT_EQ(notes.size(), 1u) << o.out;
  const std::string windows =
      "[1] windows 0-" + std::to_string(rows - 1) + " (the numbers of window 0): WARNING: poor fit";
  EXPECT_EQ(notes.front().rfind(windows, 0), 0u) << notes.front();
  EXPECT_NE(notes.front().find("--soil-scale table2"), std::string::npos) << notes.front();
}

// Standard output carries one thing, as run's: --csv - printed the CSV and then the table after
// it (a file no CSV reader parses), --csv - --geojson - both and the table.
TEST(CliIdentify, StandardOutputCarriesOneThing) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  Outcome o =
      run({"identify", dir / "r.csv", "--window", "10", "--no-profile", "-q", "--csv", "-"});
  ASSERT_EQ(o.code, 0) << o.err;
  std::istringstream rows(o.out);
  std::string header;
  std::getline(rows, header);
  EXPECT_EQ(header.rfind("window[-],", 0), 0u) << header;
  std::size_t n = 0;
  for (std::string line; std::getline(rows, line); ++n) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','),
              std::count(header.begin(), header.end(), ','))
        << line;
  }
  EXPECT_GE(n, 2u);
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--geojson", "-"}, {"--json", "-"}, {"--format", "table"}}) {
    std::vector<std::string> args = {"identify", dir / "r.csv", "--csv", "-"};
    args.insert(args.end(), extra.begin(), extra.end());
    o = run(args);
    EXPECT_EQ(o.code, 2) << extra[0] << ": " << o.err;
    EXPECT_NE(o.err.find("--csv - and " + extra[0] + " " + extra[1] +
                         " would both write to standard output"),
              std::string::npos)
        << o.err;
  }
}

// A record shorter than the default window (the two periods the paper evaluates, as another
// implementation writes them): identified whole, as one window, with a note; the same record
// with that window given explicitly is refused, as is any record shorter than its --window.
TEST(CliIdentify, ARecordShorterThanTheDefaultWindowIsIdentifiedWhole) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.3);  // about 12 periods
  const Outcome o = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err << o.out;
  EXPECT_NE(o.err.find("fewer than the default window of 40: identified whole"), std::string::npos)
      << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["window_periods"].get<double>(), 0.0);
  ASSERT_EQ(j["windows"].size(), 1u);
  EXPECT_TRUE(j["windows"][0]["valid"].get<bool>()) << o.out;
  const Outcome whole =
      run({"identify", dir / "r.csv", "--no-profile", "--format", "json", "--window", "0"});
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("identified whole"), std::string::npos) << whole.err;
  EXPECT_EQ(nlohmann::json::parse(whole.out)["windows"], j["windows"]);
  for (const char* window : {"40", "20"}) {
    const Outcome refused = run({"identify", dir / "r.csv", "--no-profile", "--window", window});
    EXPECT_EQ(refused.code, 2) << window << refused.err;
    EXPECT_NE(refused.err.find("must span at least one window"), std::string::npos) << refused.err;
  }
}

// A logger's file in field conventions: time in ms, accelerations in g, the z axis pointing up and
// gravity kept (+1 g at rest). Read by default, the z column is taken as pointing up (its mean
// says so) and the soil is identified as from the model's own record; read as pointing down it is
// not (the poor-fit diagnosis names the axis).
TEST(CliIdentify, ALoggersFileInGWithZUpAndGravityIsReadAsPointingUp) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  write_logger_file(dir / "r.csv", dir / "logger.csv", "Time [ms];Acc X [g];Acc Z [g]", ';', true,
                    1.0);
  const Outcome model = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
  const Outcome logger = run({"identify", dir / "logger.csv", "--no-profile", "--format", "json"});
  ASSERT_EQ(model.code, 0) << model.err;
  ASSERT_EQ(logger.code, 0) << logger.err;
  EXPECT_NE(logger.err.find("read as pointing up (negated)"), std::string::npos) << logger.err;
  const nlohmann::json a = nlohmann::json::parse(model.out)["windows"][0];
  const nlohmann::json b = nlohmann::json::parse(logger.out)["windows"][0];
  EXPECT_EQ(nlohmann::json::parse(logger.out)["reading"]["z_positive"], "up");
  ASSERT_TRUE(b["valid"].get<bool>()) << logger.out;
  EXPECT_NEAR(b["estimates"][0]["value"].get<double>() / a["estimates"][0]["value"].get<double>(),
              1.0, 1e-4);
  const Outcome as_down = run(
      {"identify", dir / "logger.csv", "--no-profile", "--format", "json", "--z-positive", "down"});
  EXPECT_NE(as_down.err.find("give --z-positive up or auto"), std::string::npos) << as_down.err;
  EXPECT_NE(as_down.out.find("the record's z axis points up"), std::string::npos) << as_down.out;
}

// The same logger's file with gravity removed (an AC-coupled channel): nothing in the column
// tells its axis, so the fit does: the window is fitted with z_M'' negated, says so, and gives
// the model's own record's G; given as down, it is fitted as read and diagnosed.
TEST(CliIdentify, AZUpRecordWithoutGravityIsFittedNegatedAndSaysSo) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  write_logger_file(dir / "r.csv", dir / "logger.csv", "Time [ms];Acc X [g];Acc Z [g]", ';', true,
                    0.0);
  const Outcome model = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
  const Outcome logger = run(
      {"identify", dir / "logger.csv", "--no-profile", "--format", "json", "--csv", dir / "G.csv"});
  ASSERT_EQ(model.code, 0) << model.err;
  ASSERT_EQ(logger.code, 0) << logger.err;
  const nlohmann::json a = nlohmann::json::parse(model.out)["windows"][0];
  const nlohmann::json j = nlohmann::json::parse(logger.out);
  const nlohmann::json& b = j["windows"][0];
  EXPECT_EQ(j["reading"]["z_positive"], "down");
  EXPECT_TRUE(j["reading"]["z_open"].get<bool>());
  EXPECT_FALSE(a["z_negated"].get<bool>());  // the model's own record: as read
  ASSERT_TRUE(b["valid"].get<bool>()) << logger.out;
  EXPECT_TRUE(b["z_negated"].get<bool>());
  EXPECT_NEAR(b["estimates"][0]["value"].get<double>() / a["estimates"][0]["value"].get<double>(),
              1.0, 1e-4);
  EXPECT_NE(b["warnings"][0].get<std::string>().find("z_M'' fitted negated"), std::string::npos)
      << b["warnings"];
  EXPECT_EQ(column(slurp(dir / "G.csv"), "z_negated"), std::vector<double>{1.0});
  const Outcome as_down = run(
      {"identify", dir / "logger.csv", "--no-profile", "--format", "json", "--z-positive", "down"});
  ASSERT_EQ(as_down.code, 0) << as_down.err;
  const nlohmann::json c = nlohmann::json::parse(as_down.out)["windows"][0];
  EXPECT_FALSE(c["z_negated"].get<bool>());
  EXPECT_GT(c["reduced_chi2"].get<double>(), 4.0);
  EXPECT_NE(as_down.out.find("the record's z axis points up"), std::string::npos) << as_down.out;
}

// A logger's columns in g without a unit, z up, gravity removed: nothing in the file tells the
// unit or the axis, so the fit does (read_in_g, z_negated), and gives the model's own record's
// G; with gravity kept, the reader itself reads the columns in g and the axis up.
TEST(CliIdentify, ColumnsInGWithoutAUnitAreFittedInG) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  for (const double gravity : {0.0, 1.0}) {
    SCOPED_TRACE(gravity);
    write_logger_file(dir / "r.csv", dir / "logger.csv", "t,ax,az", ',', false, gravity);
    const Outcome model = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
    const Outcome logger =
        run({"identify", dir / "logger.csv", "--no-profile", "--format", "json"});
    ASSERT_EQ(model.code, 0) << model.err;
    ASSERT_EQ(logger.code, 0) << logger.err;
    const nlohmann::json j = nlohmann::json::parse(logger.out);
    const nlohmann::json& b = j["windows"][0];
    const double G = nlohmann::json::parse(model.out)["windows"][0]["estimates"][0]["value"];
    ASSERT_TRUE(b["valid"].get<bool>()) << logger.out;
    EXPECT_NEAR(b["estimates"][0]["value"].get<double>() / G, 1.0, 1e-4);
    EXPECT_EQ(j["reading"]["units_open"].get<bool>(), gravity == 0.0);
    EXPECT_EQ(b["read_in_g"].get<bool>(), gravity == 0.0);
    EXPECT_EQ(b["z_negated"].get<bool>(), gravity == 0.0);
    if (gravity != 0.0) {
      EXPECT_NE(logger.err.find("is gravity in g"), std::string::npos) << logger.err;
    }
  }
}

// A record read (with notes on how) that the analysis then refuses (at --rate 1 no excitation
// frequency can be searched): the refusal is one line on stderr, exit code 2, as every refusal;
// the notes on the reading come only once nothing can fail (found by the fuzz suite, seed 112).
TEST(CliIdentify, ARefusalAfterTheRecordIsReadIsOneLine) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"analyze", dir / "r.csv", "--rate", "1"},
        {"identify", dir / "r.csv", "--rate", "1"},
        {"calibrate", dir / "r.csv@25", "--rate", "1"}}) {
    SCOPED_TRACE(args[0]);
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 2) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_EQ(o.err.rfind("oscidrum: error: ", 0), 0u) << o.err;
  }
  // Read and analysed: the notes are said.
  const Outcome ok = run({"analyze", dir / "r.csv", "--rate", "1000"});
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.err.find("oscidrum: record: t: from the row number at --rate 1000 Hz"),
            std::string::npos)
      << ok.err;
}

// A record written by write_record (t, x_M'', z_M'' in m/s^2), rewritten under `header` with
// each row made by row(k, t, x, z) (k counts the rows from 0): a logger's conventions.
void rewrite_record(const std::filesystem::path& from, const std::filesystem::path& to,
                    const std::string& header,
                    const std::function<std::string(int, double, double, double)>& row) {
  std::ifstream in(from);
  std::ofstream out(to);
  out << header << "\n";
  std::string line;
  std::getline(in, line);  // the header
  for (int k = 0; std::getline(in, line); ++k) {
    double t = 0, x = 0, z = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &x, &z), 3) << line;
    out << row(k, t, x, z);
  }
}

// "t,v1,v2,...\n", t to the microsecond and the values to 9 digits.
std::string format_row(double t, std::initializer_list<double> values) {
  char cell[40];
  std::snprintf(cell, sizeof cell, "%.6f", t);
  std::string out = cell;
  for (double v : values) {
    std::snprintf(cell, sizeof cell, ",%.9g", v);
    out += cell;
  }
  return out + "\n";
}

// A 2 kHz record whose time stamps were rounded down to the millisecond (pairs of rows share a
// time): each pair was averaged into one sample at the wrong time, and G came out 1 % high with
// intervals missing the truth (reduced chi^2 17 at 2 % noise). The rows of each stamp are spread
// to the next: the same G as the record with its exact times.
TEST(CliIdentify, ACoarseClockIsSpreadBetweenItsStamps) {
  TempDir dir;
  // 1 % noise: the clock's error, not the noise, would decide the fit.
  SyntheticRecord sr;
  sr.duration = 0.6;
  sr.sample_rate = 2000;
  sr.noise = 0.01;
  sr.seed = 4;
  const RecordSamples r = synthetic_record({truth(17.3e6)}, sr);
  {
    std::ofstream exact(dir / "exact.csv"), ms(dir / "ms.csv");
    exact << "t,ddx_M,ddz_M\n";
    ms << "t,ddx_M,ddz_M\n";
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      exact << format_row(r.t[i], {r.ddx_M[i], r.ddz_M[i]});
      ms << format_row(std::floor(r.t[i] * 1e3 + 1e-6) / 1e3, {r.ddx_M[i], r.ddz_M[i]});
    }
  }
  const Outcome a = run({"identify", dir / "exact.csv", "--no-profile", "--format", "json"});
  const Outcome b = run({"identify", dir / "ms.csv", "--no-profile", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NE(b.err.find("so the rows of each stamp are spread evenly to the next stamp"),
            std::string::npos)
      << b.err;
  const auto G = [](const Outcome& o) {
    return nlohmann::json::parse(o.out)["windows"][0]["estimates"][0]["value"].get<double>();
  };
  EXPECT_NEAR(G(b) / G(a), 1.0, 1e-6);
}

// The warning about windows too short to check for a change within them counts the windows
// identify reports as valid: a sliver of 30 samples after a logger's pause passed the record's
// gates (unchecked) but was too short for the identification's fit, and the warning said "1 of
// N valid windows" of a pass whose N - 1 valid windows were all checked.
TEST(CliIdentify, TheUncheckedWindowsWarningCountsTheValidEstimates) {
  TempDir dir;
  SyntheticRecord sr;
  sr.sample_rate = 1000;
  sr.noise = 0.02;
  sr.seed = 6;
  sr.duration = 2.5;
  const RecordSamples a = synthetic_record({truth(17.3e6)}, sr);
  // The logger resumes 30 ms before the end of the sixth window (40 periods each).
  const double W = 40.0 / kF;
  sr.start = 6.0 * W - 0.030;
  sr.duration = 3.0;
  sr.seed = 7;
  const RecordSamples b = synthetic_record({truth(17.3e6)}, sr);
  {
    std::ofstream out(dir / "pause.csv");
    out << "t,ddx_M,ddz_M\n";
    for (const RecordSamples* r : {&a, &b})
      for (std::size_t i = 0; i < r->t.size(); ++i)
        out << format_row(r->t[i], {r->ddx_M[i], r->ddz_M[i]});
  }
  const Outcome o = run({"identify", dir / "pause.csv", "--no-profile", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<double> t_start = column(o.out, "t_start");
  const std::vector<double> valid = column(o.out, "valid");
  const std::vector<double> change = column(o.out, "change");
  ASSERT_EQ(valid.size(), change.size());
  std::size_t n_valid = 0, unchecked = 0;
  for (std::size_t i = 0; i < valid.size(); ++i) {
    n_valid += valid[i] == 1.0 ? 1 : 0;
    unchecked += valid[i] == 1.0 && std::isnan(change[i]) ? 1 : 0;
  }
  ASSERT_GE(n_valid, 3u) << o.out;
  const std::string warning = "valid windows are too short to check";
  if (unchecked == 0)
    EXPECT_EQ(o.err.find(warning), std::string::npos) << o.err;
  else
    EXPECT_NE(
        o.err.find(std::to_string(unchecked) + " of " + std::to_string(n_valid) + " " + warning),
        std::string::npos)
        << o.err;
  // The sliver is there, and not valid.
  EXPECT_NE(o.out.find("samples are too few for"), std::string::npos) << o.out;
}

// G on the formulas scale (the default) goes through Appendix B, where the soil's nu and rho and
// the drum width b take effect: --nu was refused as having "no effect while soil.input =
// table2" (the default case's input), and calibrate's --b alike. On the table2 scale it has none.
TEST(CliIdentify, TheFormulasScaleTakesNuRhoAndTheDrumWidth) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  const auto G = [](const Outcome& o) {
    return nlohmann::json::parse(o.out)["windows"][0]["estimates"][0]["value"].get<double>();
  };
  const Outcome plain = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
  const Outcome same =
      run({"identify", dir / "r.csv", "--no-profile", "--format", "json", "--nu", "0.3"});
  const Outcome other =
      run({"identify", dir / "r.csv", "--no-profile", "--format", "json", "--nu", "0.35"});
  ASSERT_EQ(plain.code, 0) << plain.err;
  ASSERT_EQ(same.code, 0) << same.err;
  ASSERT_EQ(other.code, 0) << other.err;
  EXPECT_EQ(G(same), G(plain));  // the default nu
  EXPECT_GT(std::abs(G(other) / G(plain) - 1.0), 1e-3);
  const Outcome table2 =
      run({"identify", dir / "r.csv", "--no-profile", "--soil-scale", "table2", "--nu", "0.35"});
  EXPECT_EQ(table2.code, 2) << table2.err;
  EXPECT_NE(table2.err.find("soil.nu has no effect"), std::string::npos) << table2.err;
  const Outcome calibrate =
      run({"calibrate", std::string(dir / "r.csv") + "@17.3", "--fit", "roller.M0", "--b", "2.1",
           "--no-profile", "--out", dir / "cal.toml"});
  EXPECT_EQ(calibrate.code, 0) << calibrate.err;
  EXPECT_NE(slurp(dir / "cal.toml").find("input = \"modulus\""), std::string::npos);
}

// A three-axis logger mounted with y vertical (up, gravity kept) and z along the drum's axle (a
// small lateral signal, no gravity), in g: the reader takes y as the vertical and says so, and
// identify gives the model's own record's G.
TEST(CliIdentify, AThreeAxisLoggerMountedWithYVerticalIsIdentified) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  rewrite_record(dir / "r.csv", dir / "logger.csv", "Time [s],Acc X [g],Acc Y [g],Acc Z [g]",
                 [](int k, double t, double x, double z) {
                   return format_row(t, {x / kStandardGravity, 1.0 - z / kStandardGravity,
                                         0.01 * std::sin(0.37 * k)});
                 });
  const Outcome model = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
  const Outcome logger = run({"identify", dir / "logger.csv", "--no-profile", "--format", "json"});
  ASSERT_EQ(model.code, 0) << model.err;
  ASSERT_EQ(logger.code, 0) << logger.err;
  EXPECT_NE(logger.err.find("the y column 'Acc Y [g]' is read as the vertical"), std::string::npos)
      << logger.err;
  const nlohmann::json j = nlohmann::json::parse(logger.out);
  EXPECT_EQ(j["reading"]["z_positive"], "up");
  const nlohmann::json& b = j["windows"][0];
  ASSERT_TRUE(b["valid"].get<bool>()) << logger.out;
  EXPECT_NEAR(
      b["estimates"][0]["value"].get<double>() /
          nlohmann::json::parse(model.out)["windows"][0]["estimates"][0]["value"].get<double>(),
      1.0, 1e-4);
  // --z-col reads the lateral channel as asked: no vertical motion there, no valid fit.
  const Outcome as_z = run(
      {"identify", dir / "logger.csv", "--no-profile", "--format", "json", "--z-col", "Acc Z [g]"});
  EXPECT_EQ(as_z.err.find("is read as the vertical"), std::string::npos) << as_z.err;
  EXPECT_EQ(as_z.code, 1) << as_z.err;  // no window identified
  EXPECT_FALSE(nlohmann::json::parse(as_z.out)["windows"][0]["valid"].get<bool>()) << as_z.out;
}

// A logger mounted with x vertical (gravity in m/s^2 in x's mean, y the direction of travel, z
// along the axle), and a sensor's y and z channels without x: identified as the model's own
// record is.
TEST(CliIdentify, ALoggerMountedWithXVerticalAndAYZSensorAreIdentified) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6);
  rewrite_record(dir / "r.csv", dir / "x_vertical.csv",
                 "Time [s],Acc X [m/s^2],Acc Y [m/s^2],Acc Z [m/s^2]",
                 [](int k, double t, double x, double z) {
                   return format_row(t, {kStandardGravity - z, x, 0.05 * std::sin(0.37 * k)});
                 });
  rewrite_record(dir / "r.csv", dir / "yz.csv", "t,ay,az", [](int, double t, double x, double z) {
    return format_row(t, {x, z});
  });
  const Outcome model = run({"identify", dir / "r.csv", "--no-profile", "--format", "json"});
  ASSERT_EQ(model.code, 0) << model.err;
  const nlohmann::json m = nlohmann::json::parse(model.out);
  const double G = m["windows"][0]["estimates"][0]["value"].get<double>();
  for (const char* file : {"x_vertical.csv", "yz.csv"}) {
    SCOPED_TRACE(file);
    const Outcome logger = run({"identify", dir / file, "--no-profile", "--format", "json"});
    ASSERT_EQ(logger.code, 0) << logger.err;
    EXPECT_NE(logger.err.find(std::string(file) == "yz.csv"
                                  ? "the y column 'ay' is read as the horizontal"
                                  : "the x column 'Acc X [m/s^2]' is read as the vertical"),
              std::string::npos)
        << logger.err;
    const nlohmann::json j = nlohmann::json::parse(logger.out);
    const nlohmann::json& b = j["windows"][0];
    ASSERT_TRUE(b["valid"].get<bool>()) << logger.out;
    EXPECT_NEAR(b["estimates"][0]["value"].get<double>() / G, 1.0, 1e-4);
  }
}

// A logger's clock in s since 1970: the tables tell the windows apart (to the millisecond; with
// five significant digits every window was 1.7646e+09).
TEST(CliIdentify, WindowTimesOfALoggersClockAreToTheMillisecond) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 1.2, 1000, 1764630000.0);
  for (const char* command : {"analyze", "identify"}) {
    SCOPED_TRACE(command);
    std::vector<std::string> args = {command, dir / "r.csv", "--window", "20"};
    if (std::string(command) == "identify") args.push_back("--no-profile");
    const Outcome o = run(args);
    ASSERT_EQ(o.code, 0) << o.err << o.out;
    EXPECT_EQ(o.out.find("1.7646e+09"), std::string::npos) << o.out;
    EXPECT_NE(o.out.find("  1764630000."), std::string::npos) << o.out;
  }
}

TEST(CliIdentify, PassPrintsAndWritesTheGProfileWithItsBandAndPlots) {
  TempDir dir;
  // Two soils along the pass: G = 17.3 for 0.8 s, then 8.1 MN/m^2.
  write_record(dir / "pass.csv", {truth(17.3e6), truth(8.1e6)}, 1.6);
  const Outcome o =
      run({"identify", dir / "pass.csv", "--window", "20", "--hop", "31.6", "--speed-col", "v",
           "--csv", dir / "G.csv", "--plot", dir / "plots", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err << o.out;
  EXPECT_NE(o.out.find("G [MN/m^2]"), std::string::npos) << o.out;
  // Windows at 0 and 31.6 periods, and one ending with the record (its last 20 periods).
  EXPECT_NE(o.out.find("3 windows, 3 identified"), std::string::npos) << o.out;
  const std::string csv = slurp(dir / "G.csv");
  EXPECT_EQ(
      csv.rfind("window[-],t_start[s],t_end[s],t[s],position[m],f[Hz],change[-],valid[-],reason[-],"
                "G[Pa],G_u[Pa],G_lo[Pa],G_hi[Pa],soil_scale[-],tau[s]",
                0),
      0u)
      << csv;
  const std::vector<double> G = column(csv, "G"), lo = column(csv, "G_lo"),
                            hi = column(csv, "G_hi"), x = column(csv, "position"),
                            t = column(csv, "t");
  ASSERT_EQ(G.size(), 3u);
  for (double change : column(csv, "change")) EXPECT_LT(std::abs(change), 0.05);  // the gate's
  const double expected[3] = {17.3e6, 8.1e6, 8.1e6};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(G[k] / expected[k], 1.0, 0.03) << k;
    EXPECT_LE(lo[k], expected[k]) << k;
    EXPECT_GE(hi[k], expected[k]) << k;
    EXPECT_NEAR(x[k], 0.8 * t[k], 1e-6);
  }
  for (const char* png :
       {"pass_G.png", "fit_accelerations.png", "fit_spectra.png", "fit_figure.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / ("plots/" + std::string(png)))) << png << o.err;
}

// A record sampled in step with the excitation (64 samples a period, as an encoder-triggered
// logger samples), in g with z up as such loggers write: every window compares the model sampled
// at the record's times (column model_sampled), says so once, and recovers G, and analyze says
// its harmonics are aliased; the same soil at 1 kHz does neither.
TEST(CliIdentify, ARecordSampledInStepComparesTheModelSampled) {
  TempDir dir;
  for (const double rate : {64 * kF, 1000.0}) {
    SyntheticRecord so;
    so.duration = 2.1;
    so.sample_rate = rate;
    so.noise = 0.002;
    so.seed = 9;
    const RecordSamples r = synthetic_record({truth(30e6)}, so);
    std::ofstream out(dir / "in_step.csv");
    out << "time,acc_x_g,acc_z_g\n";
    char line[160];
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      std::snprintf(line, sizeof line, "%.9f,%.9g,%.9g\n", r.t[i], r.ddx_M[i] / kStandardGravity,
                    -r.ddz_M[i] / kStandardGravity);
      out << line;
    }
    out.close();
    const Outcome o = run({"identify", dir / "in_step.csv", "--window", "40", "--units", "g",
                           "--z-positive", "up", "--format", "csv"});
    ASSERT_EQ(o.code, 0) << o.err << o.out;
    const std::vector<double> G = column(o.out, "G"), sampled = column(o.out, "model_sampled");
    ASSERT_GE(G.size(), 2u) << o.out;  // (and one ending with the record)
    for (std::size_t k = 0; k < G.size(); ++k) {
      EXPECT_NEAR(G[k] / 30e6, 1.0, 2e-3) << rate << " window " << k;
      EXPECT_EQ(sampled[k], rate == 1000.0 ? 0.0 : 1.0) << rate << " window " << k;
    }
    EXPECT_EQ(o.err.find("sampled in step") != std::string::npos, rate != 1000.0) << o.err;
    // analyze says the harmonics it reports are aliased.
    const Outcome a = run({"analyze", dir / "in_step.csv", "--units", "g", "--z-positive", "up"});
    ASSERT_EQ(a.code, 0) << a.err << a.out;
    EXPECT_EQ(a.err.find("sampled in step with the excitation") != std::string::npos,
              rate != 1000.0)
        << a.err;
  }
}

// The pass as a map: with GNSS columns, --geojson writes one feature per window, its point at the
// window's centre (the columns interpolated in time) and G with its interval in MN/m^2.
TEST(CliIdentify, GeoJsonPutsEachWindowOnTheMap) {
  TempDir dir;
  write_record(dir / "pass.csv", {truth(17.3e6)}, 1.6);
  {  // the same record with latitude and longitude: moving north at 1e-5 deg/s
    std::ifstream in(dir / "pass.csv");
    std::ofstream out(dir / "gnss.csv");
    std::string line;
    std::getline(in, line);
    out << "t,ddx_M,ddz_M,v,lat,lon\n";
    char extra[64];
    while (std::getline(in, line)) {
      const double t = std::strtod(line.c_str(), nullptr);
      std::snprintf(extra, sizeof extra, ",%.12f,16.37", 48.2 + 1e-5 * t);
      out << line << extra << "\n";
    }
  }
  const Outcome o = run({"identify", dir / "gnss.csv", "--window", "20", "--lat-col", "lat",
                         "--lon-col", "lon", "--geojson", dir / "pass.geojson", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const auto j = nlohmann::json::parse(slurp(dir / "pass.geojson"));
  EXPECT_EQ(j["type"], "FeatureCollection");
  ASSERT_GE(j["features"].size(), 2u);
  for (const auto& f : j["features"]) {
    EXPECT_EQ(f["type"], "Feature");
    ASSERT_EQ(f["geometry"]["type"], "Point");
    const auto& p = f["properties"];
    const double t = p["t"].get<double>();
    EXPECT_NEAR(f["geometry"]["coordinates"][0].get<double>(), 16.37, 1e-12);
    EXPECT_NEAR(f["geometry"]["coordinates"][1].get<double>(), 48.2 + 1e-5 * t, 1e-10);
    EXPECT_TRUE(p["valid"].get<bool>());
    EXPECT_EQ(p["G_unit"], "MN/m^2");
    EXPECT_NEAR(p["G"].get<double>(), 17.3, 0.03 * 17.3);
    EXPECT_LE(p["G_lower"].get<double>(), p["G"].get<double>());
    EXPECT_GE(p["G_upper"].get<double>(), p["G"].get<double>());
    EXPECT_TRUE(p["warnings"].is_array());
  }
  // Without GNSS columns the features have no geometry; one of the two columns is an error.
  const Outcome plain =
      run({"identify", dir / "pass.csv", "--geojson", dir / "plain.geojson", "--quiet"});
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_TRUE(
      nlohmann::json::parse(slurp(dir / "plain.geojson"))["features"][0]["geometry"].is_null());
  const Outcome half = run({"identify", dir / "gnss.csv", "--lat-col", "lat"});
  EXPECT_EQ(half.code, 2);
  EXPECT_NE(half.err.find("give both --lat-col and --lon-col"), std::string::npos) << half.err;
  // Projected coordinates [m]: easting and northing at each window's centre as properties, and
  // the position the path length along them (0.3 m/s east and 0.4 m/s north: 0.5 m/s along the
  // track).
  {
    std::ifstream in(dir / "pass.csv");
    std::ofstream out(dir / "utm.csv");
    std::string line;
    std::getline(in, line);
    out << "t,ddx_M,ddz_M,v,E,N\n";
    char extra[96];
    while (std::getline(in, line)) {
      const double t = std::strtod(line.c_str(), nullptr);
      std::snprintf(extra, sizeof extra, ",%.9f,%.9f", 600000.0 + 0.3 * t, 5340000.0 + 0.4 * t);
      out << line << extra << "\n";
    }
  }
  const Outcome utm = run({"identify", dir / "utm.csv", "--window", "20", "--east-col", "E",
                           "--north-col", "N", "--geojson", dir / "utm.geojson", "--quiet"});
  ASSERT_EQ(utm.code, 0) << utm.err;
  const auto projected = nlohmann::json::parse(slurp(dir / "utm.geojson"));  // kept alive
  for (const auto& f : projected["features"]) {
    const auto& p = f["properties"];
    const double t = p["t"].get<double>();  // the record starts at t = 0
    EXPECT_NEAR(p["easting"].get<double>(), 600000.0 + 0.3 * t, 1e-6);
    EXPECT_NEAR(p["northing"].get<double>(), 5340000.0 + 0.4 * t, 1e-6);
    EXPECT_NEAR(p["position"].get<double>(), 0.5 * t, 1e-6);
    EXPECT_TRUE(f["geometry"].is_null());
  }
}

// The fit plots show the fit: on a record whose clock starts at 1.2345 s, the model drawn in
// fit_model.csv and at the samples in fit_measured.csv differs from the samples by the noise
// (5 % of the peak), as the fit's residual says, not by a curve shifted in time.
TEST(CliIdentify, TheFitPlotsModelLiesOnTheSamples) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6, 1500, 1.2345);
  const Outcome o = run({"identify", dir / "r.csv", "--window", "0", "--plot", dir / "plots",
                         "--format", "json", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::string measured = slurp(dir / "plots/fit_measured.csv"),
                    model = slurp(dir / "plots/fit_model.csv");
  const std::vector<double> t = column(measured, "t"), x = column(measured, "ddx_M"),
                            fit = column(measured, "ddx_M_fit"), tm = column(model, "t"),
                            xm = column(model, "ddx_M");
  ASSERT_GT(t.size(), 50u);
  EXPECT_NEAR(t.front(), 1.2345, 1e-6);
  double s2 = 0, peak = 0, s2_curve = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    s2 += (x[i] - fit[i]) * (x[i] - fit[i]);
    peak = std::max(peak, std::abs(fit[i]));
    // The drawn curve, linearly interpolated at the sample, is the model at the sample.
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(tm.begin(), tm.end(), t[i]) - tm.begin());
    if (k == 0 || k >= tm.size()) continue;
    const double w = (t[i] - tm[k - 1]) / (tm[k] - tm[k - 1]);
    const double curve = (1 - w) * xm[k - 1] + w * xm[k];
    s2_curve += (curve - fit[i]) * (curve - fit[i]);
  }
  const double n = static_cast<double>(t.size());
  EXPECT_NEAR(std::sqrt(s2 / n) / (0.05 * peak), 1.0, 0.3);
  EXPECT_LT(std::sqrt(s2_curve / n), 0.01 * peak);
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_NEAR(std::sqrt(s2 / n), j["windows"][0]["noise_x"].get<double>(), 0.3 * 0.05 * peak);
}

// The soil under a vibratory drum (docs/model.md section 14) from its record: 60 steady periods
// of examples/vibratory.toml on the Table 2 soil of G = 40 MN/m^2 (partial uplift), identified
// with the same roller on the Table 2 scale: G comes back (seen: 40.00009 MN/m^2, standard
// uncertainty 0.00002 MN/m^2).
TEST(CliIdentify, TheSoilUnderAVibratoryDrum) {
  TempDir dir;
  const std::string vibratory = std::string(OSCIDRUM_SOURCE_DIR) + "/examples/vibratory.toml";
  const Outcome r = run({"run", vibratory, "--set", "soil.table2_G=40e6", "--set",
                         "numerics.output_periods=60", "--csv", dir / "r.csv", "-q"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Outcome o = run({"identify", dir / "r.csv", "--case", vibratory, "--window", "0",
                         "--soil-scale", "table2", "--format", "json", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  const nlohmann::json& e = j["windows"][0]["estimates"][0];
  EXPECT_EQ(e["name"], "G");
  EXPECT_NEAR(e["value"].get<double>() / 40e6, 1.0, 1e-3);
  EXPECT_LE(e["lower"].get<double>(), 40e6 * (1.0 + 1e-4));
  EXPECT_GE(e["upper"].get<double>(), 40e6 * (1.0 - 1e-4));
}

TEST(CliIdentify, FromTheMetricsOfAnalyze) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6, 1500);
  const Outcome a = run({"analyze", dir / "r.csv", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  std::ofstream(dir / "r.json") << a.out;
  const Outcome o = run({"identify", "--metrics", dir / "r.json", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["schema"], "oscidrum-identify/1");
  const nlohmann::json& e = j["windows"][0]["estimates"][0];
  EXPECT_EQ(e["name"], "G");
  EXPECT_NEAR(e["value"].get<double>() / 17.3e6, 1.0, 0.03);
  EXPECT_LE(e["lower"].get<double>(), 17.3e6);
  EXPECT_GE(e["upper"].get<double>(), 17.3e6);
  // The window's times are analyze's (they were 0: lost on the way).
  const nlohmann::json analyzed = nlohmann::json::parse(a.out);
  for (const char* key : {"t_start", "t_end", "t"}) {
    ASSERT_TRUE(analyzed[key].is_number()) << key;
    EXPECT_EQ(j["windows"][0][key], analyzed[key]) << key;
  }
  EXPECT_GT(analyzed["t_end"].get<double>(), 0.5);
}

// The record's reading flags with --metrics were accepted without effect (and the advice of a
// warning, "read it with --z-positive up", changed nothing): refused, naming them; the advice
// points to analyze, which measured the metrics.
TEST(CliIdentify, TheMetricsOfAnalyzeRefuseTheReadingFlags) {
  TempDir dir;
  write_record(dir / "r.csv", {truth(17.3e6)}, 0.6, 1500);
  const Outcome a = run({"analyze", dir / "r.csv", "--format", "json"});
  ASSERT_EQ(a.code, 0) << a.err;
  std::ofstream(dir / "r.json") << a.out;
  const Outcome o = run({"identify", "--metrics", dir / "r.json", "--z-positive", "up", "--f", "45",
                         "--window", "10", "--no-profile"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("--z-positive, --f, --window"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("oscidrum analyze"), std::string::npos) << o.err;
  // z_M'' negated in the metrics: the warning sends the user to analyze.
  nlohmann::json j = nlohmann::json::parse(a.out);
  for (nlohmann::json& h : j["ddz_harmonics"])
    if (h["n"].get<int>() > 0) h["phase"] = h["phase"].get<double>() + M_PI;
  std::ofstream(dir / "up.json") << j.dump();
  const Outcome u = run({"identify", "--metrics", dir / "up.json", "--no-profile", "--quiet"});
  EXPECT_NE(u.out.find("analyze the record again with --z-positive up"), std::string::npos)
      << u.out << u.err;
}

// A drum that rolls without slipping: --fit-mu must say that mu is not identifiable (and
// still recover G), with the upper limit of mu open (null in the JSON), quickly.
TEST(CliIdentify, PureRollingWithFitMuWarnsThatMuIsNotIdentifiable) {
  TempDir dir;
  Case c = truth(25.3e6);
  c.contact.pure_rolling = true;
  write_record(dir / "r.csv", {c}, 0.6);
  const Outcome o = run({"identify", dir / "r.csv", "--window", "0", "--pure-rolling", "--fit-mu",
                         "--format", "json", "--quiet"});
  ASSERT_EQ(o.code, 0) << o.err;
  const nlohmann::json j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["model_method"], "shooting");
  const nlohmann::json& w = j["windows"][0];
  EXPECT_NEAR(w["estimates"][0]["value"].get<double>() / 25.3e6, 1.0, 0.03);
  const nlohmann::json& mu = w["estimates"][1];
  EXPECT_EQ(mu["name"], "mu");
  EXPECT_TRUE(mu["upper_open"].get<bool>());
  EXPECT_TRUE(mu["upper"].is_null()) << mu;
  EXPECT_NE(w["warnings"].dump().find("mu is not identifiable"), std::string::npos) << w;
}

TEST(CliIdentify, NothingIdentifiableExitsOneWithTheReason) {
  TempDir dir;
  {
    std::ofstream out(dir / "noise.csv");
    out << "t,ddx_M,ddz_M\n";
    std::mt19937 rng(2);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int i = 0; i < 1200; ++i) out << i * 1e-3 << "," << g(rng) << "," << g(rng) << "\n";
  }
  const Outcome o = run({"identify", dir / "noise.csv", "--quiet"});
  EXPECT_EQ(o.code, 1) << o.err;
  EXPECT_NE(o.err.find("no window could be identified"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("fit residual"), std::string::npos) << o.err;
}

// Each defect of a record gives its documented flag and exit code 1 (docs/cli.md).
TEST(CliAnalyze, DefectiveRecordsGiveTheirFlagAndExitOne) {
  TempDir dir;
  SyntheticRecord so;
  so.duration = 0.5;
  so.noise = 0.02;
  const RecordSamples r = synthetic_record({truth(17.3e6)}, so);
  auto write = [&](const std::string& name, auto&& edit) {
    std::ofstream out(dir / name);
    out << "t,ddx_M,ddz_M\n";
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      double t = r.t[i], x = r.ddx_M[i], z = r.ddz_M[i];
      if (!edit(t, x, z)) continue;
      out << t << "," << x << "," << z << "\n";
    }
  };
  write("clipped.csv", [](double&, double& x, double&) {
    x = std::clamp(x, -9.0, 9.0);
    return true;
  });
  write("gap.csv", [](double& t, double&, double&) { return t < 0.2 || t > 0.23; });
  write("scaled_time.csv", [](double& t, double&, double&) {  // a 30.3 Hz record
    t *= kF / 30.3;
    return true;
  });
  struct Case {
    std::vector<std::string> args;
    std::string flag;
  };
  for (const Case& c :
       {Case{{"clipped.csv"}, "clipped"}, Case{{"gap.csv"}, "gap of"},
        Case{{"scaled_time.csv", "--f", "39.39", "--harmonics", "6"}, "fit residual"}}) {
    std::vector<std::string> args = {"analyze", dir / c.args[0], "--format", "json"};
    args.insert(args.end(), c.args.begin() + 1, c.args.end());
    const Outcome o = run(args);
    EXPECT_EQ(o.code, 1) << c.args[0] << o.err;
    EXPECT_NE(o.err.find(c.flag), std::string::npos) << c.args[0] << ": " << o.err;
    const nlohmann::json j = nlohmann::json::parse(o.out);
    EXPECT_FALSE(j["valid"].get<bool>());
    EXPECT_TRUE(j["ddx_max"].is_null()) << "a failed fit is not reported as a number";
    // identify --metrics on it: the analysis's reason (it said "ddx_harmonics holds a value that
    // is not a number").
    std::ofstream(dir / "failed.json") << o.out;
    const Outcome id = run({"identify", "--metrics", dir / "failed.json"});
    EXPECT_EQ(id.code, 2) << id.err;
    EXPECT_NE(id.err.find("the analysis in it is not valid (" + j["reason"].get<std::string>()),
              std::string::npos)
        << id.err;
  }
  // The other frequency, estimated: found and valid.
  const Outcome o = run({"analyze", dir / "scaled_time.csv", "--format", "json"});
  ASSERT_EQ(o.code, 0) << o.err;
  EXPECT_NEAR(nlohmann::json::parse(o.out)["f"].get<double>(), 30.3, 0.01);
}

TEST(CliAnalyze, SemicolonsDecimalCommasUnitsGColumnsByIndexAndWindows) {
  TempDir dir;
  SyntheticRecord so;
  so.duration = 1.1;
  const RecordSamples r = synthetic_record({truth(17.3e6)}, so);
  {
    std::ofstream out(dir / "eu.csv");
    out << "% exported by a logger\nZeit;ax;az\n";
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      char line[120];
      std::snprintf(line, sizeof line, "%.6f;%.7f;%.7f\n", r.t[i], r.ddx_M[i] / 9.80665,
                    r.ddz_M[i] / 9.80665);
      std::string s = line;
      std::replace(s.begin(), s.end(), '.', ',');
      out << s;
    }
  }
  const Outcome o = run({"analyze", dir / "eu.csv", "--t-col", "1", "--x-col", "ax", "--z-col", "3",
                         "--units", "g", "--window", "20", "--format", "csv"});
  ASSERT_EQ(o.code, 0) << o.err;
  const std::vector<double> f = column(o.out, "f"), valid = column(o.out, "valid"),
                            xmax = column(o.out, "ddx_max");
  ASSERT_EQ(f.size(), 3u);  // 43 periods: windows at 0 and 20, and one ending with the record
  const Metrics m = compute_metrics(simulate(truth(17.3e6)), 10);
  for (std::size_t k = 0; k < f.size(); ++k) {
    EXPECT_EQ(valid[k], 1.0);
    EXPECT_NEAR(f[k] / kF, 1.0, 1e-5);
    EXPECT_NEAR(xmax[k] / m.ddx_max, 1.0, 0.03);  // m/s^2 again, from g
  }
}

TEST(CliAnalyze, EmptyStdinIsBadInput) {
  const Outcome o = run({"analyze", "-"});
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("<stdin>: no data"), std::string::npos) << o.err;
}

// Calibration on two references of known soil writes a case file; identify --case with it finds
// the soil of a third record of the same (not the paper's) roller, which the paper's roller
// misses. The references are written as a logger writes them: z up, in g.
TEST(CliCalibrate, WritesTheCaseThatIdentifyThenUses) {
  TempDir dir;
  auto roller = [](double G) {
    Case c = truth(G);
    c.roller.M0 *= 1.15;
    c.roller.P0 *= 1.2;
    return c;
  };
  auto write_logger = [&](const std::string& path, double G, unsigned seed) {
    SyntheticRecord so;
    so.duration = 1.0;
    so.noise = 0.03;
    so.drift = 0.05;
    so.jitter = 0.1;
    so.seed = seed;
    const RecordSamples r = synthetic_record({roller(G)}, so);
    std::ofstream out(path);
    out << "Time [s],acc_x,acc_z [g]\n";
    char line[160];
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g\n", r.t[i], r.ddx_M[i],
                    -r.ddz_M[i] / 9.80665);
      out << line;
    }
  };
  write_logger(dir / "a.csv", 15e6, 1);
  write_logger(dir / "b.csv", 60e6, 2);
  write_logger(dir / "pass.csv", 32e6, 3);
  const Outcome o =
      run({"calibrate", dir / "a.csv@15", dir / "b.csv@60", "--z-positive", "up", "--fit",
           "roller.M0,roller.P0", "--out", dir / "roller.toml", "--json", dir / "cal.json"});
  ASSERT_EQ(o.code, 0) << o.err << o.out;
  EXPECT_NE(o.out.find("roller.M0 [N m]"), std::string::npos) << o.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "cal.json"));
  EXPECT_EQ(j["schema"], "oscidrum-calibrate/1");
  const double truths[] = {Roller{}.M0 * 1.15, Roller{}.P0 * 1.2};
  ASSERT_EQ(j["estimates"].size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json& e = j["estimates"][k];
    EXPECT_NEAR(e["value"].get<double>() / truths[k], 1.0, 0.02) << e;
    EXPECT_LE(e["lower"].get<double>(), truths[k]) << e;
    EXPECT_GE(e["upper"].get<double>(), truths[k]) << e;
  }
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];
  const std::string toml = slurp(dir / "roller.toml");
  EXPECT_EQ(toml.rfind("# Calibrated by oscidrum", 0), 0u) << toml;

  const Outcome id = run({"identify", dir / "pass.csv", "--z-positive", "up", "--window", "0",
                          "--case", dir / "roller.toml", "--format", "json"});
  ASSERT_EQ(id.code, 0) << id.err;
  const nlohmann::json e = nlohmann::json::parse(id.out)["windows"][0]["estimates"][0];
  EXPECT_NEAR(e["value"].get<double>() / 32e6, 1.0, 0.03) << e;
  EXPECT_LE(e["lower"].get<double>(), 32e6) << e;
  EXPECT_GE(e["upper"].get<double>(), 32e6) << e;
  const Outcome naive = run(
      {"identify", dir / "pass.csv", "--z-positive", "up", "--window", "0", "--format", "json"});
  ASSERT_EQ(naive.code, 0) << naive.err;
  const nlohmann::json n = nlohmann::json::parse(naive.out)["windows"][0];
  EXPECT_GT(std::abs(n["estimates"][0]["value"].get<double>() / 32e6 - 1.0), 0.1) << n;

  // Bad input: one line naming the value and the rule, exit 2.
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"calibrate", dir / "a.csv@15", "--fit", "soil.G"},
        {"calibrate", dir / "a.csv@fifteen"},
        {"calibrate", dir / "a.csv@0.001"},
        {"calibrate", dir / "a.csv@15", "--fit", "roller.kdd"},
        {"calibrate", dir / "a.csv@15", "--range", "1"},
        {"calibrate", dir / "missing.csv@15"}}) {
    const Outcome b = run(bad);
    EXPECT_EQ(b.code, 2) << bad.back() << ": " << b.err;
    EXPECT_NE(b.err.find("error"), std::string::npos) << b.err;
  }
  // A G written in Pa (as --G 15e6 would be) is named as such, with the reference meant; a G
  // out of range in MN/m^2 too gets no such hint.
  const Outcome pa = run({"calibrate", dir / "a.csv@15e6", "--fit", "roller.kd"});
  EXPECT_EQ(pa.code, 2) << pa.err;
  EXPECT_NE(
      pa.err.find("(G after '@' is in MN/m^2, not in Pa: did you mean " + dir / "a.csv" + "@15?)"),
      std::string::npos)
      << pa.err;
  const Outcome high = run({"calibrate", dir / "a.csv@2500", "--fit", "roller.kd"});
  EXPECT_EQ(high.code, 2) << high.err;
  EXPECT_EQ(high.err.find("not in Pa"), std::string::npos) << high.err;
}

// The sign rules of the window and gate flags say the rule, not CLI11's range of 0 to 1.8e308
// printed with all its digits.
TEST(CliAnalyze, SignRulesOfFlagsNameTheRule) {
  for (const auto& [flag, value, rule] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"--max-change", "-1", "must be > 0; got -1"},
           {"--f", "0", "must be > 0; got 0"},
           {"--hop", "-2", "must be >= 0; got -2"}}) {
    const Outcome o = run({"analyze", "missing.csv", flag, value});
    EXPECT_EQ(o.code, 2) << flag;
    EXPECT_NE(o.err.find(flag + ": " + rule), std::string::npos) << o.err;
    EXPECT_LT(o.err.size(), 200u) << o.err;
  }
}

}  // namespace
}  // namespace oscidrum::test
