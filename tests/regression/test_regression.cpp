// Regression profiles: stored outputs of a fixed set of cases (the paper's validation cases and a
// few others), compared with what the engine computes now. Every restructuring of the engine must
// leave these numbers unchanged; an intended change regenerates the file on request
// (OSCIDRUM_REGENERATE_PROFILES=1 ctest -R Regression) and says why in its commit.
//
// The comparison (after Cantera's compareProfiles): integers (status, multiplicity, periods to the
// steady state) exactly; every real column to kRegression relative to that column's largest
// magnitude over the whole profile set (a harmonic's cosine and sine parts share the scale of
// all harmonics of that signal), so that values near zero by symmetry are compared on the scale
// of the quantity and not on their own round-off. The test also counts the values that are not
// bit-for-bit identical, so that a refactoring that should not touch the arithmetic can say so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "oscidrum/oscidrum.hpp"
#include "oscidrum_paper/validation.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

constexpr int kHarmonics = 6;  // n = 0 ... 6 stored for x_M'' and z_M''
const std::string kFile = std::string(OSCIDRUM_SOURCE_DIR) + "/tests/regression/profiles.csv";

struct ProfileCase {
  std::string id;
  Case c;
};

// The paper's validation cases, plus cases that exercise what those do not: the spiral trough in
// stick-slip, a negative driving torque, the suspension measured from static equilibrium, the
// frictionless drum, another mu and another frequency (M0 scaled by f^2, (5)).
std::vector<ProfileCase> profile_cases() {
  std::vector<ProfileCase> out;
  for (const PaperSeries& s : paper_series())
    for (double G : s.G) {
      char id[96];
      std::snprintf(id, sizeof id, "%s@G%g", s.id.c_str(), G / 1e6);
      out.push_back({id, paper_case(s, G)});
    }
  auto table2 = [](double G) {
    Case c;
    c.soil = table2_soil(G);
    return c;
  };
  {
    Case c = table2(10e6);
    c.trough.shape = trough_shape(0.002, 0.601);
    out.push_back({"extra.spiral_stickslip@G10", c});
  }
  {
    Case c = table2(40e6);
    c.MMd = -0.03 * c.roller.M0;
    out.push_back({"extra.stickslip_MMd-0.03@G40", c});
  }
  {
    Case c = table2(25e6);
    c.numerics.suspension_from_static = true;
    out.push_back({"extra.suspension_from_static@G25", c});
  }
  {
    Case c = table2(25e6);
    c.contact.mu = 0.0;
    out.push_back({"extra.frictionless@G25", c});
  }
  {
    Case c = table2(50e6);
    c.contact.mu = 0.3;
    c.MMd = 0.05 * c.roller.M0;
    out.push_back({"extra.mu0.3_MMd0.05@G50", c});
  }
  {
    Case c = table2(15e6);
    c.roller.f = 30.0;
    c.roller.M0 *= (30.0 / 39.0) * (30.0 / 39.0);
    c.contact.pure_rolling = true;
    out.push_back({"extra.rolling_f30@G15", c});
  }
  return out;
}

std::vector<std::string> columns() {
  std::vector<std::string> c = {"status",
                                "multiplicity",
                                "periods_to_steady",
                                "switches_per_period",
                                "ddx_max",
                                "ddx_min",
                                "ddz_max",
                                "ddz_min",
                                "delta_max",
                                "delta_min",
                                "phi_lag",
                                "phi_amplitude",
                                "psi_xz",
                                "area",
                                "stick_fraction",
                                "slip_positive_fraction",
                                "slip_negative_fraction"};
  for (const char* s : {"ddx", "ddz"})
    for (int n = 0; n <= kHarmonics; ++n)
      for (const char* part : {"cos", "sin"})
        c.push_back(std::string(s) + "_" + part + std::to_string(n));
  return c;
}

// The scale group of a column: harmonics share one per signal, every other column its own.
std::string group(const std::string& column) {
  if (column.rfind("ddx_cos", 0) == 0 || column.rfind("ddx_sin", 0) == 0) return "ddx_harmonics";
  if (column.rfind("ddz_cos", 0) == 0 || column.rfind("ddz_sin", 0) == 0) return "ddz_harmonics";
  return column;
}

bool is_integer_column(const std::string& column) {
  return column == "status" || column == "multiplicity" || column == "periods_to_steady";
}

