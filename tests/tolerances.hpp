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

}  // namespace oscidrum::test
