// Tests of Appendix B (soil coefficients (42)-(45)), the paper's Table 2 and Appendix A
// (transmissibility (40)), against paper Table 2 (docs/model.md section 1).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "oscidrum/error.hpp"
#include "oscidrum/model.hpp"
#include "oscidrum/parameters.hpp"
#include "oscidrum/soil.hpp"
#include "oscidrum/transmissibility.hpp"
#include "tolerances.hpp"

namespace oscidrum {
namespace {

using test::kHalfLastDigit;
using test::kIdentity;

constexpr double kNu = 0.3;      // Table 2's Poisson's ratio
constexpr double kRho = 1900.0;  // Table 2's density [kg/m^3]

// |value - printed| within half a unit of the printed number's last digit `unit`.
void expect_to_print_precision(double value, double printed, double unit, const char* what) {
  EXPECT_LE(std::abs(value - printed), kHalfLastDigit * unit)
      << what << ": computed " << value << ", printed " << printed;
}

// ---- Table 2 ---------------------------------------------------------------------------------

TEST(Table2, HasFourteenRowsFromFiveToSeventyMegapascal) {
  const auto& rows = table2();
  ASSERT_EQ(rows.size(), 14u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].G, 5e6 * static_cast<double>(i + 1)) << i;
    EXPECT_EQ(rows[i].csh, 141e3) << i;
    EXPECT_EQ(rows[i].csv, 263e3) << i;
    if (i > 0) {  // stiffer soil: shorter contact, stiffer springs
      EXPECT_LT(rows[i].a0, rows[i - 1].a0);
      EXPECT_GT(rows[i].ksh, rows[i - 1].ksh);
      EXPECT_GT(rows[i].ksv, rows[i - 1].ksv);
    }
  }
  // Spot checks against the printed table (docs/model.md section 1).
  EXPECT_EQ(rows[0].a0, 0.217);
  EXPECT_EQ(rows[0].ksh, 11.4e6);
  EXPECT_EQ(rows[0].ksv, 16.3e6);
  EXPECT_EQ(rows[7].ksv, 101e6);
  EXPECT_EQ(rows[13].a0, 0.058);
  EXPECT_EQ(rows[13].ksh, 98.3e6);
  EXPECT_EQ(rows[13].ksv, 169e6);
}

TEST(Table2, SoilReturnsEachRowAsTheTable2Input) {
  for (const Table2Row& row : table2()) {
    const Soil s = table2_soil(row.G);
    EXPECT_EQ(s.input, SoilInput::table2);
    EXPECT_EQ(s.ksh, row.ksh);  // for reading: the model converts G itself
    EXPECT_EQ(s.ksv, row.ksv);
    EXPECT_EQ(s.csh, row.csh);
    EXPECT_EQ(s.csv, row.csv);
    EXPECT_EQ(s.G, row.G);
    EXPECT_EQ(s.nu, kNu);
    EXPECT_EQ(s.rho, kRho);
    const SoilCoefficients c = soil_coefficients(s);
    EXPECT_EQ(c.ksh, row.ksh);
    EXPECT_EQ(c.csv, row.csv);
    EXPECT_EQ(c.a0, row.a0);  // Table 2's contact length
    // Given directly, the same coefficients have no contact length.
    Soil direct = s;
    direct.input = SoilInput::coefficients;
    EXPECT_EQ(soil_coefficients(direct).ksh, row.ksh);
    EXPECT_EQ(soil_coefficients(direct).a0, 0.0);
  }
}