std::vector<double> row_of(const CaseOutcome& o) {
  const Metrics& m = o.metrics;
  const Diagnostics& d = o.result.diagnostics;
  std::vector<double> r = {static_cast<double>(o.result.status),
                           static_cast<double>(d.multiplicity),
                           static_cast<double>(d.periods_to_steady),
                           d.switches_per_period,
                           m.ddx_max,
                           m.ddx_min,
                           m.ddz_max,
                           m.ddz_min,
                           m.delta_max,
                           m.delta_min,
                           m.phi_lag,
                           m.phi_amplitude,
                           m.psi_xz,
                           m.area,
                           m.stick_fraction,
                           m.slip_positive_fraction,
                           m.slip_negative_fraction};
  for (const auto* h : {&m.ddx_harmonics, &m.ddz_harmonics})
    for (int n = 0; n <= kHarmonics; ++n) {
      const Harmonic a = n < static_cast<int>(h->size()) ? (*h)[n] : Harmonic{};
      // A sin(n nu t + theta) = A sin(theta) cos(n nu t) + A cos(theta) sin(n nu t)
      r.push_back(a.amplitude * std::sin(a.phase));
      r.push_back(a.amplitude * std::cos(a.phase));
    }
  return r;
}

std::vector<std::vector<double>> compute(const std::vector<ProfileCase>& cases) {
  // The profiles were computed by the transient method (it is the paper's, and they store the
  // period at which the steady state was found): pinned here. Shooting is compared with the
  // transient method on the paper's cases in tests/paper (test_method_agreement).
  std::vector<Case> cs;
  for (const ProfileCase& p : cases) {
    cs.push_back(p.c);
    cs.back().numerics.method = SteadyMethod::transient;
  }
  StudyOptions options;
  options.n_harmonics = 10;
  const std::vector<CaseOutcome> outcomes = run_study(cs, options);
  std::vector<std::vector<double>> rows;
  for (const CaseOutcome& o : outcomes) {
    EXPECT_TRUE(o.valid) << o.error;
    rows.push_back(row_of(o));
  }
  return rows;
}

void write_profiles(const std::vector<ProfileCase>& cases,
                    const std::vector<std::vector<double>>& rows) {
  std::ofstream out(kFile);
  out << "id";
  for (const std::string& c : columns()) out << ',' << c;
  out << '\n';
  for (std::size_t i = 0; i < cases.size(); ++i) {
    out << cases[i].id;
    for (double v : rows[i]) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.17g", v);
      out << ',' << buf;
    }
    out << '\n';
  }
}

std::map<std::string, std::vector<double>> read_profiles() {
  std::ifstream in(kFile);
  std::map<std::string, std::vector<double>> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string id, cell;
    std::getline(ss, id, ',');
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::strtod(cell.c_str(), nullptr));
    out[id] = v;
  }
  return out;
}

TEST(Regression, ProfilesAreUnchanged) {
  const std::vector<ProfileCase> cases = profile_cases();
  const std::vector<std::vector<double>> rows = compute(cases);
  if (std::getenv("OSCIDRUM_REGENERATE_PROFILES")) {
    write_profiles(cases, rows);
    GTEST_SKIP() << "regenerated " << kFile;
  }
  const auto stored = read_profiles();
  ASSERT_EQ(stored.size(), cases.size()) << "the profile set changed: regenerate " << kFile;
  const std::vector<std::string> cols = columns();

  std::map<std::string, double> scale;
  for (const auto& [id, v] : stored) {
    ASSERT_EQ(v.size(), cols.size()) << id;
    for (std::size_t j = 0; j < cols.size(); ++j)
      scale[group(cols[j])] = std::max(scale[group(cols[j])], std::abs(v[j]));
  }
  long not_identical = 0, compared = 0;
  double worst = 0.0;
  std::string worst_where;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto it = stored.find(cases[i].id);
    ASSERT_NE(it, stored.end()) << "no stored profile for " << cases[i].id;
    const std::vector<double>& ref = it->second;
    for (std::size_t j = 0; j < cols.size(); ++j) {
      ++compared;
      const double a = rows[i][j], b = ref[j];
      if (a != b && !(std::isnan(a) && std::isnan(b))) ++not_identical;
      if (is_integer_column(cols[j])) {
        EXPECT_EQ(a, b) << cases[i].id << " " << cols[j];
        continue;
      }
      const double s = scale[group(cols[j])];
      // NaN where a value is undefined (psi_xz of a drum without horizontal motion): equal to a
      // stored NaN, and a deviation (NaN) against a number either way.
      const double dev = std::isnan(a) && std::isnan(b) ? 0.0
                         : s > 0                        ? std::abs(a - b) / s
                                                        : std::abs(a - b);
      if (dev > worst) {
        worst = dev;
        worst_where = cases[i].id + " " + cols[j];
      }
      EXPECT_LE(dev, test::kRegression)
          << cases[i].id << " " << cols[j] << ": now " << a << ", stored " << b;
    }
  }
  std::printf(
      "regression profiles: %zu cases, %ld values, %ld not bit-for-bit identical, largest "
      "scaled deviation %.3g (%s)\n",
      cases.size(), compared, not_identical, worst, worst_where.c_str());
}

}  // namespace
}  // namespace oscidrum
