// tests/tolerances.hpp: the one place where test tolerances are stated and justified.
#pragma once

namespace oscidrum::test {

/// Round-off level for closed-form identities evaluated in double precision.
inline constexpr double kIdentity = 1e-12;
/// Central finite differences with step h = 1e-5: truncation O(h^2) ~ 1e-10, round-off
/// ~ eps / h ~ 1e-11, relative to the derivative's scale.
inline constexpr double kFiniteDifference = 1e-7;
/// Independent linear solves of the same balance equations (condition numbers up to ~1e4).
inline constexpr double kIndependentSolve = 1e-9;
/// Table 2 prints three significant figures.
inline constexpr double kTable2Print = 0.005;

/// A printed number is right "to print precision" when it is within half a unit of its last
/// printed digit (e.g. 141 kN s/m: within 0.5 kN s/m; 0.014: within 0.0005).
inline constexpr double kHalfLastDigit = 0.5;

/// Residual of a balance equation (19), (20), (23), or of N and T from (21)-(22) against (26),
/// relative to the force scale W = P0 (torques: W r; rates of force: nu W). The terms of the
/// balances are at most ~1e6 N at realistic states (soil springs 1e8 N/m times 1e-3 m, dashpots
/// 3e5 N s/m times 0.2 m/s, m x_M'' ~ 1e5 N), so double round-off leaves residuals of
/// ~1e6 * 1e-16 / 4.5e4 ~ 1e-14 of W; 1e-10 leaves four orders of margin, while any missing or
/// wrong term of the equations (the smallest, I f6 delta'^2 / r for k = 0.002, is ~3 N, i.e.
/// 1e-4 of W) is caught by six orders.
inline constexpr double kBalanceResidual = 1e-10;

/// Mirror symmetry (circle, MMd = 0): the mirrored evaluation rounds differently (the sine's
/// argument nu (t + T/2) carries an absolute error ~ eps nu t, and the accelerations are solved
/// from sums that cancel by ~1e3), so agreement is to ~1e-13 relative; 1e-10 leaves margin.
inline constexpr double kSymmetry = 1e-10;

/// Regression profiles (tests/regression): a restructuring that keeps the arithmetic reproduces
/// the stored numbers bit for bit; one that reorders floating-point operations moves a steady
/// state by round-off amplified by the period-to-period contraction, far below the steady-state
/// tolerance 1e-8 that bounds what the numbers mean. 1e-9 of each column's scale separates the
/// two: any change of the equations, the events or the metrics shows up well above it.
inline constexpr double kRegression = 1e-9;

}  // namespace oscidrum::test
