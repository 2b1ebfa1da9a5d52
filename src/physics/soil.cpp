// Appendix B: discrete soil coefficients (42)-(45), and the paper's Table 2.
#include "oscidrum/soil.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "oscidrum/error.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

using detail::shortest;
std::string num(double v) { return shortest(v); }

void require(bool ok, const char* key, const char* rule, double value) {
  if (!ok) throw Error(std::string(key) + " must be " + rule + "; got " + num(value), key, value);
}

[[noreturn]] void no_table2_row(double G) {
  throw Error(
      "soil.G must be a G of paper Table 2 while soil.input = \"table2\": 5e6, 10e6, ..., "
      "70e6 [Pa] (5 ... 70 MN/m^2 in steps of 5); got " +
          num(G) + " (for other G set soil.input = \"modulus\": Appendix B)",
      "soil.G", G);
}

}  // namespace

SoilCoefficients soil_coefficients(double G, double nu, double rho, const Roller& roller) {
  require(std::isfinite(G) && G > 0, "soil.G", "> 0 [Pa]", G);
  require(std::isfinite(nu) && nu >= 0 && nu < 0.5, "soil.nu", "in [0, 0.5)", nu);
  require(std::isfinite(rho) && rho > 0, "soil.rho", "> 0 [kg/m^3]", rho);
  require(std::isfinite(roller.r) && roller.r > 0, "roller.r", "> 0 [m]", roller.r);
  require(std::isfinite(roller.b) && roller.b > 0, "roller.b", "> 0 [m]", roller.b);
  require(std::isfinite(roller.P0) && roller.P0 > 0, "roller.P0", "> 0 [N]", roller.P0);

  const double r = roller.r, b0 = roller.b / 2.0, P0 = roller.P0;
  SoilCoefficients s;
  // (43): 2 a0 = 4 [2 sqrt(2 r P0 (1 - nu) / (pi G b0))], i.e. a0 = 4 sqrt(...).
  s.a0 = 4.0 * std::sqrt(2.0 * r * P0 * (1.0 - nu) / (M_PI * G * b0));
  const double q = b0 / s.a0;
  // (42), as printed in the paper (it does not reproduce Table 2's stiffness columns; see
  // docs/model.md section 1.3 and docs/validation.md).
  s.ksh = G * s.a0 / (2.0 - nu) * (6.8 * std::pow(q, 0.65) + 0.8 * q + 1.6);
  s.ksv = G * s.a0 / (1.0 - nu) * (3.1 * std::pow(q, 0.75) + 1.6);
  // (44): csh = 2 rho sqrt(G / rho) 4 a0 b0 = 8 a0 b0 sqrt(G rho); csv = sqrt(2(1-nu)/(1-2nu)) csh.
  s.csh = 8.0 * s.a0 * b0 * std::sqrt(G * rho);
  s.csv = std::sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu)) * s.csh;
  return s;
}

SoilCoefficients soil_coefficients(const Soil& soil, const Roller& roller) {
  SoilCoefficients s;
  switch (soil.input) {
    case SoilInput::modulus:
      return soil_coefficients(soil.G, soil.nu, soil.rho, roller);
    case SoilInput::table2: {
      const Table2Row* row = table2_row(soil.G);
      if (!row) no_table2_row(soil.G);
      s.a0 = row->a0;
      s.ksh = row->ksh;
      s.ksv = row->ksv;
      s.csh = row->csh;
      s.csv = row->csv;
      return s;
    }
    case SoilInput::coefficients:
      break;
  }
  s.ksh = soil.ksh;
  s.ksv = soil.ksv;
  s.csh = soil.csh;
  s.csv = soil.csv;
  return s;
}

std::string soil_summary(const Soil& soil) {
  const std::string G = num(soil.G / 1e6) + " MN/m^2";
  switch (soil.input) {
    case SoilInput::table2:
      return "paper Table 2 at G = " + G + (soil.G == Soil{}.G ? " (the default soil)" : "");
    case SoilInput::modulus:
      return "Appendix B (42)-(45) from G = " + G + ", nu = " + num(soil.nu) +
             ", rho = " + num(soil.rho) + " kg/m^3";
    case SoilInput::coefficients:
      break;
  }
  return "coefficients given directly";
}

const char* soil_source_id(const Soil& soil) {
  switch (soil.input) {
    case SoilInput::table2:
      return "table2";
    case SoilInput::modulus:
      return "appendix_b";
    case SoilInput::coefficients:
      break;
  }
  return "coefficients";
}

