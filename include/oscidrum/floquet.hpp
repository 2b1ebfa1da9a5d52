// oscidrum/floquet.hpp: the Floquet multipliers of a periodic steady state (docs/periodic.md).
#pragma once

#include <complex>
#include <vector>

namespace oscidrum {

/// Stability of a periodic orbit from its multipliers (the eigenvalues of the monodromy matrix,
/// the linearised period map on (delta, x_A, s_A, delta', x_A', s_A', phi')).
enum class Stability {
  unknown,          ///< no multipliers (the steady state was not found by shooting)
  stable,           ///< every multiplier inside the unit circle (or on it within 1e-6: neutral)
  fold,             ///< a real multiplier beyond +1 (saddle-node: jumps, hysteresis)
  period_doubling,  ///< a real multiplier beyond -1 (flip: a period-2 orbit branches off)
  torus,            ///< a complex pair outside the unit circle (Neimark-Sacker: quasi-periodic)
};

/// "unknown", "stable", "fold", "period_doubling", "torus".
const char* to_string(Stability stability);

struct Floquet {
  std::vector<std::complex<double>> multipliers;  ///< by decreasing modulus [-]
  double max_modulus = 0.0;  ///< largest |multiplier|; the transient decays like it per period
  Stability stability = Stability::unknown;
};

/// Sort the multipliers by modulus and classify by the largest one (a pair with an imaginary
/// part above 1e-8 of its modulus counts as complex).
Floquet classify_multipliers(std::vector<std::complex<double>> multipliers);

}  // namespace oscidrum