// The one conversion of every soil input (soil_coefficients(Soil)), which Model makes: the
// Table 2 row at G (only at the table's G, with the key in the error), Appendix B for modulus,
// the coefficients as given.
TEST(SoilInput, EachInputConvertsOnce) {
  Soil s;  // the default: Table 2 at G = 25 MN/m^2
  EXPECT_EQ(s.input, SoilInput::table2);
  EXPECT_EQ(soil_coefficients(s).ksv, 66.3e6);
  s.G = 27e6;
  try {
    (void)soil_coefficients(s);
    ADD_FAILURE() << "Table 2 converted G = 27e6";
  } catch (const Error& e) {
    EXPECT_EQ(e.key(), "soil.G");
    EXPECT_EQ(e.value(), 27e6);
    EXPECT_NE(std::string(e.what()).find("soil.input = \"modulus\""), std::string::npos);
  }
  s.input = SoilInput::modulus;
  const SoilCoefficients b = soil_coefficients(s);
  const SoilCoefficients direct = soil_coefficients(27e6, s.nu, s.rho);
  EXPECT_EQ(b.ksh, direct.ksh);
  EXPECT_EQ(b.a0, direct.a0);
  EXPECT_EQ(std::string(soil_source_id(s)), "appendix_b");
  EXPECT_EQ(soil_summary(s),
            "Appendix B (42)-(45) from G = 27 MN/m^2, nu = 0.3, rho = 1900 kg/m^3");
  EXPECT_EQ(soil_summary(Soil{}), "paper Table 2 at G = 25 MN/m^2 (the default soil)");
  EXPECT_EQ(soil_summary(table2_soil(40e6)), "paper Table 2 at G = 40 MN/m^2");
  EXPECT_EQ(std::string(soil_source_id(table2_soil(40e6))), "table2");
  s.input = SoilInput::coefficients;
  EXPECT_EQ(soil_summary(s), "coefficients given directly");
  EXPECT_EQ(std::string(soil_source_id(s)), "coefficients");
  EXPECT_EQ(table2_row(40e6)->ksh, 61.2e6);
  EXPECT_EQ(table2_row(41e6), nullptr);
}

TEST(Table2, SoilThrowsForAGNotInTheTable) {
  for (double G : {7e6, 0.0, -5e6, 75e6, 4.9e6}) {
    try {
      (void)table2_soil(G);
      ADD_FAILURE() << "no error for G = " << G;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("Table 2"), std::string::npos) << e.what();
    }
  }
}

// ---- Table 2 between its rows (table2_coefficients) ------------------------------------------

double column(const SoilCoefficients& s, int k) {
  const double v[5] = {s.a0, s.ksh, s.ksv, s.csh, s.csv};
  return v[k];
}

TEST(Table2Interpolated, IsTheRowAtEveryRow) {
  for (const Table2Row& row : table2()) {
    const SoilCoefficients s = table2_coefficients(row.G);
    EXPECT_EQ(s.ksh, row.ksh);
    EXPECT_EQ(s.ksv, row.ksv);
    EXPECT_EQ(s.csv, row.csv);
    EXPECT_EQ(s.a0, row.a0);
    // Just off the row the interpolant is continuous with it.
    const SoilCoefficients near = table2_coefficients(row.G * (1 + 1e-9));
    EXPECT_NEAR(near.ksh / row.ksh, 1.0, 1e-8);
    EXPECT_NEAR(near.ksv / row.ksv, 1.0, 1e-8);
  }
}

// Monotone in G where the table is: a0 falls, ksh and ksv rise, csh and csv stay; between two
// rows every coefficient lies between theirs.
TEST(Table2Interpolated, IsMonotoneAndBetweenTheRows) {
  SoilCoefficients previous = table2_coefficients(kTable2InterpolatedMin);
  for (double G = kTable2InterpolatedMin * 1.01; G <= kTable2InterpolatedMax; G *= 1.01) {
    const SoilCoefficients s = table2_coefficients(G);
    EXPECT_LT(s.a0, previous.a0) << G;
    EXPECT_GT(s.ksh, previous.ksh) << G;
    EXPECT_GT(s.ksv, previous.ksv) << G;
    EXPECT_EQ(s.csh, 141e3);
    EXPECT_EQ(s.csv, 263e3);
    previous = s;
  }
  const auto& rows = table2();
  for (std::size_t k = 0; k + 1 < rows.size(); ++k) {
    const SoilCoefficients s = table2_coefficients(0.5 * (rows[k].G + rows[k + 1].G));
    EXPECT_GT(s.ksh, rows[k].ksh);
    EXPECT_LT(s.ksh, rows[k + 1].ksh);
    EXPECT_LT(s.a0, rows[k].a0);
    EXPECT_GT(s.a0, rows[k + 1].a0);
  }
}

// Continuously differentiable: the log-log slope just left and just right of every inner row
// agrees (a piecewise linear interpolation would jump there, and a Jacobian by finite
// differences across a row would see the jump).
TEST(Table2Interpolated, HasAContinuousSlopeAtTheRows) {
  const auto& rows = table2();
  const double h = 1e-5;
  for (std::size_t k = 1; k + 1 < rows.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double G = rows[k].G;
      const double at = std::log(column(table2_coefficients(G), c));
      const double left = (at - std::log(column(table2_coefficients(G * std::exp(-h)), c))) / h;
      const double right = (std::log(column(table2_coefficients(G * std::exp(h)), c)) - at) / h;
      EXPECT_NEAR(left, right, 1e-4) << "row " << k << " column " << c;
    }
}

