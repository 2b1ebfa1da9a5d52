// test_outputs.cpp: the output table (oscidrum/outputs.hpp, output_table.hpp) describes every
// output once and consistently: unique names, a unit and a description each, statuses named as
// to_string names them, and the table reaching every member of the result structs.
#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>
#include <string_view>

#include "oscidrum/output_table.hpp"

namespace oscidrum {
namespace {

template <class Table>
void expect_described(const Table& table, std::set<std::string>& names) {
  for (const auto& o : table) {
    SCOPED_TRACE(o.name);
    EXPECT_TRUE(names.insert(o.name).second) << "duplicate output name";
    EXPECT_FALSE(std::string_view(o.unit).empty());
    EXPECT_FALSE(std::string_view(o.label).empty());
    EXPECT_GT(std::string_view(o.description).size(), 3u);
    // Names are identifiers (CSV headers, JSON keys, Python attributes).
    for (char ch : std::string_view(o.name))
      EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_') << ch;
  }
}

TEST(Outputs, EveryOutputHasAUniqueNameAUnitAndADescription) {
  std::set<std::string> samples, diagnostics, metrics, record;
  expect_described(sample_outputs(), samples);
  expect_described(diagnostic_outputs(), diagnostics);
  expect_described(metric_outputs(), metrics);
  expect_described(record_outputs(), record);
  // Diagnostics and metrics share the sweep CSV: no name may appear in both.
  for (const std::string& d : diagnostics) EXPECT_EQ(metrics.count(d), 0u) << d;
  EXPECT_EQ(sample_outputs().size(), 21u);
  EXPECT_EQ(sample_outputs().front().name, std::string("t"));
  EXPECT_EQ(sample_outputs().back().name, std::string("phase"));
}

TEST(Outputs, StatusesAreNamedAsToStringNamesThem) {
  ASSERT_FALSE(statuses().empty());
  EXPECT_EQ(statuses().front().status, Status::steady_state);
  for (const StatusInfo& s : statuses()) EXPECT_EQ(std::string(to_string(s.status)), s.name);
}

TEST(Outputs, TheTableReadsTheStructMembers) {
  Diagnostics d;
  EXPECT_EQ(d.periods_to_steady, -1);  // the initial value comes from the table too
  d.inconsistent_slip_ends = 3;
  d.max_slip_residual = 2.5e-9;
  double found = 0;
  for (const DiagnosticOutput& o : diagnostic_outputs()) {
    if (o.name == std::string_view("inconsistent_slip_ends")) {
      EXPECT_TRUE(is_integer(o));
      found += scalar_value(d, o);
    }
    if (o.name == std::string_view("max_slip_residual")) {
      EXPECT_FALSE(is_integer(o));
      EXPECT_EQ(scalar_value(d, o), 2.5e-9);
      // One unit, one normalisation: a ratio to W (the docs once said W, Python said max(N)).
      EXPECT_EQ(std::string(o.unit), "-");
      EXPECT_NE(std::string(o.description).find("/ W"), std::string::npos);
    }
  }
  EXPECT_EQ(found, 3.0);
  // The method and the fallback reason are text columns of the same table.
  d.method = SteadyMethod::shooting;
  d.fallback = "Newton did not converge";
  std::string texts;
  for (const DiagnosticOutput& o : diagnostic_outputs())
    if (is_text(o)) texts += std::string(o.name) + "=" + text_value(d, o) + ";";
  EXPECT_EQ(
      texts,
      "method=shooting;fallback=Newton did not converge;contact_mode=;operating_mode=;motion=;");
  EXPECT_TRUE(is_text_column("method") && is_text_column("fallback") && is_text_column("status"));
  EXPECT_TRUE(is_text_column("contact_mode"));
  EXPECT_FALSE(is_text_column("newton_iterations") || is_text_column("min_N"));
  Metrics m;
  m.friction_work = 12.5;
  int spectra = 0;
  for (const MetricOutput& o : metric_outputs()) {
    if (!is_scalar(o)) {
      ++spectra;
      EXPECT_EQ(spectrum_prefix(o.name) + "_harmonics", o.name);
    } else if (o.name == std::string_view("friction_work")) {
      EXPECT_EQ(scalar_value(m, o), 12.5);
      EXPECT_EQ(std::string(o.unit), "J");
    }
  }
  EXPECT_EQ(spectra, 2);
  // The acceleration metrics are shared by simulations and records, in both tables.
  int shared = 0;
  for (const RecordOutput& o : record_outputs()) shared += is_acceleration_metric(o.name);
  int in_metrics = 0;
  for (const MetricOutput& o : metric_outputs()) in_metrics += is_acceleration_metric(o.name);
  EXPECT_EQ(shared, in_metrics);
  EXPECT_GE(shared, 14);
}

}  // namespace
}  // namespace oscidrum
