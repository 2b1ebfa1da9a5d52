// Classification of Floquet multipliers (oscidrum/floquet.hpp).
#include "oscidrum/floquet.hpp"

#include <algorithm>
#include <cmath>

namespace oscidrum {

// A multiplier within this of the unit circle is a neutral direction (the mean of phi' of the
// frictionless drum), not an instability.
constexpr double kNeutral = 1e-6;

const char* to_string(Stability stability) {
  switch (stability) {
    case Stability::unknown:
      return "unknown";
    case Stability::stable:
      return "stable";
    case Stability::fold:
      return "fold";
    case Stability::period_doubling:
      return "period_doubling";
    case Stability::torus:
      return "torus";
  }
  return "unknown";
}

Floquet classify_multipliers(std::vector<std::complex<double>> multipliers) {
  Floquet f;
  std::stable_sort(multipliers.begin(), multipliers.end(),
                   [](const auto& a, const auto& b) { return std::abs(a) > std::abs(b); });
  f.multipliers = std::move(multipliers);
  if (f.multipliers.empty()) return f;
  const std::complex<double> lead = f.multipliers.front();
  f.max_modulus = std::abs(lead);
  if (f.max_modulus <= 1.0 + kNeutral) {
    f.stability = Stability::stable;
  } else if (std::abs(lead.imag()) > 1e-8 * f.max_modulus) {
    f.stability = Stability::torus;
  } else {
    f.stability = lead.real() > 0.0 ? Stability::fold : Stability::period_doubling;
  }
  return f;
}

}  // namespace oscidrum