// Beyond the table the end rows' power laws continue: equal factors of G give equal factors of
// each coefficient.
TEST(Table2Interpolated, ContinuesAsPowerLawsBeyondTheTable) {
  for (int c = 0; c < 3; ++c) {
    const double lo1 = column(table2_coefficients(1.25e6), c),
                 lo2 = column(table2_coefficients(2.5e6), c),
                 row = column(table2_coefficients(5e6), c);
    EXPECT_NEAR(lo2 * lo2 / (lo1 * row), 1.0, 1e-12) << c;
    const double hi1 = column(table2_coefficients(70e6), c),
                 hi2 = column(table2_coefficients(140e6), c),
                 hi3 = column(table2_coefficients(280e6), c);
    EXPECT_NEAR(hi2 * hi2 / (hi1 * hi3), 1.0, 1e-12) << c;
  }
  for (const double G : {1.2e6, 300e6, 0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    try {
      (void)table2_coefficients(G);
      ADD_FAILURE() << "no error for G = " << G;
    } catch (const Error& e) {
      EXPECT_EQ(e.key(), "soil.G");
      EXPECT_NE(std::string(e.what()).find("Table 2 scale"), std::string::npos) << e.what();
    }
  }
}

// ---- Appendix B -------------------------------------------------------------------------------

// (43): a0 comes out 0.4-1.7 % below the a0 column, always low (docs/model.md section 1.3).
// The computed deficits are 0.43 % (G = 30) to 1.65 % (G = 60): both ends are inside the band.
TEST(AppendixB, HalfContactLengthIsSlightlyBelowTable2) {
  const Roller roller;
  for (const Table2Row& row : table2()) {
    const SoilCoefficients s = soil_coefficients(row.G, kNu, kRho, roller);
    const double deficit = (row.a0 - s.a0) / row.a0;
    EXPECT_GE(deficit, 0.004) << "G = " << row.G << ", a0 = " << s.a0;
    EXPECT_LE(deficit, 0.017) << "G = " << row.G << ", a0 = " << s.a0;
  }
}

// (43) written out here, independently: a0 = 4 sqrt(2 r P0 (1 - nu) / (pi G b0)).
TEST(AppendixB, HalfContactLengthFormula) {
  const Roller roller;
  const double b0 = roller.b / 2.0;
  for (double G : {5e6, 25e6, 70e6, 123.4e6}) {
    const double a0 = 4.0 * std::sqrt(2.0 * 0.6 * 45224.0 * (1.0 - kNu) / (M_PI * G * b0));
    EXPECT_NEAR(soil_coefficients(G, kNu, kRho, roller).a0, a0, kIdentity * a0) << G;
  }
}

// (44)-(45) reproduce Table 2's damping columns to print precision (141 and 263 kN s/m).
TEST(AppendixB, DampingReproducesTable2ToPrintPrecision) {
  const Roller roller;
  for (const Table2Row& row : table2()) {
    const SoilCoefficients s = soil_coefficients(row.G, kNu, kRho, roller);
    expect_to_print_precision(s.csh / 1e3, row.csh / 1e3, 1.0, "csh [kN s/m]");
    expect_to_print_precision(s.csv / 1e3, row.csv / 1e3, 1.0, "csv [kN s/m]");
    // (45): csv = sqrt(2 (1 - nu) / (1 - 2 nu)) csh.
    EXPECT_NEAR(s.csv, std::sqrt(2.0 * (1.0 - kNu) / (1.0 - 2.0 * kNu)) * s.csh, kIdentity * s.csv);
  }
}

// The two forms of csh in (44)-(45) agree: 8 a0 b0 sqrt(G rho) = 32 sqrt(2 rho r b0 P0 (1-nu)/pi)
// once a0 from (43) is put in; so csh does not depend on G.
TEST(AppendixB, TheTwoFormsOfHorizontalDampingAgree) {
  for (const Roller& roller : {Roller{}, Roller{0.75, 2.1, 3000.0, 800.0, 60000.0}}) {
    const double b0 = roller.b / 2.0;
    const double closed =
        32.0 * std::sqrt(2.0 * kRho * roller.r * b0 * roller.P0 * (1.0 - kNu) / M_PI);
    for (double G : {5e6, 25e6, 70e6, 300e6}) {
      for (double nu : {0.0, 0.3, 0.45}) {
        const SoilCoefficients s = soil_coefficients(G, nu, kRho, roller);
        const double first = 8.0 * s.a0 * b0 * std::sqrt(G * kRho);
        const double second =
            32.0 * std::sqrt(2.0 * kRho * roller.r * b0 * roller.P0 * (1.0 - nu) / M_PI);
        EXPECT_NEAR(s.csh, first, kIdentity * first) << G << " " << nu;
        EXPECT_NEAR(first, second, kIdentity * second) << G << " " << nu;
        if (nu == kNu) {
          EXPECT_NEAR(s.csh, closed, kIdentity * closed);
        }
      }
    }
  }
}

// (42) as printed does not reproduce Table 2 (docs/model.md section 1.3): ksh comes out
// 18-26 % high and ksv 3-16 % low. The bands are docs/model.md's whole-percent figures, so each end
// is taken to +-0.5 %: the computed values are ksh +17.6 % (G = 5) to +25.5 % (G = 70) and ksv -3.8
// % (G = 5) to -15.8 % (G = 70). A change of the formula moves them out of the band.
TEST(AppendixB, StiffnessFormulaDeviatesFromTable2AsDocumented) {
  const Roller roller;
  for (const Table2Row& row : table2()) {
    const SoilCoefficients s = soil_coefficients(row.G, kNu, kRho, roller);
    const double ksh_excess = (s.ksh - row.ksh) / row.ksh;
    const double ksv_deficit = (row.ksv - s.ksv) / row.ksv;
    EXPECT_GE(ksh_excess, 0.175) << "G = " << row.G << ", ksh = " << s.ksh;
    EXPECT_LE(ksh_excess, 0.265) << "G = " << row.G << ", ksh = " << s.ksh;
    EXPECT_GE(ksv_deficit, 0.025) << "G = " << row.G << ", ksv = " << s.ksv;
    EXPECT_LE(ksv_deficit, 0.165) << "G = " << row.G << ", ksv = " << s.ksv;
  }
}

// (42) written out here, independently.
TEST(AppendixB, StiffnessFormula) {
  const Roller roller;
  const double b0 = roller.b / 2.0;
  for (double G : {5e6, 40e6, 70e6}) {
    for (double nu : {0.0, 0.3, 0.45}) {
      const SoilCoefficients s = soil_coefficients(G, nu, kRho, roller);
      const double q = b0 / s.a0;
      const double ksh = G * s.a0 / (2.0 - nu) * (6.8 * std::pow(q, 0.65) + 0.8 * q + 1.6);
      const double ksv = G * s.a0 / (1.0 - nu) * (3.1 * std::pow(q, 0.75) + 1.6);
      EXPECT_NEAR(s.ksh, ksh, kIdentity * ksh);
      EXPECT_NEAR(s.ksv, ksv, kIdentity * ksv);
    }
  }
}

TEST(AppendixB, ModulusSoilUsesTheFormulas) {
  Soil soil;
  soil.input = SoilInput::modulus;
  soil.G = 35e6;
  const SoilCoefficients a = soil_coefficients(soil);
  const SoilCoefficients b = soil_coefficients(35e6, 0.3, 1900.0);
  EXPECT_EQ(a.a0, b.a0);
  EXPECT_EQ(a.ksh, b.ksh);
  EXPECT_EQ(a.ksv, b.ksv);
  EXPECT_EQ(a.csh, b.csh);
  EXPECT_EQ(a.csv, b.csv);
}

TEST(AppendixB, RejectsNonPhysicalInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(soil_coefficients(0.0, kNu, kRho), Error);
  EXPECT_THROW(soil_coefficients(-5e6, kNu, kRho), Error);
  EXPECT_THROW(soil_coefficients(nan, kNu, kRho), Error);
  EXPECT_THROW(soil_coefficients(25e6, 0.5, kRho), Error);
  EXPECT_THROW(soil_coefficients(25e6, -0.1, kRho), Error);
  EXPECT_THROW(soil_coefficients(25e6, kNu, 0.0), Error);
  EXPECT_THROW(soil_coefficients(25e6, kNu, nan), Error);
  Roller bad;
  bad.r = 0.0;
  EXPECT_THROW(soil_coefficients(25e6, kNu, kRho, bad), Error);
  try {
    (void)soil_coefficients(25e6, 0.5, kRho);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("soil.nu"), std::string::npos) << e.what();
  }
}

