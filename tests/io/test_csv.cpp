// Tests of src/io/csv.cpp: quoting, splitting and numbers that read back exactly; the study
// row and the steady-state header, the contract of the CSV files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "io/io_test_util.hpp"
#include "oscidrum_io/csv.hpp"

namespace oscidrum::io {
namespace {

using namespace oscidrum::io::test;

TEST(Csv, QuoteSplitAndNumbersRoundTrip) {
  const std::vector<std::string> cells = {"plain", "a,b", "say \"hi\"", "", "x\ny"};
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line += ',';
    line += csv_quote(cells[i]);
  }
  EXPECT_EQ(csv_split(line), cells);
  for (double v : {0.05, 1.0 / 3.0, 5e6, -2.5e-300, 0.1 + 0.2}) {
    EXPECT_EQ(std::strtod(format_double(v).c_str(), nullptr), v);
    EXPECT_EQ(std::strtod(format_double_short(v).c_str(), nullptr), v);
  }
  EXPECT_EQ(format_double_short(0.05), "0.05");
  EXPECT_EQ(format_double(std::nan("")), "nan");
}

// The text format_double_short wrote before it started its search at the length of the
// shortest round-trip digits: the first %.*g, precision 1, 2, ..., that reads back.
std::string shortest_by_search(double v) {
  char buf[64];
  if (v == std::trunc(v) && std::abs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", v);
    return std::string(buf) == "-0" ? "0" : buf;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

TEST(Csv, ShortNumbersAreTheShortestPrintfTextThatReadsBack) {
  // Random bit patterns (every exponent, subnormals included), random values of a sweep's
  // magnitudes, and the edges: powers of two (asymmetric rounding intervals), 17-digit values.
  std::mt19937_64 rng(20261127);
  std::vector<double> values = {0.1 + 0.2,
                                1.0 / 3.0,
                                5e-324,
                                2.2250738585072014e-308,
                                0.5,
                                std::ldexp(1.0, -60),
                                std::ldexp(1.0, 70),
                                1e15 + 0.5,
                                9007199254740993.0,
                                -0.0,
                                123456.78901234567};
  for (int i = 0; i < 20000; ++i) {
    double v;
    const std::uint64_t bits = rng();
    std::memcpy(&v, &bits, sizeof v);
    if (std::isfinite(v)) values.push_back(v);
    values.push_back(std::ldexp(std::uniform_real_distribution<double>(0.5, 1.0)(rng),
                                static_cast<int>(rng() % 80) - 40));
  }
  for (int e = -1074; e <= 1023; ++e) values.push_back(std::ldexp(1.0, e));
  for (const double v : values) {
    SCOPED_TRACE(shortest_by_search(v));
    EXPECT_EQ(format_double_short(v), shortest_by_search(v));
    EXPECT_EQ(std::strtod(format_double_short(v).c_str(), nullptr), v);
  }
}

TEST(Csv, StudyRowHasAsManyCellsAsTheHeader) {
  const StudyColumns columns{{"soil.table2_G", "contact.pure_rolling"}, 4};
  const std::size_t n = csv_split(study_csv_header(columns)).size();
  CaseOutcome invalid;
  invalid.valid = false;
  invalid.error = "bad, really";
  EXPECT_EQ(csv_split(study_csv_row(columns, 3, {5e6, true}, invalid)).size(), n);
  CaseOutcome no_samples;
  no_samples.result.status = Status::contact_lost;
  EXPECT_EQ(csv_split(study_csv_row(columns, 3, {5e6, true}, no_samples)).size(), n);
  CaseOutcome full;
  full.result.samples.t = {0.0};
  full.metrics.ddx_harmonics.resize(5);
  full.metrics.ddz_harmonics.resize(5);
  EXPECT_EQ(csv_split(study_csv_row(columns, 3, {5e6, true}, full)).size(), n);
  EXPECT_EQ(csv_split(study_csv_header(columns))[1], "soil.table2_G[Pa]");
}

// A diagnostic that does not apply (NaN) is an empty cell (docs/outputs.md: phi_drift,
// final_change, switches_per_period "empty" where they do not apply), not the text nan.
TEST(Csv, DiagnosticsThatDoNotApplyAreEmptyCells) {
  const StudyColumns columns{{"soil.table2_G"}, 2};
  const std::vector<std::string> header = csv_split(study_csv_header(columns));
  CaseOutcome chattering;
  chattering.result.status = Status::chattering;
  chattering.result.diagnostics.phi_drift = std::numeric_limits<double>::quiet_NaN();
  chattering.result.diagnostics.final_change = std::numeric_limits<double>::quiet_NaN();
  chattering.result.diagnostics.switches_per_period = 2.5;
  const std::vector<std::string> row = csv_split(study_csv_row(columns, 0, {5e6}, chattering));
  ASSERT_EQ(row.size(), header.size());
  const auto cell = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    return at == header.end() ? std::string("(no column)") : row[at - header.begin()];
  };
  EXPECT_EQ(cell("phi_drift[rad]"), "");
  EXPECT_EQ(cell("final_change[-]"), "");
  EXPECT_EQ(cell("switches_per_period[-]"), "2.5");
  EXPECT_EQ(study_row_defect(header, study_csv_row(columns, 0, {5e6}, chattering)), "");
}

TEST(Csv, SteadyStateHeaderIsTheContract) {
  std::ostringstream out;
  write_steady_state_csv(out, Result{});
  EXPECT_EQ(out.str(),
            "t[s],delta[rad],phi[rad],x_A[m],s_A[m],ddelta[rad/s],dphi[rad/s],dx_A[m/s],ds_A[m/s],"
            "x_M[m],z_M[m],ddx_M[m/s^2],ddz_M[m/s^2],N[N],T[N],v_rel[m/s],gap[m],dgap[m/"
            "s],torque[N m],alpha[rad],phase[-]\n");
}

}  // namespace
}  // namespace oscidrum::io
