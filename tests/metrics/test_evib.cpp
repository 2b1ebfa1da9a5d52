// The Evib-type vibration modulus (docs/outputs.md, src/metrics/evib.cpp): Lundberg's relation
// by hand at one point, synthetic force-displacement loops built from Lundberg's relation with a
// known E (continuous contact and with a flight), the degenerate loops, and the value on
// simulated vibratory steady states (finite, positive, increasing with the soil's G).
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <vector>

#include "oscidrum/oscidrum.hpp"

namespace oscidrum {
namespace {

constexpr double kR = 0.6, kL = 1.68, kNu = 0.3;  // the paper's drum (Table 1), Table 2's nu

// By hand (docs/outputs.md): F = 100 kN, E = 50 MN/m^2 on the paper's drum, nu = 0.3:
//   b = sqrt(16 * 0.6 * 0.91 * 1e5 / (pi * 1.68 * 5e7)) = sqrt(873600 / 2.63894e8) = 0.0575363 m
//   1.8864 + ln(1.68 / 0.0575363) = 1.8864 + 3.37413 = 5.26053
//   z = 0.91 / 5e7 * 1e5 / 1.68 * (2 / pi) * 5.26053 = 6.89675e-4 * 5.26053 = 3.62804e-3 m.
TEST(Evib, LundbergsRelationByHandAtOnePoint) {
  EXPECT_NEAR(lundberg_displacement(1e5, 5e7, kR, kL, kNu), 3.62804e-3, 1e-8);
  // ... and back: the E that gives this settlement from the unloaded surface.
  const double z = lundberg_displacement(1e5, 5e7, kR, kL, kNu);
  EXPECT_NEAR(lundberg_modulus(0.0, 0.0, 1e5, z, kR, kL, kNu), 5e7, 1e-9 * 5e7);
  EXPECT_EQ(lundberg_displacement(0.0, 5e7, kR, kL, kNu), 0.0);
}

// A closed loop over one period, rotated so that it starts at an arbitrary point: the loading
// branch z(F) = z1 + (Lundberg(F) - Lundberg(F1)) from (F1, z1) up to F2, the unloading branch
// back to F1 above it (hysteresis, still monotone in z), and, with a flight, a parabola in z at
// F = 0 from the lift-off through the top back to the landing at z1.
std::vector<std::vector<double>> synthetic_loop(double E, double F1, double F2, bool flight,
                                                std::size_t rotate) {
  std::vector<double> z, F;
  const double z1 = 2e-3, zL1 = lundberg_displacement(F1, E, kR, kL, kNu);
  const int n = 200;
  for (int k = 0; k <= n; ++k) {  // loading: F1 ... F2 (at k = n)
    const double s = static_cast<double>(k) / n, Fk = F1 + (F2 - F1) * s * s;
    F.push_back(Fk);
    z.push_back(z1 + lundberg_displacement(Fk, E, kR, kL, kNu) - zL1);
  }
  const double rise = z.back() - z1;
  for (int k = n - 1; k >= 1; --k) {  // unloading: F2 ... F1, above the loading branch
    const double s = static_cast<double>(k) / n, Fk = F1 + (F2 - F1) * s * s;
    F.push_back(Fk);
    z.push_back(z1 + lundberg_displacement(Fk, E, kR, kL, kNu) - zL1 +
                0.05 * rise * std::sin(std::numbers::pi * s));
  }
  if (flight) {  // lift-off at F = 0, up by 3 rises and down to the landing (excluded: k = 0)
    const int m = 100;
    for (int k = m; k >= 1; --k) {
      const double s = static_cast<double>(k) / m;  // 1 at the lift-off, 0 at the landing
      F.push_back(0.0);
      z.push_back(z1 + 0.02 * rise * s - 3.0 * rise * 4.0 * s * (1.0 - s));
    }
  }
  std::vector<double> zr(z.size()), Fr(F.size());
  for (std::size_t j = 0; j < z.size(); ++j) {
    zr[j] = z[(j + rotate) % z.size()];
    Fr[j] = F[(j + rotate) % F.size()];
  }
  return {zr, Fr};
}

TEST(Evib, RecoversTheModulusOfASyntheticLoopInContinuousContact) {
  for (double E : {2e7, 8e7, 3e8}) {
    for (std::size_t rotate : {0u, 37u, 250u}) {
      const auto loop = synthetic_loop(E, 25e3, 90e3, false, rotate);
      EXPECT_NEAR(vibration_modulus(loop[0], loop[1], kR, kL, kNu), E, 1e-6 * E)
          << E << " " << rotate;
    }
  }
}

TEST(Evib, RecoversTheModulusOfASyntheticLoopWithAFlight) {
  for (double E : {2e7, 8e7, 3e8}) {
    for (std::size_t rotate : {0u, 120u, 400u}) {
      const auto loop = synthetic_loop(E, 0.0, 120e3, true, rotate);
      EXPECT_NEAR(vibration_modulus(loop[0], loop[1], kR, kL, kNu), E, 1e-6 * E)
          << E << " " << rotate;
    }
  }
}

// The same loop read with the wrong radius, length or Poisson's ratio does not give E back: the
// geometry enters (this test fails if the implementation ignores an argument).
TEST(Evib, TheDrumGeometryAndPoissonsRatioEnter) {
  const double E = 8e7;
  const auto loop = synthetic_loop(E, 25e3, 90e3, false, 0);
  EXPECT_GT(std::abs(vibration_modulus(loop[0], loop[1], 2.0 * kR, kL, kNu) - E), 1e-3 * E);
  EXPECT_GT(std::abs(vibration_modulus(loop[0], loop[1], kR, 2.0 * kL, kNu) - E), 1e-3 * E);
  EXPECT_GT(std::abs(vibration_modulus(loop[0], loop[1], kR, kL, 0.45) - E), 1e-3 * E);
}

TEST(Evib, DegenerateLoopsAndArgumentsOutOfRange) {
  const std::vector<double> z = {0.0, 1e-3, 2e-3, 1e-3}, zero(4, 0.0), flat(4, 1e-3);
  EXPECT_TRUE(std::isnan(vibration_modulus(z, zero, kR, kL, kNu)));  // no contact force
  EXPECT_TRUE(std::isnan(vibration_modulus(flat, z, kR, kL, kNu)));  // the drum does not move
  EXPECT_TRUE(std::isnan(lundberg_modulus(1e4, 0.0, 1e4, 1e-3, kR, kL, kNu)));   // no rise in F
  EXPECT_TRUE(std::isnan(lundberg_modulus(0.0, 1e-3, 1e4, 1e-3, kR, kL, kNu)));  // no rise in z
  try {
    (void)vibration_modulus(z, z, 0.0, kL, kNu);
    ADD_FAILURE() << "R = 0 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("radius R must be > 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)vibration_modulus(z, z, kR, -1.0, kNu), Error);
  EXPECT_THROW((void)vibration_modulus(z, z, kR, kL, 0.5), Error);
}

}  // namespace
}  // namespace oscidrum