// ---- Appendix A -------------------------------------------------------------------------------

// (40) for the frame m_f = 2760 kg on kd = 4e6 N/m, cd = 3e3 N s/m at nu = 2 pi 39: the paper
// prints omega = 38.1 rad/s, zeta = 0.014, nu/omega = 6.4, Tp = 0.025.
TEST(AppendixA, ReproducesThePrintedNumbers) {
  const Transmissibility t = transmissibility(4e6, 3e3, 2760.0, 2.0 * M_PI * 39.0);
  expect_to_print_precision(t.omega, 38.1, 0.1, "omega");
  expect_to_print_precision(t.zeta, 0.014, 0.001, "zeta");
  expect_to_print_precision(t.ratio, 6.4, 0.1, "nu/omega");
  expect_to_print_precision(t.Tp, 0.025, 0.001, "Tp");
  // Independently: the definitions of docs/model.md section 1.
  const double omega = std::sqrt(4e6 / 2760.0);
  const double zeta = 3e3 / (2.0 * 2760.0 * omega);
  const double r = 2.0 * M_PI * 39.0 / omega;
  const double Tp = std::sqrt((1.0 + std::pow(2.0 * zeta * r, 2)) /
                              (std::pow(1.0 - r * r, 2) + std::pow(2.0 * zeta * r, 2)));
  EXPECT_NEAR(t.omega, omega, kIdentity * omega);
  EXPECT_NEAR(t.zeta, zeta, kIdentity * zeta);
  EXPECT_NEAR(t.ratio, r, kIdentity * r);
  EXPECT_NEAR(t.Tp, Tp, kIdentity * Tp);
}

