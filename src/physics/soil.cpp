// Appendix B: discrete soil coefficients (42)-(45), and the paper's Table 2.
#include "oscidrum/soil.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "oscidrum/error.hpp"
#include "util/format.hpp"

namespace oscidrum {
namespace {

using detail::shortest;
std::string num(double v) { return shortest(v); }

void require(bool ok, const char* what, double value) {
  if (!ok) throw Error(std::string(what) + "; got " + num(value));
}

}  // namespace

SoilCoefficients soil_coefficients(double G, double nu, double rho, const Roller& roller) {
  require(std::isfinite(G) && G > 0, "soil.G must be > 0 [Pa]", G);
  require(std::isfinite(nu) && nu >= 0 && nu < 0.5, "soil.nu must be in [0, 0.5)", nu);
  require(std::isfinite(rho) && rho > 0, "soil.rho must be > 0 [kg/m^3]", rho);
  require(std::isfinite(roller.r) && roller.r > 0, "roller.r must be > 0 [m]", roller.r);
  require(std::isfinite(roller.b) && roller.b > 0, "roller.b must be > 0 [m]", roller.b);
  require(std::isfinite(roller.P0) && roller.P0 > 0, "roller.P0 must be > 0 [N]", roller.P0);

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
  if (soil.input == SoilInput::modulus) return soil_coefficients(soil.G, soil.nu, soil.rho, roller);
  SoilCoefficients s;
  s.ksh = soil.ksh;
  s.ksv = soil.ksv;
  s.csh = soil.csh;
  s.csv = soil.csv;
  return s;
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

Soil table2_soil(double G) {
  for (const Table2Row& row : table2()) {
    if (std::abs(row.G - G) <= 1e-9 * row.G) {
      Soil s;
      s.input = SoilInput::coefficients;
      s.G = row.G;
      s.nu = 0.3;
      s.rho = 1900.0;
      s.ksh = row.ksh;
      s.ksv = row.ksv;
      s.csh = row.csh;
      s.csv = row.csv;
      return s;
    }
  }
  throw Error("Table 2 has no row for G = " + num(G) +
              " Pa; it has G = 5e6, 10e6, ..., 70e6 Pa (5 ... 70 MN/m^2 in steps of 5)");
}

bool is_table2_G(double G) {
  for (const Table2Row& row : table2())
    if (std::abs(row.G - G) <= 1e-9 * row.G) return true;
  return false;
}

}  // namespace oscidrum
