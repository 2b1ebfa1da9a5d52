// oscidrum/soil.hpp: Appendix B (discrete soil coefficients) and the paper's Table 2.
#pragma once

#include <array>

#include "oscidrum/parameters.hpp"

namespace oscidrum {

/// Discrete Kelvin-Voigt soil coefficients and the half contact length they were built with.
struct SoilCoefficients {
  double a0 = 0.0;   ///< half contact length (43) [m] (0 when given directly)
  double ksh = 0.0;  ///< [N/m]
  double ksv = 0.0;  ///< [N/m]
  double csh = 0.0;  ///< [N s/m]
  double csv = 0.0;  ///< [N s/m]
};

/// Appendix B: a0 (43), ksh, ksv (42), csh, csv (44-45) from G [Pa], nu [-], rho [kg/m^3] and
/// the roller's r, b, P0. Throws oscidrum::Error on non-physical input.
SoilCoefficients soil_coefficients(double G, double nu, double rho, const Roller& roller = {});

/// The coefficients a Soil describes (through Appendix B when input == modulus).
SoilCoefficients soil_coefficients(const Soil& soil, const Roller& roller = {});

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

/// True when G [Pa] is one of Table 2's shear moduli (to 1e-9 relative).
bool is_table2_G(double G);

/// The Table 2 soil (input == coefficients) at G [Pa]; G must be one of the table's values
/// (5e6, 10e6, ..., 70e6), else oscidrum::Error.
Soil table2_soil(double G);

}  // namespace oscidrum