TEST(AppendixA, Limits) {
  // Static base motion (nu -> 0) is transmitted fully; far above resonance Tp -> 0.
  EXPECT_NEAR(transmissibility(4e6, 3e3, 2760.0, 1e-6).Tp, 1.0, 1e-9);
  EXPECT_LT(transmissibility(4e6, 3e3, 2760.0, 1e4).Tp, 1e-3);
  // The undamped isolator (cd = 0) is a valid case: Tp = 1 / |1 - (nu/omega)^2|.
  const Transmissibility u = transmissibility(4e6, 0.0, 2760.0, 2.0 * M_PI * 39.0);
  EXPECT_EQ(u.zeta, 0.0);
  EXPECT_NEAR(u.Tp, 1.0 / std::abs(1.0 - u.ratio * u.ratio), kIdentity);
}

TEST(AppendixA, RejectsNonPositiveInput) {
  const double nu = 2.0 * M_PI * 39.0, nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(transmissibility(0.0, 3e3, 2760.0, nu), Error);
  EXPECT_THROW(transmissibility(-4e6, 3e3, 2760.0, nu), Error);
  EXPECT_THROW(transmissibility(4e6, -3e3, 2760.0, nu), Error);
  EXPECT_THROW(transmissibility(4e6, 3e3, 0.0, nu), Error);
  EXPECT_THROW(transmissibility(4e6, 3e3, -2760.0, nu), Error);
  EXPECT_THROW(transmissibility(4e6, 3e3, 2760.0, 0.0), Error);
  EXPECT_THROW(transmissibility(4e6, 3e3, 2760.0, -nu), Error);
  EXPECT_THROW(transmissibility(nan, 3e3, 2760.0, nu), Error);
  EXPECT_THROW(transmissibility(4e6, 3e3, 2760.0, std::numeric_limits<double>::infinity()), Error);
}

// Each input valid, their ratio beyond the doubles: omega = sqrt(1e308 / 1e-300) overflows (it
// printed omega inf, Tp 1 and "the frame hardly follows"), and sqrt(1e-300 / 1e300) underflows
// to 0. The undamped resonance (Tp very large or infinite) stays a result.
TEST(AppendixA, RefusesInputsWhoseQuantitiesLeaveTheDoubles) {
  const double nu = 2.0 * M_PI * 39.0;
  EXPECT_THROW(transmissibility(1e308, 3e3, 1e-300, nu), Error);
  EXPECT_THROW(transmissibility(1e-300, 3e3, 1e300, nu), Error);
  EXPECT_THROW(transmissibility(1e-300, 1e300, 1e-10, nu), Error);
  const Transmissibility ok = transmissibility(4e6, 3e3, 1e-3, nu);  // extreme but finite
  EXPECT_TRUE(std::isfinite(ok.omega) && std::isfinite(ok.Tp));
  const double kd = 2760.0 * nu * nu;  // omega = nu to rounding
  EXPECT_GT(transmissibility(kd, 0.0, 2760.0, nu).Tp, 1e6);
}

}  // namespace
}  // namespace oscidrum
