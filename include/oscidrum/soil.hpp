// oscidrum/soil.hpp: the soil input as the discrete coefficients the model uses: Appendix B and
// the paper's Table 2.
#pragma once

#include <array>
#include <string>

#include "oscidrum/parameters.hpp"

namespace oscidrum {

/// Discrete Kelvin-Voigt soil coefficients and the half contact length they were built with.
struct SoilCoefficients {
  double a0 = 0.0;   ///< half contact length (43) [m] (Table 2's a0; 0 when given directly)
  double ksh = 0.0;  ///< [N/m]
  double ksv = 0.0;  ///< [N/m]
  double csh = 0.0;  ///< [N s/m]
  double csv = 0.0;  ///< [N s/m]
};

/// Appendix B: a0 (43), ksh, ksv (42), csh, csv (44-45) from G [Pa], nu [-], rho [kg/m^3] and
/// the roller's r, b, P0. Throws oscidrum::Error on non-physical input.
SoilCoefficients soil_coefficients(double G, double nu, double rho, const Roller& roller = {});

/// The coefficients a Soil describes: the one conversion of every soil input, which Model makes
/// (Table 2's row at G when input == table2, Appendix B (42)-(45) when input == modulus, as given
/// when input == coefficients). Throws oscidrum::Error (key soil.G) for a G that Table 2 does not
/// hold, or (as above) for non-physical modulus input.
SoilCoefficients soil_coefficients(const Soil& soil, const Roller& roller = {});

/// How the soil is given, in words: "paper Table 2 at G = 25 MN/m^2 (the default soil)",
/// "Appendix B (42)-(45) from G = 27 MN/m^2, nu = 0.3, rho = 1900 kg/m^3", "coefficients given
/// directly".
std::string soil_summary(const Soil& soil);

/// The same as a machine name: "table2", "appendix_b", "coefficients".
const char* soil_source_id(const Soil& soil);

/// One row of the paper's Table 2 (SI units).
struct Table2Row {
  double G;    ///< [Pa]
  double a0;   ///< [m]
  double ksh;  ///< [N/m]
  double ksv;  ///< [N/m]
  double csh;  ///< [N s/m]
  double csv;  ///< [N s/m]
};

/// Paper Table 2, G = 5 ... 70 MN/m^2 in steps of 5 (nu = 0.3, rho = 1900 kg/m^3).
const std::array<Table2Row, 14>& table2();

/// The Poisson's ratio [-] and density [kg/m^3] of every row of Table 2.
inline constexpr double kTable2Nu = 0.3;
inline constexpr double kTable2Rho = 1900.0;

/// The row of Table 2 at G [Pa] (to 1e-9 relative), or nullptr.
const Table2Row* table2_row(double G);

/// True when G [Pa] is one of Table 2's shear moduli (to 1e-9 relative).
bool is_table2_G(double G);

/// The range of G [Pa] table2_coefficients covers: Table 2's 5 ... 70 MN/m^2, and a factor 4
/// beyond each end.
inline constexpr double kTable2InterpolatedMin = 1.25e6;
inline constexpr double kTable2InterpolatedMax = 280e6;

/// Table 2's coefficients at any G [Pa] in [kTable2InterpolatedMin, kTable2InterpolatedMax]:
/// the rows themselves at the table's G; between rows, a monotone cubic (Fritsch-Carlson,
/// PCHIP) through the rows of ln(coefficient) against ln(G) (continuously differentiable,
/// monotone in G where the column is: a0 falls, ksh and ksv rise, csh and csv are constant);
/// beyond the table, the end rows' power laws (the log-log slope at the end row). The scale on
/// which `identify --soil-scale table2` gives G (docs/identify.md). Throws oscidrum::Error (key
/// soil.G) outside the range.
SoilCoefficients table2_coefficients(double G);

/// The Table 2 soil at G [Pa]: input == table2 at the row's G, with the row's coefficients also
/// in ksh, ksv, csh, csv (for reading; the model takes them from the table). G must be one of
/// the table's values (5e6, 10e6, ..., 70e6), else oscidrum::Error.
Soil table2_soil(double G);

}  // namespace oscidrum