const std::array<Table2Row, 14>& table2() {
  // Paper Table 2 (nu = 0.3, rho = 1900 kg/m^3), converted to SI.
  static const std::array<Table2Row, 14> rows = {{
      {5e6, 0.217, 11.4e6, 16.3e6, 141e3, 263e3},
      {10e6, 0.153, 19.7e6, 29.5e6, 141e3, 263e3},
      {15e6, 0.125, 27.3e6, 42.1e6, 141e3, 263e3},
      {20e6, 0.108, 34.5e6, 54.3e6, 141e3, 263e3},
      {25e6, 0.097, 41.4e6, 66.3e6, 141e3, 263e3},
      {30e6, 0.088, 48.2e6, 78.1e6, 141e3, 263e3},
      {35e6, 0.082, 54.8e6, 89.8e6, 141e3, 263e3},
      {40e6, 0.077, 61.2e6, 101e6, 141e3, 263e3},
      {45e6, 0.072, 67.6e6, 113e6, 141e3, 263e3},
      {50e6, 0.069, 73.9e6, 124e6, 141e3, 263e3},
      {55e6, 0.065, 80.1e6, 136e6, 141e3, 263e3},
      {60e6, 0.063, 86.2e6, 147e6, 141e3, 263e3},
      {65e6, 0.060, 92.3e6, 158e6, 141e3, 263e3},
      {70e6, 0.058, 98.3e6, 169e6, 141e3, 263e3},
  }};
  return rows;
}

const Table2Row* table2_row(double G) {
  for (const Table2Row& row : table2())
    if (std::abs(row.G - G) <= 1e-9 * row.G) return &row;
  return nullptr;
}

bool is_table2_G(double G) { return table2_row(G) != nullptr; }

namespace {

// Fritsch-Carlson (PCHIP) slopes of y(x) at the nodes: the harmonic mean of the neighbouring
// secants where they have the same sign (0 otherwise), one-sided three-point formulas at the
// ends, limited so that the interpolant stays monotone between nodes.
template <std::size_t N>
std::array<double, N> pchip_slopes(const std::array<double, N>& x, const std::array<double, N>& y) {
  std::array<double, N - 1> h{}, d{};
  for (std::size_t k = 0; k + 1 < N; ++k) {
    h[k] = x[k + 1] - x[k];
    d[k] = (y[k + 1] - y[k]) / h[k];
  }
  std::array<double, N> m{};
  for (std::size_t k = 1; k + 1 < N; ++k) {
    if (d[k - 1] * d[k] <= 0) continue;
    const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
    m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
  }
  auto end = [](double h0, double h1, double d0, double d1) {
    double s = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (s * d0 <= 0) return 0.0;
    if (d0 * d1 <= 0 && std::abs(s) > 3 * std::abs(d0)) s = 3 * d0;
    return s;
  };
  m[0] = end(h[0], h[1], d[0], d[1]);
  m[N - 1] = end(h[N - 2], h[N - 3], d[N - 2], d[N - 3]);
  return m;
}

}  // namespace

SoilCoefficients table2_coefficients(double G) {
  if (!(G >= kTable2InterpolatedMin && G <= kTable2InterpolatedMax))
    throw Error("soil.G must be in [" + num(kTable2InterpolatedMin) + ", " +
                    num(kTable2InterpolatedMax) +
                    "] [Pa] on the Table 2 scale (its rows 5 ... 70 MN/m^2, and a factor 4 "
                    "beyond each end); got " +
                    num(G),
                "soil.G", G);
  if (const Table2Row* row = table2_row(G))
    return {row->a0, row->ksh, row->ksv, row->csh, row->csv};
  constexpr std::size_t n = 14;
  const auto& rows = table2();
  std::array<double, n> x{};
  for (std::size_t k = 0; k < n; ++k) x[k] = std::log(rows[k].G);
  const double u = std::log(G);
  std::size_t k = 0;  // the interval [x_k, x_k+1] holding u (clamped to the end intervals)
  while (k + 2 < n && u > x[k + 1]) ++k;
  auto column = [&](double Table2Row::*member) {
    bool constant = true;  // csh, csv: the same in every row, and exactly so between them
    for (const Table2Row& row : rows) constant = constant && row.*member == rows[0].*member;
    if (constant) return rows[0].*member;
    std::array<double, n> y{};
    for (std::size_t j = 0; j < n; ++j) y[j] = std::log(rows[j].*member);
    const std::array<double, n> m = pchip_slopes(x, y);
    if (u < x[0]) return std::exp(y[0] + m[0] * (u - x[0]));  // power laws beyond the ends
    if (u > x[n - 1]) return std::exp(y[n - 1] + m[n - 1] * (u - x[n - 1]));
    // Cubic Hermite on [x_k, x_k+1].
    const double h = x[k + 1] - x[k], s = (u - x[k]) / h;
    const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
    const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
    return std::exp(h00 * y[k] + h10 * h * m[k] + h01 * y[k + 1] + h11 * h * m[k + 1]);
  };
  return {column(&Table2Row::a0), column(&Table2Row::ksh), column(&Table2Row::ksv),
          column(&Table2Row::csh), column(&Table2Row::csv)};
}

Soil table2_soil(double G) {
  const Table2Row* row = table2_row(G);
  if (!row)
    throw Error("Table 2 has no row for G = " + num(G) +
                    " Pa; it has G = 5e6, 10e6, ..., 70e6 Pa (5 ... 70 MN/m^2 in steps of 5)",
                "soil.G", G);
  Soil s;
  s.input = SoilInput::table2;
  s.G = row->G;
  s.nu = kTable2Nu;
  s.rho = kTable2Rho;
  s.ksh = row->ksh;
  s.ksv = row->ksv;
  s.csh = row->csh;
  s.csv = row->csv;
  return s;
}

}  // namespace oscidrum
